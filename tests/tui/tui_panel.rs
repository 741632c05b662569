//! The parameter panel through the real event loop on ratatui's TestBackend: every label fits its row
//! (whole, or cut at a word with an ellipsis) at 80 x 24 and 160 x 48, in Unicode and ASCII, in shot
//! mode and with parameters marked free; in shot mode the frame's effective masses and e_A are the
//! racquet's, whatever bounce is on screen; the list scrolls no further than the selection needs.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use snapback::model::params::{PARAMS, ParamId, ParamSpec, spec};
use snapback::model::{Params, units};
use snapback::shot::racquet::Hold;
use snapback::tui::theme::Theme;
use snapback::tui::{App, Scripted, run, ui};

use crate::support::screen::text;

fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

fn preset(name: &str) -> Params {
    snapback::config::preset(name)
        .unwrap()
        .apply(Params::default())
}

/// The explorer on `params` after `events` on a `width` x `height` screen.
fn drive(app: &mut App, width: u16, height: u16, events: Vec<Event>) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    run(&mut terminal, app, &mut Scripted::from(events)).unwrap();
    text(&terminal)
}

/// The screen as `app` is now.
fn draw(app: &App, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal.draw(|frame| ui::draw(frame, app)).unwrap();
    text(&terminal)
}

/// The panel's rows on `screen`: the text inside its borders, top to bottom, down to its bottom border.
fn panel(screen: &str) -> Vec<String> {
    screen
        .lines()
        .skip(1)
        .take_while(|l| !l.starts_with('└'))
        .map(|l| {
            let inner: String = l.chars().skip(1).collect();
            inner.split('│').next().unwrap().to_string()
        })
        .collect()
}

/// The forms a label may take on a row: whole, or cut after one of its words with `ellipsis`.
fn forms(label: &str, ellipsis: &str) -> Vec<String> {
    let mut forms = vec![label.to_string()];
    for (i, _) in label.match_indices(' ') {
        let head = label[..i].trim_end_matches([':', ',']);
        forms.push(format!("{head}{ellipsis}"));
    }
    forms
}

/// The row of `spec` among `rows` (its symbol after the pointer), if shown.
fn row_of<'a>(rows: &'a [String], spec: &ParamSpec, theme: &Theme) -> Option<&'a String> {
    let symbol = theme.words(spec.symbol).into_owned();
    rows.iter().find(|r| {
        let rest: String = r.chars().skip(1).collect();
        rest.starts_with(&format!("{symbol} "))
    })
}

/// Every parameter's row, the selection moved over each in turn: its label is whole or cut at a word.
fn assert_labels_fit(mut app: App, width: u16, height: u16, what: &str) {
    let theme = app.theme;
    let ellipsis = theme.words("…").into_owned();
    let listed = app.listed();
    for (i, spec) in listed.iter().enumerate() {
        app.selected = i;
        let screen = draw(&app, width, height);
        let rows = panel(&screen);
        let row = row_of(&rows, spec, &theme)
            .unwrap_or_else(|| panic!("{} not shown ({what}):\n{screen}", spec.symbol));
        let labels = [
            spec.label.to_string(),
            format!("free: {}", spec.label),
            "free for the fit".into(),
            "set by the shot".into(),
            "from the racquet".into(),
        ];
        let fits = labels
            .iter()
            .flat_map(|l| forms(l, &ellipsis))
            .any(|form| row.contains(&format!(" {form} ")))
            // Where no word fits, the symbol alone names it.
            || row.split_whitespace().count() <= 3;
        assert!(fits, "{row:?} cuts a label mid-word ({what}):\n{screen}");
        assert_eq!(
            row.chars().count(),
            rows[0].chars().count(),
            "{row:?} overflows ({what})"
        );
    }
}

fn solved_app(params: Params, theme: Theme, shot: bool) -> App {
    let mut app = App::new(params, theme).unwrap();
    if shot {
        app.start_in_shot_mode();
    }
    drive(&mut app, 80, 24, vec![]);
    app
}

#[test]
fn every_label_fits_at_80_and_160_columns() {
    let ascii = Theme {
        ascii: true,
        ..Theme::default()
    };
    for (w, h) in [(80, 24), (160, 48)] {
        for theme in [Theme::default(), ascii] {
            let bounce = solved_app(Params::default(), theme, false);
            assert_labels_fit(bounce, w, h, &format!("bounce {w}x{h}"));
            let shot = solved_app(preset("topspin-forehand"), theme, true);
            assert_labels_fit(shot, w, h, &format!("shot {w}x{h}"));
            // Every bounce parameter that can be marked free, marked.
            let mut free = solved_app(Params::default(), theme, false);
            let mut events = Vec::new();
            for _ in 0..free.listed().len() {
                events.push(key(KeyCode::Char('f')));
                events.push(key(KeyCode::Down));
            }
            drive(&mut free, w, h, events);
            assert_labels_fit(free, w, h, &format!("free {w}x{h}"));
        }
    }
    // The long one at 80 columns: cut after a word.
    let app = solved_app(Params::default(), Theme::default(), false);
    let mut app = app;
    app.selected = app.listed().len() - 1;
    let screen = draw(&app, 80, 24);
    assert!(
        screen.contains("M_n frame normal…    frame mass"),
        "{screen}"
    );
    assert!(!screen.contains("frame normal mas "), "{screen}");
}

