//! The inverse square root of a symmetric positive definite 3 × 3 matrix, in closed form where
//! that is accurate: the Gram matrix of a frame's projected axes, which Löwdin's symmetric
//! orthonormalisation ([`super::Tetrad::with_velocity`]) multiplies them by.
//!
//! The eigenvalues are the roots of the characteristic cubic in Smith's trigonometric form
//! (O. K. Smith 1961, "Eigenvalues of a symmetric 3 × 3 matrix", CACM 4(4), 168), and `S^{-1/2}`
//! is the polynomial in `S` that takes the values `λ^{-1/2}` at them (Sylvester), in Newton's
//! form, whose divided differences of `λ^{-1/2}` have closed forms in `s = √λ` that stay exact
//! when eigenvalues coincide:
//!
//! `f[λ₁, λ₂] = −1 / (s₁ s₂ (s₁ + s₂))`,
//! `f[λ₁, λ₂, λ₃] = (s₁ + s₂ + s₃) / (s₁ s₂ s₃ (s₁ + s₂)(s₂ + s₃)(s₁ + s₃))`.
//!
//! No eigenvectors and no iteration. The cubic's roots carry absolute errors of about
//! ε·λ_max, so the result is trusted only while the condition number is at most
//! [`MAX_CONDITION`]; beyond it the eigen-decomposition gives it.

use nalgebra::Matrix3;

/// Largest `λ_max / λ_min` trusted: the whitening error grows as about 20 ε·λ_max/λ_min (4 × 10⁻¹¹
/// at 5700), and 100 keeps it near 10⁻¹³ while covering every frame outside a strong field (a
/// static observer's radial axis is stretched by `1/(1 − 2M/r)`: 100 at r = 2.02 M).
pub const MAX_CONDITION: f64 = 100.0;

/// `S^{-1/2}` of the symmetric matrix `s`, or `None` where `s` is not positive definite or not
/// finite: in closed form, or by the eigen-decomposition where the closed form cannot be
/// trusted (ill-conditioned, as deep in a strong field).
pub fn inverse_square_root(s: &Matrix3<f64>) -> Option<Matrix3<f64>> {
    closed_form(s).or_else(|| {
        let eig = nalgebra::SymmetricEigen::new(*s);
        eig.eigenvalues.iter().all(|&l| l > 0.0).then(|| {
            eig.eigenvectors
                * Matrix3::from_diagonal(&eig.eigenvalues.map(|l| 1.0 / l.sqrt()))
                * eig.eigenvectors.transpose()
        })
    })
}

/// `S^{-1/2}` in closed form, or `None` where it cannot be trusted: `s` not positive definite,
/// not finite, or with a condition number above [`MAX_CONDITION`].
fn closed_form(s: &Matrix3<f64>) -> Option<Matrix3<f64>> {
    let [l1, l2, l3] = eigenvalues(s)?;
    if !(l3 > 0.0 && l1 <= MAX_CONDITION * l3) {
        return None;
    }
    let [s1, s2, s3] = [l1.sqrt(), l2.sqrt(), l3.sqrt()];
    let f1 = 1.0 / s1;
    let f12 = -1.0 / (s1 * s2 * (s1 + s2));
    let f123 = (s1 + s2 + s3) / (s1 * s2 * s3 * (s1 + s2) * (s2 + s3) * (s1 + s3));
    let identity = Matrix3::identity();
    let a = s - identity * l1;
    let b = s - identity * l2;
    Some(identity * f1 + a * f12 + a * b * f123)
}

