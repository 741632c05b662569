//! Scenarios in the explorer, on ratatui's TestBackend with scripted keys: the preset picker, saving and
//! opening scenario files (and every kind of bad file), undo and redo, the baseline and exporting.

use std::path::{Path, PathBuf};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use snapback::config::preset;
use snapback::model::{ParamId, Params, solve};
use snapback::scenario::{PRESETS, Scenario};
use snapback::tui::app::Tone;
use snapback::tui::theme::Theme;
use snapback::tui::{App, Mode, Scripted, keys, run};

use crate::support::screen;
use screen::{line_with, text};

fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

fn char(c: char) -> Event {
    key(KeyCode::Char(c))
}

fn ctrl(c: char) -> Event {
    Event::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::CONTROL))
}

fn typed(text: &str) -> Vec<Event> {
    text.chars().map(char).collect()
}

/// A directory of its own under the system's temporary directory, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!(
            "snapback-tui-scenarios-{}-{name}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// An explorer on `params` whose files go to `dir`.
fn app_in(params: Params, dir: &Path) -> App {
    let mut app = App::new(params, Theme::default()).unwrap();
    app.dir = dir.to_path_buf();
    app
}

/// `app` after `events` on a `width` x `height` screen, and the screen as text.
fn drive(app: &mut App, width: u16, height: u16, events: Vec<Event>) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    run(&mut terminal, app, &mut Scripted::from(events)).unwrap();
    text(&terminal)
}

fn message(app: &App) -> String {
    app.message
        .as_ref()
        .map(|m| m.text.clone())
        .unwrap_or_default()
}

fn omega2(params: &Params) -> f64 {
    solve(params).unwrap().outcome.omega2
}

/// The keys that pick preset number `i` in the picker and apply it.
fn pick(i: usize) -> Vec<Event> {
    let mut events = vec![char('p')];
    // The picker opens on the preset the parameters are (the first one, for the defaults).
    events.extend(std::iter::repeat_n(char('j'), i));
    events.push(key(KeyCode::Enter));
    events
}

#[test]
fn every_preset_can_be_picked_and_solves() {
    let dir = TempDir::new("every-preset");
    assert_eq!(
        PRESETS[0].scenario().apply(Params::default()),
        Params::default()
    );
    for (i, p) in PRESETS.iter().enumerate() {
        let scenario = p.scenario();
        let expected = scenario.apply(Params::default());
        // A shot preset turns shot mode on: the incidence is what the strings see.
        let expected = if scenario.is_shot() {
            snapback::tui::shot::strings_params(&expected).unwrap()
        } else {
            expected
        };
        let mut app = app_in(Params::default(), dir.path());
        let screen = drive(&mut app, 160, 48, pick(i));
        assert_eq!(app.params, expected, "{}", p.name);
        assert_eq!(app.mode, Mode::Normal);
        let shown = format!("{:.1} rad/s", omega2(&expected));
        assert!(
            line_with(&screen, "rebound spin ω2").contains(&shown),
            "{}: {shown} not on\n{screen}",
            p.name
        );
        assert!(message(&app).contains(p.name), "{}", message(&app));
    }
}

#[test]
fn the_picker_lists_the_presets_and_applies_one_undoable_change() {
    let dir = TempDir::new("picker");
    for (w, h) in [(80, 24), (160, 48)] {
        let mut app = app_in(Params::default(), dir.path());
        let screen = drive(
            &mut app,
            w,
            h,
            vec![char('p'), char('j'), char('j'), char('j')],
        );
        assert_eq!(app.mode, Mode::Picker(3));
        assert!(screen.contains(" presets "), "{screen}");
        for p in PRESETS {
            assert!(
                screen.contains(p.name),
                "{} missing at {w}x{h}:\n{screen}",
                p.name
            );
        }
        // The highlighted preset's description is written out in full under the list.
        let description = preset("light-1g").unwrap().description;
        let first_words: String = description.chars().take(40).collect();
        assert!(screen.contains(&first_words), "{screen}");
    }

    let light = preset("light-1g").unwrap().apply(Params::default());
    let mut app = app_in(Params::default(), dir.path());
    let screen = drive(&mut app, 80, 24, pick(3));
    assert_eq!(app.params, light);
    let shown = format!("{:.1} rad/s", omega2(&light));
    assert!(line_with(&screen, "ω2 ").contains(&shown), "{screen}");
    // One u goes back to where it was.
    drive(&mut app, 80, 24, vec![char('u')]);
    assert_eq!(app.params, Params::default());

    // Esc (or p again) closes the picker and changes nothing.
    for close in [key(KeyCode::Esc), char('p')] {
        let mut app = app_in(Params::default(), dir.path());
        drive(&mut app, 80, 24, vec![char('p'), char('j'), close]);
        assert_eq!(app.mode, Mode::Normal);
        assert_eq!(app.params, Params::default());
        assert!(!app.quit);
    }
}

