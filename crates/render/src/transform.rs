//! Affine object-to-world maps.
//!
//! A [`Transform`] carries the forward map and its inverse side by side, each built exactly from
//! its factors (the inverse of a scale is the reciprocal scale, of a rotation its transpose), so
//! that shapes can intersect rays in object space without inverting matrices numerically and
//! without accumulating inversion error across compositions (pbrt-v4 §3.9 makes the same choice).
//!
//! # Order of composition
//!
//! `a.then(&b)` applies `a` first and `b` second; `b * a` is the same map written as a matrix
//! product. Scene files list `translate`, `rotate`, `scale`, and the map they mean is the
//! conventional `T·R·S`: scale about the object's origin, then rotate, then translate:
//!
//! ```
//! # use render::transform::Transform;
//! # use render::geometry::Vec3;
//! let s = Transform::scale(Vec3::new(2.0, 1.0, 1.0))?;
//! let r = Transform::rotate_deg(Vec3::Z, 90.0)?;
//! let t = Transform::translate(Vec3::new(0.0, 0.0, 5.0));
//! let object_to_world = s.then(&r).then(&t); // == t * r * s
//! assert!((object_to_world.point(Vec3::X) - Vec3::new(0.0, 2.0, 5.0)).length() < 1e-12);
//! # Ok::<(), render::transform::TransformError>(())
//! ```

use crate::geometry::{Aabb, Vec3};
use glam::{DAffine3, DMat3};
use std::fmt;
use std::ops::Mul;

/// Why a transform could not be built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TransformError {
    /// A scale factor is NaN or infinite.
    NonFiniteScale(Vec3),
    /// A scale factor is zero: the map would flatten space and have no inverse.
    ZeroScale(Vec3),
    /// The rotation axis is zero, NaN or infinite.
    InvalidAxis(Vec3),
    /// The rotation angle is NaN or infinite.
    NonFiniteAngle(f64),
    /// A general affine map is not finite or not invertible.
    Singular,
}

impl fmt::Display for TransformError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFiniteScale(s) => write!(f, "scale factors must be finite, got {s}"),
            Self::ZeroScale(s) => write!(f, "scale factors must be non-zero, got {s}"),
            Self::InvalidAxis(a) => {
                write!(f, "rotation axis must be a finite non-zero vector, got {a}")
            }
            Self::NonFiniteAngle(d) => write!(f, "rotation angle must be finite, got {d} degrees"),
            Self::Singular => write!(f, "transform is not finite or not invertible"),
        }
    }
}

impl std::error::Error for TransformError {}

/// An invertible affine map from object space to world space, with its inverse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    to_world: DAffine3,
    to_object: DAffine3,
}

impl Default for Transform {
    fn default() -> Self {
        Self::identity()
    }
}

impl Transform {
    pub const IDENTITY: Transform = Transform { to_world: DAffine3::IDENTITY, to_object: DAffine3::IDENTITY };

    pub fn identity() -> Self {
        Self::IDENTITY
    }

    /// Translation by `offset`. Infallible: the caller validates that `offset` is finite (shape
    /// constructors reject transforms that are not, see [`Transform::is_finite`]).
    pub fn translate(offset: Vec3) -> Self {
        Self { to_world: DAffine3::from_translation(offset), to_object: DAffine3::from_translation(-offset) }
    }

    /// Scale by `factors` along the object axes. Negative factors mirror (see
    /// [`Transform::swaps_handedness`]); zero or non-finite ones are rejected because the map
    /// would have no inverse.
    pub fn scale(factors: Vec3) -> Result<Self, TransformError> {
        if !factors.is_finite() {
            return Err(TransformError::NonFiniteScale(factors));
        }
        if factors.cmpeq(Vec3::ZERO).any() {
            return Err(TransformError::ZeroScale(factors));
        }
        Ok(Self { to_world: DAffine3::from_scale(factors), to_object: DAffine3::from_scale(factors.recip()) })
    }

