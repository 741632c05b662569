//! The parameter panel: every parameter of the table in `model::params::PARAMS`, its value in the unit
//! people think in, the selected one highlighted, a dot beside any value that differs from the default,
//! and a heading where a new group begins (the surface: cart, spring, string friction; in shot mode the
//! shot, whose frame change sets the incidence: those rows are dimmed and labelled `set by the shot`). A
//! parameter marked free for a fit says so before its label, and one typed with an uncertainty shows it
//! (`60.0±1.0 deg`). On a short screen the list scrolls to keep the selected parameter in view, with a
//! mark on the border where more is hidden.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

use crate::model::units;
use crate::model::{ParamId, ParamSpec};
use crate::tui::app::App;
use crate::tui::shot;
use crate::tui::values::shown;

/// The fewest rows the panel is given, borders included, however short the screen.
pub const MIN_HEIGHT: u16 = 7;

pub fn render(frame: &mut Frame, area: Rect, app: &App) {
    let theme = &app.theme;
    let block = Block::bordered().title(Span::styled(" parameters ", theme.title()));
    let inner = block.inner(area);
    let width = usize::from(inner.width);
    let specs = app.listed();
    let mut lines: Vec<Line> = Vec::with_capacity(specs.len() + group_headings(specs));
    let mut selected_line = 0;
    // The symbols' column: 4 wide, wider where ASCII spells a symbol out (`theta1`).
    let column = specs
        .iter()
        .map(|spec| theme.words(spec.symbol).chars().count() + 1)
        .fold(4, usize::max);
    let ellipsis = theme.words("…");
    // Pointer, symbol, label (cut at a word to fit), value and the changed mark on the right.
    let head = |pointer: char, symbol: &str| format!("{pointer}{:<column$}", theme.words(symbol));
    let room = |symbol: &str, shown: &str| {
        width.saturating_sub(head(' ', symbol).chars().count() + shown.chars().count() + 2)
    };
    let row = |pointer: char, symbol: &str, label: &str, shown: &str, changed: char| {
        let head = head(pointer, symbol);
        let room = room(symbol, shown);
        let label = fit_label(label, room, &ellipsis);
        let gap = room.saturating_sub(label.chars().count()) + 1;
        format!("{head}{label}{:gap$}{shown}{changed}", "")
    };
    // In shot mode the derived rows show what the shot decides, not the bounce on screen (which a
    // refused change leaves behind).
    let decided = app.shots.on.then(|| shot::Decided::of(&app.params));
    for (i, spec) in specs.iter().enumerate() {
        if i > 0 && specs[i - 1].group != spec.group {
            let name = format!(" {} ", spec.group.name());
            let rule = "─".repeat(width.saturating_sub(name.chars().count() + 2));
            lines.push(Line::from(vec![
                Span::styled("──", theme.dim()),
                Span::styled(name, theme.title()),
                Span::styled(rule, theme.dim()),
            ]));
        }
        if i == app.selected {
            selected_line = lines.len();
        }
        let derived = decided.filter(|_| shot::derived(spec.id));
        let value = derived
            .and_then(|d| d.value(spec.id))
            .unwrap_or(app.params.get(spec.id));
        let shown = match app.lab.spread(spec.id) {
            Some(sigma) => theme.words(&with_spread(spec, value, sigma)).into_owned(),
            None => shown(spec, value).to_string(),
        };
        let changed = if value == spec.default { ' ' } else { '•' };
        let pointer = if i == app.selected { '▸' } else { ' ' };
        let racquet = matches!(spec.id, ParamId::FrameMass | ParamId::FrameNormalMass);
        // A free parameter says so before its label, or in place of it where both do not fit (the
        // symbol names it).
        let label = if derived.is_some() && racquet {
            FROM_RACQUET.to_string()
        } else if derived.is_some() {
            SET_BY_SHOT.to_string()
        } else if app.lab.is_free(spec.id) {
            let long = format!("{FREE}{}", spec.label);
            if long.chars().count() <= room(spec.symbol, &shown) {
                long
            } else {
                FREE_SHORT.to_string()
            }
        } else {
            spec.label.to_string()
        };
        let line = Line::from(row(pointer, spec.symbol, &label, &shown, changed));
        lines.push(if i == app.selected {
            line.style(theme.selected())
        } else if derived.is_some() {
            line.style(theme.dim())
        } else if app.lab.is_free(spec.id) {
            line.style(theme.key())
        } else {
            line
        });
        // The ball's apparent restitution on the racquet's frame follows its effective masses.
        if let Some(d) = derived
            && spec.id == ParamId::FrameNormalMass
        {
            let e = d.ey_apparent().map_or("?".into(), |e| format!("{e:.2}"));
            let text = row(' ', "e_A", APPARENT, &e, ' ');
            lines.push(Line::styled(text, theme.dim()));
        }
    }
    // Scroll no further than the selected line and the one under it need, so that the top rows (the
    // incidence) stay in view while they can, and say where lines are hidden.
    let visible = usize::from(inner.height);
    let start = scroll(lines.len(), visible, selected_line);
    let mut block = block;
    if start > 0 {
        block = block.title(Line::styled(" ▲ more ", theme.dim()).right_aligned());
    }
    if start + visible < lines.len() {
        block = block.title_bottom(Line::styled(" ▼ more ", theme.dim()).right_aligned());
    }
    let shown: Vec<Line> = lines.into_iter().skip(start).take(visible).collect();
    frame.render_widget(Paragraph::new(shown).block(block), area);
}

