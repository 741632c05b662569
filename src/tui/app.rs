//! The explorer's state and the one place it changes: [`App::update`] applies an [`Action`], re-solves the
//! bounce and recomputes the derived curves. Drawing only reads an `App`.

use std::path::PathBuf;

use crate::model::params::{PARAMS, ParamSpec};
use crate::model::{Bounce, Params, Sample, SolveError, solve};

use super::baseline::Baseline;
use super::history::History;
use super::scenarios::FilePrompt;
use super::sweep::Sweep;
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
}

impl View {
    const ALL: [View; 2] = [View::Contact, View::Sweep];

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
        }
    }
}

/// Something the user asked for; [`super::keys`] turns key presses into these.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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
#[derive(Clone, Debug)]
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
            bounce,
            start: params,
            history: History::default(),
            baseline: None,
            dir: std::env::current_dir().unwrap_or_else(|_| PathBuf::from(".")),
            last_file: None,
        })
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
            Action::NextView => self.view = self.view.next(),
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
        self.params = params;
        self.series = bounce.series(SERIES_SAMPLES);
        self.sweep = Sweep::compute(&params);
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
