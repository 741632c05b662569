//! The status line: the value prompt while typing, else the last message (errors in red), the progress
//! of a fit under way, or a note that the schematic is hidden, then as many key hints from the key table
//! as fit the width: the essential ones first, the others where there is room, all in the table's order.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Wrap};

use crate::model::units;
use crate::tui::app::App;
use crate::tui::keys;
use crate::tui::ui::picker;
use crate::tui::vocabulary::{Mode, Tone};

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

/// The note shown while the screen is too small for the schematic.
pub const SCHEMATIC_HIDDEN: &str = "schematic hidden";

pub fn render(frame: &mut Frame, area: Rect, app: &App, schematic_shown: bool) {
    let theme = &app.theme;
    let mut spans: Vec<Span> = Vec::new();
    let prompt = match &app.mode {
        Mode::Editing(text) => Some((prompt_label(app), text.clone())),
        _ => picker::prompt(app),
    };
    if let Some((label, text)) = prompt {
        spans.push(Span::styled(theme.words(&label).into_owned(), theme.key()));
        spans.push(Span::raw(text));
        let cursor_x = area.x + spans.iter().map(|s| s.width() as u16).sum::<u16>();
        frame.set_cursor_position((cursor_x.min(area.right().saturating_sub(1)), area.y));
        spans.push(Span::raw("   "));
    } else if let Some(message) = &app.message {
        let style = match message.tone {
            Tone::Error => theme.error(),
            Tone::Info => Style::new(),
        };
        spans.push(Span::styled(theme.words(&message.text).into_owned(), style));
        spans.push(Span::raw("   "));
    } else if let Some(progress) = app.lab.progress_text() {
        spans.push(Span::styled(
            theme.words(&progress).into_owned(),
            theme.key(),
        ));
        spans.push(Span::raw("   "));
    } else {
        if area.width >= 100 {
            spans.push(Span::styled(
                format!("[{}]  ", theme.words(app.view.name())),
                theme.dim(),
            ));
        }
        if !schematic_shown {
            spans.push(Span::styled(format!("{SCHEMATIC_HIDDEN}   "), theme.dim()));
        }
    }
    let used: usize = spans.iter().map(Span::width).sum();
    let hints: Vec<keys::Hint> = keys::bindings(&app.mode)
        .iter()
        .filter(|b| keys::offered(b, &app.key_context(schematic_shown)))
        .filter_map(|b| b.hint)
        .collect();
    // Each hint after the first takes two spaces before it.
    let width =
        |h: &keys::Hint| 2 + theme.words(h.keys).chars().count() + 1 + h.word.chars().count();
    let mut room = (usize::from(area.width) + 2).saturating_sub(used);
    let mut chosen = vec![false; hints.len()];
    for essential in [true, false] {
        for (i, h) in hints.iter().enumerate() {
            if h.essential == essential && width(h) <= room {
                chosen[i] = true;
                room -= width(h);
            }
        }
    }
    let shown = hints.iter().zip(chosen).filter(|(_, c)| *c).map(|(h, _)| h);
    for (i, h) in shown.enumerate() {
        if i > 0 {
            spans.push(Span::raw("  "));
        }
        spans.push(Span::styled(theme.words(h.keys), theme.key()));
        spans.push(Span::styled(format!(" {}", h.word), theme.dim()));
    }
    frame.render_widget(
        Paragraph::new(Line::from(spans)).wrap(Wrap { trim: true }),
        area,
    );
}
