//! The schematic: a picture of the bounce at the time cursor, drawn on ratatui's Canvas.
//!
//! ```text
//! ┌ t 1.320 ms · grip ───────── ␣ plays 1 ms / 2 s ┐
//! │                    ⢀⡠⠤⠤⢄⡀                      │  the ball, with a mark that turns with it
//! │ ▏                ⢠⠊  ╱   ⠑⡄                    │
//! │ ▏                ⢣  ●    ⡜                     │
//! │ ▏            ◀━━━━━⠑⠤⠤⠤⠊                       │  the friction force on the ball
//! │ ▏╱╲╱╲╱╲╱╲╱╲ ┌──────────────────────────┐       │  the spring and the cart
//! │ ▏───────────┴──────────────────────────┴───────│
//! └ X ×2 · arrow F: 200 N per r ───────────────────┘
//! ```
//!
//! Lengths are in mm and at true scale (the ball's radius and its travel along the surface), except the
//! cart's displacement X, which is magnified by [`Scene::x_scale`] so that it shows; the factor is written
//! under the picture. The ball's travel and its rotation angle are the integrals of v_x and omega,
//! computed numerically from the exact solution ([`crate::tui::travel::Travel`]).
//!
//! With a chain of N masses (`--chain N`) the cart is its first mass, the one the ball touches, and the
//! other N - 1 masses stand between it and the wall, a spring between each pair and from the last to the
//! wall (`--chain 6`, masses 6 to 2 solid, the first mass the open cart under the ball):
//!
//! ```text
//! │ ⣼                         F⢦⡀       ⣠⠞  │
//! │⠨⣺  ⢀⣀⡀  ⣀⣀  ⢀⣀⡀  ⣀⣀  ⢀⣀⡀    ⠭⣷⠦⠤⠤⠤⠖⠋⠁⠤⠤⡄│
//! │⢐⢽⠜⡄⣼⣿⡧⢣⢠⣿⣿⠜⡄⣼⣿⡧⢣⢠⣿⣿⠜⡄⣼⣿⡧⠜⢆⢀⠎⢆⢠⡇        ⡇│
//! │⠠⠻⠤⠬⠼⠿⠧⠤⠥⠿⠿⠤⠬⠼⠿⠧⠤⠥⠿⠿⠤⠬⠼⠿⠧⠤⠤⠥⠤⠤⠥⠧⠤⠤⠤⠤⠤⠤⠤⠤⠧│
//! └ mass 1: X ×2 · F: 200 N per r ──────────┘
//! ```
//!
//! Only the first mass is drawn moving. The other masses move too, in the chain's modes, but what the
//! core gives the explorer ([`crate::model::Sample`], [`crate::model::State`]) holds the first mass's
//! displacement X alone, so masses 2 to N are drawn at their rest positions, not moving, and the spring
//! between the first and the second takes up X. Their widths are a drawing's, not their masses' (all N
//! are M/N); a long chain is drawn closer together and its short springs straight.
//!
//! Which picture it is, the single cart or a chain, tied to the wall or to a free frame, the solved
//! bounce's model says ([`crate::model::Params::model`]); the schematic counts and checks nothing of
//! its own. A free frame (`--frame-mass`, the racquet in the hand) carries the spring's end, drawn
//! moving by the frame's travel and without the wall's hatching.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Circle, Context, Line as Segment};
use ratatui::widgets::{Block, Widget};

use super::charts::fixed;
use crate::model::quadrature::integrate;
use crate::model::{Bounce, FrameKind, ModelKind, PhaseKind, SupportKind};
use crate::tui::app::App;
use crate::tui::solved::Solved;

/// The smallest panel, borders included, the picture is drawn in.
pub const MIN_WIDTH: u16 = 30;
pub const MIN_HEIGHT: u16 = 10;

/// The cart's height, in ball radii.
const CART_HEIGHT: f64 = 0.6;
/// The cart reaches this far beyond the ball's path at each end, in radii.
const CART_OVERHANG: f64 = 0.5;
/// The spring's shortest length as drawn, in radii.
const SPRING_LENGTH: f64 = 1.0;
/// The magnified cart displacement stays within this many radii.
const X_ROOM: f64 = 1.25;
/// Zigzags of the spring.
const COILS: usize = 6;
/// With a chain: the width of each of the other masses, and the length of the springs between them at
/// rest, in radii, while the N - 1 of them fit in [`CHAIN_ROOM`].
const LINK_WIDTH: f64 = 0.25;
const LINK_SPRING: f64 = 0.45;
/// With a chain: the most room, in radii, the other masses and their springs take; a long chain is
/// drawn closer together.
const CHAIN_ROOM: f64 = 3.5;
/// Zigzags of each spring of a chain, at most, and the marker's dots along the spring each one needs.
const LINK_COILS: usize = 2;
const DOTS_PER_COIL: f64 = 4.0;