/// The eigenvalues of the symmetric matrix `s`, largest first (Smith 1961): with `q = tr S / 3`
/// and `p² = ‖S − qI‖²_F / 6`, the roots of the characteristic cubic are
/// `q + 2p cos(φ + 2πk/3)`, `cos 3φ = det((S − qI)/p) / 2`.
fn eigenvalues(s: &Matrix3<f64>) -> Option<[f64; 3]> {
    if !s.iter().all(|v| v.is_finite()) {
        return None;
    }
    let q = s.trace() / 3.0;
    let off = s[(0, 1)] * s[(0, 1)] + s[(0, 2)] * s[(0, 2)] + s[(1, 2)] * s[(1, 2)];
    let diagonal = (s[(0, 0)] - q).powi(2) + (s[(1, 1)] - q).powi(2) + (s[(2, 2)] - q).powi(2);
    let p2 = (diagonal + 2.0 * off) / 6.0;
    if p2 == 0.0 {
        return Some([q; 3]);
    }
    let p = p2.sqrt();
    let b = (s - Matrix3::identity() * q) / p;
    let phi = (b.determinant() / 2.0).clamp(-1.0, 1.0).acos() / 3.0;
    let largest = q + 2.0 * p * phi.cos();
    let smallest = q + 2.0 * p * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos();
    Some([largest, 3.0 * q - largest - smallest, smallest])
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A symmetric matrix with eigenvalues `lambda` and eigenvectors the rotation by `angles`.
    fn with_eigenvalues(lambda: [f64; 3], angles: [f64; 3]) -> Matrix3<f64> {
        let r = nalgebra::Rotation3::from_euler_angles(angles[0], angles[1], angles[2]).into_inner();
        r * Matrix3::from_diagonal(&nalgebra::Vector3::from(lambda)) * r.transpose()
    }

    /// `‖X S X − I‖` for the claimed `X = S^{-1/2}`, largest entry.
    fn whitening_error(s: &Matrix3<f64>, x: &Matrix3<f64>) -> f64 {
        (x * s * x - Matrix3::identity()).abs().max()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Random spectra up to the trusted condition number, random orientations: the result
        /// whitens `S`, is symmetric, and matches the eigen-decomposition.
        #[test]
        fn whitens_and_matches_the_eigen_decomposition(
            scale in -3.0f64..3.0, spread in [0.0f64..1.0, 0.0f64..1.0],
            angles in [0.0f64..6.3, 0.0f64..6.3, 0.0f64..6.3],
        ) {
            let log_kappa = MAX_CONDITION.log10();
            let lambda = [0.0, spread[0] * log_kappa, spread[1] * log_kappa].map(|e| 10f64.powf(scale + e));
            let s = with_eigenvalues(lambda, angles);
            let x = closed_form(&s).expect("within the trusted condition number");
            prop_assert!(whitening_error(&s, &x) < 1e-12, "{lambda:?}: {}", whitening_error(&s, &x));
            prop_assert!((x - x.transpose()).abs().max() < 1e-12 * x.abs().max());
            let eig = nalgebra::SymmetricEigen::new(s);
            let reference = eig.eigenvectors
                * Matrix3::from_diagonal(&eig.eigenvalues.map(|l| 1.0 / l.sqrt()))
                * eig.eigenvectors.transpose();
            prop_assert!((x - reference).abs().max() < 1e-12 * reference.abs().max());
        }
    }

    #[test]
    fn repeated_eigenvalues_are_exact() {
        let identity = Matrix3::identity();
        assert_eq!(closed_form(&(identity * 4.0)), Some(identity * 0.5));
        for lambda in [[2.0, 2.0, 0.5], [3.0, 1.0, 1.0], [1.0 + 1e-9, 1.0, 1.0 - 1e-9]] {
            let s = with_eigenvalues(lambda, [0.3, 1.1, -0.4]);
            let x = closed_form(&s).unwrap();
            assert!(whitening_error(&s, &x) < 1e-13, "{lambda:?}: {}", whitening_error(&s, &x));
        }
    }

    #[test]
    fn refuses_what_it_cannot_trust() {
        let s = |lambda| with_eigenvalues(lambda, [0.2, 0.5, 0.9]);
        assert_eq!(closed_form(&s([1.0, 1.0, -0.1])), None, "indefinite");
        assert_eq!(closed_form(&s([1.0, 1.0, 0.0])), None, "singular");
        assert_eq!(closed_form(&s([1.0, 1.0, 0.5 / MAX_CONDITION])), None, "ill-conditioned");
        assert_eq!(closed_form(&(Matrix3::identity() * f64::NAN)), None);
    }
}
