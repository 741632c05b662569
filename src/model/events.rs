//! Locating the transitions between phases: the first time an exact event function rises above zero.
//!
//! Each phase supplies its event function `f` with its derivative (and, where its closed form gives
//! them cheaply, the next two: see [`Branch`]), and a bound `curvature` on |f''| taken from the
//! amplitudes of its closed-form solution. Between two points `a < b` the function then lies below
//! both parabolas `f(a) + f'(a) s + curvature s²/2` and `f(b) - f'(b) (b - t) + curvature (b - t)²/2`;
//! when the lower of the two stays below the noise floor, the interval provably holds no rise. When a
//! branch has risen by the interval's end, its crossing is predicted from the secant point by Newton's
//! method (or by the cubic Taylor model where the branch has its higher derivatives), and the rest,
//! `[a, crossing]`, is proved empty in the same way, split at the refinement's last point below zero;
//! an interval that cannot be proved is halved, earliest half first, so the crossing found is the
//! first one, however close two crossings lie (a short phase is never skipped).
//!
//! Every search is metered ([`metered`]): a solve has a budget of evaluations, and a search whose step
//! no longer advances time stops. Either way the search gives up, and the solve is refused with the
//! [`Stall`] rather than left to run for ever.

use std::cell::Cell;

/// The smallest interval the search splits, relative to the time: below it, a rise is taken as found.
const FINEST: f64 = 1e-14;

/// 1/6, for the third derivative's Taylor coefficient by a product rather than a division.
const SIXTH: f64 = 1.0 / 6.0;

/// Where Newton's step n is this small against the curvature's scale, |f'' n / (2 f')|, a
/// refinement's step is the cubic model's root by its series ([`cubic_step`]): its next term, about
/// 5e-15 of the step, is then far below the resolution of the crossing.
const NEAR: f64 = 1e-5;

/// [`NEAR`] for the step on the interpolant that predicts a crossing ([`predicted`]), whose own error
/// is a few parts in 1e6 of its interval: the series' next term is then at most 4e-5 of the step.
const NEAR_PREDICTED: f64 = 2e-2;

/// A Newton step this small relative to the time (a few units in the last place) means the iteration
/// has converged.
const CONVERGED: f64 = 4.0 * f64::EPSILON;

/// Why an event search gave up.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum Stall {
    #[error(
        "the solve used up its budget of {evaluations} evaluations of the event functions near t = \
         {t:.3e} s: the contact switches or oscillates faster than the solver can follow"
    )]
    Budget { evaluations: u64, t: f64 },
    #[error(
        "the event search cannot advance past t = {t:.3e} s: the bounce's fastest timescale is below \
         what f64 resolves at that time"
    )]
    Resolution { t: f64 },
}

/// The budget of the solve running on this thread, and why its search stalled, if it did. A solve
/// runs on one thread from start to end, and the searches' signature is shared by every contact model,
/// so the meter is kept here rather than passed through them. The two things every evaluation reads,
/// the evaluations left and whether the search stalled, have cells of their own ([`LEFT`],
/// [`STALLED`]).
#[derive(Clone, Copy)]
struct Meter {
    armed: bool,
    budget: u64,
    stall: Option<Stall>,
}

const IDLE: Meter = Meter {
    armed: false,
    budget: u64::MAX,
    stall: None,
};

thread_local! {
    static METER: Cell<Meter> = const { Cell::new(IDLE) };
    /// The evaluations left to the solve.
    static LEFT: Cell<u64> = const { Cell::new(u64::MAX) };
    /// True once the solve's search stalled (its reason is the meter's).
    static STALLED: Cell<bool> = const { Cell::new(false) };
    /// The evaluations the last outermost metered solve on this thread spent.
    static SPENT: Cell<u64> = const { Cell::new(0) };
}

/// Runs `solve` with a budget of `budget` event evaluations; `Err` when one of its searches gave up
/// (its result, which a search that gave up has cut short, is then dropped). Nested calls share the
/// outermost budget.
#[inline]
pub fn metered<T>(budget: u64, solve: impl FnOnce() -> T) -> Result<T, Stall> {
    let outer = METER.get();
    if !outer.armed {
        METER.set(Meter {
            armed: true,
            budget,
            stall: None,
        });
        LEFT.set(budget);
        STALLED.set(false);
    }
    let result = solve();
    let meter = METER.get();
    if !outer.armed {
        SPENT.set(meter.budget - LEFT.get());
        METER.set(IDLE);
        LEFT.set(u64::MAX);
        STALLED.set(false);
    }
    meter.stall.map_or(Ok(result), Err)
}

/// The evaluations the last (outermost) [`metered`] solve on this thread spent.
pub fn spent() -> u64 {
    SPENT.get()
}

/// True while a metered solve runs on this thread.
pub fn metering() -> bool {
    METER.get().armed
}

/// Records one evaluation at `t`.
#[inline]
fn spend(t: f64) {
    let left = LEFT.get();
    if left == 0 {
        stall(Stall::Budget {
            evaluations: METER.get().budget,
            t,
        });
    } else {
        LEFT.set(left - 1);
    }
}

