//! The grip phase, Eqs. (4)-(6): the contact point moves with the cart, held by static friction.

use super::oscillator::free;
use super::setup::{Setup, State};

/// A grip phase from `start`.
#[derive(Clone, Copy, Debug)]
pub struct Grip {
    pub start: State,
}

impl Grip {
    /// The static friction on the ball, Eq. (5): F_s = k m_eff X / (M + m_eff), positive backward.
    #[inline]
    pub fn friction(setup: &Setup, x: f64) -> f64 {
        setup.grip_gain * x
    }

    /// The state at `t`. The cart is a free oscillator of mass M + m alpha/(1+alpha), Eq. (6). Since
    /// F_s = -m_eff dV/dt, the impulse on the ball is -m_eff (V - V0), which gives v_x and omega.
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> State {
        let s0 = &self.start;
        let (x, v) = free(s0.x, s0.v, setup.omega_grip, t - s0.t);
        let impulse = -setup.m_eff * (v - s0.v);
        State {
            t,
            vx: s0.vx - impulse / setup.m,
            omega: s0.omega + impulse * setup.r / setup.inertia,
            x,
            v,
        }
    }

    /// How far the grip is from breaking forward and backward: sign F_s - mu N for sign = +1 and -1,
    /// each with its rate. The grip breaks when either rises above zero.
    #[inline]
    pub fn margins(setup: &Setup, s: &State) -> [(f64, f64); 2] {
        let (sin_wt, cos_wt) = (setup.w * s.t).sin_cos();
        let limit = setup.mu * setup.n0 * sin_wt.max(0.0);
        let limit_rate = setup.mu * setup.n0 * setup.w * cos_wt;
        let (force, force_rate) = (setup.grip_gain * s.x, setup.grip_gain * s.v);
        [
            (force - limit, force_rate - limit_rate),
            (-force - limit, -force_rate - limit_rate),
        ]
    }

    /// A bound on the second derivative of either margin over the phase: F_s is k m_eff/(M + m_eff)
    /// times a free oscillation of known amplitude, and mu N a sine of amplitude mu N0.
    pub fn margin_curvature(&self, setup: &Setup) -> f64 {
        let (x0, v0, omega) = (self.start.x, self.start.v, setup.omega_grip);
        let x_accel = omega * (omega * omega * x0 * x0 + v0 * v0).sqrt();
        setup.grip_gain * x_accel + setup.mu * setup.n0 * setup.w * setup.w
    }
}