/// The picture at the cursor, in mm: x along the surface from the point the ball first touches, y up from
/// the cart's top.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Ball radius.
    pub radius: f64,
    /// Ball centre: its travel along the surface (integral of v_x) and one radius up.
    pub centre: (f64, f64),
    /// The ball's rotation angle, rad: the integral of omega. Positive omega turns the ball clockwise as
    /// drawn (topspin for a ball travelling to the right), so the mark turns clockwise from the top.
    pub angle: f64,
    /// The end of the rotation mark on the rim; at t = 0 it points straight up.
    pub mark: (f64, f64),
    /// The cart's left and right edges and its height (its top is y = 0).
    pub cart: (f64, f64),
    pub cart_height: f64,
    /// The wall the spring is fixed to, or the free frame (the racquet in the hand), moved as the cart is.
    pub wall: f64,
    /// The model of the bounce drawn, as it says of itself ([`crate::model::Params::model`]): on a chain,
    /// its other masses are drawn; tied to a free frame, the spring's end moves without the wall's
    /// hatching.
    pub model: ModelKind,
    /// With a chain of N > 1 masses, masses 2 to N (left and right edges, at rest), from the one next to
    /// the cart to the one next to the wall; empty for the single cart.
    pub links: Vec<(f64, f64)>,
    /// Drawn cart displacement per true displacement.
    pub x_scale: f64,
    /// The friction force on the ball, N, positive backward (to the left).
    pub force: f64,
    /// The force an arrow one ball radius long stands for, N.
    pub newtons_per_radius: f64,
    /// The force arrow along the surface (tail at the contact point, head), if long enough to draw.
    pub arrow: Option<((f64, f64), (f64, f64))>,
    pub kind: PhaseKind,
    /// The region the picture needs, before it is widened to the panel's shape.
    pub x_bounds: [f64; 2],
    pub y_bounds: [f64; 2],
}

/// How far the free frame has moved along the surface by `t`, m: the integral of its velocity over the
/// phases (0 on a clamped frame).
fn frame_travel(bounce: &Bounce, t: f64) -> f64 {
    if bounce.params.model().frame == FrameKind::Clamped {
        return 0.0;
    }
    bounce
        .phases
        .iter()
        .filter(|p| p.start < t)
        .map(|p| {
            // Panels a radian of the phase's fastest swing wide, at most a tenth of the phase.
            let panel = (1.0 / p.fastest(&bounce.setup)).min(0.1 * p.duration());
            let velocity = |s: f64| p.motion().frame_velocity(&bounce.setup, s);
            integrate(velocity, p.start, p.end.min(t), panel)
        })
        .sum()
}

/// The 1-2-5 values: ..., 0.5, 1, 2, 5, 10, ...
fn nice(exponent: i32, index: usize) -> f64 {
    [1.0, 2.0, 5.0][index] * 10f64.powi(exponent)
}

/// The smallest 1-2-5 value at least `v` (> 0).
fn nice_up(v: f64) -> f64 {
    let e = v.log10().floor() as i32;
    (0..3)
        .map(|i| nice(e, i))
        .chain(std::iter::once(nice(e + 1, 0)))
        .find(|n| *n >= v * (1.0 - 1e-12))
        .unwrap_or(nice(e + 1, 0))
}

/// The largest 1-2-5 value at most `v` (> 0).
fn nice_down(v: f64) -> f64 {
    let e = v.log10().floor() as i32;
    (0..3)
        .rev()
        .map(|i| nice(e, i))
        .find(|n| *n <= v * (1.0 + 1e-12))
        .unwrap_or(nice(e, 0))
}

