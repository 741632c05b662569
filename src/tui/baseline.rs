//! A pinned bounce to compare against: `b` keeps the current bounce, its time series and its sweep, so
//! the charts can draw them as a second, dimmer curve and the outcome panel can give the differences.

use crate::model::params::PARAMS;
use crate::model::{Bounce, Params, Sample};

use super::sweep::Sweep;

/// A bounce kept for comparison.
#[derive(Clone, Debug)]
pub struct Baseline {
    pub params: Params,
    pub bounce: Bounce,
    /// The same samples the contact charts draw for the current bounce.
    pub series: Vec<Sample>,
    /// omega2 against theta1 for the baseline's parameters.
    pub sweep: Sweep,
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
        let (now, then) = (&current.outcome, &self.bounce.outcome);
        Deltas {
            omega2: now.omega2 - then.omega2,
            ex: now.ex.zip(then.ex).map(|(a, b)| a - b),
        }
    }

    /// The symbols of the parameters in which `current` differs from the baseline: `θ1, M`.
    pub fn differences(&self, current: &Params) -> Vec<&'static str> {
        PARAMS
            .iter()
            .filter(|s| self.params.get(s.id) != current.get(s.id))
            .map(|s| s.symbol)
            .collect()
    }
}

/// A signed difference with `decimals` places that never reads `-0.0`: `+12.3`, `-0.004`, `±0.0`.
pub fn signed(delta: f64, decimals: usize) -> String {
    let text = format!("{:+.*}", decimals, delta);
    if text[1..].chars().all(|c| c == '0' || c == '.') {
        format!("±{}", &text[1..])
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
        assert_eq!(signed(-0.00001, 1), "±0.0");
        assert_eq!(signed(0.0, 3), "±0.000");
    }
}
