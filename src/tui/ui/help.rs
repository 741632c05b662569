//! The help overlay: every key from the key table, the prompt's keys, and what the selected parameter is,
//! its range and the units it accepts.

use ratatui::Frame;
use ratatui::layout::{Constraint, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Wrap};

use crate::tui::app::App;
use crate::tui::keys::{self, Binding};
use crate::tui::ui::theme::Theme;

fn rows<'a>(bindings: &[Binding], theme: &Theme, key_width: usize) -> Vec<Line<'a>> {
    keys::help_rows(bindings)
        .into_iter()
        .map(|(label, help)| {
            Line::from(vec![
                Span::styled(format!(" {label:<key_width$} "), theme.key()),
                Span::raw(help),
            ])
        })
        .collect()
}

/// The widest key column of the overlay.
fn key_width() -> usize {
    keys::help_rows(keys::EXPLORER)
        .iter()
        .chain(&keys::help_rows(keys::PROMPT))
        .map(|(label, _)| label.chars().count())
        .max()
        .unwrap_or(0)
}

pub fn render(frame: &mut Frame, area: Rect, app: &App) {
    let theme = &app.theme;
    let key_width = key_width();
    let spec = app.selected_spec();
    let units: Vec<&str> = spec
        .dimension
        .units()
        .iter()
        .flat_map(|u| u.symbols.iter().copied())
        .collect();
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
    let notes = vec![
        Line::styled(
            format!("{} {} (--{})", spec.label, spec.symbol, spec.flag),
            theme.title(),
        ),
        Line::raw(format!(" {}", spec.help)),
        Line::raw(format!(
            " range {}; {units}; default {}",
            spec.range_text(),
            spec.show(spec.default)
        )),
    ];

    let width = area.width.saturating_sub(2).min(100);
    // Keys come first; on a short screen the sections after them are left out whole, in this order (the
    // status line shows the prompt's keys while typing).
    let text_width = usize::from(width.saturating_sub(2)).max(1);
    let rows_of = |lines: &[Line]| -> usize {
        lines
            .iter()
            .map(|l| l.width().max(1).div_ceil(text_width))
            .sum()
    };
    let room = usize::from(area.height.saturating_sub(2));
    for section in [prompt, notes] {
        if rows_of(&lines) + rows_of(&section) <= room {
            lines.extend(section);
        }
    }
    let height = (rows_of(&lines) as u16 + 2).min(area.height);
    let popup = area.centered(Constraint::Length(width), Constraint::Length(height));
    let block = Block::bordered()
        .title(Span::styled(" help ", theme.title()))
        .title_bottom(Line::from(" ? or Esc closes ").right_aligned());
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(lines)
            .block(block)
            .wrap(Wrap { trim: false }),
        popup,
    );
}
