//! Fitting parameters to measured rebounds by weighted least squares.
//!
//! Method: the residual of each measurement is (model - measured) / sigma (sigma = 1 where the data give
//! none). The global search ([`search`]) scores a seeded Halton set of points over the free parameters'
//! start boxes (half of them guided by the cart's half-period against the contact time), gives the best
//! distinct ones ([`Options::starts`]) each a short run of Levenberg-Marquardt (`levenberg-marquardt`) on
//! the Jacobian of [`problem::Model`] in parallel (the scan and the short runs skip bounces of more than
//! 200 phases), sorts where they end into distinct minima and runs each to convergence; the lowest is the
//! fit, and every one is reported ([`Fit::minima`]). At the optimum the covariance in the optimiser's
//! coordinates is s^2 (J^T J)^-1, with s^2 = 1 when every measurement has a sigma and chi2/dof otherwise.
//! A parameter in the numerical null space of the column-scaled J (singular value below 1e-7 of the
//! largest) is reported as not determined by the data, and the covariance is taken over the others. The
//! Wald 95% interval is u +- t se_u in the optimiser's coordinates (the logarithm for a positive
//! parameter), t from Student's t with dof degrees of freedom (the normal quantile when the sigmas are
//! absolute); the standard error is given in SI by the delta method. The profile-likelihood interval
//! ([`profile`]) is where the profile chi2 rises by no more than t^2 s^2 (3.84 with absolute sigmas); a
//! side that reaches an end of the parameter's range is open. With absolute sigmas the verdict is the
//! chi-squared test: p = P(chi2_dof >= chi2), "poor" below [`P_POOR`].

pub mod data;
pub mod free;
pub mod problem;
pub mod profile;
pub mod search;
pub mod watch;

use std::sync::atomic::{AtomicUsize, Ordering};

use levenberg_marquardt::LevenbergMarquardt;
use nalgebra::DMatrix;
use rayon::prelude::*;
use statrs::distribution::{ChiSquared, ContinuousCDF, Normal, StudentsT};

use self::data::{Dataset, Quantity};
use self::free::{Free, Scale, coordinates, place, place_for};
use self::problem::{Model, Problem};
use self::profile::{Axis, Side};
use self::search::Point;
use self::watch::{Stage, Tally, Watch};
use super::AnalysisError;
use crate::model::params::{ParamId, spec};
use crate::model::{Params, units};

/// Levenberg-Marquardt's evaluation budget, in evaluations per free parameter and one: for the short
/// runs from the starting points, and for the runs to convergence.
const SHORT_PATIENCE: usize = 20;
const PATIENCE: usize = 200;

/// The most phases a bounce may take while the scan and the short runs explore: a light cart on a stiff
/// spring grips and slips thousands of times, slowly, far from any data.
const EXPLORE_PHASES: usize = 60;
/// The most half-periods of the cart within the contact time while the scan and the short runs
/// explore: four times the most the guided starting points hold (see [`search::RATIO`]).
const EXPLORE_SWINGS: f64 = 4.0 * search::RATIO.1;
/// ... and while the minima converge and the profiles are walked: a bounce of more phases counts as
/// one the model cannot solve, so that the optimiser steps back from it.
const FINAL_PHASES: usize = 1000;
/// ... and the most half-periods of the cart then: ten times the most the guided starting points hold.
const FINAL_SWINGS: f64 = 10.0 * search::RATIO.1;

/// Points of the scan scored per starting point given a short run.
const SCAN_PER_START: usize = 48;
/// Points closer than this (the largest coordinate difference, in widths of its start box) are one:
/// starting points, and the ends of runs (one minimum).
const START_RADIUS: f64 = 0.03;
const SAME_MINIMUM: f64 = 0.01;
/// The most distinct ends of the short runs run to convergence, and how far above the best one's chi2
/// an end may lie and still be (chi2 at most this times the best's, plus [`AMBIGUOUS`]).
const MOST_MINIMA: usize = 8;
const PROMISING: f64 = 4.0;

