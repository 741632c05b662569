//! The explorer's state and the one place it changes: [`App::update`] applies an [`Action`] and asks the
//! workers for what the new parameters need ([`super::solver`]); [`App::poll`] takes their answers as they
//! come; [`App::advance`] moves the time cursor while playing. Nothing here waits for a solve, and drawing
//! only reads an `App`.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::analysis::uncertainty::parse_uncertain;
use crate::model::params::{self, BOUNCE_PARAMS as PARAMS, ParamSpec};
use crate::model::{Params, Sample, SolveError};

mod lab;
mod scenarios;
mod shot_mode;

pub use super::vocabulary::{Action, Message, Mode, Tone, View};

use super::baseline::Baseline;
use super::heatmap::Heatmap;
use super::history::History;
use super::keys::Context;
use super::lab::Lab;
use super::playback::{self, Speed};
use super::shot::{self, Shots};
use super::solved::Solved;
use super::solver::{Answer, Arrival, Solver};
use super::sweep::Sweeps;
use super::theme::Theme;
use super::worker::Crash;

/// Everything the explorer shows.
#[derive(Debug)]
pub struct App {
    /// The parameters as the user set them; shown at once, solved on the worker.
    pub params: Params,
    /// Index into [`PARAMS`] of the highlighted parameter.
    pub selected: usize,
    pub view: View,
    pub mode: Mode,
    pub message: Option<Message>,
    pub quit: bool,
    /// Colours and chart marker.
    pub theme: Theme,
    /// The newest bounce solved: for `params`, or for earlier ones while those are being solved (the
    /// charts are then marked stale). `None` until the first answer.
    pub solved: Option<Arc<Solved>>,
    /// Rebound spin against incidence angle for the current and the comparison spin, for the sweep view:
    /// the newest computed (stale while the current parameters' are being computed).
    pub sweeps: Option<Arc<Sweeps>>,
    /// Where the explorer started (R goes back here): the defaults, or a preset, scenario or flags.
    pub start: Params,
    /// Parameter changes that can be undone and redone.
    pub history: History,
    /// The history as it was when `solved` was made current: put back if a change is refused.
    settled_history: History,
    /// Says what a refusal of the parameters asked for leaves unchanged: `value` or `parameters`.
    unchanged: &'static str,
    /// A pinned bounce the charts and the outcome compare against.
    pub baseline: Option<Baseline>,
    /// Where scenario files and exports go, and relative file names are read from.
    pub dir: PathBuf,
    /// The scenario file last opened or saved, as typed, offered by the next prompt.
    pub last_file: Option<String>,
    /// What the picker lists, read when it opens: the built-in presets, then the user's (true).
    pub presets: Vec<(crate::scenario::Scenario, bool)>,
    /// The parameters as that file holds them: quitting with others asks once.
    pub(super) file_params: Option<Params>,
    /// True after a quit that was asked about: the next quit goes.
    quit_asked: bool,
    /// True when the explorer started in shot mode: `R` comes back to it.
    start_shot: bool,
    /// Rows the help is scrolled down by (the overlay stops at its last row).
    pub help_scroll: u16,
    /// The time cursor, s, in `[0, T]`: the charts' vertical line, their readouts and the schematic.
    pub cursor: f64,
    /// The time along the flight, s, in the shot view: where its ball is drawn.
    pub flight: f64,
    /// True while the bounce plays in slow motion (in the shot view: the flight, in real time).
    pub playing: bool,
    pub speed: Speed,
    /// Wall time between frames while playing.
    pub frame: Duration,
    /// omega2 over cart mass and stiffness, for the heatmap view; computed when that view is shown.
    pub heatmap: Heatmap,
    /// Shot mode and the shots played for the shot view.
    pub shots: Shots,
    /// The workers and their answers so far.
    solver: Solver,
    /// When the parameters or the view last changed: pending panels are marked stale only once an
    /// answer has taken [`STALE_AFTER`], so a quick answer costs no dimmed frame.
    changed_at: Instant,
    /// True while pending panels are drawn dimmed.
    pub stale_marked: bool,
    /// Measurements, free parameters, fits and uncertainties (`--data`, `f`, `F`, `60±1`).
    pub lab: Lab,
}

/// The most the help scrolls: more than its rows on the narrowest screen.
const HELP_SCROLL_LIMIT: u16 = 80;

/// How long an answer may take before the panels waiting for it are dimmed.
pub const STALE_AFTER: Duration = Duration::from_millis(150);

