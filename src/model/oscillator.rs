//! Closed-form pieces of the harmonic oscillator `X'' + Ω² X = f(t)`, written so that they stay exact
//! for a free cart (Ω = 0) and at resonance with the normal force (Ω = π/T), where the textbook formulas
//! divide by zero.

use super::trig::{sin, sin_cos};

/// sin(x)/x, with its Taylor series near 0.
#[inline]
pub fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        sin(x) / x
    }
}

/// The free oscillator's state after `tau`: `X = X0 cos Ωτ + V0 sin(Ωτ)/Ω`, `V = X'` (for Ω = 0,
/// `X = X0 + V0 τ`).
#[inline]
pub fn free(x0: f64, v0: f64, omega: f64, tau: f64) -> (f64, f64) {
    let (s, c) = sin_cos(omega * tau);
    free_given(x0, v0, omega, tau, s, c)
}

/// [`free`] with sin(Ωτ) and cos(Ωτ) already at hand.
#[inline]
pub fn free_given(x0: f64, v0: f64, omega: f64, tau: f64, s: f64, c: f64) -> (f64, f64) {
    let x = x0 * c + v0 * sin_over(s, omega, tau);
    let v = -x0 * omega * s + v0 * c;
    (x, v)
}

/// What the forcing sin(w t), switched on at t0, adds at t0 + τ to a free oscillator, per unit of the
/// particular solution's amplitude A = 1/(Ω² - w²): sin(w t) less its free continuation from t0, and its
/// rate. Cheaper than [`forced`] (no further trig given the sines and cosines of w t0, w τ and Ωτ), but
/// scaled by A it cancels badly near resonance, where [`forced`] is the form to use.
#[inline]
pub fn detuned(
    omega: f64,
    w: f64,
    tau: f64,
    (sin_wt0, cos_wt0): (f64, f64),
    (sin_w_tau, cos_w_tau): (f64, f64),
    (s, c): (f64, f64),
) -> (f64, f64) {
    let cos_diff = cos_w_tau - c;
    let x = sin_wt0 * cos_diff + cos_wt0 * (sin_w_tau - w * sin_over(s, omega, tau));
    let v = w * cos_wt0 * cos_diff - sin_wt0 * (w * sin_w_tau - omega * s);
    (x, v)
}

/// The response to a unit constant force per unit mass switched on at τ = 0, from rest:
/// `X = (1 - cos Ωτ)/Ω²`, `V = sin(Ωτ)/Ω` (τ²/2 and τ at Ω = 0), given sin(Ωτ) and cos(Ωτ).
/// 1 - cos is written as sin²/(1 + cos) where that avoids cancellation.
#[inline]
pub fn step(sin_omega_tau: f64, cos_omega_tau: f64, omega: f64, tau: f64) -> (f64, f64) {
    if omega == 0.0 {
        return (0.5 * tau * tau, tau);
    }
    let (s, c) = (sin_omega_tau, cos_omega_tau);
    let one_minus_cos = if c > 0.0 { s * s / (1.0 + c) } else { 1.0 - c };
    (one_minus_cos / (omega * omega), s / omega)
}

/// sin(Ωτ)/Ω from `sin_omega_tau` = sin(Ωτ), with its limit τ at Ω = 0.
#[inline]
pub fn sin_over(sin_omega_tau: f64, omega: f64, tau: f64) -> f64 {
    if omega > 0.0 {
        sin_omega_tau / omega
    } else {
        tau
    }
}

