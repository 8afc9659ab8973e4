//! Adaptive Gauss–Kronrod quadrature along one step of a ray: the coordinate time of the
//! tracers that do not integrate it ([`plane`](super::plane), Kerr's Mino stepper) is the
//! integral of its rate over the step's dense output, asked for only by callers that need it.
//!
//! The rule is QUADPACK's QK15 (Piessens et al. 1983, "QUADPACK", §2.2): the 7-point Gauss rule
//! and its 15-point Kronrod extension, whose difference bounds the error of the 7-point rule and
//! vastly overestimates that of the 15-point one, which is returned. An interval whose
//! difference exceeds its share of the tolerance is halved (depth-first, at most
//! [`MAX_DEPTH`] times): near a pole just outside the step (the rate's `r²` where `r` runs off to
//! infinity) the halves nearest the pole shrink until the pole is far on their scale.

/// Kronrod nodes on `[0, 1]` (symmetric about 0); the odd ones are the Gauss nodes.
const NODES: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights of [`NODES`].
const KRONROD: [f64; 8] = [
    0.022_935_322_010_529_224,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];
/// Gauss weights of the nodes `NODES[1], NODES[3], NODES[5]` and the centre.
const GAUSS: [f64; 4] =
    [0.129_484_966_168_869_7, 0.279_705_391_489_276_7, 0.381_830_050_505_118_9, 0.417_959_183_673_469_4];

/// Halvings of the step before an interval is accepted whatever its error: 2⁻³⁰ of a step is
/// far below any scale a ray has.
const MAX_DEPTH: u32 = 30;

/// `∫ₐᵇ f` to the tolerance `rtol` of `∫ₐᵇ |f|` (as the first 15-point estimate gives it) or
/// `atol`, whichever is larger.
pub(crate) fn integrate(f: &impl Fn(f64) -> f64, a: f64, b: f64, rtol: f64, atol: f64) -> f64 {
    if a == b {
        return 0.0;
    }
    let estimate = kronrod(f, a, b);
    let tolerance = (rtol * estimate.magnitude).max(atol);
    refine(f, (a, b), estimate, tolerance, 0)
}

/// `∫ₐᵇ f` from its first `estimate`, to absolute tolerance `tolerance`, at halving `depth`. An
/// interval whose difference is within rounding of its own magnitude is accepted (as in QUADPACK):
/// halving cannot make it smaller.
fn refine(f: &impl Fn(f64) -> f64, (a, b): (f64, f64), estimate: Estimate, tolerance: f64, depth: u32) -> f64 {
    let Estimate { value, error, magnitude } = estimate;
    if error <= tolerance.max(ROUNDING * magnitude) || depth >= MAX_DEPTH || !error.is_finite() {
        return value;
    }
    let mid = 0.5 * (a + b);
    let halves = [(a, mid), (mid, b)];
    halves.iter().map(|&(a, b)| refine(f, (a, b), kronrod(f, a, b), 0.5 * tolerance, depth + 1)).sum()
}

/// A 15-point estimate over one interval.
struct Estimate {
    value: f64,
    /// Its difference from the 7-point estimate.
    error: f64,
    /// The 15-point estimate of `∫ |f|`.
    magnitude: f64,
}

/// Rounding of a 15-point sum relative to its magnitude (QUADPACK's `50 ε`).
const ROUNDING: f64 = 50.0 * f64::EPSILON;

/// The 15-point estimate of `∫ₐᵇ f`.
fn kronrod(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> Estimate {
    let (centre, half) = (0.5 * (a + b), 0.5 * (b - a));
    let fc = f(centre);
    let (mut kronrod, mut gauss, mut magnitude) = (KRONROD[7] * fc, GAUSS[3] * fc, KRONROD[7] * fc.abs());
    for (i, x) in NODES[..7].iter().enumerate() {
        let (lo, hi) = (f(centre - half * x), f(centre + half * x));
        kronrod += KRONROD[i] * (lo + hi);
        magnitude += KRONROD[i] * (lo.abs() + hi.abs());
        if i % 2 == 1 {
            gauss += GAUSS[i / 2] * (lo + hi);
        }
    }
    Estimate { value: kronrod * half, error: ((kronrod - gauss) * half).abs(), magnitude: magnitude * half.abs() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomials_up_to_degree_22_are_exact_in_one_interval() {
        // Kronrod's 15 points integrate degree 3·7 + 1 exactly.
        let f = |x: f64| x.powi(22) - 3.0 * x.powi(5) + 1.0;
        let exact = |x: f64| x.powi(23) / 23.0 - 0.5 * x.powi(6) + x;
        let value = integrate(&f, -0.3, 1.1, 1e-14, 0.0);
        assert!((value - (exact(1.1) - exact(-0.3))).abs() < 1e-14, "{value}");
    }

    #[test]
    fn a_pole_just_past_the_end_is_resolved_by_halving() {
        // ∫₀¹ dx/(1.001 − x)² = 1/0.001 − 1/1.001: a pole a thousandth of the interval past its
        // end, as the rate `r²` of a ray that reaches the escape radius in one step.
        let f = |x: f64| 1.0 / ((1.001 - x) * (1.001 - x));
        let exact = 1.0 / 0.001 - 1.0 / 1.001;
        let value = integrate(&f, 0.0, 1.0, 1e-12, 0.0);
        assert!((value / exact - 1.0).abs() < 1e-12, "{value} vs {exact}");
        // And backwards.
        assert!((integrate(&f, 1.0, 0.0, 1e-12, 0.0) / exact + 1.0).abs() < 1e-12);
    }
}
