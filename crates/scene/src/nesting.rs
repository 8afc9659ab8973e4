//! A guard in front of the TOML parser: brackets nested too deep are refused before parsing.
//!
//! The parser recurses once per open `[` or `{`, and in its error recovery past its own depth
//! limit, so a few kilobytes of `a={[t]` repeated overflow a thread's stack and abort the
//! process (found by `tests/fuzz.rs`). No scene nests more than a handful of levels.

/// The deepest nesting of arrays and inline tables a scene file may have.
pub(crate) const MAX_NESTING: usize = 64;

/// The byte offset of the first `[` or `{` that opens a level deeper than [`MAX_NESTING`],
/// outside strings and comments; `None` when there is none.
pub(crate) fn too_deep(text: &str) -> Option<usize> {
    let bytes = text.as_bytes();
    let (mut depth, mut i) = (0usize, 0);
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                i += bytes[i..].iter().position(|&b| b == b'\n').unwrap_or(bytes.len() - i);
                continue;
            }
            quote @ (b'"' | b'\'') => {
                i = string_end(bytes, i, quote);
                continue;
            }
            b'[' | b'{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Some(i);
                }
            }
            b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        i += 1;
    }
    None
}

/// The offset just past the string opening at `start` with `quote` (basic `"` strings take
/// backslash escapes; a tripled quote opens a multi-line string). An unterminated one-line
/// string ends at its line, which the parser then reports.
fn string_end(bytes: &[u8], start: usize, quote: u8) -> usize {
    let triple = bytes[start..].starts_with(&[quote; 3]);
    let mut i = start + if triple { 3 } else { 1 };
    while i < bytes.len() {
        match bytes[i] {
            b'\\' if quote == b'"' => i += 1,
            b'\n' if !triple => return i,
            b if b == quote && !triple => return i + 1,
            b if b == quote && bytes[i..].starts_with(&[quote; 3]) => return i + 3,
            _ => {}
        }
        i += 1;
    }
    bytes.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deep_nesting_is_found_outside_strings_and_comments() {
        assert_eq!(too_deep("[camera]\nposition = [[1, 2], {a = [3]}]\n"), None);
        let deep = "a={[t]".repeat(2000);
        // Each repeat nets one level; the 64th repeat's `[` opens level 65.
        assert_eq!(too_deep(&deep), Some(6 * (MAX_NESTING - 1) + 3));
        // Brackets in strings and comments do not count.
        let quoted = format!(
            "a = \"{}\"\nb = '{}'\nc = \"\"\"\n{}\"\"\"\n# {}\n",
            "[".repeat(99),
            "{".repeat(99),
            "[".repeat(99),
            "[".repeat(99)
        );
        assert_eq!(too_deep(&quoted), None);
        assert_eq!(too_deep("a = \"\\\"[[\"\n"), None, "an escaped quote does not end the string");
    }
}