/// Below this p-value the model does not describe the data: the verdict is poor.
pub const P_POOR: f64 = 1e-3;
/// A measurement whose standardised residual exceeds this is a likely outlier.
pub const OUTLIER: f64 = 3.0;
/// A second minimum within this of the best chi2 is one the data do not rule out.
pub const AMBIGUOUS: f64 = 10.0;

/// How the search starts and what it reports.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Starting points given a short run of Levenberg-Marquardt: the effort of the global search (the
    /// scan scores 48 points for each).
    pub starts: usize,
    pub seed: u64,
    /// Compute the profile-likelihood intervals too (about as costly again as the search).
    pub profile: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            starts: 32,
            seed: 14,
            profile: true,
        }
    }
}

/// A fitted parameter: shared by every row (`group` `None`), or one group's value. `stderr` (SI) and
/// `ci95` are `None` when the data cannot determine it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fitted {
    pub id: ParamId,
    pub group: Option<usize>,
    pub value: f64,
    pub stderr: Option<f64>,
    pub ci95: Option<(f64, f64)>,
    /// The profile-likelihood 95% interval, its low and high ends; an end `None` is open (the interval
    /// reaches 0, infinity or the end of the parameter's range). `None` when not computed.
    pub profile95: Option<(Option<f64>, Option<f64>)>,
}

impl Fitted {
    /// Not determined by the data, or an interval open on a side.
    pub fn poorly_determined(&self) -> bool {
        self.stderr.is_none()
            || self
                .profile95
                .is_some_and(|(lo, hi)| lo.is_none() || hi.is_none())
    }
}

/// One measurement beside the model at the optimum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compared {
    pub quantity: Quantity,
    pub measured: f64,
    pub model: f64,
    /// (model - measured) / sigma, with the data's sigma or, without one, the scatter s.
    pub standardised: f64,
}

/// One row of the data at the optimum.
#[derive(Clone, Debug, PartialEq)]
pub struct RowFit {
    pub line: usize,
    pub values: Vec<Compared>,
}

/// A minimum of chi2 the search found: chi2 and the free parameters' values (SI, in their order).
#[derive(Clone, Debug, PartialEq)]
pub struct Minimum {
    pub chi2: f64,
    pub values: Vec<f64>,
}

/// What the chi-squared test says of the fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// p >= [`P_POOR`]: the model describes the data within their sigmas.
    Consistent,
    /// p < [`P_POOR`]: it does not (or the sigmas are understated, or some rows are outliers).
    Poor,
    /// No sigmas: the scatter was estimated from the residuals, so nothing can be judged.
    Unjudged,
}

impl Verdict {
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Consistent => "consistent",
            Verdict::Poor => "poor",
            Verdict::Unjudged => "unjudged",
        }
    }
}

/// The result of a fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    pub free: Vec<Fitted>,
    /// The fixed parameters with the shared fitted ones in place.
    pub params: Params,
    /// Sum of squared weighted residuals.
    pub chi2: f64,
    /// Measurements less free parameters.
    pub dof: usize,
    /// sqrt(chi2 / measurements): in the data's units without sigmas, in sigmas with them.
    pub rms: f64,
    /// Correlations of the free parameters, in their order; `None` beside an undetermined one.
    pub correlation: Vec<Vec<Option<f64>>>,
    pub rows: Vec<RowFit>,
    /// Levenberg-Marquardt met its tolerance and every parameter is determined.
    pub converged: bool,
    pub absolute_sigma: bool,
    /// P(chi2 with dof degrees of freedom >= chi2), with absolute sigmas.
    pub p_value: Option<f64>,
    pub verdict: Verdict,
    /// Every distinct minimum the search found, best (the fit) first.
    pub minima: Vec<Minimum>,
    /// The incoming conditions no column of the data sets, with the value every row took (SI).
    pub assumed: Vec<(ParamId, f64)>,
    /// The labels of the data's groups (the `group` of a [`Fitted`] indexes them).
    pub groups: Vec<String>,
}

