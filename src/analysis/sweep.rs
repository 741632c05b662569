//! `sweep`: one bounce per value of a parameter, solved on all cores, the rows kept in order.

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
    let values = span.steps(steps);
    range
        .into_par_iter()
        .map(|i| row(base, span, values.at(i), options))
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
        let chunk_text = |first: usize| -> Result<Vec<u8>, AnalysisError> {
            let last = (first + CHUNK).min(end);
            if layout != Layout::Csv {
                let rows = rows(base, span, steps, first..last, options)?;
                return Ok(format_rows(&rows, &column, layout, first == 0).into_bytes());
            }
            let mut text = Vec::with_capacity((last - first) * LINE);
            let mut varied = span.varied(base, options);
            let values = span.steps(steps);
            let mut scratch = [0; LINE_BYTES];
            for i in first..last {
                let value = values.at(i);
                bounce_csv_line(
                    &mut text,
                    &mut scratch,
                    value,
                    span.solve_varied(&mut varied, value)?,
                );
            }
            Ok(text)
        };
        let chunks: Vec<usize> = (start..end).step_by(CHUNK).collect();
        let texts = chunks
            .into_par_iter()
            .map(chunk_text)
            .collect::<Result<Vec<Vec<u8>>, _>>()?;
        // The opening follows the first block, so a sweep of up to BLOCK bounces that fails writes nothing.
        if start == 0 {
            match layout {
                Layout::Csv => writeln!(out, "{column},{}", COLUMNS.join(","))?,
                Layout::Json => out.write_all(b"[")?,
                Layout::JsonLines => {}
            }
        }
        for text in &texts {
            out.write_all(text)?;
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
            Layout::Csv => {
                let mut line = Vec::with_capacity(LINE);
                csv_line(&mut line, r);
                text.push_str(std::str::from_utf8(&line).expect("a CSV line is ASCII"));
            }
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
fn csv_line(text: &mut Vec<u8>, r: &Row) {
    let mut scratch = [0; LINE_BYTES];
    let numbers = [r.value, r.omega2, r.vx2, r.vy2, r.theta2_deg];
    let flags = [r.slides_throughout, r.cart_stuck];
    let phases = |line: &mut Line| line.name(r.phases.as_bytes());
    let patch = [r.stretch, r.patch_slip];
    csv_fields(text, &mut scratch, numbers, r.ex, phases, flags, patch);
}

/// The CSV line of the bounce with the varied parameter at `value`, the same as its [`row`]'s, written
/// without the row (no allocation for its phases).
fn bounce_csv_line(
    text: &mut Vec<u8>,
    scratch: &mut [u8; LINE_BYTES],
    value: f64,
    bounce: &Bounce,
) {
    let o = &bounce.outcome;
    let patch = bounce.final_patch();
    let numbers = [value, o.omega2, o.vx2, o.vy2, o.theta2_deg];
    let flags = [bounce.slides_throughout(), bounce.cart_ever_stuck()];
    let phases = |line: &mut Line| {
        for (i, kind) in bounce.ball_phase_kinds().enumerate() {
            // A name leaves room for its line's end, so the dash after it fits.
            if i > 0 {
                line.byte(b'-');
            }
            line.name(kind.name().as_bytes());
        }
    };
    let patch = [patch.map(|(e, _)| e), patch.map(|(_, slip)| slip)];
    csv_fields(text, scratch, numbers, o.ex, phases, flags, patch);
}

/// One CSV line in [`COLUMNS`]' order after the value, gathered in a [`Line`] on the stack and its
/// numbers written by zmij (no formatting machinery: the line is a large part of a fast bounce's cost).
fn csv_fields(
    text: &mut Vec<u8>,
    scratch: &mut [u8; LINE_BYTES],
    numbers: [f64; 5],
    ex: Option<f64>,
    phases: impl FnOnce(&mut Line),
    flags: [bool; 2],
    patch: [Option<f64>; 2],
) {
    let mut digits = zmij::Buffer::new();
    let mut line = Line {
        text,
        bytes: scratch,
        len: 0,
    };
    for x in numbers {
        line.number(&mut digits, x);
        line.byte(b',');
    }
    if let Some(ex) = ex {
        line.number(&mut digits, ex);
    }
    line.byte(b',');
    phases(&mut line);
    for flag in flags {
        if flag {
            line.name(b",true");
        } else {
            line.name(b",false");
        }
    }
    for x in patch {
        line.byte(b',');
        if let Some(x) = x {
            line.number(&mut digits, x);
        }
    }
    line.byte(b'\n');
    line.flush();
}

/// The bytes of a CSV line, gathered on the stack and appended to the text in one copy (each byte or
/// number written straight, without the text's capacity checks). The numbers and flags of a line take
/// at most 8 x 25 + 12 bytes; only the phases' names, which can run long, ask for room first.
struct Line<'a> {
    text: &'a mut Vec<u8>,
    /// The chunk's scratch, reused from line to line.
    bytes: &'a mut [u8; LINE_BYTES],
    len: usize,
}

/// The stack's share of a line: every line's numbers and flags (at most 212 bytes) and the phases'
/// names of any usual bounce.
const LINE_BYTES: usize = 320;

/// The most bytes one number takes (zmij writes at most 24; NaN and infinities fewer).
const NUMBER_BYTES: usize = 24;

/// Room for what may follow a name on its line: the other flag, two numbers, their commas and the end.
const TAIL_BYTES: usize = 2 * NUMBER_BYTES + 16;

