//! Stopping a render from outside. Every request to stop is answered within a sample, and the
//! work is kept in a checkpoint:
//!
//! | signal | what it does |
//! |---|---|
//! | SIGINT (Ctrl-C) | stop and write the checkpoint; a second Ctrl-C, 0.1 s or more after the first, quits at once without it |
//! | SIGTERM | stop and write the checkpoint; sent again, it is the same request |
//! | SIGHUP (terminal closed) | as SIGTERM |
//!
//! SIGTERM never quits at once, because supervisors send it more than once without meaning more:
//! `timeout` signals the process and then its whole process group, which holds the process, so it
//! arrives twice within microseconds; a scheduler that will not wait follows it with SIGKILL
//! anyway. A second Ctrl-C is a person who will not wait for the checkpoint. Copies of one press
//! (a wrapper that forwards the SIGINT the terminal already sent to the whole group) arrive
//! within milliseconds, far sooner than a person presses twice, so a SIGINT less than
//! [`SAME_PRESS`] after the first is taken for the same press.
//!
//! Signals are answered by a thread of their own ([`signal_hook::iterator`]), in ordinary code,
//! so that the first signal's name can be kept and the time between presses measured.

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::{Duration, Instant};

/// A SIGINT within this time of the first is a copy of the same Ctrl-C, not a second one.
pub const SAME_PRESS: Duration = Duration::from_millis(100);

/// Why a render was asked to stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    Signal(&'static str, i32),
    TimeLimit,
}

impl StopReason {
    /// The process's exit status for this stop: 128 + the signal's number, as shells report a
    /// process killed by it, and 75 (EX_TEMPFAIL: try again, here with `--resume`) for a time limit.
    pub fn exit_code(self) -> u8 {
        match self {
            StopReason::Signal(_, number) => 128 + number as u8,
            StopReason::TimeLimit => 75,
        }
    }

    fn of_signal(number: i32) -> Self {
        match number {
            SIGINT => StopReason::Signal("SIGINT (Ctrl-C)", SIGINT),
            SIGTERM => StopReason::Signal("SIGTERM", SIGTERM),
            _ => StopReason::Signal("SIGHUP", SIGHUP),
        }
    }
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StopReason::Signal(name, _) => write!(f, "interrupted by {name}"),
            StopReason::TimeLimit => f.write_str("stopped at the time limit"),
        }
    }
}

/// The flag renders poll, and what first set it.
pub struct Interrupts {
    /// Set by any of the signals, or by [`Interrupts::stop_for_time_limit`].
    pub cancel: Arc<AtomicBool>,
    /// The first reason to stop; later ones change nothing.
    reason: Arc<OnceLock<StopReason>>,
}

impl Interrupts {
    /// Starts answering SIGINT, SIGTERM and SIGHUP.
    pub fn install() -> Result<Self, String> {
        let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])
            .map_err(|e| format!("cannot handle SIGINT, SIGTERM and SIGHUP: {e}"))?;
        let interrupts = Self { cancel: Arc::default(), reason: Arc::default() };
        let (cancel, reason) = (Arc::clone(&interrupts.cancel), Arc::clone(&interrupts.reason));
        let answer = move || {
            let mut first_press: Option<Instant> = None;
            for number in signals.forever() {
                if number == SIGINT {
                    match first_press {
                        Some(first) if first.elapsed() >= SAME_PRESS => {
                            eprintln!("nullpath: quit at a second Ctrl-C, without writing the checkpoint");
                            std::process::exit(i32::from(StopReason::of_signal(SIGINT).exit_code()));
                        }
                        Some(_) => {}
                        None => first_press = Some(Instant::now()),
                    }
                }
                stop(&cancel, &reason, StopReason::of_signal(number));
            }
        };
        std::thread::Builder::new()
            .name("signals".into())
            .spawn(answer)
            .map_err(|e| format!("cannot handle SIGINT, SIGTERM and SIGHUP: {e}"))?;
        Ok(interrupts)
    }

    /// Asks the render to stop because its time is up.
    pub fn stop_for_time_limit(&self) {
        stop(&self.cancel, &self.reason, StopReason::TimeLimit);
    }

    /// Why the render was asked to stop, if it was: the first signal, or the time limit.
    pub fn reason(&self) -> Option<StopReason> {
        self.reason.get().copied()
    }
}

/// Records `why` unless an earlier reason is recorded, then sets `cancel`: the reason is there
/// before a render can see the flag and stop.
fn stop(cancel: &AtomicBool, reason: &OnceLock<StopReason>, why: StopReason) {
    reason.get_or_init(|| why);
    cancel.store(true, Ordering::SeqCst);
}
