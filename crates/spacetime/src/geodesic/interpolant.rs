//! One step of either integrator, with the dense output the renderer needs to place a hit
//! anywhere inside the step.

use super::{dopri5, rk4, Stepping};

/// An accepted or attempted step `y0 → y1` of size `h`, with the state anywhere inside it.
#[derive(Clone, Copy, Debug)]
pub enum Interpolant<const N: usize> {
    /// Dormand–Prince's own 4th-order continuous extension.
    Dopri(dopri5::Attempt<N>),
    /// RK4 with cubic Hermite interpolation from the end values and derivatives.
    Hermite { y0: [f64; N], d0: [f64; N], y1: [f64; N], d1: [f64; N], h: f64 },
}

impl<const N: usize> Interpolant<N> {
    /// Takes one step of `integrator` of size `h` from `y0` (with `d0 = f(t0, y0)`); returns the
    /// step and, for the adaptive integrator, its local error estimate.
    #[inline]
    pub fn step(
        stepping: Stepping,
        f: &impl Fn(f64, &[f64; N]) -> [f64; N],
        t0: f64,
        y0: &[f64; N],
        d0: &[f64; N],
        h: f64,
    ) -> (Self, Option<[f64; N]>) {
        match stepping {
            Stepping::Adaptive { .. } => {
                let a = dopri5::attempt(f, t0, y0, d0, h);
                (Interpolant::Dopri(a), Some(a.error))
            }
            Stepping::Rk4 { .. } => {
                let y1 = rk4::step(f, t0, y0, d0, h);
                let d1 = f(t0 + h, &y1);
                (Interpolant::Hermite { y0: *y0, d0: *d0, y1, d1, h }, None)
            }
        }
    }

    pub fn y0(&self) -> [f64; N] {
        match self {
            Interpolant::Dopri(a) => a.y0,
            Interpolant::Hermite { y0, .. } => *y0,
        }
    }

    pub fn y1(&self) -> [f64; N] {
        match self {
            Interpolant::Dopri(a) => a.y1,
            Interpolant::Hermite { y1, .. } => *y1,
        }
    }

    pub fn h(&self) -> f64 {
        match self {
            Interpolant::Dopri(a) => a.h,
            Interpolant::Hermite { h, .. } => *h,
        }
    }

    /// `f` at the end of the step: the next step's first stage.
    pub fn end_derivative(&self) -> [f64; N] {
        match self {
            Interpolant::Dopri(a) => a.end_derivative(),
            Interpolant::Hermite { d1, .. } => *d1,
        }
    }

    /// State at fraction `θ ∈ [0, 1]` of the step.
    #[inline]
    pub fn dense(&self, theta: f64) -> [f64; N] {
        match self {
            Interpolant::Dopri(a) => a.dense(theta),
            Interpolant::Hermite { y0, d0, y1, d1, h } => rk4::hermite(y0, d0, y1, d1, *h, theta),
        }
    }

    /// The first `M` components of [`Interpolant::dense`]: placing a point needs only the
    /// position part.
    #[inline]
    pub fn dense_head<const M: usize>(&self, theta: f64) -> [f64; M] {
        match self {
            Interpolant::Dopri(a) => std::array::from_fn(|i| a.dense_component(theta, i)),
            Interpolant::Hermite { y0, d0, y1, d1, h } => rk4::hermite_head(y0, d0, y1, d1, *h, theta),
        }
    }
}
