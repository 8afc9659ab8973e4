//! The parameters of each built-in spacetime by name, as a user interface offers them (the
//! preview's sliders): each with its value and a range set by the spacetime's length scale, and
//! the spacetime rebuilt from new values by its validating constructor, so that a changed value
//! can never make a metric a scene file could not.

use super::{Dneg, ParameterError, Spacetime};

/// A parameter of a spacetime: its value and the range (inclusive) a user may move it over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parameter {
    pub name: &'static str,
    pub value: f64,
    pub min: f64,
    pub max: f64,
}

/// The kinds of range a parameter takes, relative to the largest value offered.
#[derive(Clone, Copy)]
enum Span {
    /// `[0, top]`: a mass or a length that may vanish.
    NonNegative,
    /// `[10⁻³ top, top]`: a length that must stay positive (a throat radius).
    Positive,
    /// `[−top, top]`: a spin or a charge.
    Signed,
}

/// Rebuilds a spacetime (given the one it replaces) from its parameters' values, in the order [`family`] lists them.
type Rebuild = fn(&Spacetime, &[f64]) -> Result<Spacetime, ParameterError>;

/// The spacetime's parameters (name, value, kind of range) and the constructor that takes them
/// back: the one place that lists them per spacetime.
fn family(spacetime: &Spacetime) -> (Vec<(&'static str, f64, Span)>, Rebuild) {
    use Span::{NonNegative, Positive, Signed};
    match spacetime {
        Spacetime::Minkowski(_) => (Vec::new(), |_, _| Ok(Spacetime::Minkowski(super::Minkowski))),
        Spacetime::Schwarzschild(s) => (vec![("mass", s.mass, NonNegative)], |_, v| Spacetime::schwarzschild(v[0])),
        Spacetime::Kerr(k) => {
            (vec![("mass", k.mass, NonNegative), ("spin", k.spin, Signed)], |_, v| Spacetime::kerr(v[0], v[1]))
        }
        Spacetime::Ellis(e) => (vec![("throat", e.throat, Positive)], |_, v| Spacetime::ellis(v[0])),
        Spacetime::ReissnerNordstrom(h) => {
            (vec![("mass", h.mass, NonNegative), ("charge", h.charge, Signed)], |_, v| {
                Spacetime::reissner_nordstrom(v[0], v[1])
            })
        }
        Spacetime::KerrNewman(h) => {
            (vec![("mass", h.mass, NonNegative), ("spin", h.spin, Signed), ("charge", h.charge, Signed)], |_, v| {
                Spacetime::kerr_newman(v[0], v[1], v[2])
            })
        }
        Spacetime::Wormhole(w) => {
            let Dneg { throat, length, lensing_width } = w.shape;
            let listed = vec![
                ("throat", throat, Positive),
                ("length", length, NonNegative),
                ("lensing_width", lensing_width, Positive),
            ];
            (listed, |_, v| Spacetime::wormhole(v[0], v[1], v[2]))
        }
        // A written metric's parameters are folded into its compiled expressions: none to move.
        Spacetime::Written(_) => (Vec::new(), |s, _| Ok(s.clone())),
    }
}

impl Span {
    fn range(self, top: f64) -> (f64, f64) {
        match self {
            Span::NonNegative => (0.0, top),
            Span::Positive => (1e-3 * top, top),
            Span::Signed => (-top, top),
        }
    }
}

impl Spacetime {
    /// The parameters with their values, each ranging up to three times the length scale (and at
    /// least 1, so that a hole of mass 0 can still be given one).
    pub fn parameters(&self) -> Vec<Parameter> {
        let top = (3.0 * self.length_scale()).max(1.0);
        family(self)
            .0
            .into_iter()
            .map(|(name, value, span)| {
                let (min, max) = span.range(top);
                Parameter { name, value, min, max }
            })
            .collect()
    }

    /// This spacetime with the named parameters set to new values (the others keep theirs):
    /// every name must be one of [`Spacetime::parameters`], every value finite and in its range,
    /// and the result valid for the spacetime's constructor.
    pub fn with_parameters(&self, values: &[(&str, f64)]) -> Result<Spacetime, ParameterError> {
        let known = self.parameters();
        let mut chosen: Vec<f64> = known.iter().map(|p| p.value).collect();
        for &(name, value) in values {
            let Some(i) = known.iter().position(|p| p.name == name) else {
                let names: Vec<&str> = known.iter().map(|p| p.name).collect();
                let names = if names.is_empty() { "none".to_string() } else { names.join(", ") };
                return Err(ParameterError(format!(
                    "the {} spacetime has no parameter \"{name}\" (it has: {names})",
                    self.name()
                )));
            };
            let p = known[i];
            if !(value.is_finite() && value >= p.min && value <= p.max) {
                return Err(ParameterError(format!(
                    "{name} must be a number from {} to {}, got {value}",
                    p.min, p.max
                )));
            }
            chosen[i] = value;
        }
        family(self).1(self, &chosen)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_follow_the_spacetime() {
        let kerr = Spacetime::kerr(0.5, 0.2).expect("valid");
        let names: Vec<&str> = kerr.parameters().iter().map(|p| p.name).collect();
        assert_eq!(names, ["mass", "spin"]);
        assert_eq!((kerr.parameters()[1].min, kerr.parameters()[1].max), (-1.5, 1.5));
        assert!(Spacetime::Minkowski(super::super::Minkowski).parameters().is_empty());
        let hole = Spacetime::schwarzschild(0.0).expect("valid");
        assert_eq!(hole.parameters()[0].max, 1.0, "a massless hole can be given a mass");
    }

    /// Every spacetime rebuilt from its own values is itself.
    #[test]
    fn unchanged_values_rebuild_the_same_spacetime() {
        for s in [
            Spacetime::Minkowski(super::super::Minkowski),
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
        let unknown = hole.with_parameters(&[("spin", 0.1)]).expect_err("unknown").0;
        assert!(unknown.contains("no parameter \"spin\" (it has: mass)"), "{unknown}");
        let kerr = Spacetime::kerr(0.5, 0.0).expect("valid");
        assert!(kerr.with_parameters(&[("spin", 0.9)]).is_err(), "|spin| > mass");
        assert_eq!(kerr.with_parameters(&[("spin", 0.4), ("mass", 1.2)]), Spacetime::kerr(1.2, 0.4));
    }
}
