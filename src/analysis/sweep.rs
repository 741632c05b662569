//! `sweep`: one bounce per value of a parameter, solved on all cores, the rows kept in order.

use std::fmt::Write as _;
use std::io::{self, Write};

use crate::model::{Bounce, Params, SolveOptions};
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
    /// True when string friction holds the cart still at some time in the contact.
    pub cart_stuck: bool,
    /// A compliant ball's stretch e as it leaves, m (`None` for a rigid ball).
    pub stretch: Option<f64>,
    /// The slip of a compliant ball's contact patch on the cart as it leaves, m/s (`None` for a rigid
    /// ball).
    pub patch_slip: Option<f64>,
}

/// The columns after the varied value's.
pub const COLUMNS: [&str; 10] = [
    "omega2",
    "vx2",
    "vy2",
    "theta2_deg",
    "ex",
    "phases",
    "slides_throughout",
    "cart_stuck",
    "stretch",
    "patch_slip",
];

/// One bounce per value of `span` (`steps` values, ends included), on all cores, in order. For a
/// whole-number parameter (the chain) every value must land on a whole number: a `steps` that does not
/// is refused before anything is solved.
pub fn sweep(base: &Params, span: &Span, steps: usize) -> Result<Vec<Row>, AnalysisError> {
    sweep_with(base, span, steps, &SolveOptions::default())
}

/// [`sweep`] with every bounce solved on the caller's terms.
pub fn sweep_with(
    base: &Params,
    span: &Span,
    steps: usize,
    options: &SolveOptions,
) -> Result<Vec<Row>, AnalysisError> {
    span.check_steps("--steps", steps)?;
    rows(base, span, steps, 0..steps, options)
}

/// The rows of the values with indices `range` out of `steps`, on all cores, in order.
fn rows(
    base: &Params,
    span: &Span,
    steps: usize,
    range: std::ops::Range<usize>,
    options: &SolveOptions,
) -> Result<Vec<Row>, AnalysisError> {
    range
        .into_par_iter()
        .map(|i| row(base, span, span.at(i, steps), options))
        .collect()
}

/// The row of the bounce with the varied parameter at `value`.
pub fn row(
    base: &Params,
    span: &Span,
    value: f64,
    options: &SolveOptions,
) -> Result<Row, AnalysisError> {
    let bounce = span.solve(base, value, options)?;
    let o = &bounce.outcome;
    let patch = bounce.final_patch();
    Ok(Row {
        value,
        omega2: o.omega2,
        vx2: o.vx2,
        vy2: o.vy2,
        theta2_deg: o.theta2_deg,
        ex: o.ex,
        phases: bounce.phase_summary(),
        slides_throughout: bounce.slides_throughout(),
        cart_stuck: bounce.cart_ever_stuck(),
        stretch: patch.map(|(e, _)| e),
        patch_slip: patch.map(|(_, slip)| slip),
    })
}

/// How [`write()`] lays the rows out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// A header line, then one line per row; an undefined `ex` is an empty field.
    Csv,
    /// One JSON array of objects, pretty-printed (two-space indent).
    Json,
    /// One compact JSON object per line.
    JsonLines,
}

/// Why a written sweep stopped.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    #[error(transparent)]
    Io(#[from] io::Error),
}

/// Bounces solved and written per block, so memory stays bounded for any number of steps.
const BLOCK: usize = 1 << 16;

/// Rows solved and formatted per chunk, the chunks on all cores.
const CHUNK: usize = 256;

/// A CSV line's usual length at most (a rigid ball's about 135 bytes, a compliant one's about 190),
/// for the chunk's one allocation.
const LINE: usize = 192;

/// Solves the sweep and writes it as CSV with a header; see [`write()`].
pub fn write_csv(
    out: &mut impl Write,
    base: &Params,
    span: &Span,
    steps: usize,
) -> Result<(), WriteError> {
    write(
        out,
        base,
        span,
        steps,
        Layout::Csv,
        &SolveOptions::default(),
    )
}

