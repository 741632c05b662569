//! The rigid ball's event search on a chain without string friction, by Taylor bounds: the slide's slip
//! and the grip's margins carry their second and third derivatives from the phase's sums (S' and
//! S4 = Σ Φ_1j Ω_j⁴ q_j with its rate, [`Motion::probe`]), and each phase bounds their fourth, so that
//! [`first_rise_within`] proves by the branches' cubic Taylor polynomials the intervals its parabolas
//! cannot (a slip that leaves zero with zero rate after a grip broke, the stretch before a grip's
//! crossing) instead of halving them. On the wall the crossing itself is refined by Newton's step from
//! the secant point, so every crossing is the one the parabolas alone find, bit for bit. On a free frame
//! (whose bounce has two more phases, the frame's recoil) it is refined from the root predicted from f to
//! f''' at both ends of its interval by the cubic model's step ([`first_rise_predicted`], as the single
//! cart's): two or three evaluations a crossing instead of four to six, the same root by another path
//! (to its last bits: the polished reference of `tests/physics/chain_reference.rs` shows every framed
//! line of the golden corpus that moved no less exact). On the wall that reference shows it landing a
//! unit or two in the last place from the polished crossing where Newton's last step lands on it (an
//! `ex` of 1.9e-4 moved by 3.2e-12 of itself), so the wall keeps Newton's step.

use super::super::contact::{Cause, ROUNDING};
use super::super::events::{Branch, first_rise_predicted, first_rise_within};
use super::super::setup::Setup;
use super::super::trig::sin_cos;
use super::motion::{MARGINS, MARGINS_FOURTH, Motion, Probe, SLIP, SLIP_FOURTH};

/// The fourth-derivative bounds' room for the rounding of the bounds themselves.
const ROOM: f64 = 1.0 + 1e-9;

/// One branch with f, f', f'' and f''': the Taylor bound reads f'' and f''', and the crossing is
/// refined by Newton's step -f/f', exactly as the plain (f, f') branch's; with `CUBIC` (on a free
/// frame, where the crossing is refined from the root predicted from f to f''' at both ends of its
/// interval, [`first_rise_predicted`]) by the cubic Taylor model's step, as the single cart's: two
/// evaluations a crossing where Newton's step from the secant point takes three to six.
#[derive(Clone, Copy, Debug)]
pub struct Taylor<const CUBIC: bool = false>([f64; 4]);

impl<const CUBIC: bool> Branch for Taylor<CUBIC> {
    #[inline]
    fn value(&self) -> f64 {
        self.0[0]
    }
    #[inline]
    fn rate(&self) -> f64 {
        self.0[1]
    }
    #[inline]
    fn step(&self) -> f64 {
        let [f, rate, second, third] = self.0;
        if CUBIC {
            (f, rate, second, third).step()
        } else {
            -(f / rate)
        }
    }
    #[inline]
    fn higher(&self) -> Option<(f64, f64)> {
        Some((self.0[2], self.0[3]))
    }
}

/// The slide's event: the slip (in direction `dir`) reaching zero, measured from its start value when
/// it starts on its zero (`cause` a slip zero or a broken grip). `speeds` is the scale of the speeds
/// in the slip (for its rounding floor, with the terms of its modal sums).
pub fn slide(
    setup: &Setup,
    motion: &Motion,
    (t0, dir, cause): (f64, f64, Cause),
    speeds: f64,
) -> Option<(f64, Cause)> {
    let drives = motion.drives();
    let branch = |p: &Probe, offset: f64| {
        let c = &p.contact;
        let rate = -c.friction / setup.m_eff - c.accel;
        let (second, third) = motion.slip_higher(setup, p, drives);
        let slip = setup.slip(&c.state) - offset;
        Taylor([-dir * slip, -dir * rate, -dir * second, -dir * third])
    };
    let start = motion.probe::<SLIP, SLIP_FOURTH>(setup, t0);
    let offset = if matches!(cause, Cause::SlipZero | Cause::GripBreak(_)) {
        setup.slip(&start.contact.state)
    } else {
        0.0
    };
    // The start is evaluated once, for the offset and as the search's first point.
    let first = branch(&start, offset);
    let f = |t: f64| {
        if t == t0 {
            [first]
        } else {
            [branch(&motion.probe::<SLIP, SLIP_FOURTH>(setup, t), offset)]
        }
    };
    let [curvature, terms, fourth] = motion.slip_bounds(setup);
    let noise = ROUNDING * (speeds + terms);
    let step = setup.event_step(motion.chain().slide.fastest);
    let bounds = [[curvature], [fourth * ROOM]];
    searched(
        "slide",
        motion,
        f,
        (t0, setup.duration, step),
        bounds,
        [noise],
    )
    .map(|(t, _)| (t, Cause::SlipZero))
}

/// The grip's event: F_s reaching +mu N or -mu N (its margins, [`Setup::grip_margins`]).
pub fn grip(setup: &Setup, motion: &Motion, t0: f64) -> Option<(f64, Cause)> {
    let drives = motion.drives();
    let f = |t: f64| {
        let p = motion.probe::<MARGINS, MARGINS_FOURTH>(setup, t);
        let force = motion.grip_force(setup, &p, drives);
        let margins = setup.grip_margins_with_derivatives(sin_cos(setup.w * t), force);
        margins.map(|(f, rate, second, third)| Taylor([f, rate, second, third]))
    };
    let [curvature, terms, fourth] = motion.margin_bounds(setup);
    let noise = ROUNDING * terms;
    // The margins' own rate, sqrt(|F_s''| bound / its terms), not the fastest mode's.
    let fastest = motion.chain().grip().fastest;
    let step = setup.event_step((curvature / terms).sqrt().min(fastest));
    let bounds = [[curvature; 2], [fourth * ROOM; 2]];
    searched(
        "grip",
        motion,
        f,
        (t0, setup.duration, step),
        bounds,
        [noise; 2],
    )
    .map(|(t, branch)| {
        let sign = if branch == 0 { 1.0 } else { -1.0 };
        (t, Cause::GripBreak(sign))
    })
}

/// [`first_rise_within`] for the phase `regime` names; under test, where [`super::bounds`] asks it,
/// the bounds are first checked against the branches they bound.
#[inline(always)]
fn searched<const K: usize>(
    regime: &'static str,
    motion: &Motion,
    f: impl Fn(f64) -> [Taylor; K],
    (t0, end, step): (f64, f64, f64),
    bounds: [[f64; K]; 2],
    noise: [f64; K],
) -> Option<(f64, usize)> {
    #[cfg(test)]
    let sampled = crate::model::bound_samples::sample(
        || {
            let place = if motion.start.frame > 0 {
                "on a frame"
            } else {
                "on the wall"
            };
            format!("{regime} {place}")
        },
        &|t| f(t).map(|b| b.0),
        (t0, end, step),
        bounds,
    );
    #[cfg(not(test))]
    let _ = regime;
    let found = if motion.start.frame > 0 {
        let cubic = |t: f64| f(t).map(|b| Taylor::<true>(b.0));
        first_rise_predicted(cubic, t0, end, step, bounds, noise)
    } else {
        first_rise_within(f, t0, end, step, bounds, noise)
    };
    #[cfg(test)]
    crate::model::bound_samples::check(sampled, found.map_or(end, |(t, _)| t));
    found
}
