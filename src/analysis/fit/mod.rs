//! Fitting parameters to measured rebounds by weighted least squares.
//!
//! Method: the residual of each measurement is (model - measured) / sigma (sigma = 1 where the data give
//! none). Starting points are a seeded random scan of each free parameter's start box (see
//! [`Free::start_box`]) plus the given values; the best few by chi2 are each refined by
//! Levenberg-Marquardt (`levenberg-marquardt`) on the Jacobian of [`problem::Model`] (both skip bounces of
//! more than 200 phases), and the lowest result is run to convergence without that limit. At the optimum the covariance in the optimiser's coordinates is s^2 (J^T J)^-1, with s^2 = 1
//! when every measurement has a sigma and chi2/dof otherwise. A parameter in the numerical null space of
//! the column-scaled J (singular value below 1e-7 of the largest) is reported as not determined by the
//! data, and the covariance is taken over the others. The 95% interval is u +- t se_u in the optimiser's
//! coordinates (the logarithm for a positive parameter), t from Student's t with dof degrees of freedom
//! (the normal quantile when the sigmas are absolute); the standard error is given in SI by the delta
//! method.

pub mod data;
pub mod free;
pub mod problem;
pub mod watch;

use levenberg_marquardt::LevenbergMarquardt;
use nalgebra::DMatrix;
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

use self::data::{Dataset, Quantity};
use self::free::{Free, Scale, coordinates, place};
use self::problem::{Model, Problem};
use self::watch::{Stage, Tally, Watch};
use super::AnalysisError;
use crate::model::params::{ParamId, spec};
use crate::model::{Params, solve, units};

/// Levenberg-Marquardt's evaluation budget, in evaluations per free parameter and one: for the short
/// runs from the starting points, and for the final run to convergence.
const SHORT_PATIENCE: usize = 20;
const PATIENCE: usize = 200;

/// The most phases a bounce may take while the scan and the short runs explore: a light cart on a stiff
/// spring grips and slips thousands of times, slowly, far from any data. The final run has no limit.
const EXPLORE_PHASES: usize = 200;

/// How the starting points are chosen.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Random points of the scan per free parameter.
    pub scan_per_parameter: usize,
    /// Points of the scan given a short run of Levenberg-Marquardt; the best result is run to convergence.
    pub refined: usize,
    pub seed: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            scan_per_parameter: 12,
            refined: 4,
            seed: 14,
        }
    }
}

/// A fitted parameter. `stderr` (SI) and `ci95` are `None` when the data cannot determine it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fitted {
    pub id: ParamId,
    pub value: f64,
    pub stderr: Option<f64>,
    pub ci95: Option<(f64, f64)>,
}

/// One measurement beside the model at the optimum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compared {
    pub quantity: Quantity,
    pub measured: f64,
    pub model: f64,
}

/// One row of the data at the optimum.
#[derive(Clone, Debug, PartialEq)]
pub struct RowFit {
    pub line: usize,
    pub values: Vec<Compared>,
}

/// The result of a fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    pub free: Vec<Fitted>,
    /// The fixed parameters with the fitted ones in place.
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
            "{}: {n} measurements cannot determine {} free parameters; give more rows than free parameters",
            data.origin,
            free.len()
        )));
    }
    let explore = Model {
        base: *base,
        free,
        data,
        phase_limit: Some(EXPLORE_PHASES),
        tally: &tally,
    };
    let model = Model {
        phase_limit: None,
        ..explore
    };
    let starts = starting_points(&explore, options);
    if let Some(stopped) = stopped() {
        return stopped;
    }
    if !starts[0].1.is_finite() {
        let row = &data.rows[0];
        let err = solve(&row.params(base)).err();
        return Err(AnalysisError::Input(format!(
            "{}: the model cannot be solved at any starting point{}",
            data.origin,
            err.map_or(String::new(), |e| format!(" (line {}: {e})", row.line))
        )));
    }
    let refine = |model: &Model, u: &[f64], patience: usize| {
        let problem = Problem {
            model,
            u: nalgebra_lm::DVector::from_column_slice(u),
        };
        let (problem, report) = LevenbergMarquardt::new()
            .with_patience(patience)
            .minimize(problem);
        let u = problem.u.as_slice().to_vec();
        let chi2 = model.chi2(&u);
        (u, chi2, report.termination.was_successful())
    };
    // A short run from each of the best starting points, then the best of them to convergence.
    let runs = options.refined.max(1).min(starts.len());
    let (best, _, _) = starts
        .iter()
        .take(runs)
        .enumerate()
        .filter(|(_, (_, chi2))| chi2.is_finite())
        .map(|(i, (u, _))| {
            tally.at(Stage::Refine, i, runs);
            refine(&explore, u, SHORT_PATIENCE)
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("the best starting point solves");
    tally.at(Stage::Converge, 0, 1);
    if let Some(stopped) = stopped() {
        return stopped;
    }
    let (u, _, converged) = refine(&model, &best, PATIENCE);
    let fit = summarise(&model, &u, converged);
    if let Some(stopped) = stopped() {
        return stopped;
    }
    tally.at(Stage::Converge, 1, 1);
    fit
}

/// The given values and a seeded random scan of the start boxes, with their chi2, best first.
fn starting_points(model: &Model, options: &Options) -> Vec<(Vec<f64>, f64)> {
    let given = coordinates(&model.base, model.free);
    let boxes: Vec<(f64, f64)> = model
        .free
        .iter()
        .map(|f| f.start_box(model.base.get(f.id())))
        .collect();
    let mut rng = StdRng::seed_from_u64(options.seed);
    let total = 1 + options.scan_per_parameter * model.free.len();
    let mut points = vec![given];
    for _ in 0..options.scan_per_parameter * model.free.len() {
        points.push(
            boxes
                .iter()
                .map(|&(a, b)| a + (b - a) * rng.random::<f64>())
                .collect(),
        );
    }
    let mut scored: Vec<_> = points
        .into_iter()
        .enumerate()
        .map(|(i, u)| {
            model.tally.at(Stage::Scan, i, total);
            let chi2 = model.chi2(&u);
            (u, chi2)
        })
        .collect();
    scored.sort_by(|a, b| a.1.total_cmp(&b.1));
    scored
}

/// The statistics at the optimum `u`.
fn summarise(model: &Model, u: &[f64], converged: bool) -> Result<Fit, AnalysisError> {
    let (free, data) = (model.free, model.data);
    let (n, k) = (data.measurements(), free.len());
    let failed = || {
        AnalysisError::Input(format!(
            "{}: the model cannot be solved at the fitted parameters",
            data.origin
        ))
    };
    let residuals = model.residuals(u).ok_or_else(failed)?;
    let jacobian = DMatrix::from_row_slice(n, k, &model.jacobian(u).ok_or_else(failed)?);
    let chi2: f64 = residuals.iter().map(|r| r * r).sum();
    let dof = n - k;
    let determined = determined_columns(&jacobian);
    let s2 = if data.absolute_sigma {
        1.0
    } else {
        chi2 / dof as f64
    };
    let covariance = covariance(&jacobian, &determined).map(|c| c * s2);
    let t = if data.absolute_sigma {
        Normal::standard().inverse_cdf(0.975)
    } else {
        StudentsT::new(0.0, 1.0, dof as f64)
            .expect("dof is at least 1")
            .inverse_cdf(0.975)
    };
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
                value,
                stderr,
                ci95,
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
                    })
                    .collect(),
            })
        })
        .collect::<Result<_, AnalysisError>>()?;
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
