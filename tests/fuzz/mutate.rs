//! The mutation engine of nullpath's fuzz tests (see `tests/fuzz/README.md`): a seeded random
//! number generator, byte- and text-level mutations steered to the edges of the formats (boundary
//! numbers, long runs, deep nesting, pieces of other corpus inputs), a structural mutator for
//! JSON, and a runner that checks each input under `catch_unwind` within a time limit, and on a
//! failure saves the input, minimises it and fails the test with both.
//!
//! cargo-fuzz needs a nightly toolchain; these run as ordinary tests, deterministically: the same
//! seed makes the same inputs everywhere. `NULLPATH_FUZZ_ITERATIONS` sets how many inputs each
//! target makes (its default keeps `cargo test --release` short), `NULLPATH_FUZZ_SEED` which ones.
//!
//! Included by each fuzz test with `#[path = "fuzz/mutate.rs"] mod mutate;`.

#![allow(dead_code)] // Each fuzz test uses its share.
#![allow(clippy::unwrap_used)] // A panic is a failed test.

use serde_json::Value;
use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;
use std::hash::{Hash, Hasher};
use std::io::Write;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, Once};
use std::time::{Duration, Instant};

/// Overrides every target's number of inputs: `NULLPATH_FUZZ_ITERATIONS=1000000`.
pub const ITERATIONS_VAR: &str = "NULLPATH_FUZZ_ITERATIONS";
/// Picks another sequence of inputs (decimal or `0x` hex): `NULLPATH_FUZZ_SEED=7`.
pub const SEED_VAR: &str = "NULLPATH_FUZZ_SEED";
/// A file checked before the corpus: `NULLPATH_FUZZ_REPLAY=target/tmp/fuzz-crashes/scene/<hash>.min`
/// (name the one test it belongs to).
pub const REPLAY_VAR: &str = "NULLPATH_FUZZ_REPLAY";
/// When set, each input is written to `<crash folder>/current` before it is checked, so that one
/// that aborts the process (a stack overflow, memory exhausted) is left behind.
pub const TRACE_VAR: &str = "NULLPATH_FUZZ_TRACE";

/// How many inputs a target makes: `default`, unless [`ITERATIONS_VAR`] says otherwise.
pub fn iterations(default: usize) -> usize {
    match std::env::var(ITERATIONS_VAR) {
        Ok(v) => v.trim().replace('_', "").parse().unwrap_or_else(|_| panic!("{ITERATIONS_VAR}={v:?} is not a count")),
        Err(_) => default,
    }
}

/// The random generator of a target: seeded by [`SEED_VAR`] when set (mixed with the target's
/// own `salt`, so that targets differ), else by `salt` alone.
pub fn random(salt: u64) -> Random {
    let seed = match std::env::var(SEED_VAR) {
        Ok(v) => {
            let v = v.trim();
            let parsed = match v.strip_prefix("0x") {
                Some(hex) => u64::from_str_radix(hex, 16),
                None => v.parse(),
            };
            parsed.unwrap_or_else(|_| panic!("{SEED_VAR}={v:?} is not a number"))
        }
        Err(_) => 0,
    };
    Random(salt ^ seed.wrapping_mul(0x9e37_79b9_7f4a_7c15))
}

/// splitmix64: a fixed seed gives the same run everywhere.
#[derive(Clone, Debug)]
pub struct Random(pub u64);

impl Random {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A number below `n` (> 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    /// True once in `n` times.
    pub fn one_in(&mut self, n: usize) -> bool {
        self.below(n) == 0
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }

    /// A length for a run: mostly short, sometimes long.
    pub fn run_length(&mut self, max: usize) -> usize {
        let scale = [4, 16, 64, 1024, 65536][self.below(5)];
        (1 + self.below(scale)).min(max.max(1))
    }
}

/// A corpus input: the file's name and bytes.
#[derive(Clone, Debug)]
pub struct Seed {
    pub name: String,
    pub bytes: Vec<u8>,
}

/// The folder of `target`'s corpus: `tests/fuzz/corpus/<target>/`.
pub fn corpus_dir(target: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz/corpus").join(target)
}

/// The inputs of `target`'s corpus whose names end with one of `extensions`, sorted by name (the
/// order of a directory listing is the file system's; the run must not depend on it).
pub fn corpus(target: &str, extensions: &[&str]) -> Vec<Seed> {
    let dir = corpus_dir(target);
    let mut seeds: Vec<Seed> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.is_file())
        .filter(|path| extensions.iter().any(|ext| path.extension().is_some_and(|e| e == *ext)))
        .map(|path| Seed {
            name: path.file_name().unwrap().to_string_lossy().to_string(),
            bytes: std::fs::read(&path).unwrap(),
        })
        .collect();
    seeds.sort_by(|a, b| a.name.cmp(&b.name));
    assert!(!seeds.is_empty(), "no corpus in {}", dir.display());
    seeds
}

