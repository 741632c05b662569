//! The heatmap view: rebound spin omega2 over cart mass M (across, log) and spring stiffness k (up, log)
//! for the other parameters as they are, with the current (M, k) marked `+` and the best `*` (the best
//! cell so far, then the peak refined from it by Brent's method, [`crate::tui::peak`]),
//! and a colour scale beneath. Cells fill in row by row as the worker thread solves them.
//!
//! With colour, each character shows two cells one above the other (`▀`, the upper in the foreground
//! colour, the lower in the background) in an eight-step scale of the 16 basic colours; without colour
//! (NO_COLOR), one cell per character in the shades `·░▒▓█`; a cell not computed yet is blank.

use ratatui::Frame;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Paragraph};

use crate::tui::app::App;
use crate::tui::grid::{self, MASS_RANGE, MASSES, STIFFNESS_RANGE, STIFFNESSES, cell_of};
use crate::tui::solved::Solved;

/// The colour scale, low to high.
const RAMP: [Color; 8] = [
    Color::Blue,
    Color::LightBlue,
    Color::Cyan,
    Color::Green,
    Color::LightGreen,
    Color::Yellow,
    Color::LightRed,
    Color::Red,
];

/// The shades without colour, low to high.
const SHADES: [&str; 5] = ["·", "░", "▒", "▓", "█"];

/// The step of `value` on a scale of `steps` over `[low, high]`.
fn level(value: f64, (low, high): (f64, f64), steps: usize) -> usize {
    if high <= low {
        return steps - 1;
    }
    (((value - low) / (high - low)) * steps as f64)
        .floor()
        .clamp(0.0, (steps - 1) as f64) as usize
}

/// Mass labels at the decades, and stiffness labels.
const MASS_TICKS: [(f64, &str); 4] = [
    (1e-4, "0.1 g"),
    (1e-3, "1 g"),
    (1e-2, "10 g"),
    (1e-1, "100 g"),
];
const STIFFNESS_TICKS: [(f64, &str); 3] = [(1e3, "1 kN/m"), (1e4, "10 kN/m"), (1e5, "100 kN/m")];
const LABEL_WIDTH: u16 = 9;

/// The fraction (0 to 1) of the way along a log axis over `range`.
fn log_fraction(value: f64, range: [f64; 2]) -> f64 {
    (value / range[0]).ln() / (range[1] / range[0]).ln()
}

