//! Light running forwards in time about a spinning hole, traced as the backward light of its
//! spin-reversed twin.
//!
//! The charts of Kerr's family here are outgoing Kerr–Schild: regular on the past horizon, which
//! backward-traced rays cross, and singular on the future horizon, which light followed forwards
//! from its sources falls through. The chart regular there is the ingoing one,
//! `x + iy = (r + ia) sin θ e^{iφ̄}`, `dφ̄ = dφ + a/Δ dr`, `dt̄ = dt + (r² + a² − Δ)/Δ dr`
//! (Boyer–Lindquist `t, φ`; Visser 2007, §3), against the outgoing `x + iy = (r − ia) sin θ e^{iφ̃}`,
//! `dφ̃ = dφ − a/Δ dr`, `dt̃ = dt − (r² + a² − Δ)/Δ dr`, `Δ = r² − 2Mr + a² + Q²`. With its time
//! reversed, `t' = −t̄`, the ingoing chart of spin `a` is the outgoing chart of spin `−a`: so a
//! future-directed ray of the hole is a past-directed ray of the twin of spin `−a`, which the
//! backward tracer follows through the horizon as it follows any camera ray.
//!
//! The twin's points are the hole's turned about the spin axis by `δ(r) = φ̄ − φ̃ =
//! 2 atan(a/r) − 2a ∫_r^∞ dr'/Δ` (zero far away) with `t' = −t − H(r)`, `H' = 2(r² + a² − Δ)/Δ`,
//! so `H = 2(r* − r)` with the tortoise radius `dr*/dr = (r² + a²)/Δ`:
//! `H = 4M ln((r − r₋)/M) − 2(r₊² + a²) ∫_r^∞ dr'/Δ` (its constant chosen so; no stationary
//! metric sees it). The spheroidal radius `r` is the same in both. Ray tracing needs only the
//! spatial map; the time map is what places a body falling through the future horizon
//! ([`crate::worldline`]) at the hole's coordinate times. Covectors go across with the Jacobian of the
//! map back, `p'_μ = p_ν ∂x^ν/∂x'^μ`, so `p_t` changes sign and the conserved energy of the
//! forward ray is that of the backward one.

use super::{KerrNewman, KerrSchild};
use crate::tensor::{Covector4, Vector4};

/// The map between the chart of a hole of Kerr's family (mass `M`, spin `a`, charge `Q`) and
/// its twin's (spin `−a`): see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpinTwin {
    hole: KerrNewman,
}

/// Which way a point crosses: from the hole's chart to the twin's, or back.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Way {
    ToTwin,
    FromTwin,
}

impl SpinTwin {
    /// The twin of a hole with `spin² + charge² ≤ mass²` (the horizon exists).
    pub fn new(mass: f64, spin: f64, charge: f64) -> Self {
        Self { hole: KerrNewman::new(mass, spin, charge) }
    }

    /// The twin spacetime, in whose chart forward rays are traced backwards.
    pub fn twin(&self) -> KerrNewman {
        KerrNewman { spin: -self.hole.spin, ..self.hole }
    }

    /// A point and covariant momentum of the hole's chart in the twin's. Both charts meet
    /// outside the horizon, where `δ` and `H` are finite; points inside map to NaN.
    pub fn to_twin(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        self.cross(x, p, Way::ToTwin)
    }

    /// A point and covariant momentum of the twin's chart in the hole's.
    pub fn from_twin(&self, x: &Vector4, p: &Covector4) -> (Vector4, Covector4) {
        self.cross(x, p, Way::FromTwin)
    }

    /// A spatial point of the twin's chart in the hole's.
    pub fn point_from_twin(&self, x: &Vector4) -> [f64; 3] {
        let y = self.point(x, Way::FromTwin);
        [y[1], y[2], y[3]]
    }

    /// A point of the twin's chart in the hole's, its time included (NaN inside the horizon).
    pub fn event_from_twin(&self, x: &Vector4) -> Vector4 {
        self.point(x, Way::FromTwin)
    }

