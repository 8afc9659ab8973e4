//! Small scenes and a seeded random stream shared by the crate's unit tests.

use crate::geometry::Vec3;
use crate::material::Material;
use crate::rgb::Rgb;
use crate::shape::Shape;
use crate::sky::Sky;
use crate::texture::Texture;
use crate::transform::Transform;
use crate::world::{Emission, Object, World};

/// The black-hole room's walls, all facing in (a box 12 × 8 × 16 about the origin).
pub const ROOM: [[[f64; 3]; 3]; 6] = [
    [[-6.0, -4.0, -8.0], [12.0, 0.0, 0.0], [0.0, 8.0, 0.0]],
    [[-6.0, -4.0, 8.0], [12.0, 0.0, 0.0], [0.0, 0.0, -16.0]],
    [[-6.0, 4.0, -8.0], [12.0, 0.0, 0.0], [0.0, 0.0, 16.0]],
    [[-6.0, -4.0, 8.0], [0.0, 0.0, -16.0], [0.0, 8.0, 0.0]],
    [[6.0, -4.0, -8.0], [0.0, 0.0, 16.0], [0.0, 8.0, 0.0]],
    [[6.0, -4.0, 8.0], [-12.0, 0.0, 0.0], [0.0, 8.0, 0.0]],
];

/// A floor and a ceiling lamp round a hole of mass 0.3 at the origin, with a flat board and a
/// ball in the way of some rays (objects 0 to 3 in that order).
pub fn floor_lamp_board_ball() -> World {
    let t = Transform::identity();
    let rectangle = |corner: [f64; 3], u: [f64; 3], v: [f64; 3]| {
        Shape::rectangle(Vec3::from_array(corner), Vec3::from_array(u), Vec3::from_array(v), &t).unwrap()
    };
    let object = |shape: Shape, emission: Option<Emission>| Object { shape, material: 0, emission };
    let lamp = Emission::uniform(Rgb::ONE, false);
    let objects = vec![
        object(rectangle([-6.0, -4.0, 8.0], [12.0, 0.0, 0.0], [0.0, 0.0, -16.0]), None),
        object(rectangle([-2.5, 3.98, -2.5], [5.0, 0.0, 0.0], [0.0, 0.0, 5.0]), Some(lamp)),
        object(rectangle([1.0, 0.0, 2.0], [3.0, 0.0, 0.0], [0.0, 0.0, -4.0]), None),
        object(Shape::sphere(Vec3::new(-3.0, -2.0, 3.0), 1.0, &t).unwrap(), None),
    ];
    let black = || Sky::Constant(Rgb::ZERO);
    let materials = vec![Material::Diffuse { reflectance: Texture::from(Rgb::splat(0.5)) }];
    World::new(materials, (objects, black()), (Vec::new(), black()))
}

/// Diffuse rectangles `[corner, edge_u, edge_v]` (facing `edge_u × edge_v`) under a black sky.
pub fn rectangles(shapes: &[[[f64; 3]; 3]]) -> World {
    let t = Transform::identity();
    let objects = shapes
        .iter()
        .map(|[corner, u, v]| Object {
            shape: Shape::rectangle(Vec3::from_array(*corner), Vec3::from_array(*u), Vec3::from_array(*v), &t).unwrap(),
            material: 0,
            emission: None,
        })
        .collect();
    let black = || Sky::Constant(Rgb::ZERO);
    let materials = vec![Material::Diffuse { reflectance: Texture::from(Rgb::splat(0.5)) }];
    World::new(materials, (objects, black()), (Vec::new(), black()))
}

/// A reproducible stream of uniform numbers in `[0, 1)` (a 64-bit LCG's high bits).
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}