/// The inputs that once failed `target` (`tests/fuzz/regressions/<target>/`, any file), checked
/// at the start of every run; none if the folder does not exist.
pub fn regressions(target: &str) -> Vec<Vec<u8>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz/regressions").join(target);
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Vec::new();
    };
    let mut paths: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).filter(|p| p.is_file()).collect();
    paths.sort();
    paths.iter().map(|p| std::fs::read(p).unwrap()).collect()
}

/// Numbers at the edges of what parsers and checks expect: zeros, signs, the ends of `f64`, `f32`
/// and the integer types, the specials, and things that look like numbers but are not.
pub const BOUNDARY_NUMBERS: &[&str] = &[
    "0",
    "-0",
    "0.0",
    "-0.0",
    "1",
    "-1",
    "2",
    "3",
    "0.5",
    "-0.5",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "1e309",
    "1e-308",
    "5e-324",
    "1e-400",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "+inf",
    "NaN",
    "9223372036854775807",
    "9223372036854775808",
    "-9223372036854775808",
    "-9223372036854775809",
    "18446744073709551615",
    "18446744073709551616",
    "4294967295",
    "4294967296",
    "2147483647",
    "2147483648",
    "65535",
    "65536",
    "16384",
    "16385",
    "1048576",
    "33554432",
    "1e20",
    "1e21",
    "1e-20",
    "1e12",
    "1e-13",
    "3.4028235e38",
    "3.5e38",
    "1e-45",
    "1.0000000000000002",
    "0.9999999999999999",
    "1_000",
    "0x10",
    "0o7",
    "0b1",
    "1e",
    "1.",
    ".5",
    "00",
    "1e+",
    "--1",
    "99999999999999999999999999999999999999",
];

/// Integers for binary fields (`u32` little-endian): lengths, counts and magic numbers at their
/// edges.
const BOUNDARY_U32: &[u32] = &[
    0,
    1,
    2,
    3,
    4,
    12,
    20,
    0x7f,
    0x80,
    0xff,
    0x100,
    0xffff,
    0x1_0000,
    0x7fff_ffff,
    0x8000_0000,
    0xffff_fffe,
    0xffff_ffff,
    0x4e4f_534a, // "JSON"
    0x004e_4942, // "BIN\0"
    0x4654_6c67, // "glTF"
];

/// Bytes worth inserting on their own.
const INTERESTING_BYTES: &[u8] = b"\0\xff\xfe\x80\xc3\xe2\n\r\t \"'\\[]{}()=,.:;#-+*/^e0129";

/// Byte- and text-level mutations, steered by a target's dictionary and nesting pairs.
#[derive(Clone, Debug)]
pub struct Mutator {
    /// Pieces of the format (keys, values, keywords) worth inserting whole.
    pub tokens: Vec<Vec<u8>>,
    /// Pairs that nest (`[` and `]`, `(` and `)`, `{"a":` and `}`): opened and closed many times
    /// over to reach the parsers' depth bounds.
    pub nesting: Vec<(Vec<u8>, Vec<u8>)>,
    /// The longest input made.
    pub max_len: usize,
}

impl Mutator {
    pub fn new(tokens: &[&[u8]], nesting: &[(&str, &str)], max_len: usize) -> Self {
        Self {
            tokens: tokens.iter().map(|t| t.to_vec()).collect(),
            nesting: nesting.iter().map(|(a, b)| (a.as_bytes().to_vec(), b.as_bytes().to_vec())).collect(),
            max_len,
        }
    }

