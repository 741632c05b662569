//! The contact view (the paper's Fig. 3): a row for the time cursor, the phase timeline, then three stacked
//! charts sharing the time axis in ms: friction force F with the grip limit +/- mu N, cart displacement X
//! and ball spin omega. Curves take the colour of their phase; dashed verticals mark the transitions. With
//! `--data`, omega2 measured at the current parameters is a point at the end of the spin chart.
//!
//! The time cursor is a solid vertical line across the three charts. The values at it are written at the
//! right of each chart's title (F and mu N; X and the cart velocity V; omega and the slip speed), and its
//! time, phase and the playback state on the row above the timeline. All come from the core's
//! `Bounce::sample_at`: exactly at a transition they are those of the phase that begins there; the
//! friction force, the one value that jumps there, is written `before→after`.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::baseline;
use super::plot::{Band, FRAME_ROWS, Mark, Plot, Scale, Segment, tick_budget, y_extent};
use crate::model::{Cart, Sample};
use crate::tui::app::App;
use crate::tui::solved::Solved;
use crate::tui::theme::Theme;

/// Points of the dashed grip-limit envelope.
const ENVELOPE_POINTS: usize = 200;

/// y ticks that fit `rows` rows of plot: about one every other row, at most 7.
fn y_budget(rows: u16) -> usize {
    (usize::from(rows) + 2).div_ceil(2).clamp(2, 7)
}

/// `value` with `decimals` places, never `-0.0`.
pub fn fixed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

/// Where everything of the contact view goes, and the scales; drawing and mouse clicks both use it.
struct ContactLayout {
    cursor_row: Rect,
    band_row: Rect,
    rows: [Rect; 3],
    marks: [Vec<Mark>; 3],
    scales: Vec<Scale>,
    x: Scale,
    label_width: u16,
}

fn layout(area: Rect, app: &App, solved: &Solved) -> ContactLayout {
    let theme = &app.theme;
    let bounce = &solved.bounce;
    let [cursor_row, band_row, charts] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Length(1),
        Constraint::Min(0),
    ])
    .areas(area);
    let rows: [Rect; 3] = Layout::vertical([Constraint::Fill(1); 3]).areas(charts);

    let ms = |s: &Sample| s.t * 1e3;
    let path = |value: fn(&Sample) -> f64| {
        Mark::Path(
            solved
                .series
                .iter()
                .map(|s| (ms(s), value(s), theme.phase(s.kind)))
                .collect(),
        )
    };
    // The pinned baseline, if any, under the current curve.
    let faint = |value: fn(&Sample) -> f64| match &app.baseline {
        Some(b) => {
            let points: Vec<(f64, f64)> =
                b.solved.series.iter().map(|s| (ms(s), value(s))).collect();
            baseline::curve(&points, theme, area.width)
        }
        None => Vec::new(),
    };
    let transitions: Vec<Mark> = bounce
        .phases
        .iter()
        .skip(1)
        .map(|p| Mark::Vertical(p.start * 1e3, theme.guide()))
        .collect();
    let duration = bounce.setup.duration;
    let limit: Vec<(f64, f64)> = (0..=ENVELOPE_POINTS)
        .map(|i| {
            let t = duration * i as f64 / ENVELOPE_POINTS as f64;
            (t * 1e3, bounce.setup.mu * bounce.setup.normal(t))
        })
        .collect();
    let negative = limit.iter().map(|&(t, f)| (t, -f)).collect();
    let zero = Mark::Horizontal(0.0, theme.guide());

    let mut force = vec![
        zero.clone(),
        Mark::Dashed(limit, theme.limit()),
        Mark::Dashed(negative, theme.limit()),
    ];
    force.extend(faint(|s| s.friction));
    force.push(path(|s| s.friction));
    let mut displacement = vec![zero.clone()];
    displacement.extend(faint(|s| s.x * 1e3));
    // The cart's curve shows where string friction holds it still.
    displacement.push(Mark::Path(
        solved
            .series
            .iter()
            .map(|s| {
                let color = if s.cart_stuck {
                    theme.stuck()
                } else {
                    theme.phase(s.kind)
                };
                (ms(s), s.x * 1e3, color)
            })
            .collect(),
    ));
    let mut spin = vec![zero];
    spin.extend(faint(|s| s.omega));
    spin.push(path(|s| s.omega));
    spin.extend(super::measured::contact_marks(
        app,
        &solved.params,
        duration * 1e3,
    ));
    for marks in [&mut force, &mut displacement, &mut spin] {
        marks.extend(transitions.iter().cloned());
        marks.push(Mark::Cursor(app.cursor * 1e3, theme.cursor()));
    }

    let scales: Vec<Scale> = [&force, &displacement, &spin]
        .iter()
        .zip(rows)
        .map(|(marks, row)| {
            let (low, high) = y_extent(marks);
            Scale::rounded(low, high, y_budget(row.height.saturating_sub(FRAME_ROWS)))
        })
        .collect();
    let label_width = scales
        .iter()
        .map(Scale::label_width)
        .max()
        .unwrap_or(0)
        .max(X_TITLE.len() as u16);
    let (_, data_width) = Plot::data_columns(area, label_width);
    // Time runs to the end of the longer contact when a baseline is pinned.
    let end = app
        .baseline
        .as_ref()
        .map_or(duration, |b| b.solved.duration().max(duration));
    let x = Scale::exact(0.0, end * 1e3, tick_budget(data_width, 6));
    ContactLayout {
        cursor_row,
        band_row,
        rows,
        marks: [force, displacement, spin],
        scales,
        x,
        label_width,
    }
}

