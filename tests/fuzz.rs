//! Deterministic mutational fuzzing of what reads untrusted text and files (see
//! `tests/fuzz/README.md`): the scene reader, the glTF importer (`.gltf` and `.glb`) and the
//! metric expression compiler (on its own and inside a scene). Each target mutates the real inputs
//! of its corpus, `tests/fuzz/corpus/<target>/`, and checks that no input panics or runs long and
//! that every refusal is a well-formed error. (The preview's HTTP request parser has its own, in
//! `tests/preview_http_request.rs`.)

#![allow(clippy::unwrap_used)] // A panic is a failed test.

#[path = "fuzz/mutate.rs"]
mod mutate;

use mutate::{Mutator, Random, Runner, Seed, Verdict};
use serde_json::Value;
use spacetime::metric::expression::{Expression, Names};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The most an input may take: scenes and glTF files this small load in milliseconds; the loader
/// refuses what would take long. Unoptimised builds are given longer.
fn limit() -> Duration {
    Duration::from_secs(if cfg!(debug_assertions) { 20 } else { 2 })
}

/// How many inputs a target makes: `release` in optimised builds (a few seconds each), a quarter
/// of it in unoptimised ones, unless `NULLPATH_FUZZ_ITERATIONS` says otherwise.
fn budget(release: usize) -> usize {
    mutate::iterations(if cfg!(debug_assertions) { release / 4 } else { release })
}

