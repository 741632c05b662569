//! The preset picker overlay (`p`): every preset with its description (the user's marked `(user)`), the highlighted one's full
//! description and source below; and what the status line asks while a file name is typed (`s`, `o`) or
//! an overwrite is to be confirmed.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

use super::overlay;
use crate::tui::app::App;
use crate::tui::vocabulary::{FileKind, Mode};

/// `text` cut to `width` characters, with `…` when cut.
fn fit(text: &str, width: usize) -> String {
    if text.chars().count() <= width {
        text.to_string()
    } else {
        let mut cut: String = text.chars().take(width.saturating_sub(1)).collect();
        cut.push('…');
        cut
    }
}

pub fn render(frame: &mut Frame, area: Rect, app: &App) {
    let Mode::Picker(selected) = app.mode else {
        return;
    };
    let theme = &app.theme;
    let width = area.width.saturating_sub(2).min(110);
    let inner = usize::from(width.saturating_sub(2));
    let names: Vec<String> = app
        .presets
        .iter()
        .map(|(s, user)| {
            if *user {
                format!("{} (user)", s.name)
            } else {
                s.name.clone()
            }
        })
        .collect();
    let name_width = names.iter().map(|n| n.chars().count()).max().unwrap_or(0);
    let mut lines: Vec<Line> = app
        .presets
        .iter()
        .zip(&names)
        .enumerate()
        .map(|(i, ((scenario, _), name))| {
            let row = fit(
                &format!(" {name:<name_width$}  {}", scenario.description),
                inner,
            );
            if i == selected {
                Line::styled(format!("{row:<inner$}"), theme.selected())
            } else {
                Line::from(vec![
                    Span::styled(format!(" {name:<name_width$}"), theme.key()),
                    Span::raw(row.chars().skip(name_width + 1).collect::<String>()),
                ])
            }
        })
        .collect();
    if let Some((chosen, _)) = app.presets.get(selected) {
        lines.push(Line::raw(""));
        lines.push(Line::raw(chosen.description.clone()));
        if !chosen.source.is_empty() {
            lines.push(Line::styled(
                format!("source: {}", chosen.source),
                theme.dim(),
            ));
        }
    }
    let title = Span::styled(" presets ", theme.title());
    let footer = " ↑↓ choose · ⏎ apply (u undoes) · Esc close ";
    overlay::render(frame, area, width, title, footer.into(), lines, 0);
}

/// What the status line asks, and the text typed so far, while a file prompt or question is open.
pub fn prompt(app: &App) -> Option<(String, String)> {
    match &app.mode {
        Mode::File(prompt) => {
            let what = match prompt.kind {
                FileKind::Save => "save the parameters as",
                FileKind::Open => "open scenario file",
            };
            let label = if prompt.default.is_empty() {
                format!("{what}: ")
            } else {
                format!("{what} [{}]: ", prompt.default)
            };
            Some((label, prompt.text.clone()))
        }
        // The file's name only, so the question fits on one line; the saved message gives the full path.
        Mode::Overwrite(path) => Some((
            format!(
                "{} exists; overwrite it? ",
                path.file_name().map_or_else(
                    || path.display().to_string(),
                    |n| n.to_string_lossy().into_owned()
                )
            ),
            String::new(),
        )),
        _ => None,
    }
}
