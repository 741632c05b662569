//! `reproduce`: every number of the paper listed in `assets/claims.md`, computed by the model and
//! compared with the printed value. Nothing is hard-coded but the printed numbers themselves, each
//! beside the id of the claim that states it (and the tests check that the claim's text contains it).

mod causes;
mod checks;
mod stepping;

use std::fmt;

use serde::Serialize;

use crate::model::{Params, SolveOptions};

use super::AnalysisError;
use super::claims::{self, Claim};

/// How a computed value compares with the printed one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Equal within the printed precision (half a unit of the last printed digit).
    Reproduced,
    /// Within 3 % of the printed value, with a cause the model demonstrates beside it (a parameter the
    /// paper rounded, or how the paper itself evaluated the number); without one the row differs.
    Close,
    /// Further off; the row says why, with evidence the model computes.
    Differs,
    /// The model gives no finite value under these parameters (no critical angle, no grip, ...); the
    /// note says why.
    #[serde(rename = "not-computed")]
    NotComputed,
}

impl Status {
    pub fn name(self) -> &'static str {
        match self {
            Status::Reproduced => "reproduced",
            Status::Close => "close",
            Status::Differs => "differs",
            Status::NotComputed => "not computed",
        }
    }
}

/// The relative gap below which a value is [`Status::Close`].
pub const CLOSE: f64 = 0.03;

/// One printed number and the model's value for it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    /// The claim's id in `assets/claims.md`.
    pub id: &'static str,
    pub quantity: String,
    /// The paper's value.
    pub paper: f64,
    /// The model's value, in the unit the paper prints.
    pub computed: f64,
    pub unit: &'static str,
    pub status: Status,
    /// Evidence: how the value was computed, and for a difference the reason the model demonstrates.
    pub note: String,
    /// computed - paper.
    pub difference: f64,
    /// The number as the paper prints it, e.g. `2.25`.
    #[serde(skip)]
    pub printed: &'static str,
    /// True when a difference comes with a demonstrated reason.
    #[serde(skip)]
    pub explained: bool,
}

/// Half a unit of the last digit of a printed number.
fn precision(printed: &str) -> f64 {
    let decimals = printed.split_once('.').map_or(0, |(_, frac)| frac.len());
    0.5 * 10f64.powi(-(decimals as i32))
}

impl Row {
    /// Compares `computed` with the paper's `printed` number (in `unit`).
    fn new(
        id: &'static str,
        quantity: impl Into<String>,
        printed: &'static str,
        unit: &'static str,
        computed: f64,
    ) -> Row {
        let paper: f64 = printed
            .parse()
            .expect("printed values in the check table are numbers");
        let difference = computed - paper;
        let status = if !computed.is_finite() {
            Status::NotComputed
        } else if difference.abs() <= precision(printed) * (1.0 + 1e-9) {
            Status::Reproduced
        } else if difference.abs() <= CLOSE * paper.abs() {
            Status::Close
        } else {
            Status::Differs
        };
        let note = if status == Status::NotComputed {
            "not computed: the model has no such value under these parameters (no critical angle, no \
             grip or no crossover where the paper's case has one)"
        } else {
            ""
        };
        Row {
            id,
            quantity: quantity.into(),
            paper,
            computed,
            unit,
            status,
            note: note.to_string(),
            difference,
            printed,
            explained: false,
        }
    }

    /// Adds evidence to the note.
    fn note(mut self, text: impl AsRef<str>) -> Row {
        if !self.note.is_empty() {
            self.note.push_str("; ");
        }
        self.note.push_str(text.as_ref());
        self
    }

    /// Adds the demonstrated reason for a difference (`None`: no reason could be demonstrated).
    fn reason(mut self, reason: Option<String>) -> Row {
        if let Some(text) = reason {
            self = self.note(text);
            self.explained = true;
        }
        self
    }

