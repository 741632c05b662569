//! Drawing: one frame from an [`App`], reading only. The screen at 80 x 24 and up:
//!
//! ```text
//! ┌ parameters ─────────────────┐ t 1.320 ms · grip          ␣ plays 1 ms / 2 s  (cursor, contact view)
//! │▸θ1  incidence angle 60.0 deg│ phases  0 slide 1.32 grip 4.39 slide 5     (timeline, contact view)
//! │ v1  incident speed  10.0 m/s│─ F (N) ┄ ±μN ─────────────── F 95.3 N  μN 120.4 N
//! │ …   (every parameter)       │ 100┤    ⣀⡠⠤⠒⠉ ┃
//! └─────────────────────────────┘   0┤⠤⠒⠉      ┃   charts.rs: F, X and ω over the
//! ┌ outcome ────────────────────┐    └┬────┬────┬───   contact with the time cursor, or
//! │ ω2, v_x2, θ2, e_x, phases,  │ t (ms)   1    2      sweep.rs: ω2 against θ1, or
//! │                             │                      heatmap.rs: ω2 over M and k
//! │ energy lost to friction     │─ X (mm) ──────────────────── X 4.213 mm  V 1.234 m/s
//! └─────────────────────────────┘ …
//! ┌ t 1.320 ms · grip ──────────┐
//! │ schematic.rs: the bounce at │─ ω (rad/s) ──────────── ω 12.3 rad/s  slip 0.000 m/s
//! │ the time cursor (when the   │ …
//! │ left column has room)       │
//! └─────────────────────────────┘
//!  status.rs: message, value prompt or key hints
//! ```
//!
//! help.rs draws its overlay on top, and picker.rs the preset picker; below [`MIN_WIDTH`] x [`MIN_HEIGHT`] only a notice is drawn.
//! Panels whose answer takes longer than [`crate::tui::app::STALE_AFTER`] are marked "solving…" and the
//! outcome dimmed (stale.rs); before the first answer they hold the mark alone.

mod baseline;
mod charts;
mod court;
mod heatmap;
mod help;
mod measured;
mod outcome;
mod overlay;
mod params;
pub mod picker;
pub mod plot;
mod residuals;
pub mod schematic;
mod stale;
mod status;
mod sweep;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::Line;
use ratatui::widgets::Paragraph;

pub use charts::fixed;

use super::app::App;
use super::vocabulary::{Mode, View};

/// The smallest terminal the layout is drawn in.
pub const MIN_WIDTH: u16 = 80;
pub const MIN_HEIGHT: u16 = 24;

/// True when a screen of `area` is large enough for the layout (else only a notice is drawn).
pub fn fits(area: Rect) -> bool {
    area.width >= MIN_WIDTH && area.height >= MIN_HEIGHT
}

/// Where each part of the screen goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Regions {
    pub params: Rect,
    pub outcome: Rect,
    /// The schematic, when the left column has room for it under the outcome.
    pub schematic: Option<Rect>,
    /// The contact charts or the sweep.
    pub view: Rect,
    pub status: Rect,
}

/// The layout of a screen of `area`; `None` below the smallest size.
pub fn regions(area: Rect, app: &App) -> Option<Regions> {
    if !fits(area) {
        return None;
    }
    let status_height = status::height(app, area.width);
    let [main, status] =
        Layout::vertical([Constraint::Min(0), Constraint::Length(status_height)]).areas(area);
    let left_width = (area.width * 27 / 100).clamp(35, 44);
    let [left, view] =
        Layout::horizontal([Constraint::Length(left_width), Constraint::Min(0)]).areas(main);
    // The outcome gets the rows it needs first; on a short screen the parameter list scrolls.
    let outcome_height = outcome::height(app, left_width);
    let params_height = params::height(app).min(
        left.height
            .saturating_sub(outcome_height)
            .max(params::MIN_HEIGHT),
    );
    let [params, rest] =
        Layout::vertical([Constraint::Length(params_height), Constraint::Min(0)]).areas(left);
    let (outcome, schematic) = if rest.height >= outcome_height + schematic::MIN_HEIGHT
        && left_width >= schematic::MIN_WIDTH
    {
        let [outcome, schematic] =
            Layout::vertical([Constraint::Length(outcome_height), Constraint::Min(0)]).areas(rest);
        (outcome, Some(schematic))
    } else {
        (rest, None)
    };
    Some(Regions {
        params,
        outcome,
        schematic,
        view,
        status,
    })
}