/// Records that the search cannot advance past `t`.
fn stall_at(t: f64) {
    stall(Stall::Resolution { t });
}

/// Records why the search stalled (the first reason stands).
#[cold]
fn stall(why: Stall) {
    let mut meter = METER.get();
    meter.stall.get_or_insert(why);
    METER.set(meter);
    STALLED.set(true);
}

/// True once this thread's solve has stalled: every search then ends at once.
#[inline]
fn stalled() -> bool {
    STALLED.get()
}

/// The event: `K` branches, each a value and its time derivatives at `t`. The phase ends when any
/// branch rises (a grip, for example, breaks when F_s reaches +mu N or -mu N). A closure is one; a
/// hot event can be a type of its own whose `at` is inlined at each of the search's calls (the single
/// cart's slide by its sums).
pub trait Event<B: Branch, const K: usize> {
    /// The branches at `t`.
    fn at(&self, t: f64) -> [B; K];

    /// The branches at `t`, a refinement's step from the last evaluation (usually a few millionths of
    /// an oscillation away), where an event may reuse that evaluation's work.
    #[inline(always)]
    fn near(&self, t: f64) -> [B; K] {
        self.at(t)
    }
}

impl<B: Branch, const K: usize, F: Fn(f64) -> [B; K]> Event<B, K> for F {
    #[inline(always)]
    fn at(&self, t: f64) -> [B; K] {
        self(t)
    }
}

/// An event given as two closures: its branches at any time, and at a refinement's step from the last
/// evaluation ([`Event::near`]).
pub struct WithNear<A, N>(pub A, pub N);

impl<B: Branch, const K: usize, A: Fn(f64) -> [B; K], N: Fn(f64) -> [B; K]> Event<B, K>
    for WithNear<A, N>
{
    #[inline(always)]
    fn at(&self, t: f64) -> [B; K] {
        (self.0)(t)
    }

    #[inline(always)]
    fn near(&self, t: f64) -> [B; K] {
        (self.1)(t)
    }
}

/// One branch of an event at one time: its value f, its rate f', and the step toward its zero that
/// the crossing's refinement takes from there.
pub trait Branch: Copy {
    fn value(&self) -> f64;
    fn rate(&self) -> f64;
    /// The step toward the zero; infinite or NaN where it is undefined (the refinement then halves).
    fn step(&self) -> f64;
    /// f'' and f''', where the branch carries them (for [`first_rise_within`]'s sharper bound).
    #[inline]
    fn higher(&self) -> Option<(f64, f64)> {
        None
    }
}

/// (f, f'): Newton's step -f/f', which converges quadratically.
impl Branch for (f64, f64) {
    #[inline]
    fn value(&self) -> f64 {
        self.0
    }
    #[inline]
    fn rate(&self) -> f64 {
        self.1
    }
    #[inline]
    fn step(&self) -> f64 {
        -(self.0 / self.1)
    }
}

/// (f, f', f'', f'''), for a phase whose closed form gives the higher derivatives at little cost: the
/// step to the zero of the cubic Taylor model f + f' d + f'' d²/2 + f''' d³/6 (`cubic_step`: near
/// the root by its series in Newton's step, one division; farther by Halley's step and Newton's on the
/// model), which converges with order four: from the secant point one evaluation fewer than Newton's
/// to a few units in the last place.
impl Branch for (f64, f64, f64, f64) {
    #[inline]
    fn value(&self) -> f64 {
        self.0
    }
    #[inline]
    fn rate(&self) -> f64 {
        self.1
    }
    #[inline]
    fn higher(&self) -> Option<(f64, f64)> {
        Some((self.2, self.3))
    }
    #[inline]
    fn step(&self) -> f64 {
        cubic_step(*self, NEAR)
    }
}

/// The root of the cubic Taylor model of (f, f', f'', f''') nearest zero: by its series in Newton's
/// step n = -f/f', n - c2 n² + (2 c2² - c3) n³ with c2 = f''/(2 f') and c3 = f'''/(6 f') (one
/// division), where |c2 n| is at most `near` (the series' next term is about 5 |c2 n|³ |n|); else by
/// Halley's step and Newton's on the model (two divisions in a row).
#[inline(always)]
fn cubic_step((f, rate, second, third): (f64, f64, f64, f64), near: f64) -> f64 {
    let inverse = 1.0 / rate;
    let newton = -f * inverse;
    let c2 = 0.5 * second * inverse;
    if (c2 * newton).abs() <= near {
        // f'''/6 by a product, ready before the division (a second division would wait on it).
        let c3 = third * SIXTH * inverse;
        return newton * (1.0 + newton * (newton * (2.0 * c2 * c2 - c3) - c2));
    }
    let d = -2.0 * f * rate / (2.0 * rate * rate - f * second);
    let model = f + d * (rate + d * (0.5 * second + d * third * SIXTH));
    let model_rate = rate + d * (second + 0.5 * d * third);
    d - model / model_rate
}

