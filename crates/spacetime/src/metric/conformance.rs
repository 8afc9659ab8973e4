//! Checks every metric must pass: the shared conformance suite (`tests/conformance.rs` runs it
//! on every built-in spacetime), public so that a user's own [`Metric`] can be checked the same
//! way. Each check panics with a message at the first failure, as a test does.

use super::capabilities::{Capabilities, Forwards, LocalFrame, NoRest, OwnStepper, Tracers};
use super::spin_twin::SpinTwin;
use super::{Metric, Region};
use crate::geodesic::plane::PlaneMetric;
use crate::observer::Tetrad;
use crate::tensor::{contract, quadratic, Vector4};

/// `g · g⁻¹ = I` and the derivatives of `g^{μν}` agree with central finite differences.
pub fn check_metric(m: &dyn Metric, x: &Vector4) {
    let g = m.metric(x);
    let (ginv, d) = m.inverse_metric_derivatives(x);
    let ginv_plain = m.inverse_metric(x);
    for i in 0..4 {
        for j in 0..4 {
            let id: f64 = (0..4).map(|k| g[i][k] * ginv[k][j]).sum();
            let expect = if i == j { 1.0 } else { 0.0 };
            assert!((id - expect).abs() < 1e-12, "g·g⁻¹ at {x:?}: [{i}][{j}] = {id}");
            assert!((ginv[i][j] - ginv_plain[i][j]).abs() < 1e-12 * (1.0 + ginv[i][j].abs()));
            assert!((g[i][j] - g[j][i]).abs() < 1e-14, "metric symmetric");
        }
    }
    let h = 1e-5 * m.length_scale().max(crate::tensor::norm3(&crate::tensor::spatial(x)));
    for a in 0..4 {
        let mut xp = *x;
        let mut xm = *x;
        xp[a] += h;
        xm[a] -= h;
        let (gp, _) = m.inverse_metric_derivatives(&xp);
        let (gm, _) = m.inverse_metric_derivatives(&xm);
        for i in 0..4 {
            for j in 0..4 {
                let fd = (gp[i][j] - gm[i][j]) / (2.0 * h);
                let scale = 1.0 + fd.abs() + d[a][i][j].abs();
                assert!((fd - d[a][i][j]).abs() < 1e-6 * scale, "∂_{a} g^{i}{j}: fd {fd} vs {}", d[a][i][j]);
            }
        }
    }
    // The RHS default and any override agree.
    let p = [-1.0, 0.3, -0.2, 0.5];
    let (dx, dp) = m.geodesic_rhs(x, &p);
    let dx_ref = contract(&ginv, &p);
    for k in 0..4 {
        assert!((dx[k] - dx_ref[k]).abs() < 1e-12 * (1.0 + dx_ref[k].abs()));
        let dp_ref = -0.5 * quadratic(&d[k], &p, &p);
        assert!((dp[k] - dp_ref).abs() < 1e-11 * (1.0 + dp_ref.abs()), "dp_{k}: {} vs {dp_ref}", dp[k]);
    }
}

/// Which tracer a metric chose.
struct Chosen;

impl Tracers for Chosen {
    type Output = &'static str;
    fn straight(self) -> &'static str {
        "straight"
    }
    fn in_plane<M: PlaneMetric>(self, _metric: &M) -> &'static str {
        "in-plane"
    }
    fn four_d<M: Metric>(self, _metric: &M) -> &'static str {
        "4-D"
    }
    fn own_stepper<M: OwnStepper>(self, _metric: &M) -> &'static str {
        "own 4-D"
    }
}

/// The name of the tracer `m` chooses: "straight", "in-plane", "4-D" or "own 4-D".
pub fn chosen_tracer<M: Capabilities>(m: &M) -> &'static str {
    m.choose_tracer(Chosen)
}

/// Runs [`check_plane_metric`] at world radius `rho` where the metric chooses the in-plane tracer.
struct PlaneCheck {
    rho: f64,
}

impl Tracers for PlaneCheck {
    type Output = ();
    fn straight(self) {}
    fn in_plane<M: PlaneMetric>(self, metric: &M) {
        check_plane_metric(metric, self.rho);
    }
    fn four_d<M: Metric>(self, _metric: &M) {}
    fn own_stepper<M: OwnStepper>(self, _metric: &M) {}
}

/// The reduction of a static spherically symmetric metric to a ray's plane is consistent at
/// world radius `rho` (where a static observer exists): the radius and its inverse agree, the
/// Binet equation `u'' = −u + G(u)` is the derivative of its first integral
/// (`u'' = ½ d(u'²)/du`, central differences), and a ray leaving the static observer in any
/// direction, as [`PlaneStart::from_observer`](crate::geodesic::plane::PlaneStart) starts it,
/// is null: on the first integral and with zero plane Hamiltonian.
pub fn check_plane_metric<M: PlaneMetric>(m: &M, rho: f64) {
    let Some(u) = m.u_of_world_radius(rho) else { return };
    assert!((m.world_radius(u) - rho).abs() < 1e-12 * rho, "world radius at u = {u}: {}", m.world_radius(u));
    let h = 1e-6 * u;
    let fd = (m.world_radius(u + h) - m.world_radius(u - h)) / (2.0 * h);
    let slope = m.world_radius_slope(u);
    assert!((fd - slope).abs() < 1e-6 * slope.abs(), "dρ/du at u = {u}: {slope} vs {fd}");
    for t in [0.3, 1.1, std::f64::consts::FRAC_PI_2, 2.4f64] {
        let (d_r, d_phi) = (t.cos(), t.sin());
        let du = -u * d_r / (m.radial_stretch(u) * d_phi);
        let b = m.impact_factor(u) * d_phi;
        let inv_b2 = 1.0 / (b * b);
        let first = m.slope_squared(u, inv_b2);
        assert!((du * du - first).abs() < 1e-10 * (du * du + u * u), "u'² at u = {u}, b = {b}: {} vs {first}", du * du);
        let ham = m.plane_hamiltonian(u, du, b);
        assert!(ham.abs() < 1e-10 * (1.0 + b * b * (du * du + u * u)), "plane H at u = {u}, b = {b}: {ham}");
        let fd = (m.slope_squared(u + h, inv_b2) - m.slope_squared(u - h, inv_b2)) / (4.0 * h);
        let binet = -u + m.binet_source(u, inv_b2);
        assert!((fd - binet).abs() < 1e-6 * (u + binet.abs()), "u'' at u = {u}, b = {b}: {binet} vs {fd}");
    }
}

