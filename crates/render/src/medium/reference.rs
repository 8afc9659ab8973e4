//! Deterministic references for the tracking estimators and for tests: a chord cut into `steps`
//! equal pieces, the coefficients read at each piece's midpoint and held there, and the
//! transfer equation solved exactly on each piece. Exact for a homogeneous medium whatever
//! `steps`; for a smooth heterogeneous one the error falls as `steps⁻²` (the midpoint rule).

use super::tracking::Chord;
use super::Medium;
use crate::rgb::Rgb;

/// The chord's pieces: their midpoints' `t` and their world and rest-frame lengths.
fn pieces(chord: &Chord, steps: usize) -> impl Iterator<Item = (f64, f64)> + '_ {
    let steps = steps.max(1);
    let dt = chord.length / steps as f64;
    let ds = chord.rest_length / steps as f64;
    (0..steps).map(move |i| ((i as f64 + 0.5) * dt, ds))
}

/// `exp(−∫ σ_t ds)` along the chord, `ds` its rest-frame length.
pub fn transmittance(medium: &Medium, chord: &Chord, steps: usize) -> f64 {
    let depth: f64 = pieces(chord, steps).map(|(t, ds)| medium.coefficients(chord.at(t)).extinction() * ds).sum();
    (-depth).exp()
}

/// The radiance that the medium's emission adds along the chord, seen at frequency ratio `g`
/// (RGB), light lost on the way by absorption and out-scattering but none scattered in: on a
/// piece of extinction `σ` and emission `j`, `I ← I e^{−σ Δs} + (j/σ)(1 − e^{−σ Δs})`, which is
/// `I + j Δs` where `σ = 0`. Returns the radiance at the chord's end and the transmittance.
pub fn emitted(medium: &Medium, chord: &Chord, steps: usize, g: f64) -> (Rgb, f64) {
    let mut radiance = [0.0f64; 3];
    let mut transmittance = 1.0;
    for (t, ds) in pieces(chord, steps) {
        let p = chord.at(t);
        let sigma = medium.coefficients(p).extinction();
        let j: Rgb = medium.emission_seen(p, g, &());
        let piece_transmittance = (-sigma * ds).exp();
        // (1 − e^{−σΔs})/σ, which tends to Δs as σ → 0; `exp_m1` keeps its digits there.
        let path = if sigma * ds > 1e-12 { -(-sigma * ds).exp_m1() / sigma } else { ds };
        for c in 0..3 {
            radiance[c] = radiance[c] * piece_transmittance + f64::from(j[c]) * path;
        }
        transmittance *= piece_transmittance;
    }
    (Rgb::from_array(radiance.map(|c| c as f32)), transmittance)
}
