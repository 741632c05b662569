//! The explorer's shot view (issue 16 item 3) through the real event loop on ratatui's TestBackend: Tab
//! reaches it and turns shot mode on, its readouts are `snapback shot`'s, a shot parameter changes them,
//! the incidence the frame change sets is refused, a pinned baseline draws, and it reads at 80 x 24 and
//! in ASCII.

use crate::support::bin;

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::symbols::Marker;
use snapback::model::Params;
use snapback::model::params::{PARAMS, ParamId};
use snapback::scenario;
use snapback::shot::{self, Shot};
use snapback::tui::output::ascii;
use snapback::tui::theme::Theme;
use snapback::tui::{App, Scripted, View, run};

use crate::support::screen;
use screen::{line_with, text};

fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

fn char(c: char) -> Event {
    key(KeyCode::Char(c))
}

fn tabs(n: usize) -> Vec<Event> {
    vec![key(KeyCode::Tab); n]
}

/// The parameters of a preset, as the explorer's picker and `--preset` give them.
fn preset(name: &str) -> Params {
    snapback::config::preset(name)
        .unwrap()
        .apply(Params::default())
}

/// `app` after `events` on a `width` x `height` screen, and the terminal.
fn drive(app: &mut App, width: u16, height: u16, events: Vec<Event>) -> Terminal<TestBackend> {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    run(&mut terminal, app, &mut Scripted::from(events)).unwrap();
    terminal
}

/// The explorer started on `params` (not in shot mode), after `events`.
fn explore(params: Params, theme: Theme, size: (u16, u16), events: Vec<Event>) -> (App, String) {
    let mut app = App::new(params, theme).unwrap();
    let terminal = drive(&mut app, size.0, size.1, events);
    (app, text(&terminal))
}