impl Fit {
    /// The free parameters the data cannot determine.
    pub fn undetermined(&self) -> Vec<ParamId> {
        self.free
            .iter()
            .filter(|f| f.stderr.is_none())
            .map(|f| f.id)
            .collect()
    }

    /// The measurements whose standardised residual exceeds [`OUTLIER`]: line, quantity, residual.
    pub fn outliers(&self) -> Vec<(usize, Quantity, f64)> {
        self.rows
            .iter()
            .flat_map(|r| r.values.iter().map(move |c| (r.line, c)))
            .filter(|(_, c)| c.standardised.abs() > OUTLIER)
            .map(|(line, c)| (line, c.quantity, c.standardised))
            .collect()
    }

    /// The second-best minimum, if its chi2 lies within [`AMBIGUOUS`] of the best.
    pub fn rival(&self) -> Option<&Minimum> {
        self.minima
            .get(1)
            .filter(|m| m.chi2 - self.chi2 < AMBIGUOUS)
    }
}

/// A value in a parameter's display unit, to the decimal place of the second significant digit of
/// `precision` (its standard error; at most 9 decimals), or to 5 significant digits without one.
pub fn shown(id: ParamId, value: f64, precision: Option<f64>) -> String {
    let s = spec(id);
    let display = |x: f64| units::in_unit(x, s.dimension, s.display_unit);
    match precision.map(display).filter(|p| *p > 0.0) {
        Some(p) => {
            let decimals = (1 - p.log10().floor() as i32).clamp(0, 9) as usize;
            format!("{:.decimals$}", display(value))
        }
        None => units::brief(display(value), 5),
    }
}

/// Fits `free` to `data`, the other parameters as in `base` (and each row's conditions).
pub fn fit(
    base: &Params,
    free: &[Free],
    data: &Dataset,
    options: &Options,
) -> Result<Fit, AnalysisError> {
    fit_watched(base, free, data, options, &Watch::none())
}

/// [`fit`], telling `watch` where it has got to and stopping once it cancels
/// ([`AnalysisError::Cancelled`]); the result is the same as [`fit`]'s.
pub fn fit_watched(
    base: &Params,
    free: &[Free],
    data: &Dataset,
    options: &Options,
    watch: &Watch,
) -> Result<Fit, AnalysisError> {
    let tally = Tally::new(watch);
    let stopped = || tally.cancelled().then_some(Err(AnalysisError::Cancelled));
    let n = data.measurements();
    if free.is_empty() {
        return Err(AnalysisError::Input(
            "--free: name at least one parameter to fit".into(),
        ));
    }
    if n <= free.len() {
        return Err(AnalysisError::Input(format!(
            "{}: {n} measurements cannot determine {} free {}; give more rows than free parameters",
            data.origin,
            free.len(),
            if free.len() == 1 {
                "parameter"
            } else {
                "parameters"
            }
        )));
    }
    let explore = Model {
        base: *base,
        free,
        data,
        phase_limit: Some(EXPLORE_PHASES),
        swing_limit: Some(EXPLORE_SWINGS),
        tally: &tally,
    };
    let model = Model {
        phase_limit: Some(FINAL_PHASES),
        swing_limit: Some(FINAL_SWINGS),
        ..explore
    };
    let boxes = search::boxes(base, free);
    let starts = scan(&explore, options);
    if let Some(stopped) = stopped() {
        return stopped;
    }
    if starts.is_empty() {
        // Why, at the parameters given: the first row the search refuses there, and the limit.
        let why = data.rows.iter().find_map(|row| {
            explore
                .refusal(&row.params(base), "while it searches")
                .map(|why| format!(" (line {}: {why})", row.line))
        });
        return Err(AnalysisError::Input(format!(
            "{}: the model cannot be solved at any starting point{}",
            data.origin,
            why.unwrap_or_default()
        )));
    }
    // A short run from each starting point, in parallel; their ends, one per basin, to convergence.
    let ends = in_parallel(&tally, Stage::Refine, &starts, |p| {
        refine(&explore, &p.u, SHORT_PATIENCE)
    });
    let mut ends = search::distinct(ends, &boxes, SAME_MINIMUM, MOST_MINIMA);
    if let Some(best) = ends.first().map(|p| p.chi2) {
        ends.retain(|p| p.chi2 <= PROMISING * best + AMBIGUOUS);
    }
    if let Some(stopped) = stopped() {
        return stopped;
    }
    let converged = in_parallel(&tally, Stage::Converge, &ends, |p| {
        refine(&model, &p.u, PATIENCE)
    });
    let mut minima = search::distinct(converged, &boxes, SAME_MINIMUM, usize::MAX);
    if let Some(stopped) = stopped() {
        return stopped;
    }
    if minima.is_empty() {
        return Err(unsolved_at(&model, ends.first().map(|p| p.u.as_slice())));
    }
    let mut fit = summarise(&model, &minima[0].u, minima[0].converged)?;
    if options.profile {
        // A profile that finds a lower chi2 than the search did restarts the fit from there, once.
        for last in [false, true] {
            let lower = profile_all(&model, &minima[0], &mut fit, &tally);
            if let Some(stopped) = stopped() {
                return stopped;
            }
            match lower {
                Some(point) if !last => {
                    let better = refine(&model, &point.u, PATIENCE);
                    minima.push(better);
                    minima = search::distinct(minima, &boxes, SAME_MINIMUM, usize::MAX);
                    fit = summarise(&model, &minima[0].u, minima[0].converged)?;
                }
                _ => break,
            }
        }
    }
    tally.at(Stage::Profile, 1, 1);
    fit.minima = minima
        .iter()
        .map(|m| Minimum {
            chi2: m.chi2,
            values: free.iter().zip(&m.u).map(|(f, &x)| f.value(x)).collect(),
        })
        .collect();
    fit.assumed = data.assumed(base);
    fit.groups = data.groups.clone();
    Ok(fit)
}

