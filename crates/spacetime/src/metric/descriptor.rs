//! Each built-in metric describes itself once, in its own file, with a [`MetricDescriptor`]: its
//! name in scene files, what it is, its parameters (meaning, unit, kind of range, default) and the
//! validating constructor that holds the constraints between them. Everything that lists the
//! spacetimes (the scene reader, the preview's sliders, `nullpath geodesic`, the table of
//! `docs/scene-format.md`) reads a registry of descriptors ([`super::SPACETIMES`]), so that a new
//! metric is its file and one line there.
//!
//! A constructor's [`ParameterError`] names the parameter at fault, so that a scene file's error
//! points at that key without the reader validating again.

use super::Spacetime;

/// The values a parameter may take on its own; constraints between parameters (|spin| ≤ mass)
/// are the constructor's ([`MetricDescriptor::build`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Range {
    /// `≥ 0`: a mass or a length that may vanish.
    NonNegative,
    /// `> 0`: a length that must stay positive (a throat radius).
    Positive,
    /// Either sign: a spin or a charge.
    Signed,
}

impl Range {
    /// As the scene-format table writes it after the parameter's name.
    pub fn describe(self) -> &'static str {
        match self {
            Range::NonNegative => "≥ 0",
            Range::Positive => "> 0",
            Range::Signed => "of either sign",
        }
    }

    /// The slider range (inclusive) for values up to `top`: `[0, top]`, `[10⁻³ top, top]` (a
    /// positive length never reaches 0 on a slider) or `[−top, top]`.
    fn span(self, top: f64) -> (f64, f64) {
        match self {
            Range::NonNegative => (0.0, top),
            Range::Positive => (1e-3 * top, top),
            Range::Signed => (-top, top),
        }
    }
}

/// One parameter of a metric, as scene files and user interfaces name it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParameterDescriptor {
    /// The key in scene files (`lensing_width`); `nullpath geodesic` spells it `--lensing-width`.
    pub name: &'static str,
    /// What it is, in a few words ("the hole's mass M").
    pub meaning: &'static str,
    /// Its unit: "length" for scene units (with G = c = 1 a mass, a spin `a = J/M` and a charge
    /// are lengths too).
    pub unit: &'static str,
    /// The values it may take on its own.
    pub range: Range,
    /// The value a scene file gets when it leaves the key out; `None`: the key is required.
    pub default: Option<f64>,
    /// The value `nullpath geodesic` takes when no flag sets it, else [`Self::default`]: there
    /// lengths are in units of the hole's mass or the throat radius, which are 1, and a hole
    /// has no spin or charge unless asked. `None` with no `default`: the flag is required.
    pub command_line_default: Option<f64>,
}

/// Builds the spacetime from its parameters' values, in the order of
/// [`MetricDescriptor::parameters`], checking every constraint.
pub type Build = fn(&[f64]) -> Result<Spacetime, ParameterError>;

/// A spacetime's parameter values in the order of [`MetricDescriptor::parameters`], or `None`
/// when the spacetime is not this metric's.
pub type Values = fn(&Spacetime) -> Option<Vec<f64>>;

/// A metric as every user interface offers it: the one place that lists its name, parameters
/// and constraints.
#[derive(Clone, Copy, Debug)]
pub struct MetricDescriptor {
    /// The `type` of `[spacetime]` in scene files and `--spacetime` of `nullpath geodesic`.
    pub name: &'static str,
    /// One line on what it is, for the scene-format table and help texts.
    pub description: &'static str,
    pub parameters: &'static [ParameterDescriptor],
    /// The constraint between the parameters that [`Self::build`] enforces, as the
    /// scene-format table writes it ("|spin| ≤ mass"); `None` when there is none.
    pub constraint: Option<&'static str>,
    /// Whether the metric has a preferred axis (a spin) that a scene points with `axis`: the
    /// renderer rotates between the chart, whose z axis it is, and the world.
    pub oriented: bool,
    /// The validating constructor: every spacetime made from user input goes through it.
    pub build: Build,
    /// The parameter values of a spacetime this constructor made (the inverse of `build`).
    pub values: Values,
}