/// Solves the sweep and writes it in `layout`, block by block, in constant memory; `span.column()`
/// names the varied value. Numbers are written in full, in their shortest round-trip form. A bounce
/// that cannot be solved stops the sweep after the rows before its block; a `steps` that puts a
/// whole-number parameter between whole numbers stops it before anything is written.
pub fn write(
    out: &mut impl Write,
    base: &Params,
    span: &Span,
    steps: usize,
    layout: Layout,
    options: &SolveOptions,
) -> Result<(), WriteError> {
    span.check_steps("--steps", steps)?;
    let column = span.column();
    for start in (0..steps).step_by(BLOCK) {
        let end = (start + BLOCK).min(steps);
        // Each chunk solved and formatted on one core, CSV lines straight from the bounce.
        let chunk_text = |first: usize| -> Result<String, AnalysisError> {
            let last = (first + CHUNK).min(end);
            if layout != Layout::Csv {
                let rows = rows(base, span, steps, first..last, options)?;
                return Ok(format_rows(&rows, &column, layout, first == 0));
            }
            let mut text = String::with_capacity((last - first) * LINE);
            let mut slot = None;
            for i in first..last {
                let value = span.at(i, steps);
                bounce_csv_line(
                    &mut text,
                    value,
                    span.solve_in(base, value, options, &mut slot)?,
                );
            }
            Ok(text)
        };
        let chunks: Vec<usize> = (start..end).step_by(CHUNK).collect();
        let texts = chunks
            .into_par_iter()
            .map(chunk_text)
            .collect::<Result<Vec<String>, _>>()?;
        // The opening follows the first block, so a sweep of up to BLOCK bounces that fails writes nothing.
        if start == 0 {
            match layout {
                Layout::Csv => writeln!(out, "{column},{}", COLUMNS.join(","))?,
                Layout::Json => out.write_all(b"[")?,
                Layout::JsonLines => {}
            }
        }
        for text in &texts {
            out.write_all(text.as_bytes())?;
        }
    }
    if layout == Layout::Json {
        out.write_all(b"\n]\n")?;
    }
    Ok(())
}

/// The text of `rows` in `layout`; `first` when they begin the sweep (a JSON array's first element
/// takes no comma).
pub(crate) fn format_rows(rows: &[Row], column: &str, layout: Layout, first: bool) -> String {
    let mut text = String::with_capacity(rows.len() * 300);
    for (k, r) in rows.iter().enumerate() {
        match layout {
            Layout::Csv => csv_line(&mut text, r),
            Layout::Json => push_element(&mut text, &object(column, r), first && k == 0),
            Layout::JsonLines => {
                let object = serde_json::to_string(&object(column, r))
                    .expect("JSON values always serialize");
                text.push_str(&object);
                text.push('\n');
            }
        }
    }
    text
}

/// One element of a pretty-printed JSON array, as serde_json writes it: on its own lines after a comma
/// (none before the `first`), indented by two.
pub(crate) fn push_element(text: &mut String, object: &serde_json::Value, first: bool) {
    text.push_str(if first { "\n" } else { ",\n" });
    let pretty = serde_json::to_string_pretty(object).expect("JSON values always serialize");
    for (n, line) in pretty.lines().enumerate() {
        if n > 0 {
            text.push('\n');
        }
        text.push_str("  ");
        text.push_str(line);
    }
}

/// One CSV line of `r`.
fn csv_line(text: &mut String, r: &Row) {
    let numbers = [r.value, r.omega2, r.vx2, r.vy2, r.theta2_deg];
    let flags = [r.slides_throughout, r.cart_stuck];
    let phases = |text: &mut String| text.push_str(&r.phases);
    csv_fields(
        text,
        numbers,
        r.ex,
        phases,
        flags,
        [r.stretch, r.patch_slip],
    );
}

/// The CSV line of the bounce with the varied parameter at `value`, the same as its [`row`]'s, written
/// without the row (no allocation for its phases).
fn bounce_csv_line(text: &mut String, value: f64, bounce: &Bounce) {
    let o = &bounce.outcome;
    let patch = bounce.final_patch();
    let numbers = [value, o.omega2, o.vx2, o.vy2, o.theta2_deg];
    let flags = [bounce.slides_throughout(), bounce.cart_ever_stuck()];
    let phases = |text: &mut String| bounce.push_phase_summary(text);
    let patch = [patch.map(|(e, _)| e), patch.map(|(_, slip)| slip)];
    csv_fields(text, numbers, o.ex, phases, flags, patch);
}