    /// `input` changed in one to four random ways, some of them borrowed from `other`.
    pub fn mutate(&self, random: &mut Random, input: &[u8], other: &[u8]) -> Vec<u8> {
        let mut out = input.to_vec();
        for _ in 0..=random.below(4) {
            self.once(random, &mut out, other);
        }
        out.truncate(self.max_len);
        out
    }

    /// One mutation of `out`.
    pub fn once(&self, random: &mut Random, out: &mut Vec<u8>, other: &[u8]) {
        let at = random.below(out.len() + 1);
        let room = self.max_len.saturating_sub(out.len());
        match random.below(18) {
            0 if at < out.len() => out[at] ^= 1 << random.below(8),
            1 if at < out.len() => out[at] = random.next() as u8,
            2 => out.insert(at, *random.pick(INTERESTING_BYTES)),
            3 => {
                let end = (at + random.run_length(out.len())).min(out.len());
                out.drain(at..end);
            }
            // Three times as often as the others: the dictionary is what steers a run.
            4 | 16 | 17 if !self.tokens.is_empty() => {
                let token = random.pick(&self.tokens).clone();
                out.splice(at..at, token);
            }
            5 => out.truncate(at),
            6 => {
                // A run of the input repeated: long lines, many keys, long arrays.
                let start = random.below(out.len() + 1);
                let end = (start + random.below(64)).min(out.len());
                let most = if random.one_in(4) { 2000 } else { 8 };
                let times = 1 + random.below(most);
                let piece = out[start..end].repeat(times);
                let piece = &piece[..piece.len().min(room)];
                out.splice(at..at, piece.iter().copied());
            }
            7 => {
                let start = random.below(other.len() + 1);
                let end = (start + random.run_length(256)).min(other.len());
                out.splice(at..at, other[start..end].iter().copied());
            }
            8 => {
                // Crossover: this input's beginning, the other's end.
                let from = random.below(other.len() + 1);
                out.truncate(at);
                out.extend_from_slice(&other[from..]);
            }
            9 => splice_lines(random, out, other),
            10 => replace_number(random, out),
            11 => {
                let n = random.run_length(room.min(100_000));
                let piece: Vec<u8> = match random.below(4) {
                    0 => vec![b'a'; n],
                    1 => vec![b'9'; n],
                    2 => [b"\"".as_slice(), &vec![b'x'; n], b"\""].concat(),
                    _ => "\u{1f30c}".repeat(n / 4 + 1).into_bytes(),
                };
                out.splice(at..at, piece);
            }
            12 if !self.nesting.is_empty() => {
                let (open, close) = random.pick(&self.nesting).clone();
                let depth = *random.pick(&[8, 64, 99, 100, 101, 127, 128, 129, 256, 1000, 5000, 50_000]);
                let depth = depth.min(room / (open.len() + close.len()).max(1));
                let mut piece = open.repeat(depth);
                if random.one_in(3) {
                    // Something inside: a piece of the input.
                    let start = random.below(out.len() + 1);
                    piece.extend_from_slice(&out[start..(start + random.below(32)).min(out.len())]);
                }
                if !random.one_in(4) {
                    piece.extend(close.repeat(depth));
                }
                out.splice(at..at, piece);
            }
            13 if out.len() >= 4 => {
                // A little-endian u32 overwritten: a binary length, count or magic number.
                let at = if random.one_in(2) { random.below(out.len() / 4) * 4 } else { random.below(out.len() - 3) };
                let value = match random.below(4) {
                    0 => out.len() as u32,
                    1 => (out.len() as u32).wrapping_add(1),
                    2 => (out.len() as u32).wrapping_sub(1),
                    _ => *random.pick(BOUNDARY_U32),
                };
                out[at..at + 4].copy_from_slice(&value.to_le_bytes());
            }
            14 => {
                // A chunk moved elsewhere.
                let start = random.below(out.len() + 1);
                let end = (start + random.run_length(128)).min(out.len());
                let piece: Vec<u8> = out.drain(start..end).collect();
                let to = random.below(out.len() + 1);
                out.splice(to..to, piece);
            }
            _ => out.insert(at, random.next() as u8),
        }
    }
}

