//! The closed set of spacetimes of scene files and the command line — the built-in ones and a
//! metric written in a scene file — validated on construction.

use super::capabilities::{Capabilities, Tracers};
use super::{
    Dneg, Ellis, Kerr, KerrNewman, Metric, Minkowski, MorrisThorne, Region, ReissnerNordstrom, Schwarzschild,
    UserMetric, Wormhole, WrittenMetric,
};

/// A spacetime of a scene. Cloning is cheap: a written metric shares its compiled expressions.
#[derive(Clone, Debug, PartialEq)]
pub enum Spacetime {
    Minkowski(Minkowski),
    Schwarzschild(Schwarzschild),
    Kerr(Kerr),
    Ellis(Ellis),
    ReissnerNordstrom(ReissnerNordstrom),
    KerrNewman(KerrNewman),
    /// The Morris–Thorne wormhole of *Interstellar* ([`Dneg`]'s shape).
    Wormhole(Wormhole),
    /// A metric written as expressions in a scene file.
    Written(UserMetric<WrittenMetric>),
}

/// A parameter outside the spacetime's domain.
#[derive(Clone, Debug, PartialEq)]
pub struct ParameterError(pub String);

impl std::fmt::Display for ParameterError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ParameterError {}

fn finite_non_negative(name: &str, v: f64) -> Result<f64, ParameterError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(ParameterError(format!("{name} must be a finite number ≥ 0, got {v}")))
    }
}

/// The narrowest lensing width of the *Interstellar* wormhole, as a fraction of its throat.
pub const MIN_RELATIVE_LENSING_WIDTH: f64 = 1e-9;

impl Spacetime {
    pub fn schwarzschild(mass: f64) -> Result<Self, ParameterError> {
        Ok(Spacetime::Schwarzschild(Schwarzschild::new(finite_non_negative("mass", mass)?)))
    }

    /// Kerr with `|spin| ≤ mass`; spin along +z, positive for counter-clockwise rotation seen
    /// from +z.
    pub fn kerr(mass: f64, spin: f64) -> Result<Self, ParameterError> {
        let mass = finite_non_negative("mass", mass)?;
        if !spin.is_finite() || spin.abs() > mass {
            return Err(ParameterError(format!("spin must satisfy |spin| ≤ mass = {mass}, got {spin}")));
        }
        Ok(Spacetime::Kerr(Kerr::new(mass, spin)))
    }

    /// Reissner–Nordström with `|charge| ≤ mass`.
    pub fn reissner_nordstrom(mass: f64, charge: f64) -> Result<Self, ParameterError> {
        let mass = finite_non_negative("mass", mass)?;
        if !charge.is_finite() || charge.abs() > mass {
            return Err(ParameterError(format!("charge must satisfy |charge| ≤ mass = {mass}, got {charge}")));
        }
        Ok(Spacetime::ReissnerNordstrom(ReissnerNordstrom::new(mass, charge)))
    }

    /// Kerr–Newman with `spin² + charge² ≤ mass²`; spin along +z as [`Spacetime::kerr`]'s.
    pub fn kerr_newman(mass: f64, spin: f64, charge: f64) -> Result<Self, ParameterError> {
        let mass = finite_non_negative("mass", mass)?;
        if !(spin.is_finite() && charge.is_finite() && spin * spin + charge * charge <= mass * mass) {
            return Err(ParameterError(format!(
                "spin and charge must satisfy spin² + charge² ≤ mass² = {}, got {spin}² + {charge}²",
                mass * mass
            )));
        }
        Ok(Spacetime::KerrNewman(KerrNewman::new(mass, spin, charge)))
    }

    pub fn ellis(throat: f64) -> Result<Self, ParameterError> {
        if !(throat.is_finite() && throat > 0.0) {
            return Err(ParameterError(format!("throat radius must be a finite number > 0, got {throat}")));
        }
        Ok(Spacetime::Ellis(Ellis::new(throat)))
    }

    /// The wormhole of *Interstellar* (James et al. 2015): throat radius `throat > 0`, interior
    /// length `length ≥ 0`, lensing width `lensing_width > 0`.
    pub fn wormhole(throat: f64, length: f64, lensing_width: f64) -> Result<Self, ParameterError> {
        if !(throat.is_finite() && throat > 0.0) {
            return Err(ParameterError(format!("throat radius must be a finite number > 0, got {throat}")));
        }
        let length = finite_non_negative("length", length)?;
        // The shape function's `ln(1 + x²)`, with `x ∝ ℓ/𝒲`, overflows for widths near 10⁻¹⁵⁰ of
        // the distances a ray covers; long before, a narrower lensing region is a sharp edge that
        // rays cannot tell from one of 10⁻⁹ of the throat.
        let narrowest = MIN_RELATIVE_LENSING_WIDTH * throat;
        if !(lensing_width.is_finite() && lensing_width >= narrowest) {
            return Err(ParameterError(format!(
                "lensing width must be a finite number ≥ {narrowest:e} ({MIN_RELATIVE_LENSING_WIDTH:e} of the throat \
                 radius), got {lensing_width}: narrower is an edge no ray resolves in double precision"
            )));
        }
        Ok(Spacetime::Wormhole(MorrisThorne::new(Dneg::new(throat, length, lensing_width))))
    }