/// One CSV line in [`COLUMNS`]' order after the value, its numbers written by zmij straight into `text`
/// (no formatting machinery: the line is a large part of a fast bounce's cost).
fn csv_fields(
    text: &mut String,
    numbers: [f64; 5],
    ex: Option<f64>,
    phases: impl FnOnce(&mut String),
    flags: [bool; 2],
    patch: [Option<f64>; 2],
) {
    let mut digits = zmij::Buffer::new();
    for x in numbers {
        push_number(text, &mut digits, x);
        text.push(',');
    }
    if let Some(ex) = ex {
        push_number(text, &mut digits, ex);
    }
    text.push(',');
    phases(text);
    for flag in flags {
        text.push_str(if flag { ",true" } else { ",false" });
    }
    for x in patch {
        text.push(',');
        if let Some(x) = x {
            push_number(text, &mut digits, x);
        }
    }
    text.push('\n');
}

/// A number in its shortest round-trip form: plain (`10`, `0.3`) from 1e-5 to 1e16, else with an
/// exponent (`1e308`, `2.5e-7`), as Rust's `{}` and `{:e}` write them: zmij's form (Schubfach, about
/// three times ryu's speed) without its `.0`, its exponent's `+` and its leading zeros (where two
/// shortest forms lie equally close, zmij may end on the other digit).
pub(crate) fn push_number(text: &mut String, digits: &mut zmij::Buffer, x: f64) {
    if !x.is_finite() {
        let _ = write!(text, "{x}");
        return;
    }
    let shown = digits.format_finite(x);
    // zmij writes an exponent exactly outside these bounds, as Rust does.
    let exponent = if x == 0.0 || (1e-5..1e16).contains(&x.abs()) {
        None
    } else {
        shown.bytes().rposition(|b| b == b'e')
    };
    let Some(e) = exponent else {
        text.push_str(shown.strip_suffix(".0").unwrap_or(shown));
        return;
    };
    let (mantissa, exponent) = (&shown[..e], &shown[e + 1..]);
    text.push_str(mantissa.strip_suffix(".0").unwrap_or(mantissa));
    text.push('e');
    let (minus, digits) = match exponent.as_bytes().first() {
        Some(b'-') => ("-", &exponent[1..]),
        Some(b'+') => ("", &exponent[1..]),
        _ => ("", exponent),
    };
    text.push_str(minus);
    let digits = digits.trim_start_matches('0');
    text.push_str(if digits.is_empty() { "0" } else { digits });
}

/// The row as a JSON object with the CSV's keys (`column` names the varied value).
pub fn object(column: &str, r: &Row) -> serde_json::Value {
    let mut object = serde_json::Map::with_capacity(8);
    object.insert(column.to_string(), r.value.into());
    object.insert("omega2".into(), r.omega2.into());
    object.insert("vx2".into(), r.vx2.into());
    object.insert("vy2".into(), r.vy2.into());
    object.insert("theta2_deg".into(), r.theta2_deg.into());
    object.insert("ex".into(), r.ex.into());
    object.insert("phases".into(), r.phases.clone().into());
    object.insert("slides_throughout".into(), r.slides_throughout.into());
    object.insert("cart_stuck".into(), r.cart_stuck.into());
    object.insert("stretch".into(), r.stretch.into());
    object.insert("patch_slip".into(), r.patch_slip.into());
    serde_json::Value::Object(object)
}

#[cfg(test)]
mod tests {
    use super::push_number;

    /// Rust's shortest round-trip forms, plain between 1e-5 and 1e16.
    fn reference(x: f64) -> String {
        let size = x.abs();
        if size != 0.0 && !(1e-5..1e16).contains(&size) {
            format!("{x:e}")
        } else {
            format!("{x}")
        }
    }

    /// The same notation and length as Rust's, and the same number read back.
    #[test]
    fn numbers_are_written_as_rust_writes_them() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut digits = zmij::Buffer::new();
        let edges = [
            0.0,
            -0.0,
            1e-5,
            9.999_999_999_999_999e-6,
            1e16,
            9_999_999_999_999_998.0,
            10.0,
            0.3,
        ];
        let random = (0..200_000).map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            f64::from_bits(state)
        });
        for x in edges.into_iter().chain(random).filter(|x| x.is_finite()) {
            let mut text = String::new();
            push_number(&mut text, &mut digits, x);
            let rust = reference(x);
            assert_eq!(text.len(), rust.len(), "{x:?}: {text} against {rust}");
            assert_eq!(
                text.contains('e'),
                rust.contains('e'),
                "{x:?}: {text} against {rust}"
            );
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                x.to_bits(),
                "{text}"
            );
        }
    }
}
