//! Keys: the one table that both turns key presses into [`Action`]s and writes the help overlay and the
//! status-line hints, so what the help says is what the keys do.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::vocabulary::{Action, Mode, View};

/// Where a binding does something: the help overlay lists, and the status line hints at, only the keys
/// that do something where the user is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// In every view: the parameters, the views, presets, files, history, help and quitting.
    Everywhere,
    /// The contact's time cursor and playback speed: in the contact view, and wherever the schematic is
    /// drawn, except the shot view (whose flight plays in real time).
    Contact,
    /// Playing and the ends of the timeline: the contact's, or the flight's in the shot view.
    Timeline,
    /// Marking parameters free and fitting them: with measurements (`--data`).
    Lab,
}

/// Where the user is, as far as the keys are concerned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Context {
    pub view: View,
    /// Shot mode is on.
    pub shot_on: bool,
    /// The schematic (the bounce at the time cursor) is drawn.
    pub schematic: bool,
    /// Measurements were loaded (`--data`).
    pub data: bool,
}

impl Scope {
    /// True when keys of this scope do something in `context`.
    pub fn applies(self, context: &Context) -> bool {
        let view = context.view;
        match self {
            Scope::Everywhere => true,
            Scope::Contact => view == View::Contact || (context.schematic && view != View::Shot),
            Scope::Timeline => view == View::Contact || view == View::Shot || context.schematic,
            Scope::Lab => context.data,
        }
    }
}

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
                KeyCode::Up => "↑".into(),
                KeyCode::Down => "↓".into(),
                KeyCode::Left => "←".into(),
                KeyCode::Right => "→".into(),
                KeyCode::Enter => "Enter".into(),
                KeyCode::Esc => "Esc".into(),
                KeyCode::Tab => "Tab".into(),
                KeyCode::Backspace => "Backspace".into(),
                KeyCode::Home => "Home".into(),
                KeyCode::End => "End".into(),
                KeyCode::Char(' ') => "Space".into(),
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

/// A short form of a binding for the status line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Hint {
    pub keys: &'static str,
    pub word: &'static str,
    /// Essential hints get the room first on a narrow status line; the others fill what is left.
    pub essential: bool,
}

/// An essential hint.
const fn hint(keys: &'static str, word: &'static str) -> Option<Hint> {
    Some(Hint {
        keys,
        word,
        essential: true,
    })
}

/// A hint shown when there is room.
const fn extra(keys: &'static str, word: &'static str) -> Option<Hint> {
    Some(Hint {
        keys,
        word,
        essential: false,
    })
}

/// Keys bound to one action, with the words that explain it.
#[derive(Clone, Copy, Debug)]
pub struct Binding {
    pub keys: &'static [Key],
    pub action: Action,
    /// What the help overlay says the keys do; empty for the second of a pair, whose keys the overlay
    /// writes on the row of the binding before it (`[ / ]`), whose words say what both do.
    pub help: &'static str,
    /// A short form for the status line, if the binding earns a place there.
    pub hint: Option<Hint>,
    /// Where the keys do something.
    pub scope: Scope,
    /// What the help says the keys do in the shot view, where that differs from `help`.
    pub shot_help: Option<&'static str>,
}

impl Binding {
    /// The binding, doing something only in `scope`.
    const fn only(self, scope: Scope) -> Binding {
        Binding { scope, ..self }
    }

    /// The binding, whose keys do what `words` say in the shot view.
    const fn in_shot(self, words: &'static str) -> Binding {
        Binding {
            shot_help: Some(words),
            ..self
        }
    }

    /// What the help says the keys do in `view`.
    pub fn help_in(&self, view: View) -> &'static str {
        match self.shot_help {
            Some(words) if view == View::Shot => words,
            _ => self.help,
        }
    }
}

const fn bind(
    keys: &'static [Key],
    action: Action,
    help: &'static str,
    hint: Option<Hint>,
) -> Binding {
    Binding {
        keys,
        action,
        help,
        hint,
        scope: Scope::Everywhere,
        shot_help: None,
    }
}

use Key::{Ctrl, Plain, Shift};

