//! Slow motion in the explorer: the time cursor and its readouts, the jumps to phase transitions, the
//! schematic's ball and rotation mark, playback driven by scripted clock ticks, and the frames drawn.

use std::collections::VecDeque;
use std::io;
use std::time::Duration;

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::symbols::Marker;
use snapback::model::{Bounce, ParamId, Params, Sample, solve};
use snapback::tui::theme::Theme;
use snapback::tui::ui::schematic::Scene;
use snapback::tui::ui::{self, time_at};
use snapback::tui::{Action, App, EventSource, Input, Scripted, playback, run};

use crate::support::screen;
use screen::{line_with, text};

fn key(c: char) -> Input {
    Input::Event(Event::Key(KeyEvent::new(
        KeyCode::Char(c),
        KeyModifiers::NONE,
    )))
}

fn code(code: KeyCode) -> Input {
    Input::Event(Event::Key(KeyEvent::new(code, KeyModifiers::NONE)))
}

fn tick(ms: u64) -> Input {
    Input::Tick(Duration::from_millis(ms))
}

/// The explorer after `inputs` on a `width` x `height` screen, and how many frames were drawn.
fn explore_inputs(
    params: Params,
    width: u16,
    height: u16,
    inputs: Vec<Input>,
) -> (App, Terminal<TestBackend>, usize) {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    let mut app = solved_app(params);
    run(&mut terminal, &mut app, &mut Scripted::from(inputs)).unwrap();
    let frames = terminal.get_frame().count();
    (app, terminal, frames)
}

fn explore(inputs: Vec<Input>) -> (App, String) {
    let (app, terminal, _) = explore_inputs(Params::default(), 160, 48, inputs);
    (app, text(&terminal))
}

/// An explorer on `params` once its bounce is solved.
fn solved_app(params: Params) -> App {
    let mut app = App::new(params, Theme::default()).unwrap();
    assert!(
        app.settle(Duration::from_secs(120)),
        "the bounce never came"
    );
    app
}

fn default_bounce() -> Bounce {
    solve(&Params::default()).unwrap()
}

/// What the charts' titles should say at a sample (formatted as the explorer does, without "-0.0").
fn fixed(value: f64, decimals: usize) -> String {
    ui::fixed(value, decimals)
}

fn assert_readouts(screen: &str, s: &Sample, mu: f64) {
    let force = line_with(screen, "friction force F (N)");
    assert!(
        force.contains(&format!("F {} N", fixed(s.friction, 1))),
        "{force}"
    );
    assert!(
        force.contains(&format!("μN {} N", fixed(mu * s.normal, 1))),
        "{force}"
    );
    let cart = line_with(screen, "cart displacement X (mm)");
    assert!(
        cart.contains(&format!("X {} mm", fixed(s.x * 1e3, 3))),
        "{cart}"
    );
    assert!(cart.contains(&format!("V {} m/s", fixed(s.v, 3))), "{cart}");
    let spin = line_with(screen, "ball spin ω (rad/s)");
    assert!(
        spin.contains(&format!("ω {} rad/s", fixed(s.omega, 1))),
        "{spin}"
    );
    assert!(
        spin.contains(&format!("slip {} m/s", fixed(s.slip, 3))),
        "{spin}"
    );
}

#[test]
fn the_cursor_readouts_are_the_core_values_at_t() {
    let bounce = default_bounce();
    // `]` 26 times: 1.30 ms, in the first slide; 60 times: 3.00 ms, gripping.
    for (presses, phase) in [(0, "slide"), (26, "slide"), (60, "grip"), (95, "slide")] {
        let (app, screen) = explore(vec![key(']'); presses]);
        let t = app.cursor;
        assert!((t - presses as f64 * 0.05e-3).abs() < 1e-15, "{t}");
        let sample = bounce.sample_at(t);
        assert_eq!(app.cursor_sample(), Some(sample));
        assert_readouts(&screen, &sample, bounce.setup.mu);
        let cursor_row = screen.lines().next().unwrap();
        assert!(
            cursor_row.contains(&format!("t {:.3} ms · {phase}", t * 1e3)),
            "{cursor_row}"
        );
    }
}

