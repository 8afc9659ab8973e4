use super::*;
use crate::sampling::Rng;

const N: usize = 200_000;

/// Composite Simpson's rule for `∫ g` over `[a, b]` with `n` (even) intervals.
fn simpson(g: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n).map(|i| g(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 }).sum();
    (g(a) + g(b) + inner) * h / 3.0
}

/// Mean and standard error of the mean of `values`.
fn mean_and_error(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let n = values.clone().count() as f64;
    let mean = values.clone().sum::<f64>() / n;
    let var = values.map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

fn draw(filter: &Filter, seed: u64) -> Vec<FilterSample> {
    let mut rng = Rng::new(seed);
    (0..N).map(|_| filter.sample(rng.next_2d())).collect()
}

/// Moments of the 1-D profile along `axis` (all filters are separable): returns
/// (`∫x²|g| / ∫|g|`, `∫x² g / ∫g`).
fn reference_second_moments(filter: &Filter, axis: usize) -> (f64, f64) {
    let r = filter.radius()[axis];
    let g = |x: f64| {
        let mut p = [0.0, 0.0];
        p[axis] = x;
        filter.evaluate(p)
    };
    // 4096 intervals put the kinks of the tent (0) and Mitchell (±r/2) on nodes.
    let n = 4096;
    let abs_m0 = simpson(|x| g(x).abs(), -r, r, n);
    let abs_m2 = simpson(|x| x * x * g(x).abs(), -r, r, n);
    let m0 = simpson(g, -r, r, n);
    let m2 = simpson(|x| x * x * g(x), -r, r, n);
    (abs_m2 / abs_m0, m2 / m0)
}

/// Offsets are distributed as `|f|`: per axis, zero mean and the reference second moment,
/// within 5 standard errors plus 2·10⁻⁴ r² for the tabulation's step approximation; every
/// offset lies inside the support.
fn check_offset_distribution(filter: &Filter, seed: u64) -> Vec<FilterSample> {
    let samples = draw(filter, seed);
    for axis in 0..2 {
        let r = filter.radius()[axis];
        assert!(samples.iter().all(|s| s.offset[axis].abs() <= r));
        let (mean, se) = mean_and_error(samples.iter().map(|s| s.offset[axis]));
        assert!(mean.abs() < 5.0 * se, "{filter:?} axis {axis}: mean {mean} (se {se})");
        let (m2, se2) = mean_and_error(samples.iter().map(|s| s.offset[axis].powi(2)));
        let (reference, _) = reference_second_moments(filter, axis);
        let tolerance = 5.0 * se2 + 2e-4 * r * r;
        assert!(
            (m2 - reference).abs() < tolerance,
            "{filter:?} axis {axis}: E[x²] = {m2}, reference {reference}, tolerance {tolerance}"
        );
    }
    samples
}

#[test]
fn box_offsets_are_uniform_with_unit_weights() {
    let filter = Filter::box_filter([0.5, 1.5]).expect("valid box");
    let samples = check_offset_distribution(&filter, 1);
    assert!(samples.iter().all(|s| s.weight == 1.0));
    // Analytic: a uniform density on [-r, r] has E[x²] = r²/3.
    let (reference, _) = reference_second_moments(&filter, 1);
    assert!((reference - 1.5f64.powi(2) / 3.0).abs() < 1e-6);
}

#[test]
fn tent_offsets_follow_the_tent_with_unit_weights() {
    let filter = Filter::tent([2.0, 1.0]).expect("valid tent");
    let samples = check_offset_distribution(&filter, 2);
    assert!(samples.iter().all(|s| s.weight == 1.0));
    // Analytic: the normalised tent of half-width r has E[x²] = r²/6.
    let (reference, _) = reference_second_moments(&filter, 0);
    assert!((reference - 4.0 / 6.0).abs() < 1e-6);
}

#[test]
fn tent_sampling_is_monotone_and_hits_the_ends() {
    assert_eq!(sample_tent(0.0, 2.0), -2.0);
    assert_eq!(sample_tent(0.5, 2.0), 0.0);
    let xs: Vec<f64> = (0..=1000).map(|k| sample_tent(f64::from(k) / 1000.0, 2.0)).collect();
    assert!(xs.windows(2).all(|w| w[0] <= w[1]));
    assert!((xs[1000] - 2.0).abs() < 1e-12);
}

#[test]
fn gaussian_offsets_follow_the_filter_with_unit_weights() {
    let filter = Filter::gaussian([1.5, 1.5], 0.5).expect("valid gaussian");
    let samples = check_offset_distribution(&filter, 3);
    assert!(samples.iter().all(|s| s.weight == 1.0));
    // Sanity of the reference: truncation at 3σ leaves E[x²] a little under σ².
    let (reference, _) = reference_second_moments(&filter, 0);
    assert!(reference > 0.2 && reference < 0.25, "{reference}");
}

#[test]
fn gaussian_histogram_matches_the_filter() {
    // Per-bin frequencies along x against the filter's mass in the bin, 5σ binomial bounds.
    let filter = Filter::gaussian([2.0, 2.0], 0.6).expect("valid gaussian");
    let samples = draw(&filter, 4);
    let g = |x: f64| filter.evaluate([x, 0.0]);
    let total = simpson(g, -2.0, 2.0, 4096);
    let bins = 16;
    for b in 0..bins {
        let lo = -2.0 + 4.0 * b as f64 / bins as f64;
        let hi = lo + 4.0 / bins as f64;
        let p = simpson(g, lo, hi, 256) / total;
        let count = samples.iter().filter(|s| s.offset[0] >= lo && s.offset[0] < hi).count();
        let freq = count as f64 / N as f64;
        let sigma = (p * (1.0 - p) / N as f64).sqrt();
        assert!((freq - p).abs() < 5.0 * sigma + 1e-4, "bin {b}: {freq} vs {p}");
    }
}

#[test]
fn blackman_harris_offsets_follow_the_filter_with_unit_weights() {
    let filter = Filter::blackman_harris([1.5, 0.75]).expect("valid window");
    let samples = check_offset_distribution(&filter, 5);
    assert!(samples.iter().all(|s| s.weight == 1.0));
    assert!((filter.evaluate([0.0, 0.0]) - 1.0).abs() < 1e-12);
    assert!((blackman_harris_1d(1.0) - 6e-5).abs() < 1e-12);
}

#[test]
fn mitchell_matches_published_values() {
    let b = MITCHELL_RECOMMENDED_B_C;
    // m(0) = (6 - 2B)/6, m(±1) = B/6 from both branches, m(±2) = 0.
    assert!((mitchell_1d(0.0, b, b) - (6.0 - 2.0 * b) / 6.0).abs() < 1e-15);
    assert!((mitchell_1d(1.0, b, b) - b / 6.0).abs() < 1e-15);
    assert!((mitchell_1d(1.0 + 1e-12, b, b) - b / 6.0).abs() < 1e-10);
    assert!(mitchell_1d(2.0, b, b).abs() < 1e-15);
    assert!(mitchell_1d(1.5, b, b) < 0.0, "negative lobe");
    // Unit integral for any B, C.
    for (b, c) in [(1.0 / 3.0, 1.0 / 3.0), (0.0, 0.5), (1.0, 0.0)] {
        let integral = simpson(|x| mitchell_1d(x, b, c), -2.0, 2.0, 4096);
        assert!((integral - 1.0).abs() < 1e-9, "B={b} C={c}: {integral}");
    }
}

#[test]
fn mitchell_has_signed_weights_with_the_filters_moments() {
    let b = MITCHELL_RECOMMENDED_B_C;
    let filter = Filter::mitchell([2.0, 2.0], b, b).expect("valid mitchell");
    let samples = check_offset_distribution(&filter, 6);

    // Weights are ±k with one magnitude k > 1, and some are negative.
    let k = samples[0].weight.abs();
    assert!(k > 1.0);
    assert!(samples.iter().all(|s| s.weight.abs() == k));
    let negatives = samples.iter().filter(|s| s.weight < 0.0).count() as f64;
    // A sample is negative when exactly one axis lands in a negative lobe: 2q(1 - q), with
    // q the 1-D profile's share of negative mass.
    let g = |x: f64| filter.evaluate([x, 0.0]);
    let q = simpson(|x| (-g(x)).max(0.0), -2.0, 2.0, 4096) / simpson(|x| g(x).abs(), -2.0, 2.0, 4096);
    let p = 2.0 * q * (1.0 - q);
    let sigma = (p * (1.0 - p) / N as f64).sqrt();
    assert!((negatives / N as f64 - p).abs() < 5.0 * sigma + 1e-3, "{negatives} vs {p}");

    // The weights have expectation 1 and reproduce the signed filter's second moment.
    let (mean_w, se_w) = mean_and_error(samples.iter().map(|s| s.weight));
    assert!((mean_w - 1.0).abs() < 5.0 * se_w + 1e-4, "E[w] = {mean_w}");
    for axis in 0..2 {
        let (m2, se) = mean_and_error(samples.iter().map(|s| s.weight * s.offset[axis].powi(2)));
        let (_, reference) = reference_second_moments(&filter, axis);
        assert!((m2 - reference).abs() < 5.0 * se + 1e-3, "axis {axis}: E[w x²] = {m2}, reference {reference}");
    }
}

#[test]
fn sampling_is_monotone_and_clamps_out_of_range_input() {
    const ONE_MINUS_EPSILON: f64 = 1.0 - f64::EPSILON / 2.0;
    for kind in FILTERS {
        let filter = kind.build_default().expect("defaults are valid");
        let r = filter.radius();
        // Out-of-range input is the nearest point of [0, 1)²; NaN is 0.
        for (u, clamped) in [
            ([1.0, 1.0], [ONE_MINUS_EPSILON, ONE_MINUS_EPSILON]),
            ([-0.5, 2.0], [0.0, ONE_MINUS_EPSILON]),
            ([f64::NAN, 0.5], [0.0, 0.5]),
        ] {
            let s = filter.sample(u);
            assert_eq!(s, filter.sample(clamped), "{}: u = {u:?}", kind.name);
            assert!(s.offset[0].abs() <= r[0] && s.offset[1].abs() <= r[1] && s.weight.is_finite());
        }
        // Monotone in each component, from one end of the support to the other: stratified
        // patterns stay stratified.
        for axis in 0..2 {
            let offsets: Vec<f64> = (0..=256)
                .map(|k| {
                    let mut u = [0.37, 0.61];
                    u[axis] = f64::from(k) / 256.0;
                    filter.sample(u).offset[axis]
                })
                .collect();
            assert!(offsets.windows(2).all(|w| w[0] <= w[1]), "{}: not monotone along {axis}", kind.name);
            assert!(offsets[0] < -0.5 * r[axis] && offsets[256] > 0.5 * r[axis], "{}: {offsets:?}", kind.name);
        }
    }
    // A filter rebuilt from the same parameters draws the same offsets (its tables are a
    // function of the parameters alone).
    let a = Filter::mitchell([2.0, 1.5], 0.3, 0.4).expect("valid");
    let b = Filter::mitchell([2.0, 1.5], 0.3, 0.4).expect("valid");
    let mut rng = Rng::new(7);
    for _ in 0..1000 {
        let u = rng.next_2d();
        assert_eq!(a.sample(u), b.sample(u));
    }
}

#[test]
fn filters_take_their_formulas_values_and_vanish_outside_their_support() {
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * b.abs().max(1.0);
    let boxed = Filter::box_filter([0.5, 1.5]).expect("valid");
    assert_eq!(boxed.evaluate([0.5, -1.5]), 1.0);
    assert_eq!(boxed.evaluate([0.51, 0.0]), 0.0);
    let tent = Filter::tent([2.0, 1.0]).expect("valid");
    assert!(close(tent.evaluate([0.5, -0.25]), 1.5 * 0.75));
    // σ = 0.5, r = 1.5: each factor is g(x) − g(1.5), g the normal density.
    let gaussian = Filter::gaussian([1.5, 1.5], 0.5).expect("valid");
    let g = |x: f64| (-x * x / 0.5).exp() / ((2.0 * PI).sqrt() * 0.5);
    assert!(close(gaussian.evaluate([0.0, 0.0]), (g(0.0) - g(1.5)).powi(2)));
    assert!(close(gaussian.evaluate([0.7, -0.2]), (g(0.7) - g(1.5)) * (g(0.2) - g(1.5))));
    // Mitchell with B = C = 1/3 at the centre: ((6 − 2B)/6)² = (8/9)²; at x = r/2 (m(1) = B/6).
    let third = MITCHELL_RECOMMENDED_B_C;
    let mitchell = Filter::mitchell([2.0, 2.0], third, third).expect("valid");
    assert!(close(mitchell.evaluate([0.0, 0.0]), (8.0f64 / 9.0).powi(2)));
    assert!(close(mitchell.evaluate([1.0, 0.0]), third / 6.0 * (8.0 / 9.0)));
    let window = Filter::blackman_harris([1.5, 0.75]).expect("valid");
    assert!(close(window.evaluate([0.0, 0.0]), 1.0));
    assert!(close(window.evaluate([0.75, 0.0]), 0.35875 - 0.14128));
    // Zero just outside the support along each axis, for every filter.
    for filter in [boxed, tent, gaussian, mitchell, window] {
        let [rx, ry] = filter.radius();
        for p in [[rx * 1.001, 0.0], [0.0, -ry * 1.001], [-rx * 1.5, ry * 1.5]] {
            assert_eq!(filter.evaluate(p), 0.0, "{filter:?} at {p:?}");
        }
    }
}

#[test]
fn every_filter_kind_builds_its_own_filter_with_its_defaults() {
    let names: Vec<&str> = FILTERS.iter().map(|k| k.name).collect();
    assert_eq!(names, ["box", "tent", "gaussian", "mitchell", "blackman-harris"]);
    for kind in FILTERS {
        let filter = kind.build_default().expect("defaults are valid");
        assert_eq!(filter.name(), kind.name);
        assert_eq!(filter.radius(), [kind.default_radius; 2]);
        let values: Vec<f64> = kind.parameters.iter().map(|p| p.1).collect();
        let other = kind.build([1.0, 0.75], &values).expect("valid");
        assert_eq!((other.name(), other.radius()), (kind.name, [1.0, 0.75]));
    }
    // The parameters reach the filter in their order.
    match FILTERS[3].build([2.0, 2.0], &[0.25, 0.5]) {
        Ok(Filter::Mitchell(m)) => assert_eq!((m.b(), m.c()), (0.25, 0.5)),
        other => panic!("{other:?}"),
    }
    match FILTERS[2].build([2.0, 2.0], &[0.7]) {
        Ok(Filter::Gaussian(g)) => assert_eq!(g.sigma(), 0.7),
        other => panic!("{other:?}"),
    }
    // The default filter is the box's defaults.
    assert_eq!(Filter::default().radius(), [FILTERS[0].default_radius; 2]);
}

#[test]
#[should_panic(expected = "the mitchell filter takes")]
fn a_filter_kind_refuses_the_wrong_number_of_parameters() {
    let _ = FILTERS[3].build([2.0, 2.0], &[0.3]);
}

#[test]
fn constructors_reject_bad_parameters() {
    assert!(matches!(Filter::box_filter([0.0, 0.5]), Err(FilterError::InvalidRadius { .. })));
    assert!(Filter::tent([f64::NAN, 1.0]).is_err());
    assert!(Filter::tent([1.0, -1.0]).is_err());
    assert!(Filter::blackman_harris([1.0, MAX_FILTER_RADIUS * 2.0]).is_err());
    assert!(matches!(Filter::gaussian([1.5, 1.5], 0.0), Err(FilterError::InvalidParameter { name: "sigma", .. })));
    assert!(Filter::mitchell([2.0, 2.0], f64::INFINITY, 0.3).is_err());
    let message = Filter::box_filter([-1.0, 0.5]).map(|_| ()).unwrap_err().to_string();
    assert!(message.contains("radius") && message.contains("-1"), "{message}");
}

#[test]
fn default_is_the_half_pixel_box() {
    let filter = Filter::default();
    assert_eq!(filter.radius(), [0.5, 0.5]);
    assert_eq!(filter.sample([0.0, 0.0]).offset, [-0.5, -0.5]);
}
