//! Keystroke to frame: one key press (stepping the angle), the re-solve, the Fig. 2 sweep over 180 angles
//! and a full frame drawn into ratatui's TestBackend at 160 x 48. Target: a median of at most 5 ms.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use snapback::model::Params;
use snapback::tui::ui::theme::Theme;
use snapback::tui::{App, View, draw, keys};

fn keystroke_to_frame(c: &mut Criterion) {
    let right = KeyEvent::new(KeyCode::Right, KeyModifiers::NONE);
    let left = KeyEvent::new(KeyCode::Left, KeyModifiers::NONE);
    for view in [View::Contact, View::Sweep] {
        let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
        let mut app = App::new(Params::default(), Theme::default()).unwrap();
        app.view = view;
        let mut up = true;
        c.bench_function(&format!("frame/{}", view_name(view)), |b| {
            b.iter(|| {
                // Alternate Right and Left so every press changes the angle (60 <-> 61 degrees).
                let key = if up { &right } else { &left };
                up = !up;
                let action = keys::action_for(black_box(key), &app.mode).unwrap();
                app.update(action);
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
    }
}

criterion_group!(benches, keystroke_to_frame);
criterion_main!(benches);