impl App {
    /// An explorer on `params`, with the incidence angle selected; fails only if the parameters are out
    /// of range. The bounce is solved on the worker: the first frame does not wait for it.
    pub fn new(params: Params, theme: Theme) -> Result<Self, SolveError> {
        params.validate()?;
        let mut app = App {
            params,
            selected: 0,
            view: View::Contact,
            mode: Mode::Normal,
            message: None,
            quit: false,
            theme,
            solved: None,
            sweeps: None,
            cursor: 0.0,
            flight: 0.0,
            playing: false,
            speed: Speed::default(),
            frame: playback::FRAME,
            heatmap: Heatmap::default(),
            shots: Shots::default(),
            start: params,
            history: History::default(),
            settled_history: History::default(),
            unchanged: "value",
            baseline: None,
            dir: std::env::current_dir().unwrap_or_else(|_| PathBuf::from(".")),
            last_file: None,
            presets: Vec::new(),
            file_params: None,
            quit_asked: false,
            start_shot: false,
            help_scroll: 0,
            solver: Solver::default(),
            changed_at: Instant::now(),
            stale_marked: false,
            lab: Lab::default(),
        };
        app.want();
        Ok(app)
    }

    /// Asks the workers for what the screen needs now, and takes at once what is already known: the
    /// bounce always, the sweeps in the sweep view (then the baseline's), the map in the heatmap view.
    fn want(&mut self) {
        if let Some(answer) = self.solver.bounce(&self.params) {
            self.answered(self.params, answer);
        }
        if self.view == View::Sweep
            && let Some(sweeps) = self.solver.sweeps(&self.params)
        {
            self.sweeps = Some(sweeps);
            if let Some(base) = &self.baseline {
                let params = base.solved.params;
                self.solver.sweeps(&params);
            }
        }
        if self.view == View::Heatmap {
            self.heatmap.request(&self.params);
        }
        if self.view == View::Shot {
            let base = self.baseline.as_ref().map(|b| b.solved.params);
            self.shots.request(&self.params, base.as_ref());
        }
        self.want_lab();
    }

    /// Takes what the workers have sent, and marks panels stale whose answer is overdue; true if anything
    /// on screen changed.
    pub fn poll(&mut self) -> bool {
        let arrived = self.solver.collect();
        let heatmap = self.heatmap.poll();
        let shot = self.shots.poll(&self.params);
        let lab = self.poll_lab();
        let taken = self.take(arrived);
        let crashes = [
            self.heatmap.take_crash(),
            self.shots.take_crash(),
            self.lab.take_crash(),
        ];
        let crashed = crashes.iter().any(Option::is_some);
        for crash in crashes.into_iter().flatten() {
            self.crashed(crash);
        }
        let marked = (self.solver.busy() || self.shots.pending())
            && self.changed_at.elapsed() >= STALE_AFTER;
        let flipped = marked != self.stale_marked;
        self.stale_marked = marked;
        taken || heatmap || shot || lab || crashed || flipped
    }

    /// Waits until every answer asked for has come, or `patience` has passed; true if all came. For tests
    /// and benchmarks, which step the explorer one settled state at a time; the event loop never waits.
    pub fn settle(&mut self, patience: Duration) -> bool {
        let start = Instant::now();
        loop {
            self.poll();
            if !self.busy() {
                return true;
            }
            let left = patience.saturating_sub(start.elapsed());
            if left.is_zero() {
                return false;
            }
            let wait = left.min(Duration::from_millis(20));
            if self.solver.busy() {
                let arrived = self.solver.wait(wait);
                self.take(arrived);
            } else if self.shots.pending() {
                self.shots.wait(wait, &self.params);
            } else if self.heatmap.pending() {
                self.heatmap.wait(wait);
            } else {
                self.wait_lab(wait);
            }
        }
    }

    /// True while the bounce or the sweeps asked for have not come yet.
    pub fn solving(&self) -> bool {
        self.solver.busy()
    }

    /// True while something asked for has not come yet: the event loop then wakes now and then to take it.
    pub fn busy(&self) -> bool {
        self.solver.busy() || self.heatmap.pending() || self.shots.pending() || self.lab.pending()
    }

    fn take(&mut self, arrived: Vec<Arrival>) -> bool {
        let changed = !arrived.is_empty();
        for arrival in arrived {
            match arrival {
                Arrival::Bounce(params, answer) => {
                    if *params == self.params {
                        self.answered(*params, answer);
                    }
                }
                Arrival::Sweeps(sweeps) => {
                    if sweeps.key == Sweeps::key(&self.params) {
                        self.sweeps = Some(sweeps);
                    }
                }
                Arrival::Crash(crash) => self.crashed(crash),
            }
        }
        if changed {
            self.want();
        }
        changed
    }

