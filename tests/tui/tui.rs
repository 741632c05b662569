//! The explorer on ratatui's TestBackend, driven by scripted key events through the real event loop.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::style::Color;
use ratatui::symbols::Marker;
use snapback::model::params::{BOUNCE_PARAMS as PARAMS, Group, spec};
use snapback::model::{ParamId, Params, solve};
use snapback::tui::keys::{self, keys_label};
use snapback::tui::theme::Theme;
use snapback::tui::{App, Mode, Scripted, View, run};

use crate::support::screen;
use screen::{line_with, text};

fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

fn shift(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::SHIFT))
}

fn ctrl(c: char) -> Event {
    Event::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::CONTROL))
}

/// Typing `text` character by character.
fn typed(text: &str) -> Vec<Event> {
    text.chars().map(|c| key(KeyCode::Char(c))).collect()
}

/// The explorer after `events` on a `width` x `height` screen: the app and the screen as text.
fn explore_with(
    theme: Theme,
    width: u16,
    height: u16,
    events: Vec<Event>,
) -> (App, Terminal<TestBackend>) {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    let mut app = App::new(Params::default(), theme).unwrap();
    run(&mut terminal, &mut app, &mut Scripted::from(events)).unwrap();
    (app, terminal)
}

fn explore(width: u16, height: u16, events: Vec<Event>) -> (App, String) {
    let (app, terminal) = explore_with(Theme::default(), width, height, events);
    (app, text(&terminal))
}

const SIZES: [(u16, u16); 2] = [(80, 24), (160, 48)];

#[test]
fn opens_on_fig3c_with_the_angle_selected() {
    let omega2 = format!(
        "{:.1} rad/s",
        solve(&Params::default()).unwrap().outcome.omega2
    );
    for (w, h) in SIZES {
        let (app, screen) = explore(w, h, vec![]);
        assert_eq!(app.selected_spec().id, ParamId::Angle);
        assert!(
            line_with(&screen, "incidence angle").contains("▸θ1"),
            "{screen}"
        );
        assert!(line_with(&screen, "ω2 ").contains(&omega2), "{screen}");
        // The timeline wraps where the outcome panel's width says.
        let pieces: &[&str] = if w >= 120 {
            &["slide 0-1.32, grip 1.32-4.39"]
        } else {
            &["slide 0-1.32, grip", "1.32-4.39, slide 4.39-5.00"]
        };
        for piece in pieces {
            assert!(screen.contains(piece), "{piece:?} in\n{screen}");
        }
        // Narrow charts are titled by their symbols, to leave room for the time cursor's readouts.
        let titles = if w >= 120 {
            [
                "friction force F (N)",
                "cart displacement X (mm)",
                "ball spin ω (rad/s)",
                "t (ms)",
            ]
        } else {
            [" F (N) ┄ ±μN ", " X (mm) ", " ω (rad/s) ", "t (ms)"]
        };
        for title in titles {
            assert!(
                screen.contains(title),
                "{title} missing at {w}x{h}:\n{screen}"
            );
        }
        // A short screen scrolls the panel (marked on its border); a tall one lists every parameter.
        let scrolls = screen.contains("▼ more");
        assert_eq!(scrolls, h < 48, "{screen}");
        for spec in PARAMS {
            let shown = spec.show(spec.default).to_string();
            if scrolls && spec.group != Group::Ball && !screen.contains(spec.label) {
                continue;
            }
            assert!(
                screen.contains(&shown),
                "{shown} missing at {w}x{h}:\n{screen}"
            );
        }
    }
}

#[test]
fn right_on_the_angle_shows_omega2_for_61_degrees() {
    let at61 = Params::default().with(ParamId::Angle, 61.0).unwrap();
    let outcome = solve(&at61).unwrap().outcome;
    let omega2 = format!("{:.1} rad/s", outcome.omega2);
    let vx2 = format!("{:.3} m/s", outcome.vx2);
    for (w, h) in SIZES {
        for right in [key(KeyCode::Right), key(KeyCode::Char('l'))] {
            let (app, screen) = explore(w, h, vec![right]);
            assert_eq!(app.params, at61);
            assert!(
                line_with(&screen, "incidence angle").contains("61.0 deg"),
                "{screen}"
            );
            assert!(line_with(&screen, "ω2 ").contains(&omega2), "{screen}");
            assert!(line_with(&screen, "v_x2").contains(&vx2), "{screen}");
        }
    }
}

