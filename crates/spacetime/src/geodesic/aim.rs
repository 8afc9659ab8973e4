//! Aiming a light ray of any metric at a point: the shooting problem behind next-event
//! estimation where no closed-form connection exists (Kerr, charged holes, wormholes, metrics a
//! user writes).
//!
//! A ray leaves the start `x` along a unit direction `d` measured by the local observer there
//! (traced backwards, as a camera's rays are). Where it first passes closest to the target `y`
//! (in world coordinates: `(W(λ) − y) · t(λ) = 0`, `W` the world position and `t` the world
//! tangent), it misses `y` by `m ⊥ t`. Turning `d` by small angles `α₁, α₂` about two axes
//! perpendicular to it moves that point by `J α` across the ray, with `J` the 2 × 2 Jacobian of
//! the ray bundle ([`super::bundle`]) projected onto the plane normal to `t` (moving the point
//! along the ray only moves the closest approach). Newton's method turns `d` by `α = −J⁻¹ m`,
//! each turn limited to [`MAX_TURN`] and halved while the miss grows, until the miss is within
//! the tolerance. The first guess is the straight line from `x` to `y`, so the ray found is a
//! deterministic function of the two points: the image of `y` nearest the straight line, where
//! the iteration converges to it (a sampling strategy that never produces the other images,
//! which are then found by BSDF sampling alone: see the renderer's MIS weights).
//!
//! Density: `α₁, α₂` are orthonormal coordinates on the sphere of directions at `x` to first
//! order, so the ray's cross-section at `y` per unit solid angle at `x` is `|det J|`:
//!
//! ```text
//! dΩ/dA⊥ = 1 / |det J|,
//! ```
//!
//! `A⊥` the world area across the world tangent `t` at `y` (a surface with world normal `n`
//! meets the beam with area `A⊥/|n · t|`). In flat space this is `1/d²`.

use super::bundle::{Bundle, BUNDLE};
use super::{Fate, HamiltonianTracer, State, TraceSettings, Visit};
use crate::metric::{Metric, Region};
use crate::observer::Tetrad;
use crate::tensor::{contract, cross3, dot3, norm3, normalize3, scale3, sub3, Matrix4, Vector4};

/// The largest turn of the start direction in one Newton step, in radians: beyond it the
/// linear model of the miss is not trusted.
pub const MAX_TURN: f64 = 0.25;
/// How often a Newton step whose shot missed by more than the previous one (or failed) is
/// halved before the aim gives up.
const MAX_HALVINGS: u32 = 6;
/// The tilts away from the centre of the first shots, in radians, tried in turn while they end
/// before passing the target: a ray aimed straight past a hole is captured when it passes
/// within the critical impact parameter, up to ~5 M; from a few M away, that takes a tilt of
/// up to a radian.
const TILTS: [f64; 6] = [0.0, 0.1, 0.25, 0.5, 0.8, 1.1];
/// Bisections of the step that holds the closest approach: its affine position to 2⁻⁴⁰.
const CLOSEST_BISECTIONS: u32 = 40;

/// How an [`aim`] is taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AimSettings {
    /// The tracer's settings for every shot.
    pub trace: TraceSettings,
    /// The aim is taken when the ray passes within this world distance of the target.
    pub tolerance: f64,
    /// Shots before the aim gives up.
    pub max_shots: u32,
}

/// A ray from a start point through a target point, with its density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aim {
    /// Unit direction the ray leaves the start in, in the frame it was aimed in.
    pub direction: [f64; 3],
    /// Unit world tangent at the start.
    pub start_tangent: [f64; 3],
    /// Unit world tangent at the target.
    pub end_tangent: [f64; 3],
    /// `dΩ/dA⊥`: solid angle at the start per world area across `end_tangent` at the target.
    pub solid_angle_per_area: f64,
    /// The ray at its closest approach to the target, in the chart.
    pub end: State,
    /// Shots taken.
    pub shots: u32,
}

/// Where one shot passed the target.
struct Pass {
    /// World displacement from the target to the ray's closest approach.
    miss: [f64; 3],
    /// Unit world tangent there.
    tangent: [f64; 3],
    /// World displacements there per unit turn about each of the two axes.
    spread: [[f64; 3]; 2],
    end: State,
}

