//! The outcome panel: the rebound (omega2 with rpm, v_x2, theta2, e_x), the share of the incoming energy
//! lost to friction, the phase timeline in ms and, when there is room, a few more numbers; with
//! `--data`, the residuals of the measurements last (residuals.rs).

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use crate::model::{BallPhase, Bounce};
use crate::tui::app::App;
use crate::tui::baseline::signed;
use crate::tui::solved::Solved;
use crate::tui::theme::Theme;

/// Phases listed before the rest are summarised as a count.
const LISTED_PHASES: usize = 6;

/// A time in ms for the timeline with `decimals` places: `0`, `1.32`.
fn ms(t: f64, decimals: usize) -> String {
    if t == 0.0 {
        "0".into()
    } else {
        format!("{:.*}", decimals, t * 1e3)
    }
}

/// Two decimals, or up to four when fewer would show a phase as starting where it ends.
fn timeline_decimals(phases: &[BallPhase]) -> usize {
    (2..=4)
        .find(|&d| phases.iter().all(|p| ms(p.start, d) != ms(p.end, d)))
        .unwrap_or(4)
}

/// The ball's phases as `slide 0-1.32, grip 1.32-4.39, ...`, each in its phase's colour.
pub fn timeline(bounce: &Bounce, theme: &Theme) -> Vec<Span<'static>> {
    let phases = bounce.ball_phases();
    let decimals = timeline_decimals(&phases);
    let mut spans = Vec::new();
    for (i, p) in phases.iter().take(LISTED_PHASES).enumerate() {
        if i > 0 {
            spans.push(Span::raw(", "));
        }
        spans.push(Span::styled(
            format!(
                "{} {}-{}",
                p.kind.name(),
                ms(p.start, decimals),
                ms(p.end, decimals)
            ),
            Style::new().fg(theme.phase(p.kind)),
        ));
    }
    let more = phases.len().saturating_sub(LISTED_PHASES);
    if more > 0 {
        spans.push(Span::raw(format!(", … {more} more")));
    }
    spans
}

/// The sequence of phases, `slide-grip-slide`; past [`LISTED_PHASES`] the first of them and the count,
/// so that a chattering grip of hundreds of phases keeps the panel short.
fn summary(bounce: &Bounce) -> String {
    let all = bounce.phase_summary();
    let kinds: Vec<&str> = all.split('-').collect();
    if kinds.len() <= LISTED_PHASES {
        return all;
    }
    format!(
        "{}-… ({} phases)",
        kinds[..LISTED_PHASES].join("-"),
        kinds.len()
    )
}

/// Rows a line of text takes when wrapped at word boundaries into `width` columns.
fn wrapped_rows(line: &Line, width: usize) -> usize {
    let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
    let mut rows = 1;
    let mut used = 0;
    for word in text.split(' ') {
        let len = word.chars().count();
        let needed = if used == 0 { len } else { used + 1 + len };
        if needed <= width || used == 0 {
            used = needed;
        } else {
            rows += 1;
            used = len;
        }
        while used > width {
            rows += 1;
            used -= width;
        }
    }
    rows
}

/// Rows the panel needs, borders included, when it is `width` columns wide.
pub fn height(app: &App, width: u16) -> u16 {
    let inner = usize::from(width.saturating_sub(2)).max(1);
    let Some(solved) = &app.solved else {
        return PENDING_HEIGHT;
    };
    let rows: usize = lines(app, solved, inner >= 40)
        .iter()
        .map(|l| wrapped_rows(l, inner))
        .sum();
    rows as u16 + 2
}

/// Rows the panel takes before the first bounce is solved.
const PENDING_HEIGHT: u16 = 6;

pub fn render(frame: &mut Frame, area: Rect, app: &App, solved: &Solved) {
    let theme = &app.theme;
    let block = Block::bordered().title(Span::styled(" outcome ", theme.title()));
    let inner = block.inner(area);
    let wide = inner.width >= 40;
    frame.render_widget(
        Paragraph::new(lines(app, solved, wide))
            .block(block)
            .wrap(Wrap { trim: false }),
        area,
    );
}

