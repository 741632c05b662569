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

use crate::model::ParamSpec;
use crate::model::units;
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
        lines.push({
            let value = app.params.get(spec.id);
            let shown = match app.lab.spread(spec.id) {
                Some(sigma) => theme.words(&with_spread(spec, value, sigma)).into_owned(),
                None => shown(spec, value).to_string(),
            };
            let changed = if value == spec.default { ' ' } else { '•' };
            let pointer = if i == app.selected { '▸' } else { ' ' };
            // pointer, symbol, label, value and the changed mark on the right.
            let head = format!("{pointer}{:<column$}", theme.words(spec.symbol));
            let room = width.saturating_sub(head.chars().count() + shown.chars().count() + 2);
            let derived = app.shots.on && shot::derived(spec.id);
            // A free parameter says so before its label, or in place of it where both do not fit (the
            // symbol names it).
            let label = if derived {
                "set by the shot".to_string()
            } else if app.lab.is_free(spec.id) {
                let long = format!("{FREE}{}", spec.label);
                if long.chars().count() <= room {
                    long
                } else {
                    FREE_SHORT.to_string()
                }
            } else {
                spec.label.to_string()
            };
            let label: String = if room >= 8 {
                label.chars().take(room).collect()
            } else {
                String::new()
            };
            let gap = room.saturating_sub(label.chars().count()) + 1;
            let text = format!("{head}{label}{:gap$}{shown}{changed}", "");
            let line = Line::from(text);
            if i == app.selected {
                line.style(theme.selected())
            } else if derived {
                line.style(theme.dim())
            } else if app.lab.is_free(spec.id) {
                line.style(theme.key())
            } else {
                line
            }
        });
    }
    // Scroll so the selected line sits mid-panel where it can, and say where lines are hidden.
    let visible = usize::from(inner.height);
    let start = if lines.len() > visible {
        selected_line
            .saturating_sub(visible / 2)
            .min(lines.len() - visible)
    } else {
        0
    };
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
    (specs.len() + group_headings(specs)) as u16 + 2
}
