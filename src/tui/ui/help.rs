//! The help overlay: from the key table, the keys of the view shown (the contact's time cursor, the
//! shot's flight, the schematic's time where it is drawn), then the keys of every view, the lab's with
//! measurements, the prompt's keys, and what the selected parameter is, its range and the units it
//! accepts.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use super::overlay;
use crate::tui::app::App;
use crate::tui::keys::{self, Binding, Scope};
use crate::tui::shot;
use crate::tui::theme::Theme;
use crate::tui::vocabulary::View;

/// How the prompt takes an uncertainty.
const UNCERTAINTY: &str = " 60±1 also sets an uncertainty: Fig. 2 then draws ω2's band; ±0 clears";

fn rows<'a>(bindings: &[Binding], view: View, theme: &Theme, key_width: usize) -> Vec<Line<'a>> {
    keys::help_rows_in(bindings, view)
        .into_iter()
        .map(|(label, help)| {
            Line::from(vec![
                Span::styled(
                    format!(" {:<key_width$} ", theme.words(&label)),
                    theme.key(),
                ),
                Span::raw(theme.words(help).into_owned()),
            ])
        })
        .collect()
}

/// The widest key column of the overlay.
fn key_width(theme: &Theme) -> usize {
    keys::help_rows(keys::EXPLORER)
        .iter()
        .chain(&keys::help_rows(keys::PROMPT))
        .map(|(label, _)| theme.words(label).chars().count())
        .max()
        .unwrap_or(0)
}

/// The heading over the keys of the view shown.
fn own_heading(view: View) -> String {
    match view {
        View::Contact | View::Shot => format!("Keys of the {} view", view.name()),
        View::Sweep | View::Heatmap => {
            "Keys of the schematic (the bounce at the time cursor)".into()
        }
    }
}

/// `schematic`: the schematic is drawn (its time keys work in every view).
pub fn render(frame: &mut Frame, area: Rect, app: &App, schematic: bool) {
    let theme = &app.theme;
    let context = app.key_context(schematic);
    let key_width = key_width(theme);
    let spec = app.selected_spec();
    let units = spec.dimension.symbols();
    let units = if units.is_empty() {
        "a plain number".to_string()
    } else {
        format!(
            "a bare number is in {}; also {}",
            units[0],
            units[1..].join(", ")
        )
    };
    let own = keys::explorer_keys(&context, &[Scope::Contact, Scope::Timeline]);
    let every = keys::explorer_keys(&context, &[Scope::Everywhere]);
    let lab = keys::explorer_keys(&context, &[Scope::Lab]);
    let mut lines = Vec::new();
    let every_heading = if own.is_empty() {
        format!(
            "Keys in every view (the {} view has none of its own)",
            app.view.name()
        )
    } else {
        lines.push(Line::styled(
            theme.words(&own_heading(app.view)).into_owned(),
            theme.title(),
        ));
        lines.extend(rows(&own, app.view, theme, key_width));
        "Keys in every view".to_string()
    };
    lines.push(Line::styled(
        theme.words(&every_heading).into_owned(),
        theme.title(),
    ));
    lines.extend(rows(&every, app.view, theme, key_width));
    if !lab.is_empty() {
        lines.push(Line::styled(
            "With the measurements (--data)",
            theme.title(),
        ));
        lines.extend(rows(&lab, app.view, theme, key_width));
    }
    let mut prompt = vec![Line::styled("While typing a value", theme.title())];
    prompt.extend(rows(keys::PROMPT, app.view, theme, key_width));
    prompt.push(Line::raw(theme.words(UNCERTAINTY).into_owned()));
    let mut notes = vec![
        Line::styled(
            format!(
                "{} {} (--{})",
                spec.label,
                theme.words(spec.symbol),
                spec.flag
            ),
            theme.title(),
        ),
        Line::raw(format!(" {}", theme.words(spec.help))),
        Line::raw(format!(
            " range {}; {units}; default {}",
            spec.range_text(),
            spec.show(spec.default)
        )),
    ];
    if app.shots.on && shot::derived(spec.id) {
        notes.push(Line::raw(
            " in a shot the frame change sets it: change the shot's parameters",
        ));
    }

    let width = area.width.saturating_sub(2).min(100);
    // Keys come first, then the prompt's and the parameter's notes; on a short screen the arrows scroll.
    lines.extend(prompt);
    lines.extend(notes);
    let title = Span::styled(" help ", theme.title());
    let footer = theme.words(" ↑↓ scroll · ?, q or Esc closes ").into_owned();
    overlay::render(frame, area, width, title, footer, lines, app.help_scroll);
}