    /// Right-handed rotation by `degrees` about `axis` (any finite non-zero length). Multiples of
    /// 90° are exact, so axis-aligned scenes stay axis-aligned to the last bit.
    pub fn rotate_deg(axis: Vec3, degrees: f64) -> Result<Self, TransformError> {
        let length = axis.length();
        if !(length.is_finite() && length > 0.0) {
            return Err(TransformError::InvalidAxis(axis));
        }
        if !degrees.is_finite() {
            return Err(TransformError::NonFiniteAngle(degrees));
        }
        let k = axis / length;
        let (sin, cos) = sin_cos_deg(degrees);
        // Rodrigues' formula R = cos·I + sin·[k]ₓ + (1 − cos)·k·kᵀ, column by column.
        let cross = DMat3::from_cols(Vec3::new(0.0, k.z, -k.y), Vec3::new(-k.z, 0.0, k.x), Vec3::new(k.y, -k.x, 0.0));
        let outer = DMat3::from_cols(k * k.x, k * k.y, k * k.z);
        let rotation = DMat3::IDENTITY * cos + cross * sin + outer * (1.0 - cos);
        Ok(Self { to_world: DAffine3::from_mat3(rotation), to_object: DAffine3::from_mat3(rotation.transpose()) })
    }

    /// Any affine map; its inverse is computed numerically. Rejects maps that are not finite or
    /// whose inverse is not.
    pub fn from_affine(to_world: DAffine3) -> Result<Self, TransformError> {
        let det = to_world.matrix3.determinant();
        if !to_world.is_finite() || det == 0.0 || !det.is_finite() {
            return Err(TransformError::Singular);
        }
        let to_object = to_world.inverse();
        if !to_object.is_finite() {
            return Err(TransformError::Singular);
        }
        Ok(Self { to_world, to_object })
    }

    /// The map that applies `self` first and `next` second (`next * self`).
    pub fn then(&self, next: &Transform) -> Transform {
        Transform { to_world: next.to_world * self.to_world, to_object: self.to_object * next.to_object }
    }

    /// The world-to-object map as a transform of its own.
    pub fn inverse(&self) -> Transform {
        Transform { to_world: self.to_object, to_object: self.to_world }
    }

    /// Maps an object-space point to world space.
    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        self.to_world.transform_point3(p)
    }

    /// Maps an object-space direction (or displacement) to world space; not renormalised.
    #[inline]
    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.to_world.matrix3 * v
    }

    /// Maps an object-space surface normal to world space with the inverse transpose, which keeps
    /// it perpendicular to transformed tangents under non-uniform scale. Not renormalised.
    #[inline]
    pub fn normal(&self, n: Vec3) -> Vec3 {
        // (M⁻¹)ᵀ·n, with component i = (column i of M⁻¹)·n: no transpose is materialised.
        let m = &self.to_object.matrix3;
        Vec3::new(m.x_axis.dot(n), m.y_axis.dot(n), m.z_axis.dot(n))
    }

    /// Maps a world-space point to object space.
    #[inline]
    pub fn inverse_point(&self, p: Vec3) -> Vec3 {
        self.to_object.transform_point3(p)
    }

    /// Maps a world-space direction to object space; not renormalised, which is what keeps the
    /// ray parameter `t` equal in both spaces.
    #[inline]
    pub fn inverse_vector(&self, v: Vec3) -> Vec3 {
        self.to_object.matrix3 * v
    }

    /// The forward map.
    pub fn affine(&self) -> &DAffine3 {
        &self.to_world
    }

    /// The inverse map.
    pub fn inverse_affine(&self) -> &DAffine3 {
        &self.to_object
    }

    /// The linear part `M` of the forward map.
    pub fn linear(&self) -> DMat3 {
        self.to_world.matrix3
    }

    /// The normal matrix `(M⁻¹)ᵀ`.
    pub fn normal_matrix(&self) -> DMat3 {
        self.to_object.matrix3.transpose()
    }

    pub fn is_finite(&self) -> bool {
        self.to_world.is_finite() && self.to_object.is_finite()
    }

    /// True when the map mirrors (negative determinant): a triangle's winding, and therefore the
    /// side its cross-product normal points to, flips.
    pub fn swaps_handedness(&self) -> bool {
        self.to_world.matrix3.determinant() < 0.0
    }

    /// The smallest and largest factor by which the map stretches a length: the extreme singular
    /// values of `M`. Each comes from the largest eigenvalue of a symmetric matrix (`MᵀM`, and
    /// `M⁻ᵀM⁻¹` for the smallest), which the closed form below computes to full relative accuracy,
    /// unlike the smallest eigenvalue of `MᵀM` itself.
    pub fn scale_bounds(&self) -> (f64, f64) {
        let m = self.to_world.matrix3;
        let inv = self.to_object.matrix3;
        let largest = largest_eigenvalue_symmetric(m.transpose() * m).sqrt();
        let smallest = 1.0 / largest_eigenvalue_symmetric(inv.transpose() * inv).sqrt();
        (smallest, largest)
    }

    /// World bounds of an object-space box (Arvo 1990, "Transforming axis-aligned bounding
    /// boxes"): exact for the box's image, a parallelepiped. The box must be finite.
    pub fn bounds(&self, b: &Aabb) -> Aabb {
        if b.is_empty() {
            return Aabb::EMPTY;
        }
        let m = self.to_world.matrix3;
        let mut min = self.to_world.translation;
        let mut max = self.to_world.translation;
        for (j, col) in [m.x_axis, m.y_axis, m.z_axis].into_iter().enumerate() {
            let a = col * b.min[j];
            let c = col * b.max[j];
            min += a.min(c);
            max += a.max(c);
        }
        Aabb { min, max }
    }
}

