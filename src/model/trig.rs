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
    let (sin_poly, cos_poly) = series(z);
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

/// [`sin_cos`] of two angles at once, bit for bit the same: the two run side by side in the lanes of
/// one vector register where the target has them (every operation is the scalar one, lane by lane, and
/// the quadrant is chosen by bit masks rather than a branch). A phase's closed form needs the normal
/// force's angle and its oscillator's together at every probe of the event search.
#[inline(never)]
pub fn sin_cos2(x: f64, y: f64) -> ((f64, f64), (f64, f64)) {
    let plain = |a: f64| !a.is_nan() && a.abs() <= REDUCED;
    if !(plain(x) && plain(y)) {
        return (sin_cos(x), sin_cos(y));
    }
    let (s, c) = reduced([x, y], series);
    ((s[0], c[0]), (s[1], c[1]))
}

/// The largest turn [`turned`] takes, rad: the next term of its sine's series, d^5/120, is then below
/// 1e-22, under a hundredth of a unit in the last place of sin d.
pub const SMALL_TURN: f64 = 1e-4;

/// (sin, cos) of x + d from (sin x, cos x), for |d| <= [`SMALL_TURN`]: by angle addition, with sin d
/// = d - d³/6 and 1 - cos d = d²/2 - d⁴/24 from their series.
#[inline(always)]
pub fn turned((s, c): (f64, f64), d: f64) -> (f64, f64) {
    let d2 = d * d;
    let sin_d = d - d * d2 * (1.0 / 6.0);
    let one_less_cos = d2 * (0.5 - d2 * (1.0 / 24.0));
    (
        s + (c * sin_d - s * one_less_cos),
        c - (s * sin_d + c * one_less_cos),
    )
}

/// Two angles' sines and cosines at some time, turned by a `step` in time at their `rates` (rad/s),
/// where both turns are within [`SMALL_TURN`] (else `None`).
#[inline(always)]
pub fn turned2(
    (first, second): ((f64, f64), (f64, f64)),
    rates: (f64, f64),
    step: f64,
) -> Option<((f64, f64), (f64, f64))> {
    let turns = (rates.0 * step, rates.1 * step);
    (turns.0.abs().max(turns.1.abs()) <= SMALL_TURN)
        .then(|| (turned(first, turns.0), turned(second, turns.1)))
}

/// The polynomial with `coefficients` (constant first) at `z`.
#[inline(always)]
fn horner<const N: usize>(coefficients: &[f64; N], z: f64) -> f64 {
    coefficients[..N - 1]
        .iter()
        .rev()
        .fold(coefficients[N - 1], |acc, &coefficient| {
            acc * z + coefficient
        })
}

/// The degree-7 polynomial with `c` (constant first) at `z` by Estrin's scheme: pairs, then pairs of
/// pairs, so its chain of dependent products and sums is 3 long, not Horner's 7 (as accurate: on 10^5
/// random angles sin and cos stay within 0.83 ulp, with the same rms error, 0.29 ulp, as by Horner's).
#[inline(always)]
fn estrin(c: &[f64; 8], z: f64) -> f64 {
    let z2 = z * z;
    let z4 = z2 * z2;
    let p01 = c[0] + c[1] * z;
    let p23 = c[2] + c[3] * z;
    let p45 = c[4] + c[5] * z;
    let p67 = c[6] + c[7] * z;
    (p01 + p23 * z2) + (p45 + p67 * z2) * z4
}

/// The series of [`sin_cos`] at z = r² (sin r / r - 1 over r² and (cos r - 1 + r²/2) / r⁴), by
/// Estrin's scheme: the search's probes wait on them.
#[inline(always)]
fn series(z: f64) -> (f64, f64) {
    (estrin(&SIN, z), estrin(&COS, z))
}

/// fdlibm's shorter kernels at z = r², in place of [`series`], by Horner's scheme.
#[inline(always)]
fn kernels(z: f64) -> (f64, f64) {
    (horner(&SIN_KERNEL, z), horner(&COS_KERNEL, z))
}

/// sin x alone (the same reduction and series).
#[inline]
pub fn sin(x: f64) -> f64 {
    sin_cos(x).0
}

/// ln 2 to 32 bits (k times it is exact for |k| < 2^21), and the rest of it.
const LN2_HEAD: f64 = 6.931_471_803_691_238e-1;
const LN2_TAIL: f64 = 1.908_214_929_270_587_7e-10;