pub fn render(frame: &mut Frame, area: Rect, app: &App, solved: &Solved) {
    let theme = &app.theme;
    let map = &app.heatmap;
    let wide = area.width >= 90;
    let name = if wide {
        " rebound spin ω2 (rad/s) over cart mass M and stiffness k "
    } else {
        " ω2 (rad/s) over M and k "
    };
    let block = Block::new().borders(Borders::TOP).title(Line::from(vec![
        Span::styled(name, theme.title()),
        Span::styled(format!("┆ θ1 {:.1}° ", app.params.angle_deg), theme.dim()),
    ]));
    let progress = if map.pending() {
        format!(" computing {}/{} ", map.done(), STIFFNESSES)
    } else if map.failed.is_some() {
        format!(
            " stopped at {}/{}: internal error ",
            map.done(),
            STIFFNESSES
        )
    } else {
        String::new()
    };
    let block = block.title(Line::styled(progress, theme.key()).right_aligned());
    let inner = block.inner(area);
    frame.render_widget(block, area);
    // Rows: the map, the x axis, its labels, and two of legend.
    if inner.height < 8 || inner.width < LABEL_WIDTH + 12 {
        return;
    }
    let map_area = Rect::new(
        inner.x + LABEL_WIDTH + 1,
        inner.y,
        inner.width - LABEL_WIDTH - 1,
        inner.height - 4,
    );
    let buf = frame.buffer_mut();
    let range = map.range();
    let (sub_rows, per_char) = if theme.color {
        (map_area.height * 2, 2)
    } else {
        (map_area.height, 1)
    };
    // The cell shown at a column and a sub-row (sub-row 0 at the top: the stiffest spring).
    let column_cell = |c: u16| usize::from(c) * MASSES / usize::from(map_area.width);
    let row_cell = |s: u16| STIFFNESSES - 1 - usize::from(s) * STIFFNESSES / usize::from(sub_rows);
    for r in 0..map_area.height {
        for c in 0..map_area.width {
            let i = column_cell(c);
            let cell = &mut buf[(map_area.x + c, map_area.y + r)];
            if theme.color {
                let colour = |s: u16| match (map.at(i, row_cell(s)), range) {
                    (Some(w), Some(range)) => RAMP[level(w, range, RAMP.len())],
                    _ => Color::Reset,
                };
                cell.set_symbol("▀")
                    .set_fg(colour(r * per_char))
                    .set_bg(colour(r * per_char + 1));
            } else {
                let shade = match (map.at(i, row_cell(r)), range) {
                    (Some(w), Some(range)) => SHADES[level(w, range, SHADES.len())],
                    _ => " ",
                };
                cell.set_symbol(shade);
            }
        }
    }
    // The best cell and the current parameters, drawn in the character that shows them.
    let place = |buf: &mut Buffer, i: usize, j: usize, symbol: &str| {
        let c = ((i * 2 + 1) * usize::from(map_area.width) / (2 * MASSES)) as u16;
        let s = ((STIFFNESSES - 1 - j) * 2 + 1) * usize::from(sub_rows) / (2 * STIFFNESSES);
        let r = s as u16 / per_char;
        let cell = &mut buf[(map_area.x + c.min(map_area.width - 1), map_area.y + r)];
        let style = Style::new().add_modifier(Modifier::BOLD);
        let style = if theme.color {
            style.fg(Color::White).bg(Color::Black)
        } else {
            style
        };
        cell.set_symbol(symbol).set_style(style);
    };
    // The refined peak once it is known, else the best cell so far.
    let best = match map.peak {
        Some(peak) => cell_of(peak.mass, MASS_RANGE, MASSES)
            .zip(cell_of(peak.stiffness, STIFFNESS_RANGE, STIFFNESSES))
            .map(|(i, j)| (i, j, peak.omega2, peak.mass, peak.stiffness)),
        None => map
            .best()
            .map(|(i, j, w)| (i, j, w, grid::mass(i), grid::stiffness(j))),
    };
    if let Some((i, j, ..)) = best {
        place(buf, i, j, "*");
    }
    let current = (
        cell_of(app.params.cart_mass, MASS_RANGE, MASSES),
        cell_of(app.params.stiffness, STIFFNESS_RANGE, STIFFNESSES),
    );
    if let (Some(i), Some(j)) = current {
        place(buf, i, j, "+");
    }

    // Axes.
    let axis_style = theme.dim();
    let axis_x = map_area.x - 1;
    let axis_y = map_area.bottom();
    for row in map_area.top()..axis_y {
        buf.set_string(axis_x, row, "│", axis_style);
    }
    for (k, label) in STIFFNESS_TICKS {
        let f = log_fraction(k, STIFFNESS_RANGE);
        let row = axis_y - 1 - ((f * f64::from(map_area.height - 1)).round() as u16);
        buf.set_string(axis_x, row, "┤", axis_style);
        let width = label.chars().count() as u16;
        buf.set_string(axis_x.saturating_sub(width + 1), row, label, axis_style);
    }
    buf.set_string(axis_x, axis_y, "└", axis_style);
    buf.set_string(
        map_area.x,
        axis_y,
        "─".repeat(usize::from(map_area.width)),
        axis_style,
    );
    for (m, label) in MASS_TICKS {
        let f = log_fraction(m, MASS_RANGE);
        let col = map_area.x + (f * f64::from(map_area.width - 1)).round() as u16;
        buf.set_string(col, axis_y, "┬", axis_style);
        let width = label.chars().count() as u16;
        let start = col
            .saturating_sub(width / 2)
            .clamp(map_area.x, map_area.right().saturating_sub(width));
        buf.set_string(start, axis_y + 1, label, axis_style);
    }
    buf.set_string(inner.x, axis_y + 1, "k ↑ M →", axis_style);

    // The legend: the colour scale with its ends, then the two marks.
    let mut scale = vec![Span::styled("ω2 ", theme.dim())];
    match range {
        Some((low, high)) => {
            scale.push(Span::raw(format!("{low:.1} ")));
            if theme.color {
                for colour in RAMP {
                    scale.push(Span::styled("██", Style::new().fg(colour)));
                }
            } else {
                scale.push(Span::raw(SHADES.join("")));
            }
            scale.push(Span::raw(format!(" {high:.1} rad/s")));
        }
        None => scale.push(Span::styled("(computing)", theme.dim())),
    }
    let omega2 = solved.bounce.outcome.omega2;
    let here = match (current, wide) {
        ((Some(_), Some(_)), true) => format!(
            "+ now {omega2:.1} (M {}, k {})   ",
            shown_mass(app),
            shown_k(app)
        ),
        ((Some(_), Some(_)), false) => format!("+ now {omega2:.1}  "),
        _ => format!("+ now {omega2:.1}, off the map  "),
    };
    let marks = match best {
        Some((_, _, w, m, k)) => format!(
            "{here}* best {w:.1}{} {}, {}",
            if wide { " at M" } else { ":" },
            grams(m),
            kilo(k)
        ),
        None => here,
    };
    frame.render_widget(
        Paragraph::new(vec![Line::from(scale), Line::styled(marks, theme.dim())]),
        Rect::new(inner.x, axis_y + 2, inner.width, 2),
    );
}

fn grams(kg: f64) -> String {
    let g = kg * 1e3;
    if g < 1.0 {
        format!("{g:.2} g")
    } else if g < 10.0 {
        format!("{g:.1} g")
    } else {
        format!("{g:.0} g")
    }
}

fn kilo(n_per_m: f64) -> String {
    let k = n_per_m / 1e3;
    if k < 10.0 {
        format!("{k:.1} kN/m")
    } else {
        format!("{k:.0} kN/m")
    }
}

fn shown_mass(app: &App) -> String {
    grams(app.params.cart_mass)
}

fn shown_k(app: &App) -> String {
    kilo(app.params.stiffness)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_cover_the_scale() {
        assert_eq!(level(0.0, (0.0, 8.0), 8), 0);
        assert_eq!(level(7.99, (0.0, 8.0), 8), 7);
        assert_eq!(level(8.0, (0.0, 8.0), 8), 7);
        assert_eq!(level(4.0, (0.0, 8.0), 8), 4);
        assert_eq!(level(3.0, (3.0, 3.0), 5), 4);
    }
}