/// A run of `out`'s lines replaced by a run of `other`'s (or of its own): line-based formats such
/// as TOML stay mostly well-formed while their tables and keys are rearranged.
pub fn splice_lines(random: &mut Random, out: &mut Vec<u8>, other: &[u8]) {
    let source = if random.one_in(3) { out.clone() } else { other.to_vec() };
    let lines = |b: &[u8]| -> Vec<usize> {
        let mut starts = vec![0];
        starts.extend(b.iter().enumerate().filter(|(_, &c)| c == b'\n').map(|(i, _)| i + 1));
        starts.push(b.len());
        starts
    };
    let (ours, theirs) = (lines(out), lines(&source));
    let i = random.below(ours.len());
    let j = (i + random.below(3)).min(ours.len() - 1);
    let k = random.below(theirs.len());
    let l = (k + 1 + random.below(6)).min(theirs.len() - 1);
    let piece = source[theirs[k]..theirs[l].max(theirs[k])].to_vec();
    out.splice(ours[i]..ours[j], piece);
}

/// Where `text` holds numbers: runs of digits with their signs, points and exponents.
fn numbers(text: &[u8]) -> Vec<(usize, usize)> {
    let part = |c: u8| c.is_ascii_digit() || matches!(c, b'.' | b'e' | b'E' | b'+' | b'-' | b'_');
    let mut spans = Vec::new();
    let mut i = 0;
    while i < text.len() {
        if part(text[i]) && (i == 0 || !text[i - 1].is_ascii_alphanumeric()) {
            let start = i;
            while i < text.len() && part(text[i]) {
                i += 1;
            }
            if text[start..i].iter().any(u8::is_ascii_digit) {
                spans.push((start, i));
            }
        } else {
            i += 1;
        }
    }
    spans
}

/// One number of `out` replaced by a boundary value (or one inserted where there is none).
pub fn replace_number(random: &mut Random, out: &mut Vec<u8>) {
    let value = random.pick(BOUNDARY_NUMBERS).as_bytes();
    let spans = numbers(out);
    if spans.is_empty() {
        let at = random.below(out.len() + 1);
        out.splice(at..at, value.iter().copied());
    } else {
        let (start, end) = *random.pick(&spans);
        out.splice(start..end, value.iter().copied());
    }
}

/// Values at JSON's edges, for [`mutate_json`].
fn boundary_json(random: &mut Random) -> Value {
    use serde_json::json;
    match random.below(10) {
        0..=2 => json!(random.below(6)),
        3 => {
            let n: f64 = random.pick(BOUNDARY_NUMBERS).parse().unwrap_or(0.0);
            serde_json::Number::from_f64(n).map_or(Value::Null, Value::Number)
        }
        4 => json!(*random.pick(&[
            -1i64,
            i64::MAX,
            i64::MIN,
            u32::MAX as i64,
            1 << 32,
            1 << 53,
            5120,
            5121,
            5122,
            5123,
            5125,
            5126,
            34962,
            34963,
            9729,
            10497,
        ])),
        5 => json!(*random.pick(&[
            "",
            "VEC2",
            "VEC3",
            "VEC4",
            "SCALAR",
            "MAT4",
            "2.0",
            "1.0",
            "3.0",
            "image/png",
            "image/jpeg",
            "data:application/octet-stream;base64,",
            "data:application/octet-stream;base64,AAAA",
            "data:,x",
            "../../../etc/passwd",
            "%2E%2E/x.bin",
            "file:///dev/zero",
            "http://example.com/x.bin",
            "x.gltf",
            "/",
            "KHR_draco_mesh_compression",
            "KHR_lights_punctual",
            "point",
            "spot",
            "directional",
            "perspective",
            "orthographic",
            "\u{0}",
        ])),
        6 => json!("a".repeat(random.run_length(100_000))),
        7 => random.pick(&[Value::Null, Value::Bool(true), Value::Bool(false)]).clone(),
        8 => json!([]),
        _ => json!({}),
    }
}

/// How many nodes `value` has, itself included.
fn count(value: &Value) -> usize {
    1 + match value {
        Value::Array(items) => items.iter().map(count).sum(),
        Value::Object(map) => map.values().map(count).sum(),
        _ => 0,
    }
}

