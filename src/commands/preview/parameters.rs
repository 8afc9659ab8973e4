//! The spacetime's parameters as the preview's sliders show them. The metric's descriptor lists
//! them with their ranges and rebuilds the spacetime from new values
//! ([`MetricDescriptor::sliders`], [`MetricDescriptor::with_parameters`]); the preview keeps each
//! slider's range that of the scene file's spacetime, so that moving a slider does not move the
//! range under it, narrowed to the values the spacetime allows with the other parameters as they are (|spin| ≤ mass for Kerr,
//! spin² + charge² ≤ mass² for Kerr–Newman, …), so that a slider never offers a value the
//! server must refuse.

use spacetime::metric::MetricDescriptor;
use spacetime::Spacetime;
use std::collections::BTreeMap;

/// Most halvings that find where a parameter's allowed values end: enough to narrow any range
/// of finite doubles (2¹⁰²⁴ wide) down to adjacent doubles near zero (2⁻¹⁰⁷⁴ apart).
const BISECTIONS: u32 = 2100;

/// One slider: a parameter of the spacetime, its value and its range (inclusive).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Parameter {
    pub name: &'static str,
    pub value: f64,
    pub min: f64,
    pub max: f64,
}

/// The sliders of `spacetime` (the one shown, made from `scene`'s by [`with_values`]), with the
/// ranges of `scene`'s own parameters (the file's), each narrowed to the values it can take
/// with the others as `spacetime` has them; none for a written metric.
pub fn parameters(spacetime: &Spacetime, scene: &Spacetime) -> Vec<Parameter> {
    scene.descriptor().map_or_else(Vec::new, |d| sliders(d, spacetime, scene))
}

/// [`parameters`] by the metric's descriptor `d` (`scene`'s): its parameters' names and ranges.
pub fn sliders(d: &MetricDescriptor, spacetime: &Spacetime, scene: &Spacetime) -> Vec<Parameter> {
    let ranges = d.sliders(scene).unwrap_or_default();
    let shown = d.sliders(spacetime).unwrap_or_default();
    shown
        .iter()
        .map(|p| {
            let range = ranges.iter().find(|r| r.name == p.name).unwrap_or(p);
            let valid = |x: f64| {
                let values: Vec<(&str, f64)> =
                    shown.iter().map(|q| (q.name, if q.name == p.name { x } else { q.value })).collect();
                d.with_parameters(scene, &values).is_ok()
            };
            let (min, max) = (edge(&valid, p.value, range.min), edge(&valid, p.value, range.max));
            Parameter { name: p.name, value: p.value, min, max }
        })
        .collect()
}

/// The farthest value from `inside` (valid) towards `end` that `valid` accepts: `end` itself if
/// it does, else found by bisection. The physics crate's constraints each hold on an interval of
/// one parameter (the others fixed), so the valid values between the two are one interval.
fn edge(valid: &dyn Fn(f64) -> bool, mut inside: f64, end: f64) -> f64 {
    if valid(end) {
        return end;
    }
    let mut outside = end;
    for _ in 0..BISECTIONS {
        let middle = inside + 0.5 * (outside - inside);
        if middle == inside || middle == outside {
            break;
        }
        if valid(middle) {
            inside = middle;
        } else {
            outside = middle;
        }
    }
    inside
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

    fn range(sliders: &[Parameter], name: &str) -> (f64, f64) {
        let p = sliders.iter().find(|p| p.name == name).expect("a slider");
        (p.min, p.max)
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
        assert_eq!(parameters(&heavier, &kerr)[0], Parameter { name: "mass", value: 1.4, min: 0.2, max: 1.5 });
    }

    #[test]
    fn sliders_offer_only_what_the_spacetime_allows() {
        // Kerr: |spin| ≤ mass, both ways.
        let kerr = Spacetime::kerr(0.3, 0.27).expect("valid");
        let sliders = parameters(&kerr, &kerr);
        assert_eq!(range(&sliders, "spin"), (-0.3, 0.3), "not the file's ±1");
        assert_eq!(range(&sliders, "mass"), (0.27, 1.0), "the file's range reaches 1 at least");
        let heavier = Spacetime::kerr(0.6, 0.27).expect("valid");
        assert_eq!(range(&parameters(&heavier, &kerr), "spin"), (-0.6, 0.6), "the range follows the mass set");
        // Kerr–Newman: spin² + charge² ≤ mass², to the last digit (0.6² + 0.8² is not 1 in doubles).
        let kn = Spacetime::kerr_newman(1.0, 0.6, 0.0).expect("valid");
        let close = |(lo, hi): (f64, f64), (a, b): (f64, f64)| (lo - a).abs() < 1e-12 && (hi - b).abs() < 1e-12;
        let sliders = parameters(&kn, &kn);
        assert!(close(range(&sliders, "charge"), (-0.8, 0.8)), "{sliders:?}");
        assert_eq!(range(&sliders, "spin"), (-1.0, 1.0));
        assert_eq!(range(&sliders, "mass"), (0.6, 3.0));
        let charged = Spacetime::kerr_newman(1.0, 0.6, 0.5).expect("valid");
        let sliders = parameters(&charged, &kn);
        assert!(close(range(&sliders, "spin"), (-0.75f64.sqrt(), 0.75f64.sqrt())), "{sliders:?}");
        assert!(close(range(&sliders, "mass"), (0.61f64.sqrt(), 3.0)), "{sliders:?}");
        // Every end offered is a value the server accepts, the others as they are.
        for p in &sliders {
            for end in [p.min, p.max] {
                let mut set = values(&[("mass", 1.0), ("spin", 0.6), ("charge", 0.5)]);
                set.insert(p.name.to_string(), end);
                assert!(with_values(&kn, &set).is_ok(), "{} = {end}", p.name);
            }
        }
        // A wormhole's lensing width has a least share of the throat; the sliders' ranges are within it.
        let wormhole = Spacetime::wormhole(1.0, 0.5, 0.05).expect("valid");
        assert_eq!(range(&parameters(&wormhole, &wormhole), "lensing_width"), (0.003, 3.0));
    }

    #[test]
    fn new_values_are_checked() {
        let hole = Spacetime::schwarzschild(0.3).expect("valid");
        assert_eq!(
            with_values(&hole, &values(&[("mass", 0.6)])),
            Spacetime::schwarzschild(0.6).map_err(|e| e.to_string())
        );
        assert!(with_values(&hole, &values(&[("mass", -0.1)])).is_err());
        assert!(with_values(&hole, &values(&[("mass", f64::NAN)])).is_err());
        assert!(with_values(&hole, &values(&[("mass", 1.5)])).is_err(), "beyond the slider");
        let unknown = with_values(&hole, &values(&[("spin", 0.1)])).unwrap_err();
        assert!(unknown.contains("no parameter \"spin\""), "{unknown}");
        let kerr = Spacetime::kerr(0.5, 0.0).expect("valid");
        assert!(with_values(&kerr, &values(&[("spin", 0.9)])).is_err(), "|spin| > mass");
    }
}
