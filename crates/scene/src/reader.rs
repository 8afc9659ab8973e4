//! A typed walk over toml's spanned document tree (`toml::de::DeTable`): every value keeps its byte
//! span and its field path, so that any error — a wrong type, an unknown key, a value out of range
//! found long after parsing — can name the line, column and field it is about.
//!
//! Tables are opened with the list of keys they accept ([`Node::table`]); any other key is an error
//! naming it and listing the accepted ones (serde's `deny_unknown_fields`, with better messages).

use crate::error::{suggest, SceneError};
use render::geometry::Vec3;
use render::rgb::Rgb;
use std::ops::Range;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

pub(crate) type Result<T> = std::result::Result<T, SceneError>;

/// The text being read and the name it goes by in messages.
pub(crate) struct Doc<'a> {
    pub origin: &'a str,
    pub text: &'a str,
}

impl Doc<'_> {
    pub fn error(&self, offset: usize, field: &str, message: impl Into<String>) -> SceneError {
        SceneError::at(self.origin, self.text, offset, Some(field), message)
    }
}

/// A place in the document: where to point and which field to name.
#[derive(Clone)]
pub(crate) struct Loc<'a> {
    doc: &'a Doc<'a>,
    offset: usize,
    path: String,
}

impl Loc<'_> {
    pub fn err(&self, message: impl Into<String>) -> SceneError {
        self.doc.error(self.offset, &self.path, message)
    }
}

/// One value of the document, with its span and field path.
#[derive(Clone)]
pub(crate) struct Node<'a> {
    doc: &'a Doc<'a>,
    value: &'a DeValue<'a>,
    span: Range<usize>,
    path: String,
}

/// `parent.key`, quoting keys that are not bare TOML keys.
fn join(parent: &str, key: &str) -> String {
    let bare = !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    let key = if bare { key.to_string() } else { format!("{key:?}") };
    if parent.is_empty() {
        key
    } else {
        format!("{parent}.{key}")
    }
}

/// "a string (\"big\")", "an integer (3)", …: what a value is, for type errors.
fn describe(v: &DeValue<'_>) -> String {
    match v {
        DeValue::String(s) => {
            let mut shown: String = s.chars().take(40).collect();
            if shown.len() < s.len() {
                shown.push('…');
            }
            format!("a string ({shown:?})")
        }
        DeValue::Integer(i) => format!("an integer ({i})"),
        DeValue::Float(f) => format!("a float ({f})"),
        DeValue::Boolean(b) => format!("a boolean ({b})"),
        DeValue::Datetime(d) => format!("a date-time ({d})"),
        DeValue::Array(_) => "an array".to_string(),
        DeValue::Table(_) => "a table".to_string(),
    }
}

/// "a, b or c".
pub(crate) fn one_of(options: &[&str]) -> String {
    match options {
        [] => String::new(),
        [only] => format!("\"{only}\""),
        [init @ .., last] => {
            let init: Vec<String> = init.iter().map(|o| format!("\"{o}\"")).collect();
            format!("{} or \"{last}\"", init.join(", "))
        }
    }
}

fn did_you_mean<'c>(word: &str, candidates: impl IntoIterator<Item = &'c str>) -> String {
    suggest(word, candidates).map_or_else(String::new, |s| format!(" (did you mean \"{s}\"?)"))
}