/// The given values and a seeded Halton scan of the start boxes, scored, thinned to the best
/// [`Options::starts`] distinct ones.
fn scan(model: &Model, options: &Options) -> Vec<Point> {
    let mut points = vec![coordinates(&model.base, model.free)];
    points.extend(search::starting_points(
        &model.base,
        model.free,
        SCAN_PER_START * options.starts.max(1),
        options.seed,
    ));
    let scored = in_parallel(model.tally, Stage::Scan, &points, |u| Point {
        chi2: model.chi2(u),
        u: u.clone(),
        converged: false,
    });
    let boxes = search::boxes(&model.base, model.free);
    search::distinct(scored, &boxes, START_RADIUS, options.starts.max(1))
}

/// `task` of each of `items` in parallel, in their order, the watch told of each one done at `stage`.
fn in_parallel<T: Sync, R: Send>(
    tally: &Tally,
    stage: Stage,
    items: &[T],
    task: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let done = AtomicUsize::new(0);
    tally.at(stage, 0, items.len());
    items
        .par_iter()
        .map(|item| {
            let r = task(item);
            tally.at(stage, done.fetch_add(1, Ordering::Relaxed) + 1, items.len());
            r
        })
        .collect()
}

/// Levenberg-Marquardt from `u` with the evaluation budget `patience`.
fn refine(model: &Model, u: &[f64], patience: usize) -> Point {
    let (problem, report) = LevenbergMarquardt::new()
        .with_patience(patience)
        .minimize(Problem::new(model, u));
    Point {
        chi2: model.chi2(&problem.u),
        u: problem.u,
        converged: report.termination.was_successful(),
    }
}

/// The rise of chi2 that bounds a 95% interval: the chi-squared quantile of one degree of freedom
/// with absolute sigmas, else t^2 s^2 as the Wald interval uses.
fn rise(fit: &Fit) -> f64 {
    let (t, s2) = t_and_scale(fit.absolute_sigma, fit.chi2, fit.dof);
    t * t * s2
}

