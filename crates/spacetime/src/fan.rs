//! The standard geodesic workload: a pinhole camera's fan of rays around a Schwarzschild hole,
//! as used by `nullpath bench geodesics` and the criterion benchmarks. A benchmark's workload,
//! not physics: compiled only with the `bench-workload` feature, which the binary and this
//! crate's benchmarks turn on. It lives here, not beside `nullpath bench`, because both of them
//! time it and benchmarks cannot reach into a binary.

use crate::geodesic::plane::{trace_plane, trace_plane_in_time, PlaneStart};
use crate::geodesic::{HamiltonianTracer, RayTracer, State, TraceSettings, Visit};
use crate::metric::{Metric, OwnStepper, Region, Schwarzschild};
use crate::{Fate, Tetrad};

/// A square fan of `size × size` rays with vertical field of view `fov_deg`, from a static
/// camera at distance `distance` on the −z axis looking at the centre.
#[derive(Clone, Copy, Debug)]
pub struct Fan {
    pub size: u32,
    pub fov_deg: f64,
    pub distance: f64,
}

impl Fan {
    /// The benchmark fan of the spacetime-core issue: 512², 40°, r = 30 M.
    pub fn standard(mass: f64) -> Fan {
        Fan { size: 512, fov_deg: 40.0, distance: 30.0 * mass }
    }

    pub fn camera_position(&self) -> [f64; 3] {
        [0.0, 0.0, -self.distance]
    }

    pub fn rays(&self) -> u64 {
        u64::from(self.size) * u64::from(self.size)
    }

    /// Unit direction (camera frame aligned with the world axes) through the centre of pixel
    /// `index` (row-major).
    pub fn direction(&self, index: u64) -> [f64; 3] {
        let size = u64::from(self.size);
        let (i, j) = ((index % size) as f64, (index / size) as f64);
        let half = (0.5 * self.fov_deg.to_radians()).tan();
        let x = (2.0 * (i + 0.5) / self.size as f64 - 1.0) * half;
        let y = (1.0 - 2.0 * (j + 0.5) / self.size as f64) * half;
        let norm = (x * x + y * y + 1.0).sqrt();
        [x / norm, y / norm, 1.0 / norm]
    }
}

/// Outcome of one fan ray: its fate and the integrator steps it took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FanRay {
    pub fate: Fate,
    pub steps: u32,
}

/// Traces fan ray `index` in its own plane (the fast path for spherical spacetimes).
pub fn trace_in_plane(metric: &Schwarzschild, fan: &Fan, index: u64, settings: &TraceSettings) -> FanRay {
    let dir = fan.direction(index);
    match PlaneStart::from_observer(metric, Region::Upper, fan.camera_position(), dir) {
        Some(start) => {
            let t = trace_plane(metric, start, settings, |_| Visit::Continue);
            FanRay { fate: t.fate, steps: t.steps }
        }
        None => FanRay { fate: Fate::Captured, steps: 0 },
    }
}

/// [`trace_in_plane`] carrying the chart's time from 0 at the camera (what a moving scene costs).
pub fn trace_in_plane_in_time(metric: &Schwarzschild, fan: &Fan, index: u64, settings: &TraceSettings) -> FanRay {
    let dir = fan.direction(index);
    match PlaneStart::from_observer(metric, Region::Upper, fan.camera_position(), dir) {
        Some(start) => {
            let t = trace_plane_in_time(metric, start, 0.0, settings, |_| Visit::Continue);
            FanRay { fate: t.fate, steps: t.steps }
        }
        None => FanRay { fate: Fate::Captured, steps: 0 },
    }
}

/// Traces fan ray `index` with the general 4-D Hamiltonian tracer.
pub fn trace_hamiltonian<M: Metric>(metric: &M, fan: &Fan, index: u64, settings: &TraceSettings) -> FanRay {
    match camera_ray(metric, fan, index) {
        Some(start) => run(HamiltonianTracer::new(metric, start, *settings)),
        None => FanRay { fate: Fate::Captured, steps: 0 },
    }
}

/// Traces fan ray `index` with the stepper the metric provides (Kerr's Mino-time stepper).
pub fn trace_own<M: OwnStepper>(metric: &M, fan: &Fan, index: u64, settings: &TraceSettings) -> FanRay {
    match camera_ray(metric, fan, index) {
        Some(start) => run(metric.ray_tracer(start, *settings)),
        None => FanRay { fate: Fate::Captured, steps: 0 },
    }
}

/// [`trace_own`] carrying the chart's time from 0 at the camera (what a moving scene costs).
pub fn trace_own_in_time<M: OwnStepper>(metric: &M, fan: &Fan, index: u64, settings: &TraceSettings) -> FanRay {
    match camera_ray(metric, fan, index) {
        Some(start) => run(metric.ray_tracer(start, *settings).carrying_time()),
        None => FanRay { fate: Fate::Captured, steps: 0 },
    }
}

/// The backward ray of pixel `index` from the static camera at chart time 0; `None` where no
/// static observer exists.
fn camera_ray<M: Metric>(metric: &M, fan: &Fan, index: u64) -> Option<State> {
    let [a, b, c] = fan.camera_position();
    let x = [0.0, a, b, c];
    let frame = Tetrad::local_observer(metric, &x).ok()?;
    let p = frame.backward_momentum(&metric.metric(&x), fan.direction(index), 1.0);
    Some(State { x, p })
}

fn run(tracer: impl RayTracer) -> FanRay {
    let t = tracer.run(|_| Visit::Continue);
    FanRay { fate: t.fate, steps: t.steps }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_ray_is_captured_and_corner_ray_escapes() {
        let fan = Fan { size: 64, ..Fan::standard(1.0) };
        let settings = TraceSettings::default();
        let hole = Schwarzschild::new(1.0);
        let centre = 32 * 64 + 32;
        assert_eq!(trace_in_plane(&hole, &fan, centre, &settings).fate, Fate::Captured);
        assert!(matches!(trace_in_plane(&hole, &fan, 0, &settings).fate, Fate::Escaped { .. }));
        assert_eq!(trace_hamiltonian(&hole, &fan, centre, &settings).fate, Fate::Captured);
    }

    #[test]
    fn directions_span_the_field_of_view() {
        let fan = Fan { size: 2, fov_deg: 90.0, distance: 10.0 };
        let d = fan.direction(0);
        // Pixel centres at ±½ of tan 45°.
        assert!((d[0] / d[2] + 0.5).abs() < 1e-15 && (d[1] / d[2] - 0.5).abs() < 1e-15);
    }
}
