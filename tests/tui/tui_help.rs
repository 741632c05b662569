//! The help overlay and the status line's hints, per view, from the one key table: the keys of the view
//! shown (the contact's time cursor, the shot's flight, the schematic's time where it is drawn), the
//! keys of every view, the lab's with measurements; never a key that does nothing where the user is.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::layout::Rect;
use snapback::analysis::fit::data;
use snapback::model::Params;
use snapback::tui::keys::{self, Binding, Context, EXPLORER, Scope};
use snapback::tui::theme::Theme;
use snapback::tui::{App, Mode, Scripted, View, run, ui};

use crate::support::screen::text;

fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

/// Tab presses from the contact view to `view`.
fn tabs(view: View) -> usize {
    match view {
        View::Contact => 0,
        View::Sweep => 1,
        View::Heatmap => 2,
        View::Shot => 3,
    }
}

const VIEWS: [View; 4] = [View::Contact, View::Sweep, View::Heatmap, View::Shot];

/// The explorer in `view` on a `width` x `height` screen with the help open (with the synthetic
/// measurements when `data`).
fn help_in(view: View, width: u16, height: u16, data: bool) -> (App, Terminal<TestBackend>) {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    let mut app = App::new(Params::default(), Theme::default()).unwrap();
    if data {
        let path = "assets/data/synthetic-strings.csv";
        let text = std::fs::read_to_string(path).unwrap();
        app.load_data(data::parse(&text, path).unwrap());
    }
    let mut events = vec![key(KeyCode::Tab); tabs(view)];
    events.push(key(KeyCode::Char('?')));
    run(&mut terminal, &mut app, &mut Scripted::from(events)).unwrap();
    assert_eq!(app.mode, Mode::Help);
    assert_eq!(app.view, view);
    (app, terminal)
}

/// Every line the help shows, scrolled from its top to its end.
fn whole_help(app: &mut App, terminal: &mut Terminal<TestBackend>) -> String {
    let mut seen = String::new();
    for scroll in 0..80 {
        app.help_scroll = scroll;
        terminal.draw(|frame| ui::draw(frame, app)).unwrap();
        seen.push_str(&text(terminal));
        seen.push('\n');
    }
    app.help_scroll = 0;
    seen
}

/// The help's rows in `view` (the keys, padded to the key column, and the words), each with the binding
/// that starts it.
fn rows(view: View) -> Vec<(&'static Binding, String)> {
    let width = [EXPLORER, keys::PROMPT]
        .into_iter()
        .flat_map(keys::help_rows)
        .map(|(label, _)| label.chars().count())
        .max()
        .unwrap();
    let starts: Vec<usize> = (0..EXPLORER.len())
        .filter(|&i| !EXPLORER[i].help.is_empty())
        .chain([EXPLORER.len()])
        .collect();
    starts
        .windows(2)
        .map(|pair| {
            let rows = keys::help_rows_in(&EXPLORER[pair[0]..pair[1]], view);
            assert_eq!(rows.len(), 1);
            let (label, words) = &rows[0];
            (&EXPLORER[pair[0]], format!(" {label:<width$} {words}"))
        })
        .collect()
}

