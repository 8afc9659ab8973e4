//! The data channels of a render ([`crate::film::data`]): one camera ray through each pixel's
//! centre, traced in parallel, and what it met first.

use crate::emission::{Radiance, Seen, Shift};
use crate::film::{DataLayer, FirstMet, PixelData};
use crate::propagator::{Propagator, RayEnd};
use crate::scene::Scene;
use crate::spectrum::{Colour, SampledSpectrum, SampledWavelengths, N_WAVELENGTHS};
use rayon::prelude::*;

/// The data channels `scene`'s settings ask for (`[render] channels` and `spectrum`), with the
/// scene's own propagator; `None` when it asks for none. What a whole render writes beside the
/// colour.
pub fn requested_data(scene: &Scene) -> Option<DataLayer> {
    scene.settings.has_data_channels().then(|| data_layer(scene, &super::propagator(scene)))
}

/// The data and spectral channels `scene`'s settings ask for, with its propagator.
pub fn data_layer(scene: &Scene, propagator: &Propagator) -> DataLayer {
    let settings = &scene.settings;
    let (width, height) = (settings.width, settings.height);
    let wavelengths = settings.spectrum.map(|s| s.wavelengths()).unwrap_or_default();
    let (pixels, spectra): (Vec<PixelData>, Vec<Vec<f32>>) = (0..u64::from(width) * u64::from(height))
        .into_par_iter()
        .map(|i| {
            // i < width·height, both u32: the quotient and remainder fit.
            let (x, y) = ((i % u64::from(width)) as u32, (i / u64::from(width)) as u32);
            pixel(scene, propagator, [x, y], &wavelengths)
        })
        .unzip();
    DataLayer { width, height, channels: settings.channels.clone(), pixels, wavelengths, spectra: spectra.concat() }
}

/// What the ray through the centre of `pixel` met, and the spectral radiance it brings the
/// camera at `wavelengths`.
fn pixel(scene: &Scene, propagator: &Propagator, pixel: [u32; 2], wavelengths: &[f64]) -> (PixelData, Vec<f32>) {
    let size = [scene.settings.width, scene.settings.height];
    let nothing =
        |fate| (PixelData { redshift: f64::NAN, fate, disk_radius: f64::NAN }, vec![f32::NAN; wavelengths.len()]);
    let Some(ray) = scene.camera.ray(pixel, [0.0, 0.0], size, [0.5, 0.5]) else {
        return nothing(FirstMet::Failed);
    };
    let at_camera = Shift::at_camera(ray.doppler, scene.settings.shown);
    match propagator.trace(&scene.world, scene.camera.region, ray.origin, ray.direction) {
        RayEnd::Hit(arrival) => {
            let g = ray.doppler / arrival.energy;
            let object = scene.world.object(arrival.region, arrival.object);
            let Some(emission) = &object.emission else {
                let data = PixelData { redshift: g, fate: FirstMet::Surface, disk_radius: f64::NAN };
                return (data, vec![0.0; wavelengths.len()]);
            };
            let shift = at_camera.after(arrival.energy);
            let seen = Seen { region: arrival.region, point: arrival.hit.p, shift, propagator };
            let dir = -arrival.direction;
            let spectrum = spectrum(wavelengths, |lambda| emission.seen(arrival.ng_local, dir, &seen, lambda));
            let data = match &emission.radiance {
                Radiance::Disk(disk) => {
                    let r = disk.radius(arrival.hit.p);
                    let doppler = disk.doppler(r, dir, &seen);
                    PixelData { redshift: g * doppler, fate: FirstMet::Emitter, disk_radius: r }
                }
                Radiance::Rgb(_) | Radiance::Blackbody(_) => {
                    PixelData { redshift: g, fate: FirstMet::Emitter, disk_radius: f64::NAN }
                }
            };
            (data, spectrum)
        }
        RayEnd::Escaped { region, direction, traversed, energy } => {
            let shown = at_camera.after(energy).shown(1.0);
            let sky = scene.world.sky(region);
            let data = PixelData {
                redshift: ray.doppler / energy,
                fate: if traversed { FirstMet::OtherSky } else { FirstMet::Sky },
                disk_radius: f64::NAN,
            };
            (data, spectrum(wavelengths, |lambda| sky.seen(direction, shown, lambda)))
        }
        RayEnd::Captured => nothing(FirstMet::Captured),
        RayEnd::Failed => nothing(FirstMet::Failed),
    }
}

/// `radiance` at each of `wavelengths`, taken [`N_WAVELENGTHS`] at a time.
fn spectrum(wavelengths: &[f64], radiance: impl Fn(&SampledWavelengths) -> SampledSpectrum) -> Vec<f32> {
    wavelengths
        .chunks(N_WAVELENGTHS)
        .flat_map(|chunk| {
            let lambda = SampledWavelengths::at(std::array::from_fn(|i| chunk[i.min(chunk.len() - 1)] as f32));
            let value = radiance(&lambda);
            (0..chunk.len()).map(move |i| value.component(i))
        })
        .collect()
}
