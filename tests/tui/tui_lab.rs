//! The explorer's lab on ratatui's TestBackend: measurements (`--data`) drawn on the sweep view, the
//! residuals in the outcome panel (the same model values as `snapback fit`), parameters marked free and
//! fitted in the background with the keys still answered, the fit undone, the uncertainty band; a bad
//! data file refused before the terminal is touched; and the real binary fitting in a pseudo-terminal.

use crate::support::bin;

use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use predicates::prelude::*;
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use snapback::analysis::fit::data::{self, Dataset};
use snapback::analysis::fit::{self, Options, free};
use snapback::model::params::BOUNCE_PARAMS as PARAMS;
use snapback::model::{ParamId, Params, units};
use snapback::tui::theme::Theme;
use snapback::tui::{Action, App, Scripted, run, ui};

use crate::support::screen;
use screen::{line_with, text};

use crate::support::pty;

/// The synthetic data set shipped in assets/.
const SYNTHETIC: &str = "assets/data/synthetic-strings.csv";

fn synthetic() -> Dataset {
    let text = std::fs::read_to_string(SYNTHETIC).unwrap();
    data::parse(&text, SYNTHETIC).unwrap()
}

fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

fn char(c: char) -> Event {
    key(KeyCode::Char(c))
}

fn typed(text: &str) -> Vec<Event> {
    text.chars().map(char).collect()
}

/// An explorer on `params` with the synthetic data.
fn lab(params: Params, theme: Theme) -> App {
    let mut app = App::new(params, theme).unwrap();
    app.load_data(synthetic());
    app
}

/// `app` after `events` on a `width` x `height` screen, and the screen as text.
fn drive(app: &mut App, width: u16, height: u16, events: Vec<Event>) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    run(&mut terminal, app, &mut Scripted::from(events)).unwrap();
    text(&terminal)
}

/// The screen as `app` is now, without taking anything from the workers.
fn snapshot(app: &App, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal.draw(|frame| ui::draw(frame, app)).unwrap();
    text(&terminal)
}

fn message(app: &App) -> String {
    app.message
        .as_ref()
        .map(|m| m.text.clone())
        .unwrap_or_default()
}

/// The keys that move the selection from the angle to `id`.
fn select(id: ParamId) -> Vec<Event> {
    let i = PARAMS.iter().position(|s| s.id == id).unwrap();
    vec![char('j'); i]
}

/// The keys that mark M, k and mu free, from the angle, ending on mu.
fn free_three() -> Vec<Event> {
    let at = |id: ParamId| PARAMS.iter().position(|s| s.id == id).unwrap();
    let mut events = select(ParamId::CartMass);
    events.push(char('f'));
    events.extend(vec![
        char('j');
        at(ParamId::Stiffness) - at(ParamId::CartMass)
    ]);
    events.push(char('f'));
    events.extend(vec![char('k'); at(ParamId::Stiffness) - at(ParamId::Mu)]);
    events.push(char('f'));
    events
}

#[test]
fn the_sweep_view_draws_the_measured_points_on_their_curves() {
    for (w, h) in [(80, 24), (160, 48)] {
        let mut app = lab(Params::default(), Theme::default());
        let screen = drive(&mut app, w, h, vec![key(KeyCode::Tab)]);
        // The default spin is the data's -100 rad/s: seven rows on the current curve, seven (spin 0)
        // on the comparison curve; each with its sigma as an error bar.
        let legend = line_with(&screen, "● 7");
        let expected = if w >= 100 {
            "● 7 measured here  ○ 7 at ω1 = 0 rad/s  · bars ± 1σ"
        } else {
            "● 7 here  ○ 7 at ω1=0  · bars ±1σ"
        };
        assert!(legend.contains(expected), "{screen}");
        // Two points may share a cell where the curves meet; the rest are drawn.
        let drawn = |glyph: char| screen.chars().filter(|c| *c == glyph).count() - 1;
        assert!(drawn('●') >= 6 && drawn('●') <= 7, "{screen}");
        assert!(drawn('○') >= 6 && drawn('○') <= 7, "{screen}");
    }
    // Without the data, no points and no legend.
    let mut plain = App::new(Params::default(), Theme::default()).unwrap();
    let screen = drive(&mut plain, 160, 48, vec![key(KeyCode::Tab)]);
    assert!(!screen.contains('●') && !screen.contains("measured here"));
}

