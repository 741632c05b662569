//! The grip phase, Eqs. (4)-(6): the contact point moves with the cart, held by static friction.

use super::super::contact::Cart;
use super::super::oscillator::{free_given, step};
use super::super::setup::{Setup, State};
use super::super::sums::ForceSums;
use super::super::trig::{sin_cos, sin_cos2};

/// sin and cos of Ωτ, τ the time since the phase began, and of w t.
pub type Angles = ((f64, f64), (f64, f64));

/// A grip phase from `start`.
#[derive(Clone, Copy, Debug)]
pub struct Grip {
    pub start: State,
    pub cart: Cart,
}

impl Grip {
    /// The cart's string friction over the gripped system's mass, -dir F_c / (M + m_eff).
    fn push(&self, setup: &Setup) -> f64 {
        self.cart.friction(setup) / (setup.cart_mass + setup.m_eff)
    }

    /// The static friction on the ball, positive backward. Eq. (5) with the cart moving: since
    /// F_s = -m_eff dV/dt and (M + m_eff) dV/dt = -k X - dir F_c, F_s = m_eff (k X + dir F_c)/(M + m_eff)
    /// (the paper's k m_eff X / (M + m_eff) when F_c = 0). With the cart stuck the ball rolls on a still
    /// surface and needs none.
    #[inline]
    pub fn friction(&self, setup: &Setup, x: f64) -> f64 {
        match self.cart {
            Cart::Stuck => 0.0,
            Cart::Moving(_) => setup.grip_gain * x - setup.m_eff * self.push(setup),
        }
    }

    /// The state at `t`. The cart is a free oscillator of mass M + m alpha/(1+alpha), Eq. (6), driven by
    /// the constant string friction while it moves. Since F_s = -m_eff dV/dt, the impulse on the ball
    /// is -m_eff (V - V0), which gives v_x and omega.
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> State {
        let (omega, tau) = (setup.omega_grip, t - self.start.t);
        self.at_given(setup, t, sin_cos(omega * tau))
    }

    /// The state at `t` and how far the grip is from breaking forward and backward there: sign F_s - mu N
    /// for sign = +1 and -1, each with its first three derivatives (the grip breaks when either
    /// rises above zero). The cart's angle and the normal force's are computed together.
    #[inline(always)]
    pub fn evaluate(&self, setup: &Setup, t: f64) -> (State, [(f64, f64, f64, f64); 2]) {
        let angles = self.angles(setup, t);
        let s = self.state_given(setup, t, angles);
        // F_s = k m_eff X / (M + m_eff) + const (0 on a stuck cart), so F_s'' and F_s''' follow X'' and
        // X'''.
        let [accel, jerk, _] = self.cart_derivatives(setup, &s);
        let force = [
            self.friction(setup, s.x),
            self.force_rate(setup, &s),
            setup.grip_gain * accel,
            setup.grip_gain * jerk,
        ];
        (s, setup.grip_margins_with_derivatives(angles.1, force))
    }

    /// sin and cos of Ωτ and of w t at `t`, τ = t - t0, computed together. At the phase's start, where
    /// the event search begins, the cart's angle is 0 (sin_cos2 gives exactly (0, 1) there, and its
    /// other lane is sin_cos's).
    #[inline(always)]
    pub fn angles(&self, setup: &Setup, t: f64) -> Angles {
        let tau = t - self.start.t;
        if tau == 0.0 {
            ((0.0, 1.0), sin_cos(setup.w * t))
        } else {
            sin_cos2(setup.omega_grip * tau, setup.w * t)
        }
    }

    /// The state at `t` from the `Angles` there; at the phase's start the closed form gives the start
    /// state itself.
    #[inline(always)]
    pub fn state_given(&self, setup: &Setup, t: f64, (cart, _): Angles) -> State {
        if t == self.start.t {
            State { t, ..self.start }
        } else {
            self.at_given(setup, t, cart)
        }
    }