/// The ray from chart point `x` (observer frame `frame`) through the world point `target` of
/// `x`'s region, starting from the guess `guess` (a direction in `frame`); `None` where Newton's
/// method does not converge within the settings' shots, or the rays it shoots end before they
/// pass the target.
pub fn aim<M: Metric + ?Sized>(
    metric: &M,
    x: Vector4,
    frame: &Tetrad,
    target: [f64; 3],
    guess: [f64; 3],
    settings: &AimSettings,
) -> Option<Aim> {
    let g = metric.metric(&x);
    let shooter = Shooter { metric, x, g, frame, target, region: metric.region(&x), settings };
    let (mut direction, mut pass, mut shots) = first_pass(&shooter, normalize3(&guess))?;
    loop {
        let miss = norm3(&pass.miss);
        if miss <= settings.tolerance {
            // |det J|: the area the two spreads span, projected across the tangent.
            let spread_area = dot3(&cross3(&pass.spread[0], &pass.spread[1]), &pass.tangent).abs();
            let (_, start_tangent) = shooter.world(&State { x, p: frame.backward_momentum(&g, direction, 1.0) })?;
            let aim = Aim {
                direction,
                start_tangent,
                end_tangent: pass.tangent,
                solid_angle_per_area: 1.0 / spread_area,
                end: pass.end,
                shots,
            };
            return (aim.solid_angle_per_area.is_finite()).then_some(aim);
        }
        let turn = newton_turn(&pass)?;
        let mut scale = 1.0;
        let mut halvings = 0;
        loop {
            if shots >= settings.max_shots {
                return None;
            }
            let next = turned(direction, turn, scale);
            shots += 1;
            match shooter.shoot(next) {
                Some(p) if norm3(&p.miss) < miss => {
                    (direction, pass) = (next, p);
                    break;
                }
                _ if halvings < MAX_HALVINGS => {
                    halvings += 1;
                    scale *= 0.5;
                }
                _ => return None,
            }
        }
    }
}

/// The first shot that passes the target: along the guess, else (captured on the way, or ended
/// before passing) along the guess tilted away from the centre by each of [`TILTS`], as the ray
/// round the near side of a hole leaves. Returns the direction, its pass and
/// the shots taken.
fn first_pass<M: Metric + ?Sized>(shooter: &Shooter<'_, M>, guess: [f64; 3]) -> Option<([f64; 3], Pass, u32)> {
    let centre = normalize3(&scale3(&crate::tensor::spatial(&shooter.x), -1.0));
    let across = sub3(&centre, &scale3(&guess, dot3(&centre, &guess)));
    let away = if norm3(&across) > 1e-9 { normalize3(&across) } else { perpendicular(&guess) };
    for (shots, tilt) in (1..).zip(TILTS) {
        let direction = normalize3(&std::array::from_fn(|i| guess[i] * tilt.cos() - away[i] * tilt.sin()));
        if let Some(pass) = shooter.shoot(direction) {
            return Some((direction, pass, shots));
        }
    }
    None
}

/// Newton's turn `α = −J⁻¹ m` about the two axes of the shot, at most [`MAX_TURN`] long; `None`
/// where the bundle is degenerate (a caustic at the target).
fn newton_turn(pass: &Pass) -> Option<[f64; 2]> {
    let b1 = normalize3(&perpendicular(&pass.tangent));
    let b2 = cross3(&pass.tangent, &b1);
    let j = [
        [dot3(&b1, &pass.spread[0]), dot3(&b1, &pass.spread[1])],
        [dot3(&b2, &pass.spread[0]), dot3(&b2, &pass.spread[1])],
    ];
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if !(det.abs() > 0.0 && det.is_finite()) {
        return None;
    }
    let (m1, m2) = (dot3(&b1, &pass.miss), dot3(&b2, &pass.miss));
    let alpha = [-(j[1][1] * m1 - j[0][1] * m2) / det, -(-j[1][0] * m1 + j[0][0] * m2) / det];
    let length = alpha[0].hypot(alpha[1]);
    let limit = if length > MAX_TURN { MAX_TURN / length } else { 1.0 };
    Some([alpha[0] * limit, alpha[1] * limit])
}

/// `direction` turned by `scale · turn` about its two axes ([`axes`]).
fn turned(direction: [f64; 3], turn: [f64; 2], scale: f64) -> [f64; 3] {
    let [e1, e2] = axes(&direction);
    let moved: [f64; 3] = std::array::from_fn(|i| direction[i] + scale * (turn[0] * e1[i] + turn[1] * e2[i]));
    normalize3(&moved)
}

/// Two unit axes perpendicular to the unit vector `d` and to each other, a function of `d`.
fn axes(d: &[f64; 3]) -> [[f64; 3]; 2] {
    let e1 = normalize3(&perpendicular(d));
    [e1, cross3(d, &e1)]
}

/// A vector perpendicular to `v`, built from its smallest component (never degenerate).
fn perpendicular(v: &[f64; 3]) -> [f64; 3] {
    if v[0].abs() <= v[1].abs() && v[0].abs() <= v[2].abs() {
        [0.0, -v[2], v[1]]
    } else if v[1].abs() <= v[2].abs() {
        [-v[2], 0.0, v[0]]
    } else {
        [-v[1], v[0], 0.0]
    }
}

