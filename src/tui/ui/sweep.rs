//! The sweep view (the paper's Fig. 2): rebound spin omega2 against incidence angle theta1 from 0 to 90
//! degrees for the current parameters, the angles where the ball slides throughout labelled above the
//! chart, and the current theta1 marked. A dashed curve gives omega2 for the comparison incident spin
//! (omega1 = 0, or -100 rad/s when the current spin is 0), and the title's right end the angles where the
//! two curves cross: the paper's backspin crossover. With `--data` the measured omega2 are drawn on the
//! curve they were measured on, and with an input typed with an uncertainty, omega2's band; a legend
//! under the chart says what they are (`measured`).

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::plot::{Band, FRAME_ROWS, Mark, Plot, Scale, Segment, tick_budget, y_extent};
use super::{baseline, measured};
use crate::model::PhaseKind;
use crate::tui::app::App;
use crate::tui::solved::Solved;
use crate::tui::sweep::{Sweep, Sweeps};

/// Half the angle step of the sweep: a range's edge lies between its last angle and the next one.
const HALF_STEP: f64 = 45.0 / crate::tui::sweep::Sweep::ANGLES as f64;

pub fn render(frame: &mut Frame, area: Rect, app: &App, solved: &Solved, sweeps: &Sweeps) {
    let theme = &app.theme;
    let sliding = theme.phase(PhaseKind::Slide);
    let gripping = theme.phase(PhaseKind::Grip);
    let key = sweeps.key;
    let measured = measured::on_sweep(app, &key);
    let notes: Vec<Line> = measured
        .iter()
        .map(|m| measured::sweep_legend(m, theme, Sweep::comparison_spin(key.spin), area.width))
        .chain(measured::band_legend(app, &key, area.width))
        .collect();
    let [band_row, chart, notes_rows] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Min(0),
        Constraint::Length(notes.len() as u16),
    ])
    .areas(area);

    let angle = app.params.angle_deg;
    let omega2 = solved.bounce.outcome.omega2;
    let curve = sweeps
        .current
        .points
        .iter()
        .map(|p| {
            let color = if p.slides_throughout {
                sliding
            } else {
                gripping
            };
            (p.angle_deg, p.omega2, color)
        })
        .collect();
    let comparison = sweeps
        .comparison
        .points
        .iter()
        .map(|p| (p.angle_deg, p.omega2))
        .collect();
    let mut marks = vec![
        Mark::Horizontal(0.0, theme.guide()),
        Mark::Vertical(angle, theme.current()),
        Mark::Dashed(comparison, theme.comparison()),
    ];
    if let Some(b) = app.baseline_sweeps() {
        let points: Vec<(f64, f64)> = b
            .current
            .points
            .iter()
            .map(|p| (p.angle_deg, p.omega2))
            .collect();
        marks.extend(baseline::curve(&points, theme, area.width));
    }
    marks.extend(measured::band_marks(app, &key));
    marks.extend([Mark::Path(curve), Mark::Dot(angle, omega2, theme.current())]);
    if let Some(found) = &measured {
        marks.extend(measured::sweep_marks(found, theme));
    }

    let (low, high) = y_extent(&marks);
    let rows = chart.height.saturating_sub(FRAME_ROWS);
    let y = Scale::rounded(low, high, (usize::from(rows) / 3).clamp(2, 9));
    let x_title = "θ1 (deg)";
    let label_width = y.label_width().max(x_title.chars().count() as u16);
    let (_, data_width) = Plot::data_columns(area, label_width);
    let x = Scale::exact(0.0, 90.0, tick_budget(data_width, 6));

    let mut segments = Vec::new();
    let mut covered = 0.0;
    for (first, last) in sweeps.current.sliding_ranges() {
        // The sweep starts half a step above zero: a range from its first angle starts at zero.
        let from = if first <= 2.0 * HALF_STEP {
            0.0
        } else {
            first - HALF_STEP
        };
        let to = (last + HALF_STEP).min(90.0);
        if from > covered {
            segments.push(grips(covered, from, gripping));
        }
        segments.push(Segment {
            from,
            to,
            label: "slides throughout".into(),
            color: sliding,
        });
        covered = to;
    }
    if covered < 90.0 {
        segments.push(grips(covered, 90.0, gripping));
    }
    frame.render_widget(
        Band {
            title: "regime",
            x: &x,
            segments,
            label_width,
            title_style: theme.title(),
            marker: theme.marker,
        },
        band_row,
    );

    // The title and the comparison legend, the longest forms that fit side by side.
    let current = Style::new().fg(theme.current());
    let titles = [
        Line::from(vec![
            Span::styled(
                " rebound spin ω2 (rad/s) against incidence angle θ1 ",
                theme.title(),
            ),
            Span::styled(format!("┆ θ1 {angle:.1}°: ω2 {omega2:.1} "), current),
        ]),
        Line::from(vec![
            Span::styled(" ω2 (rad/s) ", theme.title()),
            Span::styled(format!("┆ θ1 {angle:.1}°: ω2 {omega2:.1} "), current),
        ]),
        Line::from(vec![
            Span::styled(" ω2 ", theme.title()),
            Span::styled(format!("┆ θ1 {angle:.1}°: {omega2:.1} "), current),
        ]),
    ];
    let crossings: Vec<String> = sweeps
        .current
        .crossings(&sweeps.comparison)
        .iter()
        .map(|a| format!("{a:.1}°"))
        .collect();
    let other = Sweep::comparison_spin(sweeps.key.spin);
    let legends = if crossings.is_empty() {
        [
            format!(" ┄ ω1 = {other:.0} rad/s: no crossing "),
            format!(" ┄ ω1={other:.0}: no crossing "),
            format!(" ┄ ω1={other:.0} "),
        ]
    } else {
        let at = crossings.join(", ");
        [
            format!(" ┄ ω1 = {other:.0} rad/s: crosses at {at} "),
            format!(" ┄ ω1={other:.0} crosses {at} "),
            format!(" ┄ ω1={other:.0} "),
        ]
    };
    let room = usize::from(chart.width).saturating_sub(1);
    let (title, legend) = [(0, 0), (1, 0), (1, 1), (2, 1), (2, 2)]
        .into_iter()
        .map(|(t, l)| (&titles[t], &legends[l]))
        .find(|(t, l)| t.width() + l.chars().count() <= room)
        .unwrap_or((&titles[2], &legends[2]));
    let mut title = title.clone();
    if app.baseline.is_some() && area.width >= 100 {
        title.push_span(baseline::legend(theme));
    }
    let readout = Line::from(Span::styled(
        legend.clone(),
        Style::new().fg(theme.comparison()),
    ));
    let plot = Plot {
        title,
        readout: Some(readout),
        x,
        y,
        x_title,
        marks,
        label_width,
        marker: theme.marker,
        axis_style: theme.dim(),
    };
    frame.render_widget(plot, chart);
    frame.render_widget(Paragraph::new(notes), notes_rows);
}

fn grips(from: f64, to: f64, color: ratatui::style::Color) -> Segment {
    Segment {
        from,
        to,
        label: "grips during contact".into(),
        color,
    }
}