impl<'a> Node<'a> {
    fn child(&self, key: &str, value: &'a Spanned<DeValue<'a>>) -> Node<'a> {
        Node { doc: self.doc, value: value.get_ref(), span: value.span(), path: join(&self.path, key) }
    }

    pub fn path(&self) -> &str {
        &self.path
    }

    pub fn loc(&self) -> Loc<'a> {
        Loc { doc: self.doc, offset: self.span.start, path: self.path.clone() }
    }

    /// An error about this value.
    pub fn err(&self, message: impl Into<String>) -> SceneError {
        self.doc.error(self.span.start, &self.path, message)
    }

    /// An error about byte `within` of this string's text: the column inside an expression. The
    /// text starts one byte after the value's opening quote (exact for strings without escapes).
    pub fn err_within(&self, within: usize, message: impl Into<String>) -> SceneError {
        self.doc.error(self.span.start + 1 + within, &self.path, message)
    }

    /// "expected …, got …" about this value.
    pub fn expected(&self, expected: &str) -> SceneError {
        self.err(format!("expected {expected}, got {}", describe(self.value)))
    }

    pub fn is_table(&self) -> bool {
        matches!(self.value, DeValue::Table(_))
    }

    pub fn is_str(&self) -> bool {
        matches!(self.value, DeValue::String(_))
    }

    pub fn is_array(&self) -> bool {
        matches!(self.value, DeValue::Array(_))
    }

    pub fn is_number(&self) -> bool {
        matches!(self.value, DeValue::Integer(_) | DeValue::Float(_))
    }

    /// This value as a table accepting exactly the keys `allowed`.
    pub fn table(&self, allowed: &[&'static str]) -> Result<Table<'a>> {
        let table = self.any_table()?;
        table.only(allowed)?;
        Ok(Table { allowed: allowed.to_vec(), ..table })
    }

    /// This value as a table with keys of any name (a map such as `[materials]`).
    pub fn any_table(&self) -> Result<Table<'a>> {
        match self.value {
            DeValue::Table(t) => Ok(Table { node: self.clone(), table: t, allowed: Vec::new() }),
            _ => Err(self.expected("a table")),
        }
    }

    /// A table with a `type` key choosing among `kinds` (name, accepted keys besides `type`).
    /// Returns the index of the kind and the table.
    pub fn tagged(&self, what: &str, kinds: &[(&'static str, &[&'static str])]) -> Result<(usize, Table<'a>)> {
        let names: Vec<&str> = kinds.iter().map(|k| k.0).collect();
        self.tagged_by(what, &names, |index| kinds[index].1.to_vec())
    }

    /// A table with a `type` key naming one of `kinds`: that kind, and the table, which accepts
    /// `type` and the kind's [`Tagged::keys`]. An unknown or missing type is an error listing
    /// the kinds' names.
    pub fn kind<'k, K: Tagged>(&self, what: &str, kinds: &'k [K]) -> Result<(&'k K, Table<'a>)> {
        let names: Vec<&str> = kinds.iter().map(Tagged::name).collect();
        let (index, table) = self.tagged_by(what, &names, |index| kinds[index].keys())?;
        Ok((&kinds[index], table))
    }

    /// [`Node::tagged`] and [`Node::kind`]: the index into `names` of the `type`, and the table
    /// accepting `type` and `keys(index)`.
    fn tagged_by(
        &self,
        what: &str,
        names: &[&str],
        keys: impl FnOnce(usize) -> Vec<&'static str>,
    ) -> Result<(usize, Table<'a>)> {
        let table = self.any_table()?;
        let Some(type_node) = table.find("type") else {
            return Err(table.node.doc.error(
                self.span.start,
                &join(&self.path, "type"),
                format!("required field is missing: the {what} type, one of {}", one_of(names)),
            ));
        };
        let index = type_node.keyword(what, names)?;
        let mut allowed = vec!["type"];
        allowed.extend(keys(index));
        table.only(&allowed)?;
        Ok((index, Table { allowed, ..table }))
    }

    /// A string naming one of `options` (name, value): its value. An unknown name is an error
    /// listing the names, as [`Node::keyword`]'s.
    pub fn choice<T: Copy>(&self, what: &str, options: &[(&str, T)]) -> Result<T> {
        let names: Vec<&str> = options.iter().map(|o| o.0).collect();
        Ok(options[self.keyword(what, &names)?].1)
    }

    /// A string that must be one of `options`; returns its index.
    pub fn keyword(&self, what: &str, options: &[&str]) -> Result<usize> {
        let s = self.str()?;
        options.iter().position(|o| *o == s).ok_or_else(|| {
            self.err(format!(
                "unknown {what} \"{s}\"{}; expected {}",
                did_you_mean(s, options.iter().copied()),
                one_of(options)
            ))
        })
    }

    pub fn str(&self) -> Result<&'a str> {
        match self.value {
            DeValue::String(s) => Ok(s.as_ref()),
            _ => Err(self.expected("a string")),
        }
    }

    pub fn bool(&self) -> Result<bool> {
        match self.value {
            DeValue::Boolean(b) => Ok(*b),
            _ => Err(self.expected("a boolean (true or false)")),
        }
    }

    /// A finite number (integers are accepted).
    pub fn f64(&self) -> Result<f64> {
        let x = match self.value {
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix()).map(|i| i as f64).ok(),
            DeValue::Float(f) => f.as_str().parse::<f64>().ok(),
            _ => return Err(self.expected("a number")),
        };
        match x {
            Some(x) if x.is_finite() => Ok(x),
            _ => Err(self.err(format!("must be a finite number, got {}", describe(self.value)))),
        }
    }

    /// An integer.
    pub fn int(&self) -> Result<i64> {
        match self.value {
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix())
                .map_err(|_| self.err(format!("integer {i} does not fit in 64 bits"))),
            _ => Err(self.expected("an integer")),
        }
    }

    /// An integer in `lo..=hi`.
    pub fn int_in(&self, lo: i64, hi: i64) -> Result<i64> {
        let i = self.int()?;
        if (lo..=hi).contains(&i) {
            Ok(i)
        } else {
            Err(self.err(format!("must be an integer from {lo} to {hi}, got {i}")))
        }
    }

    pub fn u32_in(&self, lo: u32, hi: u32) -> Result<u32> {
        let i = self.int_in(i64::from(lo), i64::from(hi))?;
        u32::try_from(i).map_err(|_| self.err(format!("{i} is out of range")))
    }

    /// A non-negative integer (TOML integers are signed 64-bit, so up to 2⁶³ − 1).
    pub fn u64(&self) -> Result<u64> {
        let i = self.int_in(0, i64::MAX)?;
        u64::try_from(i).map_err(|_| self.err(format!("{i} is out of range")))
    }

    /// The elements of an array.
    pub fn array(&self) -> Result<Vec<Node<'a>>> {
        match self.value {
            DeValue::Array(a) => Ok(a
                .iter()
                .enumerate()
                .map(|(i, v)| Node {
                    doc: self.doc,
                    value: v.get_ref(),
                    span: v.span(),
                    path: format!("{}[{i}]", self.path),
                })
                .collect()),
            _ => Err(self.expected("an array")),
        }
    }

    /// An array of exactly `N` numbers.
    pub fn numbers<const N: usize>(&self, what: &str) -> Result<[f64; N]> {
        let expected = format!("{what} (an array of {N} numbers)");
        let DeValue::Array(a) = self.value else {
            return Err(self.expected(&expected));
        };
        if a.len() != N {
            return Err(self.err(format!("expected {expected}, got an array of {}", count(a.len(), "element"))));
        }
        let mut out = [0.0; N];
        for (o, e) in out.iter_mut().zip(self.array()?) {
            *o = e.f64()?;
        }
        Ok(out)
    }

    /// A point or vector `[x, y, z]`.
    pub fn vec3(&self) -> Result<Vec3> {
        self.numbers::<3>("a vector").map(Vec3::from_array)
    }

    /// A non-zero direction `[x, y, z]` (not normalised).
    pub fn direction(&self) -> Result<Vec3> {
        let v = self.vec3()?;
        if v.length_squared() > 0.0 && v.length_squared().is_finite() {
            Ok(v)
        } else {
            Err(self.err(format!("must be a non-zero direction, got {}", fmt_vec(v))))
        }
    }

    /// A number or a pair `[x, y]`; a number `x` means `[x, x]`.
    pub fn pair(&self) -> Result<[f64; 2]> {
        if self.is_number() {
            let x = self.f64()?;
            Ok([x, x])
        } else if self.is_array() {
            self.numbers::<2>("a pair")
        } else {
            Err(self.expected("a number or a pair [x, y]"))
        }
    }

    /// A linear RGB colour: `[r, g, b]`, or one number for a grey.
    pub fn colour(&self) -> Result<Rgb> {
        let c = if self.is_number() {
            Rgb::splat(self.f64()? as f32)
        } else if self.is_array() {
            let [r, g, b] = self.numbers::<3>("a colour")?;
            Rgb::new(r as f32, g as f32, b as f32)
        } else {
            return Err(self.expected("a colour ([r, g, b] or a number for grey)"));
        };
        if c.is_finite() {
            Ok(c)
        } else {
            Err(self.err(format!("colour {} is too large", fmt_rgb(c))))
        }
    }
}