const X_TITLE: &str = "t (ms)";

/// The time, s, under column `column` and row `row` of the contact view in `area`, if that is over the
/// timeline or a chart: a time the canvas draws in that column, so the cursor's line lands in the column
/// clicked.
pub fn time_at(area: Rect, app: &App, solved: &Solved, column: u16, row: u16) -> Option<f64> {
    let layout = layout(area, app, solved);
    let (first, width) = Plot::data_columns(area, layout.label_width);
    let charts_bottom = layout.rows[2].bottom();
    if width < 2 || !(first..first + width).contains(&column) {
        return None;
    }
    if !(layout.band_row.y..charts_bottom).contains(&row) {
        return None;
    }
    // Column c of w holds the dots c a ..= c a + a - 1 of the w a across, and the canvas puts time t on dot
    // round(t / T (w a - 1)); t = T c / (w - 1) is on dot c a + c (a - 1) / (w - 1), within column c, and
    // the first and last columns give the ends of the axis (T, or a longer pinned baseline's contact).
    let axis_end = layout.x.bounds[1] * 1e-3;
    let fraction = f64::from(column - first) / f64::from(width - 1);
    Some((fraction * axis_end).clamp(0.0, solved.duration()))
}

/// The cursor row: `t 1.320 ms · grip, phase 2 of 3` on the left, the playback state on the right.
fn cursor_line(
    app: &App,
    solved: &Solved,
    theme: &Theme,
    width: u16,
) -> (Line<'static>, Line<'static>) {
    let now = solved.sample_at(app.cursor);
    let phases = solved.bounce.phases.len();
    let mut left = vec![
        Span::styled(" t ", theme.dim()),
        Span::styled(format!("{} ms", fixed(app.cursor * 1e3, 3)), theme.key()),
        Span::styled(" · ", theme.dim()),
    ];
    match solved.sample_before(app.cursor) {
        Some(before) => {
            left.push(Span::styled(
                before.kind.name(),
                Style::new().fg(theme.phase(before.kind)),
            ));
            left.push(Span::raw(" → "));
            left.push(Span::styled(
                now.kind.name(),
                Style::new().fg(theme.phase(now.kind)),
            ));
        }
        None => {
            left.push(Span::styled(
                now.kind.name(),
                Style::new().fg(theme.phase(now.kind)),
            ));
            if width >= 60 {
                left.push(Span::styled(
                    format!(", phase {} of {phases}", now.phase + 1),
                    theme.dim(),
                ));
            }
        }
    }
    if now.cart_stuck {
        let stuck = format!(", {} stuck", solved.bounce.params.touched());
        left.push(Span::styled(stuck, Style::new().fg(theme.stuck())));
    }
    let state = if app.playing {
        Span::styled("▶ playing ", theme.key())
    } else {
        Span::styled("␣ plays ", theme.dim())
    };
    let right = Line::from(vec![state, Span::raw(app.speed.label()), Span::raw(" ")]);
    (Line::from(left), right)
}