/// The first time in `(t0, t1]` at which a branch of `f` rises above `noise`, and which branch, or
/// `None`.
///
/// Every branch is at most its `noise` at `t0`, and `curvature` bounds its second derivative.
/// `step` is the coarse sampling interval (a fraction of the fastest period in `f`, so that most
/// intervals are proved empty at once). `noise` is the rounding error of the terms of `f`: a function
/// that hovers at zero, as near the end of contact where the normal force vanishes, is not a rise.
///
/// A branch that starts on its own zero (the slip of a slide that begins where a grip broke or the
/// friction reversed, the margins of a grip at first contact) leaves it downward, the phase having been
/// chosen so, but the bound cannot see the direction it leaves in: over the first eighth of a step such
/// a branch is checked at the end only, while the others are proved as everywhere else.
pub fn first_rise<B: Branch, const K: usize>(
    f: impl Event<B, K>,
    t0: f64,
    t1: f64,
    step: f64,
    curvature: [f64; K],
    noise: [f64; K],
) -> Option<(f64, usize)> {
    let bounds = Bounds {
        curvature,
        fourth: [f64::INFINITY; K],
    };
    search::<B, K, false, false>(f, t0, t1, step, bounds, noise, Start::Downward)
}

/// As [`first_rise`], for branches that carry f'' and f''' ([`Branch::higher`]), with `fourth`
/// bounding each branch's fourth derivative. Where the parabolas of `curvature` cannot prove an
/// interval empty, the branch's Taylor polynomials from its ends, to third order with `fourth` in
/// the remainder, are tried before the interval is split (`Search::proved_below_by_taylor`). It
/// only proves more intervals empty, with fewer evaluations: every crossing it finds is
/// [`first_rise`]'s.
pub fn first_rise_within<B: Branch, const K: usize>(
    f: impl Event<B, K>,
    t0: f64,
    t1: f64,
    step: f64,
    [curvature, fourth]: [[f64; K]; 2],
    noise: [f64; K],
) -> Option<(f64, usize)> {
    let bounds = Bounds { curvature, fourth };
    search::<B, K, true, false>(f, t0, t1, step, bounds, noise, Start::Downward)
}

/// As [`first_rise_within`], each crossing refined from the crossing predicted from the branch's
/// value and first three derivatives at both ends of its interval (the two-point Hermite interpolant
/// of degree 7, `predicted`), rather than from the secant point:
/// over a coarse step one evaluation fewer a crossing. For branches whose f'' and f''' are as exact as
/// f and f' (the closed forms' sums, `sums.rs`); the crossing is the same root by another path, so it
/// may differ from [`first_rise_within`]'s in its last bits.
pub fn first_rise_predicted<B: Branch, const K: usize>(
    f: impl Event<B, K>,
    t0: f64,
    t1: f64,
    step: f64,
    [curvature, fourth]: [[f64; K]; 2],
    noise: [f64; K],
) -> Option<(f64, usize)> {
    let bounds = Bounds { curvature, fourth };
    search::<B, K, true, true>(f, t0, t1, step, bounds, noise, Start::Downward)
}

/// As [`first_rise`], for a phase whose branches may leave their zero upward (a compliant ball's grip,
/// entered whenever its patch stops slipping, can break as soon as it begins, its force leaving mu N
/// tangentially). The stretch checked at its end only is then no longer than sqrt(2 noise /
/// curvature), over which a branch leaving zero tangentially cannot rise above its noise (and a
/// millionth of a step at least).
pub fn first_rise_from_tangent<B: Branch, const K: usize>(
    f: impl Event<B, K>,
    t0: f64,
    t1: f64,
    step: f64,
    curvature: [f64; K],
    noise: [f64; K],
) -> Option<(f64, usize)> {
    let bounds = Bounds {
        curvature,
        fourth: [f64::INFINITY; K],
    };
    search::<B, K, false, false>(f, t0, t1, step, bounds, noise, Start::Tangent)
}

/// Bounds on the branches' second and fourth derivatives (infinite where none is known).
struct Bounds<const K: usize> {
    curvature: [f64; K],
    fourth: [f64; K],
}

/// How a branch that starts on its zero may leave it.
#[derive(Clone, Copy, PartialEq)]
enum Start {
    Downward,
    Tangent,
}

