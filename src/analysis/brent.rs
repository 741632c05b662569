//! One-dimensional minimisation by Brent's method: golden-section steps, parabolic steps where the
//! function allows them (R. P. Brent, *Algorithms for Minimization without Derivatives*, 1973, ch. 5).

/// (3 - sqrt 5)/2, the golden-section fraction.
const GOLDEN: f64 = 0.381_966_011_250_105_1;

/// A local minimum of `f` on `[a, b]`, searched from `start` (inside the interval), to a relative
/// tolerance `rel_tol` in x. Returns `(x, f(x))` with `f(x) <= f(start)`. `f` must not return NaN.
pub fn minimize(f: impl Fn(f64) -> f64, a: f64, b: f64, start: f64, rel_tol: f64) -> (f64, f64) {
    let (mut a, mut b) = if a <= b { (a, b) } else { (b, a) };
    let abs_tol = 1e-3 * rel_tol * (b - a) + f64::MIN_POSITIVE;
    let mut x = start.clamp(a, b);
    let mut fx = f(x);
    let (mut w, mut fw, mut v, mut fv) = (x, fx, x, fx);
    // d: the last step; e: the step before it, which a parabolic step must beat by half.
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        let tol = rel_tol * x.abs() + abs_tol;
        if (x - m).abs() <= 2.0 * tol - 0.5 * (b - a) {
            break;
        }
        let mut parabolic = false;
        if e.abs() > tol {
            // The vertex of the parabola through (x, fx), (w, fw), (v, fv), as x + p/q.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            if p.abs() < (0.5 * q * e).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < 2.0 * tol || b - u < 2.0 * tol {
                    d = tol.copysign(m - x);
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x >= m { a - x } else { b - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let fu = f(u);
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, fx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_smooth_and_kinked_minima() {
        let (x, fx) = minimize(|x| (x - 1.234567).powi(2) + 2.0, 0.0, 5.0, 2.5, 1e-10);
        assert!((x - 1.234567).abs() < 1e-8, "{x}");
        assert!((fx - 2.0).abs() < 1e-14);
        let (x, _) = minimize(|x| (x - 0.3).abs(), -1.0, 1.0, 0.9, 1e-12);
        assert!((x - 0.3).abs() < 1e-10, "{x}");
    }

    #[test]
    fn never_worse_than_the_start() {
        let f = |x: f64| (3.0 * x).sin();
        let (_, fx) = minimize(f, 0.0, 3.0, 1.6, 1e-10);
        assert!(fx <= f(1.6));
    }
}
