//! `[render]`: image size, sampling, integrator, reconstruction filter and tone mapping.

use crate::reader::{num, Node, Result, Table, Tagged};
use render::emission::Shown;
use render::film::{Curve, DataChannel, Filter, FilterError, FilterKind, SpectrumChannels, ToneMap, FILTERS};
use render::integrator::photon;
use render::settings::{IntegratorKind, Intersection, LightConnection, PhotonSettings, RenderSettings};
use spacetime::Spacetime;

pub(super) const RENDER_KEYS: &[&str] = &[
    "width",
    "height",
    "spp",
    "max_depth",
    "seed",
    "integrator",
    "photons_per_iteration",
    "photon_radius",
    "intersection",
    "poster_step",
    "poster_max_iterations",
    "geodesic_rtol",
    "connector",
    "exposure",
    "tonemap",
    "filter",
    "channels",
    "doppler",
    "beaming",
    "gravitational_shift",
    "spectral",
    "spectrum",
];

/// The largest image side accepted (as the command line's `--width`/`--height`).
const MAX_SIDE: u32 = 16384;
/// The most samples per pixel accepted (as the command line's `--spp`).
const MAX_SPP: u32 = 1 << 20;
const MAX_DEPTH: u32 = 1024;
/// The most photons per iteration accepted.
const MAX_PHOTONS: u64 = 1 << 32;

/// The integrators by name.
const INTEGRATORS: &[(&str, IntegratorKind)] =
    &[("path", IntegratorKind::Path), ("brute-force", IntegratorKind::BruteForce), ("photon", IntegratorKind::Photon)];

/// The intersection modes by name; the poster's with its default step and iterations, which
/// `poster_step` and `poster_max_iterations` replace.
const INTERSECTIONS: &[(&str, Intersection)] = &[("chord", Intersection::Chord), ("poster", Intersection::POSTER)];

/// The tone curves by name.
const TONE_CURVES: &[(&str, Curve)] = &[("filmic", Curve::Filmic), ("linear", Curve::Linear)];

/// The light connectors by name.
const CONNECTORS: &[(&str, LightConnection)] = &[("auto", LightConnection::Auto), ("aimed", LightConnection::Aimed)];

/// `[render]`, in a scene of `spacetime` (the photon integrator needs one whose light can be
/// followed forwards in time).
pub(super) fn render_settings(t: &Table<'_>, spacetime: &Spacetime) -> Result<RenderSettings> {
    let d = RenderSettings::default();
    let integrator = match t.get("integrator") {
        Some(n) => n.choice("integrator", INTEGRATORS)?,
        None => d.integrator,
    };
    if integrator == IntegratorKind::Photon && !photon::supports(spacetime) {
        return Err(t.loc("integrator").err(format!(
            "\"photon\" traces light forwards in time, and nothing says how light runs forwards in a \
             spacetime of type \"{}\" (use \"path\" or \"brute-force\")",
            spacetime.name()
        )));
    }
    let photon = photon_settings(t, integrator)?;
    let intersection = match t.get("intersection") {
        Some(n) => n.choice("intersection", INTERSECTIONS)?,
        None => d.intersection,
    };
    let intersection = match intersection {
        Intersection::Poster { step, max_iterations } => {
            let step = t.or("poster_step", step, |n| n.f64())?;
            if !(step > 0.0 && step.is_finite()) {
                return Err(t.loc("poster_step").err(format!("must be > 0, got {}", num(step))));
            }
            let max_iterations = t.or("poster_max_iterations", max_iterations, |n| n.u32_in(1, 100_000_000))?;
            Intersection::Poster { step, max_iterations }
        }
        Intersection::Chord => {
            for key in ["poster_step", "poster_max_iterations"] {
                if t.get(key).is_some() {
                    return Err(t.loc(key).err("only used with intersection = \"poster\""));
                }
            }
            Intersection::Chord
        }
    };
    let geodesic_rtol = t.or("geodesic_rtol", d.geodesic_rtol, |n| n.f64())?;
    // Below 10⁻¹³ the tolerance asks each step for less error than double precision's rounding
    // accumulates over a ray's steps: it only multiplies the steps (10⁻³⁰⁰ ran ~3000× slower).
    if !(1e-13..1.0).contains(&geodesic_rtol) {
        return Err(t.loc("geodesic_rtol").err(format!(
            "must be in [1e-13, 1), got {}: tighter than 1e-13 is below double precision's rounding over a \
             ray's steps and only adds steps",
            num(geodesic_rtol)
        )));
    }
    let curve = match t.get("tonemap") {
        Some(n) => n.choice("tone map", TONE_CURVES)?,
        None => d.tonemap.curve,
    };
    let exposure_ev = t.or("exposure", d.tonemap.exposure_ev, |n| n.f64())?;
    if exposure_ev.abs() > 64.0 {
        return Err(t.loc("exposure").err(format!("must be within ±64 EV, got {}", num(exposure_ev))));
    }
    Ok(RenderSettings {
        width: t.or("width", d.width, |n| n.u32_in(1, MAX_SIDE))?,
        height: t.or("height", d.height, |n| n.u32_in(1, MAX_SIDE))?,
        spp: t.or("spp", d.spp, |n| n.u32_in(1, MAX_SPP))?,
        max_depth: t.or("max_depth", d.max_depth, |n| n.u32_in(0, MAX_DEPTH))?,
        seed: t.or("seed", d.seed, |n| n.u64())?,
        integrator,
        photon,
        intersection,
        light_connection: match t.get("connector") {
            Some(n) => n.choice("connector", CONNECTORS)?,
            None => d.light_connection,
        },
        filter: match t.get("filter") {
            Some(n) => filter(&n)?,
            None => d.filter,
        },
        tonemap: ToneMap { exposure_ev, curve },
        geodesic_rtol,
        channels: match t.get("channels") {
            Some(n) => channels(&n)?,
            None => Vec::new(),
        },
        shown: shown(t, integrator)?,
        spectral: spectral(t, integrator)?,
        spectrum: match t.get("spectrum") {
            Some(n) => Some(spectrum(&n)?),
            None => None,
        },
    })
}

