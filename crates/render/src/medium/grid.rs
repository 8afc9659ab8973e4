//! A scalar field sampled on a regular 3-D grid (densities, temperatures), read between its
//! samples by trilinear interpolation.
//!
//! Sample `(i, j, k)` sits at the centre of voxel `(i, j, k)` of the box `bounds` (in the
//! medium's object space) divided into `dims` voxels, as in pbrt-v4's `SampledGrid`; the field
//! is 0 outside the box and, between the outermost sample centres and the box's faces, the
//! value of the nearest face's samples. Values are stored `x` fastest: sample `(i, j, k)` is
//! `values[i + nx (j + ny k)]`.

use crate::geometry::{Aabb, Vec3};
use crate::transform::Transform;
use glam::DAffine3;
use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    dims: [usize; 3],
    values: Vec<f32>,
    /// World space to the unit cube `[0, 1]³` the box maps onto.
    world_to_unit: DAffine3,
    /// The largest sample: no interpolated value exceeds it.
    max: f32,
}

/// Why a grid could not be made.
#[derive(Clone, Debug, PartialEq)]
pub enum GridError {
    /// A dimension is 0.
    EmptyDimension([usize; 3]),
    /// `values` does not hold `nx·ny·nz` samples.
    WrongLength { dims: [usize; 3], len: usize },
    /// A sample is NaN, infinite or negative (the index is `values`').
    InvalidSample { index: usize, value: f32 },
    /// The box is empty, flat or not finite.
    InvalidBounds,
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::EmptyDimension(d) => write!(f, "the grid's dimensions {d:?} include 0"),
            Self::WrongLength { dims, len } => write!(f, "{len} samples for a grid of dimensions {dims:?}"),
            Self::InvalidSample { index, value } => {
                write!(f, "sample {index} is {value}, and samples must be finite and not negative")
            }
            Self::InvalidBounds => write!(f, "the grid's bounds must be a finite box of positive volume"),
        }
    }
}

impl std::error::Error for GridError {}

