//! The measurements given with `--data` beside the model at the current parameters: each row solved at
//! its own conditions (as `snapback fit` solves it), in parallel, off the UI thread, and abandoned as
//! soon as newer parameters are asked for. The outcome panel shows the summary (`ui::residuals`).

use rayon::prelude::*;

use crate::analysis::fit::data::{Dataset, Quantity};
use crate::model::{Params, SolveError, solve_cancellable};

/// One measured value beside the model's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compared {
    /// The row's line in the file.
    pub line: usize,
    pub quantity: Quantity,
    pub measured: f64,
    pub model: f64,
    pub sigma: Option<f64>,
}

impl Compared {
    /// model - measured, in the quantity's unit.
    pub fn residual(&self) -> f64 {
        self.model - self.measured
    }

    /// The residual in sigmas (in the quantity's unit without a sigma), as the fit weighs it.
    pub fn weighted(&self) -> f64 {
        self.residual() / self.sigma.unwrap_or(1.0)
    }
}

/// The data at one set of parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Residuals {
    pub params: Params,
    /// Every measurement of the rows the model gives, in the file's order.
    pub compared: Vec<Compared>,
    /// Lines of the rows it does not: the solver refuses their conditions, or e_x without slip.
    pub unsolved: Vec<usize>,
    /// True when every measurement has a sigma: the weighted residuals are in sigmas.
    pub absolute_sigma: bool,
}

impl Residuals {
    /// The data at `params`; `None` once `cancelled` says so.
    pub fn compute(
        params: &Params,
        data: &Dataset,
        cancelled: &(impl Fn() -> bool + Sync),
    ) -> Option<Residuals> {
        let rows: Vec<Result<Vec<Compared>, usize>> = data
            .rows
            .par_iter()
            .map(|row| {
                let bounce = match solve_cancellable(&row.params(params), cancelled) {
                    Ok(bounce) => bounce,
                    Err(SolveError::Cancelled) => return None,
                    Err(_) => return Some(Err(row.line)),
                };
                let compared: Option<Vec<Compared>> = row
                    .measured
                    .iter()
                    .map(|m| {
                        Some(Compared {
                            line: row.line,
                            quantity: m.quantity,
                            measured: m.value,
                            model: m.quantity.of(&bounce)?,
                            sigma: m.sigma,
                        })
                    })
                    .collect();
                Some(compared.ok_or(row.line))
            })
            .collect::<Option<_>>()?;
        let mut residuals = Residuals {
            params: *params,
            compared: Vec::new(),
            unsolved: Vec::new(),
            absolute_sigma: data.absolute_sigma,
        };
        for row in rows {
            match row {
                Ok(compared) => residuals.compared.extend(compared),
                Err(line) => residuals.unsolved.push(line),
            }
        }
        Some(residuals)
    }

    /// The sum of squared weighted residuals.
    pub fn chi2(&self) -> f64 {
        self.compared.iter().map(|c| c.weighted().powi(2)).sum()
    }

    /// sqrt(chi2 / measurements), as `snapback fit` reports it; `None` without measurements.
    pub fn rms(&self) -> Option<f64> {
        (!self.compared.is_empty()).then(|| (self.chi2() / self.compared.len() as f64).sqrt())
    }

    /// The measurement furthest from the model, in weighted terms.
    pub fn worst(&self) -> Option<&Compared> {
        self.compared
            .iter()
            .max_by(|a, b| a.weighted().abs().total_cmp(&b.weighted().abs()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::fit::data::parse;
    use crate::model::solve;

    #[test]
    fn each_row_is_solved_at_its_conditions() {
        let data = parse("angle,omega2,sigma_omega2\n40,100,2\n60,150,5\n", "d.csv").unwrap();
        let params = Params::default();
        let r = Residuals::compute(&params, &data, &|| false).unwrap();
        let at = |angle: f64| {
            let mut p = params;
            p.angle_deg = angle;
            solve(&p).unwrap().outcome.omega2
        };
        assert_eq!(r.compared.len(), 2);
        assert_eq!(r.compared[1].model, at(60.0));
        let chi2 = ((at(40.0) - 100.0) / 2.0).powi(2) + ((at(60.0) - 150.0) / 5.0).powi(2);
        assert!((r.chi2() - chi2).abs() < 1e-9 * chi2);
        assert!(r.absolute_sigma && r.unsolved.is_empty());
        assert!(Residuals::compute(&params, &data, &|| true).is_none());
    }
}
