//! NumPy's `.npy` format (numpy.lib.format, "A simple format for saving numpy arrays to disk",
//! NEP 1): the magic `\x93NUMPY`, a version `(major, minor)`, the header's length (2 bytes
//! little-endian in version 1, 4 in versions 2 and 3), and the header, a Python dict literal
//! such as `{'descr': '<f4', 'fortran_order': False, 'shape': (64, 64, 32), }`, then the data.
//!
//! A volume is a 3-D array indexed `[x, y, z]` of `float32` or `float64` (`<f4`, `>f4`, `<f8`,
//! `>f8`; `float64` is rounded to `float32`), in C order (`z` fastest) or Fortran order (`x`
//! fastest). The header is parsed here, by a parser of just that dict, because the `npyz`
//! crate multiplies a header's dimensions unchecked (a lying shape overflows, a panic in debug
//! builds) and allocates the header's declared length before reading it; both are checked
//! below before anything is allocated.

use super::{read_exactly, sizes, Volume, VolumeError, VolumeErrorKind};
use crate::files::policy::{ReadError, Resource};

const MAGIC: &[u8] = b"\x93NUMPY";
/// The longest header read: NumPy's are a few hundred bytes (version 1 allows 65 535).
const MAX_HEADER: u64 = 1 << 20;

/// Reads the `.npy` volume `file`.
pub fn load_npy(file: &Resource<'_>) -> Result<Volume, VolumeError> {
    read(file).map_err(|kind| kind.at(file))
}

fn header_error(why: impl Into<String>) -> VolumeErrorKind {
    VolumeErrorKind::Header(why.into())
}

/// How the samples lie in the file.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Layout {
    dims: [u64; 3],
    big_endian: bool,
    /// 4 (`float32`) or 8 (`float64`).
    item: u64,
    fortran: bool,
}

fn read(file: &Resource<'_>) -> Result<Volume, VolumeErrorKind> {
    let (text_start, text_len) = header_extent(file)?;
    let prefix = file.read_prefix(text_start + text_len).map_err(VolumeErrorKind::Read)?;
    let text =
        std::str::from_utf8(&prefix[text_start as usize..]).map_err(|_| header_error("the header is not text"))?;
    let layout = parse_header(text)?;
    let offset = text_start + text_len;
    let (count, needed) = sizes(layout.dims, layout.item, offset)?;
    let bytes = read_exactly(file, needed)?;
    decode(&bytes[offset as usize..], count, layout)
}

/// Where the header's text starts and how long it is, from the magic, version and length.
fn header_extent(file: &Resource<'_>) -> Result<(u64, u64), VolumeErrorKind> {
    let start = file.read_prefix(12).map_err(|e| match e {
        ReadError::TooShort { .. } => header_error("too short for a .npy file"),
        other => VolumeErrorKind::Read(other),
    })?;
    if &start[..6] != MAGIC {
        return Err(header_error("no .npy magic (\\x93NUMPY) at its start"));
    }
    let (text_start, text_len) = match start[6] {
        1 => (10, u64::from(u16::from_le_bytes([start[8], start[9]]))),
        2 | 3 => (12, u64::from(u32::from_le_bytes([start[8], start[9], start[10], start[11]]))),
        v => return Err(header_error(format!("format version {v}, and nullpath reads versions 1 to 3"))),
    };
    if text_len > MAX_HEADER {
        return Err(header_error(format!("a header of {text_len} bytes, more than the {MAX_HEADER} nullpath reads")));
    }
    Ok((text_start, text_len))
}

/// A Python literal as `.npy` headers use them.
#[derive(Clone, Debug, PartialEq)]
enum Literal {
    Str(String),
    Bool(bool),
    Int(u64),
    Tuple(Vec<Literal>),
}

/// A recursive-descent parser of the header's dict: strings in either quotes (no escapes, which
/// no header of a float array holds), `True`/`False`, non-negative integers, tuples.
struct Parser<'a> {
    rest: &'a str,
}

impl<'a> Parser<'a> {
    fn skip_space(&mut self) {
        self.rest = self.rest.trim_start();
    }