#[test]
fn save_then_open_gives_identical_parameters() {
    let dir = TempDir::new("roundtrip");
    let awkward = Params {
        angle_deg: 47.123456789012345,
        spin: -955.0 * std::f64::consts::PI / 30.0,
        cart_mass: 1.0 / 3.0 * 1e-3,
        stiffness: 12345.678901234567,
        ..Params::default()
    };
    let mut app = app_in(awkward, dir.path());
    let mut events = vec![char('s')];
    events.extend(typed("what-if"));
    events.push(key(KeyCode::Enter));
    let screen = drive(&mut app, 160, 48, events);
    let path = dir.path().join("what-if.toml");
    assert!(path.is_file());
    let saved = format!("saved {}", path.display());
    assert_eq!(message(&app), saved);
    assert!(screen.contains(&saved), "{screen}");
    assert_eq!(
        Scenario::load(&path).unwrap().apply(Params::default()),
        awkward
    );
    // Nothing but the file is left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);

    // A fresh explorer opens it (the .toml may be left off) as one change that u undoes.
    let mut app = app_in(Params::default(), dir.path());
    let mut events = vec![char('o')];
    events.extend(typed("what-if"));
    events.push(key(KeyCode::Enter));
    let screen = drive(&mut app, 80, 24, events);
    assert_eq!(app.params, awkward);
    assert!(
        message(&app).starts_with("opened what-if.toml"),
        "{}",
        message(&app)
    );
    let shown = format!("{:.1} rad/s", omega2(&awkward));
    assert!(line_with(&screen, "ω2 ").contains(&shown), "{screen}");
    drive(&mut app, 80, 24, vec![char('u')]);
    assert_eq!(app.params, Params::default());
}

