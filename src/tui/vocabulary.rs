//! The explorer's vocabulary: what the user asks for ([`Action`]), who gets the keys ([`Mode`]), which
//! view is shown ([`View`]) and how the status line speaks ([`Message`]). It sits below the state
//! ([`super::app`]) and the key table ([`super::keys`]), which both speak it.

use std::path::PathBuf;

/// What the right-hand side of the screen shows; Tab cycles through them in this order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// Friction force, cart displacement and ball spin over the contact (the paper's Fig. 3).
    Contact,
    /// Rebound spin against incidence angle for the current parameters (the paper's Fig. 2).
    Sweep,
    /// Rebound spin over cart mass and spring stiffness, computed off the UI thread.
    Heatmap,
    /// A stroke on court from the side: the flight, the court bounce and the kick (shot mode).
    Shot,
}

impl View {
    const ALL: [View; 4] = [View::Contact, View::Sweep, View::Heatmap, View::Shot];

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
            View::Shot => "shot",
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
    /// Scroll the help a row down or up.
    ScrollHelp {
        down: bool,
    },
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
    /// Mark the selected parameter free for a fit, or fixed again.
    ToggleFree,
    /// Fit the free parameters to the measurements in the background, or stop the fit under way.
    Fit,
    /// Turn shot mode on, or off again (the bounce's own incidence comes back).
    ToggleShot,
}

/// Who gets the keys.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Mode {
    Normal,
    /// The help overlay is open.
    Help,
    /// The value prompt is open with the text typed so far.
    Editing(String),
    /// The preset picker is open with this preset (an index into `App::presets`) highlighted.
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

/// What a file prompt is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    Save,
    Open,
}

/// The file prompt: what it is for, the name typed so far, and the name Enter takes when none is typed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilePrompt {
    pub kind: FileKind,
    pub text: String,
    pub default: String,
}
