//! Ray–quadric roots that stay accurate for grazing rays and for rays that start far away.
//!
//! The textbook discriminant `b² − 4ac` cancels catastrophically when the ray passes close to the
//! quadric's silhouette or starts far from it. Haines, Günther and Akenine-Möller (2019),
//! "Precision improvements for ray/sphere intersection" (Ray Tracing Gems, ch. 7), rewrite it as
//! `a·(r² − |l|²)`, where `l` is the offset from the centre to the point of the line closest to it,
//! and take the smaller-magnitude root as `c / q` to avoid the second cancellation (Press et al.,
//! Numerical Recipes §5.6). pbrt-v4 §6.2.2 uses the same formulation.

use crate::geometry::Vec3;

/// The entry and exit distances `(t0, t1)`, `t0 ≤ t1`, of the line `f + t·d` through the ball or
/// (for vectors with their axial component dropped) the infinite cylinder of radius² `r2` centred
/// at the origin; `None` when the line misses it. `d` need not be unit length.
#[inline]
pub(super) fn centred_roots(f: Vec3, d: Vec3, r2: f64) -> Option<(f64, f64)> {
    let a = d.length_squared();
    if a == 0.0 {
        return None;
    }
    let b = f.dot(d); // half of the usual b
    let c = f.length_squared() - r2;
    let l = f - d * (b / a);
    let discriminant = a * (r2 - l.length_squared());
    if discriminant < 0.0 {
        return None;
    }
    let q = -(b + discriminant.sqrt().copysign(b));
    if q == 0.0 {
        // b = 0 and a tangent line through the closest point: a single touching point.
        return (c == 0.0).then_some((0.0, 0.0));
    }
    let (t0, t1) = (c / q, q / a);
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

/// The nearest root in `(0, t_max]` of an entry/exit pair: the entry when it lies ahead, else the
/// exit (the ray starts inside).
#[inline]
pub(super) fn nearest_ahead((t0, t1): (f64, f64), t_max: f64) -> Option<f64> {
    let t = if t0 > 0.0 { t0 } else { t1 };
    (t > 0.0 && t <= t_max).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grazing_and_distant_rays_keep_their_precision() {
        // A unit sphere seen from 1e7 away: the textbook formula loses every digit here.
        let f = Vec3::new(-1e7, 0.0, 0.0);
        let (t0, t1) = centred_roots(f, Vec3::X, 1.0).unwrap();
        assert_eq!((t0, t1), (1e7 - 1.0, 1e7 + 1.0));
        // Lines at distance 1 ∓ 1e-10 from the centre: a hit and a miss.
        assert!(centred_roots(Vec3::new(-5.0, 1.0 - 1e-10, 0.0), Vec3::X, 1.0).is_some());
        assert!(centred_roots(Vec3::new(-5.0, 1.0 + 1e-10, 0.0), Vec3::X, 1.0).is_none());
        // The chord of a near-tangent line: 2·sqrt(1 − y²).
        let y: f64 = 1.0 - 1e-8;
        let (t0, t1) = centred_roots(Vec3::new(-5.0, y, 0.0), Vec3::X, 1.0).unwrap();
        let chord = 2.0 * (1.0 - y * y).sqrt();
        assert!(((t1 - t0) / chord - 1.0).abs() < 1e-7);
    }

    #[test]
    fn unnormalised_directions_scale_t() {
        let (t0, t1) = centred_roots(Vec3::new(-3.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0), 1.0).unwrap();
        assert_eq!((t0, t1), (1.0, 2.0));
        assert_eq!(nearest_ahead((t0, t1), 10.0), Some(1.0));
        assert_eq!(nearest_ahead((-1.0, 2.0), 10.0), Some(2.0), "from inside");
        assert_eq!(nearest_ahead((-2.0, -1.0), 10.0), None, "behind");
        assert_eq!(nearest_ahead((3.0, 4.0), 2.5), None, "beyond the segment");
    }
}
