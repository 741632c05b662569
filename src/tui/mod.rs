//! The explorer: a full-screen terminal UI that redraws the force, displacement and spin charts as keys
//! change the parameters.
//!
//! A key press becomes an [`Action`] ([`keys`]), [`App::update`] applies it and asks the workers for the
//! new bounce ([`solver`]), and [`ui::draw`] draws a frame from the [`App`] without changing it; charts
//! whose answer is pending are drawn stale until it comes. While the bounce plays in slow motion, clock
//! ticks move the time cursor ([`App::advance`]). [`run`] is that loop, generic over the ratatui backend
//! and the [`EventSource`], so tests drive it with scripted events and ticks on a `TestBackend`; [`open`]
//! runs it on the real terminal.

pub mod app;
pub mod band;
pub mod baseline;
pub mod decode;
pub mod events;
pub mod grid;
pub mod heatmap;
pub mod history;
pub mod input;
pub mod keys;
pub mod lab;
pub mod locale;
pub mod output;
pub mod peak;
pub mod playback;
pub mod residuals;
pub mod scenarios;
pub mod shot;
pub mod solved;
pub mod solver;
pub mod sweep;
pub mod terminal;
pub mod theme;
pub mod travel;
pub mod ui;
pub mod values;
pub mod vocabulary;
pub mod worker;

use std::io::{self, IsTerminal};
use std::time::Duration;

use crossterm::event::{Event, MouseButton, MouseEvent, MouseEventKind};
use ratatui::Terminal;
use ratatui::backend::Backend;
use ratatui::layout::{Position, Rect};
use ratatui::symbols::Marker;

pub use app::App;
pub use events::{EventSource, Input, Scripted};
pub use input::TerminalEvents;
pub use output::FrameSync;
use theme::Theme;
pub use vocabulary::{Action, Mode, View};

use crate::analysis::fit::data::Dataset;
use crate::model::{Params, SolveError};

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

/// The action a mouse event asks for: a left click or drag on the contact charts puts the time cursor
/// at the time under the pointer.
fn mouse_action(mouse: &MouseEvent, screen: Rect, app: &App) -> Option<Action> {
    match mouse.kind {
        MouseEventKind::Down(MouseButton::Left) | MouseEventKind::Drag(MouseButton::Left) => {
            ui::time_at(screen, app, mouse.column, mouse.row).map(Action::CursorTo)
        }
        _ => None,
    }
}

/// How long a scripted run lets the workers take before each input.
const PATIENCE: Duration = Duration::from_secs(120);

/// How often the loop wakes to take the workers' answers while one is awaited and nothing plays.
pub const ANSWER_POLL: Duration = Duration::from_millis(15);

/// The event loop: draw, then wait for an input; take it and every other input already there, the
/// workers' answers too, and draw once if anything changed; until the app quits or the inputs end. While
/// the bounce plays, the loop asks for a tick every [`App::frame`] and draws each; while an answer is awaited it
/// wakes every [`ANSWER_POLL`] to take it; otherwise nothing is drawn between events.
pub fn run<B, E>(terminal: &mut Terminal<B>, app: &mut App, events: &mut E) -> io::Result<()>
where
    B: Backend + FrameSync,
    B::Error: Send + Sync + 'static,
    E: EventSource,
{
    if events.settles() {
        app.settle(PATIENCE);
    }
    draw(terminal, app)?;
    while !app.quit {
        if events.settles() && app.busy() {
            app.settle(PATIENCE);
            draw(terminal, app)?;
        }
        let wait = if app.playing {
            Some(app.frame)
        } else {
            app.busy().then_some(ANSWER_POLL)
        };
        let Some(input) = events.next_input(wait)? else {
            break;
        };
        let mut redraw = handle(terminal, app, input)?;
        while !app.quit
            && let Some(input) = events.ready_input()?
        {
            redraw |= handle(terminal, app, input)?;
        }
        redraw |= app.poll();
        if redraw && !app.quit {
            draw(terminal, app)?;
        }
    }
    Ok(())
}

/// Applies one input; true if the screen should be drawn again. Behind the "terminal too small" notice
/// only quitting is taken.
fn handle<B>(terminal: &mut Terminal<B>, app: &mut App, input: Input) -> io::Result<bool>
where
    B: Backend,
    B::Error: Send + Sync + 'static,
{
    let size = terminal.size().map_err(io::Error::other)?;
    let screen = Rect::from((Position::ORIGIN, size));
    let action = match input {
        Input::Tick(elapsed) => return Ok(app.advance(elapsed)),
        Input::Event(Event::Key(key)) => keys::action_for(&key, &app.mode),
        Input::Event(Event::Mouse(mouse)) => mouse_action(&mouse, screen, app),
        Input::Event(Event::Resize(..)) => return Ok(true),
        Input::Event(_) => None,
    };
    match action {
        Some(action) if ui::fits(screen) || action == Action::Quit => {
            app.update(action);
            Ok(true)
        }
        _ => Ok(false),
    }
}

/// How to start the explorer.
#[derive(Clone, Debug)]
pub struct Options {
    /// The starting point: the defaults, or what a preset, a scenario file and flags made of them.
    /// `r` and `R` reset to it.
    pub params: Params,
    pub marker: Marker,
    /// False to draw without colours (NO_COLOR).
    pub color: bool,
    /// Colours for a light background (`--theme light`).
    pub light: bool,
    /// Write ASCII only (a locale that is not UTF-8, or `--ascii`).
    pub ascii: bool,
    /// Frames a second while the bounce plays.
    pub fps: u32,
    /// Explore a shot from the start (a shot preset, scenario or flag).
    pub shot: bool,
    /// Measurements to show beside the model and to fit (`--data`).
    pub data: Option<Dataset>,
    /// The notes on the starting flags (a bare number far outside its usual range), for the status line.
    pub notes: Vec<String>,
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
    // Braille is not ASCII: dots stand in for it.
    let marker = match options.marker {
        Marker::Braille if options.ascii => Marker::Dot,
        marker => marker,
    };
    let theme = Theme {
        color: options.color,
        marker,
        ascii: options.ascii,
        light: options.light,
    };
    let mut app = App::new(options.params, theme)?;
    if options.shot {
        app.start_in_shot_mode();
    }
    if let Some(data) = options.data {
        app.load_data(data);
    }
    app.start_notes(&options.notes);
    app.frame = Duration::from_secs_f64(1.0 / f64::from(options.fps.max(1)));
    let mut session = terminal::Session::start(options.ascii)?;
    let mut events = TerminalEvents::start()?;
    run(&mut session.terminal, &mut app, &mut events)?;
    Ok(())
}
