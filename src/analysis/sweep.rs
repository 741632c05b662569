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

/// One bounce per value of `span` (`steps` values, ends included), on all cores, in order.
pub fn sweep(base: &Params, span: &Span, steps: usize) -> Result<Vec<Row>, AnalysisError> {
    (0..steps)
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

/// Rows formatted per block on all cores, then written in order.
const BLOCK: usize = 4096;

/// Writes the rows as CSV with a header; `column` names the varied value (see [`Span::column`]).
/// Numbers are written in full (shortest round-trip form); an undefined `ex` is an empty field.
pub fn write_csv(out: &mut impl Write, column: &str, rows: &[Row]) -> io::Result<()> {
    writeln!(out, "{column},{}", COLUMNS.join(","))?;
    let blocks: Vec<String> = rows
        .par_chunks(BLOCK)
        .map(|block| {
            let mut text = String::with_capacity(block.len() * 120);
            for r in block {
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
        })
        .collect();
    for block in &blocks {
        out.write_all(block.as_bytes())?;
    }
    Ok(())
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