/// A kind of table chosen by its `type` key (a shape, a material, a sky, …): the name `type`
/// gives, and the keys it accepts besides `type`. See [`Node::kind`].
pub(crate) trait Tagged {
    fn name(&self) -> &'static str;
    fn keys(&self) -> Vec<&'static str>;
}

/// One named kind of the builder's tables: the `type` that names it, the keys it accepts
/// besides `type`, and `build`, the function that reads those keys and builds it. The three sit
/// in one entry so that no name can be listed without its keys and its builder: a table of
/// these is the only place a kind is known by name, and there is no fallback to build a name
/// that has no entry.
pub(crate) struct Kind<B> {
    pub name: &'static str,
    pub keys: &'static [&'static str],
    pub build: B,
}

impl<B> Tagged for Kind<B> {
    fn name(&self) -> &'static str {
        self.name
    }

    fn keys(&self) -> Vec<&'static str> {
        self.keys.to_vec()
    }
}

/// A table of the document, with the keys it accepts.
#[derive(Clone)]
pub(crate) struct Table<'a> {
    node: Node<'a>,
    table: &'a DeTable<'a>,
    allowed: Vec<&'static str>,
}

impl<'a> Table<'a> {
    /// The document's root table, accepting the keys `allowed`.
    pub fn root(doc: &'a Doc<'a>, root: &'a Spanned<DeTable<'a>>, allowed: &[&'static str]) -> Result<Table<'a>> {
        // The root is a table of no particular value; give it a placeholder value for `Node`.
        static EMPTY: DeValue<'static> = DeValue::Boolean(false);
        let node = Node { doc, value: &EMPTY, span: 0..0, path: String::new() };
        let table = Table { node, table: root.get_ref(), allowed: allowed.to_vec() };
        table.only(allowed)?;
        Ok(table)
    }

    /// Errors on the first key (in file order) not in `allowed`.
    fn only(&self, allowed: &[&'static str]) -> Result<()> {
        let unknown = self.table.iter().filter(|(k, _)| !allowed.contains(&k.get_ref().as_ref()));
        let Some((key, _)) = unknown.min_by_key(|(k, _)| k.span().start) else {
            return Ok(());
        };
        let name = key.get_ref().as_ref();
        let expected = if allowed.is_empty() {
            "this table takes no fields".to_string()
        } else {
            format!("expected {}", one_of(allowed))
        };
        Err(self.node.doc.error(
            key.span().start,
            &join(&self.node.path, name),
            format!("unknown field \"{name}\"{}; {expected}", did_you_mean(name, allowed.iter().copied())),
        ))
    }

    /// An error about the table as a whole.
    pub fn err(&self, message: impl Into<String>) -> SceneError {
        self.node.err(message)
    }

    fn find(&self, key: &str) -> Option<Node<'a>> {
        self.table.get_key_value(key).map(|(_, v)| self.node.child(key, v))
    }

    /// The value of `key`, if given.
    pub fn get(&self, key: &str) -> Option<Node<'a>> {
        // The reader asks only for keys its table declares (a typo here would silently ignore
        // what the user wrote): checked in every build, it costs a scan of a few names.
        assert!(self.allows(key), "{key} not in {:?}", self.allowed);
        self.find(key)
    }

    /// Whether the table declares `key` (a table of no declared keys takes any).
    pub fn allows(&self, key: &str) -> bool {
        self.allowed.is_empty() || self.allowed.contains(&key)
    }

    /// The value of the first of `keys` (spellings of one field) that is given; an error if more
    /// than one is.
    pub fn get_alias(&self, keys: &[&str]) -> Result<Option<Node<'a>>> {
        let mut found = keys.iter().filter_map(|k| self.get(k));
        let first = found.next();
        if let (Some(a), Some(b)) = (&first, found.next()) {
            return Err(b.err(format!("same field as {}; give only one of them", a.path())));
        }
        Ok(first)
    }