#[test]
fn the_readouts_equal_the_core_series_at_its_times() {
    let bounce = default_bounce();
    let mut app = solved_app(Params::default());
    let series = bounce.series(60);
    for (i, s) in series.iter().enumerate() {
        app.update(Action::CursorTo(s.t));
        assert_eq!(app.cursor, s.t);
        let at_transition = series.get(i + 1).is_some_and(|n| n.t == s.t);
        if at_transition {
            // The series' first side of a transition is the end of the phase before: the readout shows it
            // as the "before" of the jump, and the phase that begins there as the value.
            assert_eq!(
                app.solved.as_ref().unwrap().sample_before(app.cursor),
                Some(*s)
            );
            assert_eq!(app.cursor_sample(), Some(series[i + 1]));
        } else {
            assert_eq!(app.cursor_sample(), Some(*s), "at {}", s.t);
        }
    }
}

#[test]
fn transition_jumps_land_exactly_on_the_phase_boundaries() {
    let bounce = default_bounce();
    let phases = &bounce.phases;
    assert_eq!(phases.len(), 3);
    let duration = bounce.setup.duration;
    let mut app = solved_app(Params::default());
    let forward = Action::CursorPhase { forward: true };
    let back = Action::CursorPhase { forward: false };
    for expected in [phases[1].start, phases[2].start, duration, duration] {
        app.update(forward);
        assert_eq!(app.cursor, expected);
    }
    assert_eq!(phases[1].start, phases[0].end);
    for expected in [phases[2].start, phases[1].start, 0.0, 0.0] {
        app.update(back);
        assert_eq!(app.cursor, expected);
    }
    // From between grid steps: `}` from 2 ms goes to the second transition, `{` to the first.
    app.update(Action::CursorTo(2e-3));
    app.update(forward);
    assert_eq!(app.cursor, phases[2].start);
    app.update(Action::CursorTo(2e-3));
    app.update(back);
    assert_eq!(app.cursor, phases[1].start);
    // Home and End.
    app.update(Action::CursorEnd);
    assert_eq!(app.cursor, duration);
    app.update(Action::CursorHome);
    assert_eq!(app.cursor, 0.0);
}

#[test]
fn at_a_transition_the_readout_shows_the_jump_and_the_new_phase() {
    let bounce = default_bounce();
    let t = bounce.phases[1].start;
    let (app, screen) = explore(vec![key('}')]);
    assert_eq!(app.cursor, t);
    let before = bounce.sample_in(0, t);
    let after = bounce.sample_at(t);
    assert_eq!(after.phase, 1);
    assert_ne!(before.friction, after.friction);
    let force = line_with(&screen, "friction force F (N)");
    assert!(
        force.contains(&format!(
            "F {}→{} N",
            fixed(before.friction, 1),
            fixed(after.friction, 1)
        )),
        "{force}"
    );
    assert!(
        screen.lines().next().unwrap().contains("slide → grip"),
        "{screen}"
    );
    // Every other readout is that of the phase that begins there.
    let spin = line_with(&screen, "ball spin ω (rad/s)");
    assert!(spin.contains(&format!("ω {} rad/s", fixed(after.omega, 1))));
}

/// The trapezoid rule over a very fine even grid of the exact solution.
fn integral(bounce: &Bounce, t: f64, value: fn(&Sample) -> f64) -> f64 {
    let n = 100_000;
    let h = t / n as f64;
    (0..n)
        .map(|i| {
            let a = bounce.sample_at(h * i as f64);
            let b = bounce.sample_at(h * (i + 1) as f64);
            0.5 * h * (value(&a) + value(&b))
        })
        .sum()
}

#[test]
fn the_rotation_mark_turns_by_the_integral_of_omega() {
    // The default bounce, and one with a fast topspin whose mark goes more than once round.
    let fast = Params::default().with(ParamId::Spin, 3000.0).unwrap();
    for params in [Params::default(), fast] {
        let bounce = solve(&params).unwrap();
        let mut app = solved_app(params);
        let r = bounce.setup.r * 1e3;
        for t in [0.0, 0.7e-3, 1.9e-3, 3.3e-3, bounce.setup.duration] {
            app.update(Action::CursorTo(t));
            let scene = Scene::at(&app, app.solved.as_ref().unwrap());
            let angle = integral(&bounce, t, |s| s.omega);
            assert!(
                (scene.angle - angle).abs() < 1e-7,
                "{} {angle}",
                scene.angle
            );
            // The mark: clockwise from the top by that angle, on the rim.
            let (cx, cy) = scene.centre;
            let (dx, dy) = (scene.mark.0 - cx, scene.mark.1 - cy);
            assert!((dx.hypot(dy) - r).abs() < 1e-9);
            assert!((dx - r * angle.sin()).abs() < 1e-6 && (dy - r * angle.cos()).abs() < 1e-6);
            // The ball travels along the surface by the integral of v_x, at the scale of its radius (mm).
            let travel = integral(&bounce, t, |s| s.vx) * 1e3;
            assert!((cx - travel).abs() < 1e-6, "{cx} {travel}");
            assert_eq!(cy, r);
        }
        let turned = Scene::at(&app, app.solved.as_ref().unwrap()).angle;
        if params.spin == 3000.0 {
            assert!(turned > 2.0 * std::f64::consts::PI, "{turned}");
        }
    }
}

