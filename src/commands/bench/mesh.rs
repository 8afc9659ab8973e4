//! `nullpath bench mesh`: a scene of millions of triangles in curved spacetime. The poster's
//! room with its black hole gets a rock of a million triangles of its own (in the room's BVH
//! triangle by triangle) and a shelf of instances of a second million-triangle rock (one copy
//! of the triangles, each instance a transform): the time to build the BVHs, the memory a
//! triangle costs, and the rays per second of renders on one thread and on all.

use render::geometry::Vec3;
use render::material::Material;
use render::rgb::Rgb;
use render::scene::Scene;
use render::shape::{Instance, InstancedMesh, Shape, TriangleMesh};
use render::texture::Texture;
use render::transform::Transform;
use render::world::{Object, World};
use spacetime::Region;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;

/// Rows of the rocks' latitude–longitude grid; twice as many columns, so 4 ROWS² triangles.
const ROWS: u32 = 500;
/// Instances of the second rock.
const INSTANCES: usize = 12;

/// What building the mesh scene took.
pub struct Built {
    pub scene: Scene,
    /// Triangles stored once (the rock's and the instanced rock's).
    pub stored: usize,
    /// Triangles the renders see (the rock's and every instance's).
    pub rendered: usize,
    /// Seconds to build the world's BVH with the rock's triangles and the instanced mesh's BVH.
    pub bvh_seconds: f64,
    /// Resident memory the meshes and BVHs added, where the system says (Linux).
    pub bytes: Option<u64>,
}

/// A lumpy sphere of radius about `radius`, `4 ROWS²` triangles with smooth normals: a closed
/// latitude–longitude grid whose radius varies by a few percent.
fn rock(centre: Vec3, radius: f64, lumps: f64) -> TriangleMesh {
    let (rows, columns) = (ROWS, 2 * ROWS);
    let mut positions = Vec::with_capacity(((rows + 1) * columns) as usize);
    let mut normals = Vec::with_capacity(positions.capacity());
    for i in 0..=rows {
        let theta = PI * f64::from(i) / f64::from(rows);
        for j in 0..columns {
            let phi = 2.0 * PI * f64::from(j) / f64::from(columns);
            let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            let r = radius * (1.0 + 0.06 * (lumps * theta).sin() * (3.0 * phi).cos() + 0.02 * (17.0 * phi).sin());
            positions.push(centre + n * r);
            normals.push(n);
        }
    }
    let index = |i: u32, j: u32| i * columns + j % columns;
    let mut indices = Vec::with_capacity(2 * (rows * columns) as usize);
    for i in 0..rows {
        for j in 0..columns {
            let (a, b, c, d) = (index(i, j), index(i, j + 1), index(i + 1, j), index(i + 1, j + 1));
            indices.push([a, c, b]);
            indices.push([b, c, d]);
        }
    }
    // The grid's data is valid by construction.
    TriangleMesh::new(positions, Some(normals), None, indices).unwrap_or_else(|e| panic!("rock mesh: {e}"))
}

/// What the user's path took for a rock of a million triangles written as an OBJ file: the
/// scene file read as `nullpath render` reads it, and the image metadata it writes.
pub struct UserPath {
    pub triangles: usize,
    /// Seconds to load the scene: parse the OBJ, build the mesh, the world and its BVH.
    pub load_seconds: f64,
    /// Seconds for the metadata, whose sampling hash is the scene's whole identity.
    pub metadata_seconds: f64,
}