impl Grid {
    /// The grid of `dims` samples `values` (`x` fastest) over the box `bounds` of object space,
    /// placed in the world by `object_to_world`. Samples must be finite and not negative.
    pub fn new(
        dims: [usize; 3],
        values: Vec<f32>,
        bounds: Aabb,
        object_to_world: &Transform,
    ) -> Result<Self, GridError> {
        if dims.contains(&0) {
            return Err(GridError::EmptyDimension(dims));
        }
        if dims.iter().try_fold(1usize, |n, &d| n.checked_mul(d)) != Some(values.len()) {
            return Err(GridError::WrongLength { dims, len: values.len() });
        }
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !(v.is_finite() && **v >= 0.0)) {
            return Err(GridError::InvalidSample { index, value });
        }
        let size = bounds.diagonal();
        if !(bounds.min.is_finite() && size.is_finite() && size.min_element() > 0.0) {
            return Err(GridError::InvalidBounds);
        }
        let object_to_unit = DAffine3::from_scale(size.recip()) * DAffine3::from_translation(-bounds.min);
        let world_to_unit = object_to_unit * *object_to_world.inverse_affine();
        let max = values.iter().copied().fold(0.0, f32::max);
        Ok(Self { dims, values, world_to_unit, max })
    }

    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The largest sample, hence the largest value anywhere.
    pub fn max(&self) -> f64 {
        f64::from(self.max)
    }

    /// World space to the unit cube of the grid's box.
    pub fn world_to_unit(&self) -> &DAffine3 {
        &self.world_to_unit
    }

    /// Sample `(i, j, k)`, its indices clamped into the grid.
    pub fn sample(&self, [i, j, k]: [isize; 3]) -> f64 {
        let clamp = |v: isize, n: usize| v.clamp(0, n as isize - 1) as usize;
        let [nx, ny, nz] = self.dims;
        let (i, j, k) = (clamp(i, nx), clamp(j, ny), clamp(k, nz));
        f64::from(self.values[i + nx * (j + ny * k)])
    }

    /// The field at the world point `p`: trilinear between the sample centres, 0 outside the box.
    pub fn at(&self, p: Vec3) -> f64 {
        let unit = self.world_to_unit.transform_point3(p);
        if !(unit.cmpge(Vec3::ZERO).all() && unit.cmple(Vec3::ONE).all()) {
            return 0.0;
        }
        self.at_unit(unit)
    }

    /// The field at a point of the unit cube.
    fn at_unit(&self, unit: Vec3) -> f64 {
        let dims = Vec3::new(self.dims[0] as f64, self.dims[1] as f64, self.dims[2] as f64);
        // Continuous sample coordinates: sample i's centre is at i + ½ voxels.
        let q = unit * dims - Vec3::splat(0.5);
        let base = q.floor();
        let f = q - base;
        let [i, j, k] = [base.x as isize, base.y as isize, base.z as isize];
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let along_x =
            |dj: isize, dk: isize| lerp(self.sample([i, j + dj, k + dk]), self.sample([i + 1, j + dj, k + dk]), f.x);
        let along_y = |dk: isize| lerp(along_x(0, dk), along_x(1, dk), f.y);
        lerp(along_y(0), along_y(1), f.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Aabb {
        Aabb::new(Vec3::ZERO, Vec3::ONE)
    }

    #[test]
    fn samples_are_read_at_voxel_centres_and_blended_between_them() {
        // 2×1×1: sample 0 = 1 at x = ¼, sample 1 = 3 at x = ¾.
        let grid = Grid::new([2, 1, 1], vec![1.0, 3.0], unit_box(), &Transform::IDENTITY).unwrap();
        assert_eq!(grid.at(Vec3::new(0.25, 0.5, 0.5)), 1.0);
        assert_eq!(grid.at(Vec3::new(0.75, 0.1, 0.9)), 3.0);
        assert_eq!(grid.at(Vec3::new(0.5, 0.5, 0.5)), 2.0);
        assert_eq!(grid.at(Vec3::new(0.05, 0.5, 0.5)), 1.0, "clamped at the face");
        assert_eq!(grid.at(Vec3::new(1.01, 0.5, 0.5)), 0.0, "outside");
        assert_eq!(grid.max(), 3.0);
    }

    #[test]
    fn the_layout_is_x_fastest_and_the_placement_moves_the_box() {
        // Sample (i, j, k) holds i + 10 j + 100 k.
        let values = (0..2 * 3 * 4).map(|n| (n % 2 + 10 * ((n / 2) % 3) + 100 * (n / 6)) as f32).collect();
        let bounds = Aabb::new(Vec3::ZERO, Vec3::new(2.0, 3.0, 4.0));
        let placement = Transform::translate(Vec3::new(10.0, 0.0, 0.0));
        let grid = Grid::new([2, 3, 4], values, bounds, &placement).unwrap();
        // Voxel (1, 2, 3)'s centre is (1.5, 2.5, 3.5) in the box, 10 along x in the world.
        assert_eq!(grid.at(Vec3::new(11.5, 2.5, 3.5)), 321.0);
        assert_eq!(grid.at(Vec3::new(1.5, 2.5, 3.5)), 0.0);
    }

    #[test]
    fn refuses_what_is_no_grid() {
        let id = &Transform::IDENTITY;
        assert_eq!(Grid::new([0, 1, 1], vec![], unit_box(), id), Err(GridError::EmptyDimension([0, 1, 1])));
        assert!(matches!(Grid::new([2, 2, 2], vec![0.0; 7], unit_box(), id), Err(GridError::WrongLength { .. })));
        let nan = Grid::new([2, 1, 1], vec![1.0, f32::NAN], unit_box(), id);
        assert!(matches!(nan, Err(GridError::InvalidSample { index: 1, .. })));
        assert!(matches!(Grid::new([1, 1, 1], vec![-1.0], unit_box(), id), Err(GridError::InvalidSample { .. })));
        let flat = Aabb::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0));
        assert_eq!(Grid::new([1, 1, 1], vec![1.0], flat, id), Err(GridError::InvalidBounds));
    }
}
