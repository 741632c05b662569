//! The real terminal: raw mode and the alternate screen on the way in; on the way out, whether by quit,
//! error, a panic on the main thread or signal, the terminal is given back as it was (a worker's panic is
//! the explorer's to report: it goes on running).
//!
//! SIGTERM, SIGQUIT and SIGINT (a `kill`, not Ctrl-C, which raw mode turns into a key) restore the
//! terminal and exit with 128 + the signal's number; after SIGHUP the terminal is gone, so the explorer
//! exits at once without writing to it.

use std::io::{self, Stdout, Write, stdout};
use std::thread;

use signal_hook::consts::{SIGHUP, SIGINT, SIGQUIT, SIGTERM};
use signal_hook::iterator::Signals;

use crossterm::cursor::{Hide, Show};
use crossterm::event::DisableMouseCapture;
use crossterm::execute;
use crossterm::terminal::{
    EndSynchronizedUpdate, EnterAlternateScreen, LeaveAlternateScreen, disable_raw_mode,
    enable_raw_mode,
};
use ratatui::Terminal;

use super::output::Output;
use super::worker;

/// Mouse reports of presses, releases and drags (not of every motion, which would flood a slow link),
/// in the SGR encoding.
const MOUSE_ON: &str = "\x1b[?1000h\x1b[?1002h\x1b[?1006h";

/// The terminal in explorer mode; dropping it restores the terminal.
pub struct Session {
    pub terminal: Terminal<Output<Stdout>>,
}

impl Session {
    /// Installs the panic hook and the signal watcher, then enters raw mode and the alternate screen
    /// and asks for mouse events (a click on a chart moves the time cursor; terminals that do not report
    /// the mouse ignore this). With `ascii`, every frame is written in ASCII.
    pub fn start(ascii: bool) -> io::Result<Session> {
        install_panic_hook();
        watch_signals()?;
        enable_raw_mode()?;
        let started = execute!(stdout(), EnterAlternateScreen, Hide)
            .and_then(|()| {
                let mut out = stdout();
                out.write_all(MOUSE_ON.as_bytes())?;
                out.flush()
            })
            .and_then(|()| Terminal::new(Output::new(stdout(), ascii)));
        match started {
            Ok(terminal) => Ok(Session { terminal }),
            Err(e) => {
                restore();
                Err(e)
            }
        }
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        restore();
    }
}

/// Stops the mouse reports, leaves raw mode and the alternate screen and shows the cursor; errors are
/// ignored, as there is nothing better to do on the way out. Safe to call more than once.
pub fn restore() {
    let _ = disable_raw_mode();
    let _ = execute!(
        stdout(),
        EndSynchronizedUpdate,
        DisableMouseCapture,
        LeaveAlternateScreen,
        Show
    );
}

/// A thread that waits for the signals that end the explorer and ends it, the terminal restored. It holds
/// the output while restoring, so no frame is written after the restore.
fn watch_signals() -> io::Result<()> {
    let mut signals = Signals::new([SIGTERM, SIGQUIT, SIGINT, SIGHUP])?;
    thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                if signal == SIGHUP {
                    let _ = disable_raw_mode();
                } else {
                    let _output = stdout().lock();
                    restore();
                }
                std::process::exit(128 + signal);
            }
        })?;
    Ok(())
}

/// A panic on the main thread ends the explorer: the terminal is restored before the default hook
/// prints the panic, so the message is readable. A panic on any other thread leaves the terminal to the
/// main thread, which goes on drawing: a worker's job reports it in the explorer ([`worker::Crash`]), so
/// it is not printed over the screen, only where it happened noted for that report.
fn install_panic_hook() {
    let main = thread::current().id();
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if thread::current().id() == main {
            restore();
            previous(info);
        } else {
            worker::remember_panic(info.location());
        }
    }));
}