/// Writes the rock as an OBJ file beside a scene file naming it, in a fresh temporary folder,
/// then loads the scene and makes its metadata as `nullpath render` does. A step that grows
/// faster than the mesh on that path (the metadata's hash once printed the shared mesh once per
/// triangle) shows here, where building the world directly would skip it.
pub fn user_path() -> Result<UserPath, String> {
    let folder = std::env::temp_dir().join(format!("nullpath-bench-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    let result = load_written_rock(&folder);
    // The folder is this process's own; a failure to remove it leaves only a temporary file.
    let _ = std::fs::remove_dir_all(&folder);
    result
}

fn load_written_rock(folder: &std::path::Path) -> Result<UserPath, String> {
    let mesh = rock(Vec3::ZERO, 1.0, 5.0);
    let mut obj = String::with_capacity(64 * mesh.positions().len());
    for p in mesh.positions() {
        let _ = writeln!(obj, "v {} {} {}", p.x, p.y, p.z);
    }
    for [a, b, c] in mesh.indices() {
        let _ = writeln!(obj, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    let write = |name: &str, text: &str| {
        let path = folder.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))
    };
    write("rock.obj", &obj)?;
    write(
        "rock.toml",
        "[camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\n\n[render]\nwidth = 64\nheight = 48\nspp = 1\n\n\
         [materials.stone]\ntype = \"diffuse\"\nreflectance = 0.5\n\n\
         [[objects]]\nshape = { type = \"mesh\", file = \"rock.obj\" }\nmaterial = \"stone\"\n",
    )?;
    let scene_path = folder.join("rock.toml");
    let start = Instant::now();
    let scene = scene::load(&scene_path).map_err(|e| e.to_string())?;
    let load_seconds = start.elapsed().as_secs_f64();
    let source = crate::commands::provenance::Source {
        name: scene_path.display().to_string(),
        text: String::new(),
        view: None,
        time: 0.0,
    };
    let start = Instant::now();
    std::hint::black_box(crate::commands::provenance::scene_metadata(&scene, &source));
    let metadata_seconds = start.elapsed().as_secs_f64();
    Ok(UserPath { triangles: mesh.indices().len(), load_seconds, metadata_seconds })
}

/// Resident memory of this process, in bytes (Linux `/proc/self/statm`).
fn resident_bytes() -> Option<u64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4096)
}

/// `room` with the rock on its floor left of the hole and the instanced rocks along its back
/// wall.
pub fn build(room: Scene) -> Result<Built, String> {
    let before = resident_bytes();
    let mut materials = room.world.materials.clone();
    materials.push(Material::Diffuse { reflectance: Texture::from(Rgb::new(0.55, 0.45, 0.35)) });
    let stone = materials.len() - 1;
    let shapes = TriangleMesh::shapes(&Arc::new(rock(Vec3::new(-3.2, -3.1, -2.0), 0.9, 5.0)));
    let small = rock(Vec3::ZERO, 0.35, 9.0);
    let start = Instant::now();
    let shelf = Arc::new(InstancedMesh::new(small).ok_or("the instanced rock has no triangles")?);
    let mut objects: Vec<Object> = room.world.objects(Region::Upper).to_vec();
    let stored = shapes.len() + shelf.triangle_count();
    objects.extend(shapes.into_iter().map(|shape| Object { shape, material: stone, emission: None }));
    for k in 0..INSTANCES {
        let x = -5.0 + 10.0 * k as f64 / (INSTANCES - 1) as f64;
        let turn = Transform::rotate_deg(Vec3::Y, 37.0 * k as f64).map_err(|e| e.to_string())?;
        let at = turn.then(&Transform::translate(Vec3::new(x, -3.6, -7.4)));
        let instance = Instance::new(Arc::clone(&shelf), &at).map_err(|e| e.to_string())?;
        objects.push(Object { shape: Shape::from(instance), material: stone, emission: None });
    }
    let upper = (objects, room.world.sky(Region::Upper).clone());
    let lower = (room.world.objects(Region::Lower).to_vec(), room.world.sky(Region::Lower).clone());
    let world = World::new(materials, upper, lower);
    let bvh_seconds = start.elapsed().as_secs_f64();
    let bytes = before.zip(resident_bytes()).map(|(b, a)| a.saturating_sub(b));
    let rendered = stored - shelf.triangle_count() + INSTANCES * shelf.triangle_count();
    Ok(Built { scene: Scene { world, ..room }, stored, rendered, bvh_seconds, bytes })
}
