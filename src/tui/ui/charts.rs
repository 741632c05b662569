//! The contact view (the paper's Fig. 3): the phase timeline over three stacked charts sharing the time
//! axis in ms: friction force F with the grip limit +/- mu N, cart displacement X and ball spin omega.
//! Curves take the colour of their phase; dashed verticals mark the transitions.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::baseline;
use super::plot::{Band, FRAME_ROWS, Mark, Plot, Scale, Segment, tick_budget, y_extent};
use crate::model::Sample;
use crate::tui::app::App;

/// Points of the dashed grip-limit envelope.
const ENVELOPE_POINTS: usize = 200;

/// y ticks that fit `rows` rows of plot: about one every other row, at most 7.
fn y_budget(rows: u16) -> usize {
    (usize::from(rows) + 2).div_ceil(2).clamp(2, 7)
}

pub fn render(frame: &mut Frame, area: Rect, app: &App) {
    let theme = &app.theme;
    let bounce = &app.bounce;
    let [band_row, charts] =
        Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(area);
    let rows: [Rect; 3] = Layout::vertical([Constraint::Fill(1); 3]).areas(charts);

    let ms = |s: &Sample| s.t * 1e3;
    let path = |value: fn(&Sample) -> f64| {
        Mark::Path(
            app.series
                .iter()
                .map(|s| (ms(s), value(s), theme.phase(s.kind)))
                .collect(),
        )
    };
    // The pinned baseline, if any, under the current curve.
    let faint = |value: fn(&Sample) -> f64| match &app.baseline {
        Some(b) => {
            let points: Vec<(f64, f64)> = b.series.iter().map(|s| (ms(s), value(s))).collect();
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
    displacement.push(path(|s| s.x * 1e3));
    let mut spin = vec![zero];
    spin.extend(faint(|s| s.omega));
    spin.push(path(|s| s.omega));
    for marks in [&mut force, &mut displacement, &mut spin] {
        marks.extend(transitions.iter().cloned());
    }

    let mut titles = [
        Line::from(vec![
            Span::styled(" friction force F (N) ", theme.title()),
            Span::styled("┄ ±μN grip limit ", Style::new().fg(theme.limit())),
        ]),
        Line::from(Span::styled(" cart displacement X (mm) ", theme.title())),
        Line::from(Span::styled(" ball spin ω (rad/s) ", theme.title())),
    ];
    if app.baseline.is_some() {
        for title in &mut titles[1..] {
            title.push_span(baseline::legend(theme));
        }
    }
    let scales: Vec<Scale> = [&force, &displacement, &spin]
        .iter()
        .zip(rows)
        .map(|(marks, row)| {
            let (low, high) = y_extent(marks);
            Scale::rounded(low, high, y_budget(row.height.saturating_sub(FRAME_ROWS)))
        })
        .collect();
    let x_title = "t (ms)";
    let label_width = scales
        .iter()
        .map(Scale::label_width)
        .max()
        .unwrap_or(0)
        .max(x_title.len() as u16);
    let (_, data_width) = Plot::data_columns(area, label_width);
    // Time runs to the end of the longer contact when a baseline is pinned.
    let end = app
        .baseline
        .as_ref()
        .map_or(duration, |b| b.bounce.setup.duration.max(duration));
    let x = Scale::exact(0.0, end * 1e3, tick_budget(data_width, 6));

    let segments = bounce
        .phases
        .iter()
        .map(|p| Segment {
            from: p.start * 1e3,
            to: p.end * 1e3,
            label: p.kind.name().to_string(),
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
    for (((marks, y), title), row) in [force, displacement, spin]
        .into_iter()
        .zip(scales)
        .zip(titles)
        .zip(rows)
    {
        let plot = Plot {
            title,
            x: x.clone(),
            y,
            x_title,
            marks,
            label_width,
            marker: theme.marker,
            axis_style: theme.dim(),
        };
        frame.render_widget(plot, row);
    }
}
