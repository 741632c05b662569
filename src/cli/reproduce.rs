//! `snapback reproduce`: every number of the paper's claims list, computed and compared.

use std::fmt::Write;

use clap::{Args, ValueEnum};

use super::{Failure, ParamArgs, emit};
use crate::analysis::reproduce::{self, Report, Status};
use crate::model::{Params, SolveOptions};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One line per printed number, its note below it, and a summary.
    #[default]
    Table,
    /// An array of objects: `id`, `quantity`, `paper`, `computed`, `unit`, `status`, `note`, `difference`;
    /// `computed` and `difference` are null when the status is `not-computed` (the note says why).
    Json,
}

#[derive(Clone, Debug, Default, Args)]
pub struct ReproduceArgs {
    /// The ball, speed, friction and impact (default: the paper's Sec. III); each claim's case then sets its own cart, angle and spin.
    #[command(flatten)]
    pub params: ParamArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

fn table(report: &Report) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:<19} {:<66} {:>8} {:>11} {:<5} {:>9}  status",
        "id", "quantity", "paper", "computed", "unit", "diff"
    );
    for r in &report.rows {
        let relative = if r.status == Status::NotComputed {
            "-".to_string()
        } else if r.paper != 0.0 {
            format!("{:+.1}%", 100.0 * r.difference / r.paper)
        } else {
            format!("{:+.2}", r.difference)
        };
        let _ = writeln!(
            out,
            "{:<19} {:<66} {:>8} {:>11} {:<5} {:>9}  {}",
            r.id,
            r.quantity,
            r.printed,
            r.computed_text(),
            r.unit,
            relative,
            r.status.name()
        );
        if !r.note.is_empty() {
            let _ = writeln!(out, "{:<19} - {}", "", r.note);
        }
    }
    let _ = writeln!(
        out,
        "\n{} numbers: {} reproduced, {} close (within 3 %), {} differ{}",
        report.rows.len(),
        report.count(Status::Reproduced),
        report.count(Status::Close),
        report.count(Status::Differs),
        match report.count(Status::NotComputed) {
            0 => String::new(),
            n => format!(", {n} not computed"),
        }
    );
    for id in &report.missing {
        let _ = writeln!(out, "missing: claim {id} has no check");
    }
    for r in report.unexplained() {
        let _ = writeln!(out, "unexplained: {} ({})", r.id, r.quantity);
    }
    if report.complete() {
        let _ = writeln!(
            out,
            "every claim is reproduced, close, or differs, each close value and each difference with \
             a cause shown in its note"
        );
    }
    out
}

pub fn run(args: &ReproduceArgs, options: &SolveOptions) -> Result<(), Failure> {
    let base = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let report = reproduce::reproduce_with(&base, options).map_err(Failure::usage)?;
    let text = match args.format {
        Format::Table => table(&report),
        Format::Json => {
            let mut text =
                serde_json::to_string_pretty(&report.rows).expect("rows always serialize");
            text.push('\n');
            text
        }
    };
    emit(&text)?;
    if report.complete() {
        Ok(())
    } else {
        Err(Failure {
            message: format!(
                "{} claim(s) without a check, {} difference(s) without a demonstrated reason{}",
                report.missing.len(),
                report.unexplained().len(),
                match report.count(Status::NotComputed) {
                    0 => String::new(),
                    n => format!(", {n} number(s) not computed under these parameters"),
                }
            ),
            status: 1,
        })
    }
}
