//! `sweep`: one bounce per value of a parameter, solved on all cores, the rows kept in order.

use std::fmt::Write as _;
use std::io::{self, Write};

use crate::model::Params;
use rayon::prelude::*;

use super::{AnalysisError, Span};

/// The outcome of one bounce of a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The varied parameter's value, in its base unit.
    pub value: f64,
    pub omega2: f64,
    pub vx2: f64,
    pub vy2: f64,
    pub theta2_deg: f64,
    /// `None` when the ball arrives without slip.
    pub ex: Option<f64>,
    /// The phases in order, e.g. `slide-grip-slide`.
    pub phases: String,
    pub slides_throughout: bool,
}

/// The columns after the varied value's.
pub const COLUMNS: [&str; 7] = [
    "omega2",
    "vx2",
    "vy2",
    "theta2_deg",
    "ex",
    "phases",
    "slides_throughout",
];

/// One bounce per value of `span` (`steps` values, ends included), on all cores, in order. For a
/// whole-number parameter (the chain) every value must land on a whole number: a `steps` that does not
/// is refused before anything is solved.
pub fn sweep(base: &Params, span: &Span, steps: usize) -> Result<Vec<Row>, AnalysisError> {
    span.check_steps("--steps", steps)?;
    rows(base, span, steps, 0..steps)
}

/// The rows of the values with indices `range` out of `steps`, on all cores, in order.
fn rows(
    base: &Params,
    span: &Span,
    steps: usize,
    range: std::ops::Range<usize>,
) -> Result<Vec<Row>, AnalysisError> {
    range
        .into_par_iter()
        .map(|i| row(base, span, span.at(i, steps)))
        .collect()
}

/// The row of the bounce with the varied parameter at `value`.
pub fn row(base: &Params, span: &Span, value: f64) -> Result<Row, AnalysisError> {
    let bounce = span.solve(base, value)?;
    let o = &bounce.outcome;
    Ok(Row {
        value,
        omega2: o.omega2,
        vx2: o.vx2,
        vy2: o.vy2,
        theta2_deg: o.theta2_deg,
        ex: o.ex,
        phases: bounce.phase_summary(),
        slides_throughout: bounce.slides_throughout(),
    })
}

/// Why a CSV sweep stopped.
#[derive(Debug, thiserror::Error)]
pub enum CsvError {
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    #[error(transparent)]
    Io(#[from] io::Error),
}

/// Bounces solved and written per block, so memory stays bounded for any number of steps.
const BLOCK: usize = 1 << 16;

/// Rows formatted per chunk on all cores.
const CHUNK: usize = 4096;

/// Solves the sweep and writes it as CSV with a header, block by block; `span.column()` names the
/// varied value. Numbers are written in full (shortest round-trip form); an undefined `ex` is an empty
/// field. A bounce that cannot be solved stops the sweep after the rows before its block; a `steps` that
/// puts a whole-number parameter between whole numbers stops it before the header.
pub fn write_csv(
    out: &mut impl Write,
    base: &Params,
    span: &Span,
    steps: usize,
) -> Result<(), CsvError> {
    span.check_steps("--steps", steps)?;
    for start in (0..steps).step_by(BLOCK) {
        let block = rows(base, span, steps, start..(start + BLOCK).min(steps))?;
        // The header follows the first block, so a sweep of up to BLOCK bounces that fails writes nothing.
        if start == 0 {
            writeln!(out, "{},{}", span.column(), COLUMNS.join(","))?;
        }
        let texts: Vec<String> = block.par_chunks(CHUNK).map(format_rows).collect();
        for text in &texts {
            out.write_all(text.as_bytes())?;
        }
    }
    Ok(())
}

/// CSV lines of `rows`.
fn format_rows(rows: &[Row]) -> String {
    let mut text = String::with_capacity(rows.len() * 120);
    for r in rows {
        let _ = write!(
            text,
            "{},{},{},{},{},",
            r.value, r.omega2, r.vx2, r.vy2, r.theta2_deg
        );
        if let Some(ex) = r.ex {
            let _ = write!(text, "{ex}");
        }
        let _ = writeln!(text, ",{},{}", r.phases, r.slides_throughout);
    }
    text
}

/// The rows as a JSON array of objects with the CSV's keys.
pub fn json(column: &str, rows: &[Row]) -> serde_json::Value {
    let objects = rows
        .iter()
        .map(|r| {
            let mut object = serde_json::Map::with_capacity(8);
            object.insert(column.to_string(), r.value.into());
            object.insert("omega2".into(), r.omega2.into());
            object.insert("vx2".into(), r.vx2.into());
            object.insert("vy2".into(), r.vy2.into());
            object.insert("theta2_deg".into(), r.theta2_deg.into());
            object.insert("ex".into(), r.ex.into());
            object.insert("phases".into(), r.phases.clone().into());
            object.insert("slides_throughout".into(), r.slides_throughout.into());
            serde_json::Value::Object(object)
        })
        .collect();
    serde_json::Value::Array(objects)
}
