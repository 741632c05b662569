//! `snapback sweep`: one bounce per value of a parameter, as CSV, JSON or JSON Lines, streamed.

use std::io::{BufWriter, Write};

use clap::{Args, ValueEnum};

use super::{Failure, ParamArgs};
use crate::analysis::sweep::{Layout, WriteError};
use crate::analysis::{Span, span, sweep};
use crate::model::Params;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// A header line, then one row per bounce.
    #[default]
    Csv,
    /// An array of objects with the CSV's keys.
    Json,
    /// One object per line (JSON Lines), with the CSV's keys.
    Jsonl,
}

#[derive(Clone, Debug, Args)]
pub struct SweepArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    /// The parameter to vary: a parameter flag without dashes (angle, spin, speed, mu, cart-mass, stiffness, duration, ...).
    #[arg(long, value_name = "PARAM")]
    pub vary: String,
    /// First value (a unit suffix is allowed: 1g, 15kN/m).
    #[arg(long, value_name = "A", allow_hyphen_values = true)]
    pub from: String,
    /// Last value.
    #[arg(long, value_name = "B", allow_hyphen_values = true)]
    pub to: String,
    /// Number of bounces, ends included (at least 2).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub steps: String,
    /// Space the values geometrically (both ends must be above 0).
    #[arg(long)]
    pub log: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Csv)]
    pub format: Format,
}

pub fn run(args: &SweepArgs) -> Result<(), Failure> {
    let base = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let span = Span::parse(&args.vary, &args.from, &args.to, args.log).map_err(Failure::usage)?;
    let steps = span::parse_count("--steps", &args.steps, 2).map_err(Failure::usage)?;
    let layout = match args.format {
        Format::Csv => Layout::Csv,
        Format::Json => Layout::Json,
        Format::Jsonl => Layout::JsonLines,
    };
    let mut out = BufWriter::with_capacity(1 << 20, std::io::stdout().lock());
    let written = sweep::write(&mut out, &base, &span, steps, layout)
        .and_then(|()| out.flush().map_err(WriteError::Io));
    match written {
        Err(WriteError::Analysis(e)) => Err(Failure::usage(e)),
        // A closed pipe (`| head`) is not an error.
        Err(WriteError::Io(e)) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure {
            message: format!("cannot write output: {e}"),
            status: 1,
        }),
        _ => Ok(()),
    }
}