/// What every shot of one aim shares.
struct Shooter<'a, M: Metric + ?Sized> {
    metric: &'a M,
    x: Vector4,
    /// The metric at `x`.
    g: Matrix4,
    frame: &'a Tetrad,
    target: [f64; 3],
    region: Region,
    settings: &'a AimSettings,
}

impl<M: Metric + ?Sized> Shooter<'_, M> {
    /// Traces the ray along `direction` with its bundle to where it first passes closest to the
    /// target; `None` if it ends first, or moves away from the target from the start.
    fn shoot(&self, direction: [f64; 3]) -> Option<Pass> {
        let g = &self.g;
        let p = self.frame.backward_momentum(g, direction, 1.0);
        let rest = self.frame.backward_momentum(g, [0.0; 3], 1.0);
        let mut y = [0.0; BUNDLE];
        y[..4].copy_from_slice(&self.x);
        y[4..8].copy_from_slice(&p);
        for (k, axis) in axes(&direction).iter().enumerate() {
            // The momentum is affine in the direction: a turn about an axis moves it by the
            // axis's share of the frame.
            let turned = self.frame.backward_momentum(g, *axis, 1.0);
            for i in 0..4 {
                y[8 + 8 * k + 4 + i] = turned[i] - rest[i];
            }
        }
        if self.approach(&State { x: self.x, p })? >= 0.0 {
            return None;
        }
        let mut pass = None;
        let trace =
            HamiltonianTracer::<_, BUNDLE, Bundle>::of_flow(self.metric, y, self.settings.trace).run(|step| match self
                .approach(&step.end)
            {
                Some(f) if f >= 0.0 => {
                    pass = self.closest_in(step);
                    Visit::Stop
                }
                _ => Visit::Continue,
            });
        match trace.fate {
            Fate::Stopped => pass,
            Fate::Escaped { .. } | Fate::Traversed { .. } | Fate::Captured | Fate::Failed(_) => None,
        }
    }

    /// `(W − y) · t` at the ray state `s`: negative while the ray approaches the target; `None`
    /// in the other region.
    fn approach(&self, s: &State) -> Option<f64> {
        let (at, tangent) = self.world(s)?;
        Some(dot3(&sub3(&at, &self.target), &tangent))
    }

    /// World position and unit tangent of the ray state `s`, if it lies in the target's region.
    fn world(&self, s: &State) -> Option<([f64; 3], [f64; 3])> {
        let dx = contract(&self.metric.inverse_metric(&s.x), &s.p);
        let w = self.metric.to_world(&s.x, &dx);
        (w.region == self.region).then_some((w.position, w.direction))
    }

    /// The closest approach inside a step that began approaching the target and ended
    /// receding, by bisection on the dense output.
    fn closest_in(&self, step: &super::HamiltonianStep<BUNDLE>) -> Option<Pass> {
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..CLOSEST_BISECTIONS {
            let mid = 0.5 * (lo + hi);
            match self.approach(&step.at(mid)) {
                Some(f) if f < 0.0 => lo = mid,
                _ => hi = mid,
            }
        }
        let y = step.flow_at(0.5 * (lo + hi));
        let end = State { x: [y[0], y[1], y[2], y[3]], p: [y[4], y[5], y[6], y[7]] };
        let (at, tangent) = self.world(&end)?;
        let spread =
            [0, 1].map(|k| self.world_displacement(&end.x, [y[8 + 8 * k + 1], y[8 + 8 * k + 2], y[8 + 8 * k + 3]]));
        Some(Pass { miss: sub3(&at, &self.target), tangent, spread, end })
    }

    /// The world displacement of a chart displacement `dx` (spatial) at `x`, by a forward
    /// difference of the chart-to-world map (exact for the Cartesian charts whose world is the
    /// chart).
    fn world_displacement(&self, x: &Vector4, dx: [f64; 3]) -> [f64; 3] {
        let size = norm3(&dx);
        if size == 0.0 {
            return [0.0; 3];
        }
        let h = 1e-7 * norm3(&crate::tensor::spatial(x)).max(self.metric.length_scale()) / size;
        let moved = [x[0], x[1] + h * dx[0], x[2] + h * dx[1], x[3] + h * dx[2]];
        let zero = [0.0; 4];
        let (a, b) = (self.metric.to_world(x, &zero).position, self.metric.to_world(&moved, &zero).position);
        scale3(&sub3(&b, &a), 1.0 / h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metric::{Kerr, Minkowski};

    fn settings() -> AimSettings {
        AimSettings {
            trace: TraceSettings { escape_radius: 200.0, ..TraceSettings::default() },
            tolerance: 1e-9,
            max_shots: 30,
        }
    }

    /// A target behind the hole, whose straight line from the start is captured: the aim tilts
    /// away from the centre, then converges on the ray past the near side.
    #[test]
    fn targets_behind_the_hole_are_reached_round_it() {
        let kerr = Kerr::new(1.0, 0.9);
        let x = [0.0, 6.0, 1.0, 0.5];
        let frame = Tetrad::local_observer(&kerr, &x).unwrap();
        let target = [-7.0, 3.0, -0.5];
        let aim = aim(&kerr, x, &frame, target, sub3(&target, &[6.0, 1.0, 0.5]), &settings()).unwrap();
        assert!(norm3(&sub3(&crate::tensor::spatial(&aim.end.x), &target)) < 1e-8);
    }

    /// In flat space the aim is the straight line, found at the first shot, with `dΩ/dA⊥ = 1/d²`.
    #[test]
    fn flat_space_aims_straight() {
        let x = [0.0, 1.0, 2.0, 3.0];
        let frame = Tetrad::static_observer(&Minkowski, &x).unwrap();
        let target = [4.0, -2.0, 3.5];
        let aim = aim(&Minkowski, x, &frame, target, [0.3, 0.1, 0.9], &settings()).unwrap();
        let d = sub3(&target, &[1.0, 2.0, 3.0]);
        let straight = normalize3(&d);
        assert!(norm3(&sub3(&aim.direction, &straight)) < 1e-9, "{:?}", aim.direction);
        let r2 = dot3(&d, &d);
        assert!((aim.solid_angle_per_area * r2 - 1.0).abs() < 1e-6, "{}", aim.solid_angle_per_area * r2);
    }

    /// Around a spinning hole the aimed ray passes through the target, and its density is the
    /// solid angle of a small cone of directions over the area its rays cover at the target,
    /// counted by shooting the cone's edge.
    #[test]
    fn kerr_aims_pass_through_the_target_with_the_bundles_density() {
        let kerr = Kerr::new(1.0, 0.9);
        let x = [0.0, 6.0, 1.0, 0.5];
        let frame = Tetrad::local_observer(&kerr, &x).unwrap();
        let target = [-7.0, 4.0, -0.5];
        let s = settings();
        let aim = aim(&kerr, x, &frame, target, sub3(&target, &[6.0, 1.0, 0.5]), &s).unwrap();
        let at = crate::tensor::spatial(&aim.end.x);
        assert!(norm3(&sub3(&at, &target)) < 1e-8);
        assert!(aim.shots > 2, "the hole bends the ray: {} shots", aim.shots);
        // Shoot the rays of a small circle of directions about the aim and measure the area
        // their passes span across the end tangent.
        let g = kerr.metric(&x);
        let shooter = Shooter { metric: &kerr, x, g, frame: &frame, target, region: Region::Upper, settings: &s };
        let (radius, n) = (1e-4, 64);
        let [e1, e2] = axes(&aim.direction);
        let t = aim.end_tangent;
        let (b1, b2) = (normalize3(&perpendicular(&t)), cross3(&t, &normalize3(&perpendicular(&t))));
        let ring: Vec<[f64; 2]> = (0..n)
            .map(|k| {
                let phi = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                let d: [f64; 3] =
                    std::array::from_fn(|i| aim.direction[i] + radius * (phi.cos() * e1[i] + phi.sin() * e2[i]));
                let pass = shooter.shoot(normalize3(&d)).unwrap();
                let w = sub3(&pass.miss, &scale3(&t, dot3(&pass.miss, &t)));
                [dot3(&w, &b1), dot3(&w, &b2)]
            })
            .collect();
        let area: f64 = (0..n)
            .map(|k| {
                let (a, b) = (ring[k], ring[(k + 1) % n]);
                0.5 * (a[0] * b[1] - a[1] * b[0])
            })
            .sum::<f64>()
            .abs();
        // The ring's polygon, mapped linearly to first order: compare polygon with polygon.
        let solid_angle = 0.5 * n as f64 * radius * radius * (2.0 * std::f64::consts::PI / n as f64).sin();
        let measured = solid_angle / area;
        assert!((measured / aim.solid_angle_per_area - 1.0).abs() < 1e-4, "{measured} vs {}", aim.solid_angle_per_area);
        // And it is not flat space's answer.
        let d2 = dot3(&sub3(&target, &[6.0, 1.0, 0.5]), &sub3(&target, &[6.0, 1.0, 0.5]));
        assert!((aim.solid_angle_per_area * d2 - 1.0).abs() > 0.05, "{}", aim.solid_angle_per_area * d2);
    }
}
