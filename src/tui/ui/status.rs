//! The status line: the value prompt while typing, else the last message (errors in red), then as many
//! key hints as fit the width, from the key table.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};

use crate::model::units;
use crate::tui::app::{App, Mode, Tone};
use crate::tui::keys;
use crate::tui::ui::picker;

/// What the prompt says about units: `cart mass M [kg; or e.g. 10g]`.
pub fn prompt_label(app: &App) -> String {
    let spec = app.selected_spec();
    let base = spec.dimension.base_symbol();
    let unit = if base.is_empty() {
        "a number".to_string()
    } else if spec.display_unit == base {
        base.to_string()
    } else {
        let shown = spec.show(app.params.get(spec.id)).value;
        format!(
            "{base}; or e.g. {}{}",
            units::brief(shown, 4),
            spec.display_unit
        )
    };
    format!("{} {} [{unit}]: ", spec.label, spec.symbol)
}

/// Rows the status line needs: a long message wraps onto up to three.
pub fn height(app: &App, width: u16) -> u16 {
    match (&app.mode, &app.message) {
        (Mode::Normal | Mode::Help, Some(m)) => {
            // Wrapping breaks at spaces, so allow a little more than the bare length.
            let chars = m.text.chars().count() + m.text.chars().count() / 8;
            chars.div_ceil(usize::from(width.max(1))).clamp(1, 3) as u16
        }
        _ => 1,
    }
}

pub fn render(frame: &mut Frame, area: Rect, app: &App) {
    let theme = &app.theme;
    let mut spans: Vec<Span> = Vec::new();
    let prompt = match &app.mode {
        Mode::Editing(text) => Some((prompt_label(app), text.clone())),
        _ => picker::prompt(app),
    };
    if let Some((label, text)) = prompt {
        spans.push(Span::styled(label, theme.key()));
        spans.push(Span::raw(text));
        let cursor_x = area.x + spans.iter().map(|s| s.width() as u16).sum::<u16>();
        frame.set_cursor_position((cursor_x.min(area.right().saturating_sub(1)), area.y));
        spans.push(Span::raw("   "));
    } else if let Some(message) = &app.message {
        let style = match message.tone {
            Tone::Error => theme.error(),
            Tone::Info => Style::new(),
        };
        spans.push(Span::styled(message.text.clone(), style));
        spans.push(Span::raw("   "));
    } else if area.width >= 100 {
        spans.push(Span::styled(
            format!("[{}]  ", app.view.name()),
            theme.dim(),
        ));
    }
    let mut used: usize = spans.iter().map(Span::width).sum();
    let hints = keys::bindings(&app.mode).iter().filter_map(|b| b.hint);
    for (i, (key, word)) in hints.enumerate() {
        let gap = if i == 0 { "" } else { "  " };
        let width = gap.len() + key.chars().count() + 1 + word.chars().count();
        if used + width > usize::from(area.width) {
            break;
        }
        spans.push(Span::raw(gap));
        spans.push(Span::styled(key, theme.key()));
        spans.push(Span::styled(format!(" {word}"), theme.dim()));
        used += width;
    }
    frame.render_widget(
        Paragraph::new(Line::from(spans)).wrap(Wrap { trim: true }),
        area,
    );
}