/// The keys of the explorer (also while the help overlay is open, where q and Esc close the overlay
/// instead and the up and down keys scroll it).
pub const EXPLORER: &[Binding] = &[
    bind(
        &[Plain(KeyCode::Up), Plain(KeyCode::Char('k'))],
        Action::SelectPrevious,
        "select the parameter above / below",
        hint("↑↓", "select"),
    ),
    bind(
        &[Plain(KeyCode::Down), Plain(KeyCode::Char('j'))],
        Action::SelectNext,
        "",
        None,
    ),
    bind(
        &[Plain(KeyCode::Left), Plain(KeyCode::Char('h'))],
        Action::Step {
            up: false,
            coarse: false,
        },
        "step down / up by a fine step (1 deg for the angle)",
        hint("←→", "step"),
    ),
    bind(
        &[Plain(KeyCode::Right), Plain(KeyCode::Char('l'))],
        Action::Step {
            up: true,
            coarse: false,
        },
        "",
        None,
    ),
    bind(
        &[Plain(KeyCode::Char('H')), Shift(KeyCode::Left)],
        Action::Step {
            up: false,
            coarse: true,
        },
        "a coarse step down / up (10 deg for the angle)",
        extra("H/L", "coarse"),
    ),
    bind(
        &[Plain(KeyCode::Char('L')), Shift(KeyCode::Right)],
        Action::Step {
            up: true,
            coarse: true,
        },
        "",
        None,
    ),
    bind(
        &[Plain(KeyCode::Enter), Plain(KeyCode::Char('e'))],
        Action::StartEdit,
        "type a value; units as on the command line: 10g",
        hint("⏎", "type"),
    ),
    bind(
        &[Plain(KeyCode::Char('r'))],
        Action::Reset,
        "reset this parameter / all of them to the start",
        extra("r", "reset"),
    ),
    bind(
        &[Plain(KeyCode::Char('R'))],
        Action::ResetAll,
        "",
        extra("R", "all"),
    ),
    bind(
        &[Plain(KeyCode::Tab)],
        Action::NextView,
        "next view: contact, ω2 vs θ1 (Fig. 2), ω2 map, shot",
        hint("Tab", "view"),
    ),
    bind(
        &[Plain(KeyCode::Char(' '))],
        Action::TogglePlay,
        "play or pause the bounce in slow motion",
        hint("␣", "play"),
    )
    .only(Scope::Timeline)
    .in_shot("play or pause the flight"),
    bind(
        &[Plain(KeyCode::Char('+')), Plain(KeyCode::Char('='))],
        Action::ChangeSpeed { faster: true },
        "play twice / half as fast (default 1 ms per 2 s)",
        extra("+-", "speed"),
    )
    .only(Scope::Contact),
    bind(
        &[Plain(KeyCode::Char('-'))],
        Action::ChangeSpeed { faster: false },
        "",
        None,
    )
    .only(Scope::Contact),
    bind(
        &[Plain(KeyCode::Char('['))],
        Action::CursorStep { forward: false },
        "time cursor back / on 0.05 ms; or click a chart",
        extra("[]", "time"),
    )
    .only(Scope::Contact),
    bind(
        &[Plain(KeyCode::Char(']'))],
        Action::CursorStep { forward: true },
        "",
        None,
    )
    .only(Scope::Contact),
    bind(
        &[Plain(KeyCode::Char('{'))],
        Action::CursorPhase { forward: false },
        "time cursor to the previous / next transition",
        extra("{}", "phase"),
    )
    .only(Scope::Contact),
    bind(
        &[Plain(KeyCode::Char('}'))],
        Action::CursorPhase { forward: true },
        "",
        None,
    )
    .only(Scope::Contact),
    bind(
        &[Plain(KeyCode::Home)],
        Action::CursorHome,
        "time cursor to the start / end of the contact",
        None,
    )
    .only(Scope::Timeline)
    .in_shot("the ball to the start / end of the flight"),
    bind(&[Plain(KeyCode::End)], Action::CursorEnd, "", None).only(Scope::Timeline),
    bind(
        &[Plain(KeyCode::Char('?'))],
        Action::ToggleHelp,
        "open or close this help",
        hint("?", "help"),
    ),
    bind(
        &[Plain(KeyCode::Char('q')), Plain(KeyCode::Esc), Ctrl('c')],
        Action::Quit,
        "quit (in this help, q and Esc close it)",
        hint("q", "quit"),
    ),
    bind(
        &[Plain(KeyCode::Char('p'))],
        Action::OpenPicker,
        "pick a preset: the paper's cases and some what-ifs",
        extra("p", "presets"),
    ),
    bind(
        &[Plain(KeyCode::Char('s'))],
        Action::StartSave,
        "save the parameters as a scenario file / open one",
        extra("s", "save"),
    ),
    bind(
        &[Plain(KeyCode::Char('o'))],
        Action::StartOpen,
        "",
        extra("o", "open"),
    ),
    bind(
        &[Plain(KeyCode::Char('u'))],
        Action::Undo,
        "undo / redo a parameter change",
        extra("u", "undo"),
    ),
    bind(&[Ctrl('r')], Action::Redo, "", None),
    bind(
        &[Plain(KeyCode::Char('b'))],
        Action::PinBaseline,
        "pin this bounce as a dim baseline / clear it",
        extra("b", "baseline"),
    ),
    bind(
        &[Plain(KeyCode::Char('B'))],
        Action::ClearBaseline,
        "",
        None,
    ),
    bind(
        &[Plain(KeyCode::Char('x'))],
        Action::Export,
        "export series (CSV), outcome (JSON) to this folder",
        extra("x", "export"),
    ),
    bind(
        &[Plain(KeyCode::Char('f'))],
        Action::ToggleFree,
        "mark free or fixed / fit to --data; F or Esc stops",
        None,
    )
    .only(Scope::Lab),
    bind(&[Plain(KeyCode::Char('F'))], Action::Fit, "", None).only(Scope::Lab),
    bind(
        &[Plain(KeyCode::Char('m'))],
        Action::ToggleShot,
        "shot mode on / off: θ1, v1, ω1 follow the racquet",
        hint("m", "shot off"),
    ),
];

