//! The free frame's event functions written once per phase, where the cart moves relative to the frame
//! on a spring without string friction: a detuned slide's slip and a grip's margins as fixed combinations
//! of sin and cos of the stretch's angle Ωτ and of the normal force's, each with its first three
//! derivatives (each derivative turns each oscillation a quarter and scales it by its frequency), so
//! that an evaluation of the event search is a dozen products after one `sin_cos2` and the state is
//! computed only where the search ends. The frame's rigid-body mode enters through the momentum P, which
//! only the ball's impulse changes: its terms are those of the impulse, with tau and 1 for its sine and
//! cosine. (The clamped single cart's sums, `cart/slide.rs` and `cart/grip.rs`, are the limit M_t -> ∞.)

use super::super::setup::Setup;
use super::FrameMotion;

/// sin and cos of Ωτ (τ the time since the phase began), and of the normal force's angle: w τ sliding,
/// w t gripping.
pub type Angles = ((f64, f64), (f64, f64));

/// The slip event of a detuned slide on the free frame. With B = M + M_t, the cart's velocity is
/// V = (P + M_t y')/B (see [`FrameMotion`]), the momentum P = P0 + J with the ball's impulse
/// J = F0 (cos w t0 - cos w t)/w, and the stretch's rate y' = A w cos w t + b cos Ωτ - a Ω sin Ωτ with
/// a = y0 - A sin w t0, b = y0' - A w cos w t0 (the particular and free responses). The ball's contact
/// point slips at u' = u0' - J/m_eff, so the slip u' - V is, with R = 1/m_eff + 1/B,
/// u0' - P0/B - F0 R cos(w t0)/w + (F0 R/w - (M_t/B) A w) cos w t - (M_t/B) (b cos Ωτ - a Ω sin Ωτ),
/// and the event -dir (slip - offset) is its constant less (P/w) cos w t + B' cos Ωτ - Q sin Ωτ, with
/// P = dir (F0 R - (M_t/B) A w²), B' = dir (M_t/B) b, Q = dir (M_t/B) a Ω.
#[derive(Clone, Copy, Debug)]
pub struct SlipSums {
    /// The event at the phase's start, exactly dir (offset - slip0), so that rounding cannot fake a
    /// crossing there when the offset is the start's slip.
    start: f64,
    /// Its constant term, dir (offset - u0' + P0/B) + dir F0 R cos(w t0)/w.
    constant: f64,
    sin_wt0: f64,
    cos_wt0: f64,
    /// P/w, P, P w, P w².
    ball: [f64; 4],
    /// B', B' Ω, B' Ω², B' Ω³.
    free_cos: [f64; 4],
    /// Q, Q Ω, Q Ω², Q Ω³.
    free_sin: [f64; 4],
}

/// c, c r, c r², c r³.
fn rates(c: f64, r: f64) -> [f64; 4] {
    [c, c * r, c * r * r, c * r * r * r]
}

impl SlipSums {
    /// The sums of `motion`, a slide with the event measured from `offset`, where its cart moves on a
    /// spring without string friction and its response is detuned (else `None`).
    pub fn new(motion: &FrameMotion, setup: &Setup, offset: f64) -> Option<Self> {
        let amplitude = motion.amplitude?;
        let (w, omega, dir) = (setup.w, motion.omega, motion.dir);
        if motion.held || motion.string != 0.0 || omega == 0.0 || dir == 0.0 {
            return None;
        }
        let s0 = &motion.start.s;
        let body = motion.cart + motion.frame;
        let share = motion.frame / body;
        let force_amplitude = dir * setup.peak_friction();
        let inverse = 1.0 / setup.m_eff + 1.0 / body;
        let (y0, dy0) = (s0.x, s0.v - motion.start.vf);
        let ball = dir * (force_amplitude * inverse - share * amplitude * w * w);
        let free_cos = dir * share * (dy0 - amplitude * w * motion.cos_wt0);
        let free_sin = dir * share * (y0 - amplitude * motion.sin_wt0) * omega;
        let contact = s0.vx - setup.r * s0.omega;
        Some(SlipSums {
            start: dir * (offset - setup.slip(s0)),
            constant: dir * (offset - contact + motion.p0 / body)
                + dir * force_amplitude * inverse * motion.cos_wt0 / w,
            sin_wt0: motion.sin_wt0,
            cos_wt0: motion.cos_wt0,
            ball: rates(ball / w, w),
            free_cos: rates(free_cos, omega),
            free_sin: rates(free_sin, omega),
        })
    }

