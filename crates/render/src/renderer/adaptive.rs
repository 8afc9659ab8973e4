//! Where the next pass's samples go, and when a render is done.
//!
//! Without a noise target a render has one pass: every pixel to the goal's samples. With one,
//! every pixel first takes [`WARM_UP_SPP`] samples; after each pass the film's estimated error is
//! compared with the target, and the next pass doubles every pixel's samples (uniform), or gives
//! each block of pixels the samples that minimise the image's error for their total (adaptive).
//!
//! The adaptive allocation: a pixel whose single samples have relative variance `r_p²` and that
//! takes `n_p` samples contributes `r_p²/n_p` to the image's mean relative variance. For a fixed
//! total `Σ n_p` the sum is least for `n_p ∝ r_p` (Lagrange; by Cauchy–Schwarz it never needs
//! more samples than uniform sampling, and fewer wherever noise is uneven), and it equals the
//! target's square for `n_p = r_p · mean(r) / target²`. Each block of pixels pools its estimates
//! of `r²` (single pixels' estimates are too noisy to steer by), and a pass at most doubles a
//! pixel's samples, so that the estimates are renewed before many samples are spent on them.

use super::{Goal, Outcome, WARM_UP_SPP};
use crate::film::{noise, Film, TileBounds};

/// Side of the blocks of pixels that pool their noise estimates.
const BLOCK: u32 = 8;

/// Sets `targets` (one per film pixel) for the next pass over `tiles`, or says why the render is
/// done.
pub(super) fn next_targets(film: &Film, targets: &mut [u32], tiles: &[TileBounds], goal: Goal) -> Option<Outcome> {
    let width = film.width() as usize;
    let index = |(x, y): (u32, u32)| y as usize * width + x as usize;
    let pixels = || tiles.iter().flat_map(|t| t.pixels());
    let fewest = pixels().map(|(x, y)| film.taken_at(x, y)).min().unwrap_or(goal.spp);
    if fewest >= goal.spp {
        return Some(Outcome::Finished);
    }
    let Some(noise) = goal.noise else {
        pixels().for_each(|p| targets[index(p)] = goal.spp);
        return None;
    };
    let warm_up = WARM_UP_SPP.min(goal.spp);
    if fewest < warm_up {
        pixels().for_each(|p| targets[index(p)] = targets[index(p)].max(warm_up));
        return None;
    }
    if noise::estimated_relative_error(film, pixels()).is_some_and(|e| e <= noise.relative_error) {
        return Some(Outcome::Converged);
    }
    if noise.adaptive && allocate(film, targets, tiles, noise.relative_error, goal.spp) {
        return None;
    }
    // Uniform, or nothing the allocation would add: double every pixel.
    for p @ (x, y) in pixels() {
        targets[index(p)] = goal.spp.min(film.taken_at(x, y).saturating_mul(2));
    }
    None
}

/// The adaptive allocation (module docs); false if it raises no pixel's target.
fn allocate(film: &Film, targets: &mut [u32], tiles: &[TileBounds], target_error: f64, spp: u32) -> bool {
    let blocks: Vec<(TileBounds, f64)> =
        tiles.iter().flat_map(|t| blocks(*t)).map(|b| (b, block_deviation(film, b))).collect();
    let pixel_count: usize = blocks.iter().map(|(b, _)| b.pixel_count()).sum();
    let mean_deviation =
        blocks.iter().map(|(b, r)| r * b.pixel_count() as f64).sum::<f64>() / pixel_count.max(1) as f64;
    let scale = mean_deviation / (target_error * target_error);
    let width = film.width() as usize;
    let mut raised = false;
    for (block, deviation) in &blocks {
        let wanted = (scale * deviation).ceil().min(f64::from(spp)) as u32;
        for (x, y) in block.pixels() {
            let taken = film.taken_at(x, y);
            let target = wanted.clamp(taken, spp.min(taken.saturating_mul(2)).max(taken));
            raised |= target > taken;
            targets[y as usize * width + x as usize] = target;
        }
    }
    raised
}