/// The keys of the value prompt.
pub const PROMPT: &[Binding] = &[
    bind(
        &[Plain(KeyCode::Enter)],
        Action::EditSubmit,
        "apply; bare numbers in kg, m, s, N/m, deg, rad/s",
        hint("⏎", "apply"),
    ),
    bind(
        &[Plain(KeyCode::Esc)],
        Action::EditCancel,
        "leave the value as it was",
        hint("Esc", "cancel"),
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
        hint("↑↓", "choose"),
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
        hint("⏎", "apply"),
    ),
    bind(
        &[
            Plain(KeyCode::Esc),
            Plain(KeyCode::Char('p')),
            Plain(KeyCode::Char('q')),
        ],
        Action::PickerClose,
        "close, changing nothing",
        hint("Esc", "close"),
    ),
    bind(&[Ctrl('c')], Action::Quit, "quit", None),
];

/// The keys of the file-name prompt (save and open).
pub const FILE_PROMPT: &[Binding] = &[
    bind(
        &[Plain(KeyCode::Enter)],
        Action::PromptSubmit,
        "save or open (nothing typed: the name in brackets)",
        hint("⏎", "ok"),
    ),
    bind(
        &[Plain(KeyCode::Esc)],
        Action::PromptCancel,
        "cancel",
        hint("Esc", "cancel"),
    ),
    bind(
        &[Plain(KeyCode::Tab)],
        Action::PromptComplete,
        "complete the file name (nothing typed: take the one in brackets)",
        hint("Tab", "complete"),
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
        hint("y", "overwrite"),
    ),
    bind(
        &[Plain(KeyCode::Char('n')), Plain(KeyCode::Esc)],
        Action::PromptCancel,
        "keep the file, save nothing",
        hint("n", "keep it"),
    ),
    bind(&[Ctrl('c')], Action::Quit, "quit", None),
];