/// The 97.5% quantile (normal with absolute sigmas, Student's t otherwise) and the scale s^2.
fn t_and_scale(absolute: bool, chi2: f64, dof: usize) -> (f64, f64) {
    if absolute {
        (Normal::standard().inverse_cdf(0.975), 1.0)
    } else {
        let t = StudentsT::new(0.0, 1.0, dof as f64)
            .expect("dof is at least 1")
            .inverse_cdf(0.975);
        (t, chi2 / dof as f64)
    }
}

/// The profile intervals of every free parameter of `fit`, at the optimum `best`; the lowest point
/// met below it, if any.
fn profile_all(model: &Model, best: &Point, fit: &mut Fit, tally: &Tally) -> Option<Point> {
    let delta = rise(fit);
    let sides: Vec<(usize, f64)> = (0..model.free.len())
        .flat_map(|j| [(j, -1.0), (j, 1.0)])
        .collect();
    let ends = in_parallel(tally, Stage::Profile, &sides, |&(j, direction)| {
        let f = &model.free[j];
        let step = fit.free[j].ci95.map_or(f64::NAN, |(lo, hi)| {
            (f.coordinate(hi) - f.coordinate(lo)).abs() / 2.0
        });
        let axis = Axis {
            j,
            step,
            range: f.coordinate_range(),
        };
        profile::side(model, (&best.u, best.chi2), axis, delta, direction)
    });
    let mut lower: Option<Point> = None;
    for (&(j, direction), (side, low)) in sides.iter().zip(ends) {
        let f = &model.free[j];
        let end = match side {
            Side::Closed(x) => Some(f.value(x)),
            Side::Open => None,
        };
        let interval = fit.free[j].profile95.get_or_insert((None, None));
        if direction < 0.0 {
            interval.0 = end;
        } else {
            interval.1 = end;
        }
        if let Some((u, chi2)) = low
            && chi2 < best.chi2 - 1e-6 * best.chi2.max(1.0)
            && lower.as_ref().is_none_or(|l| chi2 < l.chi2)
        {
            lower = Some(Point {
                u,
                chi2,
                converged: false,
            });
        }
    }
    lower
}

/// The error of a fit whose `model` cannot be solved at `u`: the first row it refuses there, and the
/// limit (at most [`FINAL_PHASES`] phases and [`FINAL_SWINGS`] half-periods of the cart).
fn unsolved_at(model: &Model, u: Option<&[f64]>) -> AnalysisError {
    let why = u.and_then(|u| {
        model.data.rows.iter().find_map(|row| {
            let params = row.params(&place_for(&model.base, model.free, u, row.group));
            model
                .refusal(&params, "as it converges")
                .map(|why| format!(" (line {}: {why})", row.line))
        })
    });
    AnalysisError::Input(format!(
        "{}: the model cannot be solved at the fitted parameters{}",
        model.data.origin,
        why.unwrap_or_default()
    ))
}