    /// The answer for `params`, the current parameters: shown, or if refused, the parameters go back to
    /// those of the bounce shown and the reason is given.
    fn answered(&mut self, params: Params, answer: Answer) {
        match answer {
            Ok(solved) => {
                if self.solved.as_ref().is_some_and(|s| s.params == params) {
                    return;
                }
                // The cursor keeps its time if T is unchanged, else its fraction of T; playback goes on.
                let new = solved.duration();
                if let Some(old) = self.solved.as_ref().map(|s| s.duration())
                    && new != old
                {
                    self.cursor = (self.cursor / old * new).clamp(0.0, new);
                }
                self.cursor = self.cursor.clamp(0.0, new);
                self.solved = Some(solved);
                self.settled_history = self.history.clone();
                self.stale_marked &= self.solver.busy();
            }
            Err(reason) => {
                // Back to the bounce on screen, if there is one (a refused start has none).
                if let Some(solved) = &self.solved
                    && solved.params != self.params
                {
                    self.params = solved.params;
                    self.history = self.settled_history.clone();
                    self.want();
                }
                // In shot mode the panel shows what the shot decides, which the bounce left on screen
                // (from before shot mode) may not be.
                let not_the_shot = self.shots.on
                    && self
                        .strings_params(self.params)
                        .is_ok_and(|p| p != self.params);
                let shown = if not_the_shot {
                    "; the bounce shown is not the shot's"
                } else {
                    ""
                };
                self.message = Some(Message {
                    text: format!("{reason} ({} unchanged{shown})", self.unchanged),
                    tone: Tone::Error,
                });
            }
        }
    }

    /// A worker's job panicked: the status line says so (the worker has given up that job, so nothing
    /// waits for it).
    fn crashed(&mut self, crash: Crash) {
        self.message = Some(Message {
            text: crash.to_string(),
            tone: Tone::Error,
        });
    }

    /// True while the bounce on screen is not that of the current parameters.
    pub fn stale(&self) -> bool {
        self.solved.as_ref().is_none_or(|s| s.params != self.params)
    }

    /// True while the sweeps on screen are not those of the current parameters.
    pub fn sweeps_stale(&self) -> bool {
        self.sweeps
            .as_ref()
            .is_none_or(|s| s.key != Sweeps::key(&self.params))
    }

    /// The baseline's sweeps, if computed.
    pub fn baseline_sweeps(&self) -> Option<Arc<Sweeps>> {
        let base = self.baseline.as_ref()?;
        self.solver.known_sweeps(&base.solved.params)
    }

    /// The contact time T, s, of the bounce on screen (0 before the first).
    pub fn duration(&self) -> f64 {
        self.solved.as_ref().map_or(0.0, |s| s.duration())
    }

    /// The core's sample at the cursor; at a transition, that of the phase that begins there.
    pub fn cursor_sample(&self) -> Option<Sample> {
        Some(self.solved.as_ref()?.sample_at(self.cursor))
    }

    /// Moves the cursor on by `elapsed` wall time at the playback speed, stopping at T. True if anything
    /// changed (only while playing).
    /// In the shot view the flight plays instead, in real time.
    pub fn advance(&mut self, elapsed: Duration) -> bool {
        if !self.playing {
            return false;
        }
        let rate = if self.view == View::Shot {
            1.0
        } else {
            self.speed.rate()
        };
        let (time, end) = self.timeline();
        *time += elapsed.as_secs_f64() * rate;
        if *time >= end {
            *time = end;
            self.playing = false;
        }
        true
    }

    /// The time that plays in this view and where it ends: the flight's in the shot view, s (0 before
    /// the shot is played), else the contact's cursor and T.
    fn timeline(&mut self) -> (&mut f64, f64) {
        if self.view == View::Shot {
            let end = self.shots.flight_end().unwrap_or(0.0);
            (&mut self.flight, end)
        } else {
            let end = self.duration();
            (&mut self.cursor, end)
        }
    }

    /// Shows the notes on the starting flags (a bare number far outside its usual range: `--cart-mass
    /// 10` is read as 10 kg) in the status line, as the commands write them on stderr, after any message
    /// the start gave; the next key clears them.
    pub fn start_notes(&mut self, notes: &[String]) {
        if notes.is_empty() {
            return;
        }
        let notes: Vec<String> = notes.iter().map(|n| format!("note: {n}")).collect();
        let notes = notes.join("; ");
        self.message = Some(match self.message.take() {
            Some(m) => Message {
                text: format!("{}; {notes}", m.text),
                ..m
            },
            None => Message {
                text: notes,
                tone: Tone::Info,
            },
        });
    }