/// A parameter outside the spacetime's domain, named as scene files name it.
#[derive(Clone, Debug, PartialEq)]
pub struct ParameterError {
    /// The parameter at fault ([`ParameterDescriptor::name`]), or `""` when the fault is no one
    /// parameter's (a name the spacetime does not have, a wrong count of values).
    pub parameter: &'static str,
    /// What is wrong, written to stand after the parameter's name or at its key in a scene file.
    pub message: String,
}

impl ParameterError {
    pub fn new(parameter: &'static str, message: impl Into<String>) -> Self {
        ParameterError { parameter, message: message.into() }
    }
}

impl std::fmt::Display for ParameterError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.parameter.is_empty() {
            f.write_str(&self.message)
        } else {
            write!(f, "{}: {}", self.parameter, self.message)
        }
    }
}

impl std::error::Error for ParameterError {}

/// A parameter of a spacetime: its value and the range (inclusive) a user may move it over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parameter {
    pub name: &'static str,
    pub value: f64,
    pub min: f64,
    pub max: f64,
}

impl MetricDescriptor {
    /// The parameters of `spacetime` (one this descriptor's constructor made; `None` otherwise)
    /// with their values, each ranging up to three times the length scale (and at least 1, so
    /// that a hole of mass 0 can still be given one).
    pub fn sliders(&self, spacetime: &Spacetime) -> Option<Vec<Parameter>> {
        let values = (self.values)(spacetime)?;
        let top = (3.0 * spacetime.length_scale()).max(1.0);
        let sliders = self
            .parameters
            .iter()
            .zip(values)
            .map(|(p, value)| {
                let (min, max) = p.range.span(top);
                Parameter { name: p.name, value, min, max }
            })
            .collect();
        Some(sliders)
    }

    /// `spacetime` (one this descriptor's constructor made) with the named parameters set to new
    /// values (the others keep theirs): every name must be one of [`Self::sliders`], every value
    /// finite and in its range, and the result valid for [`Self::build`].
    pub fn with_parameters(&self, spacetime: &Spacetime, values: &[(&str, f64)]) -> Result<Spacetime, ParameterError> {
        let Some(known) = self.sliders(spacetime) else {
            return Err(ParameterError::new(
                "",
                format!("the {} spacetime is not a {} spacetime", spacetime.name(), self.name),
            ));
        };
        let chosen = chosen_values(self.name, &known, values)?;
        (self.build)(&chosen)
    }
}