/// The answers of [`Capabilities`] agree with the metric at world point `p` of `region`: outside
/// horizons the static observer exists exactly where [`Capabilities::rest`] says one can stay at
/// rest, its
/// lapse is `√(−g_tt)` there, a radially scaled frame stretches radial lengths by `1/κ` as the
/// static observer measures them, flat space has lapse 1 and straight rays, and a
/// time-symmetric spacetime bounds impact parameters (by at least the radius: light slows near
/// mass and bends towards it). A spin twin carries light rays across: the Hamiltonian is the
/// same in both charts, and a future-directed ray of the hole is past-directed in the twin's.
pub fn check_capabilities<M: Capabilities>(m: &M, region: Region, p: [f64; 3]) {
    let chart = m.world_to_chart(region, p, 0.0);
    let rest = m.rest(region, p);
    let stat = chart.map(|x| Tetrad::static_observer(m, &x));
    // Inside a horizon nothing counts as at rest, though a static observer may exist again
    // (inside Kerr's inner horizon, or a written metric's where its lapse has collapsed): it
    // would see nothing but the hole.
    let horizon = matches!(rest, Err(NoRest::InsideHorizon { .. } | NoRest::Collapsed { .. }));
    let exists = matches!(stat, Some(Ok(_)));
    assert!(horizon || rest.is_ok() == exists, "rest at {p:?}: {rest:?} vs static observer {stat:?}");
    if let (Ok(()), Some(x)) = (rest, chart) {
        let lapse = (-m.metric(&x)[0][0]).sqrt();
        let said = m.observer_lapse(region, p);
        assert!((said - lapse).abs() < 1e-12 * lapse.max(1.0), "lapse at {p:?}: {said} vs √(−g_tt) = {lapse}");
        if let LocalFrame::Radial { kappa } = m.local_frame(region, p) {
            // A radial step's proper length, as the static observer measures it, is 1/κ.
            let r = crate::tensor::norm3(&p);
            let h = 1e-6 * r;
            let q = p.map(|c| c * (1.0 + h / r));
            let y = m.world_to_chart(region, q, 0.0).unwrap_or(x);
            let dx: Vector4 = std::array::from_fn(|k| y[k] - x[k]);
            let g = m.metric(&x);
            let u = [1.0 / lapse, 0.0, 0.0, 0.0];
            let along = quadratic(&g, &dx, &u);
            let proper = (quadratic(&g, &dx, &dx) + along * along).sqrt() / h;
            assert!((proper * kappa - 1.0).abs() < 1e-5, "κ at {p:?}: {kappa}, proper/world length {proper}");
        }
    }
    if rest.is_ok() {
        m.choose_tracer(PlaneCheck { rho: crate::tensor::norm3(&p) });
    }
    if m.is_flat() {
        assert_eq!(m.observer_lapse(region, p), 1.0, "flat lapse");
        assert_eq!(chosen_tracer(m), "straight", "flat rays are straight");
    }
    if let (Forwards::SpinTwin(twin), Some(x)) = (m.forwards(), chart) {
        if !m.inside_horizon(&x) {
            check_spin_twin(m, &twin, &x);
        }
    }
    if m.forwards() == Forwards::Reversed {
        let r = crate::tensor::norm3(&p);
        let b = m.impact_bound(r);
        assert!(b.is_some_and(|b| b >= r), "impact bound for radius {r}: {b:?}");
    }
    if m.throat().is_none() {
        assert_eq!(region, Region::Upper, "one region");
    }
}

/// Light carried to the twin's chart keeps its Hamiltonian (zero), and a ray leaving the local
/// observer forwards in time runs backwards in the twin's.
fn check_spin_twin<M: Metric>(m: &M, twin: &SpinTwin, x: &Vector4) {
    let Ok(frame) = Tetrad::local_observer(m, x) else { return };
    let twin_metric = twin.twin();
    for n in [[1.0, 0.0, 0.0], [0.0, -0.6, 0.8], [-0.48, 0.64, -0.6]] {
        // p = E(e₀ + n e), future-directed: minus the backward ray along −n.
        let p = frame.backward_momentum(&m.metric(x), n.map(|c| -c), 1.0).map(|c| -c);
        let (y, q) = twin.to_twin(x, &p);
        let scale = p.iter().map(|c| c * c).sum::<f64>();
        let h_twin = twin_metric.hamiltonian(&y, &q);
        assert!(h_twin.abs() < 1e-10 * scale, "light at {x:?} along {n:?}: twin's H = {h_twin}");
        let (dt, dt_twin) = (m.geodesic_rhs(x, &p).0[0], twin_metric.geodesic_rhs(&y, &q).0[0]);
        assert!(dt > 0.0 && dt_twin < 0.0, "time orientation at {x:?} along {n:?}: dt/dλ {dt}, twin {dt_twin}");
    }
}
