//! What the page says about a view that would otherwise be a picture of nothing with no word:
//! a camera that has left the room the scene file starts it in (it sees the walls' backs, or
//! an empty sky), and one whose every ray falls into the hole (its shadow fills the view). A
//! camera inside a horizon, where nothing can stay at rest, never gets this far: the move is
//! refused with the reason, which the page shows in the same place.

use super::state::Frame;
use render::geometry::{Aabb, Vec3};
use render::scene::Scene;

/// Share of a frame's camera paths that must fall into the hole for its shadow to fill the view.
const SHADOW_SHARE: f64 = 0.99;

/// The bounds of the objects around the scene file's camera: those of the objects in its region,
/// when it stands inside them (a room's walls, a dome); `None` when it looks at them from outside.
pub fn enclosure(file: &Scene) -> Option<Aabb> {
    let bounds = file.world.bounds(file.camera.region);
    (!bounds.is_empty() && inside(&bounds, file.camera.position)).then_some(bounds)
}

fn inside(b: &Aabb, p: Vec3) -> bool {
    p.cmpgt(b.min).all() && p.cmplt(b.max).all()
}

/// What to tell the user about the view of `current` (the file's scene `file` with the page's
/// changes), whose latest frame is `frame` (if one of its generation has been rendered).
pub fn notices(current: &Scene, file: &Scene, frame: Option<&Frame>) -> Vec<String> {
    let mut said = Vec::new();
    if let Some(room) = enclosure(file) {
        let camera = &current.camera;
        if camera.region == file.camera.region && !inside(&room, camera.position) {
            let span = |i: usize| format!("{} to {}", short(room.min[i]), short(room.max[i]));
            said.push(format!(
                "The camera is outside the room the scene starts it in (the objects around it span x {}, y {}, \
                 z {}), so it sees the walls from behind, or nothing: drag back in, or press Reset. Drags keep the \
                 camera inside; hold Alt while dragging to leave.",
                span(0),
                span(1),
                span(2)
            ));
        }
    }
    if let Some(f) = frame {
        let fates = f.fates;
        let paths = fates.escaped + fates.captured + fates.absorbed + fates.traversed + fates.failed;
        if paths > 0 && fates.captured as f64 >= SHADOW_SHARE * paths as f64 {
            said.push(
                "The camera is inside the black hole's shadow: every ray it sends falls into the hole, so the whole \
                 view is black. Back away (wheel), turn (shift-drag), or press Reset."
                    .to_string(),
            );
        }
    }
    said
}

/// A coordinate for a message: as written for round values, else to 4 significant digits.
fn short(x: f64) -> String {
    format!("{}", (x * 1e4).round() / 1e4)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::preview::view::{Eye, Overrides};
    use render::integrator::FateCounts;
    use std::sync::Arc;

    /// A room x, z ∈ [−4, 4], y ∈ [−3, 3] round a hole of mass 0.3, the camera inside.
    const ROOM: &str = "[spacetime]\ntype = \"schwarzschild\"\nmass = 0.3\n[camera]\nposition = [0, 0, 3]\n\
        look_at = [0, 0, 0]\n[[objects]]\nshape = { type = \"box\", min = [-4, -3, -4], max = [4, 3, 4] }\n";

    fn frame(fates: FateCounts) -> Frame {
        let png = Arc::new(Vec::new());
        Frame { png, version: 1, generation: 1, width: 1, height: 1, spp: 1, done: true, seconds: 0.0, fates }
    }

    fn moved_to(file: &Scene, position: [f64; 3]) -> Scene {
        let eye = Eye { position, look_at: [0.0; 3], up: [0.0, 1.0, 0.0], fov: 40.0 };
        Overrides { eye: Some(eye), ..Overrides::default() }.apply(file).expect("a camera may stand there")
    }

    #[test]
    fn a_camera_that_leaves_its_room_is_told() {
        let file = scene::parse(ROOM, "t.toml", ".".as_ref()).expect("valid scene");
        let room = enclosure(&file).expect("the camera starts inside");
        assert_eq!((room.min, room.max), (Vec3::new(-4.0, -3.0, -4.0), Vec3::new(4.0, 3.0, 4.0)));
        assert!(notices(&moved_to(&file, [3.9, 0.0, 0.0]), &file, None).is_empty());
        let outside = notices(&moved_to(&file, [4.1, 0.0, 0.0]), &file, None);
        assert_eq!(outside.len(), 1, "{outside:?}");
        assert!(outside[0].contains("outside the room") && outside[0].contains("x -4 to 4"), "{outside:?}");
        // A scene whose camera looks at its objects from outside has no room to leave.
        let away = scene::parse(&ROOM.replace("position = [0, 0, 3]", "position = [0, 0, 9]"), "t.toml", ".".as_ref())
            .expect("valid scene");
        assert!(enclosure(&away).is_none());
        assert!(notices(&moved_to(&away, [0.0, 0.0, 20.0]), &away, None).is_empty());
    }

    #[test]
    fn a_view_filled_by_the_shadow_is_told() {
        let file = scene::parse(ROOM, "t.toml", ".".as_ref()).expect("valid scene");
        let all_in = FateCounts { captured: 995, absorbed: 5, ..FateCounts::default() };
        let said = notices(&file, &file, Some(&frame(all_in)));
        assert!(said.len() == 1 && said[0].contains("shadow"), "{said:?}");
        let some_in = FateCounts { captured: 900, absorbed: 100, ..FateCounts::default() };
        assert!(notices(&file, &file, Some(&frame(some_in))).is_empty());
        assert!(notices(&file, &file, Some(&frame(FateCounts::default()))).is_empty(), "no paths, no word");
    }
}
