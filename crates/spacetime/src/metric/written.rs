//! A metric written by a user as expressions ([`Expression`]) for its components `g_ab`, in
//! Cartesian `(t, x, y, z)` or spherical `(t, r, θ, φ)` coordinates, with derivatives by dual
//! numbers through [`UserMetric`]: no Christoffel symbols are written by anyone.
//!
//! **Chart.** Rays are always traced in the Cartesian chart. Spherical components are pulled back
//! pointwise, `g_cart = Jᵀ g_sph J` with `J = ∂(t, r, θ, φ)/∂(t, x, y, z)` evaluated over the same
//! dual numbers, so the derivatives are those of the Cartesian components and a ray never meets
//! the coordinate pole as a place where its equations break down. On the polar axis itself
//! (`ρ = √(x² + y²) = 0`) `J` is singular though `Jᵀ g J` has a finite limit for a metric regular
//! there; the product is evaluated at the point moved off the axis, within the cylinder
//! `ρ < η r`, to `ρ = η r` (keeping its azimuth; along +x from the axis itself), its dual parts
//! unchanged. Near the axis the terms of `Jᵀ g J` and of its derivatives grow as `1/ρ` and
//! cancel to their finite sum, losing `ε r/ρ` of relative precision (`ε` = 2⁻⁵²); the move
//! changes the metric by `O(η)` of its size and its derivatives likewise. `η = √ε ≈ 1.5·10⁻⁸`
//! balances the two: everywhere, on the axis included, the metric and its derivatives are
//! good to about 10⁻⁸, far below the integrator's tolerance, and a camera looking along the axis
//! sees no seam.
//!
//! **Horizons.** A written metric has no horizon the tracer knows of, and its chart may end at
//! one: Schwarzschild's coordinates have `g_tt → 0`, `g_rr → ∞` at `r = 2M`, which a backward ray
//! approaches with `dt/dλ → ∞`. Two criteria capture such rays:
//!
//! - the lapse `α = 1/√(−g^tt)` of the chart's time slices (the proper time of their normal
//!   observer per coordinate time) falls below [`LAPSE_FLOOR`], or `g^tt ≥ 0` (the slices are not
//!   spacelike): at a Killing horizon of a static or stationary chart `α → 0`. Light from there
//!   reaches an observer with `α ≈ 1` redshifted by `1/α` at least (`α` is `√(−g_tt)` for a static
//!   metric), its radiance by the fourth power (`I_ν/ν³` is invariant): at `α < 10⁻³` less than
//!   10⁻¹² of it is left, nothing a film records. Unlike `√(−g_tt)` it does not vanish at an
//!   ergosurface, which rays cross and leave again;
//! - the integration collapses ([`Metric::collapse_captures`]): the step error control asks for
//!   shrinks to nothing, or the state stops being finite, as at a curvature singularity.
//!
//! An optional `horizon` expression, captured where it is ≤ 0 (`"r - 2*M"`), adds the exact
//! horizon of a chart that crosses it (Kerr–Schild forms), where neither criterion fires until
//! the singularity.

use super::capabilities::{tetrad_frame, tetrad_lapse, Capabilities, Forwards, LocalFrame, NoRest, Tracers};
use super::expression::{atan2, Expression};
use super::user::{MetricFunction, Scalar, UserMetric};
use super::{Metric, ParameterError, Region};
use crate::disk::CircularOrbits;
use crate::metric::schwarzschild::connect::Connector;
use crate::observer::Tetrad;
use crate::tensor::{invert, Matrix4, Vector4};
use std::sync::Arc;

/// Rays where the time slices' lapse `1/√(−g^tt)` is below this are captured (module
/// documentation).
pub const LAPSE_FLOOR: f64 = 1e-3;

/// The range of a written metric's curvature length `scale`, in scene units (measured: the
/// Schwarzschild metric of mass 1 written by hand renders alike for scales from 10⁻⁹ to 10¹²,
/// loses most rays at 10¹⁵).
pub const MIN_SCALE: f64 = 1e-12;
pub const MAX_SCALE: f64 = 1e12;

