//! Where a curved piece of a ray crosses the plane of a flat object, solved on the curve itself.
//!
//! The chord test finds a hit by halving a step until its chord lies within ε of the curve:
//! about five levels on the black-hole room's steps, each placing a point and testing two
//! triangles against the scene. Against a flat object the crossing can be solved instead. The
//! height `s(θ) = n · (x(θ) − p)` of the ray's point above the object's plane is a smooth function
//! of the step's fraction `θ`, and its root is found by Newton's method kept inside a bracket,
//! to far below ε in two or three iterations.
//!
//! Which pieces hold a root follows from the heights of their ends alone where rays bend towards
//! the centre (Schwarzschild): within a sweep below π, a ray that has crossed a plane to the
//! centre's side cannot come back to it (`spacetime::metric::schwarzschild::connect::short_way_arrives_behind`,
//! a Sturm comparison). So a piece with its ends on opposite sides crosses exactly once, a piece
//! with both ends on the far side from the centre never does, and only a piece with both ends on
//! the centre's side may cross twice (poke out and come back), which the caller settles by
//! splitting it.

use crate::geometry::Vec3;

/// How a piece of a ray, with its ends at heights `s_a`, `s_b` above a plane, meets it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Meeting {
    /// Not at all.
    Never,
    /// Exactly once.
    Once,
    /// Twice or not at all.
    Maybe,
}

impl Meeting {
    /// The meeting of a piece that sweeps less than π about the centre, bending towards it, with
    /// the plane whose height above the centre is `s_centre`.
    pub fn of(s_a: f64, s_b: f64, s_centre: f64) -> Self {
        if s_a * s_b < 0.0 {
            Meeting::Once
        } else if s_a == 0.0 || s_b == 0.0 {
            Meeting::Maybe
        } else if s_centre == 0.0 || (s_a > 0.0) != (s_centre > 0.0) {
            // Crossing a plane through the centre twice takes a sweep of π.
            Meeting::Never
        } else {
            Meeting::Maybe
        }
    }
}

/// Most iterations of [`crossing`]: Newton's method converges in two or three from its start,
/// and each bisection that replaces a wild step halves the bracket.
const MAX_ITERATIONS: u32 = 60;

