//! Waiting for a command with a deadline that tells an answer from a hang.
//!
//! A test that a command answers "at once" (an interrupt obeyed, a bad flag refused before the
//! render) must not assert on seconds: a busy machine takes them. The commands these tests run
//! would otherwise render for hours (a million samples per pixel), so a minute separates an answer
//! from a hang, or from the work that should have been refused, by orders of magnitude.

use std::process::{Child, Command, Output};
use std::time::Duration;

/// Long enough for any busy machine to answer, far shorter than the hours of work a hung or
/// unrefused command does.
pub const ANSWER: Duration = Duration::from_secs(60);

/// `child`'s output once it exits within `limit`; past it the child is killed and the test fails,
/// naming `what` was awaited.
pub fn output_within(child: Child, limit: Duration, what: &str) -> Output {
    let pid = child.id();
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || send.send(child.wait_with_output()));
    match receive.recv_timeout(limit) {
        Ok(output) => output.expect("the command's output"),
        Err(_) => {
            let _ = Command::new("kill").args(["-KILL", &pid.to_string()]).status();
            panic!("{what}: the command was still running {limit:?} later")
        }
    }
}