/// Half the digits of `f64`: how far from the polar axis spherical components are evaluated
/// (module documentation).
const AXIS_OFFSET: f64 = 1.4901161193847656e-8;

/// The coordinates a metric is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinates {
    /// `(t, x, y, z)`, the chart rays are traced in.
    Cartesian,
    /// `(t, r, θ, φ)` about the chart's z axis: `x = r sin θ cos φ`, `y = r sin θ sin φ`,
    /// `z = r cos θ`.
    Spherical,
}

impl Coordinates {
    /// The names of the coordinates in expressions, `t` first.
    pub fn names(self) -> [&'static str; 4] {
        match self {
            Coordinates::Cartesian => ["t", "x", "y", "z"],
            Coordinates::Spherical => ["t", "r", "theta", "phi"],
        }
    }
}

/// A metric written as expressions for its components.
#[derive(Clone, Debug, PartialEq)]
pub struct WrittenMetric(Arc<Definition>);

#[derive(Debug, PartialEq)]
struct Definition {
    coordinates: Coordinates,
    /// The components `g_ab` with `a ≤ b` that are written; the others are 0.
    components: Vec<(usize, usize, Expression)>,
    /// Which components `g_ab` (both orders) are written.
    written: [[bool; 4]; 4],
    horizon: Option<Expression>,
    scale: f64,
}

impl WrittenMetric {
    /// The metric of `components` (`(a, b, g_ab)`, each pair at most once in either order) in
    /// `coordinates`, captured also where `horizon` is ≤ 0, with curvature length scale `scale`.
    pub fn new(
        coordinates: Coordinates,
        components: Vec<(usize, usize, Expression)>,
        horizon: Option<Expression>,
        scale: f64,
    ) -> Result<Self, ParameterError> {
        if !(MIN_SCALE..=MAX_SCALE).contains(&scale) {
            return Err(ParameterError::new(
                "scale",
                format!(
                    "must lie in [{MIN_SCALE:e}, {MAX_SCALE:e}], got {scale:?}: the curvature length sets the \
                 first steps and the escape radius (hundreds of it), which beyond these bounds fall outside what \
                 double-precision steps resolve, and rays are lost"
                ),
            ));
        }
        let mut written = [[false; 4]; 4];
        let mut upper = Vec::with_capacity(components.len());
        for (a, b, e) in components {
            let (a, b) = (a.min(b), a.max(b));
            if b > 3 || written[a][b] {
                let names = coordinates.names();
                let name = |i: usize| names.get(i).copied().unwrap_or("?");
                return Err(ParameterError::new("", format!("g_{}{} is given twice", name(a), name(b))));
            }
            (written[a][b], written[b][a]) = (true, true);
            upper.push((a, b, e));
        }
        Ok(Self(Arc::new(Definition { coordinates, components: upper, written, horizon, scale })))
    }

    /// The components in the written coordinates at `x` (those coordinates).
    fn written_components<D: Scalar>(&self, x: &[D; 4]) -> [[D; 4]; 4] {
        let mut g = [[D::from(0.0); 4]; 4];
        for (a, b, e) in &self.0.components {
            let v = e.eval(x);
            g[*a][*b] = v;
            g[*b][*a] = v;
        }
        g
    }

