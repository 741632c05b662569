//! sin and cos together for the closed forms, inlined: the phases evaluate them at every probe of the
//! event search, and the library call was a fifth of a bounce's work.
//!
//! The angle is reduced by π/2 in two parts (a 33-bit head, so that k times it is exact for |k| < 2^20,
//! and the rest to 53 bits), then sin and cos of the remainder r, |r| <= π/4, come from their Taylor
//! series to r^17 and r^18 (the first term left out is below 1e-19). The result is within about an ulp
//! of the correctly rounded one, the remainder's absolute error about 1e-21; angles beyond
//! `REDUCED` (none of the closed forms' arguments, which [`super::error::MAX_RADIANS`] bounds) and
//! non-finite ones go to the library.

use std::f64::consts::FRAC_2_PI;

/// The largest |x| reduced here: k = x 2/π stays below 2^20.
const REDUCED: f64 = 1.5e6;
/// π/2 to 33 bits, and the rest of it.
const HALF_PI_HEAD: f64 = 1.570_796_326_734_125_6;
const HALF_PI_TAIL: f64 = 6.077_100_506_506_192e-11;
/// Added and taken away, rounds to the nearest integer (below 2^51).
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// The Taylor coefficients of sin r / r - 1 and of (cos r - 1 + r²/2) / r⁴, as polynomials in r².
const SIN: [f64; 8] = [
    -1.0 / 6.0,
    1.0 / 120.0,
    -1.0 / 5_040.0,
    1.0 / 362_880.0,
    -1.0 / 39_916_800.0,
    1.0 / 6_227_020_800.0,
    -1.0 / 1_307_674_368_000.0,
    1.0 / 355_687_428_096_000.0,
];
const COS: [f64; 8] = [
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40_320.0,
    -1.0 / 3_628_800.0,
    1.0 / 479_001_600.0,
    -1.0 / 87_178_291_200.0,
    1.0 / 20_922_789_888_000.0,
    -1.0 / 6_402_373_705_728_000.0,
];

/// (sin x, cos x).
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    // NaN and infinities go to libm too.
    if x.is_nan() || x.abs() > REDUCED {
        return x.sin_cos();
    }
    // k = x 2/π to the nearest integer; the last bits of `rounded` are those of k (2^51 + k, in two's
    // complement), so they give the quadrant.
    let rounded = x * FRAC_2_PI + ROUNDER;
    let k = rounded - ROUNDER;
    // x - k head is exact; r + low is the remainder to about 1e-21.
    let (head, tail) = (x - k * HALF_PI_HEAD, k * HALF_PI_TAIL);
    let r = head - tail;
    let low = (head - r) - tail;
    let z = r * r;
    let (sin_poly, cos_poly) = (horner(&SIN, z), horner(&COS, z));
    // sin(r + low) = sin r + low cos r, cos(r + low) = cos r - low sin r, to first order; 1 - z/2
    // rounds, and its rounding error is added back.
    let half = 0.5 * z;
    let one_less = 1.0 - half;
    let s = r + (r * z * sin_poly + low * one_less);
    let c = one_less + (((1.0 - one_less) - half) + (z * z * cos_poly - r * low));
    match rounded.to_bits() & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// The polynomial with `coefficients` (constant first) at `z`.
#[inline(always)]
fn horner(coefficients: &[f64; 8], z: f64) -> f64 {
    coefficients[..7]
        .iter()
        .rev()
        .fold(coefficients[7], |acc, &coefficient| acc * z + coefficient)
}

/// sin x alone (the same reduction and series).
#[inline]
pub fn sin(x: f64) -> f64 {
    sin_cos(x).0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the library: within a unit in the last place of the larger of the result and 1/4
    /// (about 6e-17 absolute near a zero of sin or cos), over the angles the closed forms take.
    #[test]
    fn agrees_with_the_library() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut worst: f64 = 0.0;
        for span in [1e-8, 1e-3, 0.8, 3.2, 10.0, 1e3, 1e5, 1.5e6] {
            for _ in 0..200_000 {
                let x = (2.0 * uniform() - 1.0) * span;
                let (s, c) = sin_cos(x);
                let (ls, lc) = x.sin_cos();
                for (got, want) in [(s, ls), (c, lc)] {
                    let ulp = f64::EPSILON * want.abs().max(0.25);
                    worst = worst.max((got - want).abs() / ulp);
                }
            }
        }
        assert!(worst <= 1.0, "{worst} ulp");
    }

    #[test]
    fn exact_where_it_must_be() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert_eq!(sin_cos(1e-300), (1e-300, 1.0));
        assert!(sin_cos(f64::NAN).0.is_nan());
        let (s, c) = sin_cos(1e9);
        assert_eq!((s, c), 1e9f64.sin_cos());
    }
}
