//! Quantities read off the time series of one bounce: when the ball first grips, the two sides of a
//! transition, the peak of a quantity and when it happens, and how far and how fast the strings travel.

use std::f64::consts::TAU;

use serde::Serialize;

use crate::model::{Bounce, PhaseKind, Sample, State};

use super::brent;

/// Samples of the dense scan that [`peak`] refines.
const SCAN: usize = 2001;

/// Scan points per period of a phase's fastest swing in [`travel`]: a sinusoid's sampled maximum is then
/// within 1 - cos(pi/16) = 2% of its true one, inside the margin [`NEAR`] keeps for refinement.
const PER_PERIOD: f64 = 16.0;

/// Scanned local maxima at least this fraction of the best so far are refined.
const NEAR: f64 = 0.9;

/// The most scan intervals in one phase (a phase of hundreds of swings is a chattering grip, whose
/// excursion its neighbours' scans bound as well).
const MAX_SCAN: usize = 20_000;

/// How far and how fast the cart (on a chain, the first mass, the one the ball touches) travels during
/// the contact, measured from its rest position, where the spring is tied to the wall: the string's
/// sideways travel, which a real string bed bounds by the spacing of its strings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Travel {
    /// The largest |X| over the contact, m.
    pub peak_x: f64,
    /// When it happens, s.
    pub peak_x_at: f64,
    /// The largest |V| over the contact, m/s.
    pub peak_v: f64,
    /// When it happens, s.
    pub peak_v_at: f64,
}

/// The cart's largest |X| and |V| over the contact, from the phases' closed forms: extrema to rounding
/// (see `largest`), not the largest of a set of samples.
pub fn travel(b: &Bounce) -> Travel {
    let (peak_x_at, peak_x) = largest(b, |s| s.x.abs());
    let (peak_v_at, peak_v) = largest(b, |s| s.v.abs());
    Travel {
        peak_x,
        peak_x_at,
        peak_v,
        peak_v_at,
    }
}

/// The largest value of `f` of the state over the contact and when, `(t, value)`. `f` need only be
/// continuous within each phase. Each phase is scanned at [`PER_PERIOD`] points per period of the
/// fastest swing in that phase, as its model answers ([`crate::model::Phase::fastest`]), or of the normal
/// force if faster; its ends are candidates, and every scanned local maximum (an end too) within [`NEAR`]
/// of the best so far is refined by Brent's method between its scanned neighbours to a relative 1e-12 in
/// time, which puts the value at the maximum to rounding.
fn largest(b: &Bounce, f: impl Fn(&State) -> f64) -> (f64, f64) {
    let setup = &b.setup;
    let mut best = (0.0, f64::NEG_INFINITY);
    let keep = |best: &mut (f64, f64), t: f64, v: f64| {
        if v > best.1 {
            *best = (t, v);
        }
    };
    for phase in &b.phases {
        let (t0, t1) = (phase.start, phase.end);
        let value = |t: f64| f(&phase.state_at(setup, t));
        let omega = phase.fastest(setup).max(setup.w);
        let n = ((PER_PERIOD * omega * (t1 - t0) / TAU).ceil() as usize).clamp(2, MAX_SCAN);
        let t = |i: usize| {
            if i == n {
                t1
            } else {
                t0 + (t1 - t0) * i as f64 / n as f64
            }
        };
        let scan: Vec<f64> = (0..=n).map(|i| value(t(i))).collect();
        keep(&mut best, t(0), scan[0]);
        keep(&mut best, t(n), scan[n]);
        let top = scan.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        // A scanned local maximum, the phase's ends included (a peak can lie between an end and its
        // neighbour), refined between its neighbours.
        for i in 0..=n {
            let (lo, hi) = (i.saturating_sub(1), (i + 1).min(n));
            let local = scan[i] >= scan[lo] && scan[i] >= scan[hi];
            if local && scan[i] >= NEAR * top.max(best.1) {
                let (at, neg) = brent::minimize(|s| -value(s), t(lo), t(hi), t(i), 1e-12);
                keep(&mut best, at, -neg);
            }
        }
    }
    best
}

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