/// The path (keys and indices) to node `k` of `value` in pre-order, counting `value` itself as 0.
fn nth_node(value: &Value, mut k: usize) -> Vec<String> {
    let mut path = Vec::new();
    let mut node = value;
    while k > 0 {
        k -= 1;
        let children: Vec<(String, &Value)> = match node {
            Value::Array(items) => items.iter().enumerate().map(|(i, v)| (i.to_string(), v)).collect(),
            Value::Object(map) => map.iter().map(|(key, v)| (key.clone(), v)).collect(),
            _ => Vec::new(),
        };
        let mut found = false;
        for (key, child) in children {
            let size = count(child);
            if k < size {
                path.push(key);
                node = child;
                found = true;
                break;
            }
            k -= size;
        }
        if !found {
            break;
        }
    }
    path
}

/// The path to a node of `value` picked at random.
fn random_node(random: &mut Random, value: &Value) -> Vec<String> {
    let k = random.below(count(value));
    nth_node(value, k)
}

fn pointer(path: &[String]) -> String {
    path.iter().map(|p| format!("/{}", p.replace('~', "~0").replace('/', "~1"))).collect()
}

/// One structural change to a JSON document: a node replaced by a boundary value or by a node of
/// `other`, removed, duplicated, or nested deep. The document stays JSON, so the change reaches
/// past the parser into what reads the document.
pub fn mutate_json(random: &mut Random, doc: &mut Value, other: &Value) {
    let path = random_node(random, doc);
    let replacement = match random.below(10) {
        0..=2 => Some(boundary_json(random)),
        8 | 9 => match doc.pointer(&pointer(&path)) {
            // A number nudged: an index to its neighbour, a length one short, a scale turned over.
            Some(Value::Number(n)) => {
                let x = n.as_f64().unwrap_or(0.0);
                let nudged = match random.below(5) {
                    0 => x + 1.0,
                    1 => x - 1.0,
                    2 => x * 2.0,
                    3 => -x,
                    _ => x / 2.0,
                };
                Some(match n.as_i64() {
                    Some(_) if nudged.fract() == 0.0 && nudged.abs() < 9e15 => Value::from(nudged as i64),
                    _ => serde_json::Number::from_f64(nudged).map_or(Value::Null, Value::Number),
                })
            }
            _ => Some(boundary_json(random)),
        },
        3 => {
            let theirs = random_node(random, other);
            other.pointer(&pointer(&theirs)).cloned()
        }
        4 => {
            // Removed: a key from its object, an element from its array.
            if let Some((last, parent)) = path.split_last() {
                match doc.pointer_mut(&pointer(parent)) {
                    Some(Value::Object(map)) => {
                        map.remove(last);
                    }
                    Some(Value::Array(items)) => {
                        if let Ok(i) = last.parse::<usize>() {
                            if i < items.len() {
                                items.remove(i);
                            }
                        }
                    }
                    _ => {}
                }
            }
            None
        }
        5 => {
            // An array's elements repeated: many nodes, children listed twice.
            if let Some(Value::Array(items)) = doc.pointer_mut(&pointer(&path)) {
                if !items.is_empty() {
                    // At most some thousands of elements and 64 KiB more: documents stay small enough
                    // to make fast.
                    let size = serde_json::to_vec(items).map_or(1, |v| v.len());
                    let times = (*random.pick(&[1, 2, 16, 1000])).min(4096 / items.len()).min(65536 / size);
                    let copy = items.clone();
                    for _ in 0..times {
                        items.extend(copy.iter().cloned());
                    }
                }
            }
            None
        }
        6 => {
            let node = doc.pointer(&pointer(&path)).cloned().unwrap_or(Value::Null);
            let mut nested = node;
            for _ in 0..*random.pick(&[2, 64, 127, 128, 129, 1000]) {
                nested = if random.one_in(2) {
                    Value::Array(vec![nested])
                } else {
                    // (Not `json!`, which would copy `nested` at every level.)
                    Value::Object([("a".to_string(), nested)].into_iter().collect())
                };
            }
            Some(nested)
        }
        _ => {
            // Another node of the same document: indices and types swapped around.
            let source = random_node(random, doc);
            doc.pointer(&pointer(&source)).cloned()
        }
    };
    if let Some(replacement) = replacement {
        if let Some(node) = doc.pointer_mut(&pointer(&path)) {
            *node = replacement;
        }
    }
}

