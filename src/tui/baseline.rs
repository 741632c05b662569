//! A pinned bounce to compare against: `b` keeps the current bounce and its time series (its sweep is
//! asked of the worker when the sweep view shows it), so the charts can draw them as a second, dimmer
//! curve and the outcome panel can give the differences.

use std::sync::Arc;

use crate::model::params::PARAMS;
use crate::model::{Bounce, Params};

use super::solved::Solved;

/// A bounce kept for comparison.
#[derive(Clone, Debug)]
pub struct Baseline {
    pub solved: Arc<Solved>,
}

/// The current bounce minus the baseline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Deltas {
    /// Rebound spin, rad/s.
    pub omega2: f64,
    /// Tangential restitution; `None` when either bounce has none (no slip at the start).
    pub ex: Option<f64>,
}

impl Baseline {
    /// The differences `current - baseline` of the outcomes the panel shows.
    pub fn deltas(&self, current: &Bounce) -> Deltas {
        let (now, then) = (&current.outcome, &self.solved.bounce.outcome);
        Deltas {
            omega2: now.omega2 - then.omega2,
            ex: now.ex.zip(then.ex).map(|(a, b)| a - b),
        }
    }

    /// The symbols of the parameters in which `current` differs from the baseline: `θ1, M`.
    pub fn differences(&self, current: &Params) -> Vec<&'static str> {
        PARAMS
            .iter()
            .filter(|s| self.solved.params.get(s.id) != current.get(s.id))
            .map(|s| s.symbol)
            .collect()
    }
}

/// A signed difference with `decimals` places: `+12.3`, `-0.004`, and no sign where it rounds to
/// nothing, `0.0` (not `-0.0`, nor `±0.0`, which reads as an uncertainty).
pub fn signed(delta: f64, decimals: usize) -> String {
    let text = format!("{:+.*}", decimals, delta);
    if text[1..].chars().all(|c| c == '0' || c == '.') {
        text[1..].to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_shows_the_sign_and_never_minus_zero() {
        assert_eq!(signed(12.34, 1), "+12.3");
        assert_eq!(signed(-0.0041, 3), "-0.004");
        assert_eq!(signed(-0.00001, 1), "0.0");
        assert_eq!(signed(0.0, 3), "0.000");
    }
}
