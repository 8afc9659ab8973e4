//! How to render, kept apart from the algorithms that read it (Tungsten's habit).

use crate::film::{Filter, ToneMap};

/// Which light-transport algorithm.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Unidirectional path tracing with next-event estimation and MIS: lights are joined to
    /// shading points by straight rays in flat space, by geodesics in curved spacetime
    /// ([`LightConnection`]); by BSDF sampling alone in the poster's intersection mode.
    Path,
    /// Path tracing that only finds lights by hitting them: the unbiased reference.
    BruteForce,
    /// Stochastic progressive photon mapping (Hachisuka & Jensen 2009): camera paths end at
    /// visible points, photons traced from the lights are gathered there. Consistent, and it finds
    /// small or distant lights (e.g. through a wormhole) that camera paths rarely hit. Needs a
    /// spacetime whose light can be followed forwards in time (every built-in one; not a
    /// metric written in a scene file).
    Photon,
}

/// How the path integrator joins light points to shading points in curved spacetime.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightConnection {
    /// The spacetime's own connector where it has one (Schwarzschild), else rays aimed by
    /// Newton's method: in the ray's plane where the spacetime is static and spherically
    /// symmetric, in 4-D elsewhere.
    Auto,
    /// Rays aimed by Newton's method in 4-D in every curved spacetime: to check a spacetime's
    /// own connector, and the in-plane aim, against the generic one.
    Aimed,
}

/// Settings of the photon integrator ([`IntegratorKind::Photon`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhotonSettings {
    /// Photons traced per iteration; `None`: one per pixel.
    pub per_iteration: Option<u64>,
    /// Initial gather radius in scene units; `None`: 1 % of the diagonal of the bounds of the region a pixel first sees.
    pub radius: Option<f64>,
}

/// How a geodesic step is tested against the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Intersection {
    /// Each step's chord is tested against the BVH, subdivided where the step bends more than
    /// the tolerance, and hits are refined on the curved step.
    Chord,
    /// The poster's Algorithm 1: sign change of the surface function between step ends, then
    /// bisection (Ayush & Chaudhuri 2017); kept to reproduce its figures. Rays are integrated
    /// as the poster did, with classical RK4 at a fixed affine step `step` (≈ a length in scene
    /// units; for the wormhole's in-plane tracer, an azimuth in radians) for at most
    /// `max_iterations` steps (its MAXITER); a ray still going after that has failed.
    Poster { step: f64, max_iterations: u32 },
}

impl Intersection {
    /// The poster's method with the middle of its settings (dt from 10 to 0.5, MAXITER from
    /// 100 to 4000).
    pub const POSTER: Intersection = Intersection::Poster { step: 0.5, max_iterations: 4000 };
}

/// Everything about a render that is not the scene itself.
#[derive(Clone, Debug)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel (iterations of the photon integrator, one camera sample each).
    pub spp: u32,
    /// Longest path, in surface interactions.
    pub max_depth: u32,
    pub seed: u64,
    pub integrator: IntegratorKind,
    pub photon: PhotonSettings,
    pub intersection: Intersection,
    pub light_connection: LightConnection,
    pub filter: Filter,
    pub tonemap: ToneMap,
    /// Relative tolerance of the adaptive geodesic integrator. The default, 1e-7, is derived from
    /// the chord tolerance ε = 10⁻⁴ of the scene's radius: the position error a ray accumulates
    /// across the scene then stays an order of magnitude below ε (tests/geodesic_tolerance.rs),
    /// while 1e-8 cost a third more time for no visible difference.
    pub geodesic_rtol: f64,
    /// Data channels written beside the colour in EXR images ([`crate::film::DataChannel`]).
    pub channels: Vec<crate::film::DataChannel>,
    /// Spectral radiance channels written beside them ([`crate::film::SpectrumChannels`]).
    pub spectrum: Option<crate::film::SpectrumChannels>,
    /// The frequency shifts light is shown with (`doppler`, `beaming`, `gravitational_shift`).
    pub shown: crate::emission::Shown,
    /// Paths carry radiance at sampled wavelengths instead of RGB ([`crate::spectrum::Colour`]):
    /// frequency shifts change the colour of every light, and dispersing glass splits it.
    pub spectral: bool,
}

impl RenderSettings {
    /// Whether the image carries data beside its colour (data or spectral channels: EXR only).
    pub fn has_data_channels(&self) -> bool {
        !self.channels.is_empty() || self.spectrum.is_some()
    }
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            spp: 64,
            max_depth: 8,
            seed: 0,
            integrator: IntegratorKind::Path,
            photon: PhotonSettings::default(),
            intersection: Intersection::Chord,
            light_connection: LightConnection::Auto,
            filter: Filter::default(),
            tonemap: ToneMap::default(),
            geodesic_rtol: 1e-7,
            channels: Vec::new(),
            shown: crate::emission::Shown::default(),
            spectrum: None,
            spectral: false,
        }
    }
}