    fn eat(&mut self, token: char) -> bool {
        self.skip_space();
        match self.rest.strip_prefix(token) {
            Some(rest) => {
                self.rest = rest;
                true
            }
            None => false,
        }
    }

    fn expect(&mut self, token: char) -> Result<(), VolumeErrorKind> {
        if self.eat(token) {
            Ok(())
        } else {
            Err(header_error(format!("expected '{token}' at \"{}\"", self.rest.chars().take(20).collect::<String>())))
        }
    }

    fn literal(&mut self) -> Result<Literal, VolumeErrorKind> {
        self.skip_space();
        if let Some(quote) = self.rest.chars().next().filter(|c| *c == '\'' || *c == '"') {
            let body = &self.rest[1..];
            let end = body.find(quote).ok_or_else(|| header_error("a string without its closing quote"))?;
            let value = &body[..end];
            if value.contains('\\') {
                return Err(header_error("an escaped string"));
            }
            self.rest = &body[end + 1..];
            return Ok(Literal::Str(value.to_owned()));
        }
        if self.eat('(') {
            let mut items = Vec::new();
            while !self.eat(')') {
                items.push(self.literal()?);
                if !self.eat(',') {
                    self.expect(')')?;
                    break;
                }
            }
            return Ok(Literal::Tuple(items));
        }
        for (word, value) in [("True", true), ("False", false)] {
            if let Some(rest) = self.rest.strip_prefix(word) {
                self.rest = rest;
                return Ok(Literal::Bool(value));
            }
        }
        let digits = self.rest.len() - self.rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        if digits == 0 {
            return Err(header_error(format!("unexpected \"{}\"", self.rest.chars().take(20).collect::<String>())));
        }
        let value = self.rest[..digits].parse().map_err(|_| header_error("an integer beyond 2⁶⁴"))?;
        self.rest = &self.rest[digits..];
        Ok(Literal::Int(value))
    }

    /// The dict `{key: value, ...}` (a trailing comma allowed), keys strings, each once.
    fn dict(&mut self) -> Result<Vec<(String, Literal)>, VolumeErrorKind> {
        self.expect('{')?;
        let mut entries: Vec<(String, Literal)> = Vec::new();
        while !self.eat('}') {
            let Literal::Str(key) = self.literal()? else {
                return Err(header_error("a key that is not a string"));
            };
            self.expect(':')?;
            let value = self.literal()?;
            if entries.iter().any(|(k, _)| *k == key) {
                return Err(header_error(format!("the key '{key}' twice")));
            }
            entries.push((key, value));
            if !self.eat(',') {
                self.expect('}')?;
                break;
            }
        }
        Ok(entries)
    }
}

/// The layout a header declares: exactly the keys `descr`, `fortran_order` and `shape`.
fn parse_header(text: &str) -> Result<Layout, VolumeErrorKind> {
    let mut parser = Parser { rest: text };
    let entries = parser.dict()?;
    if !parser.rest.trim().is_empty() {
        return Err(header_error("text after the header's dict"));
    }
    let get = |key: &str| {
        entries
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v)
            .ok_or_else(|| header_error(format!("no '{key}' in the header")))
    };
    if let Some((key, _)) = entries.iter().find(|(k, _)| !["descr", "fortran_order", "shape"].contains(&k.as_str())) {
        return Err(header_error(format!("an unknown key '{key}' in the header")));
    }
    let (big_endian, item) = match get("descr")? {
        Literal::Str(descr) => match descr.as_str() {
            "<f4" => (false, 4),
            ">f4" => (true, 4),
            "<f8" => (false, 8),
            ">f8" => (true, 8),
            other => return Err(header_error(format!("samples of type '{other}', not float32 or float64"))),
        },
        other => return Err(header_error(format!("'descr' is {other:?}, not a type string"))),
    };
    let Literal::Bool(fortran) = *get("fortran_order")? else {
        return Err(header_error("'fortran_order' is not True or False"));
    };
    let dims = match get("shape")? {
        Literal::Tuple(items) => match items.as_slice() {
            [Literal::Int(x), Literal::Int(y), Literal::Int(z)] => [*x, *y, *z],
            _ => return Err(header_error(format!("a shape of {} dimensions, not 3", items.len()))),
        },
        other => return Err(header_error(format!("'shape' is {other:?}, not a tuple"))),
    };
    Ok(Layout { dims, big_endian, item, fortran })
}