    /// The static friction written once for the phase, where the cart moves on a spring without string
    /// friction (else `None`).
    pub fn force_sums(&self, setup: &Setup) -> Option<ForceSums> {
        let omega = setup.omega_grip;
        if self.cart == Cart::Stuck || self.push(setup) != 0.0 || omega == 0.0 {
            return None;
        }
        let start = (self.start.x, self.start.v);
        Some(ForceSums::new(setup, setup.grip_gain, omega, start))
    }

    /// [`Grip::at`] with sin(Ωτ) and cos(Ωτ) at hand.
    #[inline]
    fn at_given(&self, setup: &Setup, t: f64, (s, c): (f64, f64)) -> State {
        let s0 = &self.start;
        if self.cart == Cart::Stuck {
            return State { t, ..*s0 };
        }
        let (omega, tau) = (setup.omega_grip, t - s0.t);
        let (mut x, mut v) = free_given(s0.x, s0.v, omega, tau, s, c);
        let push = self.push(setup);
        if push != 0.0 {
            let (x_push, v_push) = step(s, c, omega, tau);
            x += push * x_push;
            v += push * v_push;
        }
        let impulse = -setup.m_eff * (v - s0.v);
        State {
            t,
            vx: s0.vx - impulse / setup.m,
            omega: s0.omega + impulse * setup.r / setup.inertia,
            x,
            v,
        }
    }

    /// The cart's acceleration, -(k X + dir F_c)/(M + m_eff), or 0 when stuck.
    #[inline]
    pub fn cart_acceleration(&self, setup: &Setup, s: &State) -> f64 {
        match self.cart {
            Cart::Stuck => 0.0,
            Cart::Moving(_) => -setup.k * s.x / (setup.cart_mass + setup.m_eff) + self.push(setup),
        }
    }

    /// The cart's V', V'' = -k V / (M + m_eff) and V''' = -k V' / (M + m_eff), or 0 when stuck.
    #[inline]
    pub fn cart_derivatives(&self, setup: &Setup, s: &State) -> [f64; 3] {
        match self.cart {
            Cart::Stuck => [0.0; 3],
            Cart::Moving(_) => {
                let accel = self.cart_acceleration(setup, s);
                let gain = -setup.k / (setup.cart_mass + setup.m_eff);
                [accel, gain * s.v, gain * accel]
            }
        }
    }

    /// The rate of the static friction, k m_eff V / (M + m_eff) (0 on a stuck cart).
    #[inline]
    fn force_rate(&self, setup: &Setup, s: &State) -> f64 {
        if self.cart == Cart::Stuck {
            0.0
        } else {
            setup.grip_gain * s.v
        }
    }

    /// The size of the terms the cart's velocity is computed from, for the rounding floor of its event.
    pub fn cart_speed_scale(&self, setup: &Setup) -> f64 {
        let s0 = &self.start;
        s0.v.abs()
            + s0.x.abs() * setup.omega_grip
            + self.push(setup).abs() * (setup.duration - s0.t)
    }

    /// Bounds over the phase on the second derivatives of its event functions: the margins, and the
    /// cart's velocity. The cart swings about its equilibrium X_e = -dir F_c / k with a known
    /// amplitude A, so |X''| <= Ω² A and |V''| <= Ω³ A; mu N is a sine of amplitude mu N0.
    pub fn curvature(&self, setup: &Setup) -> (f64, f64) {
        let normal = setup.peak_friction() * setup.w * setup.w;
        if self.cart == Cart::Stuck || setup.k == 0.0 {
            return (normal, 0.0);
        }
        let omega = setup.omega_grip;
        let offset = self.start.x - self.push(setup) * (setup.cart_mass + setup.m_eff) / setup.k;
        let x_accel = omega * ((omega * offset).powi(2) + self.start.v.powi(2)).sqrt();
        (setup.grip_gain * x_accel + normal, omega * x_accel)
    }
}