    /// `g_cart = Jᵀ g_sph J` at the Cartesian point `x`, off the axis as the module documentation
    /// says. `J`'s `t` row and column are those of the identity and `∂φ/∂z = 0`; only written
    /// components are multiplied.
    fn spherical<D: Scalar>(&self, x: [D; 4]) -> [[D; 4]; 4] {
        let (px, py, z) = off_axis(x[1], x[2], x[3]);
        let rho2 = px * px + py * py;
        let rho = rho2.sqrt();
        let r2 = rho2 + z * z;
        let r = r2.sqrt();
        let zero = D::from(0.0);
        let over = (r2 * rho).recip();
        let jac = [
            [D::from(1.0), zero, zero, zero],
            [zero, px / r, py / r, z / r],
            [zero, px * z * over, py * z * over, -rho / r2],
            [zero, -py / rho2, px / rho2, zero],
        ];
        let g = self.written_components(&[x[0], r, atan2(rho, z), atan2(py, px)]);
        let w = &self.0.written;
        // m[a][j] = g_ab J^b_j.
        let mut m = [[zero; 4]; 4];
        for a in 0..4 {
            if w[a][0] {
                m[a][0] = g[a][0];
            }
            for j in 1..4 {
                for b in (1..4).filter(|&b| w[a][b] && !(b == 3 && j == 3)) {
                    m[a][j] += g[a][b] * jac[b][j];
                }
            }
        }
        // out[i][j] = J^a_i m[a][j].
        let mut out = [[zero; 4]; 4];
        out[0] = m[0];
        for i in 1..4 {
            for j in i..4 {
                let mut s = zero;
                for a in (1..4).filter(|&a| !(a == 3 && i == 3)) {
                    s += jac[a][i] * m[a][j];
                }
                out[i][j] = s;
                out[j][i] = s;
            }
        }
        for j in 1..4 {
            out[j][0] = out[0][j];
        }
        out
    }

    /// The lapse `1/√(−g^tt)` of the chart's time slices at `x`; 0 where `g^tt ≥ 0` or the metric
    /// is singular.
    pub fn lapse(&self, x: &Vector4) -> f64 {
        let ginv = invert(&self.metric(*x)).map_or(f64::NAN, |g| g[0][0]);
        if ginv < 0.0 {
            1.0 / (-ginv).sqrt()
        } else {
            0.0
        }
    }

    fn stationary(&self) -> bool {
        !self.0.components.iter().any(|(_, _, e)| e.reads(0))
    }
}

/// The point `(x, y, z)` moved out to `ρ = η r` where it lies closer to the polar axis, by
/// constants: its dual parts (the derivatives) are untouched.
fn off_axis<D: Scalar>(x: D, y: D, z: D) -> (D, D, D) {
    let (xr, yr, zr) = (x.re(), y.re(), z.re());
    let rho = xr.hypot(yr);
    let floor = AXIS_OFFSET * (rho * rho + zr * zr).sqrt();
    if rho >= floor {
        (x, y, z)
    } else if rho > 0.0 {
        let grow = floor / rho - 1.0;
        (x + xr * grow, y + yr * grow, z)
    } else {
        (x + floor, y, z)
    }
}

impl MetricFunction for WrittenMetric {
    fn metric<D: Scalar>(&self, x: [D; 4]) -> [[D; 4]; 4] {
        match self.0.coordinates {
            Coordinates::Cartesian => self.written_components(&x),
            Coordinates::Spherical => self.spherical(x),
        }
    }

    fn length_scale(&self) -> f64 {
        self.0.scale
    }

    /// Behind the written horizon, or where the lapse has collapsed (module documentation).
    fn inside_horizon(&self, x: &Vector4) -> bool {
        let behind = self.0.horizon.as_ref().is_some_and(|h| {
            let at = match self.0.coordinates {
                Coordinates::Cartesian => *x,
                Coordinates::Spherical => {
                    let (px, py, z) = off_axis(x[1], x[2], x[3]);
                    let rho = px.hypot(py);
                    [x[0], rho.hypot(z), rho.atan2(z), py.atan2(px)]
                }
            };
            !(h.eval(&at) > 0.0)
        });
        behind || !(self.lapse(x) >= LAPSE_FLOOR)
    }

    fn collapse_captures(&self) -> bool {
        true
    }

    fn is_stationary(&self) -> bool {
        self.stationary()
    }

    /// Spherical components that do not read `φ` are symmetric about the z axis; Cartesian ones
    /// are not known to be.
    fn is_axisymmetric(&self) -> bool {
        self.0.coordinates == Coordinates::Spherical && !self.0.components.iter().any(|(_, _, e)| e.reads(3))
    }
}

