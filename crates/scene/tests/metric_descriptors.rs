//! The metric descriptors are all the scene reader, the sliders and the documentation need: the
//! table of `docs/scene-format.md` is made from them, and a metric the crates do not know (a toy
//! one, its descriptor written here) is read, checked and documented once registered.

use scene::SceneError;
use spacetime::metric::{
    exactly, positive, MetricDescriptor, Parameter, ParameterDescriptor, ParameterError, Range, SPACETIMES,
};
use spacetime::{Schwarzschild, Spacetime};
use std::path::Path;

const CAMERA: &str = "[camera]\nposition = [0, 0, 20]\nlook_at = [0, 0, 0]\nfov = 40\n";

const START: &str = "<!-- spacetimes:";
const END: &str = "<!-- end spacetimes -->";

/// The generated part of `docs/scene-format.md` is what the registry makes of it. With
/// `NULLPATH_BLESS=1` the test writes it instead.
#[test]
fn the_scene_format_table_is_the_registrys() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let doc = std::fs::read_to_string(&path).expect("docs/scene-format.md");
    let start = doc.find(START).expect("the start marker");
    let body = start + doc[start..].find('\n').expect("a line after the start marker") + 1;
    let end = body + doc[body..].find(END).expect("the end marker");
    let expected = scene::spacetime_table(SPACETIMES);
    if doc[body..end] == expected {
        return;
    }
    if std::env::var_os("NULLPATH_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&path, format!("{}{expected}{}", &doc[..body], &doc[end..])).expect("write the doc");
        return;
    }
    panic!(
        "the spacetime table of docs/scene-format.md is not the descriptors': replace the lines between the \
         markers with these (or run with NULLPATH_BLESS=1):\n{expected}"
    );
}

/// Schwarzschild by the size of its horizon, `size = 2M`: a metric that no crate knows, made of
/// one descriptor.
static TOY: MetricDescriptor = MetricDescriptor {
    name: "toy",
    description: "a black hole given by its horizon's diameter",
    parameters: &[ParameterDescriptor {
        name: "size",
        meaning: "horizon radius 2M",
        unit: "length",
        range: Range::Positive,
        default: Some(2.0),
        command_line_default: None,
    }],
    constraint: Some("size ≤ 100"),
    oriented: false,
    build: |v| {
        let [size] = exactly(v)?;
        let size = positive("size", size)?;
        if size > 100.0 {
            return Err(ParameterError::new("size", format!("must be ≤ 100, got {size}")));
        }
        Spacetime::schwarzschild(0.5 * size)
    },
    values: |s| if let Spacetime::Schwarzschild(h) = s { Some(vec![2.0 * h.mass]) } else { None },
};

fn parse(text: &str, metrics: &[&MetricDescriptor]) -> Result<render::scene::Scene, SceneError> {
    scene::parse_with_metrics(&format!("{text}{CAMERA}"), "toy.toml", Path::new("."), metrics)
}

fn error(text: &str, metrics: &[&MetricDescriptor]) -> String {
    match parse(text, metrics) {
        Ok(_) => panic!("expected an error for {text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_registered_toy_metric_is_read_checked_and_documented() {
    let toy = "[spacetime]\ntype = \"toy\"\n";
    let with_toy: Vec<&MetricDescriptor> = SPACETIMES.iter().copied().chain([&TOY]).collect();
    // Read, with its parameter and its default.
    let s = parse(&format!("{toy}size = 3\n"), &with_toy).expect("a toy scene").spacetime;
    assert_eq!(s, Spacetime::Schwarzschild(Schwarzschild::new(1.5)));
    assert_eq!(parse(toy, &[&TOY]).expect("the default size").spacetime, Spacetime::schwarzschild(1.0).expect("valid"));
    // Out of range, at the key, whichever check refuses it.
    let e = error(&format!("{toy}size = -1\n"), &[&TOY]);
    assert!(e.starts_with("toy.toml:3:8: spacetime.size: must be a finite number > 0, got -1"), "{e}");
    let e = error(&format!("{toy}size = 200\n"), &[&TOY]);
    assert!(e.starts_with("toy.toml:3:8: spacetime.size: must be ≤ 100, got 200"), "{e}");
    // Unknown keys and types are refused as the built-in ones are.
    assert!(error(&format!("{toy}mass = 1\n"), &[&TOY]).contains("unknown field \"mass\""));
    let e = error("[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = 0\n", &[&TOY]);
    assert!(e.contains("unknown spacetime \"kerr\"") && e.contains("\"toy\"") && e.contains("\"metric\""), "{e}");
    assert!(parse("[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = 0.5\n", &with_toy).is_ok(), "the others stay");
    // A view sets it within the sliders' range, checked at its key.
    let view = "[views.big]\nposition = [0, 0, 30]\nlook_at = [0, 0, 0]\nfov = 40\n[views.big.spacetime]\n";
    assert!(parse(&format!("{toy}size = 3\n{view}size = 4\n"), &[&TOY]).is_ok());
    let e = error(&format!("{toy}size = 3\n{view}size = 40\n"), &[&TOY]);
    assert!(e.contains("views.big.spacetime.size: must be a number from"), "{e}");
    // The sliders offer it, and set it.
    let sliders = TOY.sliders(&s).expect("the toy's spacetime");
    assert_eq!(sliders, [Parameter { name: "size", value: 3.0, min: 1e-3 * 4.5, max: 4.5 }]);
    assert_eq!(TOY.with_parameters(&s, &[("size", 4.0)]), Spacetime::schwarzschild(2.0));
    assert_eq!(TOY.with_parameters(&s, &[("size", 5.0)]).map_err(|e| e.parameter), Err("size"));
    // The documentation lists it.
    let table = scene::spacetime_table(&with_toy);
    assert!(table.contains("| `\"toy\"` | `size` > 0 (default 2) | size ≤ 100 | a black hole given by"), "{table}");
    assert!(table.contains("| `size` | length | horizon radius 2M | `\"toy\"` |"), "{table}");
}

/// A `[spacetime]` table alone reads as in a scene file, with the same messages, and nothing
/// else may stand beside it.
#[test]
fn a_spacetime_table_alone_reads_as_in_a_scene() {
    let text = "[spacetime]\ntype = \"kerr\"\nmass = 2\nspin = 1.5\naxis = [0, 0, 1]\n";
    let (alone, axis) = scene::parse_spacetime(text, "t.toml").expect("valid");
    let in_scene = scene::parse(&format!("{text}{CAMERA}"), "t.toml", Path::new(".")).expect("valid");
    assert_eq!((alone, axis), (in_scene.spacetime, in_scene.axis));
    let bad = "[spacetime]\ntype = \"kerr\"\nmass = 1\nspin = 1.5\n";
    let e = scene::parse_spacetime(bad, "t.toml").expect_err("too fast");
    let in_scene = scene::parse(&format!("{bad}{CAMERA}"), "t.toml", Path::new(".")).expect_err("too fast");
    assert_eq!(e.to_string(), in_scene.to_string());
    assert!(e.to_string().contains("spacetime.spin"), "{e}");
    assert!(scene::parse_spacetime(&format!("{text}{CAMERA}"), "t.toml").is_err(), "a camera is not a spacetime");
}
