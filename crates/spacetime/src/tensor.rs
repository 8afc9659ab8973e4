//! Components of 4-vectors, covectors and symmetric rank-2 tensors in a coordinate basis.
//!
//! Plain arrays keep the hot loops transparent to the optimiser; the names say which index
//! position a value has.

/// Contravariant components `v^μ`.
pub type Vector4 = [f64; 4];
/// Covariant components `p_μ`.
pub type Covector4 = [f64; 4];
/// A rank-2 tensor's components `T_{μν}` or `T^{μν}` (symmetric where it is a metric).
pub type Matrix4 = [[f64; 4]; 4];

/// Minkowski metric η = diag(−1, 1, 1, 1); it is its own inverse.
pub const ETA: Matrix4 = [[-1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]];

/// `T^{μν} p_ν` (raise with an inverse metric) or `T_{μν} v^ν` (lower with a metric).
#[inline]
pub fn contract(t: &Matrix4, v: &[f64; 4]) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (o, row) in out.iter_mut().zip(t) {
        *o = row[0] * v[0] + row[1] * v[1] + row[2] * v[2] + row[3] * v[3];
    }
    out
}

/// `T(a, b) = T_{μν} a^μ b^ν`.
#[inline]
pub fn quadratic(t: &Matrix4, a: &[f64; 4], b: &[f64; 4]) -> f64 {
    dot(a, &contract(t, b))
}

/// Plain component sum `a_μ b^μ`.
#[inline]
pub fn dot(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

/// Inverse of a 4×4 matrix, `None` when singular or not finite.
pub fn invert(m: &Matrix4) -> Option<Matrix4> {
    let inv = nalgebra::Matrix4::from_fn(|i, j| m[i][j]).try_inverse()?;
    let out: Matrix4 = std::array::from_fn(|i| std::array::from_fn(|j| inv[(i, j)]));
    out.iter().flatten().all(|v| v.is_finite()).then_some(out)
}

/// Spatial part `[v^1, v^2, v^3]`.
#[inline]
pub fn spatial(v: &[f64; 4]) -> [f64; 3] {
    [v[1], v[2], v[3]]
}

#[inline]
pub fn norm3(v: &[f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

#[inline]
pub fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub fn cross3(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `a − b`.
#[inline]
pub fn sub3(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
pub fn scale3(a: &[f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a / |a|`; the zero vector stays zero.
#[inline]
pub fn normalize3(a: &[f64; 3]) -> [f64; 3] {
    let n = norm3(a);
    if n > 0.0 {
        scale3(a, 1.0 / n)
    } else {
        *a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_of_a_boosted_metric() {
        let m = [[-2.0, 0.3, 0.0, 0.1], [0.3, 1.5, 0.2, 0.0], [0.0, 0.2, 1.0, 0.0], [0.1, 0.0, 0.0, 3.0]];
        let inv = invert(&m).unwrap();
        for i in 0..4 {
            let row = contract(&inv, &[m[0][i], m[1][i], m[2][i], m[3][i]]);
            for (j, v) in row.iter().enumerate() {
                let expect = if i == j { 1.0 } else { 0.0 };
                assert!((v - expect).abs() < 1e-14);
            }
        }
        assert!(invert(&[[0.0; 4]; 4]).is_none());
    }
}
