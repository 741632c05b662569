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
        for value in [s.t, s.normal, s.friction, s.x, s.v, s.vx, s.omega, s.slip] {
            let _ = write!(out, "{},", Number(value));
        }
        let _ = writeln!(
            out,
            "{},{},{},{}",
            s.kind.name(),
            s.cart_stuck,
            Number(s.stretch),
            Number(s.patch_slip)
        );
    }
    out
}

/// A number as CSV writes it: the shortest text that reads back as the same f64, in exponent form
/// outside [1e-5, 1e16) so that no field runs to hundreds of digits (`1e300`, not 301 of them).
pub struct Number(pub f64);

impl std::fmt::Display for Number {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let size = self.0.abs();
        if size == 0.0 || (1e-5..1e16).contains(&size) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_read_back_exactly() {
        for (x, text) in [
            (0.0, "0"),
            (0.057, "0.057"),
            (-15000.0, "-15000"),
            (1e300, "1e300"),
            (-2.5e-300, "-2.5e-300"),
            (1.2345e16, "1.2345e16"),
        ] {
            assert_eq!(Number(x).to_string(), text);
            assert_eq!(text.parse::<f64>(), Ok(x));
        }
    }
}