/// The search; with `TAYLOR`, proofs that the parabolas fail are tried by the Taylor polynomials
/// (only [`first_rise_within`]'s, [`first_rise_predicted`]'s and
/// [`first_rise_predicted_from_tangent`]'s, so that the other searches carry no
/// test for it); with `PREDICT`, crossings are refined from their [`predicted`] place (only
/// [`first_rise_predicted`]'s and [`first_rise_predicted_from_tangent`]'s).
fn search<B: Branch, const K: usize, const TAYLOR: bool, const PREDICT: bool>(
    f: impl Event<B, K>,
    t0: f64,
    t1: f64,
    step: f64,
    Bounds { curvature, fourth }: Bounds<K>,
    noise: [f64; K],
    start: Start,
) -> Option<(f64, usize)> {
    if t1 <= t0 || stalled() {
        return None;
    }
    let mut a = Point::at(&f, t0);
    let at_zero: [bool; K] = std::array::from_fn(|i| a.branches[i].value() >= -noise[i]);
    let mut search = Search::<_, B, K, TAYLOR, PREDICT> {
        f: &f,
        branch: std::marker::PhantomData,
        start: t0,
        half_curvature: curvature.map(|c| 0.5 * c),
        fourth_term: fourth.map(|c| c / 24.0),
        noise,
        ends_only: at_zero,
    };
    // The first coarse interval, when a branch starts on its zero: proved empty as any other if the
    // bound allows, else split at the window.
    let mut pending = None;
    if at_zero.contains(&true) {
        let b = Point::at(&f, (t0 + step).min(t1));
        if search.proved_empty(&a, &b) {
            a = b;
        } else {
            let window = match start {
                Start::Downward => step / 8.0,
                Start::Tangent => {
                    let tangent = (0..K)
                        .filter(|&i| at_zero[i] && curvature[i] > 0.0)
                        .map(|i| (2.0 * noise[i] / curvature[i]).sqrt())
                        .fold(f64::INFINITY, f64::min);
                    (step / 8.0).min(tangent.max(step * 1e-6))
                }
            };
            let w = Point::at(&f, (t0 + window).min(t1));
            if let Some(t) = search.first_in(&a, &w, true) {
                return Some(t);
            }
            a = w;
            pending = Some(b);
        }
        search.ends_only = [false; K];
    }
    while a.t < t1 && !stalled() {
        let b = match pending.take() {
            Some(b) if b.t > a.t => b,
            _ => {
                let next = (a.t + step).min(t1);
                if next <= a.t {
                    stall_at(a.t);
                    return None;
                }
                Point::at(&f, next)
            }
        };
        if let Some(t) = search.first_in(&a, &b, true) {
            return Some(t);
        }
        a = b;
    }
    None
}

#[derive(Clone, Copy)]
struct Point<B, const K: usize> {
    t: f64,
    branches: [B; K],
}

impl<B: Branch, const K: usize> Point<B, K> {
    fn at(f: &impl Event<B, K>, t: f64) -> Self {
        spend(t);
        Point {
            t,
            branches: f.at(t),
        }
    }
}

struct Search<'a, F, B, const K: usize, const TAYLOR: bool, const PREDICT: bool> {
    f: &'a F,
    /// The branches' type, which the event names only as its trait's parameter.
    branch: std::marker::PhantomData<B>,
    /// Where the phase starts: no crossing lies before it.
    start: f64,
    half_curvature: [f64; K],
    /// The bounds on the branches' fourth derivatives over 4! (infinite where none is known).
    fourth_term: [f64; K],
    noise: [f64; K],
    /// Branches checked at the ends of an interval only (those leaving their zero at the start).
    ends_only: [bool; K],
}

