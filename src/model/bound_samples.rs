//! The check behind the bounds tests (`cart/bounds.rs`, `chain/bounds.rs`): a search that proves
//! intervals empty by bounds on its branches' f'' and f'''' hands its branches here before it runs, and
//! they are sampled densely from the phase's start to the event the search found (or the end of
//! contact); at each sample |f''| must stay within the curvature bound and |f''''| within the
//! fourth-derivative bound. A bound that is too small lets the search miss a transition silently.
//!
//! f'' is the branch's own; f'''' is the central difference of the f''' it carries,
//! (f'''(t + h) - f'''(t - h)) / ((t + h) - (t - h)) with h = 1e-5 of the search's coarse step (pi over
//! the fastest angular frequency Ω present), or an eighth of the phase if that is less: its truncation
//! error is (hΩ)²/6 ≈ 2e-10 of the bound, covered by a relative room of 1e-6, and its rounding is at
//! most a few ulps of the largest |f'''| over h, covered by 1e3 ulps of it over h (about 1e-8 of
//! Ω max |f'''|, far below any bound a real violation would cross). The differences stay 2h inside the
//! phase: N = max(sin w t, 0) is not smooth at the start and end of contact, so a difference across
//! t = 0 or T is no f''''. Only the thread that asked (`violations`) is checked.

use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;

use proptest::prelude::*;

use super::events::Event;
use super::params::Params;
use super::setup::Setup;
use super::solve::solve;

