//! The explorer's state and the one place it changes: [`App::update`] applies an [`Action`], re-solves the
//! bounce and recomputes the derived curves; [`App::advance`] moves the time cursor while playing. Drawing
//! only reads an `App`.

use std::time::Duration;

use std::path::PathBuf;

use crate::model::params::{BOUNCE_PARAMS as PARAMS, ParamSpec};
use crate::model::{Bounce, Params, Sample, SolveError, solve};

use super::baseline::Baseline;
use super::heatmap::Heatmap;
use super::history::History;
use super::playback::{self, Speed};
use super::scenarios::FilePrompt;
use super::sweep::Sweep;
use super::travel::Travel;
use super::ui::theme::Theme;

/// Evenly spaced samples of the time series behind the contact charts (transitions are added by the core).
pub const SERIES_SAMPLES: usize = 400;

/// What the right-hand side of the screen shows; Tab cycles through them in this order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// Friction force, cart displacement and ball spin over the contact (the paper's Fig. 3).
    Contact,
    /// Rebound spin against incidence angle for the current parameters (the paper's Fig. 2).
    Sweep,
    /// Rebound spin over cart mass and spring stiffness, computed off the UI thread.
    Heatmap,
}

impl View {
    const ALL: [View; 3] = [View::Contact, View::Sweep, View::Heatmap];

    /// The next view in the Tab order.
    pub fn next(self) -> View {
        let i = Self::ALL.iter().position(|v| *v == self).unwrap_or(0);
        Self::ALL[(i + 1) % Self::ALL.len()]
    }

    /// A short name for the status line.
    pub fn name(self) -> &'static str {
        match self {
            View::Contact => "contact",
            View::Sweep => "ω2 vs θ1",
            View::Heatmap => "ω2 over M, k",
        }
    }
}

/// Something the user asked for; [`super::keys`] turns key presses into these (and a mouse click on a
/// chart into [`Action::CursorTo`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    SelectPrevious,
    SelectNext,
    /// Step the selected parameter up or down by its fine or coarse step.
    Step {
        up: bool,
        coarse: bool,
    },
    /// Open the prompt to type an exact value for the selected parameter.
    StartEdit,
    /// A character typed into the prompt.
    EditInsert(char),
    EditBackspace,
    /// Parse the prompt and apply it.
    EditSubmit,
    EditCancel,
    /// Reset the selected parameter to its default.
    Reset,
    /// Reset every parameter to its default.
    ResetAll,
    NextView,
    /// Move the time cursor to the previous or next multiple of 0.05 ms.
    CursorStep {
        forward: bool,
    },
    /// Move the time cursor to the previous or next phase transition (or to 0 or T past the last one).
    CursorPhase {
        forward: bool,
    },
    /// Move the time cursor to the start of the contact.
    CursorHome,
    /// Move the time cursor to the end of the contact, T.
    CursorEnd,
    /// Move the time cursor to this time, s (clamped to the contact).
    CursorTo(f64),
    /// Play the bounce in slow motion from the cursor, or pause; from the end it starts again at 0.
    TogglePlay,
    /// Double or halve the playback speed.
    ChangeSpeed {
        faster: bool,
    },
    ToggleHelp,
    CloseHelp,
    Quit,
    /// Open the preset picker.
    OpenPicker,
    PickerUp,
    PickerDown,
    /// Apply the preset chosen in the picker.
    PickerApply,
    PickerClose,
    /// Ask for a file name to save the parameters to.
    StartSave,
    /// Ask for a scenario file to open.
    StartOpen,
    /// A character typed into the file prompt.
    PromptInsert(char),
    PromptBackspace,
    /// Complete the file name typed so far.
    PromptComplete,
    PromptSubmit,
    PromptCancel,
    /// Yes, overwrite the existing file.
    ConfirmOverwrite,
    Undo,
    Redo,
    /// Pin the current bounce as the baseline (replacing any).
    PinBaseline,
    ClearBaseline,
    /// Write the time series as CSV and the outcome as JSON.
    Export,
}

/// Who gets the keys.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Mode {
    Normal,
    /// The help overlay is open.
    Help,
    /// The value prompt is open with the text typed so far.
    Editing(String),
    /// The preset picker is open with this preset (an index into `scenario::PRESETS`) highlighted.
    Picker(usize),
    /// A file name is being typed, to save to or open.
    File(FilePrompt),
    /// Saving would replace this existing file: yes or no?
    Overwrite(PathBuf),
}