#[test]
fn coarse_steps_selection_and_resets() {
    let (app, screen) = explore(160, 48, vec![shift(KeyCode::Left), key(KeyCode::Char('H'))]);
    assert_eq!(app.params.angle_deg, 40.0);
    assert!(screen.contains("40.0 deg"));

    // Down to the cart mass (index 11, after the ball's stiffness and damping), halve it, then reset
    // it and everything.
    let mut events = vec![key(KeyCode::Char('j')); 11];
    events.push(shift(KeyCode::Left));
    let (app, screen) = explore(160, 48, events.clone());
    assert_eq!(app.selected_spec().id, ParamId::CartMass);
    assert_eq!(app.params.cart_mass, 0.005);
    let expected = solve(&app.params).unwrap().outcome.omega2;
    assert!(
        line_with(&screen, "cart mass").contains("5.00 g•"),
        "{screen}"
    );
    assert!(screen.contains(&format!("{expected:.1} rad/s")));

    events.push(key(KeyCode::Char('r')));
    let (app, _) = explore(160, 48, events.clone());
    assert_eq!(app.params, Params::default());

    events.extend([
        key(KeyCode::Up),
        key(KeyCode::Right),
        key(KeyCode::Char('R')),
    ]);
    let (app, _) = explore(160, 48, events);
    assert_eq!(app.params, Params::default());
    assert_eq!(app.selected_spec().id, ParamId::BallDamping);
}

#[test]
fn a_typed_value_takes_units_like_the_command_line() {
    // Wraps round to the last parameter (the frame's normal mass), then up past the frame's mass, the
    // chain and string friction to the stiffness.
    let mut events = vec![key(KeyCode::Char('k')); 5];
    events.push(key(KeyCode::Enter));
    events.extend(typed("2.2kN/m"));
    events.push(key(KeyCode::Enter));
    let (app, screen) = explore(80, 24, events);
    assert_eq!(app.params.stiffness, 2200.0);
    assert!(
        line_with(&screen, "spring stiffness").contains("2.20 kN/m"),
        "{screen}"
    );
    let omega2 = solve(&app.params).unwrap().outcome.omega2;
    assert!(screen.contains(&format!("{omega2:.1} rad/s")), "{screen}");
}

#[test]
fn the_prompt_names_the_unit_of_a_bare_number() {
    let mut events = vec![key(KeyCode::Char('j')); 11];
    events.extend([key(KeyCode::Char('e'))]);
    events.extend(typed("12"));
    let (app, screen) = explore(80, 24, events);
    assert_eq!(app.mode, Mode::Editing("12".into()));
    let last = screen.lines().last().unwrap();
    assert!(
        last.starts_with("cart mass M [kg; or e.g. 10g]: 12"),
        "{last}"
    );
}

#[test]
fn a_bare_number_far_outside_the_usual_range_gets_the_command_lines_note() {
    let select = || vec![key(KeyCode::Char('j')); 11];
    let mut events = select();
    events.push(key(KeyCode::Char('e')));
    events.extend(typed("10"));
    events.push(key(KeyCode::Enter));
    let (app, screen) = explore(120, 40, events);
    assert_eq!(app.params.cart_mass, 10.0, "the value is taken as written");
    let message = app.message.as_ref().expect("a note").text.clone();
    assert_eq!(
        message,
        "note: cart mass 10 is read as 10 kg; write 10g for grams"
    );
    assert!(screen.contains(&message), "{screen}");
    // With its unit, no note.
    let mut events = select();
    events.push(key(KeyCode::Char('e')));
    events.extend(typed("10g"));
    events.push(key(KeyCode::Enter));
    let (app, _) = explore(120, 40, events);
    assert_eq!(app.params.cart_mass, 0.010);
    assert!(app.message.is_none(), "{:?}", app.message);
}

#[test]
fn a_rejected_edit_shows_why_and_keeps_the_value() {
    for (w, h) in SIZES {
        let mut events = vec![key(KeyCode::Enter)];
        events.extend(typed("95"));
        events.push(key(KeyCode::Enter));
        let (app, screen) = explore(w, h, events);
        assert_eq!(app.params, Params::default());
        assert_eq!(app.mode, Mode::Normal);
        let status = screen.lines().last().unwrap();
        assert!(
            status.starts_with("incidence angle θ1 must be in (0, 90] deg; got 95"),
            "{status}"
        );
        assert!(line_with(&screen, "incidence angle").contains("60.0 deg"));
    }
    // Not a number, and a unit of the wrong kind.
    for (text, reason) in [
        ("abc", "'abc' is not a number"),
        ("3kg", "unit 'kg' is a mass"),
    ] {
        let mut events = vec![key(KeyCode::Enter)];
        events.extend(typed(text));
        events.push(key(KeyCode::Enter));
        let (app, screen) = explore(160, 48, events);
        assert_eq!(app.params, Params::default());
        assert!(
            line_with(&screen, reason).starts_with("incidence angle θ1: "),
            "{screen}"
        );
    }
}