/// `snapback shot --preset NAME --format json`.
fn shot_json(name: &str) -> serde_json::Value {
    let out = bin::command()
        .args(["shot", "--preset", name, "--format", "json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Index of `id` in the panel's list in shot mode.
fn row(id: ParamId) -> usize {
    PARAMS.iter().position(|s| s.id == id).unwrap()
}

/// The keys that move the selection from `from` to `to` in shot mode.
fn select(from: ParamId, to: ParamId) -> Vec<Event> {
    let (a, b) = (row(from), row(to));
    if b >= a {
        vec![key(KeyCode::Down); b - a]
    } else {
        vec![key(KeyCode::Up); a - b]
    }
}

/// The readouts of `shot` as the narrow and the wide view write them.
fn readouts(shot: &Shot) -> Vec<String> {
    let launch = shot.strings.leaving;
    vec![
        format!("{:.1} m/s", launch.speed()),
        format!("{:.1}°", launch.angle_deg()),
        format!("{:.0} rpm", launch.topspin() * 30.0 / std::f64::consts::PI),
        format!("clears it by {:.1} cm", shot.net_clearance.unwrap() * 100.0),
        format!("{:.2} m past", shot.landing_x.unwrap() - shot::court::NET_X),
        format!("{:.2} m", shot.kick_height.unwrap()),
        format!("{:.2} s", shot.flight_time),
    ]
}

/// The court's rows: from under the readouts to the row of labels under the court, in the view's columns.
fn court(screen: &str) -> Vec<Vec<char>> {
    let lines: Vec<&str> = screen.lines().collect();
    let labels = lines
        .iter()
        .rposition(|l| l.contains("net") && l.contains("23.77 m"))
        .unwrap();
    let first = lines.iter().position(|l| l.contains("kick")).unwrap() + 1;
    lines[first..=labels]
        .iter()
        .map(|l| l.chars().collect())
        .collect()
}

/// Cells of the court picture (above the labels) that are drawn, right of column `left`.
fn drawn(screen: &str, left: usize) -> usize {
    let rows = court(screen);
    rows[..rows.len() - 1]
        .iter()
        .map(|r| {
            r.iter()
                .skip(left)
                .filter(|c| !c.is_whitespace() && **c != '\u{2800}')
                .count()
        })
        .sum()
}

#[test]
fn tab_reaches_the_shot_view_with_snapback_shots_numbers_and_the_court() {
    let json = shot_json("topspin-forehand");
    let params = preset("topspin-forehand");
    let shot = shot::play(&params, false).unwrap();
    // The same shot as the command line's.
    assert_eq!(
        json["launch"]["speed"].as_f64().unwrap(),
        shot.strings.leaving.speed()
    );
    assert_eq!(json["net_clearance_m"].as_f64(), shot.net_clearance);
    assert_eq!(
        json["landing_m"].as_f64(),
        shot.landing_x.map(|x| x - shot::court::NET_X)
    );
    assert_eq!(json["kick_height_m"].as_f64(), shot.kick_height);
    for size in [(160, 48), (80, 24)] {
        let (app, screen) = explore(params, Theme::default(), size, tabs(3));
        assert_eq!(app.view, View::Shot);
        assert!(app.shots.on);
        assert!(line_with(&screen, "shot").contains(" IN "), "{screen}");
        for readout in readouts(&shot) {
            assert!(screen.contains(&readout), "{readout:?} in\n{screen}");
        }
        // The strings see the shot's contact: the panel shows the incidence `snapback shot` reports.
        assert_eq!(
            app.params.angle_deg,
            json["contact"]["angle_deg"].as_f64().unwrap()
        );
        assert_eq!(app.params.speed, json["contact"]["speed"].as_f64().unwrap());
        assert_eq!(app.params.spin, json["contact"]["spin"].as_f64().unwrap());
        if size.1 == 48 {
            // At 48 rows the panel shows the incidence the shot sets, and the frame the racquet
            // sets, above the shot group.
            assert!(
                line_with(&screen, "θ1").contains("set by the shot"),
                "{screen}"
            );
            assert!(
                line_with(&screen, "M_t").contains("from the racquet"),
                "{screen}"
            );
        }
        assert!(
            screen.contains("── shot "),
            "the shot group's heading in\n{screen}"
        );
        assert_eq!(
            app.solved.as_ref().unwrap().bounce.outcome.omega2,
            shot.strings.bounce.outcome.omega2
        );
        // The net stands over its label, drawn up from the ground; the baselines rise from it too.
        let rows = court(&screen);
        let labels = rows.last().unwrap();
        let text: String = labels.iter().collect();
        let net = text
            .find("net")
            .map(|b| text[..b].chars().count() + 1)
            .unwrap();
        let standing = rows[..rows.len() - 1]
            .iter()
            .rev()
            .take_while(|r| (net - 1..=net + 1).any(|c| !r[c].is_whitespace()))
            .count();
        assert!(standing >= 3, "a net {standing} rows high in\n{screen}");
        let ground = &rows[rows.len() - 2];
        let zero = text
            .find(" 0 ")
            .map(|b| text[..b].chars().count() + 1)
            .unwrap();
        assert!(
            (zero - 1..=zero + 1).any(|c| !rows[rows.len() - 3][c].is_whitespace()),
            "the hitter's baseline rises above the ground in\n{screen}"
        );
        assert!(
            ground[net + 5..]
                .iter()
                .filter(|c| !c.is_whitespace())
                .count()
                > 10
        );
    }
}

#[test]
fn a_shot_parameter_changes_the_readouts_and_the_strings() {
    let params = preset("topspin-forehand");
    let mut events = tabs(3);
    events.extend(select(ParamId::Height, ParamId::RacquetSpeed));
    events.extend([key(KeyCode::Right), key(KeyCode::Right)]);
    let (app, screen) = explore(params, Theme::default(), (160, 48), events);
    assert_eq!(app.selected_spec().id, ParamId::RacquetSpeed);
    assert!(app.params.racquet_speed > params.racquet_speed);
    let before = shot::play(&params, false).unwrap();
    let after = shot::play(&app.params, false).unwrap();
    assert_ne!(readouts(&before)[0], readouts(&after)[0]);
    for readout in readouts(&after) {
        assert!(screen.contains(&readout), "{readout:?} in\n{screen}");
    }
    // The contact view's bounce follows: what the strings see for the faster racquet.
    assert_eq!(app.params.speed, after.strings.incidence.speed);
    assert_eq!(
        app.solved.as_ref().unwrap().bounce.outcome.omega2,
        after.strings.bounce.outcome.omega2
    );
}

#[test]
fn the_incidence_is_refused_in_shot_mode_naming_the_shot_parameters() {
    let params = preset("slice");
    let mut start = tabs(3);
    start.extend(select(ParamId::Height, ParamId::Speed));
    for attempt in [
        key(KeyCode::Right),
        key(KeyCode::Enter),
        char('r'),
        char('L'),
        char('f'),
    ] {
        let mut events = start.clone();
        events.push(attempt);
        let (app, screen) = explore(params, Theme::default(), (80, 24), events);
        assert_eq!(app.selected_spec().id, ParamId::Speed);
        assert_eq!(app.mode, snapback::tui::Mode::Normal, "no prompt opens");
        let message = app.message.as_ref().expect("a message").text.clone();
        for words in [
            "set by the frame change",
            "incoming speed v_b",
            "racquet speed V_r",
            "face angle",
        ] {
            assert!(message.contains(words), "{words:?} in {message}");
        }
        assert!(message.ends_with("(value unchanged)"), "{message}");
        assert!(screen.contains("set by the frame change"), "{screen}");
        assert_eq!(
            app.params.speed,
            shot::hit(&params).unwrap().incidence.speed
        );
    }
    // The help says so too.
    let mut events = start.clone();
    events.push(char('?'));
    let (_, help) = explore(params, Theme::default(), (160, 48), events);
    assert!(
        help.contains("in a shot the frame change sets it"),
        "{help}"
    );
    // Outside shot mode the incident speed steps as ever.
    let (app, _) = explore(
        params,
        Theme::default(),
        (80, 24),
        vec![key(KeyCode::Down), key(KeyCode::Right)],
    );
    assert_eq!(app.params.speed, params.speed + 0.5);
    assert!(!app.shots.on);
}

#[test]
fn a_racquet_that_never_meets_the_ball_is_refused_or_said_in_the_view() {
    // The kick serve's ball is at rest: a racquet at rest never meets it.
    let params = preset("kick-serve");
    let mut events = tabs(3);
    events.extend(select(ParamId::Height, ParamId::RacquetSpeed));
    events.extend([key(KeyCode::Enter), char('0'), key(KeyCode::Enter)]);
    let (app, screen) = explore(params, Theme::default(), (80, 24), events);
    assert_eq!(app.params.racquet_speed, params.racquet_speed);
    let message = app.message.as_ref().expect("a message").text.clone();
    assert!(message.contains("never meets the ball"), "{message}");
    assert!(screen.contains(" IN "), "the shot before stays:\n{screen}");
    // Where there is no shot before it (a start the frame change cannot take), the view says why.
    let never = Params {
        racquet_speed: 0.0,
        ..params
    };
    let mut app = App::new(never, Theme::default()).unwrap();
    app.explore_shot();
    let screen = text(&drive(&mut app, 80, 24, vec![]));
    assert_eq!(app.view, View::Contact);
    let screen_shot = text(&drive(&mut app, 80, 24, tabs(3)));
    assert!(!screen.contains("no shot to draw"));
    assert!(screen_shot.contains("no shot to draw"), "{screen_shot}");
    assert!(screen_shot.contains("never meets"), "{screen_shot}");
}

#[test]
fn a_pinned_baseline_draws_dimmer_with_the_differences() {
    let params = preset("topspin-forehand");
    let left = 36;
    let mut events = tabs(3);
    let (_, plain) = explore(params, Theme::default(), (160, 48), events.clone());
    events.push(char('b'));
    events.extend(select(ParamId::Height, ParamId::FaceAngle));
    events.extend(vec![key(KeyCode::Left); 2]);
    let (app, pinned) = explore(params, Theme::default(), (160, 48), events.clone());
    assert!(app.baseline.is_some());
    assert!(
        line_with(&pinned, "shot from the side").contains("baseline"),
        "{pinned}"
    );
    let base = shot::play(&params, false).unwrap();
    let now = shot::play(&app.params, false).unwrap();
    let d_land = now.landing_x.unwrap() - base.landing_x.unwrap();
    assert!(d_land.abs() > 0.01);
    assert!(pinned.contains(&format!("({:+.2} m)", d_land)), "{pinned}");
    // The second path: more of the court is drawn, and clearing the baseline takes it away.
    assert!(drawn(&pinned, left) > drawn(&plain, left) + 20, "{pinned}");
    events.push(char('B'));
    let (_, cleared) = explore(params, Theme::default(), (160, 48), events);
    assert!(drawn(&cleared, left) < drawn(&pinned, left));
    assert!(!line_with(&cleared, "shot from the side").contains("baseline"));
    // Without colour the baseline is dotted: still drawn.
    let no_colour = Theme {
        color: false,
        ..Theme::default()
    };
    let mut events = tabs(3);
    events.push(char('b'));
    events.extend(select(ParamId::Height, ParamId::FaceAngle));
    events.extend(vec![key(KeyCode::Left); 2]);
    let (_, dotted) = explore(params, no_colour, (160, 48), events);
    assert!(
        line_with(&dotted, "shot from the side").contains("· baseline"),
        "{dotted}"
    );
}

#[test]
fn ascii_mode_writes_nothing_the_ascii_output_cannot_spell() {
    let theme = Theme {
        ascii: true,
        marker: Marker::Dot,
        ..Theme::default()
    };
    for size in [(80, 24), (160, 48)] {
        let (_, screen) = explore(preset("kick-serve"), theme, size, tabs(3));
        // Past the left column, every character is ASCII or one the output turns into its look-alike.
        for line in screen.lines() {
            for c in line.chars().skip(44) {
                let s = c.to_string();
                assert!(
                    c.is_ascii() || !ascii(&s).contains('?'),
                    "{c:?} in {line}\n{screen}"
                );
            }
        }
        assert!(screen.contains("deg"), "angles spelt out in\n{screen}");
        assert!(screen.contains(" IN "), "{screen}");
        for symbol in ["delta_b", "psi", "phi"] {
            if size.1 == 48 {
                assert!(screen.contains(symbol), "{symbol} in\n{screen}");
            }
        }
    }
}

#[test]
fn at_80_x_24_the_key_readouts_fit() {
    for name in ["flat-drive", "topspin-forehand", "slice", "kick-serve"] {
        let (_, screen) = explore(preset(name), Theme::default(), (80, 24), tabs(3));
        let shot = shot::play(&preset(name), false).unwrap();
        for word in ["launch", "net ", "lands", "kick", "flight", "23.77 m"] {
            assert!(screen.contains(word), "{word:?} for {name} in\n{screen}");
        }
        for readout in readouts(&shot) {
            assert!(
                screen.contains(&readout),
                "{readout:?} for {name} in\n{screen}"
            );
        }
        // No readout is cut at the screen's edge, with a baseline's differences too: each fits the 45
        // columns of the view (a difference that would not is left out).
        let mut events = tabs(3);
        events.push(char('b'));
        events.extend(select(ParamId::Height, ParamId::RacquetSpeed));
        events.extend(vec![key(KeyCode::Char('L')); 2]);
        let (_, pinned) = explore(preset(name), Theme::default(), (80, 24), events);
        for screen in [&screen, &pinned] {
            let first = screen.lines().position(|l| l.contains("launch")).unwrap();
            for line in screen.lines().skip(first).take(4) {
                assert_eq!(line.chars().nth(79), Some(' '), "{line}\n{screen}");
            }
        }
        assert!(line_with(&pinned, "net ").contains(" cm)"), "{pinned}");
    }
}

#[test]
fn the_command_line_starts_a_shot_as_snapback_shot_plays_it() {
    for (args, expected) in [
        (
            vec!["--preset", "topspin-forehand", "--angle", "30"],
            "--angle is what the strings see",
        ),
        (
            vec!["--preset", "kick-serve", "--racquet-speed", "0"],
            "the racquet never meets the ball",
        ),
    ] {
        let out = bin::command().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {out:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
    // A bounce start is as it was: the incidence flags are taken (and no terminal is the one error).
    let out = bin::command().args(["--angle", "30"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("needs a terminal"), "{stderr}");
}

#[test]
fn picking_a_shot_preset_turns_shot_mode_on_and_the_picker_finds_it_again() {
    let index = scenario::PRESETS
        .iter()
        .position(|p| p.name == "kick-serve")
        .unwrap();
    let mut events = vec![char('p')];
    events.extend(vec![key(KeyCode::Down); index]);
    events.push(key(KeyCode::Enter));
    let (mut app, screen) = explore(Params::default(), Theme::default(), (160, 48), events);
    assert!(app.shots.on, "{screen}");
    assert_eq!(app.view, View::Contact);
    let params = preset("kick-serve");
    assert_eq!(
        app.params.speed,
        shot::hit(&params).unwrap().incidence.speed
    );
    assert!(screen.contains("── shot "), "{screen}");
    // The contact view shows the bounce on the strings.
    assert_eq!(
        app.solved.as_ref().unwrap().bounce.outcome.omega2,
        shot::hit(&params).unwrap().bounce.outcome.omega2
    );
    drive(&mut app, 160, 48, vec![char('p')]);
    assert_eq!(app.mode, snapback::tui::Mode::Picker(index));
}

#[test]
fn m_leaves_shot_mode_and_the_bounces_own_incidence_comes_back() {
    let own = Params {
        angle_deg: 45.0,
        speed: 12.0,
        spin: -50.0,
        ..Params::default()
    };
    // Tab into the shot view turns shot mode on; m turns it off and shows the contact view again.
    let (app, screen) = explore(own, Theme::default(), (160, 48), {
        let mut events = tabs(3);
        events.push(char('m'));
        events
    });
    assert!(!app.shots.on);
    assert_eq!(app.view, View::Contact);
    assert_eq!(
        (app.params.angle_deg, app.params.speed, app.params.spin),
        (45.0, 12.0, -50.0)
    );
    assert!(screen.contains("shot mode off"), "{screen}");
    assert!(!screen.contains("set by the shot"), "{screen}");
    // m turns it on again from any view, and the strings' incidence follows the shot.
    let (app, screen) = explore(own, Theme::default(), (160, 48), vec![char('m')]);
    assert!(app.shots.on);
    assert_eq!(app.view, View::Contact);
    let strings = shot::hit(&own).unwrap().incidence;
    assert_eq!(app.params.angle_deg, strings.theta1_deg);
    assert!(
        line_with(&screen, "M_t").contains("from the racquet"),
        "{screen}"
    );
    // And m once more gives the bounce back.
    let (app, _) = explore(own, Theme::default(), (160, 48), vec![char('m'), char('m')]);
    assert!(!app.shots.on);
    assert_eq!(app.params, own);
}

#[test]
fn a_file_listing_the_shot_keys_at_their_defaults_is_a_bounce() {
    // The explorer used to save every key: such a file is a bounce, a shot preset is a shot.
    let p = Params {
        angle_deg: 40.0,
        ..Params::default()
    };
    let every_key = scenario::Scenario::from_params("old", "saved before shot mode", &p);
    assert!(!every_key.is_shot());
    assert!(
        snapback::config::preset("topspin-forehand")
            .unwrap()
            .is_shot()
    );
    let dir = std::env::temp_dir().join(format!("snapback-tui-shot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("old.toml");
    every_key.save(&path).unwrap();
    let mut app = App::new(Params::default(), Theme::default()).unwrap();
    app.dir = dir.clone();
    let mut events = vec![char('o')];
    events.extend("old.toml".chars().map(char));
    events.push(key(KeyCode::Enter));
    drive(&mut app, 160, 48, events);
    assert!(!app.shots.on);
    assert_eq!(app.params.angle_deg, 40.0);
    // A shot saved in shot mode, even the default one, opens as a shot.
    let mut app = App::new(Params::default(), Theme::default()).unwrap();
    app.dir = dir.clone();
    let mut events = vec![char('m'), char('s')];
    events.extend("shot.toml".chars().map(char));
    events.push(key(KeyCode::Enter));
    drive(&mut app, 160, 48, events);
    let saved = scenario::Scenario::load(&dir.join("shot.toml")).unwrap();
    assert!(saved.is_shot(), "{saved:?}");
    let mut reopened = App::new(Params::default(), Theme::default()).unwrap();
    reopened.dir = dir.clone();
    let mut events = vec![char('o')];
    events.extend("shot.toml".chars().map(char));
    events.push(key(KeyCode::Enter));
    drive(&mut reopened, 160, 48, events);
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(reopened.shots.on);
    assert_eq!(reopened.params, app.params);
}

#[test]
fn tab_from_the_default_bounce_plays_the_shot_snapback_shot_plays() {
    // `snapback shot` with no flag starts from shot::base(), not from the bounce's e_y = 1.
    let expected = shot::play(&shot::base(), false).unwrap();
    let (_, screen) = explore(Params::default(), Theme::default(), (160, 48), tabs(3));
    assert!(
        screen.contains("snapback shot"),
        "the message says so:\n{screen}"
    );
    // A key that changes nothing (help opened and closed) clears the message for the hints.
    let (app, screen) = explore(Params::default(), Theme::default(), (160, 48), {
        let mut events = tabs(3);
        events.extend([char('?'), char('?')]);
        events
    });
    assert!(app.shots.on);
    assert_eq!(app.view, View::Shot);
    assert_eq!(app.params.ey, shot::base().ey);
    for readout in readouts(&expected) {
        assert!(screen.contains(&readout), "{readout} in\n{screen}");
    }
    // The hint line names m, and offers play (the flight) but not the contact's time keys.
    let hints = screen.lines().last().unwrap();
    assert!(
        hints.contains("m shot off") && hints.contains("␣ play"),
        "{hints}"
    );
    for absent in ["[] time", "{} phase", "+- speed"] {
        assert!(!hints.contains(absent), "{absent} in {hints}");
    }
    // Back in the contact view, shot mode stays on and m is still offered, with the time keys.
    let (_, screen) = explore(Params::default(), Theme::default(), (160, 48), {
        let mut events = tabs(4);
        events.extend([char('?'), char('?')]);
        events
    });
    let hints = screen.lines().last().unwrap();
    assert!(
        hints.contains("m shot off") && hints.contains("␣ play"),
        "{hints}"
    );
    // m leaves it: e_y, which the shot's start set, comes back with the incidence.
    let (app, screen) = explore(Params::default(), Theme::default(), (160, 48), {
        let mut events = tabs(3);
        events.push(char('m'));
        events
    });
    assert_eq!(app.params, Params::default());
    assert!(
        screen.contains("θ1, v1, ω1, M_t, M_n and e_y are back"),
        "{screen}"
    );
}

#[test]
fn reset_all_leaves_the_shot_for_the_bounce_the_explorer_started_with() {
    let start = Params {
        mu: 0.3,
        ..Params::default()
    };
    let (app, screen) = explore(start, Theme::default(), (160, 48), {
        let mut events = tabs(3);
        events.extend([char('l'), char('R')]);
        events
    });
    assert!(!app.shots.on);
    assert_eq!(app.view, View::Contact);
    assert_eq!(app.params, start);
    assert!(
        screen.contains("reset: every parameter is back to the start, and shot mode is off"),
        "{screen}"
    );
    // Started as a shot, R comes back to the shot.
    let params = preset("topspin-forehand");
    let mut app = App::new(params, Theme::default()).unwrap();
    app.start_in_shot_mode();
    let screen = text(&drive(&mut app, 160, 48, vec![char('m'), char('R')]));
    assert!(app.shots.on);
    assert_eq!(
        app.params,
        snapback::tui::shot::strings_params(&params).unwrap()
    );
    assert!(
        screen.contains("shot mode is on, as at the start"),
        "{screen}"
    );
}

#[test]
fn space_plays_the_flight_in_the_shot_view() {
    use snapback::tui::Input;
    use std::time::Duration;
    let params = preset("topspin-forehand");
    let mut app = App::new(params, Theme::default()).unwrap();
    app.start_in_shot_mode();
    let mut inputs: Vec<Input> = tabs(3).into_iter().map(Input::from).collect();
    inputs.push(char(' ').into());
    inputs.extend(vec![Input::Tick(Duration::from_millis(100)); 3]);
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    run(&mut terminal, &mut app, &mut Scripted::from(inputs)).unwrap();
    let screen = text(&terminal);
    assert!(app.playing);
    assert!((app.flight - 0.3).abs() < 1e-9, "{}", app.flight);
    assert!(screen.contains("t 0.30 s"), "{screen}");
    assert!(screen.contains('●'), "the ball on its path:\n{screen}");
    // End puts it where the path ends (past the court bounce), and the contact's cursor never moved.
    let screen = text(&drive(
        &mut app,
        160,
        48,
        vec![char(' '), key(KeyCode::End)],
    ));
    let end = shot::play(&params, true)
        .unwrap()
        .trajectory
        .last()
        .unwrap()[0];
    assert_eq!(app.flight, end);
    assert!(screen.contains(&format!("t {end:.2} s")), "{screen}");
    assert_eq!(app.cursor, 0.0);
}
