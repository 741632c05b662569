//! The weighted residuals of a fit, (model - measured) / sigma for every measurement, and their Jacobian
//! by central differences of the exact solver; rows are solved in parallel. The optimiser
//! (`levenberg-marquardt`, built on nalgebra 0.34) sees them through [`Problem`], which may hold some
//! coordinates still (a profile moves the others).

use levenberg_marquardt::LeastSquaresProblem;
use nalgebra_lm::{DMatrix, DVector, Dyn, U1, VecStorage};
use rayon::prelude::*;

use super::data::{Dataset, Row};
use super::free::{Free, place_for};
use super::watch::Tally;
use crate::model::error::MAX_TRANSITIONS;
use crate::model::{Params, SolveError, SolveOptions, solve_with, units};

/// The residual given to the optimiser where the model cannot be solved, so that it steps back.
const UNSOLVABLE: f64 = 1e100;

/// Relative step of the central differences in the optimiser's coordinates.
const STEP: f64 = 1e-5;

/// The data, the fixed parameters and the free ones: residuals and Jacobian at any coordinates.
pub struct Model<'a> {
    pub base: Params,
    pub free: &'a [Free],
    pub data: &'a Dataset,
    /// Bounces of more phases count as unsolvable.
    pub phase_limit: Option<usize>,
    /// Bounces in which the cart swings more half-periods than this within the contact time count as
    /// unsolvable: each phase of such a bounce searches for its end across every swing, slowly, and the
    /// search does not need them.
    pub swing_limit: Option<f64>,
    /// Counts the bounces solved, tells the watch after each evaluation, and stops every solve once
    /// the watch cancels.
    pub tally: &'a Tally<'a>,
}

impl Model<'_> {
    /// How many residuals: one per measurement.
    pub fn measurements(&self) -> usize {
        self.data.measurements()
    }

    /// The model's value of each measured quantity of `row`, with the free parameters at `u`.
    pub fn predict(&self, row: &Row, u: &[f64]) -> Option<Vec<f64>> {
        if self.tally.cancelled() {
            return None;
        }
        let params = row.params(&place_for(&self.base, self.free, u, row.group));
        if self
            .swing_limit
            .is_some_and(|limit| swings(&params) > limit)
        {
            return None;
        }
        let cancelled = || self.tally.cancelled();
        let options = SolveOptions {
            cancelled: &cancelled,
            max_phases: self.phase_limit.unwrap_or(MAX_TRANSITIONS),
            work: self.tally.work(),
        };
        self.tally.solved();
        let bounce = solve_with(&params, &options).ok()?;
        row.measured
            .iter()
            .map(|m| m.quantity.of(&bounce))
            .collect()
    }

    /// Why this stage of the fit counts the bounce of `params` as one it cannot solve, naming the limit
    /// that refused it (`stage` says when the limit holds: "while it searches"); `None` when it solves.
    /// For the message of a fit that fails, never on the fit's path.
    pub fn refusal(&self, params: &Params, stage: &str) -> Option<String> {
        let swung = swings(params);
        if let Some(limit) = self.swing_limit.filter(|&limit| swung > limit) {
            return Some(format!(
                "the cart swings {} half-periods within the contact time, more than the {limit} a fit \
                 allows {stage}: a heavier --cart-mass or a softer --stiffness swings fewer",
                units::brief(swung, 3)
            ));
        }
        let options = SolveOptions {
            max_phases: self.phase_limit.unwrap_or(MAX_TRANSITIONS),
            ..SolveOptions::default()
        };
        solve_with(params, &options).err().map(|e| match e {
            SolveError::TooManyPhases { limit, .. } => format!(
                "the bounce switched between sliding and gripping more than {limit} times, the most a \
                 fit allows {stage}"
            ),
            e => e.to_string(),
        })
    }

    fn row_residuals(&self, row: &Row, u: &[f64]) -> Option<Vec<f64>> {
        let model = self.predict(row, u)?;
        Some(
            row.measured
                .iter()
                .zip(model)
                .map(|(m, y)| (y - m.value) / m.sigma.unwrap_or(1.0))
                .collect(),
        )
    }

    /// The weighted residuals at `u`; `None` when a row cannot be solved there.
    pub fn residuals(&self, u: &[f64]) -> Option<Vec<f64>> {
        let rows: Option<Vec<Vec<f64>>> = self
            .data
            .rows
            .par_iter()
            .map(|row| self.row_residuals(row, u))
            .collect();
        self.tally.report();
        rows.map(|r| r.concat())
    }

    /// The sum of squared weighted residuals at `u` (infinite where a row cannot be solved).
    pub fn chi2(&self, u: &[f64]) -> f64 {
        self.residuals(u)
            .map_or(f64::INFINITY, |r| r.iter().map(|x| x * x).sum())
    }

    /// The Jacobian of the weighted residuals in the optimiser's coordinates `columns` (all of them:
    /// `0..free.len()`), row-major (one row per measurement). Each derivative is a central difference;
    /// where a range clamps a step, the step actually taken divides, and where one side cannot be solved
    /// the other side is used. A coordinate of another group than the row's has derivative zero.
    pub fn jacobian(&self, u: &[f64], columns: &[usize]) -> Option<Vec<f64>> {
        let rows: Option<Vec<Vec<f64>>> = self
            .data
            .rows
            .par_iter()
            .map(|row| self.row_jacobian(row, u, columns))
            .collect();
        self.tally.report();
        rows.map(|r| r.concat())
    }

    fn row_jacobian(&self, row: &Row, u: &[f64], wanted: &[usize]) -> Option<Vec<f64>> {
        let mut columns = Vec::with_capacity(wanted.len());
        for &j in wanted {
            let f = &self.free[j];
            if !f.holds_for(row.group) {
                columns.push(vec![0.0; row.measured.len()]);
                continue;
            }
            let h = STEP * u[j].abs().max(1.0);
            let shifted = |d: f64| {
                let mut v = u.to_vec();
                v[j] = f.coordinate(f.value(u[j] + d));
                let r = self.row_residuals(row, &v);
                (v[j], r)
            };
            let (up, r_up) = shifted(h);
            let (down, r_down) = shifted(-h);
            let column = match (r_up, r_down) {
                (Some(a), Some(b)) if up != down => diff(&a, &b, up - down),
                (Some(a), None) => diff(&a, &self.row_residuals(row, u)?, up - u[j]),
                (None, Some(b)) => diff(&self.row_residuals(row, u)?, &b, u[j] - down),
                _ => return None,
            };
            columns.push(column);
        }
        let m = row.measured.len();
        Some(
            (0..m)
                .flat_map(|i| columns.iter().map(move |c| c[i]))
                .collect(),
        )
    }
}

