//! Light rays aimed between two points of any curved spacetime, in the renderer's world and
//! local frames: the generic light connector. Static, spherically symmetric spacetimes aim in
//! the ray's plane, one unknown ([`spacetime::geodesic::plane`]); every other one in 4-D,
//! two unknowns with the ray bundle ([`spacetime::geodesic::aim`]).

use super::Propagator;
use crate::geometry::Vec3;
use spacetime::geodesic::aim::{aim, AimSettings};
use spacetime::geodesic::plane::{plane_aim, PlaneAimSettings, PlaneMetric, Side, Way};
use spacetime::geodesic::{Stepping, TraceSettings};
use spacetime::metric::{LocalFrame, Metric, OwnStepper, Tracers};
use spacetime::{Region, Tetrad};

/// Shots an aim may take: Newton's method converges in two or three from a good first shot;
/// aims that need more are near a caustic or the photon sphere, where BSDF sampling does as well.
const MAX_SHOTS: u32 = 12;

/// Relative tolerance of an aim's shots. Their rays are not tested against the scene (the aimed
/// ray is then traced as any ray is, at the render's tolerance), so they need only pass the
/// light point within the chord tolerance ε: at 10⁻⁵ a step's error stays within 10⁻⁵ of the
/// distance from the centre, and a shot across a scene errs by a few 10⁻⁴ of its radius at most,
/// well inside the 64 ε a traced aim may land from its point; the density errs by ~10⁻⁵.
const AIM_RTOL: f64 = 1e-5;

/// Relative tolerance of an in-plane aim's shots: the ray's error stays ~10⁻⁶ of its distance
/// from the centre, far inside the chord tolerance ε it must land within, and the density's
/// ~10⁻⁶, far below the noise. A tighter tolerance only costs steps.
const PLANE_AIM_RTOL: f64 = 1e-6;

/// The step cap of an aim's shots, as a fraction of the distance to the centre: loose, since no
/// chord of theirs is tested against the scene: error control, not the cap, sets their steps.
const AIM_STEP_FRACTION: f64 = 8.0;

/// A light ray from a shading point to a light point, aimed ([`Propagator::aim`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aimed {
    /// Direction the ray leaves the start in, in the local frame there (world axes).
    pub start: Vec3,
    /// Direction of travel at the end, in the local frame there (world axes).
    pub end: Vec3,
    /// Unit world tangent at the end.
    pub end_tangent: Vec3,
    /// Solid angle at the start per world area across `end_tangent` at the end.
    pub solid_angle_per_area: f64,
}

impl Propagator {
    /// Whether rays are aimed between points ([`Propagator::aim`]) rather than connected by the
    /// spacetime's own connector: in curved spacetimes without one, or where asked to
    /// ([`Propagator::with_generic_connector`]), when rays are traced by the chord method.
    pub fn aims(&self) -> bool {
        !self.flat && self.connector.is_none() && matches!(self.intersection, crate::settings::Intersection::Chord)
    }

    /// Connects light by the generic 4-D aim in every curved spacetime, the spacetime's own
    /// connector and the in-plane aim set aside (to compare them with it).
    pub fn with_generic_connector(mut self) -> Self {
        self.connector = None;
        self.aims_in_plane = false;
        self
    }

    /// Whether light is aimed each [`Way`] round the centre ([`Propagator::aim`]): in the
    /// ray's plane, where the two ways are two rays; a 4-D aim finds one ray, the short way's.
    pub fn aims_both_ways(&self) -> bool {
        self.aims() && self.spacetime.choose_tracer(InPlane(self))
    }

    /// The radius of the wormhole's throat (about the world origin of both regions) where light
    /// is aimed through it, from one region to the other (in the ray's plane; a 4-D aim stays
    /// in its region); `None` where it is not.
    pub fn aims_through_throat(&self) -> Option<f64> {
        self.spacetime.capabilities().throat().filter(|_| self.aims_both_ways())
    }

    /// The light ray from world point `from` to world point `to` (each with its region) that
    /// Newton's method finds, with its bundle density; `None` where it finds none (or in flat
    /// space, where shadow rays are straight). In the ray's plane it is the ray going `way`
    /// round the centre, less than once, through the throat where the points lie in different
    /// regions; in 4-D only [`Way::Short`] in one region is aimed, from the straight line
    /// between the points (the image nearest it).
    pub fn aim(&self, from: (Region, Vec3), to: (Region, Vec3), way: Way) -> Option<Aimed> {
        self.spacetime.choose_tracer(AimRay { propagator: self, from, to, way })
    }

