//! The sweep view (the paper's Fig. 2): rebound spin omega2 against incidence angle theta1 from 0 to 90
//! degrees for the current parameters, the angles where the ball slides throughout labelled above the
//! chart, and the current theta1 marked.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::plot::{Band, FRAME_ROWS, Mark, Plot, Scale, Segment, tick_budget, y_extent};
use crate::model::PhaseKind;
use crate::tui::app::App;

/// Half the angle step of the sweep: a range's edge lies between its last angle and the next one.
const HALF_STEP: f64 = 45.0 / crate::tui::sweep::Sweep::ANGLES as f64;

pub fn render(frame: &mut Frame, area: Rect, app: &App) {
    let theme = &app.theme;
    let sliding = theme.phase(PhaseKind::Slide);
    let gripping = theme.phase(PhaseKind::Grip);
    let [band_row, chart] =
        Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(area);

    let angle = app.params.angle_deg;
    let omega2 = app.bounce.outcome.omega2;
    let curve = app
        .sweep
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
    let marks = vec![
        Mark::Horizontal(0.0, theme.guide()),
        Mark::Vertical(angle, theme.current()),
        Mark::Path(curve),
        Mark::Dot(angle, omega2, theme.current()),
    ];

    let (low, high) = y_extent(&marks);
    let rows = chart.height.saturating_sub(FRAME_ROWS);
    let y = Scale::rounded(low, high, (usize::from(rows) / 3).clamp(2, 9));
    let x_title = "θ1 (deg)";
    let label_width = y.label_width().max(x_title.chars().count() as u16);
    let (_, data_width) = Plot::data_columns(area, label_width);
    let x = Scale::exact(0.0, 90.0, tick_budget(data_width, 6));

    let mut segments = Vec::new();
    let mut covered = 0.0;
    for (first, last) in app.sweep.sliding_ranges() {
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

    let name = if area.width >= 100 {
        " rebound spin ω2 (rad/s) against incidence angle θ1 "
    } else {
        " ω2 (rad/s) against θ1 "
    };
    let title = Line::from(vec![
        Span::styled(name, theme.title()),
        Span::styled(
            format!("┆ θ1 {angle:.1}°: ω2 {omega2:.1} "),
            Style::new().fg(theme.current()),
        ),
    ]);
    let plot = Plot {
        title,
        readout: None,
        x,
        y,
        x_title,
        marks,
        label_width,
        marker: theme.marker,
        axis_style: theme.dim(),
    };
    frame.render_widget(plot, chart);
}

fn grips(from: f64, to: f64, color: ratatui::style::Color) -> Segment {
    Segment {
        from,
        to,
        label: "grips during contact".into(),
        color,
    }
}