#[test]
fn save_offers_a_default_name_and_never_overwrites_without_a_yes() {
    let dir = TempDir::new("overwrite");
    let default_file = dir.path().join("snapback-scenario.toml");
    let mut app = app_in(Params::default(), dir.path());
    let screen = drive(&mut app, 80, 24, vec![char('s')]);
    assert!(
        screen
            .lines()
            .last()
            .unwrap()
            .starts_with("save the parameters as [snapback-scenario.toml]: "),
        "{screen}"
    );
    drive(&mut app, 80, 24, vec![key(KeyCode::Enter)]);
    let first = std::fs::read_to_string(&default_file).unwrap();

    // Change a parameter, save again: asked, and n (or Esc) keeps the file as it was.
    for no in [char('n'), key(KeyCode::Esc)] {
        let screen = drive(
            &mut app,
            160,
            48,
            vec![char('l'), char('s'), key(KeyCode::Enter)],
        );
        assert_eq!(app.mode, Mode::Overwrite(default_file.clone()));
        assert!(
            screen.contains("snapback-scenario.toml exists; overwrite it?"),
            "{screen}"
        );
        drive(&mut app, 160, 48, vec![no]);
        assert_eq!(app.mode, Mode::Normal);
        assert_eq!(std::fs::read_to_string(&default_file).unwrap(), first);
        assert!(message(&app).starts_with("not saved"), "{}", message(&app));
    }
    // y replaces it.
    drive(
        &mut app,
        80,
        24,
        vec![char('s'), key(KeyCode::Enter), char('y')],
    );
    let loaded = Scenario::load(&default_file).unwrap();
    assert_eq!(loaded.apply(Params::default()), app.params);
    assert_eq!(app.params.angle_deg, 62.0);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn each_kind_of_bad_file_names_the_file_line_and_key_and_changes_nothing() {
    let dir = TempDir::new("bad-files");
    let cases = [
        ("not TOML", "[params\nangle = 30\n", "bad.toml:1:", None),
        (
            "unknown key",
            "description = \"x\"\n[params]\nangel = 30\n",
            "bad.toml:3: unknown parameter 'angel'",
            Some("angel"),
        ),
        (
            "wrong type",
            "[params]\nangle = 30\nmu = true\n",
            "bad.toml:3: mu must be a number or a string with a unit, not boolean",
            Some("mu"),
        ),
        (
            "bad unit",
            "[params]\ncart_mass = \"10 m\"\n",
            "bad.toml:2: cart_mass:",
            Some("cart_mass"),
        ),
        (
            "out of range",
            "[params]\n\nmu = -1\n",
            "bad.toml:3: mu must be in [0, inf); got -1",
            Some("mu"),
        ),
    ];
    for (kind, text, expected, key_name) in cases {
        std::fs::write(dir.path().join("bad.toml"), text).unwrap();
        let start = Params::default().with(ParamId::Angle, 45.0).unwrap();
        let mut app = app_in(start, dir.path());
        let mut events = vec![char('o')];
        events.extend(typed("bad.toml"));
        events.push(key(KeyCode::Enter));
        let screen = drive(&mut app, 160, 48, events);
        let shown = message(&app);
        assert!(shown.starts_with(expected), "{kind}: {shown}");
        assert!(shown.ends_with("(parameters unchanged)"), "{kind}: {shown}");
        if let Some(name) = key_name {
            assert!(shown.contains(name), "{kind}: {shown}");
        }
        assert_eq!(app.message.as_ref().unwrap().tone, Tone::Error);
        assert!(screen.contains(expected), "{kind}:\n{screen}");
        assert_eq!(app.params, start, "{kind}");
        assert_eq!(app.mode, Mode::Normal);
        // Nothing to undo: the state did not change.
        drive(&mut app, 160, 48, vec![char('u')]);
        assert_eq!(message(&app), "undo: nothing to undo");
    }
    // A file that is not there.
    let mut app = app_in(Params::default(), dir.path());
    let mut events = vec![char('o')];
    events.extend(typed("missing.toml"));
    events.push(key(KeyCode::Enter));
    drive(&mut app, 80, 24, events);
    assert!(
        message(&app).starts_with("missing.toml: "),
        "{}",
        message(&app)
    );
    assert_eq!(app.params, Params::default());
    // Standard input is the terminal, and a FIFO would block the explorer: both are refused at once.
    let fifo = dir.path().join("pipe.toml");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    for (name, reason) in [("-", "standard input"), ("pipe.toml", "not a regular file")] {
        let mut app = app_in(Params::default(), dir.path());
        let mut events = vec![char('o')];
        events.extend(typed(name));
        events.push(key(KeyCode::Enter));
        drive(&mut app, 80, 24, events);
        assert!(message(&app).contains(reason), "{name}: {}", message(&app));
        assert_eq!(app.params, Params::default());
    }
}

#[test]
fn undo_and_redo_walk_the_changes() {
    let dir = TempDir::new("undo");
    let at = |angle: f64| Params::default().with(ParamId::Angle, angle).unwrap();
    let mut app = app_in(Params::default(), dir.path());
    drive(&mut app, 80, 24, vec![char('u')]);
    assert_eq!(message(&app), "undo: nothing to undo");
    drive(&mut app, 80, 24, vec![ctrl('r')]);
    assert_eq!(message(&app), "redo: nothing to redo");

    // Three steps, two undone, one redone.
    drive(&mut app, 80, 24, vec![char('l'), char('l'), char('l')]);
    assert_eq!(app.params, at(63.0));
    let screen = drive(&mut app, 80, 24, vec![char('u'), char('u')]);
    assert_eq!(app.params, at(61.0));
    assert_eq!(
        message(&app),
        "undo: θ1 62.0 deg → 61.0 deg (1 more to undo)"
    );
    assert!(line_with(&screen, "incidence angle").contains("61.0 deg"));
    drive(&mut app, 80, 24, vec![ctrl('r')]);
    assert_eq!(app.params, at(62.0));
    // A new change drops what was left to redo.
    drive(&mut app, 80, 24, vec![char('h'), ctrl('r')]);
    assert_eq!(app.params, at(61.0));
    assert_eq!(message(&app), "redo: nothing to redo");

    // A typed value, a reset and a reset of everything are changes too.
    let mut events = vec![key(KeyCode::Enter)];
    events.extend(typed("30"));
    events.extend([key(KeyCode::Enter), char('r'), char('l'), char('R')]);
    drive(&mut app, 80, 24, events);
    assert_eq!(app.params, Params::default());
    let undone: Vec<Params> = (0..4)
        .map(|_| {
            drive(&mut app, 80, 24, vec![char('u')]);
            app.params
        })
        .collect();
    assert_eq!(undone, [at(61.0), at(60.0), at(30.0), at(61.0)]);
    // Back to the start, then nothing more.
    drive(&mut app, 80, 24, vec![char('u'); 3]);
    assert_eq!(app.params, Params::default());
    assert_eq!(
        message(&app),
        "undo: θ1 61.0 deg → 60.0 deg (0 more to undo)"
    );
    drive(&mut app, 80, 24, vec![char('u')]);
    assert_eq!(message(&app), "undo: nothing to undo");
    // Everything can be redone.
    drive(&mut app, 80, 24, vec![ctrl('r'); 7]);
    assert_eq!(app.params, Params::default());
    drive(&mut app, 80, 24, vec![ctrl('r')]);
    assert_eq!(message(&app), "redo: nothing to redo");
}

#[test]
fn reset_goes_back_to_where_the_explorer_started() {
    let dir = TempDir::new("reset");
    let light = preset("light-1g").unwrap().apply(Params::default());
    let mut app = app_in(light, dir.path());
    drive(
        &mut app,
        80,
        24,
        vec![char('l'), char('j'), char('L'), char('R')],
    );
    assert_eq!(app.params, light);
    // r resets the selected parameter to its starting value, too.
    let mut events = vec![char('k'); 7]; // from the speed, round past the frame and the chain to the cart mass
    events.extend([char('L'), char('r')]);
    drive(&mut app, 80, 24, events);
    assert_eq!(app.selected_spec().id, ParamId::CartMass);
    assert_eq!(app.params, light);
    // The picker opens on the preset the parameters are.
    drive(&mut app, 80, 24, vec![char('p')]);
    let index = PRESETS.iter().position(|p| p.name == "light-1g").unwrap();
    assert_eq!(app.mode, Mode::Picker(index));
}

#[test]
fn the_baseline_gives_the_cores_differences() {
    let dir = TempDir::new("baseline");
    let mut app = app_in(Params::default(), dir.path());
    // Pin, then halve the cart mass and raise the angle.
    let mut events = vec![char('b'), char('l'), char('l')];
    // The cart mass is row 11, after the ball's stiffness and damping.
    events.extend(std::iter::repeat_n(char('j'), 11));
    events.push(char('H'));
    let screen = drive(&mut app, 160, 48, events);
    let base = solve(&Params::default()).unwrap().outcome;
    let now = solve(&app.params).unwrap().outcome;
    assert_eq!(app.params.cart_mass, 0.005);
    let deltas = app
        .baseline
        .as_ref()
        .unwrap()
        .deltas(&app.solved.as_ref().unwrap().bounce);
    assert_eq!(deltas.omega2, now.omega2 - base.omega2);
    assert_eq!(deltas.ex, Some(now.ex.unwrap() - base.ex.unwrap()));
    let d_omega2 = format!("{:+.1} rad/s", now.omega2 - base.omega2);
    let d_ex = format!("{:+.3}", now.ex.unwrap() - base.ex.unwrap());
    assert!(
        line_with(&screen, "Δω2 vs baseline").contains(&d_omega2),
        "{screen}"
    );
    assert!(
        line_with(&screen, "Δe_x vs baseline").contains(&d_ex),
        "{screen}"
    );
    assert!(
        line_with(&screen, "baseline differs").contains("θ1, M"),
        "{screen}"
    );
    assert!(
        screen.contains("cart displacement X (mm) ━ baseline"),
        "{screen}"
    );

    // On a small screen the differences sit beside the values.
    let screen = drive(&mut app, 80, 24, vec![]);
    assert!(
        line_with(&screen, "ω2 ").contains(&format!("Δ{:+.1}", now.omega2 - base.omega2)),
        "{screen}"
    );
    assert!(
        line_with(&screen, "e_x ").contains(&format!("Δ{d_ex}")),
        "{screen}"
    );

    // The baseline's curve is drawn in dark grey on the charts and the sweep.
    for view in [vec![], vec![key(KeyCode::Tab)]] {
        let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
        run(&mut terminal, &mut app, &mut Scripted::from(view)).unwrap();
        let grey_dots = terminal
            .backend()
            .buffer()
            .content()
            .iter()
            .filter(|c| {
                c.fg == ratatui::style::Color::DarkGray
                    && ('\u{2801}'..='\u{28ff}').contains(&c.symbol().chars().next().unwrap())
            })
            .count();
        assert!(grey_dots > 50, "{grey_dots} grey braille cells");
    }

    // b again pins the current bounce: no differences; B clears it.
    let screen = drive(&mut app, 160, 48, vec![key(KeyCode::Tab), char('b')]);
    assert!(
        line_with(&screen, "Δω2 vs baseline").contains(" 0.0 rad/s"),
        "{screen}"
    );
    assert!(
        line_with(&screen, "baseline differs").contains("nothing yet"),
        "{screen}"
    );
    let screen = drive(&mut app, 160, 48, vec![char('B')]);
    assert!(app.baseline.is_none());
    assert!(!screen.contains("Δω2"), "{screen}");
    assert!(!screen.contains("━ baseline"), "{screen}");
}

#[test]
fn export_writes_the_series_and_the_outcome_and_says_where() {
    let dir = TempDir::new("export");
    let mut app = app_in(Params::default(), dir.path());
    let screen = drive(&mut app, 160, 48, vec![char('x')]);
    let csv = dir.path().join("snapback-1.csv");
    let json = dir.path().join("snapback-1.json");
    let said = message(&app);
    assert!(said.contains(&csv.display().to_string()), "{said}");
    assert!(said.contains(&json.display().to_string()), "{said}");
    assert!(screen.contains("exported the series to"), "{screen}");

    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(snapback::export::csv::HEADER));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(rows.len() >= 501, "{} rows", rows.len());
    for row in &rows {
        assert_eq!(row.len(), 12);
        for value in &row[..8] {
            value.parse::<f64>().unwrap();
        }
    }
    let last_omega: f64 = rows.last().unwrap()[6].parse().unwrap();
    let expected = solve(&Params::default()).unwrap().outcome.omega2;
    assert!((last_omega - expected).abs() < 1e-6 * expected.abs());

    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(value["omega2"].as_f64(), Some(expected));
    assert_eq!(value["params"]["angle_deg"].as_f64(), Some(60.0));

    // A second export never overwrites the first.
    drive(&mut app, 80, 24, vec![char('l'), char('x')]);
    assert!(dir.path().join("snapback-2.csv").is_file());
    assert!(dir.path().join("snapback-2.json").is_file());
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), text);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 4);
}