#[test]
fn the_cart_and_the_arrow_follow_x_and_f() {
    let bounce = default_bounce();
    let mut app = solved_app(Params::default());
    let rest = Scene::at(&app, app.solved.as_ref().unwrap());
    assert!(rest.arrow.is_none() || rest.force.abs() < 1.0);
    for t in [1.0e-3, 2.5e-3, 4.0e-3] {
        app.update(Action::CursorTo(t));
        let s = bounce.sample_at(t);
        let scene = Scene::at(&app, app.solved.as_ref().unwrap());
        // The cart moves by X times the written scale.
        let moved = scene.cart.0 - rest.cart.0;
        assert!((moved - scene.x_scale * s.x * 1e3).abs() < 1e-9);
        // The arrow points backward (left) for a positive F, one radius per newtons_per_radius.
        let ((tx, _), (hx, _)) = scene.arrow.expect("an arrow");
        assert_eq!(tx, scene.centre.0);
        let expected = -s.friction / scene.newtons_per_radius * scene.radius;
        assert!((hx - tx - expected).abs() < 1e-9);
        assert_eq!(scene.kind, s.kind);
    }
}

#[test]
fn a_chain_draws_its_other_masses_at_rest_and_the_first_moving_with_x() {
    let params = Params {
        chain: 6.0,
        ..Params::default()
    };
    let bounce = solve(&params).unwrap();
    let mut app = solved_app(params);
    let rest = Scene::at(&app, app.solved.as_ref().unwrap());
    // Masses 2 to 6, from the cart towards the wall, equal, apart, between the wall and the cart.
    assert_eq!(rest.links.len(), 5);
    let width = rest.links[0].1 - rest.links[0].0;
    assert!(width > 0.0);
    let mut right = rest.cart.0;
    for &(left, r) in &rest.links {
        assert!((r - left - width).abs() < 1e-9);
        assert!(r < right, "{:?}", rest.links);
        right = left;
    }
    assert!(rest.wall < right);
    // The chain and the ball fit in the picture.
    assert!(rest.x_bounds[0] < rest.wall && rest.cart.1 < rest.x_bounds[1]);
    let mut times: Vec<f64> = app
        .solved
        .as_ref()
        .unwrap()
        .series
        .iter()
        .map(|s| s.t)
        .collect();
    times.extend([1.0e-3, 2.5e-3, 4.0e-3]);
    for t in times {
        app.update(Action::CursorTo(t));
        let scene = Scene::at(&app, app.solved.as_ref().unwrap());
        // Only the first mass moves, by its X times the written scale (the core gives no other mass's
        // displacement); the others and the wall stay put.
        let moved = scene.cart.0 - rest.cart.0;
        assert!((moved - scene.x_scale * bounce.sample_at(t).x * 1e3).abs() < 1e-9);
        assert_eq!(scene.links, rest.links);
        assert_eq!(scene.wall, rest.wall);
        // The spring between the first and second masses never turns inside out.
        assert!(scene.cart.0 > scene.links[0].1, "at {t}");
    }
    // The single cart has no other masses.
    let single = solved_app(Params::default());
    assert!(
        Scene::at(&single, single.solved.as_ref().unwrap())
            .links
            .is_empty()
    );
}

#[test]
fn a_long_chain_still_draws_the_ball_at_a_readable_size() {
    // Sixteen masses, the most: the picture keeps the ball at least a fifth of its width.
    for n in [2.0, 16.0] {
        let params = Params {
            chain: n,
            ..Params::default()
        };
        let scene = {
            let app = solved_app(params);
            Scene::at(&app, app.solved.as_ref().unwrap())
        };
        assert_eq!(scene.links.len(), n as usize - 1);
        let width = scene.x_bounds[1] - scene.x_bounds[0];
        assert!(2.0 * scene.radius > 0.2 * width, "N {n}: {width}");
    }
    let (_, terminal, _) = explore_inputs(
        Params {
            chain: 16.0,
            ..Params::default()
        },
        160,
        48,
        vec![key('}')],
    );
    let screen = text(&terminal);
    assert!(screen.contains(" mass 1: X ×"), "{screen}");
}

