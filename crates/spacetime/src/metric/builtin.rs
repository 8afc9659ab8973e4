//! The closed set of spacetimes of scene files and the command line — the built-in ones and a
//! metric written in a scene file — validated on construction. Each built-in metric's file holds
//! its validating constructor and its [`MetricDescriptor`]; this enum is what the renderer
//! dispatches on, once per ray.

use super::capabilities::{Capabilities, Tracers};
use super::descriptor::{chosen_values, MetricDescriptor, Parameter, ParameterError};
use super::{
    Ellis, Kerr, KerrNewman, Metric, Minkowski, Region, ReissnerNordstrom, Schwarzschild, UserMetric, Wormhole,
    WrittenMetric,
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
    /// The Morris–Thorne wormhole of *Interstellar* ([`Dneg`](super::Dneg)'s shape).
    Wormhole(Wormhole),
    /// A metric written as expressions in a scene file.
    Written(UserMetric<WrittenMetric>),
}

/// The `type` of a metric written in a scene file, which has no descriptor: its parameters are
/// folded into its compiled expressions.
pub const WRITTEN_NAME: &str = "metric";

impl Spacetime {
    /// The descriptor of this spacetime's metric (its name and parameters); `None` for a metric
    /// written in a scene file. The one place that pairs the variants with the registry.
    pub fn descriptor(&self) -> Option<&'static MetricDescriptor> {
        match self {
            Spacetime::Minkowski(_) => Some(&super::minkowski::MINKOWSKI),
            Spacetime::Schwarzschild(_) => Some(&super::schwarzschild::SCHWARZSCHILD),
            Spacetime::Kerr(_) => Some(&super::kerr::KERR),
            Spacetime::Ellis(_) => Some(&super::ellis::ELLIS),
            Spacetime::ReissnerNordstrom(_) => Some(&super::reissner_nordstrom::REISSNER_NORDSTROM),
            Spacetime::KerrNewman(_) => Some(&super::kerr_newman::KERR_NEWMAN),
            Spacetime::Wormhole(_) => Some(&super::morris_thorne::WORMHOLE),
            Spacetime::Written(_) => None,
        }
    }

    /// Stable lower-case name, as in scene files.
    pub fn name(&self) -> &'static str {
        self.descriptor().map_or(WRITTEN_NAME, |d| d.name)
    }

    /// The parameters with their values and the ranges a user interface offers
    /// ([`MetricDescriptor::sliders`]); none for a written metric.
    pub fn parameters(&self) -> Vec<Parameter> {
        self.descriptor().and_then(|d| d.sliders(self)).unwrap_or_default()
    }

    /// This spacetime with the named parameters set to new values
    /// ([`MetricDescriptor::with_parameters`]); a written metric takes none and stays itself.
    pub fn with_parameters(&self, values: &[(&str, f64)]) -> Result<Spacetime, ParameterError> {
        match self.descriptor() {
            Some(d) => d.with_parameters(self, values),
            None => chosen_values(self.name(), &[], values).map(|_| self.clone()),
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

    #[test]
    fn parameters_follow_the_spacetime() {
        let kerr = Spacetime::kerr(0.5, 0.2).expect("valid");
        let names: Vec<&str> = kerr.parameters().iter().map(|p| p.name).collect();
        assert_eq!(names, ["mass", "spin"]);
        assert_eq!((kerr.parameters()[1].min, kerr.parameters()[1].max), (-1.5, 1.5));
        assert!(Spacetime::Minkowski(Minkowski).parameters().is_empty());
        let hole = Spacetime::schwarzschild(0.0).expect("valid");
        assert_eq!(hole.parameters()[0].max, 1.0, "a massless hole can be given a mass");
    }

    /// Every spacetime rebuilt from its own values is itself.
    #[test]
    fn unchanged_values_rebuild_the_same_spacetime() {
        for s in [
            Spacetime::Minkowski(Minkowski),
            Spacetime::schwarzschild(0.3).expect("valid"),
            Spacetime::kerr(1.0, -0.7).expect("valid"),
            Spacetime::ellis(2.0).expect("valid"),
            Spacetime::reissner_nordstrom(1.0, 0.4).expect("valid"),
            Spacetime::kerr_newman(1.0, 0.6, -0.5).expect("valid"),
            Spacetime::wormhole(1.0, 0.01, 0.05).expect("valid"),
        ] {
            let values: Vec<(&str, f64)> = s.parameters().iter().map(|p| (p.name, p.value)).collect();
            assert_eq!(s.with_parameters(&values), Ok(s.clone()));
            assert_eq!(s.with_parameters(&[]), Ok(s));
        }
    }

    #[test]
    fn new_values_are_checked() {
        let hole = Spacetime::schwarzschild(0.3).expect("valid");
        assert_eq!(hole.with_parameters(&[("mass", 0.6)]), Spacetime::schwarzschild(0.6));
        assert!(hole.with_parameters(&[("mass", -0.1)]).is_err());
        assert!(hole.with_parameters(&[("mass", f64::NAN)]).is_err());
        assert!(hole.with_parameters(&[("mass", 1.5)]).is_err(), "beyond the range");
        let unknown = hole.with_parameters(&[("spin", 0.1)]).expect_err("unknown").message;
        assert!(unknown.contains("no parameter \"spin\" (it has: mass)"), "{unknown}");
        let kerr = Spacetime::kerr(0.5, 0.0).expect("valid");
        assert!(kerr.with_parameters(&[("spin", 0.9)]).is_err(), "|spin| > mass");
        assert_eq!(kerr.with_parameters(&[("spin", 0.4), ("mass", 1.2)]), Spacetime::kerr(1.2, 0.4));
    }
}
