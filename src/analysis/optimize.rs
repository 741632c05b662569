//! `optimize`: the value of one parameter that maximises (or minimises) an outcome of the bounce.
//! A scan fine enough not to miss a narrow peak, then Brent's method around the best scan point; for a
//! whole-number parameter (the chain's N), every whole number in the range.

use rayon::prelude::*;

use crate::model::{Bounce, Outcome, Params, SolveOptions};

use super::{AnalysisError, Span, brent};

/// What to optimise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Objective {
    /// Rebound spin omega2, rad/s.
    Omega2,
    /// Tangential coefficient of restitution e_x.
    Ex,
    /// Rebound velocity along the surface v_x2, m/s.
    Vx2,
    /// Rebound angle theta2 from the surface, degrees.
    Theta2,
}

impl Objective {
    pub const ALL: [Objective; 4] = [
        Objective::Omega2,
        Objective::Ex,
        Objective::Vx2,
        Objective::Theta2,
    ];

    /// The name `--objective` takes.
    pub fn name(self) -> &'static str {
        match self {
            Objective::Omega2 => "omega2",
            Objective::Ex => "ex",
            Objective::Vx2 => "vx2",
            Objective::Theta2 => "theta2",
        }
    }

    /// The unit of the objective's value (`""` for a pure number).
    pub fn unit(self) -> &'static str {
        match self {
            Objective::Omega2 => "rad/s",
            Objective::Ex => "",
            Objective::Vx2 => "m/s",
            Objective::Theta2 => "deg",
        }
    }

    /// Reads `--objective`.
    pub fn parse(text: &str) -> Result<Objective, AnalysisError> {
        Objective::ALL
            .into_iter()
            .find(|o| o.name() == text.trim())
            .ok_or_else(|| {
                let names: Vec<&str> = Objective::ALL.iter().map(|o| o.name()).collect();
                AnalysisError::Input(format!(
                    "--objective must be one of {}; got {}",
                    names.join(", "),
                    crate::model::units::echo(text.trim())
                ))
            })
    }

    /// The objective's value for an outcome; `None` where it is undefined (e_x without incoming slip).
    pub fn of(self, o: &Outcome) -> Option<f64> {
        match self {
            Objective::Omega2 => Some(o.omega2),
            Objective::Ex => o.ex,
            Objective::Vx2 => Some(o.vx2),
            Objective::Theta2 => Some(o.theta2_deg),
        }
    }
}

/// The scan points of [`optimize`] unless told otherwise.
pub const DEFAULT_SCAN: usize = 400;

/// A range spanning this ratio or more is scanned geometrically even without `--log`.
const DECADES: f64 = 100.0;

/// The optimum found.
#[derive(Clone, Debug)]
pub struct Optimum {
    /// The varied parameter's value, base unit.
    pub value: f64,
    /// The objective there.
    pub objective_value: f64,
    /// The bounce there.
    pub bounce: Bounce,
    /// The span actually scanned (geometric when the range spans decades); for a whole-number
    /// parameter, the whole numbers' span: its ends rounded inwards, never geometric.
    pub span: Span,
    /// True when the parameter takes whole numbers and every one of them in the span was solved (no
    /// scan between them, no Brent): the optimum is exact.
    pub exhaustive: bool,
}

/// The span with geometric spacing switched on when the range spans two decades or more.
pub fn scan_span(span: &Span) -> Span {
    let (lo, hi) = (span.from.min(span.to), span.from.max(span.to));
    Span {
        log: span.log || (lo > 0.0 && hi / lo >= DECADES),
        ..*span
    }
}

/// The value in `span` that maximises the objective (minimises it with `minimize`): `scan` evenly
/// spaced points (geometric for a span of decades), then Brent's method between the best point's
/// neighbours, in the scan's coordinate, to a relative 1e-10.
///
/// A whole-number parameter is not scanned: every whole number in the span is solved and the best
/// taken (the first from `span.from` on a tie), `scan` and `log` unused. A span holding no whole
/// number is refused.
pub fn optimize(
    base: &Params,
    span: &Span,
    objective: Objective,
    minimize: bool,
    scan: usize,
) -> Result<Optimum, AnalysisError> {
    optimize_with(
        base,
        span,
        objective,
        minimize,
        scan,
        &SolveOptions::default(),
    )
}

