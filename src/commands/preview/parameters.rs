//! The spacetime's parameters as the preview's sliders show them: each with its value and the
//! range a slider may take it over, and the spacetime rebuilt from new values (checked by the
//! physics crate's constructors, so a slider can never make a metric the scene file could not).

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

/// The largest value a slider offers: three times the scene's value, and at least 1 (so that a
/// scene with mass 0 can still be given one).
fn upper(value: f64) -> f64 {
    (3.0 * value).max(1.0)
}

/// The parameters of `spacetime`, with ranges set by `scene`'s own spacetime (the file's), so
/// that moving a slider does not move the range under it.
pub fn parameters(spacetime: &Spacetime, scene: &Spacetime) -> Vec<Parameter> {
    let scale = upper(scene.length_scale());
    match spacetime {
        // A written metric's parameters are folded into its compiled expressions.
        Spacetime::Minkowski(_) | Spacetime::Written(_) => Vec::new(),
        Spacetime::Schwarzschild(s) => vec![Parameter { name: "mass", value: s.mass, min: 0.0, max: scale }],
        Spacetime::Kerr(k) => vec![
            Parameter { name: "mass", value: k.mass, min: 0.0, max: scale },
            Parameter { name: "spin", value: k.spin, min: -scale, max: scale },
        ],
        Spacetime::Ellis(e) => vec![Parameter { name: "throat", value: e.throat, min: 1e-3 * scale, max: scale }],
        Spacetime::ReissnerNordstrom(h) => vec![
            Parameter { name: "mass", value: h.mass, min: 0.0, max: scale },
            Parameter { name: "charge", value: h.charge, min: -scale, max: scale },
        ],
        Spacetime::KerrNewman(h) => vec![
            Parameter { name: "mass", value: h.mass, min: 0.0, max: scale },
            Parameter { name: "spin", value: h.spin, min: -scale, max: scale },
            Parameter { name: "charge", value: h.charge, min: -scale, max: scale },
        ],
    }
}

/// `scene`'s spacetime with the parameters in `values` set; every name must be one of its
/// parameters and every value finite and in its slider's range.
pub fn with_values(scene: &Spacetime, values: &BTreeMap<String, f64>) -> Result<Spacetime, String> {
    let known = parameters(scene, scene);
    for (name, &value) in values {
        let Some(p) = known.iter().find(|p| p.name == name) else {
            let names: Vec<&str> = known.iter().map(|p| p.name).collect();
            return Err(format!(
                "the {} spacetime has no parameter \"{name}\" (it has: {})",
                scene.name(),
                if names.is_empty() { "none".to_string() } else { names.join(", ") }
            ));
        };
        if !(value.is_finite() && value >= p.min && value <= p.max) {
            return Err(format!("{name} must be a number from {} to {}, got {value}", p.min, p.max));
        }
    }
    let get = |name: &str, default: f64| values.get(name).copied().unwrap_or(default);
    let result = match scene {
        Spacetime::Minkowski(_) | Spacetime::Written(_) => Ok(scene.clone()),
        Spacetime::Schwarzschild(s) => Spacetime::schwarzschild(get("mass", s.mass)),
        Spacetime::Kerr(k) => Spacetime::kerr(get("mass", k.mass), get("spin", k.spin)),
        Spacetime::Ellis(e) => Spacetime::ellis(get("throat", e.throat)),
        Spacetime::ReissnerNordstrom(h) => Spacetime::reissner_nordstrom(get("mass", h.mass), get("charge", h.charge)),
        Spacetime::KerrNewman(h) => {
            Spacetime::kerr_newman(get("mass", h.mass), get("spin", h.spin), get("charge", h.charge))
        }
    };
    result.map_err(|e| e.to_string())
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