/// `spectrum = { min, max, count }`: spectral radiance channels, wavelengths in nm.
fn spectrum(n: &Node<'_>) -> Result<SpectrumChannels> {
    let t = n.table(&["min", "max", "count"])?;
    let min = t.or("min", 380.0, |n| n.f64())?;
    let max = t.or("max", 780.0, |n| n.f64())?;
    let count = t.or("count", 41, |n| n.u32_in(1, SpectrumChannels::MAX_COUNT))?;
    SpectrumChannels::new(min, max, count).map_err(|e| n.err(e))
}

/// `spectral = true`: paths carry sampled wavelengths. Photon mapping carries RGB power.
fn spectral(t: &Table<'_>, integrator: IntegratorKind) -> Result<bool> {
    let spectral = t.or("spectral", false, |n| n.bool())?;
    if spectral && integrator == IntegratorKind::Photon {
        return Err(t
            .loc("spectral")
            .err("\"photon\" carries RGB power; spectral rendering needs \"path\" or \"brute-force\""));
    }
    Ok(spectral)
}

/// `doppler`, `beaming`, `gravitational_shift`: the teaching toggles, each on by default. Photon
/// mapping carries its photons' power with every shift in, so it takes none of them off.
fn shown(t: &Table<'_>, integrator: IntegratorKind) -> Result<Shown> {
    let shown = Shown {
        doppler: t.or("doppler", true, |n| n.bool())?,
        beaming: t.or("beaming", true, |n| n.bool())?,
        gravitational: t.or("gravitational_shift", true, |n| n.bool())?,
    };
    if integrator == IntegratorKind::Photon && shown != Shown::default() {
        let key = ["doppler", "beaming", "gravitational_shift"].into_iter().find(|k| t.get(k).is_some());
        let message = "\"photon\" shows every frequency shift; switching one off needs \"path\" or \"brute-force\"";
        return Err(match key {
            Some(key) => t.loc(key).err(message),
            None => t.err(message),
        });
    }
    Ok(shown)
}

/// `channels = ["redshift", "fate", "disk_radius"]`: data channels for EXR images, each once.
fn channels(n: &Node<'_>) -> Result<Vec<DataChannel>> {
    let names = DataChannel::ALL.map(DataChannel::name);
    let mut channels = Vec::new();
    for element in n.array()? {
        let channel = DataChannel::ALL[element.keyword("data channel", &names)?];
        if channels.contains(&channel) {
            return Err(element.err(format!("\"{}\" is listed twice", channel.name())));
        }
        channels.push(channel);
    }
    Ok(channels)
}

/// `photons_per_iteration` and `photon_radius`, only with `integrator = "photon"`.
fn photon_settings(t: &Table<'_>, integrator: IntegratorKind) -> Result<PhotonSettings> {
    if integrator != IntegratorKind::Photon {
        for key in ["photons_per_iteration", "photon_radius"] {
            if t.get(key).is_some() {
                return Err(t.loc(key).err("only used with integrator = \"photon\""));
            }
        }
        return Ok(PhotonSettings::default());
    }
    let per_iteration = t.opt("photons_per_iteration", |n| n.u64())?;
    if let Some(p) = per_iteration.filter(|&p| !(1..=MAX_PHOTONS).contains(&p)) {
        return Err(t.loc("photons_per_iteration").err(format!("must be in 1–{MAX_PHOTONS}, got {p}")));
    }
    let radius = t.opt("photon_radius", |n| n.f64())?;
    if let Some(r) = radius.filter(|r| !(*r > 0.0 && r.is_finite())) {
        return Err(t.loc("photon_radius").err(format!("must be > 0, got {}", num(r))));
    }
    Ok(PhotonSettings { per_iteration, radius })
}

/// The filters' table is the render crate's [`FILTERS`]: name, default radius, parameters with
/// their defaults, and constructor. Its keys are `radius` and the parameters.
impl Tagged for FilterKind {
    fn name(&self) -> &'static str {
        self.name
    }

    fn keys(&self) -> Vec<&'static str> {
        std::iter::once("radius").chain(self.parameters.iter().map(|p| p.0)).collect()
    }
}

/// `filter = "name"` (default parameters) or `filter = { type = "name", … }`.
fn filter(n: &Node<'_>) -> Result<Filter> {
    if n.is_str() {
        let names: Vec<&str> = FILTERS.iter().map(|f| f.name).collect();
        let kind = &FILTERS[n.keyword("filter", &names)?];
        return kind.build_default().map_err(|e| n.err(e.to_string()));
    }
    let (kind, t) = n.kind("filter", FILTERS)?;
    let radius = t.or("radius", [kind.default_radius; 2], |n| n.pair())?;
    let values =
        kind.parameters.iter().map(|&(key, default)| t.or(key, default, |n| n.f64())).collect::<Result<Vec<_>>>()?;
    kind.build(radius, &values).map_err(|e| match &e {
        FilterError::InvalidRadius { .. } => t.loc("radius").err(e.to_string()),
        FilterError::InvalidParameter { name, .. } if kind.parameters.iter().any(|p| p.0 == *name) => {
            t.loc(name).err(e.to_string())
        }
        FilterError::InvalidParameter { .. } | FilterError::NonPositiveIntegral | FilterError::NonFiniteValue => {
            t.err(e.to_string())
        }
    })
}