/// [`optimize`] with every bounce solved on the caller's terms.
pub fn optimize_with(
    base: &Params,
    span: &Span,
    objective: Objective,
    minimize: bool,
    scan: usize,
    options: &SolveOptions,
) -> Result<Optimum, AnalysisError> {
    if span.spec.integer {
        return exhaustive(base, span, objective, minimize, options);
    }
    let span = scan_span(span);
    let cost = |value: f64| cost_at(base, &span, objective, minimize, value, options);
    let scan = scan.max(3);
    let costs: Vec<f64> = (0..scan)
        .into_par_iter()
        .map(|i| cost(span.at(i, scan)))
        .collect::<Result<_, _>>()?;
    let best = best_of(&costs, objective, &span)?;
    // Brent works on u in [0, 1], the fraction of the span, so a geometric scan stays geometric. The
    // solves cannot fail inside the bracket: its ends were solved and the parameter checks are intervals.
    let unit = |i: usize| i as f64 / (scan - 1) as f64;
    let (lo, hi) = (unit(best.saturating_sub(1)), unit((best + 1).min(scan - 1)));
    let refined = |u: f64| cost(span.from_unit(u)).unwrap_or(f64::INFINITY);
    let (u, c) = brent::minimize(refined, lo, hi, unit(best), 1e-10);
    let value = if c < costs[best] {
        span.from_unit(u)
    } else {
        span.at(best, scan)
    };
    optimum(base, span, objective, value, false, options)
}

/// The quantity minimised: the objective, negated to maximise; an undefined objective counts as the
/// worst value.
fn cost_at(
    base: &Params,
    span: &Span,
    objective: Objective,
    minimize: bool,
    value: f64,
    options: &SolveOptions,
) -> Result<f64, AnalysisError> {
    let sign = if minimize { 1.0 } else { -1.0 };
    let bounce = span.solve(base, value, options)?;
    Ok(objective
        .of(&bounce.outcome)
        .map_or(f64::INFINITY, |v| sign * v))
}

/// The index of the lowest cost (the first of equals); an error when the objective is undefined at
/// every point.
fn best_of(costs: &[f64], objective: Objective, span: &Span) -> Result<usize, AnalysisError> {
    let best = (0..costs.len())
        .min_by(|&i, &j| costs[i].total_cmp(&costs[j]))
        .expect("the scan has points");
    if costs[best] == f64::INFINITY {
        return Err(AnalysisError::Input(format!(
            "--objective {} is undefined over the whole range of --{}",
            objective.name(),
            span.spec.flag
        )));
    }
    Ok(best)
}

/// The optimum of a whole-number parameter: every whole number of the span solved, on all cores.
fn exhaustive(
    base: &Params,
    span: &Span,
    objective: Objective,
    minimize: bool,
    options: &SolveOptions,
) -> Result<Optimum, AnalysisError> {
    let values = span.whole_numbers()?;
    let span = Span {
        log: false,
        ..span.whole()?
    };
    let costs: Vec<f64> = values
        .par_iter()
        .map(|&value| cost_at(base, &span, objective, minimize, value, options))
        .collect::<Result<_, _>>()?;
    let value = values[best_of(&costs, objective, &span)?];
    optimum(base, span, objective, value, true, options)
}

/// The bounce at the optimum `value`, with its objective.
fn optimum(
    base: &Params,
    span: Span,
    objective: Objective,
    value: f64,
    exhaustive: bool,
    options: &SolveOptions,
) -> Result<Optimum, AnalysisError> {
    let bounce = span.solve(base, value, options)?;
    let objective_value = objective
        .of(&bounce.outcome)
        .expect("the optimum has a defined objective");
    Ok(Optimum {
        value,
        objective_value,
        bounce,
        span,
        exhaustive,
    })
}