#[test]
fn a_value_the_solver_refuses_is_not_applied() {
    // A 1 mg cart on a 1 MN/m spring oscillates too fast to resolve.
    let mut events = vec![key(KeyCode::Char('k')); 5];
    events.push(key(KeyCode::Enter));
    events.extend(typed("1e9"));
    events.push(key(KeyCode::Enter));
    events.push(key(KeyCode::Up));
    events.push(key(KeyCode::Enter));
    events.extend(typed("1mg"));
    events.push(key(KeyCode::Enter));
    let (app, terminal) = explore_with(Theme::default(), 80, 24, events);
    assert_eq!(app.params.stiffness, 1e9);
    assert_eq!(app.params.cart_mass, spec(ParamId::CartMass).default);
    let screen = text(&terminal);
    assert!(screen.contains("oscillates too fast"), "{screen}");
    assert!(screen.contains("unchanged)"), "{screen}");
    let message = app.message.expect("a message").text;
    assert!(message.ends_with("(value unchanged)"), "{message}");
}

#[test]
fn escape_cancels_the_prompt() {
    let mut events = vec![key(KeyCode::Enter)];
    events.extend(typed("10"));
    events.push(key(KeyCode::Backspace));
    events.push(key(KeyCode::Esc));
    let (app, _) = explore(80, 24, events);
    assert_eq!(app.mode, Mode::Normal);
    assert!(!app.quit);
    assert_eq!(app.params, Params::default());
}

#[test]
fn the_help_overlay_lists_every_key_of_the_contact_view() {
    // Without measurements the lab's keys are left out (tui_help.rs goes through every view).
    let contact: Vec<keys::Binding> = keys::EXPLORER
        .iter()
        .filter(|b| b.scope != keys::Scope::Lab)
        .copied()
        .collect();
    for (w, h) in SIZES {
        let (app, screen) = explore(w, h, vec![key(KeyCode::Char('?'))]);
        assert_eq!(app.mode, Mode::Help);
        // At 80 x 24 the last rows and the prompt's keys are below the fold (the arrows scroll).
        let (bindings, prompt) = if h >= 48 {
            (&contact[..], keys::PROMPT)
        } else {
            (&contact[..contact.len() - 6], &[][..])
        };
        let rows: Vec<(String, &str)> = [keys::EXPLORER, keys::PROMPT]
            .into_iter()
            .flat_map(keys::help_rows)
            .collect();
        let width = rows.iter().map(|(k, _)| k.chars().count()).max().unwrap();
        let shown: Vec<(String, &str)> = [bindings, prompt]
            .into_iter()
            .flat_map(keys::help_rows)
            .collect();
        for (label, help) in &shown {
            let row = format!("{label:<width$} {help}");
            assert!(
                screen.contains(&row),
                "{row:?} missing at {w}x{h}:\n{screen}"
            );
        }
        // Every binding's keys are on some row.
        for binding in bindings.iter().chain(prompt) {
            assert!(screen.contains(&keys_label(binding)), "{binding:?}");
        }
        assert!(!screen.contains("f / F"), "{screen}");
    }
    // Esc and q close the overlay without quitting; a second Esc quits.
    for close in [KeyCode::Esc, KeyCode::Char('q')] {
        let (app, _) = explore(80, 24, vec![key(KeyCode::Char('?')), key(close)]);
        assert_eq!(app.mode, Mode::Normal);
        assert!(!app.quit);
    }
    let (app, _) = explore(
        80,
        24,
        vec![
            key(KeyCode::Char('?')),
            key(KeyCode::Esc),
            key(KeyCode::Esc),
        ],
    );
    assert!(app.quit);
}

#[test]
fn q_esc_and_ctrl_c_quit() {
    for quit in [key(KeyCode::Char('q')), key(KeyCode::Esc), ctrl('c')] {
        // Keys after the quit are never read.
        let (app, _) = explore(80, 24, vec![quit, key(KeyCode::Right)]);
        assert!(app.quit);
        assert_eq!(app.params, Params::default());
    }
}

