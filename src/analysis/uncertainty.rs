//! Outcomes of uncertain inputs by Monte Carlo: each uncertain parameter is drawn from a normal
//! distribution (its value, its standard uncertainty), clamped into its range, the bounce is solved for
//! every draw (in parallel), and each outcome's mean and sample standard deviation are reported. Draw i
//! comes from a generator seeded by (seed, i), so a result depends on the seed and the count alone, not on
//! the threads.

use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use rayon::prelude::*;

use super::AnalysisError;
use super::fit::data::Quantity;
use crate::model::params::{ParamId, ParamSpec, spec};
use crate::model::{ParamError, Params, SolveOptions, solve_with, units};

/// The default number of draws.
pub const DEFAULT_SAMPLES: usize = 1000;

/// A parameter's standard uncertainty, in its base unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    pub id: ParamId,
    pub sigma: f64,
}

/// A value with an uncertainty that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum UncertainError {
    #[error(transparent)]
    Value(#[from] ParamError),
    /// The uncertainty, as typed, is not a number >= 0 in the value's unit.
    #[error(
        "--{flag}: the uncertainty must be a number >= 0 (a unit suffix as for the value); got {given}"
    )]
    Spread { flag: &'static str, given: String },
}

/// `text` split at `±` or `+-` into the value and its uncertainty, if it has one.
pub fn split_uncertainty(text: &str) -> (&str, Option<&str>) {
    for mark in ["±", "+-"] {
        if let Some((value, spread)) = text.split_once(mark) {
            return (value, Some(spread));
        }
    }
    (text, None)
}

/// The unit suffix of a value as typed (`rpm` of `-3820rpm`, empty for a bare number).
fn suffix(value: &str) -> &str {
    value
        .trim()
        .trim_start_matches(|c: char| c.is_ascii_digit() || "+-.eE ".contains(c))
}

/// A value of `spec` as typed, with its standard uncertainty if it carries one (`50±1`, `50+-1`,
/// `-3820rpm±200`: a bare uncertainty is in the value's unit); both in the base unit.
pub fn parse_uncertain(spec: &ParamSpec, text: &str) -> Result<(f64, Option<f64>), UncertainError> {
    let (value, spread) = split_uncertainty(text);
    let parsed = spec.parse(value)?;
    let Some(spread) = spread else {
        return Ok((parsed, None));
    };
    let spread = spread.trim();
    let typed = if spread.parse::<f64>().is_ok() {
        format!("{spread}{}", suffix(value))
    } else {
        spread.to_string()
    };
    let sigma = units::parse(&typed, spec.dimension)
        .ok()
        .filter(|v| v.is_finite() && *v >= 0.0)
        .ok_or_else(|| UncertainError::Spread {
            flag: spec.flag,
            given: spread.to_string(),
        })?;
    Ok((parsed, Some(sigma)))
}

/// One outcome's mean and standard deviation over the draws (`None` where no draw defines it: e_x
/// without incoming slip).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Band {
    pub quantity: Quantity,
    pub mean: f64,
    pub sd: f64,
    /// Draws in which the outcome is defined.
    pub count: usize,
}

/// The result of a Monte Carlo run.
#[derive(Clone, Debug, PartialEq)]
pub struct Bands {
    pub samples: usize,
    pub seed: u64,
    pub bands: Vec<Band>,
}

/// Solves `samples` draws of `base` with `spreads`, seeded by `seed`.
pub fn monte_carlo(
    base: &Params,
    spreads: &[Spread],
    samples: usize,
    seed: u64,
) -> Result<Bands, AnalysisError> {
    monte_carlo_with(base, spreads, samples, seed, &SolveOptions::default())
}

/// [`monte_carlo`] with every draw solved on the caller's terms.
pub fn monte_carlo_with(
    base: &Params,
    spreads: &[Spread],
    samples: usize,
    seed: u64,
    options: &SolveOptions,
) -> Result<Bands, AnalysisError> {
    let draws: Vec<Params> = (0..samples)
        .map(|i| {
            let mut rng =
                StdRng::seed_from_u64(seed ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
            let mut p = *base;
            for s in spreads {
                let normal = Normal::new(base.get(s.id), s.sigma).expect("sigma is finite, >= 0");
                p.set(s.id, spec(s.id).range.clamp(normal.sample(&mut rng)));
            }
            p
        })
        .collect();
    let outcomes: Vec<Vec<Option<f64>>> = draws
        .par_iter()
        .map(|p| {
            let bounce = solve_with(p, options).map_err(|source| {
                AnalysisError::Input(format!(
                    "a Monte Carlo draw cannot be solved ({}): {source}",
                    spreads
                        .iter()
                        .map(|s| format!("{} {}", spec(s.id).flag, p.get(s.id)))
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            })?;
            Ok(Quantity::ALL.iter().map(|q| q.of(&bounce)).collect())
        })
        .collect::<Result<_, AnalysisError>>()?;
    let bands = Quantity::ALL
        .iter()
        .enumerate()
        .map(|(k, &quantity)| {
            let values: Vec<f64> = outcomes.iter().filter_map(|o| o[k]).collect();
            let n = values.len();
            let mean = values.iter().sum::<f64>() / n.max(1) as f64;
            let var =
                values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n.max(2) - 1) as f64;
            Band {
                quantity,
                mean,
                sd: var.sqrt(),
                count: n,
            }
        })
        .collect();
    Ok(Bands {
        samples,
        seed,
        bands,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::solve;

    #[test]
    fn a_spread_in_angle_spreads_the_spin_and_no_spread_gives_none() {
        let base = Params::default();
        let none = monte_carlo(&base, &[], 50, 1).unwrap();
        let omega2 = solve(&base).unwrap().outcome.omega2;
        assert!((none.bands[0].mean / omega2 - 1.0).abs() < 1e-12);
        assert!(none.bands[0].sd < 1e-9 * omega2);
        let spread = [Spread {
            id: ParamId::Angle,
            sigma: 1.0,
        }];
        let a = monte_carlo(&base, &spread, 400, 7).unwrap();
        assert_eq!(a, monte_carlo(&base, &spread, 400, 7).unwrap());
        // d omega2 / d theta1 at 60 deg, times 1 deg, is the spread to first order.
        let slope = (solve(&base.with(ParamId::Angle, 60.5).unwrap())
            .unwrap()
            .outcome
            .omega2
            - solve(&base.with(ParamId::Angle, 59.5).unwrap())
                .unwrap()
                .outcome
                .omega2)
            .abs();
        let sd = a.bands[0].sd;
        assert!((sd / slope - 1.0).abs() < 0.15, "{sd} against {slope}");
        assert!((a.bands[0].mean - omega2).abs() < 3.0 * sd / 20.0 + 1.0);
    }
}