/// True when the schematic is drawn on a screen of `area`.
pub fn schematic_shown(area: Rect, app: &App) -> bool {
    regions(area, app).is_some_and(|r| r.schematic.is_some())
}

/// The time, s, under the cell (`column`, `row`) of a screen of `area`, if that is on the contact charts.
pub fn time_at(area: Rect, app: &App, column: u16, row: u16) -> Option<f64> {
    let regions = regions(area, app)?;
    if app.view != View::Contact || app.mode == Mode::Help {
        return None;
    }
    charts::time_at(regions.view, app, app.solved.as_deref()?, column, row)
}

/// Draws the whole screen.
pub fn draw(frame: &mut Frame, app: &App) {
    let area = frame.area();
    let Some(regions) = regions(area, app) else {
        too_small(frame, area);
        return;
    };
    params::render(frame, regions.params, app);
    let stale = app.stale() && app.stale_marked;
    let view_stale = match app.view {
        View::Sweep => app.stale() || app.sweeps_stale(),
        View::Contact | View::Heatmap => app.stale(),
        View::Shot => app.shot_stale(),
    };
    match app.solved.as_deref() {
        Some(solved) => {
            outcome::render(frame, regions.outcome, app, solved);
            if let Some(schematic) = regions.schematic {
                schematic::render(frame, schematic, app, solved);
            }
            match (app.view, app.sweeps.as_deref()) {
                (View::Contact, _) => charts::render(frame, regions.view, app, solved),
                (View::Sweep, Some(sweeps)) => {
                    sweep::render(frame, regions.view, app, solved, sweeps)
                }
                (View::Sweep, None) => stale::pending(frame, regions.view, app, app.view.name()),
                (View::Heatmap, _) => heatmap::render(frame, regions.view, app, solved),
                (View::Shot, _) => court::render(frame, regions.view, app),
            }
            if stale {
                stale::dim(frame, regions.outcome, app);
                if let Some(schematic) = regions.schematic {
                    stale::mark(frame, schematic, app);
                }
            }
            let drawn = match app.view {
                View::Sweep => app.sweeps.is_some(),
                View::Shot => app.shots.shown.is_some(),
                View::Contact | View::Heatmap => true,
            };
            if view_stale && drawn && app.stale_marked {
                stale::mark(frame, regions.view, app);
            }
        }
        None => {
            stale::pending(frame, regions.outcome, app, "outcome");
            if let Some(schematic) = regions.schematic {
                stale::pending(frame, schematic, app, "schematic");
            }
            stale::pending(frame, regions.view, app, app.view.name());
        }
    }
    status::render(frame, regions.status, app, regions.schematic.is_some());
    // Overlays cover everything above the status line.
    let main = Rect {
        height: regions.status.y - area.y,
        ..area
    };
    if app.mode == Mode::Help {
        help::render(frame, main, app, regions.schematic.is_some());
    }
    if let Mode::Picker(_) = app.mode {
        picker::render(frame, main, app);
    }
}

fn too_small(frame: &mut Frame, area: Rect) {
    let lines = vec![
        Line::from(format!(
            "terminal too small: need {MIN_WIDTH} x {MIN_HEIGHT}"
        )),
        Line::from(format!("(now {} x {}; q quits)", area.width, area.height)),
    ];
    let height = (lines.len() as u16).min(area.height);
    let y = area.y + area.height.saturating_sub(height) / 2;
    frame.render_widget(
        Paragraph::new(lines).centered(),
        Rect::new(area.x, y, area.width, height),
    );
}