/// What a check makes of an input: the name of its outcome (counted, e.g. `"loaded"` or
/// `"refused"`), or what is wrong with how the code under test answered it.
pub type Verdict = Result<&'static str, String>;

type Check = dyn Fn(&[u8]) -> Verdict;

/// How a check ended.
#[derive(Clone, Debug)]
enum Ending {
    Passed(&'static str),
    /// The check found the answer wrong.
    Failed(String),
    /// The code under test panicked: the panic's location and message.
    Panicked(String),
    TimedOut,
}

impl Ending {
    /// Whether two failures are the same: the same kind, and for panics the same place.
    fn same(&self, other: &Ending) -> bool {
        match (self, other) {
            (Ending::Failed(_), Ending::Failed(_)) => true,
            (Ending::Panicked(a), Ending::Panicked(b)) => a.lines().next() == b.lines().next(),
            _ => false,
        }
    }
}

struct Report {
    ending: Ending,
    /// Panics caught inside the code under test (which answered anyway): where each was.
    contained: Vec<String>,
    elapsed: Duration,
}

thread_local! {
    /// Whether this thread is checking a fuzz input: its panics are recorded, not printed.
    static CHECKING: Cell<bool> = const { Cell::new(false) };
    static PANICS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Records the panics of threads checking inputs (location and message), leaving the others' to
/// the hook that was there.
fn install_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if CHECKING.with(Cell::get) {
                PANICS.with(|p| p.borrow_mut().push(info.to_string()));
            } else {
                previous(info);
            }
        }));
    });
}

/// Checks `input` on this thread, its panics caught.
fn check_here(check: &Check, input: &[u8]) -> Report {
    install_hook();
    PANICS.with(|p| p.borrow_mut().clear());
    CHECKING.with(|c| c.set(true));
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| check(input)));
    let elapsed = start.elapsed();
    CHECKING.with(|c| c.set(false));
    let panics = PANICS.with(|p| std::mem::take(&mut *p.borrow_mut()));
    let mut panics = panics;
    let ending = match result {
        Ok(Ok(outcome)) => Ending::Passed(outcome),
        Ok(Err(message)) => Ending::Failed(message),
        Err(payload) => {
            let message = panics.last().cloned().unwrap_or_else(|| {
                payload
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_else(|| "a panic".to_string())
            });
            panics.pop();
            Ending::Panicked(message)
        }
    };
    let contained = panics.iter().map(|p| p.lines().next().unwrap_or_default().to_string()).collect();
    Report { ending, contained, elapsed }
}

/// The input being checked and since when, for the watchdog.
#[derive(Default)]
struct Watch {
    current: Mutex<Option<(Instant, Vec<u8>)>>,
    done: AtomicBool,
}

/// A thread that ends the process when the input being checked has run past `limit`: a hang
/// would never return to be timed. It saves the input and says so on standard error (past the
/// test harness's capture, which the exit would lose).
fn watchdog(target: &'static str, limit: Duration) -> Arc<Watch> {
    let watch = Arc::new(Watch::default());
    let watched = watch.clone();
    std::thread::Builder::new()
        .name(format!("fuzz-{target}-watchdog"))
        .spawn(move || {
            while !watched.done.load(Ordering::Relaxed) {
                std::thread::sleep((limit / 4).min(Duration::from_millis(100)));
                let current = watched.current.lock().unwrap_or_else(|e| e.into_inner());
                if let Some((start, input)) = current.as_ref().filter(|(start, _)| start.elapsed() > limit) {
                    let path = save(target, input, None);
                    let _ = writeln!(
                        std::io::stderr(),
                        "fuzz target {target}: an input has run for {:?}, more than {limit:?}; saved to {}: {}",
                        start.elapsed(),
                        path.display(),
                        shown(input)
                    );
                    std::process::exit(101);
                }
            }
        })
        .unwrap();
    watch
}

/// Counts of a run, for its summary and for tests that want every outcome reached.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    pub inputs: usize,
    pub outcomes: BTreeMap<&'static str, usize>,
    /// Panics caught by the code under test itself (it answered with an error), by where they were.
    pub contained_panics: BTreeMap<String, usize>,
    pub slowest: Duration,
    /// Time spent checking inputs (the rest of `elapsed` made them).
    pub checking: Duration,
    pub elapsed: Duration,
}

