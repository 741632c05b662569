//! The shot view: the court from the side on a Canvas (x from behind the hitter's baseline to past the
//! opponent's, y up), the ball's path from the strings over the net to the court bounce and on to the
//! opponent's baseline, the readouts above it and, when a baseline is pinned, its path dimmer beneath.
//!
//! ```text
//! ─ shot from the side  IN ━ baseline ──────────────────────────────────── solving… (while stale)
//! launch  35.6 m/s (128.1 km/h) at 9.0° up, 3762 rpm topspin   flight 0.77 s           (readouts: three
//! net     clears it by 65.6 cm (+7.0 cm)   lands 8.32 m past the net, 3.57 m in         rows, or four
//! kick    0.71 m at the baseline   court bounce 18.0 m/s at 15.3°, 5027 rpm             shorter, narrow)
//! 2 m
//!                  ⢀⣀⡠⠤⠤⠤⠤⢄⣀
//!         ⣀⡠⠤⠒⠊⠉⠁          ⠉⠑⠢⢄⡀                     the path to the bounce and on,
//!    ⣀⠤⠒⠉                   ⡇      ⠑⠢⡀   ⣀⠤⠒⠉       the baseline's dimmer beneath
//!     ⢰                     ⡇        ⠈⠢⡠⠊     ⢰
//! ⣀⣀⣀⣀⣸⣀⣀⣀⣀⣀⣆⣀⣀⣀⣀⣀⣀⣀⣀⣀⣀⣀⣀⣇⣀⣀⣀⣀⣀⣀⣀⣀⣀⣆⣀⣀⣀⣀⣀⣀⣀⣀⣸⣀   the ground, baselines, service lines, net
//!     0                    net              23.77 m
//! ```
//!
//! `␣` plays the flight in real time, the ball drawn on its path and its time in the title; Home and
//! End put it at the stroke and at the end of the path.
//!
//! A shot the model cannot play (a racquet that never meets the ball, a flight that does not end) is
//! shown as its reason in place of the court.

use std::f64::consts::PI;

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Context, Line as Segment, Points};
use ratatui::widgets::{Block, Borders, Paragraph, Wrap};

use super::baseline as pinned;
use super::stale;
use crate::model::PhaseKind;
use crate::shot::Shot;
use crate::shot::court::{BASELINE_X, NET_HEIGHT, NET_X, SERVICE_LINE_FROM_NET};
use crate::tui::app::App;
use crate::tui::baseline::signed;
use crate::tui::theme::Theme;

/// The court's left end, m: a little behind the hitter's baseline.
const LEFT: f64 = -1.0;
/// The court's right end at the least, m: a little past the opponent's baseline.
const RIGHT: f64 = 25.0;
/// The lowest top of the picture, m.
const MIN_TOP: f64 = 2.0;
/// Views at least this wide get the long readouts on three rows; narrower ones the short on four.
const WIDE: u16 = 90;

/// Where the ball lands against the lines, as the verdict in the title says it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Verdict {
    In,
    /// Beyond the opponent's baseline.
    Long,
    /// Into the net, or down before it.
    Net,
}

impl Verdict {
    fn of(shot: &Shot) -> Verdict {
        if shot.is_in() {
            Verdict::In
        } else if shot.net_clearance.is_some_and(|c| c > 0.0) {
            Verdict::Long
        } else {
            Verdict::Net
        }
    }

    fn word(self) -> &'static str {
        match self {
            Verdict::In => "IN",
            Verdict::Long => "OUT (long)",
            Verdict::Net => "NET",
        }
    }
}

pub fn render(frame: &mut Frame, area: Rect, app: &App) {
    let theme = &app.theme;
    let Some(played) = app.shots.shown.as_deref() else {
        stale::pending(frame, area, app, "shot");
        return;
    };
    let wide = area.width >= WIDE;
    let name = if wide {
        " shot from the side "
    } else {
        " shot "
    };
    let mut title = vec![Span::styled(name, theme.title())];
    let kept = app
        .baseline
        .as_ref()
        .and_then(|b| app.shots.known(&b.solved.params));
    let base = kept.as_deref().and_then(|p| p.shot.as_ref().ok());
    let shot = match &played.shot {
        Ok(shot) => shot,
        Err(reason) => {
            let block = Block::new().borders(Borders::TOP).title(Line::from(title));
            let text = vec![
                Line::styled(theme.words("no shot to draw:").into_owned(), theme.error()),
                Line::raw(theme.words(reason).into_owned()),
            ];
            frame.render_widget(
                Paragraph::new(text).block(block).wrap(Wrap { trim: true }),
                area,
            );
            return;
        }
    };
    let verdict = Verdict::of(shot);
    let style = if verdict == Verdict::In {
        theme.emphasis()
    } else {
        theme.error()
    };
    title.push(Span::styled(format!(" {} ", verdict.word()), style));
    if base.is_some() {
        title.push(pinned::legend(theme));
    }
    let ball = flying(app, shot);
    if let Some((t, _)) = ball {
        title.push(Span::styled(format!("t {t:.2} s "), theme.key()));
    }
    let block = Block::new().borders(Borders::TOP).title(Line::from(title));
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let lines = readouts(shot, base, theme, inner.width);
    let rows = (lines.len() as u16).min(inner.height);
    frame.render_widget(
        Paragraph::new(lines),
        Rect {
            height: rows,
            ..inner
        },
    );
    // The court below the readouts, with a row of labels under it.
    let court = Rect {
        y: inner.y + rows,
        height: inner.height.saturating_sub(rows + 1),
        ..inner
    };
    if court.height >= 3 && court.width >= 20 {
        draw_court(frame, court, app, shot, base, ball.map(|(_, at)| at));
    }
}

