//! Checks the bounds the single cart gives its event search against the branches they bound: over random
//! valid bounces, every phase's branches are sampled densely from the phase's start to the event the
//! search found (or the end of contact), and at each sample |f''| must stay within the curvature bound and
//! |f''''| within the fourth-derivative bound. A bound that is too small lets the search miss a
//! transition silently, so each is tested where the solver uses it.
//!
//! f'' is the branch's own (the 4-tuple carries it, from the closed form); f'''' is the central difference
//! of the f''' it carries, (f'''(t + h) - f'''(t - h)) / 2h with h = 1e-5 of the search's coarse step
//! (pi over the fastest angular frequency Ω present): its truncation error is (hΩ)²/6 ≈ 2e-10 of the
//! bound, covered by a relative room of 1e-6, and its rounding is at most a few ulps of the largest
//! |f'''| over h, covered by 1e3 ulps of it over h (about 1e-8 of Ω max |f'''|, far below any bound a real
//! violation would cross: halving a bound that is reached fails the test, see `fails_when_halved`).
//! The differences stay 2h inside the phase (h is at most an eighth of it): N = max(sin w t, 0) is not
//! smooth at the start and end of contact, so a difference across t = 0 or T is no f''''. There the slide carries the rate from inside the
//! contact (F' = mu N0 w at t = 0, tested below), as the Taylor polynomials from an interval's ends need.

use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;

use proptest::prelude::*;

use crate::model::params::Params;
use crate::model::setup::Setup;
use crate::model::solve::solve;

thread_local! {
    /// Whether the searches check their bounds (only the tests here ask it).
    static ON: Cell<bool> = const { Cell::new(false) };
    /// Each bound is scaled by this before the check (1, or 0.5 to show the check can fail).
    static SCALE: Cell<f64> = const { Cell::new(1.0) };
    /// Phases checked, by regime.
    static CHECKED: RefCell<BTreeMap<&'static str, usize>> = const { RefCell::new(BTreeMap::new()) };
    /// The violations found: regime, branch, which bound, time, value, bound.
    static VIOLATIONS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// A phase's samples before its search ran: the regime, the bounds (scaled), and at each time f'' and the
/// central difference of f''', with the tolerance of the difference.
pub struct Sampled<const K: usize> {
    regime: &'static str,
    bounds: [[f64; K]; 2],
    samples: Vec<(f64, [f64; K], [f64; K])>,
    slack: [f64; K],
}

/// Samples the branches of `f` over [t0, end] when the check is on (before the search, so the states the
/// search records are its own).
pub fn sample<const K: usize>(
    regime: &'static str,
    f: &impl Fn(f64) -> [(f64, f64, f64, f64); K],
    t0: f64,
    end: f64,
    step: f64,
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
        let second = at.map(|b| b.2);
        let fourth = std::array::from_fn(|k| (after[k].3 - before[k].3) / (high - low));
        for k in 0..K {
            third_scale[k] = third_scale[k].max(at[k].3.abs());
        }
        samples.push((t, second, fourth));
    }
    let slack = third_scale.map(|s| 1e3 * f64::EPSILON * s / h);
    Some(Sampled {
        regime,
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
    CHECKED.with_borrow_mut(|c| *c.entry(regime).or_default() += 1);
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

/// Random valid single-cart bounces, as the property tests draw them (tests/physics/properties.rs):
/// light and heavy carts, no spring, string friction in half the cases, tiny and large mu, spin either
/// way; no chain, no compliant ball.
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
    let string = prop_oneof![Just(0.0), 0.0f64..2.0];
    let cart = (
        log(1e-5, 1e6),
        prop_oneof![Just(0.0), log(1.0, 1e6)],
        string,
    );
    (ball, throw, contact, cart).prop_map(|(ball, throw, contact, cart)| {
        let ((mass, radius, alpha), (angle_deg, speed, spin)) = (ball, throw);
        let ((mu, duration, ey), (cart_mass, stiffness, string)) = (contact, cart);
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
            chain: 1.0,
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

/// Runs the check over `cases` random bounces and the counts of phases checked by regime.
fn run(cases: u32) -> BTreeMap<&'static str, usize> {
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
fn the_search_bounds_hold_over_random_bounces() {
    let checked = run(cases(400));
    // Every regime of the single cart was entered and checked.
    for regime in [
        "slide, string friction",
        "slide by its sums",
        "slide on a still cart",
        "grip, string friction",
        "grip by its sums",
    ] {
        assert!(
            checked.get(regime).is_some_and(|&n| n > 0),
            "{regime} never checked: {checked:?}"
        );
    }
}

#[test]
#[ignore = "slow tier: cargo test --release --lib -- --ignored"]
fn the_search_bounds_hold_over_many_random_bounces() {
    run(cases(20000));
}

#[test]
fn the_friction_rate_at_first_contact_is_the_one_inside_contact() {
    use super::super::contact::Cart;
    use super::slide::Slide;
    let setup = Setup::new(&Params::default());
    let slide = Slide::new(
        &setup,
        setup.initial(Params::default().spin),
        1.0,
        Cart::Moving(1),
    );
    let (_, (friction, rate)) = slide.sample(&setup, 0.0);
    assert_eq!(friction, 0.0);
    assert_eq!(rate, setup.peak_friction() * setup.w);
}

#[test]
fn fails_when_halved() {
    // The default bounce's slide at the paper's figure: halved bounds are crossed.
    let p = Params::default();
    assert!(violations(&p, 1.0).is_empty());
    assert!(!violations(&p, 0.5).is_empty());
}

/// A last slide of 83 ns, on a cart string friction holds still, found by the slow tier: with the
/// difference step of the longer phases (h = 104 ns) the samples near T differenced across the end of
/// contact (f''' is 0 beyond it), a violation of the sampling's own making.
#[test]
fn a_phase_shorter_than_the_difference_step_is_sampled_inside_itself() {
    let p = Params {
        angle_deg: 0.5,
        speed: 0.5,
        spin: 0.0,
        mu: 1.0439194801091243,
        duration: 0.010388565645786187,
        ey: 0.0,
        mass: 0.005,
        radius: 0.005,
        alpha: 0.2,
        cart_mass: 0.931112582197682,
        stiffness: 290.3526456688556,
        cart_friction: 0.0024935718319515038,
        ..Params::default()
    };
    CHECKED.take();
    let found = violations(&p, 1.0);
    assert!(found.is_empty(), "{}", found.join("; "));
    assert_eq!(CHECKED.take().get("slide on a still cart"), Some(&2));
}