#[test]
fn a_small_terminal_gets_a_notice_ignores_parameter_keys_and_q_and_ctrl_c_still_quit() {
    // Keys that would act blind behind the notice are ignored.
    let (app, screen) = explore(79, 24, vec![key(KeyCode::Right), key(KeyCode::Tab)]);
    assert!(
        screen.contains("terminal too small: need 80 x 24"),
        "{screen}"
    );
    assert_eq!(app.params.angle_deg, 60.0);
    assert_eq!(app.view, View::Contact);
    assert!(!app.quit);
    let (app, _) = explore(79, 24, vec![ctrl('c')]);
    assert!(app.quit);
    let (app, screen) = explore(60, 10, vec![key(KeyCode::Char('q'))]);
    assert!(app.quit);
    assert!(
        screen.contains("terminal too small: need 80 x 24"),
        "{screen}"
    );
}

#[test]
fn tab_shows_the_sweep_with_the_current_angle() {
    for (w, h) in SIZES {
        let (app, screen) = explore(w, h, vec![key(KeyCode::Tab), key(KeyCode::Right)]);
        assert_eq!(app.view, View::Sweep);
        let omega2 = solve(&app.params).unwrap().outcome.omega2;
        assert!(screen.contains("θ1 (deg)"), "{screen}");
        let current = if w >= 120 {
            format!("θ1 61.0°: ω2 {omega2:.1}")
        } else {
            format!("θ1 61.0°: {omega2:.1}")
        };
        assert!(screen.contains(&current), "{screen}");
        // The comparison curve for no incident spin, and where it crosses.
        assert!(
            screen.contains("ω1") && screen.contains("crosses"),
            "{screen}"
        );
        assert!(screen.contains("slides"), "{screen}");
    }
    // Contact, sweep, heatmap, shot, and round again.
    let (app, _) = explore(80, 24, vec![key(KeyCode::Tab); 2]);
    assert_eq!(app.view, View::Heatmap);
    let (app, _) = explore(80, 24, vec![key(KeyCode::Tab); 3]);
    assert_eq!(app.view, View::Shot);
    let (app, _) = explore(80, 24, vec![key(KeyCode::Tab); 4]);
    assert_eq!(app.view, View::Contact);
}

/// Every colour on screen, foreground and background.
fn colors(terminal: &Terminal<TestBackend>) -> Vec<Color> {
    terminal
        .backend()
        .buffer()
        .content()
        .iter()
        .flat_map(|c| [c.fg, c.bg])
        .collect()
}

#[test]
fn no_color_draws_without_colours() {
    let theme = Theme {
        color: false,
        marker: Marker::Braille,
        ascii: false,
        light: false,
    };
    for events in [
        vec![],
        vec![key(KeyCode::Tab)],
        vec![key(KeyCode::Char('?'))],
    ] {
        let (_, terminal) = explore_with(theme, 160, 48, events);
        assert!(colors(&terminal).iter().all(|c| *c == Color::Reset));
        // Phases still read from the labels.
        assert!(text(&terminal).contains("slide"));
    }
}

#[test]
fn colours_are_the_sixteen_basic_ones() {
    for events in [vec![], vec![key(KeyCode::Tab)]] {
        let (_, terminal) = explore_with(Theme::default(), 160, 48, events);
        for color in colors(&terminal) {
            assert!(
                !matches!(color, Color::Rgb(..) | Color::Indexed(_)),
                "{color:?} is not one of the 16 basic colours"
            );
        }
    }
}

#[test]
fn dot_and_block_markers_draw_without_braille() {
    for marker in [Marker::Dot, Marker::Block] {
        let theme = Theme {
            color: true,
            marker,
            ascii: false,
            light: false,
        };
        let (_, terminal) = explore_with(theme, 160, 48, vec![]);
        let screen = text(&terminal);
        assert!(
            !screen
                .chars()
                .any(|c| ('\u{2801}'..='\u{28ff}').contains(&c)),
            "{screen}"
        );
    }
}

#[test]
fn snapshots_of_a_chain_of_six() {
    // At the second transition (the grip's end) the first mass is well away from its rest position.
    let params = Params {
        chain: 6.0,
        ..Params::default()
    };
    for (w, h) in SIZES {
        let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
        let mut app = App::new(params, Theme::default()).unwrap();
        let events = vec![key(KeyCode::Char('}')), key(KeyCode::Char('}'))];
        run(&mut terminal, &mut app, &mut Scripted::from(events)).unwrap();
        insta::assert_snapshot!(format!("chain6_{w}x{h}"), text(&terminal));
    }
}

