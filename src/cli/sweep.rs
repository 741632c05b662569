//! `snapback sweep`: one bounce per value of a parameter, as CSV, JSON or JSON Lines, streamed.

use std::io::Write;

use clap::{Args, ValueEnum};

use super::simulate::MonteCarloArgs;
use super::{Failure, ShotParamArgs, emit, shot};
use crate::analysis::fit::data::Quantity;
use crate::analysis::sweep::{Layout, WriteError};
use crate::analysis::uncertainty::{Spread, monte_carlo_with};
use crate::analysis::{Span, shots, span, sweep};
use crate::export;
use crate::model::{Params, SolveOptions};

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
    #[command(flatten)]
    pub monte_carlo: MonteCarloArgs,
}

pub fn run(args: &SweepArgs, options: &SolveOptions) -> Result<(), Failure> {
    let span = Span::parse(&args.vary, &args.from, &args.to, args.log).map_err(Failure::usage)?;
    let steps = span::parse_count("--steps", &args.steps, 2).map_err(Failure::usage)?;
    if args.shot {
        return run_shots(args, &span, steps, options);
    }
    shot::refuse_shot_flags(&args.params.given, Some(span.spec), "add --shot")?;
    let (base, spreads) = args
        .params
        .apply_uncertain(Params::default())
        .map_err(Failure::usage)?;
    let layout = match args.format {
        Format::Csv => Layout::Csv,
        Format::Json => Layout::Json,
        Format::Jsonl => Layout::JsonLines,
    };
    let written = if spreads.is_empty() {
        // No buffer of ours: the sweep writes whole chunks of lines, each passed straight through.
        let mut out = std::io::stdout().lock();
        sweep::write(&mut out, &base, &span, steps, layout, options)
            .and_then(|()| out.flush().map_err(WriteError::Io))
    } else {
        let mut out = std::io::stdout().lock();
        let bands = Bands {
            spreads: &spreads,
            mc: &args.monte_carlo,
        };
        write_with_bands(&mut out, &base, &span, steps, layout, &bands, options)
    };
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

/// The input spreads of a sweep with bands, and how to draw them.
struct Bands<'a> {
    spreads: &'a [Spread],
    mc: &'a MonteCarloArgs,
}

/// The sweep with each outcome's Monte Carlo mean and standard deviation beside it: after the usual
/// columns (keys), `<outcome>_mean` and `<outcome>_sd` for omega2, omega2_rpm, vx2, vy2, theta2_deg, ex
/// and speed2 (empty / null where no draw defines it). Every row draws with the same seed, so the bands
/// are smooth along the sweep. Streamed: each row is written and flushed as soon as its draws are
/// solved (a row costs `--mc-samples` bounces), so a long sweep shows its progress and `| head` stops it.
/// The rows themselves are solved first: a sweep whose own bounces fail writes nothing.
fn write_with_bands(
    out: &mut impl Write,
    base: &Params,
    span: &Span,
    steps: usize,
    layout: Layout,
    bands: &Bands,
    options: &SolveOptions,
) -> Result<(), WriteError> {
    let rows = sweep::sweep_with(base, span, steps, options)?;
    let column = span.column();
    let mut digits = zmij::Buffer::new();
    for (i, row) in rows.iter().enumerate() {
        let mut at = *base;
        at.set(span.spec.id, row.value);
        let drawn = monte_carlo_with(
            &at,
            bands.spreads,
            bands.mc.mc_samples as usize,
            bands.mc.mc_seed,
            options,
        )?;
        let mut text = String::new();
        if i == 0 {
            match layout {
                Layout::Csv => {
                    text.push_str(&column);
                    for name in sweep::COLUMNS {
                        text.push(',');
                        text.push_str(name);
                    }
                    for q in Quantity::ALL {
                        text.push_str(&format!(",{0}_mean,{0}_sd", q.name()));
                    }
                    text.push('\n');
                }
                Layout::Json => text.push('['),
                Layout::JsonLines => {}
            }
        }
        match layout {
            Layout::Csv => {
                let line = sweep::format_rows(std::slice::from_ref(row), &column, layout, false);
                text.push_str(line.trim_end_matches('\n'));
                for b in &drawn.bands {
                    for x in [b.mean, b.sd] {
                        text.push(',');
                        if b.count > 0 {
                            sweep::push_number(&mut text, &mut digits, x);
                        }
                    }
                }
                text.push('\n');
            }
            Layout::Json | Layout::JsonLines => {
                let mut object = sweep::object(&column, row);
                for b in &drawn.bands {
                    let (mean, sd) = if b.count > 0 {
                        (b.mean.into(), b.sd.into())
                    } else {
                        (serde_json::Value::Null, serde_json::Value::Null)
                    };
                    object[format!("{}_mean", b.quantity.name())] = mean;
                    object[format!("{}_sd", b.quantity.name())] = sd;
                }
                if layout == Layout::JsonLines {
                    text.push_str(&object.to_string());
                    text.push('\n');
                } else {
                    sweep::push_element(&mut text, &object, i == 0);
                }
            }
        }
        out.write_all(text.as_bytes())?;
        out.flush()?;
    }
    if layout == Layout::Json {
        out.write_all(b"\n]\n")?;
        out.flush()?;
    }
    Ok(())
}

/// `sweep --shot`: one shot per value, in order, as CSV (an empty field for a null), JSON or JSON Lines,
/// with `snapback shot`'s keys.
fn run_shots(
    args: &SweepArgs,
    span: &Span,
    steps: usize,
    options: &SolveOptions,
) -> Result<(), Failure> {
    shot::refuse_bounce_incidence(&args.params.given, Some(span.spec))?;
    let base = args.params.apply(shot::base()).map_err(Failure::usage)?;
    let rows = shots::sweep(&base, span, steps, options).map_err(Failure::usage)?;
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
