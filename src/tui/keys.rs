//! Keys: the one table that both turns key presses into [`Action`]s and writes the help overlay and the
//! status-line hints, so what the help says is what the keys do.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::app::{Action, Mode};

/// One key, with the modifiers that matter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// The key without Shift, Ctrl or Alt (a letter matches whatever its case says, Shift or not).
    Plain(KeyCode),
    /// The key with Shift.
    Shift(KeyCode),
    /// The letter with Ctrl.
    Ctrl(char),
}

impl Key {
    fn matches(self, event: &KeyEvent) -> bool {
        let m = event.modifiers;
        let ctrl_or_alt = m.intersects(KeyModifiers::CONTROL | KeyModifiers::ALT);
        match self {
            // Terminals report upper-case letters with or without Shift; the character decides.
            Key::Plain(KeyCode::Char(c)) => event.code == KeyCode::Char(c) && !ctrl_or_alt,
            Key::Plain(code) => event.code == code && m.is_empty(),
            Key::Shift(code) => event.code == code && m == KeyModifiers::SHIFT,
            Key::Ctrl(c) => {
                event.code == KeyCode::Char(c)
                    && m.contains(KeyModifiers::CONTROL)
                    && !m.contains(KeyModifiers::ALT)
            }
        }
    }

    /// How the help overlay names the key.
    pub fn label(self) -> String {
        fn code(code: KeyCode) -> String {
            match code {
                KeyCode::Up => "Up".into(),
                KeyCode::Down => "Down".into(),
                KeyCode::Left => "Left".into(),
                KeyCode::Right => "Right".into(),
                KeyCode::Enter => "Enter".into(),
                KeyCode::Esc => "Esc".into(),
                KeyCode::Tab => "Tab".into(),
                KeyCode::Backspace => "Backspace".into(),
                KeyCode::Char(c) => c.to_string(),
                other => format!("{other:?}"),
            }
        }
        match self {
            Key::Plain(c) => code(c),
            Key::Shift(c) => format!("Shift+{}", code(c)),
            Key::Ctrl(c) => format!("Ctrl-{}", c.to_ascii_uppercase()),
        }
    }
}

/// Keys bound to one action, with the words that explain it.
#[derive(Clone, Copy, Debug)]
pub struct Binding {
    pub keys: &'static [Key],
    pub action: Action,
    /// What the help overlay says the keys do.
    pub help: &'static str,
    /// A short form for the status line (keys, word), if the binding earns a place there.
    pub hint: Option<(&'static str, &'static str)>,
}

const fn bind(
    keys: &'static [Key],
    action: Action,
    help: &'static str,
    hint: Option<(&'static str, &'static str)>,
) -> Binding {
    Binding {
        keys,
        action,
        help,
        hint,
    }
}

use Key::{Ctrl, Plain, Shift};