impl Mul for Transform {
    type Output = Transform;

    /// Matrix-style composition: `(a * b)` applies `b` first, then `a`.
    fn mul(self, rhs: Transform) -> Transform {
        rhs.then(&self)
    }
}

/// `(sin, cos)` of an angle in degrees, exact at multiples of 90°.
fn sin_cos_deg(degrees: f64) -> (f64, f64) {
    let reduced = degrees.rem_euclid(360.0);
    if reduced % 90.0 == 0.0 {
        // `reduced / 90` is an exact small integer here.
        match (reduced / 90.0) as u8 {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        reduced.to_radians().sin_cos()
    }
}

/// Largest eigenvalue of a symmetric 3×3 matrix by the trigonometric closed form (Smith 1961,
/// "Eigenvalues of a symmetric 3 × 3 matrix", Commun. ACM 4(4)).
fn largest_eigenvalue_symmetric(a: DMat3) -> f64 {
    let (a11, a22, a33) = (a.x_axis.x, a.y_axis.y, a.z_axis.z);
    let (a12, a13, a23) = (a.y_axis.x, a.z_axis.x, a.z_axis.y);
    let off = a12 * a12 + a13 * a13 + a23 * a23;
    if off == 0.0 {
        return a11.max(a22).max(a33);
    }
    let q = (a11 + a22 + a33) / 3.0;
    let p2 = (a11 - q).powi(2) + (a22 - q).powi(2) + (a33 - q).powi(2) + 2.0 * off;
    let p = (p2 / 6.0).sqrt();
    let b = (a - DMat3::IDENTITY * q) * (1.0 / p);
    let r = (b.determinant() / 2.0).clamp(-1.0, 1.0);
    q + 2.0 * p * (r.acos() / 3.0).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn scene_order_is_scale_then_rotate_then_translate() {
        let s = Transform::scale(Vec3::new(2.0, 3.0, 4.0)).unwrap();
        let r = Transform::rotate_deg(Vec3::Z, 90.0).unwrap();
        let t = Transform::translate(Vec3::new(10.0, 0.0, 0.0));
        let trs = s.then(&r).then(&t);
        assert_eq!(trs, t * r * s);
        // (1,1,1) -scale-> (2,3,4) -rotate z 90°-> (-3,2,4) -translate-> (7,2,4).
        assert!(close(trs.point(Vec3::ONE), Vec3::new(7.0, 2.0, 4.0)));
        assert!(close(trs.vector(Vec3::ONE), Vec3::new(-3.0, 2.0, 4.0)), "no translation");
        assert!(close(trs.inverse_point(Vec3::new(7.0, 2.0, 4.0)), Vec3::ONE));
        assert!(close(trs.inverse().point(Vec3::new(7.0, 2.0, 4.0)), Vec3::ONE));
    }

    #[test]
    fn right_angles_are_exact_and_rotation_is_right_handed() {
        let r = Transform::rotate_deg(Vec3::Z, 90.0).unwrap();
        assert_eq!(r.vector(Vec3::X), Vec3::Y);
        assert_eq!(Transform::rotate_deg(Vec3::X, -270.0).unwrap().vector(Vec3::Y), Vec3::Z);
        let r = Transform::rotate_deg(Vec3::new(1.0, 1.0, 1.0), 120.0).unwrap();
        assert!(close(r.vector(Vec3::X), Vec3::Y), "a third of a turn about the diagonal");
        assert!(close(r.then(&r.inverse()).point(Vec3::new(0.3, -2.0, 5.0)), Vec3::new(0.3, -2.0, 5.0)));
    }

    #[test]
    fn normals_stay_perpendicular_under_non_uniform_scale() {
        let m = Transform::scale(Vec3::new(1.0, 5.0, 0.5))
            .unwrap()
            .then(&Transform::rotate_deg(Vec3::new(0.2, 1.0, -0.4), 33.0).unwrap());
        let n = Vec3::new(1.0, 1.0, 0.0).normalize();
        let tangent = Vec3::new(1.0, -1.0, 0.3);
        assert!(m.normal(n).dot(m.vector(tangent)).abs() < 1e-12);
        assert!((m.normal_matrix() * n - m.normal(n)).length() < 1e-12);
    }

    #[test]
    fn invalid_parameters_are_rejected() {
        assert_eq!(
            Transform::scale(Vec3::new(1.0, 0.0, 1.0)),
            Err(TransformError::ZeroScale(Vec3::new(1.0, 0.0, 1.0)))
        );
        assert!(matches!(Transform::scale(Vec3::new(1.0, f64::NAN, 1.0)), Err(TransformError::NonFiniteScale(_))));
        assert!(matches!(Transform::rotate_deg(Vec3::ZERO, 10.0), Err(TransformError::InvalidAxis(_))));
        assert!(matches!(Transform::rotate_deg(Vec3::X, f64::INFINITY), Err(TransformError::NonFiniteAngle(_))));
        assert_eq!(Transform::from_affine(DAffine3::from_scale(Vec3::ZERO)), Err(TransformError::Singular));
        assert!(TransformError::ZeroScale(Vec3::ZERO).to_string().contains("non-zero"));
    }

    #[test]
    fn scale_bounds_are_the_extreme_singular_values() {
        let s = Transform::scale(Vec3::new(-3.0, 0.5, 2.0)).unwrap();
        let m = s.then(&Transform::rotate_deg(Vec3::new(1.0, 2.0, 3.0), 71.0).unwrap());
        let (lo, hi) = m.scale_bounds();
        assert!((lo - 0.5).abs() < 1e-12 && (hi - 3.0).abs() < 1e-12, "{lo} {hi}");
        assert!(m.swaps_handedness() && !Transform::IDENTITY.swaps_handedness());
        // A shear: compare with the stretch of many directions.
        let shear = Transform::from_affine(DAffine3::from_mat3(DMat3::from_cols(
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(0.0, 0.5, 1.0),
        )))
        .unwrap();
        let (lo, hi) = shear.scale_bounds();
        let mut rng = crate::sampling::Rng::new(1);
        for _ in 0..10_000 {
            let v = crate::sampling::uniform_sphere(rng.next_2d());
            let stretch = shear.vector(v).length();
            assert!(stretch >= lo * (1.0 - 1e-12) && stretch <= hi * (1.0 + 1e-12));
        }
    }

    #[test]
    fn transformed_box_bounds_its_corners_tightly() {
        let m = Transform::rotate_deg(Vec3::new(1.0, -1.0, 0.5), 40.0)
            .unwrap()
            .then(&Transform::translate(Vec3::new(1.0, 2.0, 3.0)));
        let b = Aabb::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(0.5, 3.0, 2.5));
        let wb = m.bounds(&b);
        let mut tight = Aabb::EMPTY;
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            tight = tight.grow(m.point(c));
        }
        assert!(close(wb.min, tight.min) && close(wb.max, tight.max));
    }
}