#[test]
fn the_help_lists_the_keys_of_the_view_and_of_every_view() {
    for (w, h) in [(80, 24), (160, 48)] {
        for view in VIEWS {
            for data in [false, true] {
                let (mut app, mut terminal) = help_in(view, w, h, data);
                let schematic = ui::schematic_shown(Rect::new(0, 0, w, h), &app);
                let context = app.key_context(schematic);
                let help = whole_help(&mut app, &mut terminal);
                for (binding, row) in rows(view) {
                    let listed = help.contains(&row);
                    assert_eq!(
                        listed,
                        binding.scope.applies(&context),
                        "{row:?} at {w}x{h} in {view:?} (data {data}):\n{help}"
                    );
                }
                // The view's own keys come first, under their heading; the lab's only with data.
                let own = match view {
                    View::Contact => Some("Keys of the contact view"),
                    View::Shot => Some("Keys of the shot view"),
                    View::Sweep | View::Heatmap => {
                        schematic.then_some("Keys of the schematic (the bounce at the time cursor)")
                    }
                };
                match own {
                    Some(heading) => {
                        assert!(help.contains(heading), "{heading} in\n{help}");
                        assert!(help.contains("│Keys in every view "), "{help}");
                    }
                    None => assert!(
                        help.contains(&format!(
                            "Keys in every view (the {} view has none of its own)",
                            view.name()
                        )),
                        "{help}"
                    ),
                }
                assert_eq!(
                    help.contains("With the measurements (--data)"),
                    data,
                    "{help}"
                );
                assert!(help.contains("While typing a value"), "{help}");
            }
        }
    }
}

#[test]
fn the_shot_view_says_what_its_keys_do_there() {
    let (mut app, mut terminal) = help_in(View::Shot, 160, 48, false);
    let help = whole_help(&mut app, &mut terminal);
    assert!(help.contains("play or pause the flight"), "{help}");
    assert!(
        help.contains("the ball to the start / end of the flight"),
        "{help}"
    );
    for absent in ["play or pause the bounce", "[ / ]", "{ / }", "+, = / -"] {
        assert!(!help.contains(absent), "{absent} in\n{help}");
    }
    let (mut app, mut terminal) = help_in(View::Contact, 160, 48, false);
    let help = whole_help(&mut app, &mut terminal);
    assert!(help.contains("play or pause the bounce in slow motion"));
    assert!(!help.contains("flight"), "{help}");
}

#[test]
fn the_hints_offer_the_same_keys_as_the_help() {
    for (w, h) in [(80, 24), (160, 48)] {
        for view in VIEWS {
            let (app, terminal) = help_in(view, w, h, false);
            let status = text(&terminal).lines().last().unwrap().to_string();
            let schematic = ui::schematic_shown(Rect::new(0, 0, w, h), &app);
            let context = app.key_context(schematic);
            // Space plays where a timeline is shown, and its hint is essential: it is there or not.
            let space = EXPLORER
                .iter()
                .find(|b| b.help.starts_with("play or pause"))
                .unwrap();
            assert_eq!(
                status.contains("␣ play"),
                space.scope.applies(&context),
                "{view:?} at {w}x{h}: {status}"
            );
            assert!(keys::offered(space, &context) == space.scope.applies(&context));
            // The time cursor's hint ([] time) only where the cursor is drawn, room permitting.
            if status.contains("[] time") {
                assert!(Scope::Contact.applies(&context), "{view:?}: {status}");
            }
        }
    }
    // Where the contact's cursor is drawn, and where it is not.
    let at = |view, schematic| Context {
        view,
        shot_on: false,
        schematic,
        data: false,
    };
    assert!(Scope::Contact.applies(&at(View::Contact, false)));
    assert!(!Scope::Contact.applies(&at(View::Sweep, false)));
    assert!(Scope::Contact.applies(&at(View::Heatmap, true)));
    assert!(!Scope::Contact.applies(&at(View::Shot, true)));
    assert!(Scope::Timeline.applies(&at(View::Shot, false)));
    assert!(!Scope::Timeline.applies(&at(View::Sweep, false)));
    assert!(!Scope::Lab.applies(&at(View::Contact, true)));
}

#[test]
fn snapshots_of_the_help_per_view() {
    for (view, (w, h)) in [
        (View::Contact, (80, 24)),
        (View::Sweep, (80, 24)),
        (View::Shot, (80, 24)),
        (View::Heatmap, (160, 48)),
    ] {
        let (_, terminal) = help_in(view, w, h, false);
        let name = format!("help_{}_{w}x{h}", format!("{view:?}").to_lowercase());
        insta::assert_snapshot!(name, text(&terminal));
    }
}
