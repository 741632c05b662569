//! The help overlay: every key from the key table, the prompt's keys, and what the selected parameter is,
//! its range and the units it accepts.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use super::overlay;
use crate::tui::app::App;
use crate::tui::keys::{self, Binding};
use crate::tui::shot;
use crate::tui::theme::Theme;

/// How the prompt takes an uncertainty.
const UNCERTAINTY: &str = " 60±1 also sets an uncertainty: Fig. 2 then draws ω2's band; ±0 clears";

fn rows<'a>(bindings: &[Binding], theme: &Theme, key_width: usize) -> Vec<Line<'a>> {
    keys::help_rows(bindings)
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

pub fn render(frame: &mut Frame, area: Rect, app: &App) {
    let theme = &app.theme;
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
    let mut lines = vec![Line::styled("Keys", theme.title())];
    lines.extend(rows(keys::EXPLORER, theme, key_width));
    let mut prompt = vec![Line::styled("While typing a value", theme.title())];
    prompt.extend(rows(keys::PROMPT, theme, key_width));
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
