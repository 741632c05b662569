//! Shared by the property tests: their configuration, a log-uniform strategy, the friction cone, and the check that string
//! friction holds the cart (or a chain's first mass) still and lets a moving one turn only at an event.

use proptest::prelude::*;
use proptest::test_runner::{FileFailurePersistence, TestCaseError};
use snapback::model::{Bounce, Cart, Params, Sample};

/// `default` cases, or as many as `PROPTEST_CASES` asks for (`PROPTEST_CASES=100000` searches deeper).
/// Failures are kept beside the test's source (`chain.rs` -> `chain.proptest-regressions`).
pub fn config(default: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default);
    ProptestConfig {
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..ProptestConfig::with_cases(cases)
    }
}

/// Values spread evenly in log between `lo` and `hi` (both positive).
pub fn log_range(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..=hi.ln()).prop_map(f64::exp)
}

/// With string friction, a held cart does not move within its phase, and a moving one never turns within
/// a phase (its stopping ends it): checked at eight points of every phase.
#[allow(dead_code)] // not every property test has string friction
pub fn check_cart_motion(p: &Params, b: &Bounce) -> Result<(), TestCaseError> {
    let speed_scale = p.speed + p.radius * p.spin.abs();
    for (index, phase) in b.phases.iter().enumerate() {
        let first = b.sample_in(index, phase.start);
        for i in 1..=8 {
            let s = b.sample_in(index, phase.start + phase.duration() * f64::from(i) / 8.0);
            match phase.cart {
                Cart::Stuck => prop_assert!(s.v == 0.0 && s.x == first.x),
                Cart::Moving(dir) if p.cart_friction > 0.0 => {
                    prop_assert!(
                        f64::from(dir) * s.v >= -1e-9 * speed_scale,
                        "the cart turned inside a phase"
                    );
                }
                Cart::Moving(_) => {}
            }
        }
    }
    Ok(())
}

/// |F| <= mu N at the sample `s`, within the rounding of the forces at the peak normal force `n_peak`
/// (N vanishes at the ends of the contact).
pub fn within_the_cone(p: &Params, s: &Sample, n_peak: f64) -> Result<(), TestCaseError> {
    prop_assert!(
        s.friction.abs() <= p.mu * s.normal + 1e-9 * p.mu * n_peak + 1e-12,
        "|F| = {} > mu N = {} at t = {}",
        s.friction.abs(),
        p.mu * s.normal,
        s.t
    );
    Ok(())
}