/// How a status message should look.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tone {
    Info,
    Error,
}

/// A one-line message for the status line; it stays until the next key.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Message {
    pub text: String,
    pub tone: Tone,
}

/// Everything the explorer shows.
#[derive(Debug)]
pub struct App {
    pub params: Params,
    /// Index into [`PARAMS`] of the highlighted parameter.
    pub selected: usize,
    pub view: View,
    pub mode: Mode,
    pub message: Option<Message>,
    pub quit: bool,
    /// Colours and chart marker.
    pub theme: Theme,
    /// The solved bounce for `params`.
    pub bounce: Bounce,
    /// Its time series, for the contact charts.
    pub series: Vec<Sample>,
    /// Rebound spin against incidence angle, for the sweep view.
    pub sweep: Sweep,
    /// The same for the comparison incident spin ([`Sweep::comparison_spin`]).
    pub sweep_comparison: Sweep,
    /// Where the explorer started (R goes back here): the defaults, or a preset, scenario or flags.
    pub start: Params,
    /// Parameter changes that can be undone and redone.
    pub history: History,
    /// A pinned bounce the charts and the outcome compare against.
    pub baseline: Option<Baseline>,
    /// Where scenario files and exports go, and relative file names are read from.
    pub dir: PathBuf,
    /// The scenario file last opened or saved, as typed, offered by the next prompt.
    pub last_file: Option<String>,
    /// The time cursor, s, in `[0, T]`: the charts' vertical line, their readouts and the schematic.
    pub cursor: f64,
    /// True while the bounce plays in slow motion.
    pub playing: bool,
    pub speed: Speed,
    /// The ball's travel and rotation (numerical integrals of the exact solution), for the schematic.
    pub travel: Travel,
    /// omega2 over cart mass and stiffness, for the heatmap view; computed when that view is shown.
    pub heatmap: Heatmap,
}

impl App {
    /// An explorer on `params`, with the incidence angle selected; fails if the bounce cannot be solved.
    pub fn new(params: Params, theme: Theme) -> Result<Self, SolveError> {
        let bounce = solve(&params)?;
        Ok(App {
            params,
            selected: 0,
            view: View::Contact,
            mode: Mode::Normal,
            message: None,
            quit: false,
            theme,
            series: bounce.series(SERIES_SAMPLES),
            sweep: Sweep::compute(&params),
            sweep_comparison: Sweep::comparison(&params),
            cursor: 0.0,
            playing: false,
            speed: Speed::default(),
            travel: Travel::compute(&bounce),
            heatmap: Heatmap::default(),
            bounce,
            start: params,
            history: History::default(),
            baseline: None,
            dir: std::env::current_dir().unwrap_or_else(|_| PathBuf::from(".")),
            last_file: None,
        })
    }

    /// Takes the heatmap rows that have arrived; true if the map changed.
    pub fn poll_heatmap(&mut self) -> bool {
        self.heatmap.poll()
    }

    /// True while the heatmap is being computed: the event loop then wakes now and then to collect rows.
    pub fn heatmap_pending(&self) -> bool {
        self.heatmap.pending()
    }

    /// Asks for the heatmap of the current parameters if it is on screen.
    fn refresh_heatmap(&mut self) {
        if self.view == View::Heatmap {
            self.heatmap.request(&self.params);
        }
    }

    /// The contact time T, s.
    pub fn duration(&self) -> f64 {
        self.bounce.setup.duration
    }

    /// The core's sample at the cursor; at a transition, that of the phase that begins there.
    pub fn cursor_sample(&self) -> Sample {
        self.bounce.sample_at(self.cursor)
    }

    /// When the cursor is exactly on a transition, the sample at the end of the phase before it (the
    /// friction force jumps there; every other value is continuous).
    pub fn cursor_before(&self) -> Option<Sample> {
        let index = self.bounce.phase_index_at(self.cursor);
        (index > 0 && self.bounce.phases[index].start == self.cursor)
            .then(|| self.bounce.sample_in(index - 1, self.cursor))
    }