impl<B: Branch, F: Event<B, K>, const K: usize, const TAYLOR: bool, const PREDICT: bool>
    Search<'_, F, B, K, TAYLOR, PREDICT>
{
    /// The first branch above its noise at `p`.
    fn risen(&self, p: &Point<B, K>) -> Option<usize> {
        (0..K).find(|&i| p.branches[i].value() > self.noise[i])
    }

    /// True when no branch rises on `[a, b]`: each is at most its noise at `b` and proved so between.
    fn proved_empty(&self, a: &Point<B, K>, b: &Point<B, K>) -> bool {
        (0..K).all(|i| b.branches[i].value() <= self.noise[i] && self.proved_below(a, b, i))
    }

    /// The first rise in `[a, b]`, given that every branch is at most `noise` at `a` and nothing rose
    /// before `a`.
    fn first_in(&self, a: &Point<B, K>, b: &Point<B, K>, predict: bool) -> Option<(f64, usize)> {
        if stalled() {
            return None;
        }
        let risen = self.risen(b);
        let below = |i: usize| {
            b.branches[i].value() <= self.noise[i]
                && (self.ends_only[i] || self.proved_below(a, b, i))
        };
        if risen.is_none() && (0..K).all(below) {
            return None;
        }
        let width = b.t - a.t;
        if width <= FINEST * b.t.abs().max(f64::MIN_POSITIVE) {
            return risen.map(|branch| (self.crossing(branch, a, b).0.t, branch));
        }
        if let Some(i) = risen {
            // One branch rising throughout (f' >= f'(a) - curvature (b - a) > 0, so its crossing is
            // unique) while the others are proved below: that crossing is the first rise.
            let rising = a.branches[i].rate() - 2.0 * self.half_curvature[i] * width > 0.0;
            if rising && (0..K).all(|j| j == i || below(j)) {
                return Some((self.crossing(i, a, b).0.t, i));
            }
            if predict {
                // The risen branch's crossing, by Newton: the first rise unless another lies before it,
                // which the search of [a, crossing] (without predicting) proves absent or finds, split
                // at the refinement's last point below zero (evaluated already, and nearer the crossing
                // than a halving would be).
                let (at, below) = self.crossing(i, a, b);
                let before = match below {
                    Some(below) if below.t > a.t && below.t < at.t => self
                        .first_in(a, &below, false)
                        .or_else(|| self.first_in(&below, &at, false)),
                    _ => self.first_in(a, &at, false),
                };
                return before.or(Some((at.t, i)));
            }
        }
        let mid = Point::at(self.f, a.t + 0.5 * width);
        self.first_in(a, &mid, predict)
            .or_else(|| self.first_in(&mid, b, predict))
    }

    /// Where branch `i`, above its noise at `b`, crosses zero, with every branch there. Within the
    /// noise it may already be a little above zero at `a`; the crossing then lies before `a`, and is
    /// bracketed by stepping back. With it, the refinement's last point where branch `i` was at most
    /// zero, if any.
    #[inline(always)]
    fn crossing(
        &self,
        i: usize,
        a: &Point<B, K>,
        b: &Point<B, K>,
    ) -> (Point<B, K>, Option<Point<B, K>>) {
        // Only branch `i` and the times of the bracket's ends are read, so only they are copied.
        let (mut low, mut high) = ((a.t, a.branches[i]), (b.t, b.branches[i]));
        let mut step = b.t - a.t;
        while low.1.value() > 0.0 && low.0 > self.start && step > 0.0 {
            high = low;
            let t = (low.0 - step).max(self.start);
            low = (t, self.f.at(t)[i]);
            step *= 2.0;
        }
        refine::<B, K, PREDICT>(self.f, i, low, high)
    }

    /// True when the two parabolas through `a` and `b` prove branch `i` at most `noise` on `[a, b]`,
    /// or, where they cannot and the branch has a bound on its fourth derivative, its Taylor
    /// polynomials from the ends ([`Search::proved_below_by_taylor`]).
    #[inline]
    fn proved_below(&self, a: &Point<B, K>, b: &Point<B, K>, i: usize) -> bool {
        let (fa, ra) = (a.branches[i].value(), a.branches[i].rate());
        let (fb, rb) = (b.branches[i].value(), b.branches[i].rate());
        let width = b.t - a.t;
        crossing_peak((fa, ra), (fb, rb), self.half_curvature[i], width)
            .is_none_or(|peak| peak <= self.noise[i])
            || (TAYLOR && self.fourth_term[i].is_finite() && self.proved_below_by_taylor(a, b, i))
    }

    /// True when the Taylor polynomials of branch `i` to third order from `a` over the first half
    /// of `[a, b]` and from `b` over the second, each with the bound on the fourth derivative in its
    /// remainder, prove it at most `noise` there ([`Branch::higher`] gives f'' and f''' at the ends;
    /// a branch without them proves nothing). Each half is bounded by [`taylor_ceiling`] at once,
    /// or else in two quarters. The polynomials follow the branch through changes in its curvature that
    /// the parabolas, with one bound on |f''| for the whole interval, cannot: a slip that leaves
    /// zero with zero rate and bends away (the slide after a grip broke), or margins that turn
    /// toward zero only at the far end of a long interval.
    #[inline(never)]
    fn proved_below_by_taylor(&self, a: &Point<B, K>, b: &Point<B, K>, i: usize) -> bool {
        let (Some((second_a, third_a)), Some((second_b, third_b))) =
            (a.branches[i].higher(), b.branches[i].higher())
        else {
            return false;
        };
        let fourth = self.fourth_term[i];
        let from_a = [
            a.branches[i].value(),
            a.branches[i].rate(),
            0.5 * second_a,
            third_a / 6.0,
            fourth,
        ];
        // In the time before b, u = b - t, the odd derivatives change sign.
        let from_b = [
            b.branches[i].value(),
            -b.branches[i].rate(),
            0.5 * second_b,
            -third_b / 6.0,
            fourth,
        ];
        let half = 0.5 * (b.t - a.t);
        let noise = self.noise[i];
        let below = |near: f64, far: f64| {
            taylor_ceiling(&from_a, near, far) <= noise
                && taylor_ceiling(&from_b, near, far) <= noise
        };
        // Each half at once, or else in two quarters.
        below(0.0, half) || (below(0.0, 0.5 * half) && below(0.5 * half, half))
    }
}

/// An upper bound on c0 + c1 s + c2 s² + c3 s³ + c4 s⁴ for s in [`near`, `far`] (0 <= near <= far),
/// by Horner's scheme on bounds: with s >= 0, s X is at most `far` times X's bound where that is
/// positive and `near` times it where it is not.
#[inline]
fn taylor_ceiling(coefficients: &[f64; 5], near: f64, far: f64) -> f64 {
    coefficients[..4]
        .iter()
        .rev()
        .fold(coefficients[4], |upper, &c| {
            c + upper * if upper >= 0.0 { far } else { near }
        })
}

/// The lower of the two parabolas `f(a) + f'(a) s + k s²` and `f(b) - f'(b) (width - s) + k (width -
/// s)²` (each end given as (value, rate)), which bound from above on `[a, a + width]` any function
/// with those ends whose second derivative is at most `2 k` there: its value where they cross inside
/// the interval, or `None` when they do not (it then peaks at an end).
///
/// Both bounds are convex, so the lower of them peaks at an end or where they cross; their
/// difference is linear in `s`, so they cross at most once.
#[inline]
fn crossing_peak((fa, ra): (f64, f64), (fb, rb): (f64, f64), k: f64, width: f64) -> Option<f64> {
    let offset = fa - fb + rb * width - k * width * width;
    let slope = ra - rb + 2.0 * k * width;
    if slope == 0.0 {
        return None;
    }
    let s = -offset / slope;
    if s <= 0.0 || s >= width {
        return None;
    }
    Some(fa + ra * s + k * s * s)
}