/// Response to the forcing `sin(w t)` switched on at `t0`, zero state at `t0`:
/// `G(t) = ∫_{t0}^{t} sin(Ω(t-u))/Ω · sin(w u) du` and its time derivative, at `t = t0 + tau`.
///
/// `sin_wt0` and `cos_wt0` are sin(w t0) and cos(w t0). Derived from the particular solution
/// `sin(w t)/(Ω² - w²)` with the two differences of sines and cosines rewritten as products with
/// sinc((w-Ω)τ/2) and sinc(Ωτ), which have no singularity at Ω = w or Ω = 0.
#[inline]
pub fn forced(omega: f64, w: f64, sin_wt0: f64, cos_wt0: f64, tau: f64) -> (f64, f64) {
    let sum = w + omega;
    let half = 0.5 * sum * tau;
    let (sin_half, cos_half) = sin_cos(half);
    let beat = sinc(0.5 * (w - omega) * tau);
    let sin_omega_tau = sin(omega * tau);
    let g =
        tau / sum * (sin_wt0 * sin_half * beat + cos_wt0 * (sinc(omega * tau) - cos_half * beat));
    let dg = (w * cos_wt0 * tau * sin_half * beat
        + sin_wt0 * (w * tau * cos_half * beat + sin_omega_tau))
        / sum;
    (g, dg)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// G by the textbook formula, valid away from Ω = 0 and Ω = w.
    fn textbook(omega: f64, w: f64, t0: f64, t: f64) -> (f64, f64) {
        let a = 1.0 / (omega * omega - w * w);
        let tau = t - t0;
        let g = a
            * ((w * t).sin()
                - (w * t0).sin() * (omega * tau).cos()
                - w * (w * t0).cos() * (omega * tau).sin() / omega);
        let dg = a
            * (w * (w * t).cos() + omega * (w * t0).sin() * (omega * tau).sin()
                - w * (w * t0).cos() * (omega * tau).cos());
        (g, dg)
    }

    #[test]
    fn matches_textbook_away_from_singularities() {
        let w = std::f64::consts::PI / 5e-3;
        for &omega in &[50.0, 300.0, 1224.7, 5000.0, 60000.0] {
            for &(t0, t) in &[(0.0, 2e-3), (1.3e-3, 4.4e-3), (4.0e-3, 5e-3)] {
                let (g, dg) = forced(omega, w, (w * t0).sin(), (w * t0).cos(), t - t0);
                let (ge, dge) = textbook(omega, w, t0, t);
                let scale = 1.0 / (omega * omega - w * w).abs();
                assert!((g - ge).abs() < 1e-10 * scale, "G Ω={omega} {g} {ge}");
                assert!(
                    (dg - dge).abs() < 1e-10 * scale * w,
                    "G' Ω={omega} {dg} {dge}"
                );
            }
        }
    }

    #[test]
    fn free_cart_limit() {
        // Ω = 0: G = ∫ (t-u) sin(w u) du from 0 = t/w - sin(w t)/w²; G' = (1 - cos w t)/w.
        let w = 628.3;
        let t = 3e-3;
        let (g, dg) = forced(0.0, w, 0.0, 1.0, t);
        assert!((g - (t / w - (w * t).sin() / (w * w))).abs() < 1e-15);
        assert!((dg - (1.0 - (w * t).cos()) / w).abs() < 1e-15);
    }

    #[test]
    fn step_response() {
        // X'' + Ω² X = 1 from rest.
        for omega in [0.0f64, 1e-3, 10.0, 3000.0] {
            let tau: f64 = 2e-3;
            let (s, c) = (omega * tau).sin_cos();
            let (x, v) = step(s, c, omega, tau);
            let exact_x = if omega == 0.0 {
                tau * tau / 2.0
            } else {
                2.0 * (omega * tau / 2.0).sin().powi(2) / (omega * omega)
            };
            assert!(
                (x - exact_x).abs() <= 1e-15 * exact_x,
                "{omega}: {x} {exact_x}"
            );
            assert!((v - tau * sinc(omega * tau)).abs() <= 1e-15 * tau);
        }
    }

    #[test]
    fn resonance_limit() {
        // Ω = w: G = (sin w t - w t cos w t)/(2 w²) from t0 = 0.
        let w = 628.3;
        let t = 4e-3;
        let (g, dg) = forced(w, w, 0.0, 1.0, t);
        let exact = ((w * t).sin() - w * t * (w * t).cos()) / (2.0 * w * w);
        assert!((g - exact).abs() < 1e-15, "{g} {exact}");
        let exact_dg = t * (w * t).sin() / 2.0;
        assert!((dg - exact_dg).abs() < 1e-15, "{dg} {exact_dg}");
        // Continuous through resonance.
        let (g_near, _) = forced(w * (1.0 + 1e-9), w, 0.0, 1.0, t);
        assert!((g_near - g).abs() < 1e-12);
    }
}
