//! The terminal's input for the event loop: a thread reads the terminal's bytes as they come and another
//! waits for SIGWINCH; both hand what they get to the loop through one channel, and [`super::decode`] turns
//! the bytes into events. The loop waits on that channel alone, with a timeout while the bounce plays (for
//! its ticks), while an answer is awaited, or while an escape sequence is unfinished: one that stays
//! unfinished for [`ESCAPE_TIME`] is given up ([`super::decode::Decoder::flush`]).
//!
//! The reading thread is never joined: it is blocked in a read when the explorer quits, and ends with
//! the process.

use std::collections::VecDeque;
use std::fs::File;
use std::io::{self, IsTerminal, Read};
use std::os::fd::AsFd;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender, TryRecvError};
use std::thread;
use std::time::{Duration, Instant};

use crossterm::event::Event;
use signal_hook::consts::SIGWINCH;
use signal_hook::iterator::Signals;

use super::decode::Decoder;
use super::events::{EventSource, Input};

/// How long an unfinished escape sequence may wait for its end (a terminal sends a sequence in one
/// write; a lone ESC is the Esc key after this).
pub const ESCAPE_TIME: Duration = Duration::from_millis(50);

/// What the threads send the loop.
enum Arrival {
    Bytes(Vec<u8>),
    Resized,
    /// The terminal is gone (end of input or a read error).
    Closed,
}

/// The terminal's events and the wall clock.
pub struct TerminalEvents {
    arrivals: Receiver<Arrival>,
    decoder: Decoder,
    /// Events decoded and not yet taken.
    ready: VecDeque<Event>,
    /// When the last tick was, while waking on a timer.
    last_tick: Option<Instant>,
    /// When the last bytes came, while an escape sequence is unfinished.
    last_bytes: Instant,
    closed: bool,
}

impl TerminalEvents {
    /// Starts reading the terminal (standard input, or /dev/tty if that is not one) and watching for
    /// resizes.
    pub fn start() -> io::Result<TerminalEvents> {
        let stdin = io::stdin();
        let mut tty = if stdin.is_terminal() {
            File::from(stdin.as_fd().try_clone_to_owned()?)
        } else {
            File::open("/dev/tty")?
        };
        let (send, arrivals) = mpsc::channel();
        let resized = send.clone();
        let mut signals = Signals::new([SIGWINCH])?;
        thread::Builder::new()
            .name("resize".into())
            .spawn(move || {
                for _ in signals.forever() {
                    if resized.send(Arrival::Resized).is_err() {
                        return;
                    }
                }
            })?;
        thread::Builder::new()
            .name("input".into())
            .spawn(move || read(&mut tty, &send))?;
        Ok(TerminalEvents {
            arrivals,
            decoder: Decoder::default(),
            ready: VecDeque::new(),
            last_tick: None,
            last_bytes: Instant::now(),
            closed: false,
        })
    }

    /// Takes one arrival.
    fn take(&mut self, arrival: Arrival) {
        match arrival {
            Arrival::Bytes(bytes) => {
                self.ready.extend(self.decoder.feed(&bytes));
                self.last_bytes = Instant::now();
            }
            Arrival::Resized => {
                if let Ok((columns, rows)) = crossterm::terminal::size() {
                    self.ready.push_back(Event::Resize(columns, rows));
                }
            }
            Arrival::Closed => self.closed = true,
        }
    }

    /// When an unfinished escape sequence is to be given up.
    fn escape_deadline(&self) -> Option<Instant> {
        self.decoder
            .waiting()
            .then_some(self.last_bytes + ESCAPE_TIME)
    }
}

/// Reads the terminal until it is gone.
fn read(tty: &mut File, send: &Sender<Arrival>) {
    let mut buf = [0u8; 4096];
    loop {
        let arrival = match tty.read(&mut buf) {
            Ok(0) | Err(_) => Arrival::Closed,
            Ok(n) => Arrival::Bytes(buf[..n].to_vec()),
        };
        let closed = matches!(arrival, Arrival::Closed);
        if send.send(arrival).is_err() || closed {
            return;
        }
    }
}

impl EventSource for TerminalEvents {
    fn next_input(&mut self, wait: Option<Duration>) -> io::Result<Option<Input>> {
        if wait.is_none() {
            self.last_tick = None;
        }
        let tick = wait.map(|w| *self.last_tick.get_or_insert_with(Instant::now) + w);
        loop {
            if let Some(event) = self.ready.pop_front() {
                return Ok(Some(Input::Event(event)));
            }
            if self.closed {
                return Ok(None);
            }
            let deadline = match (tick, self.escape_deadline()) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            };
            let arrival = match deadline {
                Some(deadline) => {
                    match self
                        .arrivals
                        .recv_timeout(deadline.saturating_duration_since(Instant::now()))
                    {
                        Ok(arrival) => arrival,
                        Err(RecvTimeoutError::Timeout) => {
                            if self.escape_deadline().is_some_and(|d| Instant::now() >= d) {
                                self.ready.extend(self.decoder.flush());
                            }
                            if let Some(tick) = tick
                                && Instant::now() >= tick
                            {
                                let last = self.last_tick.unwrap_or(tick);
                                let now = Instant::now();
                                self.last_tick = Some(now);
                                return Ok(Some(Input::Tick(now - last)));
                            }
                            continue;
                        }
                        Err(RecvTimeoutError::Disconnected) => Arrival::Closed,
                    }
                }
                None => self.arrivals.recv().unwrap_or(Arrival::Closed),
            };
            self.take(arrival);
        }
    }

    fn ready_input(&mut self) -> io::Result<Option<Input>> {
        loop {
            if let Some(event) = self.ready.pop_front() {
                return Ok(Some(Input::Event(event)));
            }
            match self.arrivals.try_recv() {
                Ok(arrival) => self.take(arrival),
                Err(TryRecvError::Empty | TryRecvError::Disconnected) => return Ok(None),
            }
        }
    }
}
