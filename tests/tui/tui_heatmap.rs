//! The heatmap view through the real event loop: it fills in from the worker thread while keys are still
//! answered, the loop wakes only while rows are due, and it draws with and without colour.

use std::io;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::style::Color;
use ratatui::symbols::Marker;
use snapback::model::{Params, solve};
use snapback::tui::grid::{self, MASSES, STIFFNESSES};
use snapback::tui::heatmap;
use snapback::tui::theme::Theme;
use snapback::tui::{App, EventSource, Input, View, run};

use crate::support::screen;
use screen::text;

fn key(code: KeyCode) -> Input {
    Input::Event(Event::Key(KeyEvent::new(code, KeyModifiers::NONE)))
}

/// Scripted keys first; then, whenever the loop asks for a frame, real time passes and a tick comes; when
/// it asks to wait for an event, the script ends (the explorer would sleep).
struct RealTime {
    keys: Vec<Input>,
    ticks: usize,
    started: Instant,
}

impl EventSource for RealTime {
    fn next_input(&mut self, frame: Option<Duration>) -> io::Result<Option<Input>> {
        if !self.keys.is_empty() {
            return Ok(Some(self.keys.remove(0)));
        }
        let Some(frame) = frame else {
            return Ok(None);
        };
        assert!(
            self.started.elapsed() < Duration::from_secs(120),
            "the heatmap never finished"
        );
        std::thread::sleep(frame);
        self.ticks += 1;
        Ok(Some(Input::Tick(frame)))
    }
}

fn fill(
    theme: Theme,
    width: u16,
    height: u16,
    keys: Vec<Input>,
) -> (App, Terminal<TestBackend>, usize, usize) {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    let mut app = App::new(Params::default(), theme).unwrap();
    let mut events = RealTime {
        keys,
        ticks: 0,
        started: Instant::now(),
    };
    run(&mut terminal, &mut app, &mut events).unwrap();
    let frames = terminal.get_frame().count();
    (app, terminal, frames, events.ticks)
}

#[test]
fn the_map_fills_in_off_the_ui_thread_and_the_loop_then_sleeps() {
    let tab = key(KeyCode::Tab);
    // Into the heatmap view, then a key while it computes: the key is answered at once.
    let keys = vec![tab.clone(), tab, key(KeyCode::Char('j'))];
    let (app, terminal, frames, ticks) = fill(Theme::default(), 160, 48, keys);
    assert_eq!(app.view, View::Heatmap);
    assert_eq!(app.selected, 1, "the key was taken while the map computed");
    // Complete, for the current parameters, and the loop stopped asking for ticks (it would now sleep).
    assert!(!app.heatmap.pending());
    assert_eq!(app.heatmap.done(), STIFFNESSES);
    assert!(ticks >= 1);
    assert!(frames >= 4, "{frames}");
    let row = heatmap::compute_row(&app.params, 7, &|| false).unwrap();
    assert_eq!(app.heatmap.rows[7].as_ref().unwrap(), &row);
    // The best cell is the largest omega2, and solving it again agrees.
    let (i, j, best) = app.heatmap.best().unwrap();
    let mut p = app.params;
    p.cart_mass = grid::mass(i);
    p.stiffness = grid::stiffness(j);
    assert_eq!(solve(&p).unwrap().outcome.omega2, best);
    // The peak refined from it is at least as high, near it, and solving there agrees; the screen
    // gives the peak, not the cell.
    let peak = app.heatmap.peak.expect("the refined peak");
    assert!(peak.omega2 >= best, "{} < {best}", peak.omega2);
    assert!((peak.mass / p.cart_mass).ln().abs() < 0.3);
    assert!((peak.stiffness / p.stiffness).ln().abs() < 0.3);
    p.cart_mass = peak.mass;
    p.stiffness = peak.stiffness;
    assert_eq!(solve(&p).unwrap().outcome.omega2, peak.omega2);
    let screen = text(&terminal);
    assert!(
        screen.contains(&format!("* best {:.1}", peak.omega2)),
        "{screen}"
    );
    assert!(
        screen.contains("+ now 160.8 (M 10 g, k 15 kN/m)"),
        "{screen}"
    );
    assert!(
        screen.contains("0.1 g") && screen.contains("100 kN/m"),
        "{screen}"
    );
    assert!(!screen.contains("computing"), "{screen}");
    let cells = screen.matches('▀').count();
    assert!(cells > MASSES * 10, "{cells}");
}

#[test]
fn a_new_parameter_restarts_the_map_and_no_rows_of_the_old_one_remain() {
    let tab = key(KeyCode::Tab);
    // Change the spin (two rows down) while the map of the old spin is computing.
    let keys = vec![
        tab.clone(),
        tab,
        key(KeyCode::Down),
        key(KeyCode::Down),
        key(KeyCode::Right),
    ];
    let (app, _, _, _) = fill(Theme::default(), 120, 40, keys);
    assert_eq!(app.params.spin, -90.0);
    assert_eq!(app.heatmap.generation, 2);
    for j in [0, STIFFNESSES / 2, STIFFNESSES - 1] {
        assert_eq!(
            app.heatmap.rows[j].as_ref().unwrap(),
            &heatmap::compute_row(&app.params, j, &|| false).unwrap()
        );
    }
    // Stepping the cart mass moves the mark but needs no new map.
    let mut app = app;
    let generation = app.heatmap.generation;
    // From the spin (row 2) to the cart mass (row 11, after the ball's stiffness and damping).
    for _ in 0..9 {
        app.update(snapback::tui::Action::SelectNext);
    }
    app.update(snapback::tui::Action::Step {
        up: true,
        coarse: false,
    });
    assert_eq!(app.heatmap.generation, generation);
    assert!(!app.heatmap.pending());
}

#[test]
fn without_colour_the_map_is_drawn_in_shades() {
    let theme = Theme {
        color: false,
        marker: Marker::Braille,
        ascii: false,
        light: false,
    };
    let tab = key(KeyCode::Tab);
    let (_, terminal, _, _) = fill(theme, 80, 24, vec![tab.clone(), tab]);
    let screen = text(&terminal);
    let shades = screen.chars().filter(|c| "░▒▓█".contains(*c)).count();
    assert!(shades > 100, "{screen}");
    assert!(!screen.contains('▀'));
    let colours: Vec<Color> = terminal
        .backend()
        .buffer()
        .content()
        .iter()
        .flat_map(|c| [c.fg, c.bg])
        .collect();
    assert!(colours.iter().all(|c| *c == Color::Reset));
    assert!(screen.contains("* best"), "{screen}");
}
