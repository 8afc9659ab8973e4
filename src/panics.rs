//! A panic is a bug of nullpath's, never of its input, so it is reported as one line that says
//! so, `nullpath: error: internal error: <message> (at <file>:<line>; please report it)`, with
//! exit status 70 (EX_SOFTWARE), instead of Rust's "thread '…' panicked at …" report.
//!
//! A hook records the first panic's message and place where it happens, in whatever thread, and
//! prints nothing. The panic then unwinds to [`catching`] around the command: rayon resumes a
//! worker's panic, with its payload, in the thread that waits for the work (`install`, `join`,
//! parallel iterators), and a scope whose thread panicked panics itself. The first panic is the
//! one reported: it is the cause, and later ones ("a scoped thread panicked") its consequences.

use crate::commands::Failure;
use std::any::Any;
use std::panic::AssertUnwindSafe;
use std::sync::OnceLock;

/// The exit status of an internal error: EX_SOFTWARE of sysexits.h.
pub const EXIT_CODE: u8 = 70;

/// The first panic's message and place (`file:line`).
static FIRST: OnceLock<(String, Option<String>)> = OnceLock::new();

/// Replaces Rust's report of a panic by a record of the first one, for [`catching`].
pub fn install() {
    std::panic::set_hook(Box::new(|info| {
        FIRST.get_or_init(|| (describe(info.payload()), info.location().map(|l| format!("{}:{}", l.file(), l.line()))));
    }));
}

/// Runs `command`, turning a panic in it (or in a worker it waits for) into a [`Failure`].
pub fn catching(command: impl FnOnce() -> Result<(), Failure>) -> Result<(), Failure> {
    std::panic::catch_unwind(AssertUnwindSafe(command)).unwrap_or_else(|payload| {
        let (message, place) = FIRST.get().cloned().unwrap_or_else(|| (describe(payload.as_ref()), None));
        Err(Failure { message: report(&message, place.as_deref()), code: EXIT_CODE, is_error: true })
    })
}

/// A panic's message: `panic!` makes a `&str` or a `String` of it.
fn describe(payload: &(dyn Any + Send)) -> String {
    match (payload.downcast_ref::<&str>(), payload.downcast_ref::<String>()) {
        (Some(text), _) => (*text).to_owned(),
        (_, Some(text)) => text.clone(),
        _ => "a panic without a message".to_owned(),
    }
}

/// The line a user reads about the panic `message` at `place`.
fn report(message: &str, place: Option<&str>) -> String {
    match place {
        Some(place) => format!("internal error: {message} (at {place}; please report it)"),
        None => format!("internal error: {message} (please report it)"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::process::Command;

    /// Set in the child process that [`worker_panics_are_reported_in_one_line`] runs.
    const CHILD: &str = "NULLPATH_PANIC_TEST_CHILD";

    /// Panics in a rayon worker (`rayon`) or in a scoped thread (`scope`), as renders and their
    /// checkpoint thread may, with the hook installed as `main` installs it; reports as `main` does.
    fn child(kind: &str) -> ! {
        install();
        let result = catching(|| {
            if kind == "rayon" {
                use rayon::prelude::*;
                let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().map_err(|e| e.to_string())?;
                pool.install(|| (0..64).into_par_iter().for_each(|i| assert!(i != 37, "worker lost sample {i}")));
            } else {
                std::thread::scope(|s| {
                    s.spawn(|| panic!("checkpoint thread gave up"));
                });
            }
            Ok(())
        });
        std::process::exit(i32::from(crate::finish(result)))
    }

    #[test]
    fn worker_panics_are_reported_in_one_line() {
        if let Some(kind) = std::env::var_os(CHILD) {
            child(&kind.to_string_lossy());
        }
        // This test again, in a process of its own: the hook is for the whole process.
        let me = std::env::current_exe().expect("the test binary");
        for (kind, message) in [("rayon", "worker lost sample 37"), ("scope", "checkpoint thread gave up")] {
            let out = Command::new(&me)
                .args(["panics::tests::worker_panics_are_reported_in_one_line", "--exact", "--nocapture"])
                .env(CHILD, kind)
                .output()
                .expect("the test binary runs");
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(i32::from(EXIT_CODE)), "{kind}: {stderr}");
            let expected = format!("nullpath: error: internal error: {message} (at src/panics.rs:");
            assert!(stderr.starts_with(&expected), "{kind}: {stderr}");
            assert!(stderr.trim_end().ends_with("; please report it)"), "{kind}: {stderr}");
            assert_eq!(stderr.lines().count(), 1, "{kind}: {stderr}");
            assert!(!stderr.contains("panicked"), "{kind}: {stderr}");
        }
    }

    #[test]
    fn a_panic_without_a_place_or_message_is_still_one_clear_line() {
        let payload: Box<dyn Any + Send> = Box::new(17u32);
        assert_eq!(describe(payload.as_ref()), "a panic without a message");
        let payload: Box<dyn Any + Send> = Box::new(String::from("index out of bounds"));
        assert_eq!(report(&describe(payload.as_ref()), None), "internal error: index out of bounds (please report it)");
    }
}