/// The values at the cursor for each chart, as they sit at the right of its title.
fn readouts(app: &App, solved: &Solved, theme: &Theme) -> [Line<'static>; 3] {
    let s = solved.sample_at(app.cursor);
    let dim = |text: &'static str| Span::styled(text, theme.dim());
    // A jump shows only where it shows at the readout's precision (a compliant ball's force is
    // continuous, and rounding would otherwise print `123.9→123.9`).
    let force = match solved
        .sample_before(app.cursor)
        .map(|b| fixed(b.friction, 1))
    {
        Some(before) if before != fixed(s.friction, 1) => {
            format!("{before}→{}", fixed(s.friction, 1))
        }
        _ => fixed(s.friction, 1),
    };
    [
        Line::from(vec![
            dim(" F "),
            Span::raw(force),
            dim(" N  "),
            Span::styled("μN ", Style::new().fg(theme.limit())),
            Span::raw(fixed(solved.bounce.setup.mu * s.normal, 1)),
            dim(" N "),
        ]),
        Line::from(vec![
            dim(" X "),
            Span::raw(fixed(s.x * 1e3, 3)),
            dim(" mm  V "),
            Span::raw(fixed(s.v, 3)),
            dim(" m/s "),
        ]),
        Line::from(vec![
            dim(" ω "),
            Span::raw(fixed(s.omega, 1)),
            dim(" rad/s  slip "),
            Span::raw(fixed(s.slip, 3)),
            dim(" m/s "),
        ]),
    ]
}

pub fn render(frame: &mut Frame, area: Rect, app: &App, solved: &Solved) {
    let theme = &app.theme;
    let bounce = &solved.bounce;
    let ContactLayout {
        cursor_row,
        band_row,
        rows,
        marks,
        scales,
        x,
        label_width,
    } = layout(area, app, solved);

    let (left, right) = cursor_line(app, solved, theme, area.width);
    frame.render_widget(Paragraph::new(left), cursor_row);
    frame.render_widget(Paragraph::new(right).right_aligned(), cursor_row);

    let segments = bounce
        .phases
        .iter()
        .map(|p| Segment {
            from: p.start * 1e3,
            to: p.end * 1e3,
            label: if p.cart == Cart::Stuck {
                format!("{}, {} stuck", p.kind.name(), bounce.params.touched())
            } else {
                p.kind.name().to_string()
            },
            color: theme.phase(p.kind),
        })
        .collect();
    frame.render_widget(
        Band {
            title: "phases",
            x: &x,
            segments,
            label_width,
            title_style: theme.title(),
            marker: theme.marker,
        },
        band_row,
    );

    let titles = [
        (
            Line::from(vec![
                Span::styled(" friction force F (N) ", theme.title()),
                Span::styled("┄ ±μN grip limit ", Style::new().fg(theme.limit())),
            ]),
            Line::from(vec![
                Span::styled(" F (N) ", theme.title()),
                Span::styled("┄ ±μN ", Style::new().fg(theme.limit())),
            ]),
        ),
        (
            Line::from(Span::styled(
                format!(" {} displacement X (mm) ", bounce.params.touched()),
                theme.title(),
            )),
            Line::from(Span::styled(" X (mm) ", theme.title())),
        ),
        (
            Line::from(Span::styled(" ball spin ω (rad/s) ", theme.title())),
            Line::from(Span::styled(" ω (rad/s) ", theme.title())),
        ),
    ];
    for ((((marks, y), (long, short)), readout), row) in marks
        .into_iter()
        .zip(scales)
        .zip(titles)
        .zip(readouts(app, solved, theme))
        .zip(rows)
    {
        // The long title if it fits beside the readout, else the short one; the readout always. The
        // baseline's legend follows the title where there is room.
        let room = usize::from(row.width).saturating_sub(readout.width() + 1);
        let mut title = if long.width() <= room { long } else { short };
        if app.baseline.is_some() {
            let legend = baseline::legend(theme);
            if title.width() + legend.width() <= room {
                title.push_span(legend);
            }
        }
        let plot = Plot {
            title,
            readout: Some(readout),
            x: x.clone(),
            y,
            x_title: X_TITLE,
            marks,
            label_width,
            marker: theme.marker,
            axis_style: theme.dim(),
        };
        frame.render_widget(plot, row);
    }
}