/// Where a branch that carries f'' and f''' at both ends of `[a, b]` ([`Branch::higher`]) crosses zero,
/// predicted without evaluating it: the two-point Hermite interpolant of degree 7 that matches f and its
/// first three derivatives at both ends, stepped once from `guess` by its own cubic Taylor model
/// ([`cubic_step`] within [`NEAR_PREDICTED`]). Its error grows as (width x fastest frequency)^8 / 8!,
/// so over a coarse step (a fraction of the fastest period) it is within a few parts in 1e6 of the
/// width, close enough that one step on the branch itself takes it to the crossing to rounding; `None`
/// without the derivatives, or when the prediction is not inside `(a, b)`.
///
/// In u = (t - a)/(b - a), with F_k and G_k the Taylor coefficients f^(k) (b - a)^k / k! at the two
/// ends, the interpolant is F_0 + F_1 u + F_2 u² + F_3 u³ + c_4 u⁴ + ... + c_7 u⁷, where c_4..c_7 solve
/// the conditions at u = 1, Σ_j C(j, d) c_j = G_d for d = 0..3 (an integer matrix with an integer
/// inverse).
#[inline]
fn predicted<B: Branch>((low, high): (B, B), a: f64, b: f64, guess: f64) -> Option<f64> {
    let ((second_a, third_a), (second_b, third_b)) = (low.higher()?, high.higher()?);
    let h = b - a;
    let coefficients = |value: f64, rate: f64, second: f64, third: f64| {
        [
            value,
            rate * h,
            0.5 * second * h * h,
            third * SIXTH * (h * h * h),
        ]
    };
    let f = coefficients(low.value(), low.rate(), second_a, third_a);
    let g = coefficients(high.value(), high.rate(), second_b, third_b);
    // What the first four terms leave of the far end's coefficients.
    let r = [
        g[0] - (f[0] + f[1] + f[2] + f[3]),
        g[1] - (f[1] + 2.0 * f[2] + 3.0 * f[3]),
        g[2] - (f[2] + 3.0 * f[3]),
        g[3] - f[3],
    ];
    let c = [
        f[0],
        f[1],
        f[2],
        f[3],
        35.0 * r[0] - 15.0 * r[1] + 5.0 * r[2] - r[3],
        -84.0 * r[0] + 39.0 * r[1] - 14.0 * r[2] + 3.0 * r[3],
        70.0 * r[0] - 34.0 * r[1] + 13.0 * r[2] - 3.0 * r[3],
        -20.0 * r[0] + 10.0 * r[1] - 4.0 * r[2] + r[3],
    ];
    // The interpolant and its Taylor coefficients to third order at the guess, by Horner's scheme.
    let u = (guess - a) / h;
    // The derivatives' first steps start from zeros, and are taken out: 0 u + x is x + 0.0 for the
    // u in (0, 1) here (the same bits).
    let mut p1 = c[7] + 0.0;
    let mut p = c[7] * u + c[6];
    let mut p2 = p1;
    p1 = p1 * u + p;
    p = p * u + c[5];
    let mut p3 = p2;
    p2 = p2 * u + p1;
    p1 = p1 * u + p;
    p = p * u + c[4];
    for &coefficient in c[..4].iter().rev() {
        p3 = p3 * u + p2;
        p2 = p2 * u + p1;
        p1 = p1 * u + p;
        p = p * u + coefficient;
    }
    let t = a + h * (u + cubic_step((p, p1, 2.0 * p2, 6.0 * p3), NEAR_PREDICTED));
    (t > a && t < b).then_some(t)
}

/// The crossing of zero of branch `i` of `f` in `[a, b]`, given `f_i(a) <= 0 < f_i(b)` (up to noise),
/// each end given as its time and branch `i` there,
/// by the branch's step (Newton's, or the cubic Taylor model's where it knows its higher derivatives)
/// from the secant point (or, with `PREDICT` where the branch knows its higher derivatives at both
/// ends, from the crossing [`predicted`] from them), kept inside a shrinking bracket, to a few units in
/// the last place of `t`;
/// with every branch at that time (the last evaluation, which the solver keeps), and the last point
/// before it where branch `i` was at most zero, if any.
#[inline(always)]
fn refine<B: Branch, const K: usize, const PREDICT: bool>(
    f: &impl Event<B, K>,
    i: usize,
    (mut a, low): (f64, B),
    (mut b, high): (f64, B),
) -> (Point<B, K>, Option<Point<B, K>>) {
    let resolution = |t: f64| 4.0 * f64::EPSILON * t.abs().max(f64::MIN_POSITIVE);
    let (fa, fb) = (low.value(), high.value());
    let ends = (low, high);
    let secant = a + (b - a) * (-fa / (fb - fa));
    let mut t = if secant > a && secant < b {
        secant
    } else {
        0.5 * (a + b)
    };
    if let Some(predicted) = PREDICT.then(|| predicted(ends, a, b, t)).flatten() {
        t = predicted;
    }
    let mut last = Point {
        t,
        branches: f.at(t),
    };
    let mut below = None;
    for _ in 0..100 {
        let branch = last.branches[i];
        let risen = branch.value() > 0.0;
        if risen {
            b = t;
        } else {
            a = t;
        }
        if b - a <= resolution(b) {
            break;
        }
        // Within half the convergence test's step of the zero by Newton's measure: converged, without
        // the step's divisions.
        if branch.value().abs() <= 0.5 * CONVERGED * t.abs() * branch.rate().abs() {
            break;
        }
        let next = t + branch.step();
        // Both steps converge at least quadratically: once one is this small, t is within it of the
        // crossing, far below the resolution asked of transition times (1e-12 s). (A step that is not
        // finite fails both this test and the bracket's.)
        if (next - t).abs() <= CONVERGED * t.abs() {
            break;
        }
        t = if next > a && next < b {
            next
        } else {
            0.5 * (a + b)
        };
        if !risen {
            below = Some(last);
        }
        last = Point {
            t,
            branches: f.near(t),
        };
    }
    (last, below)
}

