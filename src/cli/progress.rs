//! What a headless command shows while it works, and how it stops: a progress line on stderr once the
//! work has taken a second (only on a terminal), and Ctrl-C interrupting every solve, so that the
//! command ends cleanly with status 130. A second Ctrl-C ends the process at once.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::model::Work;

/// How long work runs before the progress line appears.
const QUIET: Duration = Duration::from_secs(1);
/// How often the line is redrawn.
const TICK: Duration = Duration::from_millis(100);

/// The exit status of a command stopped by Ctrl-C (128 + SIGINT, as a shell reports it).
pub const INTERRUPTED: u8 = 130;

/// Set by the first Ctrl-C: the process is a command that was told to stop. Its solves see it through
/// the cancellation of their options; the core holds no such flag.
static STOP: AtomicBool = AtomicBool::new(false);

/// True once Ctrl-C was pressed.
pub fn interrupted() -> bool {
    STOP.load(Ordering::Relaxed)
}

/// The signal handler: one atomic store, async-signal-safe.
fn interrupt() {
    STOP.store(true, Ordering::Relaxed);
}

/// Runs `command` with Ctrl-C handled and, after a second, a progress line counting the bounces solved
/// under `work`. The line stops when `command` returns or panics (its end drops the sender), so a panic
/// ends the process instead of leaving it waiting on the line's thread.
pub fn watch<T>(work: &Work, command: impl FnOnce() -> T) -> T {
    handle_ctrl_c();
    let (done, finished) = mpsc::channel::<()>();
    std::thread::scope(|scope| {
        let shown = scope.spawn(move || {
            if !waiting(finished.recv_timeout(QUIET)) {
                return;
            }
            let start = work.solved();
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed} {msg}") {
                bar.set_style(style);
            }
            loop {
                let message = if interrupted() {
                    "interrupted: stopping".to_string()
                } else {
                    format!("{} bounces solved (Ctrl-C stops)", work.solved() - start)
                };
                bar.set_message(message);
                bar.tick();
                if !waiting(finished.recv_timeout(TICK)) {
                    break;
                }
            }
            bar.finish_and_clear();
        });
        let result = command();
        drop(done);
        let _ = shown.join();
        result
    })
}

/// True while the command runs: the wait timed out, the sender neither sent nor was dropped.
fn waiting(wait: Result<(), RecvTimeoutError>) -> bool {
    wait == Err(RecvTimeoutError::Timeout)
}

/// The first Ctrl-C interrupts the solves; the second ends the process with [`INTERRUPTED`].
fn handle_ctrl_c() {
    let once = Arc::new(AtomicBool::new(false));
    let int = signal_hook::consts::SIGINT;
    // Registration fails only for a forbidden signal, which SIGINT is not; without it, Ctrl-C keeps
    // its default of ending the process.
    let _ = signal_hook::flag::register_conditional_shutdown(int, INTERRUPTED.into(), once.clone());
    let _ = signal_hook::flag::register(int, once);
    // SAFETY: the handler only stores to an atomic, which is async-signal-safe.
    let _ = unsafe { signal_hook::low_level::register(int, interrupt) };
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A command that panics after the progress line has appeared ends: the panic reaches the caller
    /// (the process would exit with it) instead of the line's thread ticking for ever.
    #[test]
    fn a_panicking_command_ends_the_watch() {
        let (ended, end) = mpsc::channel();
        std::thread::spawn(move || {
            let work = Work::unlimited();
            let caught = std::panic::catch_unwind(|| {
                watch(&work, || {
                    std::thread::sleep(QUIET + 2 * TICK);
                    panic!("a bug in the command");
                })
            });
            let _ = ended.send(caught.is_err());
        });
        let ended = end.recv_timeout(Duration::from_secs(30));
        assert_eq!(ended, Ok(true), "the watch did not end with the panic");
    }
}