#[test]
fn rows_measured_elsewhere_are_counted_not_drawn() {
    // At a spin of -50 rad/s the comparison is spin 0 (seven rows); the -100 rows are elsewhere.
    let mut app = lab(Params::default(), Theme::default());
    let mut events = vec![key(KeyCode::Tab)];
    events.extend(select(ParamId::Spin));
    events.push(key(KeyCode::Enter));
    events.extend(typed("-50"));
    events.push(key(KeyCode::Enter));
    let screen = drive(&mut app, 160, 48, events);
    assert_eq!(app.params.spin, -50.0);
    let legend = line_with(&screen, "measured here");
    assert!(legend.contains("● 0 measured here"), "{screen}");
    assert!(legend.contains("○ 7 at ω1 = 0 rad/s"), "{screen}");
    assert!(legend.contains("7 elsewhere, not drawn"), "{screen}");
}

#[test]
fn ascii_writes_the_points_and_legend_in_ascii() {
    let theme = Theme {
        ascii: true,
        ..Theme::default()
    };
    let mut app = lab(Params::default(), theme);
    let screen = drive(&mut app, 160, 48, vec![key(KeyCode::Tab)]);
    // The glyphs are ASCII; the rest the output spells out (`·` as `.`, Greek letters as words).
    let legend = line_with(&screen, "measured here");
    assert!(
        legend.contains("* 7 measured here  o 7 at omega1 = 0 rad/s  · bars +- 1sd"),
        "{legend}"
    );
    assert!(!screen.contains('●') && !screen.contains('○'));
    let residuals = line_with(&screen, "data (14 rows)");
    assert!(residuals.contains("rms 5.39sd"), "{residuals}");
    let worst = line_with(&screen, "furthest: line 12");
    assert!(worst.contains("omega2 +29.1 (9.7sd)"), "{worst}");
}

#[test]
fn the_contact_view_draws_the_omega2_measured_here_at_the_end_of_the_spin_chart() {
    // The data have a row at 60 deg and -100 rad/s: the default bounce's conditions.
    let mut app = lab(Params::default(), Theme::default());
    let screen = drive(&mut app, 160, 48, vec![]);
    assert_eq!(screen.chars().filter(|c| *c == '●').count(), 1, "{screen}");
    // At 61 deg no row was measured.
    let screen = drive(&mut app, 160, 48, vec![char('l')]);
    assert!(!screen.contains('●'), "{screen}");
}