/// The statistics at the optimum `u`.
fn summarise(model: &Model, u: &[f64], converged: bool) -> Result<Fit, AnalysisError> {
    let (free, data) = (model.free, model.data);
    let (n, k) = (data.measurements(), free.len());
    let failed = || unsolved_at(model, Some(u));
    let residuals = model.residuals(u).ok_or_else(failed)?;
    let all: Vec<usize> = (0..k).collect();
    let jacobian = DMatrix::from_row_slice(n, k, &model.jacobian(u, &all).ok_or_else(failed)?);
    let chi2: f64 = residuals.iter().map(|r| r * r).sum();
    let dof = n - k;
    let determined = determined_columns(&jacobian);
    let (t, s2) = t_and_scale(data.absolute_sigma, chi2, dof);
    let covariance = covariance(&jacobian, &determined).map(|c| c * s2);
    // Position of each free parameter in the covariance of the determined ones.
    let slot = |j: usize| {
        determined
            .iter()
            .position(|&d| d == j)
            .filter(|_| covariance.is_some())
    };
    let fitted = free
        .iter()
        .enumerate()
        .map(|(j, f)| {
            let value = f.value(u[j]);
            let se_u = slot(j).and_then(|s| covariance.as_ref().map(|c| c[(s, s)].sqrt()));
            let stderr = se_u.map(|se| match f.scale {
                Scale::Log => value * se,
                Scale::Linear => se,
            });
            let ci95 = se_u.map(|se| (f.value(u[j] - t * se), f.value(u[j] + t * se)));
            Fitted {
                id: f.id(),
                group: f.group,
                value,
                stderr,
                ci95,
                profile95: None,
            }
        })
        .collect();
    let correlation = (0..k)
        .map(|a| {
            (0..k)
                .map(|b| {
                    let (sa, sb) = (slot(a)?, slot(b)?);
                    let c = covariance.as_ref()?;
                    Some(c[(sa, sb)] / (c[(sa, sa)] * c[(sb, sb)]).sqrt())
                })
                .collect()
        })
        .collect();
    let s = s2.sqrt();
    let rows = data
        .rows
        .iter()
        .map(|row| {
            let predicted = model.predict(row, u).ok_or_else(failed)?;
            Ok(RowFit {
                line: row.line,
                values: row
                    .measured
                    .iter()
                    .zip(predicted)
                    .map(|(m, y)| Compared {
                        quantity: m.quantity,
                        measured: m.value,
                        model: y,
                        standardised: (y - m.value) / m.sigma.unwrap_or(1.0) / s,
                    })
                    .collect(),
            })
        })
        .collect::<Result<_, AnalysisError>>()?;
    let p_value = data.absolute_sigma.then(|| {
        ChiSquared::new(dof as f64)
            .expect("dof is at least 1")
            .sf(chi2)
    });
    let verdict = match p_value {
        None => Verdict::Unjudged,
        Some(p) if p < P_POOR => Verdict::Poor,
        Some(_) => Verdict::Consistent,
    };
    Ok(Fit {
        free: fitted,
        params: place(&model.base, free, u),
        chi2,
        dof,
        rms: (chi2 / n as f64).sqrt(),
        correlation,
        rows,
        converged: converged && determined.len() == k && covariance.is_some(),
        absolute_sigma: data.absolute_sigma,
        p_value,
        verdict,
        minima: Vec::new(),
        assumed: Vec::new(),
        groups: Vec::new(),
    })
}

/// The columns of `jacobian` outside its numerical null space: a column of zeros, or one that takes part
/// (a component above 0.3) in a right singular vector whose singular value is below 1e-7 of the largest,
/// once every column is scaled to unit length.
fn determined_columns(jacobian: &DMatrix<f64>) -> Vec<usize> {
    let k = jacobian.ncols();
    let norms: Vec<f64> = (0..k).map(|j| jacobian.column(j).norm()).collect();
    let mut scaled = jacobian.clone();
    for (j, &norm) in norms.iter().enumerate() {
        if norm > 0.0 && norm.is_finite() {
            scaled.column_mut(j).unscale_mut(norm);
        }
    }
    let svd = scaled.svd(false, true);
    let largest = svd.singular_values.max();
    let v_t = svd.v_t.expect("v_t was asked for");
    let mut determined: Vec<bool> = norms.iter().map(|&n| n > 0.0 && n.is_finite()).collect();
    for (i, &s) in svd.singular_values.iter().enumerate() {
        if s.is_nan() || s <= 1e-7 * largest {
            for (j, d) in determined.iter_mut().enumerate() {
                if v_t[(i, j)].abs() > 0.3 {
                    *d = false;
                }
            }
        }
    }
    (0..k).filter(|&j| determined[j]).collect()
}

/// (J_d^T J_d)^-1 over the determined columns d; `None` when it cannot be inverted.
fn covariance(jacobian: &DMatrix<f64>, determined: &[usize]) -> Option<DMatrix<f64>> {
    if determined.is_empty() {
        return None;
    }
    let j = jacobian.select_columns(determined);
    (j.transpose() * &j).cholesky().map(|c| c.inverse())
}
