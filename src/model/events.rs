//! Locating the transitions between phases: the first time an exact event function rises above zero.

/// The first time in `(t0, t1]` at which `f` rises above zero, or `None`.
///
/// `f` returns the event function and its time derivative, and is at most zero at `t0`. A phase that
/// starts on its own boundary (`from_boundary`: a slide that begins where a grip broke or the friction
/// reversed) reads zero there up to rounding; that crossing is not taken again, and the first interval
/// is not searched for a peak, since the start itself is one. The interval is sampled every
/// `step` or less; `step` must be short enough that between two samples the function has at most one
/// extremum, and a maximum that pokes above zero between two negative samples is found from the sign
/// change of the derivative, so a short phase is never skipped. The crossing is refined by safeguarded
/// Newton iteration to the resolution of `f64`.
pub fn first_rise(
    f: impl Fn(f64) -> (f64, f64),
    t0: f64,
    t1: f64,
    step: f64,
    from_boundary: bool,
) -> Option<f64> {
    if t1 <= t0 {
        return None;
    }
    let intervals = ((t1 - t0) / step).ceil().max(1.0) as usize;
    let h = (t1 - t0) / intervals as f64;
    let mut a = t0;
    let mut rate_a = f(t0).1;
    let mut skip_peak = from_boundary;
    for i in 1..=intervals {
        let b = if i == intervals {
            t1
        } else {
            t0 + i as f64 * h
        };
        let (fb, rate_b) = f(b);
        if fb > 0.0 {
            return Some(refine(&f, a, b));
        }
        if rate_a > 0.0 && rate_b < 0.0 && !skip_peak {
            let (peak, f_peak) = peak(&f, a, b);
            if f_peak > 0.0 {
                return Some(refine(&f, a, peak));
            }
        }
        a = b;
        rate_a = rate_b;
        skip_peak = false;
    }
    None
}

/// The crossing in `[a, b]`, where `f(a) <= 0 < f(b)`.
fn refine(f: &impl Fn(f64) -> (f64, f64), mut a: f64, mut b: f64) -> f64 {
    let mut t = 0.5 * (a + b);
    for _ in 0..200 {
        let (value, rate) = f(t);
        if value > 0.0 {
            b = t;
        } else {
            a = t;
        }
        let newton = t - value / rate;
        let next = if rate != 0.0 && newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        if (next - t).abs() <= f64::EPSILON * t.abs().max(1e-12) || b - a <= f64::EPSILON * b.abs()
        {
            return next;
        }
        t = next;
    }
    t
}

/// The highest point of `f` in `(a, b)`, where the derivative falls from positive to negative: regula
/// falsi (Illinois) on the derivative, stopping early once `f` is above zero.
fn peak(f: &impl Fn(f64) -> (f64, f64), mut a: f64, mut b: f64) -> (f64, f64) {
    let (mut rate_a, mut rate_b) = (f(a).1, f(b).1);
    let mut side = 0;
    let mut best = (0.5 * (a + b), f64::NEG_INFINITY);
    for _ in 0..100 {
        let t = (a * rate_b - b * rate_a) / (rate_b - rate_a);
        let t = if t > a && t < b { t } else { 0.5 * (a + b) };
        let (value, rate) = f(t);
        if value > best.1 {
            best = (t, value);
        }
        if value > 0.0 || b - a <= 4.0 * f64::EPSILON * b.abs() {
            break;
        }
        if rate > 0.0 {
            a = t;
            rate_a = rate;
            if side == 1 {
                rate_b *= 0.5;
            }
            side = 1;
        } else {
            b = t;
            rate_b = rate;
            if side == -1 {
                rate_a *= 0.5;
            }
            side = -1;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_plain_crossing() {
        let t = first_rise(|t| (t - 0.3, 1.0), 0.0, 1.0, 0.1, false).unwrap();
        assert!((t - 0.3).abs() < 1e-15);
    }

    #[test]
    fn finds_a_bump_between_two_negative_samples() {
        // A narrow bump above zero between samples at 0.4 and 0.5.
        let f = |t: f64| (0.01 - (t - 0.45) * (t - 0.45), -2.0 * (t - 0.45));
        let t = first_rise(f, 0.0, 1.0, 0.1, false).unwrap();
        assert!((t - 0.35).abs() < 1e-12, "{t}");
    }

    #[test]
    fn ignores_a_start_on_the_boundary() {
        // Starts at zero and falls: no event at t0, and a later crossing is found.
        let f = |t: f64| ((t - 0.5) * (t - 0.5) - 0.25 + 1e-17, 2.0 * (t - 0.5));
        let t = first_rise(f, 0.0, 2.0, 0.1, true).unwrap();
        assert!((t - 1.0).abs() < 1e-12, "{t}");
    }

    #[test]
    fn none_when_it_stays_below() {
        assert_eq!(first_rise(|t| (-1.0 - t, -1.0), 0.0, 1.0, 0.1, false), None);
        assert_eq!(
            first_rise(|t| (-(t * 10.0).sin().abs(), 0.0), 0.0, 1.0, 0.01, true),
            None
        );
    }
}