/// The samples of `data`, reordered `x` fastest.
fn decode(data: &[u8], count: usize, layout: Layout) -> Result<Volume, VolumeErrorKind> {
    let read = |b: &[u8]| -> f64 {
        match (layout.item, layout.big_endian) {
            (4, false) => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            (4, true) => f64::from(f32::from_be_bytes([b[0], b[1], b[2], b[3]])),
            (_, false) => f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]),
            (_, true) => f64::from_be_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]),
        }
    };
    let stored: Vec<f64> = data.chunks_exact(layout.item as usize).map(read).collect();
    debug_assert_eq!(stored.len(), count);
    // `sizes` has checked that the product of the dimensions fits in a `usize`.
    let [nx, ny, nz] = layout.dims.map(|d| d as usize);
    // Fortran order is already `x` fastest; C order has `z` fastest: (x, y, z) at (x ny + y) nz + z.
    let source = |n: usize| {
        if layout.fortran {
            n
        } else {
            let (x, y, z) = (n % nx, (n / nx) % ny, n / (nx * ny));
            (x * ny + y) * nz + z
        }
    };
    let values = (0..count).map(|n| stored[source(n)] as f32).collect();
    Volume::checked([nx, ny, nz], values, |n, _| stored[source(n)])
}

#[cfg(test)]
mod tests {
    use super::super::test_files::folder;
    use super::*;
    use crate::files::policy::ReadPolicy;

    /// An `.npy` file as NumPy writes one: the header padded with spaces and a newline so that
    /// the data starts at a multiple of 64 bytes.
    fn npy(version: u8, header: &str, data: &[u8]) -> Vec<u8> {
        let start = if version == 1 { 10 } else { 12 };
        let mut text = header.to_owned();
        while (start + text.len() + 1) % 64 != 0 {
            text.push(' ');
        }
        text.push('\n');
        let mut bytes = MAGIC.to_vec();
        bytes.extend([version, 0]);
        if version == 1 {
            bytes.extend((text.len() as u16).to_le_bytes());
        } else {
            bytes.extend((text.len() as u32).to_le_bytes());
        }
        bytes.extend(text.as_bytes());
        bytes.extend(data);
        bytes
    }

    /// Value of sample (x, y, z) in the tests' 2×3×4 arrays.
    fn value(x: usize, y: usize, z: usize) -> f64 {
        (x + 10 * y + 100 * z) as f64 + 0.5
    }

    /// The 2×3×4 array in C (`z` fastest) or Fortran (`x` fastest) order.
    fn samples(fortran: bool) -> Vec<f64> {
        let mut out = Vec::new();
        if fortran {
            for z in 0..4 {
                for y in 0..3 {
                    for x in 0..2 {
                        out.push(value(x, y, z));
                    }
                }
            }
        } else {
            for x in 0..2 {
                for y in 0..3 {
                    for z in 0..4 {
                        out.push(value(x, y, z));
                    }
                }
            }
        }
        out
    }

    fn expected() -> Volume {
        let values = samples(true).iter().map(|&v| v as f32).collect();
        Volume { dims: [2, 3, 4], values }
    }

    fn load(name: &str, bytes: &[u8]) -> Result<Volume, VolumeError> {
        let dir = folder(name);
        std::fs::write(dir.join("v.npy"), bytes).unwrap();
        let policy = ReadPolicy::new(&dir);
        let result = load_npy(&policy.file(&dir, "v.npy"));
        std::fs::remove_dir_all(&dir).ok();
        result
    }

