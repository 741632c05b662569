//! CSV of a sampled time series, SI units: `t,N,F,X,V,vx,omega,slip,phase,cart_stuck,stretch,patch_slip`.

use std::fmt::Write;

use crate::model::Sample;

/// The header line of [`series`].
pub const HEADER: &str = "t,N,F,X,V,vx,omega,slip,phase,cart_stuck,stretch,patch_slip";

/// The samples as CSV with a header line.
pub fn series(samples: &[Sample]) -> String {
    let mut out = String::with_capacity(120 * (samples.len() + 1));
    out.push_str(HEADER);
    out.push('\n');
    for s in samples {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            s.t,
            s.normal,
            s.friction,
            s.x,
            s.v,
            s.vx,
            s.omega,
            s.slip,
            s.kind.name(),
            s.cart_stuck,
            s.stretch,
            s.patch_slip
        );
    }
    out
}