    /// A contravariant vector `v` at point `x` of the twin's chart in the hole's:
    /// `v^μ = ∂x^μ/∂x'^ν v'^ν`.
    pub fn vector_from_twin(&self, x: &Vector4, v: &Vector4) -> Vector4 {
        let j = self.jacobian(x, Way::FromTwin);
        std::array::from_fn(|mu| (0..4).map(|nu| j[mu][nu] * v[nu]).sum())
    }

    /// The hole whose twin this is.
    pub fn hole(&self) -> KerrNewman {
        self.hole
    }

    fn cross(&self, x: &Vector4, p: &Covector4, way: Way) -> (Vector4, Covector4) {
        let y = self.point(x, way);
        // `∂x/∂y` is the Jacobian of the opposite way, taken at `y`.
        let back = self.jacobian(&y, opposite(way));
        let q = std::array::from_fn(|mu| (0..4).map(|nu| p[nu] * back[nu][mu]).sum());
        (y, q)
    }

    /// The point `way` maps `x` to: `t' = −t − H(r)` either way, turned by `±δ(r)`.
    fn point(&self, x: &Vector4, way: Way) -> Vector4 {
        let r = self.hole.radial_coordinate(x);
        let (s, c) = (sign(way) * self.rotation(r)).sin_cos();
        [-x[0] - self.time_shift(r), c * x[1] - s * x[2], s * x[1] + c * x[2], x[3]]
    }

    /// `∂y/∂x` of the map `way` at `x` (`J[μ][ν] = ∂y^μ/∂x^ν`).
    fn jacobian(&self, x: &Vector4, way: Way) -> [[f64; 4]; 4] {
        let (r, dr) = self.radius_gradient(x);
        let sigma = sign(way);
        let (s, c) = (sigma * self.rotation(r)).sin_cos();
        let (y1, y2) = (c * x[1] - s * x[2], s * x[1] + c * x[2]);
        let turn = sigma * self.rotation_rate(r);
        let shift = self.time_shift_rate(r);
        let mut j = [[0.0; 4]; 4];
        j[0][0] = -1.0;
        j[3][3] = 1.0;
        let rotation = [[c, -s, 0.0], [s, c, 0.0]];
        for i in 0..3 {
            j[0][i + 1] = -shift * dr[i];
            j[1][i + 1] = rotation[0][i] - y2 * turn * dr[i];
            j[2][i + 1] = rotation[1][i] + y1 * turn * dr[i];
        }
        j
    }

    /// The spheroidal radius at `x` and its gradient, from
    /// `F = (x² + y²)/(r² + a²) + z²/r² − 1 = 0`: `∇r = −∇F / ∂_r F`.
    fn radius_gradient(&self, x: &Vector4) -> (f64, [f64; 3]) {
        let a2 = self.hole.spin * self.hole.spin;
        let r = self.hole.radial_coordinate(x);
        let (r2, rho2, z) = (r * r, x[1] * x[1] + x[2] * x[2], x[3]);
        let w = r2 + a2;
        let df_dr = -2.0 * r * rho2 / (w * w) - 2.0 * z * z / (r2 * r);
        let grad = [2.0 * x[1] / w, 2.0 * x[2] / w, 2.0 * z / r2];
        (r, grad.map(|g| -g / df_dr))
    }

    fn delta(&self, r: f64) -> f64 {
        let KerrNewman { mass, spin, charge } = self.hole;
        r * r - 2.0 * mass * r + spin * spin + charge * charge
    }

    /// `∫_r^∞ dr'/Δ` with `Δ = (r − r₊)(r − r₋)`: `ln(1 + d/(r − r₊))/d`, `d = r₊ − r₋`, which
    /// is `1/(r − r₊)` at `d = 0` (NaN between the horizons, where the charts do not meet).
    fn tail(&self, r: f64) -> f64 {
        let d = self.horizon_gap();
        let outer = self.hole.mass + 0.5 * d;
        if d > 0.0 {
            (d / (r - outer)).ln_1p() / d
        } else {
            1.0 / (r - outer)
        }
    }