/// The value `spec` shows for `value`, as the panel writes it.
fn shown(id: ParamId, value: f64) -> String {
    let s = spec(id).show(value);
    if s.symbol == "g" && value >= 1.0 {
        format!("{} kg", units::brief(value, 4))
    } else {
        s.to_string()
    }
}

#[test]
fn in_a_shot_the_frame_is_the_racquets_whatever_bounce_is_on_screen() {
    // The string presets (a compliant ball, string friction) and the base shot, entered with m.
    for name in ["polyester-strings", "gut-strings", "topspin-forehand"] {
        let mut app = App::new(preset(name), Theme::default()).unwrap();
        let screen = drive(&mut app, 160, 48, vec![key(KeyCode::Char('m'))]);
        assert!(app.shots.on);
        let p = app.params;
        let hold = Hold::of(&p).unwrap();
        let (normal, tangential) = hold.effective_masses().expect("a hand-held racquet");
        let rows = panel(&screen);
        for (id, mass) in [
            (ParamId::FrameMass, tangential),
            (ParamId::FrameNormalMass, normal),
        ] {
            let row = row_of(&rows, spec(id), &app.theme).unwrap();
            assert!(row.contains("from the racquet"), "{row}\n{screen}");
            assert!(row.contains(&shown(id, mass)), "{row}\n{screen}");
            assert!(!row.contains("clamped"), "{row}\n{screen}");
        }
        let e_a = hold.ey_apparent(p.ey, p.mass);
        assert!((0.0..p.ey).contains(&e_a));
        let row = rows.iter().find(|r| r.contains("e_A")).unwrap();
        assert!(row.contains("apparent restitution"), "{row}");
        assert!(row.contains(&format!("{e_a:.2}")), "{row}");
        // The incidence rows are the strings' (the frame change), not the bounce's own.
        let strings = snapback::shot::strings_params(&p).unwrap();
        let row = row_of(&rows, spec(ParamId::Angle), &app.theme).unwrap();
        assert!(
            row.contains(&shown(ParamId::Angle, strings.angle_deg)),
            "{row}"
        );
        // A bounce the core refuses on the racquet's frame leaves the one before on screen, and the
        // status line says that it is not the shot's.
        let refused = app.params.frame_mass != tangential;
        assert_eq!(
            screen.contains("the bounce shown is not the shot's"),
            refused,
            "{name}:\n{screen}"
        );
    }
    // A clamped racquet is clamped: M_t and M_n say so, and e_A is e_y.
    let mut p = preset("topspin-forehand");
    p.racquet_mass = 0.0;
    let mut app = App::new(p, Theme::default()).unwrap();
    app.start_in_shot_mode();
    let screen = drive(&mut app, 160, 48, vec![]);
    let rows = panel(&screen);
    for id in [ParamId::FrameMass, ParamId::FrameNormalMass] {
        let row = row_of(&rows, spec(id), &app.theme).unwrap();
        assert!(row.contains("from the racquet"), "{row}");
        assert!(
            row.contains("clamped") || row.contains("frame mass"),
            "{row}"
        );
    }
    let row = rows.iter().find(|r| r.contains("e_A")).unwrap();
    assert!(row.contains(&format!("{:.2}", p.ey)), "{row}");
}

#[test]
fn the_panel_scrolls_no_further_than_the_selection_needs() {
    // At 160 x 48 in shot mode the shot's first row selected leaves the incidence in view.
    let mut app = App::new(preset("topspin-forehand"), Theme::default()).unwrap();
    app.start_in_shot_mode();
    let screen = drive(&mut app, 160, 48, vec![]);
    assert_eq!(app.selected_spec().id, ParamId::Height);
    let rows = panel(&screen);
    assert!(rows[0].contains("θ1"), "{screen}");
    assert!(!screen.contains("▲ more"), "{screen}");
    // Every row selected in turn is in view, at both sizes; the top is hidden only when it must be.
    for (w, h) in [(80, 24), (160, 48)] {
        for (i, spec) in PARAMS.iter().enumerate() {
            app.selected = i;
            let screen = draw(&app, w, h);
            let rows = panel(&screen);
            let row = row_of(&rows, spec, &app.theme)
                .unwrap_or_else(|| panic!("{} hidden at {w}x{h}:\n{screen}", spec.symbol));
            assert!(row.starts_with('▸'), "{row}");
            let position = rows.iter().position(|r| r == row).unwrap();
            let scrolled = screen.lines().next().unwrap().contains("▲ more");
            // Scrolled only to keep the selection and the row under it in view: then it sits low.
            if scrolled {
                assert!(position + 2 >= rows.len(), "{w}x{h} row {i}:\n{screen}");
            } else {
                assert!(rows[0].contains("θ1"), "{w}x{h} row {i}:\n{screen}");
            }
        }
    }
}