/// The fraction `θ ∈ [a.0, b.0]` where a curve crosses the plane through `point` with unit
/// normal `normal`, and the curve's point there, given its points `a.1` and `b.1` on opposite
/// sides of the plane at the bracket's ends `a.0 < b.0` and its position and velocity
/// `motion(θ) = (x, dx/dθ)`: to within `tolerance` along the curve, where Newton's next step is
/// that short or the bracket has closed to that length. (A height within tolerance is not enough:
/// a ray that runs along the plane, just off it, has small heights far from where it crosses.)
///
/// Newton's method works on the height over the distance from the centre, `g = s/|x|`: a ray's
/// distance `1/u` changes fast where `u` is small, its direction `x/|x|` and `u` do not, and
/// `g = n · x/|x| − (n · p) u` is nearly a sinusoid in the azimuth for Schwarzschild rays, where
/// the height `s` itself is far from linear on a long step (four iterations instead of two).
/// Its step needs no distances: with `s' = n · ẋ`, `g/g' = s/(s' − s (x · ẋ)/|x|²)`, and the
/// lengths are compared squared, so an iteration waits on two divisions instead of two square
/// roots and four divisions.
pub fn crossing(
    motion: impl Fn(f64) -> (Vec3, Vec3),
    point: Vec3,
    normal: Vec3,
    a: (f64, Vec3),
    b: (f64, Vec3),
    tolerance: f64,
) -> (f64, Vec3) {
    let scaled = |x: Vec3| normal.dot(x - point) / x.length();
    let (mut a, mut b) = ((a.0, scaled(a.1)), (b.0, scaled(b.1)));
    // Regula falsi starts it.
    let mut theta = a.0 + (b.0 - a.0) * a.1 / (a.1 - b.1);
    let tolerance2 = tolerance * tolerance;
    for _ in 0..MAX_ITERATIONS {
        let (x, velocity) = motion(theta);
        let height = normal.dot(x - point);
        let slope = normal.dot(velocity) - height * x.dot(velocity) / x.length_squared();
        // Only the signs of the bracket's heights are read from here on.
        if (height < 0.0) == (a.1 < 0.0) {
            a = (theta, height);
        } else {
            b = (theta, height);
        }
        // Newton's step counts only where it stays in the bracket: a ray leaving the plane, just
        // off it, points back to where it left, not to where it comes back through.
        let newton = theta - height / slope;
        let inside = newton >= a.0 && newton <= b.0;
        let speed2 = velocity.length_squared();
        let short = |dtheta: f64| dtheta * dtheta * speed2 <= tolerance2;
        if (inside && short(newton - theta)) || short(b.0 - a.0) {
            return (theta, x);
        }
        theta = if inside { newton } else { 0.5 * (a.0 + b.0) };
    }
    (theta, motion(theta).0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_are_sorted_by_the_sides_of_their_ends() {
        // The centre 2 below the plane (height −2): its side is below.
        assert_eq!(Meeting::of(1.0, -1.0, -2.0), Meeting::Once);
        assert_eq!(Meeting::of(-1.0, 1.0, -2.0), Meeting::Once);
        assert_eq!(Meeting::of(1.0, 3.0, -2.0), Meeting::Never);
        assert_eq!(Meeting::of(-1.0, -3.0, -2.0), Meeting::Maybe);
        assert_eq!(Meeting::of(0.0, -3.0, -2.0), Meeting::Maybe);
        assert_eq!(Meeting::of(1.0, 3.0, 0.0), Meeting::Never);
        assert_eq!(Meeting::of(-1.0, -3.0, 0.0), Meeting::Never);
    }

    #[test]
    fn a_curve_running_just_off_the_plane_is_cut_where_it_crosses() {
        // It crosses y = 0 at x = 0.1, then runs just below the plane, within 10⁻⁵, to the end of
        // the bracket: y = −10⁻⁵ tanh((x − 0.1)/0.01), x ∈ [0, 1.2], a unit off the centre. Its
        // heights are within the tolerance almost all along; only Newton's step tells where it
        // crosses. (A ray met a room's wall like this, just below the ceiling's edge.)
        let curve = |t: f64| {
            let (x, th) = (1.2 * t, ((1.2 * t - 0.1) / 0.01).tanh());
            (Vec3::new(x, -1e-5 * th, 1.0), Vec3::new(1.2, -1.2e-3 * (1.0 - th * th), 0.0))
        };
        let at = |t: f64| (t, curve(t).0);
        let (theta, x) = crossing(curve, Vec3::ZERO, Vec3::Y, at(0.0), at(1.0), 1e-4);
        assert!((x.x - 0.1).abs() < 1e-4, "{theta}: {x}");
    }

    #[test]
    fn a_curve_leaving_the_plane_is_cut_where_it_comes_back() {
        // From 10⁻⁹ above y = 0 (a ray's offset start), up and back down through the plane at
        // x ≈ 0.5: y = 10⁻⁹ + x(0.5 − x). Newton's step at the start points back to it.
        let curve = |t: f64| (Vec3::new(t, 1e-9 + t * (0.5 - t), 1.0), Vec3::new(1.0, 0.5 - 2.0 * t, 0.0));
        let at = |t: f64| (t, curve(t).0);
        let (theta, _) = crossing(curve, Vec3::ZERO, Vec3::Y, at(0.0), at(1.0), 1e-6);
        assert!((theta - 0.5).abs() < 1e-5, "{theta}");
    }

    #[test]
    fn a_circle_is_cut_where_it_crosses_a_line() {
        // The unit circle from angle 0 to 1.2 (θ ∈ [0, 1]) crosses x = 0.5 at angle π/3.
        let motion = |t: f64| {
            let (s, c) = (1.2 * t).sin_cos();
            (Vec3::new(c, s, 0.0), 1.2 * Vec3::new(-s, c, 0.0))
        };
        let (point, normal) = (Vec3::new(0.5, 0.0, 0.0), Vec3::X);
        let at = |t: f64| (t, motion(t).0);
        let (theta, x) = crossing(motion, point, normal, at(0.0), at(1.0), 1e-13);
        assert!((1.2 * theta - std::f64::consts::FRAC_PI_3).abs() < 1e-12, "{theta}");
        assert_eq!(x, motion(theta).0);
        // Near the top, where the secant's start is far off and Newton's first step overshoots.
        let (point, normal) = (Vec3::new(0.0, 0.9, 0.0), Vec3::Y);
        let (theta, _) = crossing(motion, point, normal, at(0.0), at(1.0), 1e-13);
        assert!((1.2 * theta - 0.9f64.asin()).abs() < 1e-11, "{theta}");
    }
}