thread_local! {
    /// Whether the searches check their bounds (only the bounds tests ask it).
    static ON: Cell<bool> = const { Cell::new(false) };
    /// Each bound is scaled by this before the check (1, or 0.5 to show the check can fail).
    static SCALE: Cell<f64> = const { Cell::new(1.0) };
    /// Phases checked, by regime.
    static CHECKED: RefCell<BTreeMap<String, usize>> = const { RefCell::new(BTreeMap::new()) };
    /// The violations found: regime, branch, which bound, time, value, bound.
    static VIOLATIONS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// A phase's samples before its search ran: the regime, the bounds (scaled), and at each time f'' and
/// the central difference of f''', with the tolerance of the difference.
pub struct Sampled<const K: usize> {
    regime: String,
    bounds: [[f64; K]; 2],
    samples: Vec<(f64, [f64; K], [f64; K])>,
    slack: [f64; K],
}

/// Samples the branches of `f` (each f, f', f'', f''') over [t0, end] when the check is on (before the
/// search, so that the states the search records are its own). `regime` names the phase's search.
pub fn sample<const K: usize>(
    regime: impl FnOnce() -> String,
    f: &impl Fn(f64) -> [[f64; 4]; K],
    (t0, end, step): (f64, f64, f64),
    bounds: [[f64; K]; 2],
) -> Option<Sampled<K>> {
    if !ON.get() || end <= t0 {
        return None;
    }
    let scale = SCALE.get();
    let bounds = bounds.map(|b| b.map(|x| x * scale));
    // A phase shorter than 8h takes a smaller h, so that t ± h stays inside it.
    let h = (1e-5 * step).min((end - t0) / 8.0);
    let n = ((16.0 * (end - t0) / step).ceil() as usize).clamp(256, 8192);
    let mut third_scale = [0.0f64; K];
    let mut samples = Vec::with_capacity(n + 1);
    for i in 0..=n {
        let t = t0 + 2.0 * h + (end - t0 - 4.0 * h) * i as f64 / n as f64;
        // Divided by the times' own difference: on a phase a few ulps of t long, 2h is not it.
        let (low, high) = (t - h, t + h);
        let (at, before, after) = (f(t), f(low), f(high));
        let second = at.map(|b| b[2]);
        let fourth = std::array::from_fn(|k| (after[k][3] - before[k][3]) / (high - low));
        for k in 0..K {
            third_scale[k] = third_scale[k].max(at[k][3].abs());
        }
        samples.push((t, second, fourth));
    }
    let slack = third_scale.map(|s| 1e3 * f64::EPSILON * s / h);
    Some(Sampled {
        regime: regime(),
        bounds,
        samples,
        slack,
    })
}

/// Checks the samples up to the event the search found at `until` (or the end of contact).
pub fn check<const K: usize>(sampled: Option<Sampled<K>>, until: f64) {
    let Some(Sampled {
        regime,
        bounds: [curvature, fourth],
        samples,
        slack,
    }) = sampled
    else {
        return;
    };
    for (t, second, fd) in samples.into_iter().filter(|s| s.0 <= until) {
        for k in 0..K {
            let room = 1.0 + 1e-6;
            if second[k].abs() > curvature[k] * room + 1e-300 {
                VIOLATIONS.with_borrow_mut(|v| {
                    v.push(format!(
                        "{regime}: branch {k} |f''| = {:e} > {:e} at t = {t:e}",
                        second[k].abs(),
                        curvature[k]
                    ))
                });
            }
            if fd[k].abs() > fourth[k] * room + slack[k] {
                VIOLATIONS.with_borrow_mut(|v| {
                    v.push(format!(
                        "{regime}: branch {k} |f''''| = {:e} > {:e} (+ {:e}) at t = {t:e}",
                        fd[k].abs(),
                        fourth[k],
                        slack[k]
                    ))
                });
            }
        }
    }
    CHECKED.with_borrow_mut(|c| *c.entry(regime).or_default() += 1);
}

/// Solves `p` with the check on, bounds scaled by `scale`: the violations found (none when `p` is
/// refused).
pub fn violations(p: &Params, scale: f64) -> Vec<String> {
    ON.set(true);
    SCALE.set(scale);
    VIOLATIONS.with_borrow_mut(Vec::clear);
    let solved = solve(p);
    ON.set(false);
    SCALE.set(1.0);
    let found = VIOLATIONS.take();
    if solved.is_err() {
        return Vec::new();
    }
    found
}

/// The phases checked by regime since the last call.
pub fn checked() -> BTreeMap<String, usize> {
    CHECKED.take()
}

/// How many cases: `default`, or as many as `PROPTEST_CASES` asks for.
pub fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Runs the check over `cases` bounces drawn from `params`: the counts of phases checked by regime.
pub fn run(params: impl Strategy<Value = Params>, cases: u32) -> BTreeMap<String, usize> {
    checked();
    let config = ProptestConfig {
        failure_persistence: None,
        ..ProptestConfig::with_cases(cases)
    };
    proptest::test_runner::TestRunner::new(config)
        .run(&params, |p| {
            let found = violations(&p, 1.0);
            prop_assert!(found.is_empty(), "{p:?}: {}", found.join("; "));
            Ok(())
        })
        .unwrap();
    let checked = checked();
    eprintln!("phases checked by regime: {checked:?}");
    checked
}

/// [`run`], asserting that every one of `regimes` was entered and checked.
pub fn run_entering(params: impl Strategy<Value = Params>, cases: u32, regimes: &[&str]) {
    let checked = run(params, cases);
    for regime in regimes {
        assert!(
            checked.get(*regime).is_some_and(|&n| n > 0),
            "{regime} never checked: {checked:?}"
        );
    }
}

/// `search` run on the event `f`, its branches first sampled against `bounds` over [t0, end] when the
/// check is on ([`sample`]), and checked up to the event it found ([`check`]): the searches by bounds
/// call their search through this under test.
pub fn search_checked<const K: usize, F: Event<(f64, f64, f64, f64), K>>(
    regime: impl FnOnce() -> String,
    f: F,
    (t0, end, step): (f64, f64, f64),
    bounds: [[f64; K]; 2],
    search: impl FnOnce(F) -> Option<(f64, usize)>,
) -> Option<(f64, usize)> {
    let sampled = sample(
        regime,
        &|t| {
            f.at(t)
                .map(|(value, rate, second, third)| [value, rate, second, third])
        },
        (t0, end, step),
        bounds,
    );
    let found = search(f);
    check(sampled, found.map_or(end, |(t, _)| t));
    found
}

/// A random rigid ball, throw and contact, as the property tests draw them (tests/physics/properties.rs),
/// on the default cart: 5 g to 0.5 kg, grazing to normal incidence at 0.5 to 50 m/s with spin either
/// way, mu from 1e-9 to 1.2, contacts of 0.5 to 20 ms, any e_y.
pub fn rigid_ball() -> impl Strategy<Value = Params> {
    let ball = (0.005f64..0.5, 0.005f64..0.12, 0.2f64..1.0);
    let throw = (
        prop_oneof![0.5f64..=90.0, Just(90.0)],
        0.5f64..50.0,
        -500.0f64..500.0,
    );
    let contact = (
        prop_oneof![0.0f64..1.2, (-9.0f64..0.0).prop_map(|e| 10f64.powf(e))],
        0.5e-3f64..20e-3,
        0.0f64..=1.0,
    );
    (ball, throw, contact).prop_map(|(ball, throw, contact)| {
        let ((mass, radius, alpha), (angle_deg, speed, spin)) = (ball, throw);
        let (mu, duration, ey) = contact;
        Params {
            angle_deg,
            speed,
            spin,
            mu,
            duration,
            ey,
            mass,
            radius,
            alpha,
            ball_stiffness: 0.0,
            ball_damping: 0.0,
            ..Params::default()
        }
    })
}

/// Uniform in the logarithm between `lo` and `hi`.
pub fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..=hi.ln()).prop_map(f64::exp)
}

/// `p` with string friction `share` of its ball's peak friction mu N0.
pub fn with_string_friction(p: Params, share: f64) -> Params {
    let cart_friction = share * Setup::new(&p).peak_friction();
    Params { cart_friction, ..p }
}