/// `label` in `room` columns: whole where it fits, else cut after its last word that fits with
/// `ellipsis` after it (`frame normal…`), else nothing (the symbol names the parameter).
pub fn fit_label(label: &str, room: usize, ellipsis: &str) -> String {
    let width = |s: &str| s.chars().count();
    if width(label) <= room {
        return label.to_string();
    }
    let room = room.saturating_sub(width(ellipsis));
    let cut = label
        .match_indices(' ')
        .map(|(i, _)| label[..i].trim_end_matches([':', ',']))
        .rfind(|head| width(head) <= room);
    match cut {
        Some(head) if !head.is_empty() => format!("{head}{ellipsis}"),
        _ => String::new(),
    }
}

/// The first of `lines` shown in `visible` rows with `selected` in view: 0 while the selected line and
/// the one under it fit, else as little further as keeps them in view.
pub fn scroll(lines: usize, visible: usize, selected: usize) -> usize {
    (selected + 2)
        .saturating_sub(visible)
        .min(lines.saturating_sub(visible))
}

/// The label of the incidence a shot sets (theta1, v1, omega1).
pub const SET_BY_SHOT: &str = "set by the shot";

/// The label of the frame's effective masses in a shot, read from the racquet group.
pub const FROM_RACQUET: &str = "from the racquet";

/// The label of e_A, the ball's apparent restitution on the racquet in the hand, under M_n in a shot.
pub const APPARENT: &str = "apparent restitution";

/// What a free parameter's label starts with.
pub const FREE: &str = "free: ";

/// What a free parameter's label says where the label does not fit beside it.
pub const FREE_SHORT: &str = "free for the fit";

/// `value` with its uncertainty `sigma`, both in the unit the panel shows: `60.0±1.0 deg`.
fn with_spread(spec: &ParamSpec, value: f64, sigma: f64) -> String {
    let s = shown(spec, value);
    let sigma = units::in_unit(sigma, spec.dimension, s.symbol);
    let text = format!("{:.d$}±{sigma:.d$} {}", s.value, s.symbol, d = s.decimals);
    text.trim_end().to_string()
}

/// The headings between groups of `specs`.
pub fn group_headings(specs: &[ParamSpec]) -> usize {
    specs
        .windows(2)
        .filter(|pair| pair[0].group != pair[1].group)
        .count()
}

/// Rows the panel takes, borders included.
pub fn height(app: &App) -> u16 {
    let specs = app.listed();
    // In shot mode e_A follows M_n.
    let apparent = usize::from(app.shots.on);
    (specs.len() + group_headings(specs) + apparent) as u16 + 2
}

#[cfg(test)]
mod tests {
    use super::{fit_label, scroll};

    #[test]
    fn the_list_scrolls_only_as_far_as_the_selection_needs() {
        // 37 lines in 30 rows: the top stays until the selection reaches the last row.
        assert_eq!(scroll(37, 30, 0), 0);
        assert_eq!(scroll(37, 30, 19), 0);
        assert_eq!(scroll(37, 30, 28), 0);
        assert_eq!(scroll(37, 30, 29), 1);
        assert_eq!(scroll(37, 30, 36), 7);
        assert_eq!(scroll(20, 30, 19), 0);
    }

    #[test]
    fn labels_are_cut_at_a_word() {
        assert_eq!(fit_label("frame normal mass", 17, "…"), "frame normal mass");
        assert_eq!(fit_label("frame normal mass", 16, "…"), "frame normal…");
        assert_eq!(fit_label("frame normal mass", 12, "..."), "frame...");
        assert_eq!(fit_label("free: cart mass", 11, "…"), "free: cart…");
        assert_eq!(fit_label("free: cart mass", 10, "…"), "free…");
        assert_eq!(fit_label("frame normal mass", 5, "…"), "");
    }
}