    /// The value of `key`, which must be given.
    pub fn require(&self, key: &str) -> Result<Node<'a>> {
        self.get(key).ok_or_else(|| self.missing(key))
    }

    /// The error for a missing required field.
    pub fn missing(&self, key: &str) -> SceneError {
        self.node.doc.error(self.node.span.start, &join(&self.node.path, key), "required field is missing")
    }

    /// Where the value of `key` is, or where it would be (the table) when it is not given.
    pub fn loc(&self, key: &str) -> Loc<'a> {
        match self.find(key) {
            Some(n) => n.loc(),
            None => Loc { doc: self.node.doc, offset: self.node.span.start, path: join(&self.node.path, key) },
        }
    }

    /// `key` read with `read`, which must be given.
    pub fn req<T>(&self, key: &str, read: impl FnOnce(&Node<'a>) -> Result<T>) -> Result<T> {
        read(&self.require(key)?)
    }

    /// `key` read with `read`, if given.
    pub fn opt<T>(&self, key: &str, read: impl FnOnce(&Node<'a>) -> Result<T>) -> Result<Option<T>> {
        self.get(key).map(|n| read(&n)).transpose()
    }

    /// `key` read with `read`, or `default`.
    pub fn or<T>(&self, key: &str, default: T, read: impl FnOnce(&Node<'a>) -> Result<T>) -> Result<T> {
        Ok(self.opt(key, read)?.unwrap_or(default))
    }

    /// The entries in file order.
    pub fn entries(&self) -> Vec<(&'a str, Node<'a>)> {
        let mut entries: Vec<_> = self.table.iter().collect();
        entries.sort_by_key(|(k, _)| k.span().start);
        entries.into_iter().map(|(k, v)| (k.get_ref().as_ref(), self.node.child(k.get_ref(), v))).collect()
    }
}

/// A number as scene files write it (the physics crate's, so that its errors read as ours).
pub(crate) use spacetime::metric::num;

/// `[x, y, z]` as written in scene files.
pub(crate) fn fmt_vec(v: Vec3) -> String {
    format!("[{}, {}, {}]", num(v.x), num(v.y), num(v.z))
}

pub(crate) fn fmt_rgb(c: Rgb) -> String {
    format!("[{}, {}, {}]", num(c.x), num(c.y), num(c.z))
}

/// "1 element", "3 elements".
pub(crate) fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_as_written() {
        assert_eq!(fmt_rgb(Rgb::new(1.1, 0.3, 0.0)), "[1.1, 0.3, 0]");
        assert_eq!(num(1e300), "1e300");
        assert_eq!(num(2.5e-7_f32), "2.5e-7");
        assert_eq!(fmt_vec(Vec3::new(0.1, -4.0, 1e20)), "[0.1, -4, 1e20]");
    }
}