#[test]
fn snapshots_of_the_default_screens() {
    for (w, h) in SIZES {
        let (_, contact) = explore(w, h, vec![]);
        insta::assert_snapshot!(format!("contact_{w}x{h}"), contact);
        let (_, sweep) = explore(w, h, vec![key(KeyCode::Tab)]);
        insta::assert_snapshot!(format!("sweep_{w}x{h}"), sweep);
    }
}

#[test]
fn masses_of_a_kilogram_and_more_show_in_kg() {
    // From the angle down to the cart mass (after the ball's stiffness and damping), then typed.
    let mut events = vec![key(KeyCode::Down); 11];
    events.push(key(KeyCode::Enter));
    events.extend(typed("10kg"));
    events.push(key(KeyCode::Enter));
    let (app, screen) = explore(160, 48, events);
    assert_eq!(app.params.cart_mass, 10.0);
    assert!(
        line_with(&screen, "cart mass").contains("10.000 kg"),
        "{screen}"
    );
}

#[test]
fn a_long_chattering_contact_keeps_labels_inside_the_charts_and_the_outcome_short() {
    // T = 5 s: hundreds of phases, and y labels as wide as their column.
    let params = Params {
        duration: 5.0,
        ..Params::default()
    };
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    let mut app = App::new(params, Theme::default()).unwrap();
    run(
        &mut terminal,
        &mut app,
        &mut Scripted::from(Vec::<Event>::new()),
    )
    .unwrap();
    let screen = text(&terminal);
    assert!(app.solved.as_ref().unwrap().bounce.phases.len() > 100);
    // The left column's right border (column 42 at 160 wide) is whole down to the status line.
    for (row, line) in screen.lines().take(47).enumerate() {
        let border = line.chars().nth(42).unwrap();
        assert!("│┐┘┤".contains(border), "row {row}: {line}\n{screen}");
    }
    // The phase sequence is cut short with its count.
    assert!(
        screen.contains("slide-grip-slide-grip-slide-grip-… (") && screen.contains("phases)"),
        "{screen}"
    );
}

#[test]
fn the_help_scrolls_to_its_end_at_80_x_24_and_arrows_do_not_step_behind_it() {
    // Opened, the help starts with the keys; the selected parameter's notes are below the fold.
    let (_, screen) = explore(80, 24, vec![key(KeyCode::Char('?'))]);
    assert!(screen.contains("Keys"), "{screen}");
    assert!(!screen.contains("(--angle)"), "{screen}");
    // Scrolled down, they come into view; the arrows scrolled and changed nothing.
    let mut events = vec![key(KeyCode::Char('?'))];
    events.extend(vec![key(KeyCode::Down); 60]);
    let (app, screen) = explore(80, 24, events);
    assert!(screen.contains("(--angle)"), "{screen}");
    assert!(screen.contains("While typing a value"), "{screen}");
    assert_eq!(app.selected, 0);
    assert_eq!(app.params, Params::default());
    // And back up to the top.
    let mut events = vec![key(KeyCode::Char('?'))];
    events.extend(vec![key(KeyCode::Down); 60]);
    events.extend(vec![key(KeyCode::Char('k')); 200]);
    let (_, screen) = explore(80, 24, events);
    assert!(screen.contains("Keys"), "{screen}");
}

#[test]
fn a_start_the_solver_refuses_opens_and_says_so() {
    // A 1 mg cart on a 1 MN/m spring oscillates too fast to resolve: in range, but refused.
    let params = Params {
        cart_mass: 1e-6,
        stiffness: 1e9,
        ..Params::default()
    };
    let mut terminal = Terminal::new(TestBackend::new(80, 24)).unwrap();
    let mut app = App::new(params, Theme::default()).unwrap();
    run(
        &mut terminal,
        &mut app,
        &mut Scripted::from(vec![key(KeyCode::Right)]),
    )
    .unwrap();
    let screen = text(&terminal);
    assert!(screen.contains("oscillates too fast"), "{screen}");
    assert!(
        screen.contains("refused: the status line says why"),
        "{screen}"
    );
    assert!(!screen.contains("solving"), "{screen}");
    assert!(app.solved.is_none());
}