    /// The transitions the cursor can jump to: 0, the start of every phase after the first, and T.
    fn stops(&self) -> impl Iterator<Item = f64> + '_ {
        std::iter::once(0.0)
            .chain(self.bounce.phases.iter().skip(1).map(|p| p.start))
            .chain(std::iter::once(self.duration()))
    }

    /// Moves the cursor on by `elapsed` wall time at the playback speed, stopping at T. True if anything
    /// changed (only while playing).
    pub fn advance(&mut self, elapsed: Duration) -> bool {
        if !self.playing {
            return false;
        }
        let duration = self.duration();
        self.cursor += elapsed.as_secs_f64() * self.speed.rate();
        if self.cursor >= duration {
            self.cursor = duration;
            self.playing = false;
        }
        true
    }

    /// The spec of the highlighted parameter.
    pub fn selected_spec(&self) -> &'static ParamSpec {
        &PARAMS[self.selected]
    }

    /// Applies one action; any change of parameters re-solves and recomputes everything shown.
    pub fn update(&mut self, action: Action) {
        self.message = None;
        match action {
            Action::SelectPrevious => {
                self.selected = (self.selected + PARAMS.len() - 1) % PARAMS.len();
            }
            Action::SelectNext => self.selected = (self.selected + 1) % PARAMS.len(),
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
            Action::ResetAll => self.try_apply(self.start),
            Action::NextView => {
                self.view = self.view.next();
                self.refresh_heatmap();
            }
            Action::CursorStep { forward } => {
                self.cursor = playback::step(self.cursor, forward, self.duration());
            }
            Action::CursorPhase { forward } => {
                let t = self.cursor;
                let stop = if forward {
                    self.stops().find(|&s| s > t)
                } else {
                    self.stops().filter(|&s| s < t).last()
                };
                if let Some(stop) = stop {
                    self.cursor = stop;
                }
            }
            Action::CursorHome => self.cursor = 0.0,
            Action::CursorEnd => self.cursor = self.duration(),
            Action::CursorTo(t) => self.cursor = t.clamp(0.0, self.duration()),
            Action::TogglePlay => {
                if self.playing {
                    self.playing = false;
                } else {
                    if self.cursor >= self.duration() {
                        self.cursor = 0.0;
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
                self.mode = if self.mode == Mode::Help {
                    Mode::Normal
                } else {
                    Mode::Help
                }
            }
            Action::Quit => self.quit = true,
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
        match spec.parse(&text) {
            Ok(value) => {
                let mut params = self.params;
                params.set(spec.id, value);
                self.try_apply(params);
            }
            Err(e) => self.refuse(e.to_string()),
        }
    }

    /// Solves `params`; on success they become current (a change `u` undoes), otherwise the old ones stay
    /// and the reason is shown.
    fn try_apply(&mut self, params: Params) {
        if params == self.params {
            return;
        }
        let before = self.params;
        match self.set_params(params) {
            Ok(()) => self.history.record(before),
            Err(e) => self.refuse(e.to_string()),
        }
    }

    /// Solves `params` and makes them current with everything derived from them; on failure nothing
    /// changes. The history is the caller's business.
    pub(super) fn set_params(&mut self, params: Params) -> Result<(), SolveError> {
        let bounce = solve(&params)?;
        // The cursor keeps its time if T is unchanged, else its fraction of T; playback goes on.
        let (old, new) = (self.duration(), bounce.setup.duration);
        if new != old {
            self.cursor = (self.cursor / old * new).clamp(0.0, new);
        }
        // The sweeps do not depend on the angle: stepping it needs no new sweep.
        let angle_free = |p: &Params| Params {
            angle_deg: 0.0,
            ..*p
        };
        if angle_free(&params) != angle_free(&self.params) {
            self.sweep = Sweep::compute(&params);
            self.sweep_comparison = Sweep::comparison(&params);
        }
        self.params = params;
        self.refresh_heatmap();
        self.series = bounce.series(SERIES_SAMPLES);
        self.travel = Travel::compute(&bounce);
        self.bounce = bounce;
        Ok(())
    }

    fn refuse(&mut self, reason: String) {
        self.message = Some(Message {
            text: format!("{reason} (value unchanged)"),
            tone: Tone::Error,
        });
    }
}