/// The Taylor coefficients of (e^r - 1 - r) / r², 1/2! to 1/13!, constant first.
const EXP: [f64; 12] = [
    1.0 / 2.0,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5_040.0,
    1.0 / 40_320.0,
    1.0 / 362_880.0,
    1.0 / 3_628_800.0,
    1.0 / 39_916_800.0,
    1.0 / 479_001_600.0,
    1.0 / 6_227_020_800.0,
];

/// e^x, inlined, for the damped modes' growth e^{Re s τ} at every probe of the event search: with
/// x = k ln 2 + r and |r| <= ln 2 / 2 (ln 2 in two parts), e^r = 1 + (r + r² P(r)) by its Taylor series
/// to r^13 (the first term left out is below 5e-18 relative), scaled by 2^k through the exponent's
/// bits. Within about an ulp of libm's; |x| > 700 (beyond which 2^k leaves the normal range) and NaN go
/// to libm.
#[inline]
pub fn exp(x: f64) -> f64 {
    if x.is_nan() || x.abs() > 700.0 {
        return x.exp();
    }
    let rounded = x * std::f64::consts::LOG2_E + ROUNDER;
    let k = rounded - ROUNDER;
    let r = (x - k * LN2_HEAD) - k * LN2_TAIL;
    let p = EXP[..11]
        .iter()
        .rev()
        .fold(EXP[11], |acc, &coefficient| acc * r + coefficient);
    let scale = f64::from_bits(((k as i64 + 1023) as u64) << 52);
    (1.0 + (r + r * r * p)) * scale
}

/// sin r / r - 1 and (cos r - 1 + r²/2) / r⁴ on |r| <= π/4 as polynomials in r² (fdlibm's minimax
/// kernels, __kernel_sin and __kernel_cos: within 2^-58 of the functions there).
const SIN_KERNEL: [f64; 6] = [
    -1.666_666_666_666_663_2e-1,
    8.333_333_333_322_49e-3,
    -1.984_126_982_985_795e-4,
    2.755_731_370_707_006_8e-6,
    -2.505_076_025_340_686_3e-8,
    1.589_690_995_211_55e-10,
];
const COS_KERNEL: [f64; 6] = [
    4.166_666_666_666_66e-2,
    -1.388_888_888_887_411e-3,
    2.480_158_728_947_673e-5,
    -2.755_731_435_139_066_3e-7,
    2.087_572_321_298_175e-9,
    -1.135_964_755_778_819_5e-11,
];

/// sin and cos of every angle in `angles` into `sin` and `cos` (as many as the shortest of the three),
/// for the closed forms that need one pair per mode at every probe: the reduction of [`sin_cos`], then
/// fdlibm's degree-13 and -14 kernels in place of its longer series, and the quadrant by bit masks,
/// with no branch, two angles at a time in the lanes of a vector register (`reduced`). Within about
/// an ulp of the larger of the result and 1/4 as [`sin_cos`] is, and mostly the same bits, but not
/// always; when any angle is beyond `REDUCED` or not finite, every one goes to [`sin_cos`].
#[inline(always)]
pub fn sin_cos_each(angles: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    if !angles.iter().all(|a| a.abs() <= REDUCED) {
        for ((&a, s), c) in angles.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
            (*s, *c) = sin_cos(a);
        }
        return;
    }
    // Written out as pairs, so that vectorizing does not depend on the caller it is inlined into; an
    // odd angle last, alone (a lane's operations are the scalar ones: the same bits).
    let count = angles.len().min(sin.len()).min(cos.len());
    let pairs = count / 2 * 2;
    for at in (0..pairs).step_by(2) {
        let (s, c) = reduced([angles[at], angles[at + 1]], kernels);
        sin[at..at + 2].copy_from_slice(&s);
        cos[at..at + 2].copy_from_slice(&c);
    }
    if pairs < count {
        let ([s], [c]) = reduced([angles[pairs]], kernels);
        (sin[pairs], cos[pairs]) = (s, c);
    }
}

