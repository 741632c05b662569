//! Profile-likelihood intervals: for one free coordinate u_j, the range where the profile
//! chi2_p(u_j) = min over the other coordinates of chi2 rises by no more than `delta` above the minimum
//! (delta = 3.84, the 95% quantile of chi2 with one degree of freedom, with absolute sigmas; t^2 s^2
//! otherwise, as the Wald interval uses). Each side is walked out from the optimum in steps that double
//! from the Wald half-width, the others re-minimised at each step from the last, until the profile
//! crosses delta; the crossing is then found by the Illinois variant of regula falsi. A side that reaches
//! an end of the parameter's range (0 or infinity for a positive parameter: [`REACH`] beyond the
//! optimum counts as there), or a region where the model cannot be solved, without crossing is open.

use levenberg_marquardt::LevenbergMarquardt;

use super::problem::{Model, Problem};

/// How far a side is walked in a log coordinate, 4 decades beyond the optimum, before it is called
/// open (the parameter then reaches 0 or infinity); in a linear unbounded one, this many Wald
/// half-widths.
pub const REACH: f64 = 4.0 * std::f64::consts::LN_10;
const LINEAR_REACH: f64 = 50.0;

/// Levenberg-Marquardt's evaluation budget per moving coordinate and one, at each point of a profile.
const PATIENCE: usize = 40;

/// Regula falsi steps at most, and the tolerance on the crossing, relative to its distance from the
/// optimum.
const ITERATIONS: usize = 12;
const TOLERANCE: f64 = 2e-3;

/// Where one side of a profile ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Side {
    /// The profile crosses delta at this coordinate.
    Closed(f64),
    /// It does not within the parameter's range.
    Open,
}

/// The coordinate a profile moves.
#[derive(Clone, Copy, Debug)]
pub struct Axis {
    pub j: usize,
    /// The Wald half-width in the coordinate (or a guess): the first step.
    pub step: f64,
    /// The coordinate's bounds.
    pub range: (f64, f64),
}

/// One side (`direction` -1 or +1) of the profile along `axis` from the optimum `u` (chi2 `chi2`).
/// Also returns the lowest point met, if it lies below the optimum (which then was not the global one).
pub fn side(
    model: &Model,
    (u, chi2): (&[f64], f64),
    axis: Axis,
    delta: f64,
    direction: f64,
) -> (Side, Option<(Vec<f64>, f64)>) {
    let Axis { j, step, range } = axis;
    let log = range.0 == f64::NEG_INFINITY && range.1 == f64::INFINITY;
    let step = if step.is_finite() && step > 0.0 {
        step
    } else {
        0.1
    };
    let reach = if log { REACH } else { LINEAR_REACH * step };
    let end = if direction > 0.0 {
        range.1.min(u[j] + reach)
    } else {
        range.0.max(u[j] - reach)
    };
    let mut lowest: Option<(Vec<f64>, f64)> = None;
    let mut profile = |x: f64, from: &[f64]| {
        let (v, c) = minimise_holding(model, from, j, x);
        if c < chi2 - 1e-9 * chi2.max(1.0) && lowest.as_ref().is_none_or(|l| c < l.1) {
            lowest = Some((v.clone(), c));
        }
        (v, c - chi2)
    };
    // Walk out until the profile crosses delta.
    let (mut inside, mut g_inside) = (u.to_vec(), 0.0);
    let mut h = step;
    let (mut outside, mut g_outside) = loop {
        let x = u[j] + direction * h;
        let x = if direction > 0.0 {
            x.min(end)
        } else {
            x.max(end)
        };
        let (v, g) = profile(x, &inside);
        if !g.is_finite() {
            return (Side::Open, lowest);
        }
        if g >= delta {
            break (v, g);
        }
        if x == end {
            return (Side::Open, lowest);
        }
        (inside, g_inside) = (v, g);
        h *= 2.0;
    };
    // Illinois: regula falsi that halves the weight of an end kept twice.
    let tolerance = TOLERANCE * (outside[j] - u[j]).abs();
    let mut kept = 0i8;
    for _ in 0..ITERATIONS {
        let (a, b) = (inside[j], outside[j]);
        if (b - a).abs() <= tolerance {
            break;
        }
        let (ga, gb) = (g_inside - delta, g_outside - delta);
        let x = (a - ga * (b - a) / (gb - ga)).clamp(a.min(b), a.max(b));
        let (v, g) = profile(x, &inside);
        if !g.is_finite() {
            break;
        }
        if g >= delta {
            (outside, g_outside) = (v, g);
            if kept == -1 {
                g_inside = delta + (g_inside - delta) / 2.0;
            }
            kept = -1;
        } else {
            (inside, g_inside) = (v, g);
            if kept == 1 {
                g_outside = delta + (g_outside - delta) / 2.0;
            }
            kept = 1;
        }
    }
    let (a, b) = (inside[j], outside[j]);
    let (ga, gb) = (g_inside - delta, g_outside - delta);
    let x = if gb != ga {
        (a - ga * (b - a) / (gb - ga)).clamp(a.min(b), a.max(b))
    } else {
        b
    };
    (Side::Closed(x), lowest)
}

/// chi2 minimised over every coordinate but `j`, held at `x`, from `from`; the point and its chi2.
fn minimise_holding(model: &Model, from: &[f64], j: usize, x: f64) -> (Vec<f64>, f64) {
    let mut start = from.to_vec();
    start[j] = x;
    if start.len() == 1 {
        let chi2 = model.chi2(&start);
        return (start, chi2);
    }
    let problem = Problem::holding(model, &start, j);
    let (problem, _) = LevenbergMarquardt::new()
        .with_patience(PATIENCE)
        .minimize(problem);
    let chi2 = model.chi2(&problem.u);
    (problem.u, chi2)
}
