//! Spectral foundation costs: RGB → spectrum (table lookup and evaluation at a path's wavelengths),
//! sampled spectrum → XYZ per sample, and the one-time table optimisation.
//!
//! `cargo bench -p nullpath-render --bench spectrum`

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use render::sampling::Rng;
use render::spectrum::{RgbToSpectrumTable, RgbUpsampler, SampledWavelengths, Spectrum};
use std::hint::black_box;

/// Colours or samples per measured batch.
const BATCH: usize = 4096;

fn inputs() -> Vec<([f32; 3], SampledWavelengths)> {
    let mut rng = Rng::new(5);
    (0..BATCH)
        .map(|_| {
            let rgb = [rng.next_f64(), rng.next_f64(), rng.next_f64()].map(|v| v as f32);
            (rgb, SampledWavelengths::sample_visible(rng.next_f64() as f32))
        })
        .collect()
}

fn spectrum(c: &mut Criterion) {
    let up = RgbUpsampler::new(RgbToSpectrumTable::optimise(RgbToSpectrumTable::DEFAULT_RESOLUTION));
    let inputs = inputs();
    let mut group = c.benchmark_group("spectrum");
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function("rgb_albedo_to_sampled", |b| {
        b.iter(|| {
            for (rgb, w) in &inputs {
                black_box(up.albedo(*rgb).sample(w));
            }
        })
    });
    group.bench_function("rgb_illuminant_to_sampled", |b| {
        b.iter(|| {
            for (rgb, w) in &inputs {
                black_box(up.illuminant(*rgb).sample(w));
            }
        })
    });
    let spectra: Vec<_> = inputs.iter().map(|(rgb, w)| (up.albedo(*rgb).sample(w), *w)).collect();
    group.bench_function("sampled_to_xyz", |b| {
        b.iter(|| {
            for (s, w) in &spectra {
                black_box(s.to_xyz(w));
            }
        })
    });
    group.finish();
    let mut once = c.benchmark_group("spectrum_table");
    once.sample_size(10);
    once.bench_function("optimise_32", |b| {
        b.iter(|| black_box(RgbToSpectrumTable::optimise(RgbToSpectrumTable::DEFAULT_RESOLUTION)))
    });
    once.finish();
}

criterion_group!(benches, spectrum);
criterion_main!(benches);
