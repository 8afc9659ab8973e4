//! The spacetime's parameters as the preview's sliders show them. The physics crate lists them
//! with their ranges and rebuilds the spacetime from new values ([`Spacetime::parameters`],
//! [`Spacetime::with_parameters`]); the preview keeps each slider's range that of the scene
//! file's spacetime, so that moving a slider does not move the range under it.

use spacetime::Spacetime;
use std::collections::BTreeMap;

/// One slider: a parameter of the spacetime, its value and its range (inclusive).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Parameter {
    pub name: &'static str,
    pub value: f64,
    pub min: f64,
    pub max: f64,
}

/// The sliders of `spacetime` (the one shown, made from `scene`'s by [`with_values`]), with the
/// ranges of `scene`'s own parameters (the file's).
pub fn parameters(spacetime: &Spacetime, scene: &Spacetime) -> Vec<Parameter> {
    let ranges = scene.parameters();
    spacetime
        .parameters()
        .into_iter()
        .map(|p| {
            let range = ranges.iter().find(|r| r.name == p.name).unwrap_or(&p);
            Parameter { name: p.name, value: p.value, min: range.min, max: range.max }
        })
        .collect()
}

/// `scene`'s spacetime with the parameters in `values` set (checked by the physics crate).
pub fn with_values(scene: &Spacetime, values: &BTreeMap<String, f64>) -> Result<Spacetime, String> {
    let values: Vec<(&str, f64)> = values.iter().map(|(k, &v)| (k.as_str(), v)).collect();
    scene.with_parameters(&values).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(pairs: &[(&str, f64)]) -> BTreeMap<String, f64> {
        pairs.iter().map(|&(k, v)| (k.to_string(), v)).collect()
    }

    #[test]
    fn sliders_follow_the_spacetime() {
        let kerr = Spacetime::kerr(0.5, 0.2).expect("valid");
        let names: Vec<&str> = parameters(&kerr, &kerr).iter().map(|p| p.name).collect();
        assert_eq!(names, ["mass", "spin"]);
        assert_eq!(parameters(&kerr, &kerr)[0].max, 1.5);
        assert!(parameters(&Spacetime::Minkowski(spacetime::Minkowski), &kerr).is_empty());
        // A heavier hole shown keeps the file's ranges.
        let heavier = Spacetime::kerr(1.4, 0.2).expect("valid");
        assert_eq!(parameters(&heavier, &kerr)[0], Parameter { name: "mass", value: 1.4, min: 0.0, max: 1.5 });
    }

    #[test]
    fn new_values_are_checked() {
        let hole = Spacetime::schwarzschild(0.3).expect("valid");
        assert_eq!(with_values(&hole, &values(&[("mass", 0.6)])), Spacetime::schwarzschild(0.6).map_err(|e| e.0));
        assert!(with_values(&hole, &values(&[("mass", -0.1)])).is_err());
        assert!(with_values(&hole, &values(&[("mass", f64::NAN)])).is_err());
        assert!(with_values(&hole, &values(&[("mass", 1.5)])).is_err(), "beyond the slider");
        let unknown = with_values(&hole, &values(&[("spin", 0.1)])).unwrap_err();
        assert!(unknown.contains("no parameter \"spin\""), "{unknown}");
        let kerr = Spacetime::kerr(0.5, 0.0).expect("valid");
        assert!(with_values(&kerr, &values(&[("spin", 0.9)])).is_err(), "|spin| > mass");
    }
}