    #[test]
    fn reads_float32_and_float64_in_c_and_fortran_order_and_either_byte_order() {
        for (descr, version) in [("<f4", 1), (">f4", 2), ("<f8", 3), (">f8", 1)] {
            for fortran in [false, true] {
                let data: Vec<u8> = samples(fortran)
                    .iter()
                    .flat_map(|&v| match descr {
                        "<f4" => (v as f32).to_le_bytes().to_vec(),
                        ">f4" => (v as f32).to_be_bytes().to_vec(),
                        "<f8" => v.to_le_bytes().to_vec(),
                        _ => v.to_be_bytes().to_vec(),
                    })
                    .collect();
                let order = if fortran { "True" } else { "False" };
                let header = format!("{{'descr': '{descr}', 'fortran_order': {order}, 'shape': (2, 3, 4), }}");
                let volume = load(&format!("read-{descr}-{fortran}"), &npy(version, &header, &data)).unwrap();
                assert_eq!(volume, expected(), "{descr}, Fortran {fortran}");
            }
        }
    }

    #[test]
    fn refuses_truncated_oversized_and_lying_files_naming_them() {
        let header = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 4), }";
        let data: Vec<u8> = samples(false).iter().flat_map(|&v| (v as f32).to_le_bytes()).collect();
        let whole = npy(1, header, &data);
        type Expected = fn(&VolumeErrorKind) -> bool;
        let cases: [(&str, Vec<u8>, Expected); 6] = [
            ("truncated", whole[..whole.len() - 1].to_vec(), |k| matches!(k, VolumeErrorKind::Truncated { .. })),
            ("oversized", [whole.clone(), vec![0; 4]].concat(), |k| matches!(k, VolumeErrorKind::Oversized { .. })),
            (
                "lying",
                npy(1, "{'descr': '<f4', 'fortran_order': False, 'shape': (4294967296, 4294967296, 2), }", &data),
                |k| matches!(k, VolumeErrorKind::Dimensions { .. }),
            ),
            ("header past the end", whole[..40].to_vec(), |k| matches!(k, VolumeErrorKind::Read(_))),
            ("not npy", b"P6 2 3 255\n............".to_vec(), |k| matches!(k, VolumeErrorKind::Header(_))),
            ("tiny", b"\x93NU".to_vec(), |k| matches!(k, VolumeErrorKind::Header(_))),
        ];
        for (name, bytes, expected) in cases {
            let e = load(name, &bytes).unwrap_err();
            assert!(expected(&e.kind), "{name}: {e:?}");
            assert!(e.to_string().starts_with("cannot read volume 'v.npy': "), "{name}: {e}");
        }
    }

    #[test]
    fn refuses_headers_that_are_not_a_3d_float_array() {
        for header in [
            "{'descr': '<i4', 'fortran_order': False, 'shape': (2, 3, 4), }",
            "{'descr': '<f4', 'fortran_order': False, 'shape': (24,), }",
            "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 4, 1), }",
            "{'descr': '<f4', 'fortran_order': 0, 'shape': (2, 3, 4), }",
            "{'descr': '<f4', 'shape': (2, 3, 4), }",
            "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 4), 'extra': 1}",
            "{'descr': '<f4', 'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 4)}",
            "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 4) ",
            "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, -4)}",
            "[1, 2]",
        ] {
            let data = vec![0u8; 96];
            let e = load("headers", &npy(1, header, &data)).unwrap_err();
            assert!(matches!(e.kind, VolumeErrorKind::Header(_)), "{header}: {e:?}");
        }
        // A zero dimension is a shape, but no volume.
        let e =
            load("zero", &npy(1, "{'descr': '<f4', 'fortran_order': False, 'shape': (0, 3, 4), }", &[])).unwrap_err();
        assert!(matches!(e.kind, VolumeErrorKind::Dimensions { .. }), "{e:?}");
    }

    #[test]
    fn refuses_a_negative_sample_at_its_place() {
        let mut data = samples(false);
        // (x, y, z) = (1, 2, 3) in C order.
        data[(3 + 2) * 4 + 3] = -1.0;
        let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
        let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3, 4), }";
        let e = load("negative", &npy(1, header, &bytes)).unwrap_err();
        assert!(matches!(e.kind, VolumeErrorKind::Sample { at: [1, 2, 3], value } if value == -1.0), "{e:?}");
    }
}
