//! The data channels of a render ([`crate::film::data`]): one camera ray through each pixel's
//! centre, traced in parallel, and what it met first.

use crate::emission::{Radiance, Seen, Shift};
use crate::film::{DataChannel, DataLayer, FirstMet, PixelData};
use crate::propagator::{Propagator, RayEnd};
use crate::scene::Scene;
use rayon::prelude::*;

/// `channels` of `scene`'s image, with its propagator.
pub fn data_layer(scene: &Scene, propagator: &Propagator, channels: &[DataChannel]) -> DataLayer {
    let (width, height) = (scene.settings.width, scene.settings.height);
    let pixels = (0..u64::from(width) * u64::from(height))
        .into_par_iter()
        .map(|i| {
            // i < width·height, both u32: the quotient and remainder fit.
            let (x, y) = ((i % u64::from(width)) as u32, (i / u64::from(width)) as u32);
            pixel(scene, propagator, [x, y])
        })
        .collect();
    DataLayer { width, height, channels: channels.to_vec(), pixels }
}

/// What the ray through the centre of `pixel` met.
fn pixel(scene: &Scene, propagator: &Propagator, pixel: [u32; 2]) -> PixelData {
    let size = [scene.settings.width, scene.settings.height];
    let nothing = |fate| PixelData { redshift: f64::NAN, fate, disk_radius: f64::NAN };
    let Some(ray) = scene.camera.ray(pixel, [0.0, 0.0], size, [0.5, 0.5]) else {
        return nothing(FirstMet::Failed);
    };
    match propagator.trace(&scene.world, scene.camera.region, ray.origin, ray.direction) {
        RayEnd::Hit(arrival) => {
            let g = ray.doppler / arrival.energy;
            let object = scene.world.object(arrival.region, arrival.object);
            let Some(emission) = &object.emission else {
                return PixelData { redshift: g, fate: FirstMet::Surface, disk_radius: f64::NAN };
            };
            match &emission.radiance {
                Radiance::Disk(disk) => {
                    let shift = Shift { gravity: g, ..Shift::NONE };
                    let seen = Seen { region: arrival.region, point: arrival.hit.p, shift, propagator };
                    let r = disk.radius(arrival.hit.p);
                    let doppler = disk.doppler(r, -arrival.direction, &seen);
                    PixelData { redshift: g * doppler, fate: FirstMet::Emitter, disk_radius: r }
                }
                Radiance::Rgb(_) | Radiance::Blackbody(_) => {
                    PixelData { redshift: g, fate: FirstMet::Emitter, disk_radius: f64::NAN }
                }
            }
        }
        RayEnd::Escaped { traversed, energy, .. } => PixelData {
            redshift: ray.doppler / energy,
            fate: if traversed { FirstMet::OtherSky } else { FirstMet::Sky },
            disk_radius: f64::NAN,
        },
        RayEnd::Captured => nothing(FirstMet::Captured),
        RayEnd::Failed => nothing(FirstMet::Failed),
    }
}