/// Signs of the eigenvalues of a symmetric matrix: (negative, zero) counts, zero meaning below
/// 10⁻¹² of the largest.
///
/// The matrix is first scaled to unit diagonal, `D^{-1/2} g D^{-1/2}` with `D = |diag g|`: a
/// congruence, which keeps the signature (Sylvester's law of inertia), and which keeps a
/// metric's scales from posing as degeneracy. Near Schwarzschild's horizon `g_tt ≈ −10⁻⁷` beside
/// `g_rr ≈ 10⁷`: unscaled, `g_tt` falls under 10⁻¹² of the largest eigenvalue and the metric
/// would look degenerate where it is only badly scaled.
fn signature(g: &Matrix4) -> (usize, usize) {
    let scale: [f64; 4] = std::array::from_fn(|i| match g[i][i].abs().sqrt() {
        d if d > 0.0 && d.is_finite() => d,
        _ => 1.0,
    });
    let m = nalgebra::Matrix4::from_fn(|i, j| g[i][j] / (scale[i] * scale[j]));
    let eig = nalgebra::SymmetricEigen::new(m).eigenvalues;
    let big = eig.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let zero = eig.iter().filter(|v| v.abs() <= 1e-12 * big).count();
    let negative = eig.iter().filter(|v| **v < -1e-12 * big).count();
    (negative, zero)
}

/// A metric nothing is known of but its components: not flat, no symmetry assumed, observers at
/// rest wherever `∂_t` is timelike and the lapse has not collapsed, the static observer's frame,
/// the 4-D tracer, no bounds and no connector.
impl Capabilities for UserMetric<WrittenMetric> {
    fn is_flat(&self) -> bool {
        false
    }

    fn is_spherically_symmetric(&self) -> bool {
        false
    }

    fn throat(&self) -> Option<f64> {
        None
    }

    /// Reversed rays are rays of the same metric only in a static one, which is not checked.
    fn forwards(&self) -> Forwards {
        Forwards::Unsupported
    }

    /// At `t = 0`: the metric finite and Lorentzian, the lapse above the horizon criterion, and
    /// `g_tt < 0`.
    fn rest(&self, region: Region, p: [f64; 3]) -> Result<(), NoRest> {
        if region == Region::Lower {
            return Err(NoRest::NoSuchRegion);
        }
        let x = [0.0, p[0], p[1], p[2]];
        let g = Metric::metric(self, &x);
        if !g.iter().flatten().all(|v| v.is_finite()) {
            return Err(NoRest::NotFinite);
        }
        let (negative, zero) = signature(&g);
        if (negative, zero) != (1, 0) {
            return Err(NoRest::NotLorentzian { negative, zero });
        }
        if self.0.inside_horizon(&x) {
            return Err(NoRest::Collapsed { lapse: self.0.lapse(&x) });
        }
        if !(g[0][0] < 0.0) {
            return Err(NoRest::TimeNotTimelike { g_tt: g[0][0] });
        }
        Tetrad::static_observer(self, &x).map(|_| ()).map_err(|_| NoRest::TimeNotTimelike { g_tt: g[0][0] })
    }

    fn local_frame(&self, region: Region, p: [f64; 3]) -> LocalFrame {
        tetrad_frame(self, region, p)
    }

    fn observer_lapse(&self, region: Region, p: [f64; 3]) -> f64 {
        tetrad_lapse(self, region, p)
    }

    fn impact_bound(&self, _radius: f64) -> Option<f64> {
        None
    }

    fn no_turning_beyond(&self) -> Option<f64> {
        None
    }

    fn light_connector(&self) -> Option<Connector> {
        None
    }

    /// A written metric's orbits are not known in closed form, and nothing proves it
    /// stationary and axisymmetric.
    fn circular_orbits(&self) -> Option<CircularOrbits> {
        None
    }