/// The panel's lines: long labels and the extra numbers when `wide`.
fn lines(app: &App, solved: &Solved, wide: bool) -> Vec<Line<'static>> {
    let theme = &app.theme;
    let b = &solved.bounce;
    let o = &b.outcome;
    let e = &solved.energy;
    let label = |short: &'static str, long: &'static str| {
        let text = theme.words(if wide { long } else { short });
        Span::styled(
            format!("{text:<w$}", w = if wide { 18 } else { 9 }),
            theme.dim(),
        )
    };
    let rpm = o.omega2 * 30.0 / std::f64::consts::PI;
    let ex =
        o.ex.map_or("none (no slip in)".to_string(), |ex| format!("{ex:.3}"));
    let friction_share = 100.0 * e.friction_loss / e.initial;
    let spin = Line::from(vec![
        label("ω2", "rebound spin ω2"),
        Span::styled(format!("{:.1} rad/s", o.omega2), theme.emphasis()),
        Span::raw(format!(" ({rpm:.0} rpm)")),
    ]);
    let vx2 = vec![
        label("v_x2", "rebound v_x2"),
        Span::raw(format!("{:.3} m/s", o.vx2)),
    ];
    let theta2 = format!("{:.1} deg", o.theta2_deg);
    let ex = Line::from(vec![label("e_x", "tangential e_x"), Span::raw(ex)]);
    // Narrow, v_x2 and θ2 share a line and the timeline follows its label, to fit 80 x 24.
    let mut lines = if wide {
        vec![
            spin,
            Line::from(vx2),
            Line::from(vec![label("θ2", "rebound angle θ2"), Span::raw(theta2)]),
            ex,
            Line::from(vec![
                label("friction", "lost to friction"),
                Span::raw(format!("{friction_share:.1} % of the energy")),
            ]),
            Line::from(vec![
                label("phases", "phases (ms)"),
                Span::styled(summary(b), theme.dim()),
            ]),
            Line::from(timeline(b, theme)),
        ]
    } else {
        let mut vx2_theta2 = vx2;
        vx2_theta2.push(Span::styled("  θ2 ", theme.dim()));
        vx2_theta2.push(Span::raw(theta2));
        // e_x and the share lost to friction share a line too.
        let mut ex_friction = ex;
        ex_friction.push_span(Span::styled("  lost ", theme.dim()));
        ex_friction.push_span(Span::raw(format!("{friction_share:.1} %")));
        let mut phases = vec![label("phase ms", "")];
        phases.extend(timeline(b, theme));
        vec![
            spin,
            Line::from(vx2_theta2),
            ex_friction,
            Line::from(phases),
        ]
    };
    let ex_line = if wide { 3 } else { 2 };
    // Against a pinned baseline: current minus baseline, on lines of their own when there is room, else
    // in place of the rpm and after e_x.
    if let Some(base) = &app.baseline {
        let d = base.deltas(b);
        let d_omega2 = signed(d.omega2, 1);
        let d_ex = d.ex.map_or("n/a".to_string(), |x| signed(x, 3));
        if wide {
            let differs = base.differences(&app.params);
            let differs = if differs.is_empty() {
                "nothing yet".to_string()
            } else {
                differs.join(", ")
            };
            lines.splice(
                4..4,
                [
                    Line::from(vec![
                        label("", "Δω2 vs baseline"),
                        Span::styled(format!("{d_omega2} rad/s"), theme.emphasis()),
                    ]),
                    Line::from(vec![label("", "Δe_x vs baseline"), Span::raw(d_ex)]),
                    Line::from(vec![
                        label("", "baseline differs"),
                        Span::styled(format!("in {differs}"), theme.dim()),
                    ]),
                ],
            );
        } else {
            lines[0].spans[2] = Span::raw(format!(" Δ{d_omega2}"));
            // Δe_x takes the place of the friction share on the narrow e_x line.
            lines[ex_line].spans.truncate(2);
            lines[ex_line].spans.push(Span::raw(format!(" Δ{d_ex}")));
        }
    }
    if wide {
        let words = b.params.model().words();
        let share = |j: f64| format!("{:.1} %", 100.0 * j / e.initial);
        lines.push(Line::from(vec![
            label("", "rebound speed v2"),
            Span::raw(format!("{:.3} m/s", o.speed2())),
        ]));
        if let Some(ratio) = o.roll_ratio {
            lines.push(Line::from(vec![
                label("", "r ω2 / v_x2"),
                Span::raw(format!("{ratio:.3} (1 = rolling)")),
            ]));
        }
        lines.push(Line::from(vec![
            label("", words.left_in),
            Span::raw(share(e.final_cart)),
        ]));
        lines.push(Line::from(vec![
            label("", "lost to e_y < 1"),
            Span::raw(share(e.normal_loss)),
        ]));
        if b.params.cart_friction > 0.0 {
            lines.push(Line::from(vec![
                label("", words.lost_at),
                Span::raw(share(e.cart_friction_loss)),
            ]));
        }
    }
    lines.extend(super::residuals::lines(app, wide));
    lines
}