/// `snapback fit`'s JSON for the synthetic data with M, k and mu free.
fn cli_fit() -> serde_json::Value {
    let out = bin::snapback()
        .args([
            "fit",
            "--data",
            SYNTHETIC,
            "--free",
            "cart-mass,stiffness,mu",
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn the_residuals_are_those_of_snapback_fit_at_the_same_parameters() {
    let json = cli_fit();
    let fitted = |key: &str| json["free"][key]["value"].as_f64().unwrap();
    let params = Params {
        cart_mass: fitted("cart_mass"),
        stiffness: fitted("stiffness"),
        mu: fitted("mu"),
        ..Params::default()
    };
    for (w, h) in [(80, 24), (160, 48)] {
        let mut app = lab(params, Theme::default());
        let screen = drive(&mut app, w, h, vec![]);
        let r = app.lab.residuals.clone().expect("the residuals came");
        assert_eq!(r.params, params);
        let rows = json["rows"].as_array().unwrap();
        assert_eq!(r.compared.len(), rows.len());
        for (c, row) in r.compared.iter().zip(rows) {
            assert_eq!(c.line as u64, row["line"].as_u64().unwrap());
            assert_eq!(c.model, row["model"]["omega2"].as_f64().unwrap());
            assert_eq!(c.measured, row["measured"]["omega2"].as_f64().unwrap());
        }
        // The panel: rms in sigmas as `fit` gives it, chi2 per degree of freedom (no parameter is
        // marked free here: 14), and the row furthest from the model.
        let rms = json["rms"].as_f64().unwrap();
        let chi2 = json["chi2"].as_f64().unwrap();
        let (rms, per_dof) = (units::brief(rms, 3), units::brief(chi2 / 14.0, 3));
        if w >= 150 {
            assert!(line_with(&screen, "data (14 rows)").contains(&format!("rms {rms}σ")));
            let line = line_with(&screen, "chi2/dof");
            assert!(line.contains(&format!("{per_dof} (14 dof)")), "{line}");
        } else {
            let line = line_with(&screen, "data 14");
            assert!(
                line.contains(&format!("rms {rms}σ chi2/dof {per_dof}")),
                "{line}"
            );
        }
        let worst = rows
            .iter()
            .max_by(|a, b| {
                let res = |r: &serde_json::Value| r["residual"]["omega2"].as_f64().unwrap().abs();
                res(a).total_cmp(&res(b))
            })
            .unwrap();
        let residual = worst["residual"]["omega2"].as_f64().unwrap();
        let shown = format!("line {}", worst["line"].as_u64().unwrap());
        let line = line_with(&screen, &shown);
        let sign = if residual > 0.0 { "+" } else { "" };
        let expected = format!(
            "ω2 {sign}{} rad/s ({}σ)",
            units::brief(residual, 3),
            units::brief(residual.abs() / 3.0, 2)
        );
        assert!(line.contains(&expected), "{expected} not in {line}");
    }
}

#[test]
fn f_marks_parameters_free_and_refuses_what_cannot_be_fitted() {
    let mut app = lab(Params::default(), Theme::default());
    let mut events = select(ParamId::CartMass);
    events.push(char('f'));
    let screen = drive(&mut app, 160, 48, events);
    assert_eq!(app.lab.free, vec![ParamId::CartMass]);
    assert!(
        line_with(&screen, "cart mass").contains("free: cart mass"),
        "{screen}"
    );
    assert!(message(&app).starts_with("M free (free: M); F fits them to"));
    // f again fixes it.
    let screen = drive(&mut app, 160, 48, vec![char('f')]);
    assert!(app.lab.free.is_empty());
    assert!(!screen.contains("free: cart mass"), "{screen}");
    // The angle is a column of the data; the chain is a whole number.
    let mut app = lab(Params::default(), Theme::default());
    drive(&mut app, 160, 48, vec![char('f')]);
    assert!(app.lab.free.is_empty());
    assert!(
        message(&app).contains("is a column of"),
        "{}",
        message(&app)
    );
    let mut events = select(ParamId::Chain);
    events.push(char('f'));
    drive(&mut app, 160, 48, events);
    assert!(app.lab.free.is_empty());
    assert!(message(&app).contains("whole number"), "{}", message(&app));
    // In shot mode (m) the selection moves to the shot's first parameter, which the data cannot see.
    let mut app = lab(Params::default(), Theme::default());
    drive(&mut app, 160, 48, vec![char('m'), char('f')]);
    assert!(app.lab.free.is_empty());
    assert!(message(&app).contains("is the shot's"), "{}", message(&app));
}

#[test]
fn refusals_are_messages() {
    // No data.
    let mut app = App::new(Params::default(), Theme::default()).unwrap();
    drive(&mut app, 80, 24, vec![char('F')]);
    assert!(message(&app).starts_with("no measurements to fit"));
    // No free parameter.
    let mut app = lab(Params::default(), Theme::default());
    drive(&mut app, 80, 24, vec![char('F')]);
    assert!(message(&app).starts_with("no free parameters"));
    assert!(app.lab.fitting.is_none());
    // More free parameters than measurements.
    let text = "angle,omega2\n40,100\n";
    let mut app = App::new(Params::default(), Theme::default()).unwrap();
    app.load_data(data::parse(text, "one.csv").unwrap());
    let mut events = select(ParamId::CartMass);
    events.extend([char('f'), char('F')]);
    drive(&mut app, 80, 24, events);
    assert!(
        message(&app).contains("1 measurements cannot determine 1 free parameters"),
        "{}",
        message(&app)
    );
}

#[test]
fn a_parameter_the_data_cannot_determine_is_named_and_not_applied() {
    // The ball is rigid by default: its damping changes nothing.
    let mut app = lab(Params::default(), Theme::default());
    let mut events = select(ParamId::BallDamping);
    events.extend([char('f'), char('F')]);
    drive(&mut app, 80, 24, events);
    assert_eq!(app.params, Params::default());
    assert!(
        message(&app).starts_with("the data cannot determine ζ_b: fit not applied"),
        "{}",
        message(&app)
    );
}

#[test]
fn capital_f_fits_in_the_background_and_u_undoes_the_fit() {
    let mut app = lab(Params::default(), Theme::default());
    drive(&mut app, 160, 48, free_three());
    assert_eq!(
        app.lab.free,
        vec![ParamId::Mu, ParamId::CartMass, ParamId::Stiffness]
    );
    // F starts the fit on the worker and returns at once; the status line shows its progress.
    app.update(Action::Fit);
    assert!(app.lab.fitting.is_some());
    let screen = snapshot(&app, 160, 48);
    assert!(screen.contains("fitting μ, M, k: "), "{screen}");
    // Keys are answered meanwhile: the selection moves, the view changes, the help opens and closes.
    app.update(Action::SelectNext);
    app.update(Action::NextView);
    app.update(Action::ToggleHelp);
    app.update(Action::ToggleHelp);
    assert!(app.lab.fitting.is_some(), "the fit ran on the UI thread");
    assert!(app.settle(Duration::from_secs(120)));
    assert!(app.lab.fitting.is_none());

    // The same fit as `snapback fit`'s, applied as one change.
    let data = synthetic();
    let free = free::parse_list("mu,cart-mass,stiffness", &data.conditions).unwrap();
    let expected = fit::fit(&Params::default(), &free, &data, &Options::default()).unwrap();
    assert_eq!(app.params, expected.params);
    // It recovers the parameters the data were made from, within its 95% intervals.
    let truth = [
        (ParamId::Mu, 0.35),
        (ParamId::CartMass, 0.005),
        (ParamId::Stiffness, 12_000.0),
    ];
    for (f, (id, value)) in expected.free.iter().zip(truth) {
        assert_eq!(f.id, id);
        let (lo, hi) = f.ci95.unwrap();
        assert!(
            lo <= value && value <= hi,
            "{id:?}: {value} not in [{lo}, {hi}]"
        );
    }
    let text = message(&app);
    assert!(text.starts_with("fit in "), "{text}");
    for f in &expected.free {
        let se = f.stderr.unwrap();
        let shown = format!(
            "{} ± {}",
            fit::shown(f.id, f.value, Some(se)),
            fit::shown(f.id, se, Some(se))
        );
        assert!(text.contains(&shown), "{shown} not in {text}");
    }
    assert!(text.ends_with("u undoes"), "{text}");

    // u undoes the whole fit at once; Ctrl-R redoes it.
    let screen = drive(&mut app, 160, 48, vec![char('u')]);
    assert_eq!(app.params, Params::default());
    assert!(message(&app).starts_with("undo: 3 parameters"), "{screen}");
    drive(
        &mut app,
        160,
        48,
        vec![Event::Key(KeyEvent::new(
            KeyCode::Char('r'),
            KeyModifiers::CONTROL,
        ))],
    );
    assert_eq!(app.params, expected.params);
}

#[test]
fn f_again_or_esc_stops_the_fit_and_changes_nothing() {
    for stop in [Action::Fit, Action::Quit] {
        let mut app = lab(Params::default(), Theme::default());
        drive(&mut app, 80, 24, free_three());
        app.update(Action::Fit);
        app.update(stop);
        assert!(app.lab.fitting.is_none());
        assert!(!app.quit, "Esc stops the fit before it quits");
        assert!(
            message(&app).starts_with("fit stopped"),
            "{}",
            message(&app)
        );
        assert!(app.settle(Duration::from_secs(60)));
        assert_eq!(app.params, Params::default());
    }
}

#[test]
fn a_fit_is_not_applied_when_a_fixed_parameter_changed_while_it_ran() {
    let mut app = lab(Params::default(), Theme::default());
    drive(&mut app, 80, 24, free_three());
    app.update(Action::Fit);
    // The speed is neither free nor a column of the data.
    app.selected = PARAMS.iter().position(|s| s.id == ParamId::Speed).unwrap();
    app.update(Action::Step {
        up: true,
        coarse: false,
    });
    assert!(app.settle(Duration::from_secs(120)));
    assert_eq!(app.params.speed, 10.5);
    assert_eq!(app.params.cart_mass, Params::default().cart_mass);
    assert!(
        message(&app).starts_with("fit not applied: v1 changed while it ran"),
        "{}",
        message(&app)
    );
}

#[test]
fn a_value_typed_with_an_uncertainty_draws_the_band() {
    let mut app = lab(Params::default(), Theme::default());
    let mut events = vec![key(KeyCode::Tab)];
    events.extend(select(ParamId::Spin));
    let before = drive(&mut app, 160, 48, events);
    let mut events = vec![key(KeyCode::Enter)];
    events.extend(typed("-100±20"));
    events.push(key(KeyCode::Enter));
    let screen = drive(&mut app, 160, 48, events);
    assert_eq!(app.params.spin, -100.0);
    assert!(
        line_with(&screen, "incident spin").contains("-100±20 rad/s"),
        "{screen}"
    );
    let band = app
        .lab
        .band_for(&app.params)
        .expect("the band was computed");
    assert_eq!(band.points.len(), 45);
    assert!(band.points.iter().all(|p| p.sd > 0.0));
    let legend = line_with(&screen, "band:");
    assert!(
        legend.contains("band: ω2 ± 1 sd over 200 draws, for ω1 ± 20 rad/s"),
        "{legend}"
    );
    // The band's curves are drawn: the chart differs from the one without them.
    let chart =
        |s: &str| -> Vec<String> { s.lines().map(|l| l.chars().skip(45).collect()).collect() };
    let changed = chart(&before)
        .iter()
        .zip(chart(&screen))
        .filter(|(a, b)| **a != *b)
        .count();
    assert!(changed > 10, "{changed} rows changed:\n{screen}");
    // ±0 removes it.
    let mut events = vec![key(KeyCode::Enter)];
    events.extend(typed("-100±0"));
    events.push(key(KeyCode::Enter));
    let screen = drive(&mut app, 160, 48, events);
    assert!(app.lab.spreads.is_empty());
    assert!(!screen.contains("band:"), "{screen}");
}

#[test]
fn a_bad_data_file_exits_2_naming_file_line_and_column() {
    let dir = std::env::temp_dir().join(format!("snapback-tui-lab-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "angle,omega2\n40,100\n50,x1\n").unwrap();
    for args in [vec!["--data"], vec!["tui", "--data"]] {
        bin::snapback()
            .args(&args)
            .arg(&bad)
            .assert()
            .code(2)
            .stdout("")
            .stderr(format!(
                "error: {}:3:2: 'x1' is not a number\n",
                bad.display()
            ));
    }
    // Standard input is read as for `fit`.
    bin::snapback()
        .args(["--data", "-"])
        .write_stdin("angle,omega3\n40,1\n")
        .assert()
        .code(2)
        .stderr(predicate::str::starts_with(
            "error: <stdin>:1:2: unknown column 'omega3'",
        ));
    // A good file gets as far as the terminal.
    bin::snapback()
        .args(["--data", SYNTHETIC])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("needs a terminal"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_binary_fits_in_the_background_and_undoes_the_fit() {
    let data = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/data/synthetic-strings.csv"
    );
    let mut pty = pty::Pty::spawn(&["--data", data], &[], 120, 40);
    pty.wait_for("the residuals at the defaults", |s| {
        s.contains("data 14  rms 5.39σ chi2/dof 29")
    });
    let keys: String = free_three()
        .iter()
        .map(|e| match e {
            Event::Key(KeyEvent {
                code: KeyCode::Char(c),
                ..
            }) => *c,
            _ => unreachable!("free_three types letters"),
        })
        .collect();
    pty.send(keys.as_bytes());
    pty.wait_for("M, k and mu free", |s| s.contains("free: cart mass"));
    let started = Instant::now();
    pty.send(b"F");
    pty.wait_for("the fit", |s| s.contains("fit in "));
    // The fit's own figure, and the wall time from the key to the screen (printed with --nocapture).
    let screen = pty.screen();
    let message = line_with(&screen, "fit in ");
    eprintln!(
        "{message}\nfrom F to the screen: {:.0} ms",
        started.elapsed().as_secs_f64() * 1e3
    );
    pty.wait_for("the residuals at the fit", |s| {
        s.contains("data 14  rms 1.07σ chi2/dof 1.44")
    });
    pty.send(b"u");
    pty.wait_for("the fit undone", |s| {
        s.contains("undo: 3 parameters") && s.contains("10.00 g")
    });
    pty.send(b"q");
    let status = pty.exit(pty::PATIENCE).expect("it quits");
    assert!(status.success(), "{status:?}");
}

#[test]
fn a_bad_data_file_never_touches_the_terminal() {
    let dir = std::env::temp_dir().join(format!("snapback-tui-lab-pty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "angle,omega2,mu\n40,100\n").unwrap();
    let mut pty = pty::Pty::spawn(&["--data", bad.to_str().unwrap()], &[], 120, 40);
    pty.wait_for("the error", |s| s.contains("missing value for mu"));
    let status = pty.exit(pty::PATIENCE).expect("it exits");
    assert_eq!(status.exit_code(), 2);
    let written = String::from_utf8(pty.bytes_since(0)).unwrap();
    assert!(
        written.contains("bad.csv:2:3: missing value for mu"),
        "{written:?}"
    );
    // Neither the alternate screen nor raw mode's mouse reporting was asked for.
    assert!(!written.contains("\x1b[?1049h") && !written.contains("\x1b[?1000h"));
    std::fs::remove_dir_all(&dir).unwrap();
}