#[test]
fn playback_advances_time_at_the_speed_and_stops_at_t() {
    // 1 s of wall time at the default 1 ms / 2 s is 0.5 ms of bounce.
    let (app, _) = explore(vec![key(' '), tick(1000)]);
    assert!(app.playing);
    assert!((app.cursor - 0.5e-3).abs() < 1e-15, "{}", app.cursor);
    // `+` doubles the speed.
    let (app, _) = explore(vec![key('+'), key(' '), tick(1000)]);
    assert!((app.cursor - 1e-3).abs() < 1e-15);
    let (app, _) = explore(vec![key('-'), key(' '), tick(1000)]);
    assert!((app.cursor - 0.25e-3).abs() < 1e-15);
    // Frames of 33 ms until past the end: it stops exactly at T and pauses.
    let mut inputs = vec![key(' ')];
    inputs.extend(vec![tick(33); 400]);
    let (app, terminal, frames) = explore_inputs(Params::default(), 160, 48, inputs);
    let duration = app.solved.as_ref().unwrap().bounce.setup.duration;
    assert_eq!(app.cursor, duration);
    assert!(!app.playing);
    // 10 s of ticks take 5 ms; the ticks after the end find it paused and are not drawn.
    let needed = (duration / (0.033 * playback::Speed::DEFAULT_RATE)).ceil() as usize;
    assert_eq!(frames, 1 + 1 + needed);
    assert!(text(&terminal).contains("t 5.000 ms"));
    // Space at the end plays again from the start.
    let mut inputs = vec![code(KeyCode::End), key(' '), tick(100)];
    inputs.push(tick(100));
    let (app, _) = explore(inputs);
    assert!(app.playing);
    assert!((app.cursor - 0.1e-3).abs() < 1e-15);
}

#[test]
fn no_frames_are_drawn_while_paused() {
    // Paused from the start: time passing draws nothing; only the first frame is drawn.
    let (_, _, frames) = explore_inputs(Params::default(), 160, 48, vec![tick(33); 50]);
    assert_eq!(frames, 1);
    // Play for three frames, pause, then time passes: one frame per tick while playing, none after.
    let mut inputs = vec![key(' '), tick(33), tick(33), tick(33), key(' ')];
    inputs.extend(vec![tick(33); 50]);
    let (app, _, frames) = explore_inputs(Params::default(), 160, 48, inputs);
    assert!(!app.playing);
    assert_eq!(frames, 1 + 1 + 3 + 1);
    // Keys that do nothing draw nothing either.
    let (_, _, frames) = explore_inputs(Params::default(), 80, 24, vec![key('z'), key('[')]);
    assert_eq!(frames, 1 + 1);
}

/// A script that records what the loop asked for each time: a frame interval, or to wait for an event.
struct Recording {
    script: Scripted,
    asked: Vec<Option<Duration>>,
}

impl EventSource for Recording {
    fn next_input(&mut self, frame: Option<Duration>) -> io::Result<Option<Input>> {
        self.asked.push(frame);
        self.script.next_input(frame)
    }
}

#[test]
fn the_loop_waits_for_events_while_paused_and_ticks_while_playing() {
    let mut terminal = Terminal::new(TestBackend::new(80, 24)).unwrap();
    let mut app = solved_app(Params::default());
    let mut events = Recording {
        script: Scripted(VecDeque::from(vec![
            key(']'),
            key(' '),
            tick(33),
            key(' '),
            key(']'),
        ])),
        asked: Vec::new(),
    };
    run(&mut terminal, &mut app, &mut events).unwrap();
    let frame = Some(playback::FRAME);
    assert_eq!(
        events.asked,
        vec![None, None, frame, frame, None, None],
        "paused, the loop asks for no timer"
    );
    // Smooth enough to follow: at least 10 frames a second by default.
    assert!(playback::FRAME <= Duration::from_millis(100));
}

#[test]
fn changing_a_parameter_while_playing_keeps_playing_the_new_bounce() {
    let (app, _) = explore(vec![key(' '), tick(1000), code(KeyCode::Right), tick(1000)]);
    assert!(app.playing);
    assert_eq!(app.params.angle_deg, 61.0);
    assert!((app.cursor - 1e-3).abs() < 1e-15);
    assert_eq!(
        app.cursor_sample(),
        Some(app.solved.as_ref().unwrap().bounce.sample_at(app.cursor))
    );
    // A new contact time keeps the cursor's fraction of it: 2.5 ms of 5 is 3 ms of 6.
    let mut app = solved_app(Params::default());
    app.update(Action::CursorTo(2.5e-3));
    for _ in 0..4 {
        app.update(Action::SelectNext);
    }
    assert_eq!(app.selected_spec().id, ParamId::Duration);
    app.update(Action::StartEdit);
    for c in "6ms".chars() {
        app.update(Action::EditInsert(c));
    }
    app.update(Action::EditSubmit);
    assert!(app.settle(Duration::from_secs(120)));
    assert_eq!(app.params.duration, 6e-3);
    assert!((app.cursor - 3e-3).abs() < 1e-15);
}