/// km/h of a speed in m/s.
fn kmh(speed: f64) -> f64 {
    speed * 3.6
}

/// rpm of a spin in rad/s.
fn rpm(omega: f64) -> f64 {
    omega * 30.0 / PI
}

/// A spin in rpm as people say it: `3762 rpm topspin`, `2947 rpm backspin`.
fn spin_words(rpm: f64) -> String {
    let kind = if rpm < 0.0 { "backspin" } else { "topspin" };
    format!("{:.0} rpm {kind}", rpm.abs())
}

/// A piece of a readout line; optional ones (the differences from the baseline, the court bounce) go
/// where the line would not fit.
type Piece = (Span<'static>, bool);

/// `pieces` as a line of at most `room` columns: optional pieces are left out, the last first, until
/// it fits.
fn fit(mut pieces: Vec<Piece>, room: usize) -> Line<'static> {
    while pieces.iter().map(|(s, _)| s.width()).sum::<usize>() > room {
        match pieces.iter().rposition(|(_, optional)| *optional) {
            Some(i) => {
                pieces.remove(i);
            }
            None => break,
        }
    }
    Line::from(pieces.into_iter().map(|(s, _)| s).collect::<Vec<_>>())
}

/// The readouts in `room` columns: launch, net clearance, landing, kick and flight time (and the court
/// bounce, wide), with the differences from the pinned baseline's shot where there is one.
fn readouts(shot: &Shot, base: Option<&Shot>, theme: &Theme, room: u16) -> Vec<Line<'static>> {
    let wide = room >= WIDE;
    let launch = shot.strings.leaving;
    let label = |text: &str| {
        let width = if wide { 8 } else { 7 };
        (Span::styled(format!("{text:<width$}"), theme.dim()), false)
    };
    let dim = |text: &str| (Span::styled(text.to_string(), theme.dim()), false);
    let raw = |text: String| (Span::raw(theme.words(&text).into_owned()), false);
    let delta = |f: fn(&Shot) -> Option<f64>, scale: f64, decimals: usize, unit: &str| {
        let text = match (f(shot), base.and_then(f)) {
            (Some(a), Some(b)) => format!(" ({} {unit})", signed((a - b) * scale, decimals)),
            _ => String::new(),
        };
        (Span::styled(text, theme.dim()), true)
    };
    let net = match shot.net_clearance {
        Some(c) if c > 0.0 => format!("clears it by {:.1} cm", c * 100.0),
        Some(c) => format!("into it, {:.1} cm low", -c * 100.0),
        None => "down before the net".to_string(),
    };
    let net = (Span::styled(net, theme.emphasis()), false);
    let short = match shot.net_clearance {
        Some(_) => "in the net",
        None => "short of the net",
    };
    let past = if wide { "past the net" } else { "past net" };
    let lands = raw(match shot.landing_x {
        Some(x) if x <= BASELINE_X => {
            format!("{:.2} m {past}, {:.2} m in", x - NET_X, BASELINE_X - x)
        }
        Some(x) => format!("{:.2} m {past}, {:.2} m long", x - NET_X, x - BASELINE_X),
        None => short.to_string(),
    });
    let kick = raw(match (shot.kick_height, wide) {
        (Some(k), true) => format!("{k:.2} m at the baseline"),
        (Some(k), false) => format!("{k:.2} m"),
        (None, true) => "none: it does not reach the baseline".to_string(),
        (None, false) => "none".to_string(),
    });
    let d_net = delta(|s| s.net_clearance, 100.0, 1, "cm");
    let d_lands = delta(|s| s.landing_x, 1.0, 2, "m");
    let d_kick = delta(|s| s.kick_height, 1.0, 2, "m");
    let flight = raw(format!("{:.2} s", shot.flight_time));
    let spin = rpm(launch.topspin());
    let room = usize::from(room);
    let lines = if wide {
        let bounce = shot.court.as_ref().map_or(String::new(), |c| {
            format!(
                "   court bounce {:.1} m/s at {:.1}°, {}",
                c.leaving.speed(),
                c.leaving.angle_deg(),
                spin_words(rpm(c.leaving.topspin()))
            )
        });
        vec![
            vec![
                label("launch"),
                raw(format!(
                    "{:.1} m/s ({:.1} km/h) at {:.1}° {}, {}",
                    launch.speed(),
                    kmh(launch.speed()),
                    launch.angle_deg().abs(),
                    if launch.angle_deg() < 0.0 {
                        "down"
                    } else {
                        "up"
                    },
                    spin_words(spin),
                )),
                dim("   flight "),
                flight,
            ],
            vec![label("net"), net, d_net, dim("   lands "), lands, d_lands],
            vec![label("kick"), kick, d_kick, (raw(bounce).0, true)],
        ]
    } else {
        vec![
            vec![
                label("launch"),
                raw(format!(
                    "{:.1} m/s ({:.0} km/h) {:.1}° {spin:.0} rpm",
                    launch.speed(),
                    kmh(launch.speed()),
                    launch.angle_deg()
                )),
            ],
            vec![label("net"), net, d_net],
            vec![label("lands"), lands, d_lands],
            vec![label("kick"), kick, d_kick, dim("  flight "), flight],
        ]
    };
    lines.into_iter().map(|pieces| fit(pieces, room)).collect()
}