    /// `d = r₊ − r₋ = 2√(M² − a² − Q²)`.
    fn horizon_gap(&self) -> f64 {
        let KerrNewman { mass, spin, charge } = self.hole;
        2.0 * (mass * mass - spin * spin - charge * charge).max(0.0).sqrt()
    }

    /// `δ(r) = 2 atan(a/r) − 2a ∫_r^∞ dr'/Δ`.
    fn rotation(&self, r: f64) -> f64 {
        let spin = self.hole.spin;
        2.0 * (spin / r).atan() - 2.0 * spin * self.tail(r)
    }

    /// `H(r) = 2(r* − r) = 4M ln((r − r₋)/M) − 2(r₊² + a²) ∫_r^∞ dr'/Δ`, whose derivative is
    /// `4M/(r − r₋) + 2(r₊² + a²)/Δ = 2(2Mr − Q²)/Δ` since `Δ(r₊) = 0`. Partial fractions in
    /// this form stay exact as the horizons merge (`d → 0`). NaN inside the outer horizon.
    fn time_shift(&self, r: f64) -> f64 {
        let KerrNewman { mass, spin, .. } = self.hole;
        let d = self.horizon_gap();
        let (outer, inner) = (mass + 0.5 * d, mass - 0.5 * d);
        if r <= outer {
            return f64::NAN;
        }
        4.0 * mass * ((r - inner) / mass).ln() - 2.0 * (outer * outer + spin * spin) * self.tail(r)
    }

    /// `δ'(r) = −2a/(r² + a²) + 2a/Δ`.
    fn rotation_rate(&self, r: f64) -> f64 {
        let a = self.hole.spin;
        -2.0 * a / (r * r + a * a) + 2.0 * a / self.delta(r)
    }

    /// `H'(r) = 2(r² + a² − Δ)/Δ = 2(2Mr − Q²)/Δ`.
    fn time_shift_rate(&self, r: f64) -> f64 {
        let KerrNewman { mass, charge, .. } = self.hole;
        2.0 * (2.0 * mass * r - charge * charge) / self.delta(r)
    }
}

fn sign(way: Way) -> f64 {
    match way {
        Way::ToTwin => 1.0,
        Way::FromTwin => -1.0,
    }
}

