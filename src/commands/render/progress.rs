//! How a render shows its progress: a bar on a terminal, or, with `--progress-lines`, lines
//! `progress DONE TOTAL` on standard error for a program that runs nullpath and shows the
//! progress itself (the Blender add-on), since a bar drawn into a pipe reads as noise.

use indicatif::{ProgressBar, ProgressStyle};
use std::sync::Mutex;

/// Steps of the lines' resolution: a line is written when the fraction done passes a thousandth,
/// so a render writes at most about a thousand lines whatever its size.
const LINE_STEPS: u64 = 1000;

pub enum Progress {
    Silent,
    Bar(ProgressBar),
    /// The `(total, step)` last written: a new total (a noise target's next pass) starts over.
    Lines(Mutex<(u64, u64)>),
}

impl Progress {
    /// A bar on a terminal; lines if asked for; nothing when quiet.
    pub fn new(quiet: bool, lines: bool, terminal: bool) -> Progress {
        if quiet {
            Progress::Silent
        } else if lines {
            Progress::Lines(Mutex::new((0, 0)))
        } else if terminal {
            let bar = ProgressBar::new(1);
            bar.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            Progress::Bar(bar)
        } else {
            Progress::Silent
        }
    }

    /// `done` of `total` units of work are finished (called from the render's threads).
    pub fn show(&self, done: u64, total: u64) {
        match self {
            Progress::Silent => {}
            Progress::Bar(bar) => {
                bar.set_length(total);
                bar.set_position(done);
            }
            Progress::Lines(last) => {
                let step = done.saturating_mul(LINE_STEPS) / total.max(1);
                let mut last = last.lock().unwrap_or_else(|e| e.into_inner());
                if (total, step) != *last && (total != last.0 || step > last.1) {
                    *last = (total, step);
                    eprintln!("progress {done} {total}");
                }
            }
        }
    }

    /// Clears the bar once the render is over.
    pub fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn last(progress: &Progress) -> (u64, u64) {
        match progress {
            Progress::Lines(last) => *last.lock().unwrap(),
            _ => panic!("not lines"),
        }
    }

    #[test]
    fn lines_advance_by_thousandths_and_restart_with_a_new_total() {
        let progress = Progress::new(false, true, false);
        progress.show(1, 2000);
        assert_eq!(last(&progress), (2000, 0), "no step passed yet: nothing written");
        progress.show(1000, 2000);
        assert_eq!(last(&progress), (2000, 500));
        progress.show(999, 2000);
        assert_eq!(last(&progress), (2000, 500), "a late report from another thread does not go back");
        progress.show(0, 10);
        assert_eq!(last(&progress), (10, 0), "a new pass starts over");
    }

    #[test]
    fn quiet_wins_over_lines() {
        assert!(matches!(Progress::new(true, true, true), Progress::Silent));
        assert!(matches!(Progress::new(false, false, false), Progress::Silent));
    }
}