/// [`first_rise_from_tangent`] with [`first_rise_predicted`]'s Taylor polynomials and predicted
/// crossings: for a compliant ball's grip whose margins carry f'' and f''' ([`Branch::higher`], the
/// modes' sums, as exact as f and f') and a bound `fourth` on each one's fourth derivative. The
/// polynomials only prove more intervals empty, with fewer evaluations; each crossing is refined from
/// the one predicted from f, f', f'' and f''' at both ends of its interval, one evaluation fewer a
/// crossing: the same root as [`first_rise_from_tangent`]'s by another path, so it may differ in its
/// last bits.
pub fn first_rise_predicted_from_tangent<B: Branch, const K: usize>(
    f: impl Event<B, K>,
    t0: f64,
    t1: f64,
    step: f64,
    [curvature, fourth]: [[f64; K]; 2],
    noise: [f64; K],
) -> Option<(f64, usize)> {
    let bounds = Bounds { curvature, fourth };
    search::<B, K, true, true>(f, t0, t1, step, bounds, noise, Start::Tangent)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_plain_crossing() {
        let t = first_rise(|t| [(t - 0.3, 1.0)], 0.0, 1.0, 0.1, [0.0], [0.0])
            .unwrap()
            .0;
        assert!((t - 0.3).abs() < 1e-15);
    }

    #[test]
    fn finds_a_bump_between_two_negative_samples() {
        // A narrow bump above zero between samples at 0.4 and 0.5.
        let f = |t: f64| (1e-4 - (t - 0.45) * (t - 0.45), -2.0 * (t - 0.45));
        let t = first_rise(|t| [f(t)], 0.0, 1.0, 0.1, [2.0], [0.0])
            .unwrap()
            .0;
        assert!((t - 0.44).abs() < 1e-12, "{t}");
    }

    #[test]
    fn finds_the_first_of_two_close_crossings() {
        // Up through zero at 0.30, down at 0.31, up again at 0.9: one coarse interval holds all three.
        let f = |t: f64| {
            let (p, q, r) = (t - 0.30, t - 0.31, t - 0.9);
            (p * q * r, q * r + p * r + p * q)
        };
        let t = first_rise(|t| [f(t)], 0.0, 1.0, 1.0, [6.0], [0.0])
            .unwrap()
            .0;
        assert!((t - 0.30).abs() < 1e-12, "{t}");
    }

    #[test]
    fn ignores_a_start_on_the_boundary() {
        // Starts at zero and falls: no event at t0, and the later crossing is found.
        let f = |t: f64| ((t - 0.5) * (t - 0.5) - 0.25 + 1e-17, 2.0 * (t - 0.5));
        let t = first_rise(|t| [f(t)], 0.0, 2.0, 0.1, [2.0], [0.0])
            .unwrap()
            .0;
        assert!((t - 1.0).abs() < 1e-12, "{t}");
    }

    #[test]
    fn the_cubic_model_refines_in_fewer_evaluations_than_newton() {
        // sin t - 1/2 rises through zero at pi/6; the coarse step [0, 1] puts the secant point 0.07
        // beyond it (Newton needs 7 evaluations in all, the cubic model 5).
        let count = Cell::new(0);
        let newton = |t: f64| {
            count.set(count.get() + 1);
            [(t.sin() - 0.5, t.cos())]
        };
        let t = first_rise(newton, 0.0, 1.0, 1.0, [1.0], [0.0]).unwrap().0;
        assert!((t - std::f64::consts::FRAC_PI_6).abs() < 1e-15, "{t}");
        let by_newton = count.replace(0);
        let taylor = |t: f64| {
            count.set(count.get() + 1);
            [(t.sin() - 0.5, t.cos(), -t.sin(), -t.cos())]
        };
        let t = first_rise(taylor, 0.0, 1.0, 1.0, [1.0], [0.0]).unwrap().0;
        assert!((t - std::f64::consts::FRAC_PI_6).abs() < 1e-15, "{t}");
        assert!(
            count.get() < by_newton,
            "{} against {by_newton}",
            count.get()
        );
    }

    #[test]
    fn taylor_bounds_prove_what_the_parabolas_cannot_and_find_the_same_crossing() {
        // cos t - 1 + t^4/20 leaves its zero at 0 with zero rate, bending away (f'' = -1), and
        // rises through zero again near t = 2.45; |f''''| <= 1 + 24/20.
        let count = Cell::new(0);
        let f = |t: f64| {
            count.set(count.get() + 1);
            let (s, c) = (t.sin(), t.cos());
            let t2 = t * t;
            [(
                c - 1.0 + t2 * t2 / 20.0,
                -s + t2 * t / 5.0,
                -c + 0.6 * t2,
                s + 1.2 * t,
            )]
        };
        let (curvature, fourth) = ([1.0 + 0.6 * 9.0], [1.0 + 24.0 / 20.0]);
        let parabolas = first_rise(f, 0.0, 3.0, 1.0, curvature, [0.0]);
        let by_parabolas = count.replace(0);
        let taylor = first_rise_within(f, 0.0, 3.0, 1.0, [curvature, fourth], [0.0]);
        let t = taylor.unwrap().0;
        assert!((t.cos() - 1.0 + t.powi(4) / 20.0).abs() < 1e-12, "{t}");
        // The same crossing, bit for bit, in fewer evaluations.
        assert_eq!(
            taylor.map(|(t, _)| t.to_bits()),
            parabolas.map(|(t, _)| t.to_bits())
        );
        assert!(
            count.get() < by_parabolas,
            "{} against {by_parabolas}",
            count.get()
        );
        // A bound the branch does not respect is not needed for a crossing it cannot hide: with no
        // f'' and f''' the Taylor bound proves nothing, and the search is the parabolas'.
        let plain = |t: f64| [(f(t)[0].0, f(t)[0].1)];
        assert_eq!(
            first_rise_within(plain, 0.0, 3.0, 1.0, [curvature, fourth], [0.0]),
            first_rise(plain, 0.0, 3.0, 1.0, curvature, [0.0])
        );
    }

    #[test]
    fn the_taylor_ceiling_bounds_a_quartic_from_above() {
        let quartic = [-1.0, 3.0, -2.0, 0.5, 0.25];
        let p = |s: f64| quartic.iter().rev().fold(0.0, |acc, &c| acc * s + c);
        for (near, far) in [(0.0, 0.5), (0.5, 1.0), (1.0, 3.0), (0.0, 4.0)] {
            let ceiling = taylor_ceiling(&quartic, near, far);
            for k in 0..=100 {
                let s = near + (far - near) * f64::from(k) / 100.0;
                assert!(p(s) <= ceiling, "{s}: {} > {ceiling}", p(s));
            }
        }
    }

    #[test]
    fn the_earlier_of_two_branches_wins() {
        let two = |t: f64| [(t - 0.7, 1.0), (t - 0.4, 1.0)];
        let (t, branch) = first_rise(two, 0.0, 1.0, 0.25, [0.0; 2], [0.0; 2]).unwrap();
        assert!((t - 0.4).abs() < 1e-15, "{t}");
        assert_eq!(branch, 1);
    }

    #[test]
    fn noise_is_not_a_rise() {
        let hover = |t: f64| (1e-17 * (t * 1e3).sin(), 1e-14 * (t * 1e3).cos());
        assert_eq!(
            first_rise(|t| [hover(t)], 0.0, 1.0, 0.1, [1e-11], [1e-15]),
            None
        );
    }

    #[test]
    fn none_when_it_stays_below() {
        assert_eq!(
            first_rise(|t| [(-1.0 - t, -1.0)], 0.0, 1.0, 0.1, [0.0], [0.0]),
            None
        );
        // Comes within 1e-6 of zero at t = pi/20 and turns back.
        let grazes = |t: f64| ((t * 10.0).sin() - 1.0 - 1e-6, 10.0 * (t * 10.0).cos());
        assert_eq!(
            first_rise(|t| [grazes(t)], 0.0, 1.0, 0.5, [100.0], [0.0]),
            None
        );
    }

    #[test]
    fn a_step_below_the_rounding_of_t_stalls_instead_of_spinning() {
        let f = |t: f64| [(-1.0 - t, -1.0)];
        let found = metered(1000, || first_rise(f, 1.0, 2.0, 1e-20, [0.0], [0.0]));
        assert_eq!(found, Err(Stall::Resolution { t: 1.0 }));
    }

    #[test]
    fn a_search_that_proves_nothing_stops_at_its_budget() {
        // An infinite curvature proves no interval empty: unmetered, the halving would never end.
        let f = |t: f64| [(-1.0 - t, -1.0)];
        let found = metered(500, || first_rise(f, 0.0, 1.0, 0.1, [f64::INFINITY], [0.0]));
        assert!(
            matches!(
                found,
                Err(Stall::Budget {
                    evaluations: 500,
                    ..
                })
            ),
            "{found:?}"
        );
        // The meter is the solve's own: the next one starts afresh.
        assert_eq!(
            metered(500, || first_rise(f, 0.0, 1.0, 0.1, [0.0], [0.0])),
            Ok(None)
        );
    }
}
