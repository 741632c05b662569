//! Keystroke to frame: one key press (stepping the incident spin, the worst case: the re-solve and both
//! Fig. 2 sweeps over 180 angles, for the current and the comparison spin), the ball's travel integrals and
//! a full frame, schematic included, drawn into ratatui's TestBackend at 160 x 48. Target: a median of at
//! most 5 ms. Also one frame of playback: a clock tick that moves the time
//! cursor, and the frame; and a key press in the shot view (the racquet speed: the strings' bounce and
//! the shot, its flight and court bounce, both solved again) to its frame.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use snapback::model::Params;
use snapback::model::params::{PARAMS, ParamId};
use snapback::tui::theme::Theme;
use snapback::tui::{Action, App, View, draw, keys, playback};

fn keystroke_to_frame(c: &mut Criterion) {
    let right = KeyEvent::new(KeyCode::Right, KeyModifiers::NONE);
    let left = KeyEvent::new(KeyCode::Left, KeyModifiers::NONE);
    for view in [View::Contact, View::Sweep] {
        let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
        let mut app = App::new(Params::default(), Theme::default()).unwrap();
        app.view = view;
        app.settle(Duration::from_secs(60));
        // Select the incident spin: stepping it changes every curve (the angle would leave the sweeps be).
        app.update(Action::SelectNext);
        app.update(Action::SelectNext);
        let mut up = true;
        c.bench_function(&format!("frame/{}", view_name(view)), |b| {
            b.iter(|| {
                // Alternate Right and Left so every press changes the spin (-100 <-> -90 rad/s).
                let key = if up { &right } else { &left };
                up = !up;
                let action = keys::action_for(black_box(key), &app.mode).unwrap();
                app.update(action);
                // The worker's answer (cached after the first two presses: the spin alternates).
                app.settle(Duration::from_secs(60));
                draw(&mut terminal, &app).unwrap();
                black_box(terminal.backend().buffer().area);
            })
        });
    }
}

fn view_name(view: View) -> &'static str {
    match view {
        View::Contact => "contact",
        View::Sweep => "sweep",
        View::Heatmap => "heatmap",
        View::Shot => "shot",
    }
}

fn playback_frame(c: &mut Criterion) {
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    let mut app = App::new(Params::default(), Theme::default()).unwrap();
    app.settle(Duration::from_secs(60));
    c.bench_function("frame/playback", |b| {
        b.iter(|| {
            if !app.playing {
                app.update(Action::TogglePlay);
            }
            app.advance(black_box(playback::FRAME * 4));
            draw(&mut terminal, &app).unwrap();
            black_box(terminal.backend().buffer().area);
        })
    });
    assert!(app.cursor > 0.0);
}

fn shot_keystroke_to_frame(c: &mut Criterion) {
    let right = KeyEvent::new(KeyCode::Right, KeyModifiers::NONE);
    let left = KeyEvent::new(KeyCode::Left, KeyModifiers::NONE);
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    let params = snapback::config::preset("topspin-forehand")
        .unwrap()
        .apply(Params::default());
    let mut app = App::new(params, Theme::default()).unwrap();
    while app.view != View::Shot {
        app.update(Action::NextView);
    }
    app.selected = PARAMS
        .iter()
        .position(|s| s.id == ParamId::RacquetSpeed)
        .unwrap();
    app.settle(Duration::from_secs(60));
    let mut up = true;
    c.bench_function("frame/shot", |b| {
        b.iter(|| {
            // Alternate Right and Left: 20 <-> 21 m/s, cached after the first two presses.
            let key = if up { &right } else { &left };
            up = !up;
            let action = keys::action_for(black_box(key), &app.mode).unwrap();
            app.update(action);
            app.settle(Duration::from_secs(60));
            draw(&mut terminal, &app).unwrap();
            black_box(terminal.backend().buffer().area);
        })
    });
}

criterion_group!(
    benches,
    keystroke_to_frame,
    playback_frame,
    shot_keystroke_to_frame
);
criterion_main!(benches);