impl Scene {
    /// The picture of `app`'s bounce at its time cursor.
    pub fn at(app: &App, solved: &Solved) -> Scene {
        let bounce = &solved.bounce;
        let model = bounce.params.model();
        let r = bounce.setup.r * 1e3;
        let sample = solved.sample_at(app.cursor);
        let (travel, angle) = solved.travel.at(bounce, app.cursor);
        let (travel_min, travel_max) = solved.travel.x_extent();

        let (x_low, x_high) = solved
            .series
            .iter()
            .fold((0.0f64, 0.0f64), |(lo, hi), s| (lo.min(s.x), hi.max(s.x)));
        let x_max = (x_high.max(-x_low)) * 1e3;
        let x_scale = if x_max > 0.0 {
            nice_down(X_ROOM * r / x_max)
        } else {
            1.0
        };
        let f_max = solved
            .series
            .iter()
            .map(|s| s.friction.abs())
            .fold(0.0, f64::max);
        let newtons_per_radius = if f_max > 0.0 { nice_up(f_max) } else { 1.0 };

        let centre = (travel * 1e3, r);
        let mark = (centre.0 + r * angle.sin(), centre.1 + r * angle.cos());
        // A free frame carries the spring's end, and the cart with it (its x is the stretch).
        let frame_shift = x_scale * frame_travel(bounce, app.cursor) * 1e3;
        let frame_reach = x_scale * frame_travel(bounce, bounce.setup.duration).max(0.0) * 1e3;
        let shift = frame_shift + x_scale * sample.x * 1e3;
        let rest_left = travel_min * 1e3 - CART_OVERHANG * r;
        let rest_right = travel_max * 1e3 + CART_OVERHANG * r;
        // The room the cart's spring needs beside its shortest length as drawn, so that it keeps that
        // length even when the cart moves towards the wall.
        let toward_wall = -x_scale * x_low.min(0.0) * 1e3;
        // A chain's other masses (all but the first, which is drawn as the cart) at rest, spaced
        // evenly from the cart's spring to the wall's.
        let others = match model.support {
            SupportKind::Cart => 0,
            SupportKind::Chain => bounce.params.chain as usize - 1,
        };
        let (width, spring) = if others == 0 {
            (0.0, SPRING_LENGTH * r)
        } else {
            let pitch = (LINK_WIDTH + LINK_SPRING).min(CHAIN_ROOM / others as f64);
            let width = pitch * LINK_WIDTH / (LINK_WIDTH + LINK_SPRING);
            (width * r, (pitch - width) * r)
        };
        let mut links = Vec::with_capacity(others);
        let mut right = rest_left - spring - toward_wall;
        for _ in 0..others {
            links.push((right - width, right));
            right -= width + spring;
        }
        let wall = right;
        let length = -sample.friction / newtons_per_radius * r;
        // Along the surface from the contact point.
        let arrow =
            (length.abs() > 0.03 * r).then_some(((centre.0, 0.0), (centre.0 + length, 0.0)));
        Scene {
            radius: r,
            centre,
            angle,
            mark,
            cart: (rest_left + shift, rest_right + shift),
            cart_height: CART_HEIGHT * r,
            wall: wall + frame_shift,
            model,
            links,
            x_scale,
            force: sample.friction,
            newtons_per_radius,
            arrow,
            kind: sample.kind,
            x_bounds: [
                wall - 0.25 * r,
                rest_right + x_scale * x_high.max(0.0) * 1e3 + frame_reach + 0.1 * r,
            ],
            y_bounds: [-(CART_HEIGHT + 0.15) * r, 2.1 * r],
        }
    }

    /// The x-factor as written under the picture: `×2`, `×0.5`.
    pub fn x_scale_label(&self) -> String {
        format!("×{}", self.x_scale)
    }
}

/// The dots a cell holds across and up with `marker`.
fn dots_per_cell(marker: Marker) -> (f64, f64) {
    match marker {
        Marker::Braille | Marker::Octant => (2.0, 4.0),
        Marker::Sextant => (2.0, 3.0),
        Marker::Quadrant => (2.0, 2.0),
        Marker::HalfBlock => (1.0, 2.0),
        _ => (1.0, 1.0),
    }
}

/// `x` and `y` widened about their centres so that a unit across is a unit up on a panel of
/// `width` x `height` cells, a cell being twice as tall as wide.
fn fit(x: [f64; 2], y: [f64; 2], width: u16, height: u16) -> ([f64; 2], [f64; 2]) {
    let (w, h) = (f64::from(width.max(1)), f64::from(height.max(1)));
    let per_column = (x[1] - x[0]) / w;
    let per_row = (y[1] - y[0]) / h;
    if per_row < 2.0 * per_column {
        let half = per_column * h;
        let mid = 0.5 * (y[0] + y[1]);
        (x, [mid - half, mid + half])
    } else {
        let half = per_row * w / 4.0;
        let mid = 0.5 * (x[0] + x[1]);
        ([mid - half, mid + half], y)
    }
}