    /// Where the user is, for the keys the help and the hints offer; `schematic` when it is drawn.
    pub fn key_context(&self, schematic: bool) -> Context {
        Context {
            view: self.view,
            shot_on: self.shots.on,
            schematic,
            data: self.lab.data.is_some(),
        }
    }

    /// The spec of the highlighted parameter.
    pub fn selected_spec(&self) -> &'static ParamSpec {
        &self.listed()[self.selected]
    }

    /// The parameters the panel lists: the bounce's, and the shot's too in shot mode.
    pub fn listed(&self) -> &'static [ParamSpec] {
        if self.shots.on {
            params::PARAMS
        } else {
            PARAMS
        }
    }

    /// Applies one action; any change of parameters re-solves and recomputes everything shown.
    pub fn update(&mut self, action: Action) {
        self.message = None;
        // Only a quit right after the question quits.
        self.quit_asked &= action == Action::Quit;
        let listed = self.listed().len();
        if self.shots.on
            && matches!(
                action,
                Action::Step { .. } | Action::StartEdit | Action::Reset | Action::ToggleFree
            )
            && shot::derived(self.selected_spec().id)
        {
            return self.refuse(shot::refusal(self.selected_spec()));
        }
        match action {
            Action::SelectPrevious => {
                self.selected = (self.selected + listed - 1) % listed;
            }
            Action::SelectNext => self.selected = (self.selected + 1) % listed,
            Action::Step { up, coarse } => self.step(up, coarse),
            Action::StartEdit => self.mode = Mode::Editing(String::new()),
            Action::EditInsert(c) => {
                if let Mode::Editing(text) = &mut self.mode {
                    text.push(c);
                }
            }
            Action::EditBackspace => {
                if let Mode::Editing(text) = &mut self.mode {
                    text.pop();
                }
            }
            Action::EditSubmit => self.submit_edit(),
            Action::EditCancel | Action::CloseHelp => self.mode = Mode::Normal,
            Action::Reset => {
                let spec = self.selected_spec();
                let mut params = self.params;
                params.set(spec.id, self.start.get(spec.id));
                self.try_apply(params);
            }
            Action::ResetAll => self.reset_all(),
            Action::NextView => {
                // What plays is the view's own: the flight in the shot view, the contact elsewhere.
                let shot = self.view == View::Shot;
                self.view = self.view.next();
                self.playing &= shot == (self.view == View::Shot);
                if self.view == View::Shot && !self.shots.on {
                    self.enter_shot();
                }
                self.changed_at = Instant::now();
                self.want();
            }
            Action::CursorStep { forward } => {
                self.cursor = playback::step(self.cursor, forward, self.duration());
            }
            Action::CursorPhase { forward } => {
                let t = self.cursor;
                let stop = self.solved.as_ref().and_then(|s| {
                    if forward {
                        s.stops().find(|&s| s > t)
                    } else {
                        s.stops().filter(|&s| s < t).last()
                    }
                });
                if let Some(stop) = stop {
                    self.cursor = stop;
                }
            }
            Action::CursorHome => *self.timeline().0 = 0.0,
            Action::CursorEnd => {
                let (time, end) = self.timeline();
                *time = end;
            }
            Action::CursorTo(t) => self.cursor = t.clamp(0.0, self.duration()),
            Action::TogglePlay => {
                if self.playing {
                    self.playing = false;
                } else {
                    let (time, end) = self.timeline();
                    if *time >= end {
                        *time = 0.0;
                    }
                    self.playing = true;
                }
            }
            Action::ChangeSpeed { faster } => {
                if !self.speed.change(faster) {
                    let end = if faster { "fastest" } else { "slowest" };
                    self.message = Some(Message {
                        text: format!("playback is at its {end}: {}", self.speed.label()),
                        tone: Tone::Info,
                    });
                }
            }
            Action::ToggleHelp => {
                self.help_scroll = 0;
                self.mode = if self.mode == Mode::Help {
                    Mode::Normal
                } else {
                    Mode::Help
                }
            }
            Action::ScrollHelp { down } => {
                self.help_scroll = if down {
                    (self.help_scroll + 1).min(HELP_SCROLL_LIMIT)
                } else {
                    self.help_scroll.saturating_sub(1)
                };
            }
            Action::Quit if self.lab.fitting.is_some() => self.update_lab(action),
            Action::Quit => self.quit_or_ask(),
            Action::ToggleFree | Action::Fit => self.update_lab(action),
            Action::ToggleShot => {
                if self.shots.on {
                    self.leave_shot();
                } else {
                    self.enter_shot();
                }
            }
            Action::OpenPicker
            | Action::PickerUp
            | Action::PickerDown
            | Action::PickerApply
            | Action::PickerClose
            | Action::StartSave
            | Action::StartOpen
            | Action::PromptInsert(_)
            | Action::PromptBackspace
            | Action::PromptComplete
            | Action::PromptSubmit
            | Action::PromptCancel
            | Action::ConfirmOverwrite
            | Action::Undo
            | Action::Redo
            | Action::PinBaseline
            | Action::ClearBaseline
            | Action::Export => self.update_scenarios(action),
        }
    }

    /// Quits, unless the parameters differ from the scenario file last opened or saved and this is the
    /// first quit since: then it says so once, and the next quit goes.
    fn quit_or_ask(&mut self) {
        let unsaved = self.file_params.is_some_and(|p| p != self.params);
        if !unsaved || self.quit_asked {
            self.quit = true;
            return;
        }
        self.quit_asked = true;
        let file = self.last_file.clone().unwrap_or_default();
        self.message = Some(Message {
            text: format!("changes since {file} are not saved: quit again to quit, s saves"),
            tone: Tone::Info,
        });
    }

    fn step(&mut self, up: bool, coarse: bool) {
        let spec = self.selected_spec();
        let old = self.params.get(spec.id);
        let step = if coarse { spec.coarse } else { spec.fine };
        let new = step.apply(old, up, &spec.range);
        if new == old {
            self.message = Some(Message {
                text: format!(
                    "{} {} is at the end of its range {}",
                    spec.label,
                    spec.symbol,
                    spec.range_text()
                ),
                tone: Tone::Info,
            });
            return;
        }
        let mut params = self.params;
        params.set(spec.id, new);
        self.try_apply(params);
    }

    fn submit_edit(&mut self) {
        let Mode::Editing(text) = std::mem::replace(&mut self.mode, Mode::Normal) else {
            return;
        };
        let spec = self.selected_spec();
        match parse_uncertain(spec, &text) {
            Ok((_, Some(_))) if spec.integer => self.refuse(format!(
                "{} {} is a whole number: it takes no uncertainty",
                spec.label, spec.symbol
            )),
            Ok((value, sigma)) => {
                if let Some(sigma) = sigma {
                    self.spread_typed(spec, sigma);
                }
                let mut params = self.params;
                params.set(spec.id, value);
                self.try_apply(params);
                // A bare number far outside the usual range gets the command line's note, unless
                // the value was refused.
                if self.message.is_none()
                    && let Some(note) = spec.bare_note(spec.label, &text)
                {
                    self.message = Some(Message {
                        text: format!("note: {note}"),
                        tone: Tone::Info,
                    });
                }
            }
            // The core names the command-line flag; the panel's name is what the user sees here.
            Err(e) => self.refuse(e.to_string().replace(
                &format!("--{}", spec.flag),
                &format!("{} {}", spec.label, spec.symbol),
            )),
        }
    }

    /// Makes `params` current (a change `u` undoes) and asks for their bounce; if the core refuses it,
    /// the old ones come back and the reason is shown.
    fn try_apply(&mut self, params: Params) {
        let params = match self.strings_params(params) {
            Ok(params) => params,
            Err(reason) => return self.refuse(reason),
        };
        if params == self.params {
            return;
        }
        self.history.record(self.params);
        self.set_params(params, "value");
    }

    /// Makes `params` current and asks for everything derived from them. The history is the caller's
    /// business; `unchanged` names what a refusal leaves as it was (`value` or `parameters`).
    pub(super) fn set_params(&mut self, params: Params, unchanged: &'static str) {
        // Edits, presets and files the frame change cannot take are refused before they come here; what
        // comes anyway (an undo to before shot mode) is kept as it is.
        self.params = self.strings_params(params).unwrap_or(params);
        self.changed_at = Instant::now();
        self.unchanged = unchanged;
        self.want();
    }

    /// `params`, with the incidence the strings see in shot mode; why not, if the racquet never meets
    /// the ball.
    pub(super) fn strings_params(&self, params: Params) -> Result<Params, String> {
        if self.shots.on {
            shot::strings_params(&params).map_err(|e| e.to_string())
        } else {
            Ok(params)
        }
    }

    /// True while the shot on screen is not that of the current parameters.
    pub fn shot_stale(&self) -> bool {
        self.shots.stale(&self.params)
    }

    fn refuse(&mut self, reason: String) {
        self.message = Some(Message {
            text: format!("{reason} (value unchanged)"),
            tone: Tone::Error,
        });
    }
}
