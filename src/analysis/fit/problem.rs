//! The weighted residuals of a fit, (model - measured) / sigma for every measurement, and their Jacobian
//! by central differences of the exact solver; rows are solved in parallel. The optimiser
//! (`levenberg-marquardt`, built on nalgebra 0.34) sees them through [`Problem`].

use levenberg_marquardt::LeastSquaresProblem;
use nalgebra_lm::{DMatrix, DVector, Dyn, U1, VecStorage};
use rayon::prelude::*;

use super::data::{Dataset, Row};
use super::free::{Free, place};
use super::watch::Tally;
use crate::model::error::MAX_TRANSITIONS;
use crate::model::{Params, SolveOptions, solve_with};

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
        let params = row.params(&place(&self.base, self.free, u));
        let cancelled = || self.tally.cancelled();
        let options = SolveOptions {
            cancelled: &cancelled,
            max_phases: self.phase_limit.unwrap_or(MAX_TRANSITIONS),
            work: None,
        };
        self.tally.solved();
        let bounce = solve_with(&params, &options).ok()?;
        row.measured
            .iter()
            .map(|m| m.quantity.of(&bounce))
            .collect()
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

    /// The Jacobian of the weighted residuals in the optimiser's coordinates, row-major (one row per
    /// measurement). Each derivative is a central difference; where a range clamps a step, the step
    /// actually taken divides, and where one side cannot be solved the other side is used.
    pub fn jacobian(&self, u: &[f64]) -> Option<Vec<f64>> {
        let rows: Option<Vec<Vec<f64>>> = self
            .data
            .rows
            .par_iter()
            .map(|row| self.row_jacobian(row, u))
            .collect();
        self.tally.report();
        rows.map(|r| r.concat())
    }

    fn row_jacobian(&self, row: &Row, u: &[f64]) -> Option<Vec<f64>> {
        let k = self.free.len();
        let mut columns = Vec::with_capacity(k);
        for (j, f) in self.free.iter().enumerate() {
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

fn diff(a: &[f64], b: &[f64], du: f64) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| (x - y) / du).collect()
}

/// The model as `levenberg-marquardt` sees it, at coordinates `u`.
pub struct Problem<'a> {
    pub model: &'a Model<'a>,
    pub u: DVector<f64>,
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = VecStorage<f64, Dyn, U1>;
    type JacobianStorage = VecStorage<f64, Dyn, Dyn>;
    type ParameterStorage = VecStorage<f64, Dyn, U1>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.u.copy_from(x);
    }

    fn params(&self) -> DVector<f64> {
        self.u.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let r = self
            .model
            .residuals(self.u.as_slice())
            .unwrap_or_else(|| vec![UNSOLVABLE; self.model.measurements()]);
        Some(DVector::from_vec(r))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let j = self.model.jacobian(self.u.as_slice())?;
        Some(DMatrix::from_row_slice(
            self.model.measurements(),
            self.model.free.len(),
            &j,
        ))
    }
}