/// Checks inputs for one target, failing the test on the first that panics, fails its check or
/// runs past the time limit. Inputs are checked on the calling thread.
pub struct Runner {
    target: &'static str,
    limit: Duration,
    check: Box<Check>,
    /// `None`: the limit applies once an input returns (for checks that cannot hang).
    watch: Option<Arc<Watch>>,
    trace: bool,
    started: Instant,
    pub stats: Stats,
}

impl Runner {
    /// With a watchdog thread: an input that runs past `limit` ends the run even if it never
    /// returns.
    pub fn watched(target: &'static str, limit: Duration, check: impl Fn(&[u8]) -> Verdict + 'static) -> Self {
        Self::new(target, limit, Box::new(check), Some(watchdog(target, limit)))
    }

    /// An input that took longer than `limit` fails the test once it returns.
    pub fn inline(target: &'static str, limit: Duration, check: impl Fn(&[u8]) -> Verdict + 'static) -> Self {
        Self::new(target, limit, Box::new(check), None)
    }

    fn new(target: &'static str, limit: Duration, check: Box<Check>, watch: Option<Arc<Watch>>) -> Self {
        Self {
            target,
            limit,
            check,
            watch,
            trace: std::env::var_os(TRACE_VAR).is_some(),
            started: Instant::now(),
            stats: Stats::default(),
        }
    }

    fn attempt(&mut self, input: &[u8]) -> Report {
        let watch = |current| {
            if let Some(watch) = &self.watch {
                *watch.current.lock().unwrap_or_else(|e| e.into_inner()) = current;
            }
        };
        watch(Some((Instant::now(), input.to_vec())));
        let mut report = check_here(&*self.check, input);
        watch(None);
        if report.elapsed > self.limit && matches!(report.ending, Ending::Passed(_)) {
            report.ending = Ending::TimedOut;
        }
        report
    }

    /// Checks `input`; its outcome, or the test fails with the input saved and minimised.
    pub fn run(&mut self, input: &[u8]) -> &'static str {
        if self.trace {
            let dir = crash_dir(self.target);
            std::fs::create_dir_all(&dir).unwrap();
            // A new file each time: rewriting one in place makes ext4 flush it when it is closed.
            let _ = std::fs::remove_file(dir.join("current"));
            std::fs::write(dir.join("current"), input).unwrap();
        }
        let report = self.attempt(input);
        self.stats.inputs += 1;
        for site in report.contained {
            *self.stats.contained_panics.entry(site).or_default() += 1;
        }
        self.stats.slowest = self.stats.slowest.max(report.elapsed);
        self.stats.checking += report.elapsed;
        match report.ending {
            Ending::Passed(outcome) => {
                *self.stats.outcomes.entry(outcome).or_default() += 1;
                outcome
            }
            ending => self.fail(input, ending),
        }
    }

    /// The smallest input found (by removing pieces of `input`) that still fails as `ending`.
    fn minimise(&mut self, input: &[u8], ending: &Ending) -> Vec<u8> {
        let deadline = Instant::now() + Duration::from_secs(60);
        let mut best = input.to_vec();
        let mut chunk = best.len().div_ceil(2);
        while chunk >= 1 && Instant::now() < deadline {
            let mut progressed = false;
            let mut i = 0;
            while i < best.len() && Instant::now() < deadline {
                let candidate = [&best[..i], &best[(i + chunk).min(best.len())..]].concat();
                if self.attempt(&candidate).ending.same(ending) {
                    best = candidate;
                    progressed = true;
                } else {
                    i += chunk;
                }
            }
            if !progressed {
                chunk /= 2;
            }
        }
        best
    }

    fn fail(&mut self, input: &[u8], ending: Ending) -> ! {
        let path = save(self.target, input, None);
        let what = match &ending {
            Ending::Failed(message) => format!("the check failed: {message}"),
            Ending::Panicked(message) => format!("a panic: {message}"),
            Ending::TimedOut => format!("an input took longer than {:?}", self.limit),
            Ending::Passed(_) => unreachable!(),
        };
        let (minimal, minimal_path) = if matches!(ending, Ending::TimedOut) {
            (input.to_vec(), path.clone())
        } else {
            let minimal = self.minimise(input, &ending);
            let minimal_path = save(self.target, input, Some((&minimal, "min")));
            (minimal, minimal_path)
        };
        panic!(
            "fuzz target {}, input {} of the run: {what}\ninput ({} bytes) saved to {}\nminimised ({} bytes, {}): {}",
            self.target,
            self.stats.inputs,
            input.len(),
            path.display(),
            minimal.len(),
            minimal_path.display(),
            shown(&minimal),
        );
    }

    /// Prints the run's counts (seen with `--nocapture`) and returns them.
    pub fn finish(&mut self) -> Stats {
        self.stats.elapsed = self.started.elapsed();
        let s = &self.stats;
        eprintln!(
            "fuzz {}: {} inputs in {:.2} s ({:.2} s checking them, slowest {:.1} ms), outcomes {:?}, panics contained by \
             the code {:?}",
            self.target,
            s.inputs,
            s.elapsed.as_secs_f64(),
            s.checking.as_secs_f64(),
            s.slowest.as_secs_f64() * 1e3,
            s.outcomes,
            s.contained_panics,
        );
        s.clone()
    }
}