/// Why named values do not make a spacetime ([`MetricDescriptor::build_named`]).
#[derive(Clone, Debug, PartialEq)]
pub enum NamedValuesError {
    /// A name that is not one of the metric's parameters.
    Unknown(String),
    /// A parameter neither given nor defaulted.
    Missing(&'static str),
    /// Values the metric's constructor refuses.
    Invalid(ParameterError),
}

impl MetricDescriptor {
    /// The spacetime of `given` (parameter name, value) pairs: each parameter its given value,
    /// else `default(parameter)` (a user interface's default: a scene file's, or the command
    /// line's), checked by [`Self::build`]. A name the metric does not have is an error, not
    /// ignored, since it is a mistake of the user's (a misspelt or foreign parameter).
    pub fn build_named(
        &self,
        given: &[(&str, f64)],
        default: impl Fn(&ParameterDescriptor) -> Option<f64>,
    ) -> Result<Spacetime, NamedValuesError> {
        if let Some((name, _)) = given.iter().find(|(name, _)| !self.parameters.iter().any(|p| p.name == *name)) {
            return Err(NamedValuesError::Unknown((*name).to_string()));
        }
        let values = self
            .parameters
            .iter()
            .map(|p| {
                let value = given.iter().find(|(name, _)| *name == p.name).map(|&(_, v)| v);
                value.or_else(|| default(p)).ok_or(NamedValuesError::Missing(p.name))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        (self.build)(&values).map_err(NamedValuesError::Invalid)
    }
}

/// The values of `known` with those named in `values` replaced, each checked against its range.
pub(super) fn chosen_values(
    spacetime: &str,
    known: &[Parameter],
    values: &[(&str, f64)],
) -> Result<Vec<f64>, ParameterError> {
    let mut chosen: Vec<f64> = known.iter().map(|p| p.value).collect();
    for &(name, value) in values {
        let Some(i) = known.iter().position(|p| p.name == name) else {
            let names: Vec<&str> = known.iter().map(|p| p.name).collect();
            let names = if names.is_empty() { "none".to_string() } else { names.join(", ") };
            return Err(ParameterError::new(
                "",
                format!("the {spacetime} spacetime has no parameter \"{name}\" (it has: {names})"),
            ));
        };
        let p = known[i];
        if !(value.is_finite() && value >= p.min && value <= p.max) {
            return Err(ParameterError::new(
                p.name,
                format!("must be a number from {} to {}, got {value}", p.min, p.max),
            ));
        }
        chosen[i] = value;
    }
    Ok(chosen)
}

/// The `N` values a constructor takes, from the slice [`MetricDescriptor::build`] is given.
pub fn exactly<const N: usize>(values: &[f64]) -> Result<[f64; N], ParameterError> {
    <[f64; N]>::try_from(values)
        .map_err(|_| ParameterError::new("", format!("expected {N} parameter values, got {}", values.len())))
}

/// A number for messages, as scene files write it: plain for ordinary magnitudes, in exponent
/// form for huge or tiny ones (so that `1e300` does not print as 301 digits); an `f32` in its own
/// shortest form (`1.1`, not the `1.100000023841858` of its widening). The scene reader writes
/// its messages with it too, so that a constructor's error reads as the reader's.
pub fn num<T: Copy + Into<f64> + std::fmt::Display + std::fmt::LowerExp>(x: T) -> String {
    let a = x.into().abs();
    if a != 0.0 && a.is_finite() && !(1e-5..1e15).contains(&a) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Each parameter of `spacetimes` once, in the order they first list it, with the metrics that
/// have it: for the parameter table of the docs and `nullpath geodesic`'s flags.
pub fn parameters_of<'d>(
    spacetimes: &[&'d MetricDescriptor],
) -> Vec<(&'d ParameterDescriptor, Vec<&'d MetricDescriptor>)> {
    let mut out: Vec<(&'d ParameterDescriptor, Vec<&'d MetricDescriptor>)> = Vec::new();
    for &d in spacetimes {
        for p in d.parameters {
            match out.iter_mut().find(|(q, _)| q.name == p.name) {
                Some((_, of)) => of.push(d),
                None => out.push((p, vec![d])),
            }
        }
    }
    out
}

/// `value` of `parameter` if finite and ≥ 0.
pub fn non_negative(parameter: &'static str, value: f64) -> Result<f64, ParameterError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ParameterError::new(parameter, format!("must be a finite number ≥ 0, got {}", num(value))))
    }
}

/// `value` of `parameter` if finite and > 0.
pub fn positive(parameter: &'static str, value: f64) -> Result<f64, ParameterError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ParameterError::new(parameter, format!("must be a finite number > 0, got {}", num(value))))
    }
}

/// `value` of `parameter` (a spin or a charge) if `|value| ≤ mass`.
pub fn at_most_mass(parameter: &'static str, value: f64, mass: f64) -> Result<f64, ParameterError> {
    if value.abs() <= mass {
        Ok(value)
    } else {
        Err(ParameterError::new(parameter, format!("|{parameter}| must be ≤ mass = {}, got {}", num(mass), num(value))))
    }
}

/// A black hole's mass `M`, shared by the holes' descriptors.
pub const MASS: ParameterDescriptor = ParameterDescriptor {
    name: "mass",
    meaning: "the hole's mass M",
    unit: "length",
    range: Range::NonNegative,
    default: None,
    command_line_default: Some(1.0),
};

/// A hole's spin `a = J/M` about its axis, positive for counter-clockwise rotation seen from the
/// axis's tip (the prograde side of `nullpath geodesic` is then positive impact parameters).
pub const SPIN: ParameterDescriptor = ParameterDescriptor {
    name: "spin",
    meaning: "angular momentum per unit mass a = J/M, counter-clockwise seen from the spin axis's tip",
    unit: "length",
    range: Range::Signed,
    default: None,
    command_line_default: Some(0.0),
};

/// A hole's charge `Q` (Gaussian units, G = c = 4πε₀ = 1): its sign does not change how light
/// moves.
pub const CHARGE: ParameterDescriptor = ParameterDescriptor {
    name: "charge",
    meaning: "electric charge Q (G = c = 4πε₀ = 1)",
    unit: "length",
    range: Range::Signed,
    default: None,
    command_line_default: Some(0.0),
};

/// A wormhole's throat radius, shared by the wormholes' descriptors.
pub const THROAT: ParameterDescriptor = ParameterDescriptor {
    name: "throat",
    meaning: "throat radius b₀",
    unit: "length",
    range: Range::Positive,
    default: None,
    command_line_default: Some(1.0),
};

#[cfg(test)]
mod tests {
    use super::super::SPACETIMES;
    use super::*;

