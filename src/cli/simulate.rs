//! `snapback simulate`: one bounce, as a table, JSON or the CSV time series.

use clap::{Args, ValueEnum};

use super::{Failure, ParamArgs, emit};
use crate::export;
use crate::model::{Params, limits, solve};

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
}

pub fn run(args: &SimulateArgs) -> Result<(), Failure> {
    let params = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let bounce = solve(&params).map_err(Failure::usage)?;
    limits::reportable(&bounce).map_err(Failure::usage)?;
    let text = match args.format {
        Format::Table => export::table::summary(&bounce),
        Format::Json => export::json::bounce(&bounce),
        Format::Csv => export::csv::series(&bounce.series(args.samples as usize)),
    };
    emit(&text)
}