impl Drop for Runner {
    fn drop(&mut self) {
        if let Some(watch) = &self.watch {
            watch.done.store(true, Ordering::Relaxed);
        }
    }
}

/// Saves the failing `input` of `target` (or, given `(bytes, extension)`, those bytes named after
/// it) to the crash folder; where.
fn save(target: &str, input: &[u8], derived: Option<(&[u8], &str)>) -> PathBuf {
    let dir = crash_dir(target);
    std::fs::create_dir_all(&dir).unwrap();
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    input.hash(&mut hasher);
    let path = dir.join(format!("{:016x}", hasher.finish()));
    let (path, bytes) = match derived {
        Some((bytes, extension)) => (path.with_extension(extension), bytes),
        None => (path, input),
    };
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Where a target's failing inputs are saved: `target/tmp/fuzz-crashes/<target>/`.
pub fn crash_dir(target: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz-crashes").join(target)
}

/// `input` for a message: as text where it is text, escaped, at most 4000 characters.
pub fn shown(input: &[u8]) -> String {
    let text = String::from_utf8_lossy(&input[..input.len().min(4000)]);
    let more = if input.len() > 4000 { format!(" … ({} bytes more)", input.len() - 4000) } else { String::new() };
    format!("{text:?}{more}")
}

/// The usual loop: the file [`REPLAY_VAR`] names if any, the target's [`regressions`], each seed
/// as it is, then `iterations` mutants of mutants of the pool (the
/// corpus, grown by the mutants whose outcome `keep` accepts, which reach further into the code
/// than the corpus does), each made by `mutate(random, input, other)`.
pub fn drive(
    runner: &mut Runner,
    seeds: &[Seed],
    random: &mut Random,
    iterations: usize,
    mut mutate: impl FnMut(&mut Random, &[u8], &[u8]) -> Vec<u8>,
    keep: impl Fn(&'static str) -> bool,
) -> Stats {
    const POOL: usize = 256;
    let mut pool: Vec<Vec<u8>> = seeds.iter().map(|s| s.bytes.clone()).collect();
    if let Some(path) = std::env::var_os(REPLAY_VAR) {
        let input = std::fs::read(&path).unwrap_or_else(|e| panic!("{REPLAY_VAR}={path:?}: {e}"));
        let outcome = runner.run(&input);
        eprintln!("fuzz {}: {path:?} passes: {outcome}", runner.target);
    }
    for input in regressions(runner.target) {
        runner.run(&input);
    }
    for seed in seeds {
        runner.run(&seed.bytes);
    }
    for _ in 0..iterations {
        let input = random.below(pool.len());
        let other = random.below(pool.len());
        let mut mutant = mutate(random, &pool[input], &pool[other]);
        for _ in 0..random.below(3) {
            mutant = mutate(random, &mutant, &pool[other]);
        }
        let outcome = runner.run(&mutant);
        if keep(outcome) && mutant.len() <= 16 * 1024 {
            if pool.len() < seeds.len() + POOL {
                pool.push(mutant);
            } else {
                let slot = seeds.len() + random.below(POOL);
                pool[slot] = mutant;
            }
        }
    }
    runner.finish()
}
