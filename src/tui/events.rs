//! Where the event loop's inputs come from: the terminal and a clock ([`super::input`]), or a script in
//! tests ([`Scripted`]).

use std::collections::VecDeque;
use std::io;
use std::time::Duration;

use crossterm::event::Event;

/// What the event loop reacts to: a terminal event, or wall time passing while the bounce plays.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Input {
    Event(Event),
    /// Wall time elapsed since the previous tick (or since playback started).
    Tick(Duration),
}

impl From<Event> for Input {
    fn from(event: Event) -> Self {
        Input::Event(event)
    }
}

/// Where inputs come from: the terminal and a clock, or a script in tests.
pub trait EventSource {
    /// The next input. With `wait` set (while playing, or while an answer is awaited), a
    /// [`Input::Tick`] comes at least every `wait` of wall time if no event comes first; with `None`,
    /// wait for an event for as long as it takes: time passing alone brings nothing. `None` when there
    /// will be no more inputs.
    fn next_input(&mut self, wait: Option<Duration>) -> io::Result<Option<Input>>;

    /// An event that has already arrived, without waiting: the loop takes them all before it draws, so a
    /// burst of keys costs one frame.
    fn ready_input(&mut self) -> io::Result<Option<Input>> {
        Ok(None)
    }

    /// True when the loop should let the workers finish before each input, as scripted tests want: each
    /// step then sees the answers to the one before.
    fn settles(&self) -> bool {
        false
    }
}

/// Inputs given in advance; the loop ends when they run out. A tick scripted while the loop is not
/// waking on a timer stands for time passing with nothing happening, as on the terminal: it is skipped.
/// The workers finish before each input ([`EventSource::settles`]).
pub struct Scripted(pub VecDeque<Input>);

impl<I, T> From<I> for Scripted
where
    I: IntoIterator<Item = T>,
    T: Into<Input>,
{
    fn from(inputs: I) -> Self {
        Scripted(inputs.into_iter().map(Into::into).collect())
    }
}

impl EventSource for Scripted {
    fn next_input(&mut self, wait: Option<Duration>) -> io::Result<Option<Input>> {
        while let Some(input) = self.0.pop_front() {
            if wait.is_some() || !matches!(input, Input::Tick(_)) {
                return Ok(Some(input));
            }
        }
        Ok(None)
    }

    fn settles(&self) -> bool {
        true
    }
}
