//! Event functions written once per phase as fixed combinations of sin and cos, shared by the single
//! cart on the wall (`cart/`) and on a free frame (`frame/`): a detuned slide's slip and a moving grip's
//! static friction, each with its first three derivatives (each derivative turns each oscillation a
//! quarter and scales it by its frequency), so that an evaluation of the event search is a dozen
//! products after one `sin_cos2`.

use super::setup::Setup;

/// c, c r, c r², c r³.
pub fn rates(c: f64, r: f64) -> [f64; 4] {
    [c, c * r, c * r * r, c * r * r * r]
}

/// The oscillating terms of a detuned slide's slip event, -(P/w) cos w t + B cos Ωτ - Q sin Ωτ: the
/// ball's impulse and the cart's forced response at the normal force's angle w t, the cart's free swing
/// at Ωτ.
#[derive(Clone, Copy, Debug)]
pub struct SlipTerms {
    sin_wt0: f64,
    cos_wt0: f64,
    /// P/w, P, P w, P w².
    ball: [f64; 4],
    /// B, B Ω, B Ω², B Ω³.
    free_cos: [f64; 4],
    /// Q, Q Ω, Q Ω², Q Ω³.
    free_sin: [f64; 4],
}

impl SlipTerms {
    /// The terms for P = `ball`, B = `free_cos` and Q = `free_sin`, from sin and cos of w t0 at the
    /// phase's start.
    pub fn new(
        (sin_wt0, cos_wt0): (f64, f64),
        (w, omega): (f64, f64),
        [ball, free_cos, free_sin]: [f64; 3],
    ) -> Self {
        SlipTerms {
            sin_wt0,
            cos_wt0,
            ball: rates(ball / w, w),
            free_cos: rates(free_cos, omega),
            free_sin: rates(free_sin, omega),
        }
    }

    /// Bounds on the event's second and fourth derivatives over any time, |p2| + |(b2, q2)| and
    /// |p3| w + |(b3, q3)| Ω (each oscillation's amplitude times its frequency squared, and to the
    /// fourth), with room for rounding: for a search that proves intervals empty by them.
    pub fn bounds(&self, w: f64, omega: f64) -> [f64; 2] {
        let (p, b, q) = (&self.ball, &self.free_cos, &self.free_sin);
        let curvature = p[2].abs() + b[2].hypot(q[2]);
        let fourth = p[3].abs() * w + b[3].hypot(q[3]) * omega;
        [curvature, fourth].map(|bound| bound * (1.0 + 1e-9))
    }

    /// The event and its first three derivatives, given sin and cos of w τ and of Ωτ, the event's
    /// value at the phase's start (`start`, taken there exactly) and its constant term.
    #[inline(always)]
    pub fn event(
        &self,
        (sin_w_tau, cos_w_tau): (f64, f64),
        (s, c): (f64, f64),
        (start, constant): (f64, f64),
    ) -> (f64, f64, f64, f64) {
        let sin_wt = self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau;
        let cos_wt = self.cos_wt0 * cos_w_tau - self.sin_wt0 * sin_w_tau;
        let (p, b, q) = (&self.ball, &self.free_cos, &self.free_sin);
        // sin w τ is 0 only at τ = 0 (w τ <= pi in contact).
        let value = if sin_w_tau == 0.0 {
            start
        } else {
            constant - p[0] * cos_wt + b[0] * c - q[0] * s
        };
        (
            value,
            p[1] * sin_wt - b[1] * s - q[1] * c,
            p[2] * cos_wt - b[2] * c + q[2] * s,
            -p[3] * sin_wt + b[3] * s + q[3] * c,
        )
    }
}

/// The static friction of a grip whose cart moves on a spring without string friction, F_s = g X with
/// g = k m_eff / (M + m_eff) (Eq. (5); on a frame X is the stretch and M the cart's mass) and
/// X = X0 cos Ωτ + (V0/Ω) sin Ωτ (Eq. (6)), as fixed combinations of sin and cos of Ωτ.
#[derive(Clone, Copy, Debug)]
pub struct ForceSums {
    x0: f64,
    /// V0/Ω.
    swing: f64,
    /// A bound on the margins' second derivative over the whole phase, g Ω² sqrt(X0² + (V0/Ω)²) +
    /// mu N0 w² (with room for rounding): |F_s''| = g Ω² |X| and (mu N)'' = -w² mu N.
    pub curvature: f64,
    /// A bound on the margins' fourth derivative, g Ω⁴ sqrt(X0² + (V0/Ω)²) + mu N0 w⁴ (with room for
    /// rounding).
    pub fourth: f64,
    /// g, g Ω, g Ω², g Ω³.
    gains: [f64; 4],
}

impl ForceSums {
    /// The sums of a grip of gain `gain` swinging at `omega` from `x0` with rate `v0`.
    pub fn new(setup: &Setup, gain: f64, omega: f64, (x0, v0): (f64, f64)) -> Self {
        let swing = v0 / omega;
        let w2 = setup.w * setup.w;
        let amplitude = (x0 * x0 + swing * swing).sqrt();
        let fourth = gain * omega.powi(4) * amplitude + setup.peak_friction() * w2 * w2;
        let curvature = gain * omega * omega * amplitude + setup.peak_friction() * w2;
        ForceSums {
            x0,
            swing,
            curvature: curvature * (1.0 + 1e-9),
            fourth: fourth * (1.0 + 1e-9),
            gains: rates(gain, omega),
        }
    }

    /// How far the grip is from breaking forward and backward, sign F_s - mu N for sign = +1 and -1,
    /// each with its first three derivatives, given sin and cos of Ωτ and of w t.
    #[inline(always)]
    pub fn margins(
        &self,
        setup: &Setup,
        ((s, c), normal): ((f64, f64), (f64, f64)),
    ) -> [(f64, f64, f64, f64); 2] {
        let x = self.x0 * c + self.swing * s;
        let rate = self.swing * c - self.x0 * s;
        let g = &self.gains;
        setup
            .grip_margins_with_derivatives(normal, [g[0] * x, g[1] * rate, -g[2] * x, -g[3] * rate])
    }
}