#[test]
fn the_help_lists_the_scenario_keys() {
    let dir = TempDir::new("help");
    for (w, h) in [(80, 24), (160, 48)] {
        let mut app = app_in(Params::default(), dir.path());
        let screen = drive(&mut app, w, h, vec![char('?')]);
        // Related keys share a row: `s / o`, `u / Ctrl-R`, `b / B`. The key column is as wide as the widest.
        let width = [keys::EXPLORER, keys::PROMPT]
            .into_iter()
            .flat_map(keys::help_rows)
            .map(|(label, _)| label.chars().count())
            .max()
            .unwrap();
        for (keys, words) in [
            ("p", "pick a preset"),
            ("s / o", "save the parameters as a scenario file / open one"),
            ("u / Ctrl-R", "undo / redo a parameter change"),
            ("b / B", "pin this bounce as a dim baseline / clear it"),
            ("x", "export series (CSV), outcome (JSON) to this folder"),
        ] {
            let row = format!(" {keys:<width$} {words}");
            assert!(
                screen.contains(&row),
                "{row:?} missing at {w}x{h}:\n{screen}"
            );
        }
    }
}

#[test]
fn quitting_with_changes_since_the_scenario_file_asks_once() {
    let dir = TempDir::new("unsaved");
    let mut app = app_in(Params::default(), dir.path());
    let mut events = vec![char('s')];
    events.extend(typed("kept"));
    events.push(key(KeyCode::Enter));
    drive(&mut app, 160, 48, events);
    assert_eq!(
        message(&app),
        format!("saved {}", dir.path().join("kept.toml").display())
    );
    // Unchanged since the save: q quits.
    drive(&mut app, 160, 48, vec![char('q')]);
    assert!(app.quit);
    app.quit = false;
    // Changed: the first q asks, anything else forgets the question, a q right after it quits.
    drive(&mut app, 160, 48, vec![key(KeyCode::Right), char('q')]);
    assert!(!app.quit);
    assert!(
        message(&app).contains("kept.toml are not saved"),
        "{}",
        message(&app)
    );
    drive(&mut app, 160, 48, vec![char('j'), char('q')]);
    assert!(!app.quit);
    drive(&mut app, 160, 48, vec![key(KeyCode::Esc)]);
    assert!(app.quit);
}