/// The keys of the explorer (also while the help overlay is open, where Esc closes the overlay instead).
pub const EXPLORER: &[Binding] = &[
    bind(
        &[Plain(KeyCode::Up), Plain(KeyCode::Char('k'))],
        Action::SelectPrevious,
        "select the parameter above",
        Some(("↑↓", "select")),
    ),
    bind(
        &[Plain(KeyCode::Down), Plain(KeyCode::Char('j'))],
        Action::SelectNext,
        "select the parameter below",
        None,
    ),
    bind(
        &[Plain(KeyCode::Left), Plain(KeyCode::Char('h'))],
        Action::Step {
            up: false,
            coarse: false,
        },
        "decrease by a fine step (1 deg for the angle)",
        Some(("←→", "step")),
    ),
    bind(
        &[Plain(KeyCode::Right), Plain(KeyCode::Char('l'))],
        Action::Step {
            up: true,
            coarse: false,
        },
        "increase by a fine step",
        None,
    ),
    bind(
        &[Shift(KeyCode::Left), Plain(KeyCode::Char('H'))],
        Action::Step {
            up: false,
            coarse: true,
        },
        "decrease by a coarse step (10 deg for the angle)",
        Some(("H/L", "coarse")),
    ),
    bind(
        &[Shift(KeyCode::Right), Plain(KeyCode::Char('L'))],
        Action::Step {
            up: true,
            coarse: true,
        },
        "increase by a coarse step",
        None,
    ),
    bind(
        &[Plain(KeyCode::Enter), Plain(KeyCode::Char('e'))],
        Action::StartEdit,
        "type an exact value; units as on the command line: 10g",
        Some(("⏎", "type")),
    ),
    bind(
        &[Plain(KeyCode::Char('r'))],
        Action::Reset,
        "reset the selected parameter to where it started",
        Some(("r", "reset")),
    ),
    bind(
        &[Plain(KeyCode::Char('R'))],
        Action::ResetAll,
        "reset every parameter to where the explorer started",
        Some(("R", "all")),
    ),
    bind(
        &[Plain(KeyCode::Tab)],
        Action::NextView,
        "switch view: contact charts / ω2 against θ1 (Fig. 2)",
        Some(("Tab", "view")),
    ),
    bind(
        &[Plain(KeyCode::Char('?'))],
        Action::ToggleHelp,
        "open or close this help",
        Some(("?", "help")),
    ),
    bind(
        &[Plain(KeyCode::Char('q')), Plain(KeyCode::Esc), Ctrl('c')],
        Action::Quit,
        "quit (Esc closes this help first)",
        Some(("q", "quit")),
    ),
    bind(
        &[Plain(KeyCode::Char('p'))],
        Action::OpenPicker,
        "pick a preset: the paper's cases and some what-ifs",
        Some(("p", "presets")),
    ),
    bind(
        &[Plain(KeyCode::Char('s'))],
        Action::StartSave,
        "save the parameters as a scenario file (TOML)",
        Some(("s", "save")),
    ),
    bind(
        &[Plain(KeyCode::Char('o'))],
        Action::StartOpen,
        "open a scenario file",
        Some(("o", "open")),
    ),
    bind(
        &[Plain(KeyCode::Char('u'))],
        Action::Undo,
        "undo the last parameter change",
        Some(("u", "undo")),
    ),
    bind(&[Ctrl('r')], Action::Redo, "redo what u undid", None),
    bind(
        &[Plain(KeyCode::Char('b'))],
        Action::PinBaseline,
        "pin this bounce as the dimmer baseline (again: re-pin)",
        Some(("b", "baseline")),
    ),
    bind(
        &[Plain(KeyCode::Char('B'))],
        Action::ClearBaseline,
        "clear the baseline",
        None,
    ),
    bind(
        &[Plain(KeyCode::Char('x'))],
        Action::Export,
        "export the series (CSV) and outcome (JSON) here",
        Some(("x", "export")),
    ),
];

/// The keys of the value prompt.
pub const PROMPT: &[Binding] = &[
    bind(
        &[Plain(KeyCode::Enter)],
        Action::EditSubmit,
        "apply; a bare number is in kg, m, s, N/m, deg or rad/s",
        Some(("⏎", "apply")),
    ),
    bind(
        &[Plain(KeyCode::Esc)],
        Action::EditCancel,
        "leave the value as it was",
        Some(("Esc", "cancel")),
    ),
    bind(
        &[Plain(KeyCode::Backspace)],
        Action::EditBackspace,
        "delete the last character",
        None,
    ),
    bind(&[Ctrl('c')], Action::Quit, "quit", None),
];

/// The keys of the preset picker.
pub const PICKER: &[Binding] = &[
    bind(
        &[Plain(KeyCode::Up), Plain(KeyCode::Char('k'))],
        Action::PickerUp,
        "the preset above",
        Some(("↑↓", "choose")),
    ),
    bind(
        &[Plain(KeyCode::Down), Plain(KeyCode::Char('j'))],
        Action::PickerDown,
        "the preset below",
        None,
    ),
    bind(
        &[Plain(KeyCode::Enter)],
        Action::PickerApply,
        "apply it (u undoes)",
        Some(("⏎", "apply")),
    ),
    bind(
        &[
            Plain(KeyCode::Esc),
            Plain(KeyCode::Char('p')),
            Plain(KeyCode::Char('q')),
        ],
        Action::PickerClose,
        "close, changing nothing",
        Some(("Esc", "close")),
    ),
    bind(&[Ctrl('c')], Action::Quit, "quit", None),
];

/// The keys of the file-name prompt (save and open).
pub const FILE_PROMPT: &[Binding] = &[
    bind(
        &[Plain(KeyCode::Enter)],
        Action::PromptSubmit,
        "save or open (nothing typed: the name in brackets)",
        Some(("⏎", "ok")),
    ),
    bind(
        &[Plain(KeyCode::Esc)],
        Action::PromptCancel,
        "cancel",
        Some(("Esc", "cancel")),
    ),
    bind(
        &[Plain(KeyCode::Tab)],
        Action::PromptComplete,
        "complete the file name (nothing typed: take the one in brackets)",
        Some(("Tab", "complete")),
    ),
    bind(
        &[Plain(KeyCode::Backspace)],
        Action::PromptBackspace,
        "delete the last character",
        None,
    ),
    bind(&[Ctrl('c')], Action::Quit, "quit", None),
];