/// sin and cos of `L` angles side by side, lane by lane (each lane's operations are [`sin_cos`]'s
/// scalar ones: the same bits in any lane): [`sin_cos`]'s reduction, the `polynomials` at r²
/// ([`series`] or [`kernels`]: sin r / r - 1 over r² and (cos r - 1 + r²/2) / r⁴), and the quadrant
/// by bit masks rather than a branch (odd swaps sin and cos; sin is negated for q = 2, 3, cos for
/// q = 1, 2). The angles must be within `REDUCED`. [`sin_cos`] keeps its own scalar copy with the
/// quadrant by a branch: through here, one lane, it cost a chain of 8 about 570 instructions a row.
#[inline(always)]
fn reduced<const L: usize>(
    x: [f64; L],
    polynomials: impl Fn(f64) -> (f64, f64),
) -> ([f64; L], [f64; L]) {
    let rounded: [f64; L] = std::array::from_fn(|i| x[i] * FRAC_2_PI + ROUNDER);
    let k: [f64; L] = std::array::from_fn(|i| rounded[i] - ROUNDER);
    let head: [f64; L] = std::array::from_fn(|i| x[i] - k[i] * HALF_PI_HEAD);
    let tail: [f64; L] = std::array::from_fn(|i| k[i] * HALF_PI_TAIL);
    let r: [f64; L] = std::array::from_fn(|i| head[i] - tail[i]);
    let low: [f64; L] = std::array::from_fn(|i| (head[i] - r[i]) - tail[i]);
    let z: [f64; L] = std::array::from_fn(|i| r[i] * r[i]);
    let polys: [(f64, f64); L] = std::array::from_fn(|i| polynomials(z[i]));
    let sin_poly: [f64; L] = std::array::from_fn(|i| polys[i].0);
    let cos_poly: [f64; L] = std::array::from_fn(|i| polys[i].1);
    let half: [f64; L] = std::array::from_fn(|i| 0.5 * z[i]);
    let one_less: [f64; L] = std::array::from_fn(|i| 1.0 - half[i]);
    let s: [f64; L] =
        std::array::from_fn(|i| r[i] + (r[i] * z[i] * sin_poly[i] + low[i] * one_less[i]));
    let c: [f64; L] = std::array::from_fn(|i| {
        one_less[i]
            + (((1.0 - one_less[i]) - half[i]) + (z[i] * z[i] * cos_poly[i] - r[i] * low[i]))
    });
    let q: [u64; L] = std::array::from_fn(|i| rounded[i].to_bits() & 3);
    let swap: [u64; L] = std::array::from_fn(|i| 0u64.wrapping_sub(q[i] & 1));
    let (s, c) = (s.map(f64::to_bits), c.map(f64::to_bits));
    (
        std::array::from_fn(|i| {
            f64::from_bits(((c[i] & swap[i]) | (s[i] & !swap[i])) ^ ((q[i] & 2) << 62))
        }),
        std::array::from_fn(|i| {
            f64::from_bits(((s[i] & swap[i]) | (c[i] & !swap[i])) ^ (((q[i] + 1) & 2) << 62))
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform draws in [0, 1) from `seed` (xorshift), the same on every run.
    fn uniform(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A small turn lands within an ulp of the sine and cosine of the turned angle (an exact sum), turns
    /// of up to SMALL_TURN either way from angles across the contact's half turn and beyond.
    #[test]
    fn a_small_turn_is_within_an_ulp_of_the_turned_angle() {
        let mut draw = uniform(0x2545_f491_4f6c_dd1d);
        for _ in 0..100_000 {
            let a = 4.0 * draw();
            let x = a + (2.0 * draw() - 1.0) * SMALL_TURN;
            let (s, c) = turned(sin_cos(a), x - a);
            let (sin_x, cos_x) = sin_cos(x);
            assert!(
                (s - sin_x).abs() <= 2.0 * f64::EPSILON * sin_x.abs(),
                "sin {x}: {s} {sin_x}"
            );
            assert!(
                (c - cos_x).abs() <= 2.0 * f64::EPSILON * cos_x.abs(),
                "cos {x}: {c} {cos_x}"
            );
        }
    }

    /// Against the library: within a unit in the last place of the larger of the result and 1/4
    /// (about 6e-17 absolute near a zero of sin or cos), over the angles the closed forms take.
    #[test]
    fn agrees_with_the_library() {
        let mut uniform = uniform(0x2545_f491_4f6c_dd1du64);
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
    fn two_at_once_are_bit_for_bit_the_single_ones() {
        let mut uniform = uniform(0x9e37_79b9_7f4a_7c15u64);
        for span in [1e-8, 0.8, 3.2, 1e3, 1.5e6, 2e6] {
            for _ in 0..100_000 {
                let (x, y) = (
                    (2.0 * uniform() - 1.0) * span,
                    (2.0 * uniform() - 1.0) * span,
                );
                let (a, b) = sin_cos2(x, y);
                let bits = |(s, c): (f64, f64)| (s.to_bits(), c.to_bits());
                assert_eq!(bits(a), bits(sin_cos(x)), "{x}");
                assert_eq!(bits(b), bits(sin_cos(y)), "{y}");
            }
        }
        let (a, _) = sin_cos2(f64::NAN, 1.0);
        assert!(a.0.is_nan());
    }

    #[test]
    fn exact_where_it_must_be() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert_eq!(sin_cos(1e-300), (1e-300, 1.0));
        assert!(sin_cos(f64::NAN).0.is_nan());
        let (s, c) = sin_cos(1e9);
        assert_eq!((s, c), 1e9f64.sin_cos());
    }

    /// Against the library: within 2 units in the last place over the exponents the grips take, and
    /// exact where it must be.
    #[test]
    fn exp_agrees_with_the_library() {
        let mut uniform = uniform(0x2545_f491_4f6c_dd1du64);
        let mut worst: f64 = 0.0;
        for span in [1e-12, 1e-3, 0.4, 3.0, 50.0, 700.0] {
            for _ in 0..200_000 {
                let x = (2.0 * uniform() - 1.0) * span;
                let (got, want) = (exp(x), x.exp());
                worst = worst.max((got - want).abs() / (f64::EPSILON * want));
            }
        }
        assert!(worst <= 2.0, "{worst} ulp");
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-800.0), 0.0);
        assert!(exp(f64::NAN).is_nan());
        assert_eq!(exp(f64::INFINITY), f64::INFINITY);
    }

    /// An angle's sin and cos are the same bits whether it is taken in a pair's lane or alone.
    #[test]
    fn each_gives_an_angle_the_same_bits_in_a_pair_or_alone() {
        let mut uniform = uniform(0x2545_f491_4f6c_dd1du64);
        for span in [1e-8, 0.8, 3.2, 1e3, 1.5e6] {
            for _ in 0..20_000 {
                let angles: [f64; 3] = std::array::from_fn(|_| (2.0 * uniform() - 1.0) * span);
                let (mut sin, mut cos) = ([0.0; 3], [0.0; 3]);
                sin_cos_each(&angles, &mut sin, &mut cos);
                for (i, &x) in angles.iter().enumerate() {
                    let (mut alone_sin, mut alone_cos) = ([0.0], [0.0]);
                    sin_cos_each(&[x], &mut alone_sin, &mut alone_cos);
                    assert_eq!(sin[i].to_bits(), alone_sin[0].to_bits(), "{x}");
                    assert_eq!(cos[i].to_bits(), alone_cos[0].to_bits(), "{x}");
                }
            }
        }
    }

    /// Against the library: within 2 units in the last place of the larger of the result and 1/4,
    /// over the angles the closed forms take; NaN stays NaN.
    #[test]
    fn each_agrees_with_the_library() {
        let mut uniform = uniform(0x9e37_79b9_7f4a_7c15u64);
        let mut worst: f64 = 0.0;
        for span in [1e-8, 1e-3, 0.8, 3.2, 10.0, 1e3, 1e5, 1.5e6] {
            for _ in 0..20_000 {
                let angles: [f64; 9] = std::array::from_fn(|_| (2.0 * uniform() - 1.0) * span);
                let (mut sin, mut cos) = ([0.0; 9], [0.0; 9]);
                sin_cos_each(&angles, &mut sin, &mut cos);
                for (i, x) in angles.iter().enumerate() {
                    let (ls, lc) = x.sin_cos();
                    for (got, want) in [(sin[i], ls), (cos[i], lc)] {
                        let ulp = f64::EPSILON * want.abs().max(0.25);
                        worst = worst.max((got - want).abs() / ulp);
                    }
                }
            }
        }
        assert!(worst <= 2.0, "{worst} ulp");
        let (mut sin, mut cos) = ([0.0; 2], [0.0; 2]);
        sin_cos_each(&[0.0, f64::NAN], &mut sin, &mut cos);
        assert_eq!((sin[0], cos[0]), (0.0, 1.0));
        assert!(sin[1].is_nan() && cos[1].is_nan());
    }
}