    fn aim_in_plane<M: PlaneMetric>(
        &self,
        metric: &M,
        from: Vec3,
        (to, side): (Vec3, Side),
        way: Way,
    ) -> Option<Aimed> {
        let settings = PlaneAimSettings { rtol: PLANE_AIM_RTOL, tolerance: self.epsilon };
        let found = plane_aim(metric, from.to_array(), (to.to_array(), side), way, &settings)?;
        // A spherically symmetric spacetime's world points and local frames are the in-plane
        // tracer's own (no chart rotation; the static frame with world axes).
        Some(Aimed {
            start: Vec3::from_array(found.start),
            end: Vec3::from_array(found.end),
            end_tangent: Vec3::from_array(found.end_tangent),
            solid_angle_per_area: found.solid_angle_per_area,
        })
    }

    fn aim_four_d<M: Metric>(&self, metric: &M, region: Region, from: Vec3, to: Vec3) -> Option<Aimed> {
        let x = metric.world_to_chart(region, self.to_chart(from).to_array(), 0.0)?;
        let frame = Tetrad::local_observer(metric, &x).ok()?;
        let trace = TraceSettings {
            stepping: Stepping::Adaptive { rtol: AIM_RTOL },
            max_step_fraction: AIM_STEP_FRACTION,
            ..self.trace
        };
        let settings = AimSettings { trace, tolerance: self.epsilon, max_shots: MAX_SHOTS };
        let target = self.to_chart(to).to_array();
        // The first guess, in the frame whose axes follow the chart's: the chart's straight line.
        let y = metric.world_to_chart(region, target, 0.0)?;
        let guess = [y[1] - x[1], y[2] - x[2], y[3] - x[3]];
        let found = aim(metric, x, &frame, target, guess, &settings)?;
        let (end, _) = Tetrad::local_observer(metric, &found.end.x).ok()?.backward_direction(&found.end.p);
        let end_tangent = self.to_world(Vec3::from_array(found.end_tangent));
        Some(Aimed {
            start: self.local_direction(region, from, Vec3::from_array(found.direction), found.start_tangent),
            end: self.local_direction(region, to, Vec3::from_array(end), found.end_tangent),
            end_tangent,
            solid_angle_per_area: found.solid_angle_per_area,
        })
    }

    /// The direction, in the renderer's local frame at world point `p`, of a ray with unit
    /// world tangent `tangent` (chart axes) that the chart's local observer measures along
    /// `measured` (chart axes). Where the renderer's frame is the chart observer's (a tetrad)
    /// that is `measured`; a radially scaled frame maps world vectors by `diag(1/κ, 1, 1)`
    /// ([`LocalFrame::Radial`]), whose axes are the world's even where the chart's are not (the
    /// lower region of a wormhole, whose world is the chart turned inside out).
    fn local_direction(&self, region: Region, p: Vec3, measured: Vec3, tangent: [f64; 3]) -> Vec3 {
        match self.local_frame(region, p) {
            LocalFrame::Tetrad { .. } => self.to_world(measured),
            LocalFrame::Radial { kappa } => {
                let t = self.to_world(Vec3::from_array(tangent));
                if p == Vec3::ZERO {
                    return t;
                }
                (t + ((1.0 / kappa - 1.0) * t.dot(p) / p.length_squared()) * p).normalize()
            }
            LocalFrame::None => self.to_world(Vec3::from_array(tangent)),
        }
    }
}

/// An aim, handed to the tracer the spacetime chooses.
struct AimRay<'a> {
    propagator: &'a Propagator,
    from: (Region, Vec3),
    to: (Region, Vec3),
    way: Way,
}

impl Tracers for AimRay<'_> {
    type Output = Option<Aimed>;

    fn straight(self) -> Option<Aimed> {
        None
    }

    fn in_plane<M: PlaneMetric>(self, metric: &M) -> Option<Aimed> {
        if !self.propagator.aims_in_plane {
            return self.four_d(metric);
        }
        let ((from_region, from), (to_region, to)) = (self.from, self.to);
        let side = if to_region == from_region { Side::Same } else { Side::Other };
        self.propagator.aim_in_plane(metric, from, (to, side), self.way)
    }

    /// Aiming needs the ray bundle, which rides on Hamilton's equations.
    fn own_stepper<M: OwnStepper>(self, metric: &M) -> Option<Aimed> {
        self.four_d(metric)
    }

    fn four_d<M: Metric>(self, metric: &M) -> Option<Aimed> {
        let ((region, from), (to_region, to)) = (self.from, self.to);
        match self.way {
            Way::Short if to_region == region => self.propagator.aim_four_d(metric, region, from, to),
            Way::Short | Way::Long => None,
        }
    }
}

/// Whether the spacetime's light is aimed in the ray's plane, asked of the tracer it chooses.
struct InPlane<'a>(&'a Propagator);

impl Tracers for InPlane<'_> {
    type Output = bool;

    fn straight(self) -> bool {
        false
    }

    fn in_plane<M: PlaneMetric>(self, _metric: &M) -> bool {
        self.0.aims_in_plane
    }

    fn four_d<M: Metric>(self, _metric: &M) -> bool {
        false
    }

    fn own_stepper<M: OwnStepper>(self, _metric: &M) -> bool {
        false
    }
}