/// The keys of the question whether to overwrite an existing file.
pub const OVERWRITE: &[Binding] = &[
    bind(
        &[Plain(KeyCode::Char('y'))],
        Action::ConfirmOverwrite,
        "replace the file",
        Some(("y", "overwrite")),
    ),
    bind(
        &[Plain(KeyCode::Char('n')), Plain(KeyCode::Esc)],
        Action::PromptCancel,
        "keep the file, save nothing",
        Some(("n", "keep it")),
    ),
    bind(&[Ctrl('c')], Action::Quit, "quit", None),
];

/// The bindings in force in `mode`.
pub fn bindings(mode: &Mode) -> &'static [Binding] {
    match mode {
        Mode::Editing(_) => PROMPT,
        Mode::Normal | Mode::Help => EXPLORER,
        Mode::Picker(_) => PICKER,
        Mode::File(_) => FILE_PROMPT,
        Mode::Overwrite(_) => OVERWRITE,
    }
}

/// The action a key press asks for in `mode`, if any. Key releases are ignored.
pub fn action_for(event: &KeyEvent, mode: &Mode) -> Option<Action> {
    if event.kind == KeyEventKind::Release {
        return None;
    }
    if *mode == Mode::Help && Plain(KeyCode::Esc).matches(event) {
        return Some(Action::CloseHelp);
    }
    let bound = bindings(mode)
        .iter()
        .find(|b| b.keys.iter().any(|k| k.matches(event)))
        .map(|b| b.action);
    match (bound, mode, event.code) {
        (None, Mode::Editing(_), KeyCode::Char(c))
            if !event
                .modifiers
                .intersects(KeyModifiers::CONTROL | KeyModifiers::ALT) =>
        {
            Some(Action::EditInsert(c))
        }
        (None, Mode::File(_), KeyCode::Char(c))
            if !event
                .modifiers
                .intersects(KeyModifiers::CONTROL | KeyModifiers::ALT) =>
        {
            Some(Action::PromptInsert(c))
        }
        _ => bound,
    }
}

/// The keys of a binding as the help overlay writes them: `Up, k`.
pub fn keys_label(binding: &Binding) -> String {
    binding
        .keys
        .iter()
        .map(|k| k.label())
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn press(code: KeyCode, modifiers: KeyModifiers) -> KeyEvent {
        KeyEvent::new(code, modifiers)
    }

    #[test]
    fn arrows_and_letters_agree() {
        let n = Mode::Normal;
        let none = KeyModifiers::NONE;
        let fine_up = Some(Action::Step {
            up: true,
            coarse: false,
        });
        let coarse_up = Some(Action::Step {
            up: true,
            coarse: true,
        });
        assert_eq!(action_for(&press(KeyCode::Right, none), &n), fine_up);
        assert_eq!(action_for(&press(KeyCode::Char('l'), none), &n), fine_up);
        assert_eq!(
            action_for(&press(KeyCode::Right, KeyModifiers::SHIFT), &n),
            coarse_up
        );
        assert_eq!(
            action_for(&press(KeyCode::Char('L'), KeyModifiers::SHIFT), &n),
            coarse_up
        );
        assert_eq!(action_for(&press(KeyCode::Char('L'), none), &n), coarse_up);
        assert_eq!(
            action_for(&press(KeyCode::Char('R'), KeyModifiers::SHIFT), &n),
            Some(Action::ResetAll)
        );
        assert_eq!(
            action_for(&press(KeyCode::Char('c'), KeyModifiers::CONTROL), &n),
            Some(Action::Quit)
        );
        assert_eq!(action_for(&press(KeyCode::Char('z'), none), &n), None);
    }

    #[test]
    fn esc_closes_help_before_it_quits() {
        let esc = press(KeyCode::Esc, KeyModifiers::NONE);
        assert_eq!(action_for(&esc, &Mode::Help), Some(Action::CloseHelp));
        assert_eq!(action_for(&esc, &Mode::Normal), Some(Action::Quit));
        assert_eq!(
            action_for(&esc, &Mode::Editing(String::new())),
            Some(Action::EditCancel)
        );
    }

    #[test]
    fn the_prompt_takes_letters_as_text() {
        let editing = Mode::Editing("1".into());
        let q = press(KeyCode::Char('q'), KeyModifiers::NONE);
        assert_eq!(action_for(&q, &editing), Some(Action::EditInsert('q')));
        let ctrl_c = press(KeyCode::Char('c'), KeyModifiers::CONTROL);
        assert_eq!(action_for(&ctrl_c, &editing), Some(Action::Quit));
    }
}