/// The blocks of at most [`BLOCK`]² pixels that tile `tile`.
fn blocks(tile: TileBounds) -> impl Iterator<Item = TileBounds> {
    (tile.y0..tile.y1).step_by(BLOCK as usize).flat_map(move |y0| {
        (tile.x0..tile.x1).step_by(BLOCK as usize).map(move |x0| TileBounds {
            x0,
            y0,
            x1: (x0 + BLOCK).min(tile.x1),
            y1: (y0 + BLOCK).min(tile.y1),
        })
    })
}

/// The pooled relative standard deviation of one sample of the block's pixels, `√mean r_p²`;
/// a pixel without an estimate counts as deviating by 100 %.
fn block_deviation(film: &Film, block: TileBounds) -> f64 {
    let sum: f64 = block
        .pixels()
        .map(|(x, y)| noise::pixel_relative_variance(film, x, y).map_or(1.0, |v| v * f64::from(film.taken_at(x, y))))
        .sum();
    (sum / block.pixel_count().max(1) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::renderer::NoiseTarget;
    use crate::rgb::Rgb;
    use crate::sampling::Rng;

    /// A 32 × 16 film, each pixel `n` samples; the right half's samples are ten times noisier.
    fn film(n: u32) -> Film {
        let mut film = Film::new(32, 16);
        for (x, y) in film.bounds().pixels() {
            let spread = if x < 16 { 0.1 } else { 1.0 };
            for s in 0..n {
                let u = Rng::for_sample(9, u64::from(y * 32 + x), u64::from(s)).next_f64() as f32;
                film.add_sample(x, y, Rgb::splat(1.0 + spread * (2.0 * u - 1.0)), 1.0);
            }
        }
        film
    }

    fn goal(adaptive: bool) -> Goal {
        Goal { spp: 1 << 16, noise: Some(NoiseTarget { relative_error: 0.03, adaptive }) }
    }

    #[test]
    fn without_a_noise_target_one_pass_takes_every_pixel_to_the_goal() {
        let film = film(2);
        let tiles = TileBounds::grid(32, 16, 16);
        let mut targets = vec![0; 512];
        assert_eq!(next_targets(&film, &mut targets, &tiles, Goal::spp(5)), None);
        assert!(targets.iter().all(|&t| t == 5));
        assert_eq!(next_targets(&film, &mut targets, &tiles, Goal::spp(2)), Some(Outcome::Finished));
    }

    #[test]
    fn noise_targets_warm_up_then_double_or_send_samples_where_the_noise_is() {
        let tiles = TileBounds::grid(32, 16, 16);
        let mut targets = vec![0; 512];
        assert_eq!(next_targets(&film(4), &mut targets, &tiles, goal(true)), None);
        assert!(targets.iter().all(|&t| t == WARM_UP_SPP));

        let film = film(32);
        assert_eq!(next_targets(&film, &mut targets, &tiles, goal(false)), None);
        assert!(targets.iter().all(|&t| t == 64), "uniform doubles");

        assert_eq!(next_targets(&film, &mut targets, &tiles, goal(true)), None);
        let (quiet, noisy) = (targets[8 * 32 + 4], targets[8 * 32 + 20]);
        assert_eq!(quiet, 32, "the quiet half needs no more: {quiet}");
        assert_eq!(noisy, 64, "the noisy half doubles: {noisy}");

        // A loose target is met already.
        let loose = Goal { spp: 1 << 16, noise: Some(NoiseTarget { relative_error: 0.5, adaptive: true }) };
        assert_eq!(next_targets(&film, &mut targets, &tiles, loose), Some(Outcome::Converged));
    }

    #[test]
    fn blocks_tile_a_clipped_tile() {
        let tile = TileBounds { x0: 16, y0: 0, x1: 27, y1: 16 };
        let blocks: Vec<_> = blocks(tile).collect();
        assert_eq!(blocks.len(), 4);
        assert_eq!(blocks.iter().map(TileBounds::pixel_count).sum::<usize>(), tile.pixel_count());
        assert_eq!(blocks[1], TileBounds { x0: 24, y0: 0, x1: 27, y1: 8 });
    }
}