/// True when the status line offers `binding`'s hint in `context`: where its keys do something
/// ([`Scope::applies`]), and `m` only while shot mode is on (to leave it; Tab into the shot view turns
/// it on).
pub fn offered(binding: &Binding, context: &Context) -> bool {
    binding.scope.applies(context) && (binding.action != Action::ToggleShot || context.shot_on)
}

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
    // In the help, q and Esc close it rather than quit, and the arrows scroll it.
    if *mode == Mode::Help {
        let any = |keys: &[Key]| keys.iter().any(|k| k.matches(event));
        if any(&[Plain(KeyCode::Esc), Plain(KeyCode::Char('q'))]) {
            return Some(Action::CloseHelp);
        }
        if any(&[Plain(KeyCode::Down), Plain(KeyCode::Char('j'))]) {
            return Some(Action::ScrollHelp { down: true });
        }
        if any(&[Plain(KeyCode::Up), Plain(KeyCode::Char('k'))]) {
            return Some(Action::ScrollHelp { down: false });
        }
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

/// The keys of a binding as the help overlay writes them: `↑, k`.
pub fn keys_label(binding: &Binding) -> String {
    binding
        .keys
        .iter()
        .map(|k| k.label())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The explorer's bindings of `scopes` whose keys do something in `context`, in the table's order.
pub fn explorer_keys(context: &Context, scopes: &[Scope]) -> Vec<Binding> {
    EXPLORER
        .iter()
        .filter(|b| scopes.contains(&b.scope) && b.scope.applies(context))
        .copied()
        .collect()
}

/// The rows of the help overlay for `bindings`: the keys and what they do, the second of a pair on the
/// row of the first (`↑, k / ↓, j`, `select the parameter above / below`).
pub fn help_rows(bindings: &[Binding]) -> Vec<(String, &'static str)> {
    help_rows_in(bindings, View::Contact)
}

/// [`help_rows`] as the help says them in `view`.
pub fn help_rows_in(bindings: &[Binding], view: View) -> Vec<(String, &'static str)> {
    let mut rows: Vec<(String, &'static str)> = Vec::new();
    for b in bindings {
        match rows.last_mut() {
            Some((keys, _)) if b.help.is_empty() => {
                keys.push_str(" / ");
                keys.push_str(&keys_label(b));
            }
            _ => rows.push((keys_label(b), b.help_in(view))),
        }
    }
    rows
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
    fn time_keys_with_or_without_shift() {
        let n = Mode::Normal;
        let shift = KeyModifiers::SHIFT;
        let none = KeyModifiers::NONE;
        // Terminals report `{`, `}` and `+` with Shift or without it.
        for m in [none, shift] {
            assert_eq!(
                action_for(&press(KeyCode::Char('{'), m), &n),
                Some(Action::CursorPhase { forward: false })
            );
            assert_eq!(
                action_for(&press(KeyCode::Char('}'), m), &n),
                Some(Action::CursorPhase { forward: true })
            );
            assert_eq!(
                action_for(&press(KeyCode::Char('+'), m), &n),
                Some(Action::ChangeSpeed { faster: true })
            );
        }
        assert_eq!(
            action_for(&press(KeyCode::Char('='), none), &n),
            Some(Action::ChangeSpeed { faster: true })
        );
        assert_eq!(
            action_for(&press(KeyCode::Char(' '), none), &n),
            Some(Action::TogglePlay)
        );
        assert_eq!(
            action_for(&press(KeyCode::Home, none), &n),
            Some(Action::CursorHome)
        );
        assert_eq!(
            action_for(&press(KeyCode::End, none), &n),
            Some(Action::CursorEnd)
        );
        // In the prompt, a space or a bracket is text.
        let editing = Mode::Editing(String::new());
        assert_eq!(
            action_for(&press(KeyCode::Char(' '), none), &editing),
            Some(Action::EditInsert(' '))
        );
    }

    #[test]
    fn pairs_share_a_help_row() {
        let rows = help_rows(EXPLORER);
        assert!(rows.contains(&(
            "[ / ]".to_string(),
            "time cursor back / on 0.05 ms; or click a chart"
        )));
        assert!(rows.contains(&(
            "Home / End".to_string(),
            "time cursor to the start / end of the contact"
        )));
        assert!(rows.iter().all(|(_, help)| !help.is_empty()));
        assert!(!EXPLORER[0].help.is_empty());
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
