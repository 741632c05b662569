//! Drawing: one frame from an [`App`], reading only. The screen at 80 x 24 and up:
//!
//! ```text
//! ┌ parameters ─────────────────┐ phases  0 slide 1.32 grip 4.39 slide 5     (timeline, contact view)
//! │▸θ1  incidence angle 60.0 deg│─ friction force F (N) ┄ ±μN ───────────────
//! │ v1  incident speed  10.0 m/s│ 100┤    ⣀⡠⠤⠒⠉
//! │ …   (every parameter)       │   0┤⠤⠒⠉         charts.rs: F, X and ω
//! └─────────────────────────────┘    └┬────┬────┬───   over the contact, or
//! ┌ outcome ────────────────────┐ t (ms)   1    2      sweep.rs: ω2 against θ1
//! │ ω2, v_x2, θ2, e_x, phases,  │─ cart displacement X (mm) ─────────────────
//! │ energy lost to friction     │ …
//! └─────────────────────────────┘─ ball spin ω (rad/s) ───────────────────────
//!  status.rs: message, value prompt or key hints
//! ```
//!
//! help.rs draws its overlay on top, and picker.rs the preset picker; below [`MIN_WIDTH`] x [`MIN_HEIGHT`] only a notice is drawn.

mod baseline;
mod charts;
mod help;
mod outcome;
mod params;
pub mod picker;
pub mod plot;
mod status;
mod sweep;
pub mod theme;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::Line;
use ratatui::widgets::Paragraph;

use super::app::{App, Mode, View};
use crate::model::PARAMS;

/// The smallest terminal the layout is drawn in.
pub const MIN_WIDTH: u16 = 80;
pub const MIN_HEIGHT: u16 = 24;

/// Draws the whole screen.
pub fn draw(frame: &mut Frame, app: &App) {
    let area = frame.area();
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        too_small(frame, area);
        return;
    }
    let status_height = status::height(app, area.width);
    let [main, status_row] =
        Layout::vertical([Constraint::Min(0), Constraint::Length(status_height)]).areas(area);
    let left_width = (area.width * 27 / 100).clamp(35, 44);
    let [left, right] =
        Layout::horizontal([Constraint::Length(left_width), Constraint::Min(0)]).areas(main);
    let params_height = PARAMS.len() as u16 + 2;
    let [params_area, outcome_area] =
        Layout::vertical([Constraint::Length(params_height), Constraint::Min(0)]).areas(left);
    params::render(frame, params_area, app);
    outcome::render(frame, outcome_area, app);
    match app.view {
        View::Contact => charts::render(frame, right, app),
        View::Sweep => sweep::render(frame, right, app),
    }
    status::render(frame, status_row, app);
    if app.mode == Mode::Help {
        help::render(frame, main, app);
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