/// A spring as a zigzag of `coils` from `from` to `to`, at height `y`.
fn spring(
    ctx: &mut Context,
    (from, to): (f64, f64),
    y: f64,
    amplitude: f64,
    coils: usize,
    color: Color,
) {
    if coils == 0 {
        ctx.draw(&Segment::new(from, y, to, y, color));
        return;
    }
    let length = to - from;
    let lead = 0.1 * length;
    let step = (length - 2.0 * lead) / (2 * coils) as f64;
    let mut points = vec![(from, y), (from + lead, y)];
    for i in 0..2 * coils {
        let side = if i % 2 == 0 { 1.0 } else { -1.0 };
        points.push((from + lead + step * (i as f64 + 0.5), y + side * amplitude));
    }
    points.push((to - lead, y));
    points.push((to, y));
    for pair in points.windows(2) {
        ctx.draw(&Segment::new(
            pair[0].0, pair[0].1, pair[1].0, pair[1].1, color,
        ));
    }
}

/// `dot` is the size of the marker's dots across and up, for filled shapes and for springs too short
/// to zigzag.
fn paint(ctx: &mut Context, scene: &Scene, app: &App, x_bounds: [f64; 2], dot: (f64, f64)) {
    let theme = &app.theme;
    let r = scene.radius;
    let h = scene.cart_height;
    let guide = theme.guide();
    // The floor, and the wall with its hatching.
    ctx.draw(&Segment::new(scene.wall, -h, x_bounds[1], -h, guide));
    let wall_top = 0.6 * r;
    ctx.draw(&Segment::new(scene.wall, -h, scene.wall, wall_top, guide));
    let hatch = 0.2 * r;
    let mut y = -h;
    while scene.model.frame == FrameKind::Clamped && y + hatch <= wall_top {
        ctx.draw(&Segment::new(
            scene.wall,
            y + hatch,
            scene.wall - hatch,
            y,
            guide,
        ));
        y += hatch;
    }
    // The springs: wall to cart, or along a chain from the wall through masses N to 2 to the cart. A
    // chain's springs zigzag as much as their length in dots allows, down to a straight line.
    let coils = |from: f64, to: f64| match scene.model.support {
        SupportKind::Cart => COILS,
        SupportKind::Chain => (((to - from) / dot.0 / DOTS_PER_COIL) as usize).min(LINK_COILS),
    };
    let mut from = scene.wall;
    for &(left, right) in scene.links.iter().rev() {
        let turns = coils(from, left);
        spring(ctx, (from, left), -0.5 * h, 0.3 * h, turns, theme.spring());
        // Solid, so that a mass reads apart from the springs at any length of chain.
        let mut y = -h;
        while y <= 0.0 {
            ctx.draw(&Segment::new(left, y, right, y, theme.body()));
            y += dot.1.max(h / 64.0);
        }
        from = right;
    }
    let turns = coils(from, scene.cart.0);
    spring(
        ctx,
        (from, scene.cart.0),
        -0.5 * h,
        0.3 * h,
        turns,
        theme.spring(),
    );
    // The cart; its top is left open under the force arrow, which is drawn along it.
    let (left, right) = scene.cart;
    let body = theme.body();
    ctx.draw(&Segment::new(left, -h, right, -h, body));
    ctx.draw(&Segment::new(left, -h, left, 0.0, body));
    ctx.draw(&Segment::new(right, -h, right, 0.0, body));
    match scene.arrow {
        Some(((tx, _), (hx, _))) => {
            let (a, b) = (tx.min(hx), tx.max(hx));
            ctx.draw(&Segment::new(left, 0.0, a.max(left), 0.0, body));
            ctx.draw(&Segment::new(b.min(right), 0.0, right, 0.0, body));
        }
        None => ctx.draw(&Segment::new(left, 0.0, right, 0.0, body)),
    }
    ctx.layer();

    let (cx, cy) = scene.centre;
    ctx.draw(&Circle::new(cx, cy, r, theme.body()));
    ctx.draw(&Segment::new(
        cx,
        cy,
        scene.mark.0,
        scene.mark.1,
        theme.cursor(),
    ));
    // A short cross-bar at the tip, so the mark reads as a mark at any resolution.
    let (sin, cos) = scene.angle.sin_cos();
    let bar = 0.15 * r;
    let inner = (cx + 0.85 * r * sin, cy + 0.85 * r * cos);
    ctx.draw(&Segment::new(
        inner.0 - bar * cos,
        inner.1 + bar * sin,
        inner.0 + bar * cos,
        inner.1 - bar * sin,
        theme.cursor(),
    ));
    if let Some(((tx, ty), (hx, hy))) = scene.arrow {
        let color = theme.phase(scene.kind);
        ctx.draw(&Segment::new(tx, ty, hx, hy, color));
        let back = if hx < tx { 1.0 } else { -1.0 };
        let head = (0.2 * r).min(0.5 * (hx - tx).abs());
        for side in [1.0, -1.0] {
            ctx.draw(&Segment::new(
                hx,
                hy,
                hx + back * head,
                hy + side * 0.5 * head,
                color,
            ));
        }
        // Named beyond its head, for screens without colour.
        let beyond = if hx < tx { -0.15 * r } else { 0.1 * r };
        ctx.print(
            hx + beyond,
            hy + 0.1 * r,
            Span::styled("F", Style::new().fg(color)),
        );
    }
}

