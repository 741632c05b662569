//! Shared by the property tests: their configuration and a log-uniform strategy.

use proptest::prelude::*;

/// `default` cases, or as many as `PROPTEST_CASES` asks for (`PROPTEST_CASES=100000` searches deeper).
pub fn config(default: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default);
    ProptestConfig::with_cases(cases)
}

/// Values spread evenly in log between `lo` and `hi` (both positive).
pub fn log_range(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..=hi.ln()).prop_map(f64::exp)
}
