//! `snapback simulate`: one bounce, as a table, JSON or the CSV time series.

use clap::{Args, ValueEnum};

use super::{Failure, ParamArgs, emit};
use crate::analysis::uncertainty::{DEFAULT_SAMPLES, monte_carlo_with};
use crate::export;
use crate::model::reportable::reportable;
use crate::model::{Params, SolveOptions, solve_with};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// A readable summary: outcome, phases in ms, energy budget.
    #[default]
    Table,
    /// One JSON object with the parameters, outcome, phases and energy.
    Json,
    /// The sampled time series with a header line.
    Csv,
}

#[derive(Clone, Debug, Default, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Evenly spaced samples of the time series for --format csv (both sides of every transition are added).
    #[arg(long, default_value_t = 501, value_parser = clap::value_parser!(u32).range(2..=10_000_000))]
    pub samples: u32,
    #[command(flatten)]
    pub monte_carlo: MonteCarloArgs,
}

/// How the spread of outcomes is found when a parameter value carries an uncertainty (`--angle 50±1`).
#[derive(Clone, Debug, Args)]
pub struct MonteCarloArgs {
    /// Monte Carlo draws when a value carries an uncertainty (`--angle 50±1`, `--spin -3820rpm+-200`).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_SAMPLES as u32, value_parser = clap::value_parser!(u32).range(2..=10_000_000))]
    pub mc_samples: u32,
    /// Seed of the Monte Carlo draws (the same seed and count give the same result).
    #[arg(long, value_name = "SEED", default_value_t = 1)]
    pub mc_seed: u64,
}

impl Default for MonteCarloArgs {
    fn default() -> Self {
        MonteCarloArgs {
            mc_samples: DEFAULT_SAMPLES as u32,
            mc_seed: 1,
        }
    }
}

pub fn run(args: &SimulateArgs, options: &SolveOptions) -> Result<(), Failure> {
    let (params, spreads) = args
        .params
        .apply_uncertain(Params::default())
        .map_err(Failure::usage)?;
    let bounce = solve_with(&params, options).map_err(Failure::usage)?;
    reportable(&bounce).map_err(Failure::usage)?;
    if spreads.is_empty() {
        let text = match args.format {
            Format::Table => export::table::summary(&bounce),
            Format::Json => export::json::bounce(&bounce),
            Format::Csv => export::csv::series(&bounce.series(args.samples as usize)),
        };
        return emit(&text);
    }
    if args.format == Format::Csv {
        return Err(Failure::usage(
            "an uncertainty (±) gives a spread of outcomes, which the time series (--format csv) has no \
             place for: use --format table or json",
        ));
    }
    let mc = &args.monte_carlo;
    let bands = monte_carlo_with(
        &params,
        &spreads,
        mc.mc_samples as usize,
        mc.mc_seed,
        options,
    )
    .map_err(Failure::usage)?;
    let text = match args.format {
        Format::Json => {
            let value = export::uncertainty::json(&spreads, &bands);
            export::uncertainty::append_key(&export::json::bounce(&bounce), "uncertainty", &value)
        }
        _ => export::table::summary(&bounce) + &export::uncertainty::table(&spreads, &bands),
    };
    emit(&text)
}