/// The court's extent: x to past the furthest point drawn, y from the court to above the highest.
fn bounds(shot: &Shot, base: Option<&Shot>) -> ([f64; 2], [f64; 2]) {
    let points = shot
        .trajectory
        .iter()
        .chain(base.into_iter().flat_map(|b| b.trajectory.iter()));
    let (right, top) = points.fold((RIGHT, MIN_TOP), |(r, t), p| {
        (r.max(p[1] + 0.5), t.max(p[2] * 1.15))
    });
    // A round top, to the half metre.
    ([LEFT, right], [0.0, (top * 2.0).ceil() / 2.0])
}

/// A path on court: (x, y) points, m.
type Path = Vec<(f64, f64)>;

/// The path of `shot`, split where the ball meets the court: to the bounce, and after it.
fn flights(shot: &Shot) -> (Path, Path) {
    let points: Path = shot.trajectory.iter().map(|p| (p[1], p[2])).collect();
    // The second flight starts where the first lands (the court contact is an instant).
    let bounce = shot
        .landing_x
        .filter(|_| shot.court.is_some())
        .and_then(|x| points.iter().position(|p| p.0 >= x));
    match bounce {
        Some(i) => (points[..=i].to_vec(), points[i..].to_vec()),
        None => (points, Vec::new()),
    }
}

fn polyline(ctx: &mut Context, points: &[(f64, f64)], color: Color) {
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        ctx.draw(&Segment::new(a.0, a.1, b.0, b.1, color));
    }
}

/// Where the ball is at the flight's time, once `␣` has played it or while it plays: the time (within
/// the flight) and the point, by linear interpolation along the path.
fn flying(app: &App, shot: &Shot) -> Option<(f64, (f64, f64))> {
    if app.flight <= 0.0 && !app.playing {
        return None;
    }
    let path = &shot.trajectory;
    let t = app.flight.clamp(path.first()?[0], path.last()?[0]);
    let i = path
        .partition_point(|p| p[0] < t)
        .clamp(1, path.len().max(2) - 1);
    let (a, b) = (path.get(i - 1)?, path.get(i)?);
    let f = if b[0] > a[0] {
        (t - a[0]) / (b[0] - a[0])
    } else {
        1.0
    };
    Some((t, (a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]))))
}

