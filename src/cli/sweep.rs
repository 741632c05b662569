//! `snapback sweep`: one bounce per value of a parameter, as CSV, JSON or JSON Lines, streamed.

use std::io::{BufWriter, Write};

use clap::{Args, ValueEnum};

use super::{Failure, ShotParamArgs, emit, shot};
use crate::analysis::sweep::{Layout, WriteError};
use crate::analysis::{Span, shots, span, sweep};
use crate::export;
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
    pub params: ShotParamArgs,
    /// One shot on court per value instead of one bounce (`snapback shot`'s outcomes; any shot flag may
    /// be varied).
    #[arg(long)]
    pub shot: bool,
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
    let span = Span::parse(&args.vary, &args.from, &args.to, args.log).map_err(Failure::usage)?;
    let steps = span::parse_count("--steps", &args.steps, 2).map_err(Failure::usage)?;
    if args.shot {
        return run_shots(args, &span, steps);
    }
    shot::refuse_shot_flags(&args.params.given, Some(span.spec), "add --shot")?;
    let base = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
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

/// `sweep --shot`: one shot per value, in order, as CSV (an empty field for a null), JSON or JSON Lines,
/// with `snapback shot`'s keys.
fn run_shots(args: &SweepArgs, span: &Span, steps: usize) -> Result<(), Failure> {
    shot::refuse_bounce_incidence(&args.params.given, Some(span.spec))?;
    let base = args.params.apply(shot::base()).map_err(Failure::usage)?;
    let rows = shots::sweep(&base, span, steps).map_err(Failure::usage)?;
    let column = span.column();
    let docs = rows.iter().map(|(value, s)| {
        let mut doc = serde_json::json!({ column.as_str(): value });
        let serde_json::Value::Object(fields) = export::shot::value(s) else {
            unreachable!("a shot is an object")
        };
        doc.as_object_mut().expect("an object").extend(fields);
        doc
    });
    let text = match args.format {
        Format::Csv => export::shot::csv(&column, &rows),
        Format::Json => {
            let mut text =
                serde_json::to_string_pretty(&docs.collect::<Vec<_>>()).expect("shots serialize");
            text.push('\n');
            text
        }
        Format::Jsonl => docs.map(|d| format!("{d}\n")).collect(),
    };
    emit(&text)
}