    /// The event -dir (slip - offset) and its first three derivatives, given the slide's `Angles`.
    #[inline(always)]
    pub fn event(&self, ((s, c), (sin_w_tau, cos_w_tau)): Angles) -> (f64, f64, f64, f64) {
        let sin_wt = self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau;
        let cos_wt = self.cos_wt0 * cos_w_tau - self.sin_wt0 * sin_w_tau;
        let (p, b, q) = (&self.ball, &self.free_cos, &self.free_sin);
        // sin w τ is 0 only at τ = 0 (w τ <= pi in contact).
        let value = if sin_w_tau == 0.0 {
            self.start
        } else {
            self.constant - p[0] * cos_wt + b[0] * c - q[0] * s
        };
        (
            value,
            p[1] * sin_wt - b[1] * s - q[1] * c,
            p[2] * cos_wt - b[2] * c + q[2] * s,
            -p[3] * sin_wt + b[3] * s + q[3] * c,
        )
    }
}

/// The static friction of a grip on the free frame whose cart moves on a spring without string
/// friction, F_s = g y with g = k m_eff/(M + m_eff) (Eq. (5) with the stretch y for X) and
/// y = y0 cos Ωτ + (y0'/Ω) sin Ωτ, Ω = Ω_g, as fixed combinations of sin and cos of Ωτ.
#[derive(Clone, Copy, Debug)]
pub struct ForceSums {
    y0: f64,
    /// y0'/Ω.
    swing: f64,
    /// g, g Ω, g Ω², g Ω³.
    gains: [f64; 4],
}

impl ForceSums {
    /// The sums of `motion`, a grip, where its cart moves on a spring without string friction (else
    /// `None`).
    pub fn new(motion: &FrameMotion, setup: &Setup) -> Option<Self> {
        let omega = motion.omega;
        if motion.held || motion.string != 0.0 || omega == 0.0 || motion.dir != 0.0 {
            return None;
        }
        let s0 = &motion.start.s;
        let gain = setup.m_eff * setup.k / motion.cart;
        Some(ForceSums {
            y0: s0.x,
            swing: (s0.v - motion.start.vf) / omega,
            gains: rates(gain, omega),
        })
    }

    /// How far the grip is from breaking forward and backward, sign F_s - mu N for sign = +1 and -1,
    /// each with its first three derivatives, given the grip's `Angles`; mu N's second and third
    /// derivatives are -w² times its value and rate.
    #[inline(always)]
    pub fn margins(&self, setup: &Setup, ((s, c), normal): Angles) -> [(f64, f64, f64, f64); 2] {
        let y = self.y0 * c + self.swing * s;
        let rate = self.swing * c - self.y0 * s;
        let g = &self.gains;
        let (force, force_rate) = (g[0] * y, g[1] * rate);
        let (second, third) = (-g[2] * y, -g[3] * rate);
        let [(forward, forward_rate), (backward, backward_rate)] =
            setup.grip_margins_given(normal, force, force_rate);
        let w2 = setup.w * setup.w;
        let limit = setup.peak_friction() * normal.0.max(0.0);
        let limit_rate = setup.peak_friction() * setup.w * normal.1;
        [
            (
                forward,
                forward_rate,
                second + w2 * limit,
                third + w2 * limit_rate,
            ),
            (
                backward,
                backward_rate,
                w2 * limit - second,
                w2 * limit_rate - third,
            ),
        ]
    }
}