    /// Values that every built-in metric accepts, by parameter name.
    fn valid(name: &str) -> f64 {
        match name {
            "mass" | "throat" => 1.0,
            "spin" => 0.6,
            "charge" => -0.5,
            "length" => 0.01,
            "lensing_width" => 0.05,
            other => panic!("no test value for {other}"),
        }
    }

    /// Each descriptor's `values` inverts its `build`, and the spacetime built knows its
    /// descriptor: the registry and the enum agree.
    #[test]
    fn descriptors_invert_their_constructors() {
        let mut names: Vec<&str> = SPACETIMES.iter().map(|d| d.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), SPACETIMES.len(), "names are unique");
        for d in SPACETIMES {
            let values: Vec<f64> = d.parameters.iter().map(|p| valid(p.name)).collect();
            let s = (d.build)(&values).expect("valid");
            assert_eq!((d.values)(&s), Some(values), "{}", d.name);
            assert_eq!(s.descriptor().map(|found| found.name), Some(d.name));
            assert_eq!(s.name(), d.name);
            for other in SPACETIMES.iter().filter(|o| o.name != d.name) {
                assert_eq!((other.values)(&s), None, "{} is not {}", d.name, other.name);
            }
            let wrong = (d.build)(&[1.0; 7]).expect_err("wrong count");
            assert!(wrong.message.contains("expected"), "{wrong}");
        }
    }

    #[test]
    fn errors_name_their_parameter() {
        let e = Spacetime::kerr(1.0, 1.5).expect_err("too fast");
        assert_eq!(e.parameter, "spin");
        assert_eq!(e.to_string(), "spin: |spin| must be ≤ mass = 1, got 1.5");
        assert_eq!(Spacetime::schwarzschild(-2.0).expect_err("negative").parameter, "mass");
        let e = Spacetime::kerr_newman(1.0, 0.8, 0.7).expect_err("too much");
        assert_eq!(e.parameter, "charge");
        assert!(e.message.contains("spin² + charge² ≤ mass² = 1, got 0.8² + 0.7²"), "{e}");
        assert_eq!(Spacetime::wormhole(1.0, 0.0, 0.0).expect_err("no width").parameter, "lensing_width");
        assert_eq!(Spacetime::wormhole(1.0, -1.0, 0.1).expect_err("negative").parameter, "length");
        assert_eq!(num(1e-300), "1e-300");
    }
}
