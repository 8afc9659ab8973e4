//! What made an image or a checkpoint, written into it: the scene (its file and text), the view,
//! the settings, the seed, the samples reached, the program's version and the command line. A
//! checkpoint is continued only by a render that would have made the same samples: same version,
//! same scene, same sampling settings and the same part.

use render::film::{Curve, Metadata, ToneMap};
use render::integrator::PathStats;
use render::renderer::{Goal, Part, RenderStats};
use render::scene::Scene;
use std::fmt::Write as _;
use std::hash::Hasher;

/// Where a scene came from.
#[derive(Clone, Debug)]
pub struct Source {
    /// The scene file, or the default scene's name.
    pub name: String,
    /// The scene file's text.
    pub text: String,
    pub view: Option<String>,
    /// Animation time of the frame, seconds.
    pub time: f64,
}

/// A hasher fed by `write!`, so that large scenes are hashed without building their text.
struct HashWriter(std::hash::DefaultHasher);

impl std::fmt::Write for HashWriter {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.0.write(s.as_bytes());
        Ok(())
    }
}

fn hash_of(value: &dyn std::fmt::Debug) -> String {
    let mut writer = HashWriter(std::hash::DefaultHasher::new());
    // Writing into a hasher cannot fail.
    let _ = write!(writer, "{value:?}");
    format!("{:016x}", writer.0.finish())
}

/// The hash of everything in the scene that decides its samples: spacetime, camera, objects,
/// lights and skies (through their exact `Debug` text: `f64` prints round-trip), and the settings
/// other than the sample count and the tone map, which only decide how many samples are taken
/// and how they are shown.
fn sampling_hash(scene: &Scene) -> String {
    let mut settings = scene.settings.clone();
    settings.spp = 0;
    settings.tonemap = ToneMap::default();
    hash_of(&(&scene.spacetime, &scene.axis, &scene.camera, &scene.world, &scene.animation, &settings))
}

/// The settings as JSON, for people and for [`check_resumable`]'s messages.
fn settings_json(scene: &Scene) -> serde_json::Value {
    let s = &scene.settings;
    serde_json::json!({
        "width": s.width,
        "height": s.height,
        "seed": s.seed,
        "max_depth": s.max_depth,
        "integrator": format!("{:?}", s.integrator),
        "filter": format!("{:?}", s.filter),
        "geodesic_rtol": s.geodesic_rtol,
        "intersection": format!("{:?}", s.intersection),
        "photon": format!("{:?}", s.photon),
        "spectral": s.spectral,
    })
}

/// What any image made from `scene` records: the program, the command, the scene and its
/// view, time and settings.
pub fn scene_metadata(scene: &Scene, source: &Source) -> Metadata {
    let mut m = Metadata::new();
    let mut put = |key: &str, value: String| {
        m.insert(key.to_owned(), value);
    };
    put("version", env!("CARGO_PKG_VERSION").to_owned());
    put("command", std::env::args().collect::<Vec<_>>().join(" "));
    put("scene", source.name.clone());
    put("scene.source", source.text.clone());
    if let Some(view) = &source.view {
        put("view", view.clone());
    }
    put("time", source.time.to_string());
    put("sampling.hash", sampling_hash(scene));
    put("settings", settings_json(scene).to_string());
    put("seed", scene.settings.seed.to_string());
    m
}

/// The metadata of a render of `scene` from `source`, as it stands after `stats`.
pub fn metadata(scene: &Scene, source: &Source, goal: Goal, part: Part, stats: &RenderStats) -> Metadata {
    let mut m = scene_metadata(scene, source);
    let mut put = |key: &str, value: String| {
        m.insert(key.to_owned(), value);
    };
    put("spp", stats.spp_max.to_string());
    put("spp.min", stats.spp_min.to_string());
    put("spp.goal", goal.spp.to_string());
    if let Some(noise) = goal.noise {
        put("noise_target", format!("{}{}", noise.relative_error, if noise.adaptive { " adaptive" } else { "" }));
    }
    if let Some(error) = stats.relative_error {
        put("relative_error", format!("{error:.6}"));
    }
    put("part", part.to_string());
    put("tonemap.exposure_ev", scene.settings.tonemap.exposure_ev.to_string());
    put("tonemap.curve", scene.settings.tonemap.curve.name().to_owned());
    put("stats", stats.to_json(&scene.settings).to_string());
    m
}

/// Why the checkpoint `old` cannot be continued by the render described by `new`, if it can't.
pub fn check_resumable(old: &Metadata, new: &Metadata) -> Result<(), String> {
    let get = |m: &Metadata, key: &str| m.get(key).cloned().unwrap_or_else(|| "(none)".into());
    if get(old, "version") != get(new, "version") {
        return Err(format!(
            "it was made by nullpath {}, this is {}: samples may differ between versions",
            get(old, "version"),
            get(new, "version")
        ));
    }
    if get(old, "part") != get(new, "part") {
        return Err(format!("it holds part {} of the image, not part {}", get(old, "part"), get(new, "part")));
    }
    if get(old, "sampling.hash") != get(new, "sampling.hash") {
        let parse = |m: &Metadata| serde_json::from_str::<serde_json::Value>(&get(m, "settings")).unwrap_or_default();
        let (before, now) = (parse(old), parse(new));
        let changed: Vec<String> = now
            .as_object()
            .into_iter()
            .flatten()
            .filter(|(key, value)| before.get(key.as_str()) != Some(value))
            .map(|(key, value)| {
                format!("{key} {} → {value}", before.get(key.as_str()).unwrap_or(&serde_json::Value::Null))
            })
            .collect();
        return Err(if changed.is_empty() {
            format!("the scene differs from the one it was rendered from ({})", get(old, "scene"))
        } else {
            format!("the settings differ: {}", changed.join(", "))
        });
    }
    Ok(())
}

/// The tone map recorded in `metadata`.
pub fn tonemap(metadata: &Metadata) -> Result<ToneMap, String> {
    let exposure_ev = metadata
        .get("tonemap.exposure_ev")
        .and_then(|v| v.parse::<f64>().ok())
        .ok_or("it records no exposure (tonemap.exposure_ev)")?;
    let name = metadata.get("tonemap.curve").ok_or("it records no tone curve (tonemap.curve)")?;
    let curve = Curve::ALL.into_iter().find(|c| c.name() == name).ok_or(format!("unknown tone curve \"{name}\""))?;
    Ok(ToneMap { exposure_ev, curve })
}

/// The path counts and seconds recorded in `metadata`'s statistics (zero where absent).
pub fn recorded_work(metadata: &Metadata) -> (PathStats, f64) {
    let stats: serde_json::Value = metadata.get("stats").and_then(|s| serde_json::from_str(s).ok()).unwrap_or_default();
    let count = |v: &serde_json::Value| v.as_u64().unwrap_or(0);
    let mut paths = PathStats { rays: count(&stats["rays"]), ..PathStats::default() };
    let f = &stats["fates"];
    paths.fates.escaped = count(&f["escaped"]);
    paths.fates.captured = count(&f["captured"]);
    paths.fates.absorbed = count(&f["absorbed"]);
    paths.fates.traversed = count(&f["traversed"]);
    paths.fates.failed = count(&f["failed"]);
    (paths, stats["seconds"].as_f64().unwrap_or(0.0))
}
