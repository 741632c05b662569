//! Shots in the analyses: one shot per value of a parameter (`sweep --shot`), and the value that
//! maximises a shot outcome (`optimize --objective kick_height`, ...), by default among the shots that
//! land in.

use rayon::prelude::*;

use crate::model::units;
use crate::model::{Params, SolveOptions};
use crate::shot::{self, Shot};

use super::optimize::scan_span;
use super::{AnalysisError, Span, brent};

/// A shot outcome to optimise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShotObjective {
    /// Height of the centre over the opponent's baseline after the bounce, m.
    KickHeight,
    /// Net clearance, m.
    NetClearance,
    /// Landing beyond the net, m.
    Landing,
    /// Launch speed, m/s.
    LaunchSpeed,
    /// Launch topspin, rpm.
    LaunchTopspin,
}

impl ShotObjective {
    pub const ALL: [ShotObjective; 5] = [
        ShotObjective::KickHeight,
        ShotObjective::NetClearance,
        ShotObjective::Landing,
        ShotObjective::LaunchSpeed,
        ShotObjective::LaunchTopspin,
    ];

    /// The name `--objective` takes.
    pub fn name(self) -> &'static str {
        match self {
            ShotObjective::KickHeight => "kick_height",
            ShotObjective::NetClearance => "net_clearance",
            ShotObjective::Landing => "landing",
            ShotObjective::LaunchSpeed => "launch_speed",
            ShotObjective::LaunchTopspin => "launch_topspin",
        }
    }

    pub fn unit(self) -> &'static str {
        match self {
            ShotObjective::LaunchSpeed => "m/s",
            ShotObjective::LaunchTopspin => "rpm",
            _ => "m",
        }
    }

    /// The objective named `text`, if it is a shot's.
    pub fn named(text: &str) -> Option<ShotObjective> {
        ShotObjective::ALL
            .into_iter()
            .find(|o| o.name() == text.trim())
    }

    /// The objective's value for a shot; `None` where it has none (no kick, no landing).
    pub fn of(self, s: &Shot) -> Option<f64> {
        let launch = &s.strings.leaving;
        match self {
            ShotObjective::KickHeight => s.kick_height,
            ShotObjective::NetClearance => s.net_clearance,
            ShotObjective::Landing => s.landing_x.map(|x| x - shot::court::NET_X),
            ShotObjective::LaunchSpeed => Some(launch.speed()),
            ShotObjective::LaunchTopspin => Some(launch.topspin() * 30.0 / std::f64::consts::PI),
        }
    }
}

/// The shot with the varied parameter at `value`, its bounces solved on `options`' terms.
pub fn play_at(
    base: &Params,
    span: &Span,
    value: f64,
    options: &SolveOptions,
) -> Result<Shot, AnalysisError> {
    let mut params = *base;
    params.set(span.spec.id, value);
    shot::play_with(&params, false, options).map_err(|e| {
        AnalysisError::Input(format!(
            "at --{} {}: {e}",
            span.spec.flag,
            units::brief(value, 10)
        ))
    })
}

/// One shot per value of the span, on all cores, in order, solved on `options`' terms.
pub fn sweep(
    base: &Params,
    span: &Span,
    steps: usize,
    options: &SolveOptions,
) -> Result<Vec<(f64, Shot)>, AnalysisError> {
    span.values(steps)
        .into_par_iter()
        .map(|value| play_at(base, span, value, options).map(|s| (value, s)))
        .collect()
}

/// The best shot found: the varied value, the objective there and the shot.
#[derive(Clone, Debug)]
pub struct ShotOptimum {
    pub value: f64,
    pub objective_value: f64,
    pub shot: Shot,
    /// The span scanned (geometric when it spans two decades or more).
    pub span: Span,
}

/// The value in `span` that maximises `objective` (minimises with `minimize`) among the shots that land
/// in (all shots with `allow_out`): a scan of `scan` points, then Brent's method between the best
/// point's neighbours to a relative 1e-10. A shot that does not play, that is out (unless allowed) or
/// has no value of the objective counts as the worst. The shots are solved on `options`' terms.
pub fn optimize(
    base: &Params,
    span: &Span,
    objective: ShotObjective,
    minimize: bool,
    allow_out: bool,
    scan: usize,
    options: &SolveOptions,
) -> Result<ShotOptimum, AnalysisError> {
    let span = scan_span(span);
    let sign = if minimize { 1.0 } else { -1.0 };
    let cost = |value: f64| {
        play_at(base, &span, value, options)
            .ok()
            .filter(|s| allow_out || s.is_in())
            .and_then(|s| objective.of(&s))
            .map_or(f64::INFINITY, |v| sign * v)
    };
    let scan = scan.max(3);
    let costs: Vec<f64> = (0..scan)
        .into_par_iter()
        .map(|i| cost(span.at(i, scan)))
        .collect();
    let best = (0..scan)
        .min_by(|&i, &j| costs[i].total_cmp(&costs[j]))
        .expect("the scan has points");
    if costs[best] == f64::INFINITY {
        let which = if allow_out {
            "no shot over the range has"
        } else {
            "no shot over the range lands in with"
        };
        return Err(AnalysisError::Input(format!(
            "{which} a {} (--vary {}; --allow-out counts the shots that land out)",
            objective.name(),
            span.spec.flag
        )));
    }
    let unit = |i: usize| i as f64 / (scan - 1) as f64;
    let (lo, hi) = (unit(best.saturating_sub(1)), unit((best + 1).min(scan - 1)));
    let (u, c) = brent::minimize(|u| cost(span.from_unit(u)), lo, hi, unit(best), 1e-10);
    let value = if c < costs[best] {
        span.from_unit(u)
    } else {
        span.at(best, scan)
    };
    let shot = play_at(base, &span, value, options)?;
    let objective_value = objective.of(&shot).expect("the optimum has a value");
    Ok(ShotOptimum {
        value,
        objective_value,
        shot,
        span,
    })
}
