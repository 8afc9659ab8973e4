//! How a medium's emission and absorption look from a frame in which light's frequency is `g`
//! times the medium's rest-frame frequency (`g = ν_obs/ν_rest`, docs/physics.md "Frequency
//! ratios and redshift"; `g > 1` a blueshift).
//!
//! Along a ray of affine parameter `λ` and 4-momentum `p`, through gas of 4-velocity `u`, the
//! transfer equation is covariant in the invariants (Mihalas & Mihalas 1984, §91; Rybicki &
//! Lightman 1979, §4.9; the form that Gyoto, ipole and RAPTOR integrate):
//!
//! `d(I_ν/ν³)/dλ = j_ν/ν² − (ν α_ν)(I_ν/ν³)`, with `ν = −p·u`,
//!
//! where `I_ν/ν³`, `j_ν/ν²` and `ν α_ν` are the same in every frame. Measured in the gas's rest
//! frame, `ds = (−p·u) dλ` is its length along the ray, the optical depth is `dτ = α_ν,rest ds`,
//! and the radiance seen at frequency `ν` (frequency `ν/g` in the gas) grows as
//!
//! `dI_ν,obs/ds = g³ j_ν,rest(ν/g) − α_ν,rest(ν/g) I_ν,obs`.
//!
//! So per unit rest-frame length the emission is shifted exactly as a surface's radiance is
//! (`g³ I_ν(ν/g)`, or `g⁵ L_λ(gλ)`, or `g⁴` for frequency-integrated RGB) and absorption is read
//! at the rest frequency; per unit affine length both are multiplied by `−p·u`.

/// The factors by which rest-frame emission and absorption at the observed frequency are
/// multiplied to give those to integrate along the ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TransferFactors {
    pub emission: f64,
    pub absorption: f64,
}

/// The invariant emissivity `j_ν/ν²`.
pub fn emission_invariant(j_nu: f64, nu: f64) -> f64 {
    j_nu / (nu * nu)
}

/// The invariant absorption `ν α_ν`.
pub fn absorption_invariant(alpha_nu: f64, nu: f64) -> f64 {
    nu * alpha_nu
}

/// A power-law emissivity `j_ν = j₀ (ν/ν₀)^{−index}` (optically thin synchrotron-like gas) seen
/// at `g`, per unit rest-frame length: `g³ j(ν/g) = g^{3+index} j(ν)`, the same spectrum
/// brighter (the Doppler boosting of a jet's knots). Its absorption, if the gas is thermal at a
/// temperature far above `hν/k` (Kirchhoff's law in the Rayleigh–Jeans limit, `α_ν = j_ν c² /
/// (2ν²kT) ∝ ν^{−(index+2)}`), is `α(ν/g) = g^{index+2} α(ν)`.
pub fn power_law(g: f64, index: f64) -> TransferFactors {
    TransferFactors { emission: g.powf(3.0 + index), absorption: g.powf(index + 2.0) }
}

/// A frequency-independent ("grey") coefficient seen at `g` per unit rest-frame length, for
/// frequency-integrated radiance (the RGB mode's): emission `∫ g³ j(ν/g) dν = g⁴ ∫ j`,
/// absorption unchanged.
pub fn grey(g: f64) -> TransferFactors {
    TransferFactors { emission: g.powi(4), absorption: 1.0 }
}

impl TransferFactors {
    /// The factors per unit affine length of a ray along which the gas measures the photon's
    /// energy `−p·u`, with the spectral factors already in (`ds = (−p·u) dλ`).
    pub fn per_affine_length(self, minus_p_dot_u: f64) -> Self {
        Self { emission: self.emission * minus_p_dot_u, absorption: self.absorption * minus_p_dot_u }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The factors follow from the invariants: per unit rest-frame length (affine length
    /// `1/ν_rest` per unit, as `ds = (−p·u) dλ`), `I_obs = ν_obs³ (I/ν³)` grows by `ν_obs³` times
    /// the invariant `j/ν²` and falls by the invariant `ν α` over `ν_rest`.
    #[test]
    fn power_law_factors_follow_from_the_invariants() {
        for (g, s) in [(0.5, 0.7), (1.0, 0.0), (2.3, 1.5), (0.9, -0.3)] {
            let nu_obs: f64 = 3.0;
            let nu_rest = nu_obs / g;
            let j_rest = |nu: f64| nu.powf(-s);
            let alpha_rest = |nu: f64| nu.powf(-(s + 2.0));
            // d(I/ν³)/dλ = j/ν²; dλ = ds/ν_rest; dI_obs/ds = ν_obs³ · (j/ν²) / ν_rest.
            let emission = nu_obs.powi(3) * emission_invariant(j_rest(nu_rest), nu_rest) / nu_rest;
            // d(I/ν³)/dλ = −(ν α)(I/ν³): dI_obs/ds = −(ν_rest α_rest) I_obs / ν_rest.
            let absorption = absorption_invariant(alpha_rest(nu_rest), nu_rest) / nu_rest;
            let f = power_law(g, s);
            assert!((f.emission * j_rest(nu_obs) / emission - 1.0).abs() < 1e-12, "g {g}, s {s}");
            assert!((f.absorption * alpha_rest(nu_obs) / absorption - 1.0).abs() < 1e-12, "g {g}, s {s}");
        }
    }

    #[test]
    fn grey_emission_is_brightened_as_radiance() {
        assert_eq!(grey(2.0), TransferFactors { emission: 16.0, absorption: 1.0 });
        assert_eq!(grey(2.0).per_affine_length(0.5), TransferFactors { emission: 8.0, absorption: 0.5 });
    }
}
