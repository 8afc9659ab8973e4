//! Stopping a render from outside: Ctrl-C (SIGINT), SIGTERM (what schedulers send before they
//! kill a job) and SIGHUP (a closed terminal) all ask the render to stop, which it does within a
//! sample, keeping its work in a checkpoint. A second signal while the first is being answered
//! ends the process at once, as users expect of a second Ctrl-C.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

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
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StopReason::Signal(name, _) => write!(f, "interrupted by {name}"),
            StopReason::TimeLimit => f.write_str("stopped at the time limit"),
        }
    }
}

/// The flag renders poll, and which signal set it.
pub struct Interrupts {
    /// Set by any of the signals, or by [`Interrupts::stop`].
    pub cancel: Arc<AtomicBool>,
    signals: Vec<(&'static str, i32, Arc<AtomicBool>)>,
}

impl Interrupts {
    /// Installs the handlers.
    pub fn install() -> Result<Self, String> {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let cancel = Arc::new(AtomicBool::new(false));
        let mut signals = Vec::new();
        for (name, number) in [("SIGINT (Ctrl-C)", SIGINT), ("SIGTERM", SIGTERM), ("SIGHUP", SIGHUP)] {
            let seen = Arc::new(AtomicBool::new(false));
            let error = |e: std::io::Error| format!("cannot handle {name}: {e}");
            // Registered first, so that it sees the flag as the previous signal left it.
            signal_hook::flag::register_conditional_shutdown(number, 128 + number, Arc::clone(&cancel))
                .map_err(error)?;
            signal_hook::flag::register(number, Arc::clone(&seen)).map_err(error)?;
            signal_hook::flag::register(number, Arc::clone(&cancel)).map_err(error)?;
            signals.push((name, number, seen));
        }
        Ok(Self { cancel, signals })
    }

    /// Asks the render to stop because its time is up.
    pub fn stop_for_time_limit(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// Why the render was asked to stop, if it was: a signal, or else the time limit.
    pub fn reason(&self) -> Option<StopReason> {
        if !self.cancel.load(Ordering::Relaxed) {
            return None;
        }
        let signal = self.signals.iter().find(|(_, _, seen)| seen.load(Ordering::Relaxed));
        Some(signal.map_or(StopReason::TimeLimit, |&(name, number, _)| StopReason::Signal(name, number)))
    }
}