fn draw_court(
    frame: &mut Frame,
    area: Rect,
    app: &App,
    shot: &Shot,
    base: Option<&Shot>,
    ball: Option<(f64, f64)>,
) {
    let theme = &app.theme;
    let ([x0, x1], [y0, y1]) = bounds(shot, base);
    // One cell up, in metres: the height of the line marks; a dot about every third column.
    let cell = (y1 - y0) / f64::from(area.height.max(1));
    let dot_step = (x1 - x0) / f64::from(area.width.max(1)) * 3.0;
    let lines = theme.guide();
    let net = theme.body();
    let (first, kick) = flights(shot);
    let paint = |ctx: &mut Context| {
        ctx.draw(&Segment::new(x0, 0.0, x1, 0.0, lines));
        for x in [0.0, BASELINE_X] {
            ctx.draw(&Segment::new(x, 0.0, x, 1.5 * cell, lines));
        }
        for x in [NET_X - SERVICE_LINE_FROM_NET, NET_X + SERVICE_LINE_FROM_NET] {
            ctx.draw(&Segment::new(x, 0.0, x, 0.6 * cell, lines));
        }
        ctx.draw(&Segment::new(NET_X, 0.0, NET_X, NET_HEIGHT, net));
        ctx.layer();
        if let Some(base) = base {
            let (a, b) = flights(base);
            let path: Path = a.into_iter().chain(b).collect();
            if theme.color {
                polyline(ctx, &path, theme.baseline());
            } else {
                // Dotted, as the charts draw a baseline without colour.
                let mut next = f64::NEG_INFINITY;
                let dots: Vec<(f64, f64)> = path
                    .iter()
                    .filter(|p| {
                        let keep = p.0 >= next;
                        if keep {
                            next = p.0 + dot_step;
                        }
                        keep
                    })
                    .copied()
                    .collect();
                ctx.draw(&Points::new(&dots, theme.baseline()));
            }
            ctx.layer();
        }
        polyline(ctx, &first, theme.current());
        polyline(ctx, &kick, theme.phase(PhaseKind::Grip));
        ctx.print(x0, y1, Line::styled(format!("{} m", y1), theme.dim()));
        if let Some((x, y)) = ball {
            ctx.print(
                x,
                y,
                Span::styled(theme.words("●").into_owned(), theme.key()),
            );
        }
    };
    frame.render_widget(
        Canvas::default()
            .x_bounds([x0, x1])
            .y_bounds([y0, y1])
            .marker(theme.marker)
            .paint(paint),
        area,
    );
    labels(frame, area, [x0, x1], theme);
}

/// The row under the court (inside the view): the hitter's baseline, the net and the opponent's.
fn labels(frame: &mut Frame, court: Rect, [x0, x1]: [f64; 2], theme: &Theme) {
    let row = court.bottom();
    let width = court.width;
    let column = |x: f64| {
        let f = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
        court.x + (f * f64::from(width - 1)).round() as u16
    };
    let buf = frame.buffer_mut();
    let mut free = court.x;
    for (x, text) in [
        (0.0, "0".to_string()),
        (NET_X, "net".to_string()),
        (BASELINE_X, format!("{BASELINE_X:.2} m")),
    ] {
        let len = text.chars().count() as u16;
        let start = column(x)
            .saturating_sub(len / 2)
            .clamp(court.x, court.right().saturating_sub(len));
        if start >= free {
            buf.set_string(start, row, &text, theme.dim());
            free = start + len + 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config;
    use crate::model::Params;

    fn forehand() -> Shot {
        let p = config::preset("topspin-forehand")
            .unwrap()
            .apply(Params::default());
        crate::shot::play(&p, true).unwrap()
    }

    #[test]
    fn a_line_too_long_loses_its_optional_pieces_last_first() {
        let piece = |text: &str, optional| (Span::raw(text.to_string()), optional);
        let pieces = vec![
            piece("net 1.0 cm", false),
            piece(" (+2 cm)", true),
            piece(" lands 8 m", false),
            piece(" (+1 m)", true),
        ];
        let width = |line: Line| line.width();
        assert_eq!(width(fit(pieces.clone(), 80)), 35);
        assert_eq!(width(fit(pieces.clone(), 30)), 28);
        assert_eq!(width(fit(pieces.clone(), 21)), 20);
        // What is not optional stays, even cut.
        assert_eq!(width(fit(pieces, 5)), 20);
    }

    #[test]
    fn the_path_splits_where_the_ball_lands() {
        let shot = forehand();
        let (first, kick) = flights(&shot);
        let landing = shot.landing_x.unwrap();
        assert_eq!(first.last(), kick.first());
        assert_eq!(first.last().unwrap().0, landing);
        assert!(first.iter().all(|p| p.0 <= landing));
        assert!(kick.iter().all(|p| p.0 >= landing));
        assert_eq!(first.len() + kick.len(), shot.trajectory.len() + 1);
    }

    #[test]
    fn the_verdict_reads_the_shot() {
        let mut shot = forehand();
        assert_eq!(Verdict::of(&shot), Verdict::In);
        shot.landing_x = Some(BASELINE_X + 0.1);
        assert_eq!(Verdict::of(&shot), Verdict::Long);
        shot.net_clearance = Some(-0.01);
        assert_eq!(Verdict::of(&shot), Verdict::Net);
        shot.net_clearance = None;
        assert_eq!(Verdict::of(&shot), Verdict::Net);
    }
}
