//! Checks the bounds the chain's search by Taylor bounds (`search.rs`) gives it against the branches
//! they bound: over random valid chain bounces, on the wall and on a free frame, every phase searched so
//! is sampled densely from its start to the event the search found (or the end of contact), and at each
//! sample |f''| must stay within the curvature bound and |f''''| within the fourth-derivative bound. A
//! bound that is too small lets the search miss a transition silently, so each is tested where the
//! solver uses it (as `cart/bounds.rs` tests the single cart's).
//!
//! f'' is the branch's own (from the phase's sums); f'''' is the central difference of the f''' it
//! carries, (f'''(t + h) - f'''(t - h)) / 2h with h = 1e-5 of the search's coarse step (pi over the
//! fastest angular frequency present): its truncation error is (hΩ)²/6 ≈ 2e-10 of the bound, covered by
//! a relative room of 1e-6, and its rounding is at most a few ulps of the largest |f'''| over h, covered
//! by 1e3 ulps of it over h. The differences stay 2h inside the phase (h is at most an eighth of it), where N = max(sin w t, 0) is
//! smooth. Halving a bound that is reached fails the test (`fails_when_halved`).

use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;

use proptest::prelude::*;

use super::motion::Motion;
use crate::model::params::Params;
use crate::model::setup::Setup;
use crate::model::solve::solve;

thread_local! {
    /// Whether the searches check their bounds (only the tests here ask it).
    static ON: Cell<bool> = const { Cell::new(false) };
    /// Each bound is scaled by this before the check (1, or 0.5 to show the check can fail).
    static SCALE: Cell<f64> = const { Cell::new(1.0) };
    /// Phases checked, by regime.
    static CHECKED: RefCell<BTreeMap<String, usize>> = const { RefCell::new(BTreeMap::new()) };
    /// The violations found.
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

/// Samples the branches of `f` (each f, f', f'', f''') over [t0, end] when the check is on.
pub fn sample<const K: usize>(
    regime: &'static str,
    motion: &Motion,
    f: &impl Fn(f64) -> [[f64; 4]; K],
    (t0, end, step): (f64, f64, f64),
    bounds: [[f64; K]; 2],
) -> Option<Sampled<K>> {
    if !ON.get() || end <= t0 {
        return None;
    }
    let place = if motion.start.frame > 0 {
        "on a frame"
    } else {
        "on the wall"
    };
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
        regime: format!("{regime} {place}"),
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

/// Solves `p` with the check on, bounds scaled by `scale`: the violations found.
fn violations(p: &Params, scale: f64) -> Vec<String> {
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

/// Random valid chain bounces: 2 to 12 masses, light and heavy, stiff and soft, on the wall or on a
/// free frame from a tenth of the chain's mass to a thousand times it, string friction in a third of
/// the cases, tiny and large mu, spin either way; a rigid ball.
fn params() -> impl Strategy<Value = Params> {
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
    let log = |lo: f64, hi: f64| (lo.ln()..=hi.ln()).prop_map(f64::exp);
    let string = prop_oneof![Just(0.0), Just(0.0), 0.0f64..2.0];
    let frame = prop_oneof![Just(0.0), log(0.1, 1000.0)];
    let chain = (2u32..=12, log(1e-4, 10.0), log(10.0, 1e6), frame, string);
    (ball, throw, contact, chain).prop_map(|(ball, throw, contact, chain)| {
        let ((mass, radius, alpha), (angle_deg, speed, spin)) = (ball, throw);
        let (mu, duration, ey) = contact;
        let (links, cart_mass, stiffness, frame, string) = chain;
        let p = Params {
            angle_deg,
            speed,
            spin,
            mu,
            duration,
            ey,
            mass,
            radius,
            alpha,
            cart_mass,
            stiffness,
            chain: f64::from(links),
            frame_mass: frame * cart_mass,
            ball_stiffness: 0.0,
            ball_damping: 0.0,
            ..Params::default()
        };
        let cart_friction = string * Setup::new(&p).peak_friction();
        Params { cart_friction, ..p }
    })
}

/// How many cases: `default`, or as many as `PROPTEST_CASES` asks for.
fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Runs the check over `cases` random bounces: the counts of phases checked by regime.
fn run(cases: u32) -> BTreeMap<String, usize> {
    CHECKED.take();
    let config = ProptestConfig {
        failure_persistence: None,
        ..ProptestConfig::with_cases(cases)
    };
    proptest::test_runner::TestRunner::new(config)
        .run(&params(), |p| {
            let found = violations(&p, 1.0);
            prop_assert!(found.is_empty(), "{p:?}: {}", found.join("; "));
            Ok(())
        })
        .unwrap();
    let checked = CHECKED.take();
    eprintln!("phases checked by regime: {checked:?}");
    checked
}

#[test]
fn the_search_bounds_hold_over_random_chains() {
    let checked = run(cases(200));
    for regime in [
        "slide on the wall",
        "slide on a frame",
        "grip on the wall",
        "grip on a frame",
    ] {
        assert!(
            checked.get(regime).is_some_and(|&n| n > 0),
            "{regime} never checked: {checked:?}"
        );
    }
}

#[test]
#[ignore = "slow tier: cargo test --release --lib -- --ignored"]
fn the_search_bounds_hold_over_many_random_chains() {
    run(cases(5000));
}

#[test]
fn fails_when_halved() {
    // A chain of 4 on the wall and on a 188 g frame: halved bounds are crossed. The fourth
    // derivative's bounds are reached within a factor 2 by the slide on the wall and the grip on
    // both (on the frame the slide's bound on |q_j'| leaves it more room than that).
    let mut halved = Vec::new();
    for frame_mass in [0.0, 0.188] {
        let p = Params {
            chain: 4.0,
            frame_mass,
            ..Params::default()
        };
        assert!(violations(&p, 1.0).is_empty(), "{frame_mass}");
        halved.extend(violations(&p, 0.5));
    }
    for regime in ["slide on the wall", "grip on the wall", "grip on a frame"] {
        assert!(
            halved
                .iter()
                .any(|v| v.starts_with(regime) && v.contains("|f''''|")),
            "{regime}: {halved:?}"
        );
    }
}