    /// The computed value with two more decimals than the paper prints (`none` when not computed).
    pub fn computed_text(&self) -> String {
        let decimals = self.printed.split_once('.').map_or(0, |(_, f)| f.len()) + 2;
        format!("{:.*}", decimals, Num(self.computed))
    }

    /// Adds the demonstrated cause of a close value; `find` is asked only while the row is close and
    /// has none (see [`Status::Close`]).
    fn cause(self, find: impl FnOnce(&Row) -> Option<String>) -> Row {
        if self.status == Status::Close && !self.explained {
            let found = find(&self);
            self.reason(found)
        } else {
            self
        }
    }

    /// True when `value` prints as the paper's number (within half a unit of its last digit).
    fn prints(&self, value: f64) -> bool {
        (value - self.paper).abs() <= precision(self.printed) * (1.0 + 1e-9)
    }

    /// A close row without a demonstrated cause is a miss: it differs, and is unexplained.
    fn settle(mut self) -> Row {
        if self.status == Status::Close && !self.explained {
            self.status = Status::Differs;
            self = self.note("within 3 %, but no cause of the difference could be demonstrated");
        }
        self
    }

    /// True unless the row differs without a demonstrated reason.
    pub fn accounted_for(&self) -> bool {
        self.status != Status::Differs || self.explained
    }
}

/// A number in a note or a table: as formatted, or `none` where the model gives no finite value.
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_finite() {
            fmt::Display::fmt(&self.0, f)
        } else {
            f.write_str("none")
        }
    }
}

/// Every row, and the claims left without a row.
#[derive(Clone, Debug)]
pub struct Report {
    pub rows: Vec<Row>,
    /// Ids of `assets/claims.md` that no row checks.
    pub missing: Vec<String>,
}

impl Report {
    /// Rows that differ without a demonstrated reason.
    pub fn unexplained(&self) -> Vec<&Row> {
        self.rows.iter().filter(|r| !r.accounted_for()).collect()
    }

    /// True when every claim is checked and every row is reproduced, close or explained.
    pub fn complete(&self) -> bool {
        self.missing.is_empty()
            && self.unexplained().is_empty()
            && self.count(Status::NotComputed) == 0
    }

    pub fn count(&self, status: Status) -> usize {
        self.rows.iter().filter(|r| r.status == status).count()
    }
}

/// Checks every claim. `base` supplies the ball, the speed, the friction and the impact (the paper's
/// Sec. III values by default); each case then sets its own cart, angle and incident spin.
pub fn reproduce(base: &Params) -> Result<Report, AnalysisError> {
    reproduce_with(base, &SolveOptions::default())
}

/// [`reproduce`] with every bounce solved on the caller's terms.
pub fn reproduce_with(base: &Params, options: &SolveOptions) -> Result<Report, AnalysisError> {
    let rows: Vec<Row> = checks::all(base, options)?
        .into_iter()
        .map(Row::settle)
        .collect();
    let missing = claims::all()
        .into_iter()
        .map(|Claim { id, .. }| id)
        .filter(|id| !rows.iter().any(|r| r.id == id))
        .collect();
    Ok(Report { rows, missing })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_close_value_without_a_cause_is_a_miss() {
        let close = || Row::new("id", "q", "100", "N", 101.0);
        assert_eq!(close().status, Status::Close);
        let missed = close().cause(|_| None).settle();
        assert_eq!(missed.status, Status::Differs);
        assert!(!missed.accounted_for());
        let caused = close()
            .cause(|row| row.prints(100.4).then(|| "why".into()))
            .settle();
        assert_eq!(caused.status, Status::Close);
        assert!(caused.accounted_for() && caused.note == "why");
        let found = std::cell::Cell::new(false);
        let exact = Row::new("id", "q", "100", "N", 100.2).cause(|_| {
            found.set(true);
            None
        });
        assert!(!found.get(), "a reproduced value needs no cause");
        assert_eq!(exact.settle().status, Status::Reproduced);
    }
}