fn opposite(way: Way) -> Way {
    match way {
        Way::ToTwin => Way::FromTwin,
        Way::FromTwin => Way::ToTwin,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::{HamiltonianTracer, State, TraceSettings};
    use crate::metric::Metric;
    use crate::observer::Tetrad;

    const POINTS: [[f64; 4]; 5] = [
        [0.0, 3.0, -1.0, 0.5],
        [0.0, -0.4, 1.6, -0.9],
        [0.0, 0.2, 0.1, 2.5],
        [0.0, 7.0, 4.0, -3.0],
        [0.0, 1.1, -1.2, 0.05],
    ];

    fn holes() -> [SpinTwin; 3] {
        [SpinTwin::new(1.0, 0.9, 0.0), SpinTwin::new(1.0, -0.6, 0.5), SpinTwin::new(1.0, 1.0, 0.0)]
    }

    /// The map is an isometry onto the twin: `g = Jᵀ g' J` with `J = ∂x'/∂x`. A wrong sign of
    /// the rotation or of the time shift leaves off-diagonal terms of order `a/r`.
    #[test]
    fn the_twin_chart_carries_the_holes_metric() {
        for twin in holes() {
            for x in POINTS {
                if twin.hole.inside_horizon(&x) {
                    continue;
                }
                let y = twin.point(&x, Way::ToTwin);
                let j = twin.jacobian(&x, Way::ToTwin);
                let (g, h) = (twin.hole.metric(&x), twin.twin().metric(&y));
                for m in 0..4 {
                    for n in 0..4 {
                        let pulled: f64 = (0..4)
                            .flat_map(|a| (0..4).map(move |b| (a, b)))
                            .map(|(a, b)| j[a][m] * h[a][b] * j[b][n])
                            .sum();
                        assert!(
                            (pulled - g[m][n]).abs() < 1e-12,
                            "{twin:?} at {x:?}: g[{m}][{n}] {} vs {pulled}",
                            g[m][n]
                        );
                    }
                }
            }
        }
    }

    /// The time map's shift `H` has the derivative the Jacobian uses, for every kind of hole
    /// (extremal ones included, where the partial fractions merge): a wrong `H` would place
    /// bodies at the wrong times, which the isometry test (on the Jacobian alone) cannot see.
    #[test]
    fn the_time_shift_is_the_integral_of_its_rate() {
        for twin in holes().into_iter().chain([SpinTwin::new(1.0, 0.0, 0.0), SpinTwin::new(1.0, 0.0, 0.7)]) {
            for r in [2.3, 3.0, 7.5, 40.0] {
                let h = 1e-5 * r;
                let slope = (twin.time_shift(r + h) - twin.time_shift(r - h)) / (2.0 * h);
                let rate = twin.time_shift_rate(r);
                assert!((slope - rate).abs() < 1e-7 * rate.abs(), "{twin:?} at r = {r}: {slope} vs {rate}");
            }
            assert!(twin.time_shift(0.5 * twin.hole.horizon_radius()).is_nan(), "inside the horizon");
        }
    }

    #[test]
    fn points_and_momenta_come_back() {
        for twin in holes() {
            for x in POINTS.into_iter().filter(|x| !twin.hole.inside_horizon(x)) {
                let p = [-1.0, 0.3, -0.2, 0.7];
                let (y, q) = twin.to_twin(&x, &p);
                let (x2, p2) = twin.from_twin(&y, &q);
                for k in 0..4 {
                    assert!((x2[k] - x[k]).abs() < 1e-12 && (p2[k] - p[k]).abs() < 1e-12, "{x:?} {p:?}: {x2:?} {p2:?}");
                }
                assert_eq!(q[0], -p[0], "the energy's sign turns with time");
            }
        }
    }

    /// Far from the horizon the hole's own chart follows a forward ray well; the twin's backward
    /// ray, mapped back, runs along the same curve.
    #[test]
    fn a_backward_ray_of_the_twin_is_a_forward_ray_of_the_hole() {
        let twin = SpinTwin::new(1.0, 0.9, 0.0);
        let hole = twin.hole;
        let x = [0.0, 12.0, 1.0, 2.0];
        let frame = Tetrad::local_observer(&hole, &x).unwrap();
        let n = [-0.8, 0.5, -0.2];
        let norm = crate::tensor::norm3(&n);
        let n = n.map(|c| c / norm);
        // p = E(e₀ + n e): future-directed, leaving along n.
        let p = frame.backward_momentum(&hole.metric(&x), n.map(|c| -c), 1.0).map(|c| -c);
        let settings =
            TraceSettings { stepping: crate::geodesic::Stepping::Adaptive { rtol: 1e-10 }, ..TraceSettings::default() };
        let mut forward = HamiltonianTracer::new(&hole, State { x, p }, settings);
        let (y, q) = twin.to_twin(&x, &p);
        let twin_metric = twin.twin();
        let mut backward = HamiltonianTracer::new(&twin_metric, State { x: y, p: q }, settings);
        assert!(twin_metric.geodesic_rhs(&y, &q).0[0] < 0.0, "the twin's ray is past-directed");
        // Both affine parameters agree: the map is a coordinate change of one curve.
        for _ in 0..40 {
            forward.step(f64::INFINITY).unwrap();
        }
        let lambda = forward.lambda();
        while backward.lambda() < lambda {
            backward.step(lambda - backward.lambda()).unwrap();
        }
        let (a, b) = (forward.state().x, twin.point_from_twin(&backward.state().x));
        let r = hole.radial_coordinate(&a);
        assert!(r > 4.0, "the ray stays far from the hole (r = {r})");
        for k in 0..3 {
            assert!((a[k + 1] - b[k]).abs() < 1e-6, "forward {a:?}, twin mapped back {b:?}");
        }
    }
}