/// Half-periods of the cart, pi sqrt(M/k), in the contact time T.
pub fn swings(params: &Params) -> f64 {
    params.duration / (std::f64::consts::PI * (params.cart_mass / params.stiffness).sqrt())
}

fn diff(a: &[f64], b: &[f64], du: f64) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| (x - y) / du).collect()
}

/// The model as `levenberg-marquardt` sees it: at coordinates `u`, of which it moves those in `moving`.
pub struct Problem<'a> {
    pub model: &'a Model<'a>,
    pub u: Vec<f64>,
    pub moving: Vec<usize>,
}

impl<'a> Problem<'a> {
    /// The problem that moves every coordinate, from `u`.
    pub fn new(model: &'a Model<'a>, u: &[f64]) -> Self {
        Problem {
            model,
            u: u.to_vec(),
            moving: (0..u.len()).collect(),
        }
    }

    /// The problem that holds coordinate `j` at `u[j]` and moves the others.
    pub fn holding(model: &'a Model<'a>, u: &[f64], j: usize) -> Self {
        Problem {
            model,
            u: u.to_vec(),
            moving: (0..u.len()).filter(|&i| i != j).collect(),
        }
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = VecStorage<f64, Dyn, U1>;
    type JacobianStorage = VecStorage<f64, Dyn, Dyn>;
    type ParameterStorage = VecStorage<f64, Dyn, U1>;

    fn set_params(&mut self, x: &DVector<f64>) {
        for (&i, &v) in self.moving.iter().zip(x.iter()) {
            self.u[i] = v;
        }
    }

    fn params(&self) -> DVector<f64> {
        DVector::from_iterator(self.moving.len(), self.moving.iter().map(|&i| self.u[i]))
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let r = self
            .model
            .residuals(&self.u)
            .unwrap_or_else(|| vec![UNSOLVABLE; self.model.measurements()]);
        Some(DVector::from_vec(r))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let j = self.model.jacobian(&self.u, &self.moving)?;
        Some(DMatrix::from_row_slice(
            self.model.measurements(),
            self.moving.len(),
            &j,
        ))
    }
}