    fn choose_tracer<T: Tracers>(&self, tracers: T) -> T::Output {
        tracers.four_d(self)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::metric::expression::Names;
    use crate::metric::{ReissnerNordstrom, Schwarzschild};

    /// The metric of `components` (`(a, b, text)`) with parameters `params`.
    pub(crate) fn written(
        coordinates: Coordinates,
        params: &[(&str, f64)],
        components: &[(usize, usize, &str)],
        horizon: Option<&str>,
    ) -> UserMetric<WrittenMetric> {
        let names = Names { variables: coordinates.names(), constants: params };
        let compile = |text: &str| Expression::compile(text, names).unwrap_or_else(|e| panic!("{text}: {e:?}"));
        let components = components.iter().map(|(a, b, text)| (*a, *b, compile(text))).collect();
        UserMetric(WrittenMetric::new(coordinates, components, horizon.map(compile), 1.0).unwrap())
    }

    /// Schwarzschild in Schwarzschild's coordinates: static, not the Kerr–Schild chart.
    pub(crate) fn spherical_schwarzschild(m: f64) -> UserMetric<WrittenMetric> {
        written(
            Coordinates::Spherical,
            &[("M", m)],
            &[(0, 0, "-(1 - 2*M/r)"), (1, 1, "1/(1 - 2*M/r)"), (2, 2, "r^2"), (3, 3, "r^2*sin(theta)^2")],
            None,
        )
    }

    /// Reissner–Nordström in its Schwarzschild-like coordinates.
    pub(crate) fn spherical_reissner_nordstrom(m: f64, q: f64) -> UserMetric<WrittenMetric> {
        written(
            Coordinates::Spherical,
            &[("M", m), ("Q", q)],
            &[
                (0, 0, "-(1 - 2*M/r + Q^2/r^2)"),
                (1, 1, "1/(1 - 2*M/r + Q^2/r^2)"),
                (2, 2, "r^2"),
                (3, 3, "(r*sin(theta))^2"),
            ],
            None,
        )
    }

    /// The Kerr–Schild Schwarzschild of the built-in metric, written in Cartesian coordinates.
    fn cartesian_schwarzschild(m: f64) -> UserMetric<WrittenMetric> {
        let f = "2*M/sqrt(x^2 + y^2 + z^2)";
        let k = |i: &str| format!("{i}/sqrt(x^2 + y^2 + z^2)");
        let mut components = vec![(0, 0, format!("-1 + {f}"))];
        for (i, xi) in ["x", "y", "z"].iter().enumerate() {
            components.push((0, i + 1, format!("-{f}*{}", k(xi))));
            for (j, xj) in ["x", "y", "z"].iter().enumerate().skip(i) {
                let delta = if i == j { "1 + " } else { "" };
                components.push((i + 1, j + 1, format!("{delta}{f}*{}*{}", k(xi), k(xj))));
            }
        }
        let refs: Vec<(usize, usize, &str)> = components.iter().map(|(a, b, s)| (*a, *b, s.as_str())).collect();
        written(Coordinates::Cartesian, &[("M", m)], &refs, Some("sqrt(x^2 + y^2 + z^2) - 2*M"))
    }

    /// In the static chart the Cartesian metric is
    /// `−A dt² + dr²/A + r² dΩ²` with `dr = r̂·dx`: `g_ij = δ_ij + (1/A − 1) r̂_i r̂_j`.
    fn static_cartesian(a: f64, x: &Vector4) -> Matrix4 {
        let r = crate::tensor::norm3(&crate::tensor::spatial(x));
        let n = [x[1] / r, x[2] / r, x[3] / r];
        std::array::from_fn(|i| {
            std::array::from_fn(|j| match (i, j) {
                (0, 0) => -a,
                (0, _) | (_, 0) => 0.0,
                _ => f64::from(u8::from(i == j)) + (1.0 / a - 1.0) * n[i - 1] * n[j - 1],
            })
        })
    }

    /// Spherical components pulled back to Cartesian ones agree with the closed form, with
    /// exact derivatives (the conformance check's finite differences), off and on the axis.
    #[test]
    fn spherical_components_pull_back() {
        let (m, q) = (1.0, 0.6);
        let s = spherical_reissner_nordstrom(m, q);
        for x in [
            [0.0, 3.0, -4.0, 2.0],
            [0.5, 0.1, 0.2, -9.0],
            [0.0, 0.0, 0.0, 5.0],
            [0.0, 0.0, 0.0, -7.0],
            [0.0, 1e-12, 0.0, 6.0],
        ] {
            let r = crate::tensor::norm3(&crate::tensor::spatial(&x));
            let a = 1.0 - 2.0 * m / r + q * q / (r * r);
            let (got, expect) = (Metric::metric(&s, &x), static_cartesian(a, &x));
            for i in 0..4 {
                for j in 0..4 {
                    assert!(
                        (got[i][j] - expect[i][j]).abs() < 1e-7,
                        "{x:?} g_{i}{j}: {} vs {}",
                        got[i][j],
                        expect[i][j]
                    );
                }
            }
            if x[1] != 0.0 || x[2] != 0.0 {
                crate::metric::conformance::check_metric(&s, &x);
            }
        }
    }

    /// On the axis the derivatives are those just off it: no seam along the axis.
    #[test]
    fn derivatives_are_continuous_across_the_axis() {
        let s = spherical_schwarzschild(1.0);
        let (_, on) = s.inverse_metric_derivatives(&[0.0, 0.0, 0.0, 6.0]);
        let (_, off) = s.inverse_metric_derivatives(&[0.0, 1e-4, 0.0, 6.0]);
        for a in 0..4 {
            for i in 0..4 {
                for j in 0..4 {
                    assert!(
                        (on[a][i][j] - off[a][i][j]).abs() < 1e-4,
                        "∂_{a} g^{i}{j}: {} vs {}",
                        on[a][i][j],
                        off[a][i][j]
                    );
                }
            }
        }
    }

    /// The Cartesian Kerr–Schild form written out is the built-in Schwarzschild.
    #[test]
    fn cartesian_kerr_schild_is_schwarzschild() {
        let (user, hand) = (cartesian_schwarzschild(1.2), Schwarzschild::new(1.2));
        for x in [[0.0, 7.0, 1.0, -2.0], [1.0, -2.0, 0.5, 1.5], [0.0, 0.0, 0.0, 30.0]] {
            let ((a, da), (b, db)) = (user.inverse_metric_derivatives(&x), hand.inverse_metric_derivatives(&x));
            for i in 0..4 {
                for j in 0..4 {
                    assert!((a[i][j] - b[i][j]).abs() < 1e-13);
                    assert!((0..4).all(|k| (da[k][i][j] - db[k][i][j]).abs() < 1e-13));
                }
            }
        }
        assert!(user.inside_horizon(&[0.0, 0.0, 1.9 * 1.2, 0.0]) && !user.inside_horizon(&[0.0, 0.0, 2.1 * 1.2, 0.0]));
    }

    /// Capture by the lapse: `α = √(1 − 2M/r)` in Schwarzschild's chart, under 10⁻³ within
    /// `r − 2M < 2M · 10⁻⁶`; `g^tt > 0` inside.
    #[test]
    fn the_lapse_criterion_captures_at_the_horizon() {
        let s = spherical_schwarzschild(1.0);
        let alpha = |r: f64| s.0.lapse(&[0.0, r, 0.0, 0.0]);
        assert!((alpha(8.0) - 0.75f64.sqrt()).abs() < 1e-12);
        assert!(!s.inside_horizon(&[0.0, 2.0 + 1e-5, 0.0, 0.0]));
        assert!(s.inside_horizon(&[0.0, 2.0 + 1e-7, 0.0, 0.0]));
        assert!(s.inside_horizon(&[0.0, 1.5, 0.0, 0.0]) && alpha(1.5) == 0.0);
    }

    #[test]
    fn rest_and_frames() {
        let s = spherical_schwarzschild(1.0);
        assert_eq!(s.rest(Region::Upper, [0.0, 6.0, 0.0]), Ok(()));
        assert_eq!(s.rest(Region::Lower, [0.0, 6.0, 0.0]), Err(NoRest::NoSuchRegion));
        assert!(matches!(s.rest(Region::Upper, [0.0, 1.0, 0.0]), Err(NoRest::Collapsed { .. })));
        assert_eq!(s.rest(Region::Upper, [0.0, 0.0, 0.0]), Err(NoRest::NotFinite));
        // Just outside the horizon the metric is Lorentzian though badly scaled (g_tt ≈ −5·10⁻⁸,
        // g_rr ≈ 2·10⁷): what stops an observer there is the collapsed lapse, not the signature.
        assert!(matches!(s.rest(Region::Upper, [0.0, 2.000_000_1, 0.0]), Err(NoRest::Collapsed { .. })));
        let degenerate = written(
            Coordinates::Cartesian,
            &[],
            &[(0, 0, "-1"), (1, 1, "1"), (2, 2, "1"), (2, 3, "1"), (3, 3, "1")],
            None,
        );
        assert_eq!(
            degenerate.rest(Region::Upper, [1.0, 0.0, 0.0]),
            Err(NoRest::NotLorentzian { negative: 1, zero: 1 })
        );
        let euclidean =
            written(Coordinates::Cartesian, &[], &[(0, 0, "1"), (1, 1, "1"), (2, 2, "1"), (3, 3, "1")], None);
        assert_eq!(euclidean.rest(Region::Upper, [1.0, 0.0, 0.0]), Err(NoRest::NotLorentzian { negative: 0, zero: 0 }));
        // Flat space in a frame rotating about z at ω = 0.5: beyond ρ = 2, ∂_t is spacelike, though
        // the slices' lapse is 1 everywhere.
        let rotating = written(
            Coordinates::Cartesian,
            &[("w", 0.5)],
            &[(0, 0, "-(1 - w^2*(x^2 + y^2))"), (0, 1, "-w*y"), (0, 2, "w*x"), (1, 1, "1"), (2, 2, "1"), (3, 3, "1")],
            None,
        );
        assert_eq!(rotating.rest(Region::Upper, [1.0, 0.0, 0.0]), Ok(()));
        assert!(matches!(rotating.rest(Region::Upper, [3.0, 0.0, 0.0]), Err(NoRest::TimeNotTimelike { .. })));
        assert!(!rotating.inside_horizon(&[0.0, 3.0, 0.0, 0.0]));
        // The static observer of Schwarzschild's chart measures lapse √(1 − 2M/r).
        assert!((s.observer_lapse(Region::Upper, [0.0, 0.0, 8.0]) - 0.75f64.sqrt()).abs() < 1e-9);
        let rn = ReissnerNordstrom::new(1.0, 0.6);
        let p = [2.0, -3.0, 1.0];
        let user_rn = spherical_reissner_nordstrom(1.0, 0.6);
        assert!((user_rn.observer_lapse(Region::Upper, p) - rn.observer_lapse(Region::Upper, p)).abs() < 1e-9);
    }

    #[test]
    fn symmetry_and_duplicates() {
        let s = spherical_schwarzschild(1.0);
        assert!(s.is_stationary() && s.is_axisymmetric());
        let t =
            written(Coordinates::Cartesian, &[], &[(0, 0, "-1 - 0*t"), (1, 1, "1"), (2, 2, "1"), (3, 3, "1")], None);
        assert!(!t.is_stationary() && !t.is_axisymmetric());
        let names = Names { variables: Coordinates::Cartesian.names(), constants: &[] };
        let one = || Expression::compile("1", names).unwrap();
        let twice = WrittenMetric::new(Coordinates::Cartesian, vec![(0, 1, one()), (1, 0, one())], None, 1.0);
        assert_eq!(twice, Err(ParameterError::new("", "g_tx is given twice")));
        assert!(WrittenMetric::new(Coordinates::Cartesian, vec![], None, 0.0).is_err());
    }
}