    /// Stable lower-case name, as in scene files.
    pub fn name(&self) -> &'static str {
        match self {
            Spacetime::Minkowski(_) => "minkowski",
            Spacetime::Schwarzschild(_) => "schwarzschild",
            Spacetime::Kerr(_) => "kerr",
            Spacetime::Ellis(_) => "ellis",
            Spacetime::ReissnerNordstrom(_) => "reissner-nordstrom",
            Spacetime::KerrNewman(_) => "kerr-newman",
            Spacetime::Wormhole(_) => "wormhole",
            Spacetime::Written(_) => "metric",
        }
    }

    /// The curvature length scale (mass or throat radius; 1 for flat space).
    pub fn length_scale(&self) -> f64 {
        self.metric().length_scale()
    }

    /// The metric, for code that needs no more than the [`Metric`] trait.
    pub fn metric(&self) -> &dyn Metric {
        self.capabilities()
    }

    /// What the spacetime answers a renderer ([`Capabilities`]): the one place that lists the
    /// metrics for it.
    pub fn capabilities(&self) -> &dyn Capabilities {
        match self {
            Spacetime::Minkowski(m) => m,
            Spacetime::Schwarzschild(m) => m,
            Spacetime::Kerr(m) => m,
            Spacetime::Ellis(m) => m,
            Spacetime::ReissnerNordstrom(m) => m,
            Spacetime::KerrNewman(m) => m,
            Spacetime::Wormhole(m) => m,
            Spacetime::Written(m) => m,
        }
    }

    /// Calls the tracer of `tracers` that fits the metric ([`Capabilities::choose_tracer`]),
    /// generic over the metric: dispatch once per ray, none per step.
    pub fn choose_tracer<T: Tracers>(&self, tracers: T) -> T::Output {
        match self {
            Spacetime::Minkowski(m) => m.choose_tracer(tracers),
            Spacetime::Schwarzschild(m) => m.choose_tracer(tracers),
            Spacetime::Kerr(m) => m.choose_tracer(tracers),
            Spacetime::Ellis(m) => m.choose_tracer(tracers),
            Spacetime::ReissnerNordstrom(m) => m.choose_tracer(tracers),
            Spacetime::KerrNewman(m) => m.choose_tracer(tracers),
            Spacetime::Wormhole(m) => m.choose_tracer(tracers),
            Spacetime::Written(m) => m.choose_tracer(tracers),
        }
    }

    /// The asymptotic regions: a wormhole's two, else the one.
    pub fn regions(&self) -> &'static [Region] {
        match self.capabilities().throat() {
            Some(_) => &[Region::Upper, Region::Lower],
            None => &[Region::Upper],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_are_validated() {
        assert!(Spacetime::schwarzschild(-1.0).is_err());
        assert!(Spacetime::schwarzschild(f64::NAN).is_err());
        assert!(Spacetime::kerr(1.0, 1.0).is_ok());
        assert!(Spacetime::kerr(1.0, -1.01).is_err());
        assert!(Spacetime::ellis(0.0).is_err());
        assert!(Spacetime::reissner_nordstrom(1.0, -1.0).is_ok());
        assert!(Spacetime::reissner_nordstrom(1.0, 1.01).is_err());
        assert!(Spacetime::kerr_newman(1.0, 0.6, -0.8).is_ok());
        assert!(Spacetime::kerr_newman(1.0, 0.6, 0.81).is_err());
        assert!(Spacetime::kerr_newman(1.0, f64::NAN, 0.0).is_err());
        assert_eq!(Spacetime::ellis(2.0).unwrap().name(), "ellis");
        assert!(Spacetime::wormhole(1.0, 0.0, 0.05).is_ok());
        assert!(Spacetime::wormhole(0.0, 0.01, 0.05).is_err());
        assert!(Spacetime::wormhole(1.0, -0.01, 0.05).is_err());
        assert!(Spacetime::wormhole(1.0, 0.01, 0.0).is_err());
        assert!(Spacetime::wormhole(1.0, f64::INFINITY, 0.05).is_err());
    }
}