/// A folder of this process and thread, for the files a check writes.
fn scratch(target: &str) -> PathBuf {
    let thread = format!("{:?}", std::thread::current().id()).replace(|c: char| !c.is_ascii_alphanumeric(), "");
    let dir = std::env::temp_dir().join(format!("nullpath-fuzz-{}-{target}-{thread}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `bytes` to a new file at `path`. (Rewriting a file in place makes ext4 flush it to disk
/// when it is closed, which under load costs milliseconds an input.)
fn write_new(path: &Path, bytes: &[u8]) {
    let _ = std::fs::remove_file(path);
    std::fs::write(path, bytes).unwrap();
}

/// What must hold of a scene loader's refusal: one line, `origin:line:column: …`, a line within
/// the text, and something said.
fn well_formed(error: &scene::SceneError, origin: &str, text: &str) -> Result<(), String> {
    let shown = error.to_string();
    let lines = text.split('\n').count();
    if !shown.starts_with(&format!("{origin}:")) {
        return Err(format!("the error does not start with the file's name: {shown:?}"));
    }
    match (error.line(), error.column()) {
        (Some(line), Some(column)) if (1..=lines).contains(&line) && column >= 1 => {}
        _ => return Err(format!("the error has no line and column in the file ({lines} lines): {shown:?}")),
    }
    if error.message().trim().is_empty() {
        return Err(format!("the error says nothing: {shown:?}"));
    }
    if shown.contains('\n') {
        return Err(format!("the error is more than one line: {shown:?}"));
    }
    Ok(())
}

/// The scene text `text` (`origin` in messages), read with files under `base`.
fn parse_scene(text: &str, origin: &str, base: &Path) -> Verdict {
    match scene::parse(text, origin, base) {
        Ok(_) => Ok("loaded"),
        Err(e) => well_formed(&e, origin, text).map(|()| "refused"),
    }
}

// ---------------------------------------------------------------------------------------------
// The scene reader.

/// Pieces of scene files: tables, keys, values of every kind the format has.
const SCENE_TOKENS: &[&[u8]] = &[
    b"\n",
    b" = ",
    b"[spacetime]\n",
    b"[camera]\n",
    b"[render]\n",
    b"[sky]\n",
    b"[lower.sky]\n",
    b"[lower]\n",
    b"[animation]\n",
    b"[accretion_disk]\nouter_radius = 20\n",
    b"[[objects]]\n",
    b"[materials.x]\n",
    b"[views.v]\nposition = [0, 0, 9]\nlook_at = [0, 0, 0]\n",
    b"[[camera.keyframes]]\ntime = 1\nposition = [0, 1, 8]\nlook_at = [0, 0, 0]\n",
    b"type = \"schwarzschild\"\nmass = 1\n",
    b"type = \"kerr\"\nmass = 1\nspin = 0.99\n",
    b"type = \"kerr-newman\"\nmass = 1\nspin = 0.6\ncharge = 0.8\n",
    b"type = \"reissner-nordstrom\"\n",
    b"type = \"ellis\"\nthroat = 1\n",
    b"type = \"wormhole\"\nthroat = 1\nlensing_width = 0.05\n",
    b"type = \"metric\"\ng_tt = \"-1\"\ng_xx = \"1\"\ng_yy = \"1\"\ng_zz = \"1\"\n",
    b"type = \"minkowski\"\n",
    b"mass = ",
    b"spin = ",
    b"charge = ",
    b"throat = ",
    b"length = ",
    b"axis = [0, 0, 1]\n",
    b"region = \"lower\"\n",
    b"projection = \"fisheye\"\n",
    b"projection = \"ods\"\n",
    b"projection = \"equirectangular\"\n",
    b"velocity = [0, 0, -0.999999]\n",
    b"velocity = \"from-path\"\n",
    b"speed_of_light = 1e-9\n",
    b"orbit = { center = [0, 0, 0], period = 1e-300 }\n",
    b"gltf_camera = \"cam\"\n",
    b"aperture = 1e300\n",
    b"integrator = \"photon\"\n",
    b"integrator = \"brute-force\"\n",
    b"intersection = \"poster\"\n",
    b"spectral = true\n",
    b"width = 16384\nheight = 16384\n",
    b"spp = 1048576\n",
    b"photons_per_iteration = 4294967296\n",
    b"filter = { type = \"gaussian\", radius = 1e300 }\n",
    b"type = \"stars\"\ndensity = 1e12\n",
    b"type = \"grid\"\nspacing_deg = 1e-300\n",
    b"type = \"equirect\"\nfile = \"assets/sky.png\"\n",
    b"type = \"checker\"",
    b"{ type = \"image\", file = \"assets/tex.png\" }",
    b"{ type = \"earth\", seed = 18446744073709551615 }",
    b"shape = { type = \"mesh\", file = \"assets/tri.obj\" }\n",
    b"shape = { type = \"sphere\", center = [0, 0, 0], radius = 1e-300 }\n",
    b"file = \"../../../../etc/passwd\"",
    b"file = \"/dev/zero\"",
    b"file = \"assets\"",
    b"file = \"\"",
    b"transform = { scale = 1e-300, rotate = { axis = [0, 0, 0], degrees = 1e300 } }\n",
    b"emission = 1e300\n",
    b"material = \"nope\"\n",
    b"[0, 0, 0]",
    b"[1, 2]",
    b"[1e308, 1e308, 1e308]",
    b"[nan, inf, -inf]",
    b"[[1, 2, 3], [4, 5, 6], [7, 8, 9], [1, 1, 1]]",
    b"\"\"",
    b"\"\\u0000\"",
    b"\"\\n\"",
    b"'''\nx\n'''",
    b"{}",
    b"true",
    b"1979-05-27T07:32:00Z",
    b"# a comment\n",
    b"\"\xc3\xa9\"",
];

const SCENE_NESTING: &[(&str, &str)] =
    &[("[", "]"), ("{ a = ", " }"), ("[{ a = [", "] }]"), ("{ a = { b = [", "] } }")];

/// A scene file's bytes: parsed as text where they are UTF-8, else loaded from a file (whose
/// loader refuses them with the place where they stop being UTF-8).
fn check_scene(input: &[u8]) -> Verdict {
    let base = mutate::corpus_dir("scene");
    match std::str::from_utf8(input) {
        Ok(text) => parse_scene(text, "fuzz.toml", &base),
        Err(_) => {
            let path = scratch("scene").join("fuzz.toml");
            write_new(&path, input);
            let origin = path.display().to_string();
            match scene::load(&path) {
                Ok(_) => Err("a scene file that is not UTF-8 loaded".to_string()),
                Err(e) => well_formed(&e, &origin, &String::from_utf8_lossy(input)).map(|()| "not UTF-8"),
            }
        }
    }
}

#[test]
fn fuzz_scene_reader() {
    let seeds = mutate::corpus("scene", &["toml"]);
    for seed in &seeds {
        let text = std::str::from_utf8(&seed.bytes).unwrap();
        scene::parse(text, &seed.name, &mutate::corpus_dir("scene")).unwrap_or_else(|e| panic!("the corpus: {e}"));
    }
    let mutator = Mutator::new(SCENE_TOKENS, SCENE_NESTING, 256 * 1024);
    let mut runner = Runner::watched("scene", limit(), check_scene);
    let stats = mutate::drive(
        &mut runner,
        &seeds,
        &mut mutate::random(0x0073_6365_6e65),
        budget(12_000),
        |random, input, other| {
            // Bytes that are not UTF-8 stop the reader at once: a few are enough.
            let mutant = mutator.mutate(random, input, other);
            match String::from_utf8_lossy(&mutant) {
                text if !random.one_in(16) => text.into_owned().into_bytes(),
                _ => mutant,
            }
        },
        |outcome| outcome == "loaded",
    );
    // A run that only ever refuses tests only the first error: mutants load too.
    assert!(stats.outcomes.get("loaded").is_some_and(|&n| n * 20 >= stats.inputs), "{:?}", stats.outcomes);
    assert!(stats.outcomes.get("refused").is_some_and(|&n| n * 4 >= stats.inputs), "{:?}", stats.outcomes);
}

// ---------------------------------------------------------------------------------------------
// The glTF importer.

/// A `.glb`'s JSON and binary chunks, when `bytes` is one (at least as far as its chunk headers).
fn glb_chunks(bytes: &[u8]) -> Option<(Vec<u8>, Option<Vec<u8>>)> {
    if bytes.len() < 20 || &bytes[..4] != b"glTF" {
        return None;
    }
    let word = |at: usize| bytes.get(at..at + 4).map(|w| u32::from_le_bytes(w.try_into().unwrap()) as usize);
    let json_len = word(12)?;
    let json = bytes.get(20..20 + json_len)?.to_vec();
    let bin_at = 20 + json_len;
    let bin = word(bin_at).and_then(|len| bytes.get(bin_at + 8..bin_at + 8 + len)).map(<[u8]>::to_vec);
    Some((json, bin))
}

/// A `.glb` of `json` and `bin`, its lengths right.
fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
    let pad = |bytes: &[u8], with: u8| {
        let mut b = bytes.to_vec();
        b.resize(bytes.len().div_ceil(4) * 4, with);
        b
    };
    let json = pad(json, b' ');
    let mut body = [(json.len() as u32).to_le_bytes(), *b"JSON"].concat();
    body.extend(&json);
    if let Some(bin) = bin {
        let bin = pad(bin, 0);
        body.extend((bin.len() as u32).to_le_bytes());
        body.extend(b"BIN\0");
        body.extend(&bin);
    }
    let mut out = [*b"glTF", 2u32.to_le_bytes(), (12 + body.len() as u32).to_le_bytes()].concat();
    out.extend(body);
    out
}

/// The JSON document of a `.gltf` or `.glb`, and the `.glb`'s binary chunk.
fn gltf_parts(bytes: &[u8]) -> Option<(Value, Option<Option<Vec<u8>>>)> {
    match glb_chunks(bytes) {
        Some((json, bin)) => Some((serde_json::from_slice(&json).ok()?, Some(bin))),
        None => Some((serde_json::from_slice(bytes).ok()?, None)),
    }
}

const GLTF_TOKENS: &[&[u8]] = &[
    b"\"nodes\":[0,0,0,0]",
    b"\"children\":[0]",
    b"\"children\":[1,1,1,1,1,1,1,1]",
    b"\"mesh\":0,",
    b"\"indices\":0,",
    b"\"byteStride\":4,",
    b"\"byteOffset\":4294967295,",
    b"\"count\":4294967295,",
    b"\"sparse\":{\"count\":1}",
    b"\"mode\":0,",
    b"\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],",
    b"\"uri\":\"data:application/octet-stream;base64,AAAA\"",
    b"\"uri\":\"../../../../etc/passwd\"",
    b"\"uri\":\"%2E%2E/x\"",
    b"\"matrix\":[0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0],",
    b"\"rotation\":[0,0,0,0],",
    b"\"scale\":[1e308,1e308,1e308],",
    b"\"yfov\":0,",
    b"1e400",
    b"-0",
    b"null",
    b"\"\\ud800\"",
    b",",
    b":",
    b"{",
    b"}",
];

const GLTF_NESTING: &[(&str, &str)] = &[("[", "]"), ("{\"a\":", "}"), ("{\"extras\":[", "]}")];

/// A glTF input changed: structurally (its JSON document, the `.glb`'s binary chunk), or as bytes.
fn mutate_gltf(mutator: &Mutator, random: &mut Random, input: &[u8], other: &[u8]) -> Vec<u8> {
    let (Some((mut doc, container)), false) = (gltf_parts(input), random.one_in(4)) else {
        return mutator.mutate(random, input, other);
    };
    let theirs = gltf_parts(other).map_or(Value::Null, |(doc, _)| doc);
    // Mostly one change: a glTF document is a web of indices, and two changes break it twice.
    for _ in 0..if random.one_in(4) { 2 } else { 1 } {
        mutate::mutate_json(random, &mut doc, &theirs);
    }
    let json = serde_json::to_vec(&doc).unwrap();
    if json.len() > mutator.max_len {
        return mutator.mutate(random, input, other);
    }
    let mut out = match container {
        Some(bin) => {
            let mut bin = bin;
            if let Some(b) = bin.as_mut().filter(|_| random.one_in(4)) {
                *b = mutator.mutate(random, b, other);
            }
            glb(&json, bin.as_deref())
        }
        None if random.one_in(16) => glb(&json, None),
        None => json,
    };
    if random.one_in(8) {
        out = mutator.mutate(random, &out, other);
    }
    out
}

/// The scenes a glTF file is placed by: as it is, and where it has them, framed by its camera
/// `cam` and with its material `Glass` replaced.
fn gltf_scenes(file: &str, input: &[u8]) -> Vec<String> {
    let object = format!("[[objects]]\ngltf = \"{file}\"\n");
    let camera = "[camera]\nposition = [0, 1, 8]\nlook_at = [0, 0, 0]\n";
    let has = |needle: &[u8]| input.windows(needle.len()).any(|w| w == needle);
    let mut scenes = vec![format!("{camera}\n{object}")];
    if has(b"\"cam\"") {
        scenes.push(format!("[camera]\ngltf_camera = \"cam\"\n\n{object}"));
    }
    if has(b"\"Glass\"") {
        scenes
            .push(format!("{camera}\n{object}materials = {{ \"Glass\" = {{ type = \"dielectric\", ior = 1.33 }} }}\n"));
    }
    scenes
}

/// A glTF file's bytes written beside a scene that places it, and the scenes loaded.
fn check_gltf(input: &[u8]) -> Verdict {
    let dir = scratch("gltf");
    let file = if input.starts_with(b"glTF") { "x.glb" } else { "x.gltf" };
    write_new(&dir.join(file), input);
    let mut outcome = "refused";
    for text in gltf_scenes(file, input) {
        if parse_scene(&text, "scene.toml", &dir)? == "loaded" {
            outcome = "loaded";
        }
    }
    Ok(outcome)
}

#[test]
fn fuzz_gltf_importer() {
    let seeds = mutate::corpus("gltf", &["gltf", "glb"]);
    for seed in &seeds {
        assert_eq!(check_gltf(&seed.bytes), Ok("loaded"), "the corpus: {}", seed.name);
    }
    let mutator = Mutator::new(GLTF_TOKENS, GLTF_NESTING, 256 * 1024);
    let mut runner = Runner::watched("gltf", limit(), check_gltf);
    let stats = mutate::drive(
        &mut runner,
        &seeds,
        &mut mutate::random(0x676c_7446),
        budget(8_000),
        |random, input, other| mutate_gltf(&mutator, random, input, other),
        |outcome| outcome == "loaded",
    );
    assert!(stats.outcomes.get("loaded").is_some_and(|&n| n * 20 >= stats.inputs), "{:?}", stats.outcomes);
}

// ---------------------------------------------------------------------------------------------
// The metric expression compiler.

const SPHERICAL: Names<'static> = Names { variables: ["t", "r", "theta", "phi"], constants: &[("M", 1.0), ("Q", 0.5)] };
const CARTESIAN: Names<'static> = Names { variables: ["t", "x", "y", "z"], constants: &[("M", 1.0), ("Q", 0.5)] };

/// Where compiled expressions are evaluated: ordinary points, the origin, and the edges of `f64`.
const POINTS: &[[f64; 4]] = &[
    [0.0, 10.0, 0.7, 0.3],
    [0.0, 0.0, 0.0, 0.0],
    [-1.0, 2.0, -3.0, 4.0],
    [1e300, -1e300, 1e-300, -0.0],
    [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::MIN_POSITIVE],
];

const EXPRESSION_TOKENS: &[&[u8]] = &[
    b"+",
    b"-",
    b"*",
    b"/",
    b"^",
    b"**",
    b"(",
    b")",
    b",",
    b" ",
    b".",
    b"e",
    b"E",
    b"e+308",
    b"e-400",
    b"0",
    b"1",
    b"r",
    b"theta",
    b"phi",
    b"t",
    b"x",
    b"y",
    b"z",
    b"M",
    b"Q",
    b"pi",
    b"sqrt(",
    b"exp(",
    b"ln(",
    b"log(",
    b"sin(",
    b"cos(",
    b"tan(",
    b"asin(",
    b"acos(",
    b"atan(",
    b"sinh(",
    b"cosh(",
    b"tanh(",
    b"abs(",
    b"pow(",
    b"atan2(",
    b"foo(",
    b"_",
    b"/0",
    b"/(1-1)",
    b"^1024",
    b"^1025",
    b"^-1024",
    b"^0.5",
    b"\xce\xb8",
    b"\xe3\x80\x80",
    b"\xc2\xa0",
    b"\t",
    b"\n",
    b"#",
];

const EXPRESSION_NESTING: &[(&str, &str)] =
    &[("(", ")"), ("-", ""), ("+", ""), ("sin(", ")"), ("pow(r, ", ")"), ("r*(", ")"), ("2^", ""), ("(r+", ")")];

/// An expression compiled over both coordinate systems' names: a refusal points into the text, a
/// compiled expression evaluates everywhere, twice the same, and does not depend on a variable
/// it does not read.
fn check_expression(input: &[u8]) -> Verdict {
    let text = String::from_utf8_lossy(input);
    let mut outcome = "refused";
    for names in [SPHERICAL, CARTESIAN] {
        match Expression::compile(&text, names) {
            Ok(expression) => {
                outcome = "compiled";
                if Expression::compile(&text, names).as_ref() != Ok(&expression) {
                    return Err("compiled differently the second time".to_string());
                }
                for point in POINTS {
                    let value = expression.eval(point);
                    for i in (0..4).filter(|&i| !expression.reads(i)) {
                        let mut moved = *point;
                        moved[i] = 12.5;
                        let again = expression.eval(&moved);
                        if !(value == again || value.is_nan() && again.is_nan()) {
                            return Err(format!("it does not read variable {i}, yet changes with it: {value} {again}"));
                        }
                    }
                }
            }
            Err(e) => {
                if e.at > text.len() || !text.is_char_boundary(e.at) || e.message.trim().is_empty() {
                    return Err(format!("a refusal that points nowhere: {e:?}"));
                }
            }
        }
    }
    Ok(outcome)
}

#[test]
fn fuzz_expression_compiler() {
    let seeds = mutate::corpus("expression", &["expr"]);
    for seed in &seeds {
        assert_eq!(check_expression(&seed.bytes), Ok("compiled"), "the corpus: {}", seed.name);
    }
    let mutator = Mutator::new(EXPRESSION_TOKENS, EXPRESSION_NESTING, 16 * 1024);
    // Compiling is microseconds; one taking a second is a hang.
    let mut runner = Runner::inline("expression", Duration::from_secs(1), check_expression);
    let stats = mutate::drive(
        &mut runner,
        &seeds,
        &mut mutate::random(0x6578_7072),
        budget(200_000),
        |random, input, other| mutator.mutate(random, input, other),
        |outcome| outcome == "compiled",
    );
    assert!(stats.outcomes.get("compiled").is_some_and(|&n| n * 10 >= stats.inputs), "{:?}", stats.outcomes);
}

/// `text` as a TOML string: literal where it can be, else basic with escapes.
fn toml_string(text: &str) -> String {
    if !text.contains(['\'', '\n', '\r']) && !text.chars().any(char::is_control) {
        return format!("'{text}'");
    }
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A mutated expression as one component of a metric written in a scene (chosen by the input
/// itself): compiled, differentiated over dual numbers at the camera, and its errors placed in
/// the file.
fn check_metric(input: &[u8]) -> Verdict {
    let text = String::from_utf8_lossy(input);
    let mut components = [
        ("g_tt", "-(1 - 2*M/r)"),
        ("g_rr", "1/(1 - 2*M/r)"),
        ("g_thetatheta", "r^2"),
        ("g_phiphi", "r^2*sin(theta)^2"),
        ("horizon", "r - 2*M"),
    ];
    let which = input.iter().map(|&b| usize::from(b)).sum::<usize>() % components.len();
    components[which].1 = &text;
    let lines: String = components.iter().map(|(key, value)| format!("{key} = {}\n", toml_string(value))).collect();
    let scene = format!(
        "[spacetime]\ntype = \"metric\"\ncoordinates = \"spherical\"\nparameters = {{ M = 1.0, Q = 0.5 }}\n{lines}\n\
         [camera]\nposition = [0, 0, 30]\nlook_at = [0, 0, 0]\n"
    );
    parse_scene(&scene, "metric.toml", Path::new("."))
}

#[test]
fn fuzz_expressions_in_scenes() {
    let seeds: Vec<Seed> = mutate::corpus("expression", &["expr"]);
    let mutator = Mutator::new(EXPRESSION_TOKENS, EXPRESSION_NESTING, 16 * 1024);
    let mut runner = Runner::watched("expression_metric", limit(), check_metric);
    let stats = mutate::drive(
        &mut runner,
        &seeds,
        &mut mutate::random(0x6d65_7472_6963),
        budget(100_000),
        |random, input, other| mutator.mutate(random, input, other),
        |outcome| outcome == "loaded",
    );
    assert!(stats.outcomes.get("loaded").is_some_and(|&n| n * 20 >= stats.inputs), "{:?}", stats.outcomes);
}
