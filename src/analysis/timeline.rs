//! Quantities read off the time series of one bounce: when the ball first grips, the two sides of a
//! transition, and the peak of a quantity and when it happens.

use crate::model::{Bounce, PhaseKind, Sample};

use super::brent;

/// Samples of the dense scan that [`peak`] refines.
const SCAN: usize = 2001;

/// The index of the first grip phase, if the ball grips.
pub fn first_grip(b: &Bounce) -> Option<usize> {
    b.phases.iter().position(|p| p.kind == PhaseKind::Grip)
}

/// The samples just before and just after the start of phase `index`: the same instant, the ending
/// phase's forces on one side and the starting phase's on the other (for the first phase, which nothing
/// precedes, its own on both).
pub fn sides(b: &Bounce, index: usize) -> (Sample, Sample) {
    let t = b.phases[index].start;
    (
        b.sample_in(index.saturating_sub(1), t),
        b.sample_in(index, t),
    )
}

/// The largest value of `f` over the contact and the time it happens; see [`peak_between`].
pub fn peak(b: &Bounce, f: impl Fn(&Sample) -> f64) -> (f64, f64) {
    peak_between(b, 0.0, b.setup.duration, f)
}

/// The largest value of `f` over `[t0, t1]` and the time it happens: a dense scan, then Brent's
/// method between the scan's neighbours of the best sample. `f` must be continuous in time (X, V,
/// v_x, omega are; the friction force is not).
pub fn peak_between(b: &Bounce, t0: f64, t1: f64, f: impl Fn(&Sample) -> f64) -> (f64, f64) {
    let t = |i: usize| t0 + (t1 - t0) * i as f64 / (SCAN - 1) as f64;
    let value = |t: f64| f(&b.sample_at(t));
    let best = (0..SCAN)
        .map(|i| (i, value(t(i))))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |(i, _)| i);
    let (lo, hi) = (t(best.saturating_sub(1)), t((best + 1).min(SCAN - 1)));
    let (at, neg) = brent::minimize(|s| -value(s), lo, hi, t(best), 1e-12);
    (at, -neg)
}
