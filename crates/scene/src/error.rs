//! [`SceneError`]: one precise, single-line message per problem, `file:line:column: field: what`.

use std::fmt;

/// Why a scene file could not be turned into a scene.
///
/// Its `Display` is one line naming the file, where in it (line and column, 1-based, columns in
/// characters), the field (as a path such as `objects[3].shape.radius`) and what is wrong:
///
/// ```text
/// scenes/room.toml:12:10: objects[3].shape.radius: must be > 0, got -1
/// scenes/x.toml: cannot read: No such file or directory
/// ```
///
/// The parts are also available one by one, for tools that want to point at the spot themselves.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    origin: String,
    position: Option<(usize, usize)>,
    field: Option<String>,
    message: String,
}

impl SceneError {
    /// An error about the file as a whole (it cannot be read).
    pub(crate) fn file(origin: &str, message: impl Into<String>) -> Self {
        Self { origin: origin.to_string(), position: None, field: None, message: message.into() }
    }

    /// An error at byte offset `offset` of `text`, about `field` (if any).
    pub(crate) fn at(origin: &str, text: &str, offset: usize, field: Option<&str>, message: impl Into<String>) -> Self {
        Self {
            origin: origin.to_string(),
            position: Some(line_column(text, offset)),
            field: field.filter(|f| !f.is_empty()).map(str::to_string),
            message: message.into(),
        }
    }

    /// The name of the scene (its path, or e.g. `<default scene>`).
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// 1-based line of the offending text, when the problem is inside the file.
    pub fn line(&self) -> Option<usize> {
        self.position.map(|p| p.0)
    }

    /// 1-based column (in characters) of the offending text, when the problem is inside the file.
    pub fn column(&self) -> Option<usize> {
        self.position.map(|p| p.1)
    }

    /// The path of the offending field, such as `objects[3].shape.radius`, when there is one.
    pub fn field(&self) -> Option<&str> {
        self.field.as_deref()
    }

    /// What is wrong, without the location.
    pub fn message(&self) -> &str {
        &self.message
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.origin)?;
        if let Some((line, column)) = self.position {
            write!(f, ":{line}:{column}")?;
        }
        if let Some(field) = &self.field {
            write!(f, ": {field}")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for SceneError {}

/// 1-based line and column (in characters) of byte `offset` of `text`; offsets past the end or
/// inside a character are moved back to the nearest character boundary.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

/// `io::Error`'s message without the trailing ` (os error N)`.
pub(crate) fn io_message(e: &std::io::Error) -> String {
    let s = e.to_string();
    match s.find(" (os error ") {
        Some(i) if s.ends_with(')') => s[..i].to_string(),
        _ => s,
    }
}

/// The closest of `candidates` to `word` if it is a plausible typo (edit distance ≤ 2, and less
/// than the word's length), for "did you mean" hints.
pub(crate) fn suggest<'c>(word: &str, candidates: impl IntoIterator<Item = &'c str>) -> Option<&'c str> {
    let word_lower = word.to_lowercase();
    candidates
        .into_iter()
        .map(|c| (edit_distance(&word_lower, &c.to_lowercase()), c))
        .filter(|&(d, _)| d <= 2 && d < word.chars().count().max(1))
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

/// Levenshtein distance in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1).min(row[j] + 1).min(diagonal + usize::from(ca != cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_columns_are_one_based_and_count_characters() {
        let text = "a = 1\nbé = 2\n";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 4), (1, 5));
        assert_eq!(line_column(text, 6), (2, 1));
        // "é" is two bytes; the `=` after it is the fourth character.
        assert_eq!(line_column(text, 10), (2, 4));
        // Inside the two bytes of "é": moved back to its start.
        assert_eq!(line_column(text, 8), (2, 2));
        assert_eq!(line_column(text, 1000), (3, 1));
    }

    #[test]
    fn display_joins_the_parts() {
        let e = SceneError::at("s.toml", "x\ny = -1", 6, Some("objects[0].y"), "must be > 0, got -1");
        assert_eq!(e.to_string(), "s.toml:2:5: objects[0].y: must be > 0, got -1");
        assert_eq!(SceneError::file("x.toml", "cannot read: gone").to_string(), "x.toml: cannot read: gone");
    }

    #[test]
    fn suggestions_catch_typos_only() {
        assert_eq!(suggest("raduis", ["center", "radius"]), Some("radius"));
        assert_eq!(suggest("sphear", ["sphere", "plane"]), Some("sphere"));
        assert_eq!(suggest("zzz", ["sphere", "plane"]), None);
        assert_eq!(suggest("a", ["b"]), None);
    }
}