pub fn render(frame: &mut Frame, area: Rect, app: &App, solved: &Solved) {
    let theme = &app.theme;
    let scene = Scene::at(app, solved);
    let wide = area.width >= 40;
    let title = Line::from(vec![
        Span::styled(
            format!(" t {} ms · ", fixed(app.cursor * 1e3, 3)),
            theme.title(),
        ),
        Span::styled(
            format!("{} ", scene.kind.name()),
            Style::new().fg(theme.phase(scene.kind)),
        ),
    ]);
    let state = match (app.playing, wide) {
        (true, _) => "▶ ",
        (false, true) => "␣ plays ",
        (false, false) => "␣ ",
    };
    let speed = Line::from(vec![
        Span::styled(
            state,
            if app.playing {
                theme.key()
            } else {
                theme.dim()
            },
        ),
        Span::raw(format!("{} ", app.speed.label())),
    ]);
    let caption = if wide && scene.model.support == SupportKind::Chain {
        // A chain: X, the one displacement drawn, is the first mass's.
        format!(
            " mass 1: X {} · F: {} N per r ",
            scene.x_scale_label(),
            scene.newtons_per_radius
        )
    } else if wide {
        format!(
            " X {} · arrow F: {} N per r ",
            scene.x_scale_label(),
            scene.newtons_per_radius
        )
    } else {
        format!(
            " X{} · F {} N/r ",
            scene.x_scale_label(),
            scene.newtons_per_radius
        )
    };
    let block = Block::bordered()
        .title(title)
        .title(speed.right_aligned())
        .title_bottom(Line::styled(caption, theme.dim()));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let (x_bounds, y_bounds) = fit(scene.x_bounds, scene.y_bounds, inner.width, inner.height);
    let (across, up) = dots_per_cell(theme.marker);
    let dot = (
        (x_bounds[1] - x_bounds[0]) / (across * f64::from(inner.width.max(1))),
        (y_bounds[1] - y_bounds[0]) / (up * f64::from(inner.height.max(1))),
    );
    Canvas::default()
        .marker(theme.marker)
        .x_bounds(x_bounds)
        .y_bounds(y_bounds)
        .paint(|ctx| paint(ctx, &scene, app, x_bounds, dot))
        .render(inner, frame.buffer_mut());
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Params, solve};

    #[test]
    fn the_free_frame_travels_at_its_velocity_and_a_clamped_one_stays() {
        let free = solve(&Params {
            frame_mass: 0.188,
            frame_normal_mass: 0.181,
            ..Params::default()
        })
        .unwrap();
        let t = free.setup.duration;
        let h = 1e-7;
        let rate = (frame_travel(&free, t) - frame_travel(&free, t - h)) / h;
        assert!((rate - free.frame_velocity()).abs() < 1e-4 * free.frame_velocity().abs());
        assert!(frame_travel(&free, t) > 0.0);
        assert_eq!(frame_travel(&solve(&Params::default()).unwrap(), t), 0.0);
    }

    #[test]
    fn nice_values() {
        assert_eq!(nice_up(150.0), 200.0);
        assert_eq!(nice_up(200.0), 200.0);
        assert_eq!(nice_up(0.3), 0.5);
        assert_eq!(nice_up(7.0), 10.0);
        assert_eq!(nice_down(2.4), 2.0);
        assert_eq!(nice_down(0.7), 0.5);
        assert_eq!(nice_down(19.0), 10.0);
    }

    #[test]
    fn fitting_keeps_circles_round() {
        let (x, y) = fit([0.0, 100.0], [0.0, 20.0], 50, 20);
        // 2 mm a column: 4 mm a row.
        assert_eq!(x, [0.0, 100.0]);
        assert!(((y[1] - y[0]) / 20.0 - 4.0).abs() < 1e-12);
        let (x, y) = fit([0.0, 10.0], [0.0, 80.0], 50, 20);
        assert_eq!(y, [0.0, 80.0]);
        assert!(((x[1] - x[0]) / 50.0 - 2.0).abs() < 1e-12);
    }
}