impl Line<'_> {
    #[inline]
    fn byte(&mut self, b: u8) {
        self.bytes[self.len] = b;
        self.len += 1;
    }

    /// A number as [`push_number`] writes it.
    #[inline(always)]
    fn number(&mut self, digits: &mut zmij::Buffer, x: f64) {
        let out = &mut self.bytes[self.len..self.len + NUMBER_BYTES];
        self.len += shortest(digits, x, out);
    }

    /// A name (a phase's, a flag's, or a row's whole phases), the gathered bytes appended to the text
    /// first when it would not leave room for the line's end, and a name longer than the scratch
    /// appended itself.
    #[inline]
    fn name(&mut self, name: &[u8]) {
        if self.len + name.len() + TAIL_BYTES > LINE_BYTES {
            self.flush();
            if name.len() + TAIL_BYTES > LINE_BYTES {
                self.text.extend_from_slice(name);
                return;
            }
        }
        self.bytes[self.len..self.len + name.len()].copy_from_slice(name);
        self.len += name.len();
    }

    /// Appends the gathered bytes to the text.
    fn flush(&mut self) {
        self.text.extend_from_slice(&self.bytes[..self.len]);
        self.len = 0;
    }
}

/// A number in its shortest round-trip form: plain (`10`, `0.3`) from 1e-5 to 1e16, else with an
/// exponent (`1e308`, `2.5e-7`), as Rust's `{}` and `{:e}` write them: zmij's form (Schubfach, about
/// three times ryu's speed) without its `.0`, its exponent's `+` and its leading zeros (where two
/// shortest forms lie equally close, zmij may end on the other digit).
pub(crate) fn push_number(text: &mut String, digits: &mut zmij::Buffer, x: f64) {
    let mut out = [0; NUMBER_BYTES];
    let len = shortest(digits, x, &mut out);
    text.push_str(std::str::from_utf8(&out[..len]).expect("a number is ASCII"));
}

/// [`push_number`]'s text of `x` written at the start of `out`; its length.
#[inline(always)]
fn shortest(digits: &mut zmij::Buffer, x: f64, out: &mut [u8]) -> usize {
    let mut put = |at: usize, part: &[u8]| {
        out[at..at + part.len()].copy_from_slice(part);
        at + part.len()
    };
    if !x.is_finite() {
        let text: &[u8] = if x.is_nan() {
            b"NaN"
        } else if x > 0.0 {
            b"inf"
        } else {
            b"-inf"
        };
        return put(0, text);
    }
    let shown = digits.format_finite(x).as_bytes();
    let unpointed =
        |part: &'_ [u8]| -> usize { part.len() - 2 * usize::from(part.ends_with(b".0")) };
    // zmij writes an exponent exactly outside these bounds, as Rust does.
    if x == 0.0 || (1e-5..1e16).contains(&x.abs()) {
        return put(0, &shown[..unpointed(shown)]);
    }
    let Some(e) = shown.iter().rposition(|&b| b == b'e') else {
        return put(0, &shown[..unpointed(shown)]);
    };
    let (mantissa, exponent) = (&shown[..e], &shown[e + 1..]);
    let mut at = put(0, &mantissa[..unpointed(mantissa)]);
    at = put(at, b"e");
    let digits = match exponent.first() {
        Some(b'-') => {
            at = put(at, b"-");
            &exponent[1..]
        }
        Some(b'+') => &exponent[1..],
        _ => exponent,
    };
    let zeros = digits.iter().take_while(|&&b| b == b'0').count();
    let digits = if zeros == digits.len() {
        &b"0"[..]
    } else {
        &digits[zeros..]
    };
    put(at, digits)
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
    use super::{Layout, Row, csv_line, format_rows, push_number, sweep, write};
    use crate::analysis::Span;
    use crate::model::{Params, SolveOptions};

    /// The CSV written straight from each bounce (the sweep's fast path) is the CSV of its rows, over
    /// bounces of one to five phases.
    #[test]
    fn a_bounces_line_is_its_rows_line() {
        let span = Span::parse("cart-mass", "0.1g", "1kg", true).unwrap();
        let base = Params::default();
        let mut out = Vec::new();
        let options = SolveOptions::default();
        write(&mut out, &base, &span, 40, Layout::Csv, &options).unwrap();
        let rows = sweep(&base, &span, 40).unwrap();
        let phases: std::collections::BTreeSet<&str> =
            rows.iter().map(|r| r.phases.as_str()).collect();
        assert!(phases.len() >= 3, "{phases:?}");
        let text = String::from_utf8(out).unwrap();
        let body = text.split_once('\n').unwrap().1;
        assert_eq!(body, format_rows(&rows, &span.column(), Layout::Csv, true));
    }

    /// A row's line, however long its phases, is its fields joined as text would join them.
    #[test]
    fn a_rows_line_is_its_fields() {
        for repeats in [1, 20, 300] {
            let phases = vec!["slide-grip"; repeats].join("-");
            let row = Row {
                value: 10.5,
                omega2: -1.25e-7,
                vx2: 3.0,
                vy2: 1e20,
                theta2_deg: 45.0,
                ex: None,
                phases: phases.clone(),
                slides_throughout: false,
                cart_stuck: true,
                stretch: Some(2.5e-300),
                patch_slip: Some(-0.1),
            };
            let mut line = Vec::new();
            csv_line(&mut line, &row);
            let expected = format!("10.5,-1.25e-7,3,1e20,45,,{phases},false,true,2.5e-300,-0.1\n");
            assert_eq!(String::from_utf8(line).unwrap(), expected);
        }
    }

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
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut text = String::new();
            push_number(&mut text, &mut digits, x);
            assert_eq!(text, format!("{x}"));
        }
    }
}
