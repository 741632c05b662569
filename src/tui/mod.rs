//! The explorer: a full-screen terminal UI that redraws the force, displacement and spin charts as keys
//! change the parameters.
//!
//! A key press becomes an [`Action`] ([`keys`]), [`App::update`] applies it and re-solves, and [`ui::draw`]
//! draws a frame from the [`App`] without changing it. [`run`] is that loop, generic over the ratatui
//! backend and the [`EventSource`], so tests drive it with scripted events on a `TestBackend`; [`open`]
//! runs it on the real terminal.

pub mod app;
pub mod baseline;
pub mod history;
pub mod keys;
pub mod scenarios;
pub mod sweep;
pub mod terminal;
pub mod ui;

use std::collections::VecDeque;
use std::io::{self, IsTerminal};

use crossterm::event::{self, Event};
use ratatui::Terminal;
use ratatui::backend::Backend;
use ratatui::symbols::Marker;

pub use app::{Action, App, Mode, View};
pub use terminal::FrameSync;
use ui::theme::Theme;

use crate::model::{Params, SolveError};

/// Where events come from: the terminal, or a script in tests.
pub trait EventSource {
    /// The next event, waiting for it; `None` when there will be no more.
    fn next_event(&mut self) -> io::Result<Option<Event>>;
}

/// The terminal's events. Blocks until one arrives, so an idle explorer uses no CPU.
pub struct TerminalEvents;

impl EventSource for TerminalEvents {
    fn next_event(&mut self) -> io::Result<Option<Event>> {
        event::read().map(Some)
    }
}

/// Events given in advance; the loop ends when they run out.
pub struct Scripted(pub VecDeque<Event>);

impl<I: IntoIterator<Item = Event>> From<I> for Scripted {
    fn from(events: I) -> Self {
        Scripted(events.into_iter().collect())
    }
}

impl EventSource for Scripted {
    fn next_event(&mut self) -> io::Result<Option<Event>> {
        Ok(self.0.pop_front())
    }
}

/// Draws one frame, bracketed so the terminal shows it whole.
pub fn draw<B>(terminal: &mut Terminal<B>, app: &App) -> io::Result<()>
where
    B: Backend + FrameSync,
    B::Error: Send + Sync + 'static,
{
    terminal.backend_mut().begin_frame()?;
    terminal
        .draw(|frame| ui::draw(frame, app))
        .map_err(io::Error::other)?;
    terminal.backend_mut().end_frame()
}

/// The event loop: draw, then for each event that matters update and draw again, until the app quits or
/// the events end. Nothing is drawn between events.
pub fn run<B, E>(terminal: &mut Terminal<B>, app: &mut App, events: &mut E) -> io::Result<()>
where
    B: Backend + FrameSync,
    B::Error: Send + Sync + 'static,
    E: EventSource,
{
    draw(terminal, app)?;
    while !app.quit {
        let Some(event) = events.next_event()? else {
            break;
        };
        match event {
            Event::Key(key) => match keys::action_for(&key, &app.mode) {
                Some(action) => app.update(action),
                None => continue,
            },
            Event::Resize(..) => {}
            _ => continue,
        }
        if !app.quit {
            draw(terminal, app)?;
        }
    }
    Ok(())
}

/// How to start the explorer.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// The starting point: the defaults, or what a preset, a scenario file and flags made of them.
    /// `r` and `R` reset to it.
    pub params: Params,
    pub marker: Marker,
    /// False to draw without colours (NO_COLOR).
    pub color: bool,
}

/// Why the explorer could not run.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    #[error("the explorer needs a terminal; for headless use try `snapback simulate`")]
    NotATerminal,
    #[error(transparent)]
    Solve(#[from] SolveError),
    #[error("terminal: {0}")]
    Io(#[from] io::Error),
}

/// True when the NO_COLOR convention asks for no colours (the variable is set and not empty).
pub fn no_color_requested() -> bool {
    std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty())
}

/// Runs the explorer on the real terminal until the user quits; the terminal is restored on every way out.
pub fn open(options: Options) -> Result<(), OpenError> {
    if !io::stdout().is_terminal() {
        return Err(OpenError::NotATerminal);
    }
    let theme = Theme {
        color: options.color,
        marker: options.marker,
    };
    let mut app = App::new(options.params, theme)?;
    let mut session = terminal::Session::start()?;
    run(&mut session.terminal, &mut app, &mut TerminalEvents)?;
    Ok(())
}