#[test]
fn a_click_on_a_chart_puts_the_cursor_there() {
    let (width, height) = (160, 48);
    let screen = Rect::new(0, 0, width, height);
    let app = solved_app(Params::default());
    // A row inside the spin chart; columns from the left to the right of the plot.
    let row = 40;
    let columns: Vec<u16> = (0..width)
        .filter(|&c| time_at(screen, &app, c, row).is_some())
        .collect();
    assert!(columns.len() > 100, "{}", columns.len());
    let (first, last) = (columns[0], *columns.last().unwrap());
    assert_eq!(time_at(screen, &app, first, row), Some(0.0));
    assert_eq!(time_at(screen, &app, last, row), Some(app.duration()));
    for column in [first + 7, first + (last - first) / 2, last - 3] {
        let click = Input::Event(Event::Mouse(MouseEvent {
            kind: MouseEventKind::Down(MouseButton::Left),
            column,
            row,
            modifiers: KeyModifiers::NONE,
        }));
        let (app, terminal, frames) = explore_inputs(Params::default(), width, height, vec![click]);
        assert_eq!(frames, 2);
        assert_eq!(Some(app.cursor), time_at(screen, &app, column, row));
        // The cursor's line is drawn in the clicked column, on every chart.
        let buffer = terminal.backend().buffer();
        let magenta: Vec<u16> = (0..width)
            .filter(|&x| buffer[(x, row)].fg == Color::Magenta)
            .collect();
        assert_eq!(magenta, vec![column], "row {row}");
    }
    // Outside the plots a click does nothing, and draws nothing.
    let click = Input::Event(Event::Mouse(MouseEvent {
        kind: MouseEventKind::Down(MouseButton::Left),
        column: 5,
        row: 5,
        modifiers: KeyModifiers::NONE,
    }));
    let (app, _, frames) = explore_inputs(Params::default(), width, height, vec![click]);
    assert_eq!(app.cursor, 0.0);
    assert_eq!(frames, 1);
}

#[test]
fn the_schematic_shows_when_there_is_room_and_says_so_when_not() {
    let (_, big, _) = explore_inputs(Params::default(), 160, 48, vec![key(']')]);
    let big = text(&big);
    assert!(big.contains("t 0.050 ms · slide"), "{big}");
    assert!(big.contains("X ×"), "{big}");
    assert!(big.contains("arrow F:"), "{big}");
    assert!(!big.contains("schematic hidden"));
    assert!(ui::schematic_shown(
        Rect::new(0, 0, 160, 48),
        &solved_app(Params::default())
    ));
    let (_, small, _) = explore_inputs(Params::default(), 80, 24, vec![key(']')]);
    let small = text(&small);
    let status = small.lines().last().unwrap();
    assert!(status.starts_with("schematic hidden"), "{status}");
    // The essentials still fit beside the note.
    for hint in ["␣ play", "? help", "q quit"] {
        assert!(status.contains(hint), "{status}");
    }
    // The cursor and its readouts work at 80 x 24 too.
    assert!(small.contains("t 0.050 ms · slide"), "{small}");
    assert!(small.contains("F (N)"), "{small}");
}

#[test]
fn every_marker_draws_the_cursor_and_the_schematic() {
    for marker in [Marker::Braille, Marker::Dot, Marker::Block] {
        let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
        let theme = Theme {
            color: true,
            marker,
            ascii: false,
            light: false,
        };
        let mut app = App::new(Params::default(), theme).unwrap();
        let inputs = vec![key('}'), key(']'), key(' '), tick(500)];
        run(&mut terminal, &mut app, &mut Scripted::from(inputs)).unwrap();
        let buffer = terminal.backend().buffer();
        let cursor_cells = buffer
            .content()
            .iter()
            .filter(|c| c.fg == Color::Magenta)
            .count();
        // The cursor's line down three charts and the mark on the ball.
        assert!(cursor_cells > 30, "{marker:?}: {cursor_cells}");
        let screen = text(&terminal);
        assert!(screen.contains("▶ playing"), "{screen}");
    }
}
