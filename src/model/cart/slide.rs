//! The sliding phase, Eqs. (1)-(3): friction of magnitude mu N opposing the slip.

use super::super::contact::Cart;
use super::super::oscillator::{detuned, forced, free, free_given, step};
use super::super::setup::{Setup, State};
use super::super::sums::SlipTerms;
use super::super::trig::{sin_cos, sin_cos2};

/// A sliding phase from `start`, with the slip's sign `dir` (+1: the contact point moves forward
/// relative to the cart and the friction on the ball, F = dir mu N, acts backward).
#[derive(Clone, Copy, Debug)]
pub struct Slide {
    pub start: State,
    pub dir: f64,
    pub cart: Cart,
    sin_wt0: f64,
    cos_wt0: f64,
    response: CartResponse,
    /// The cart's string friction over its mass, -dir_cart F_c / M (0 without string friction).
    push: f64,
}

/// sin and cos of w τ and of Ωτ, τ the time since the phase began.
pub type Angles = ((f64, f64), (f64, f64));

/// How the cart's motion is written. Detuned: the response to the friction through the particular
/// solution A sin(w t), A = F0 / (M (Ω² - w²)), two `sin_cos` per evaluation. Forced: through
/// [`forced`], which has no 1/(Ω² - w²) and stays exact at resonance and for very light carts, where
/// the particular and free responses are huge and cancel. Stuck: the cart does not move.
#[derive(Clone, Copy, Debug)]
enum CartResponse {
    Detuned { amplitude: f64 },
    Forced,
    Stuck,
}

/// The detuned form is used while the particular response's speed A w is at most this many times the
/// speeds at the start of the phase (so that cancellation costs at most about one digit).
const DETUNED_GAIN: f64 = 16.0;

impl Slide {
    pub fn new(setup: &Setup, start: State, dir: f64, cart: Cart) -> Self {
        // The first slide starts at t = 0, where sin_cos gives exactly (0, 1).
        let angle = if start.t == 0.0 {
            (0.0, 1.0)
        } else {
            sin_cos(setup.w * start.t)
        };
        Slide::at_angle(setup, start, dir, cart, angle)
    }

    /// [`Slide::new`] with sin and cos of w t0 at the start at hand (as `sin_cos` gives them).
    #[inline]
    pub fn at_angle(
        setup: &Setup,
        start: State,
        dir: f64,
        cart: Cart,
        (sin_wt0, cos_wt0): (f64, f64),
    ) -> Self {
        let (w, omega) = (setup.w, setup.omega_slide);
        let amplitude = dir * setup.peak_friction() / (setup.cart_mass * (omega * omega - w * w));
        let speeds = start.vx.abs() + setup.r * start.omega.abs() + start.v.abs();
        let response = if cart == Cart::Stuck {
            CartResponse::Stuck
        } else if (amplitude * w).abs() <= DETUNED_GAIN * speeds {
            CartResponse::Detuned { amplitude }
        } else {
            CartResponse::Forced
        };
        Slide {
            start,
            dir,
            cart,
            sin_wt0,
            cos_wt0,
            response,
            push: cart.friction(setup) / setup.cart_mass,
        }
    }

    /// Friction on the ball, positive when it acts backward: F = dir mu N(t).
    #[inline]
    pub fn friction(&self, setup: &Setup, t: f64) -> f64 {
        self.dir * setup.mu * setup.normal(t)
    }

    /// The state at `t`: Eq. (1) for v_x, Eq. (2) for omega, and Eq. (3), M X'' = F - k X (less the
    /// string friction while the cart moves), solved in closed form.
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> State {
        self.evaluate(setup, t).0
    }

    /// The state at `t` and the friction F there.
    #[inline]
    pub fn evaluate(&self, setup: &Setup, t: f64) -> (State, f64) {
        let (state, (friction, _)) = self.sample(setup, t);
        (state, friction)
    }

    /// The state at `t`, and the friction F there with its rate F'.
    #[inline(always)]
    pub fn sample(&self, setup: &Setup, t: f64) -> (State, (f64, f64)) {
        self.sample_given(setup, t, self.angles(setup, t))
    }

    /// sin and cos of w τ and of Ωτ at `t`, τ = t - t0, computed together (the cart's are wasted when it
    /// is stuck); both angles are 0 at the start of the phase, where the event search begins (sin_cos2
    /// gives exactly (0, 1) there).
    #[inline(always)]
    pub fn angles(&self, setup: &Setup, t: f64) -> Angles {
        let tau = t - self.start.t;
        if tau == 0.0 {
            ((0.0, 1.0), (0.0, 1.0))
        } else {
            sin_cos2(setup.w * tau, setup.omega_slide * tau)
        }
    }

    /// [`Slide::sample`] with the phase's `Angles` at `t` at hand.
    #[inline(always)]
    pub fn sample_given(
        &self,
        setup: &Setup,
        t: f64,
        ((sin_w_tau, cos_w_tau), (s, c)): Angles,
    ) -> (State, (f64, f64)) {
        let s0 = &self.start;
        let tau = t - s0.t;
        let (w, omega) = (setup.w, setup.omega_slide);
        let force_amplitude = self.dir * setup.peak_friction();
        let sin_wt = self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau;
        let cos_wt = self.cos_wt0 * cos_w_tau - self.sin_wt0 * sin_w_tau;
        // At the phase's start, where the event search begins, the closed forms give the start state
        // itself.
        let state = if tau == 0.0 {
            let v = match self.response {
                CartResponse::Stuck => 0.0,
                _ => s0.v,
            };
            State { t, v, ..*s0 }
        } else {
            // Eqs. (1), (2): the impulse ∫ F dt = F0 (cos w t0 - cos w t)/w.
            let impulse =
                force_amplitude * (self.cos_wt0 * (1.0 - cos_w_tau) + self.sin_wt0 * sin_w_tau) / w;
            let (x, v) = match self.response {
                CartResponse::Detuned { amplitude } => {
                    // Free response from the start state, plus A (sin w t - its free continuation
                    // from t0).
                    let (x_free, v_free) = free_given(s0.x, s0.v, omega, tau, s, c);
                    let phase0 = (self.sin_wt0, self.cos_wt0);
                    let (x_forced, v_forced) =
                        detuned(omega, w, tau, phase0, (sin_w_tau, cos_w_tau), (s, c));
                    let (x_push, v_push) = self.push_response(s, c, omega, tau);
                    (
                        x_free + amplitude * x_forced + x_push,
                        v_free + amplitude * v_forced + v_push,
                    )
                }
                CartResponse::Forced => {
                    let (x_free, v_free) = free(s0.x, s0.v, omega, tau);
                    let (g, dg) = forced(omega, w, self.sin_wt0, self.cos_wt0, tau);
                    let drive = force_amplitude / setup.cart_mass;
                    let (x_push, v_push) = self.push_response(s, c, omega, tau);
                    (x_free + drive * g + x_push, v_free + drive * dg + v_push)
                }
                CartResponse::Stuck => (s0.x, 0.0),
            };
            State {
                t,
                vx: s0.vx - impulse / setup.m,
                omega: s0.omega + impulse * setup.r / setup.inertia,
                x,
                v,
            }
        };
        let friction = force_amplitude * sin_wt.max(0.0);
        let friction_rate = if sin_wt >= 0.0 {
            force_amplitude * w * cos_wt
        } else {
            0.0
        };
        (state, (friction, friction_rate))
    }

    /// The slip event written once for the phase, where the cart's response is detuned, it has a spring
    /// and no string friction (else `None`).
    #[inline]
    pub fn slip_sums(&self, setup: &Setup) -> Option<SlipSums> {
        let CartResponse::Detuned { amplitude } = self.response else {
            return None;
        };
        let (w, omega) = (setup.w, setup.omega_slide);
        if self.push != 0.0 || omega == 0.0 {
            return None;
        }
        let s0 = &self.start;
        let dir = self.dir;
        let force_amplitude = dir * setup.peak_friction();
        // slip = slip0 - J/m_eff - V with the impulse J = F0 (cos w t0 - cos w t)/w and the cart's
        // V = A w cos w t + b cos Ωτ - a Ω sin Ωτ, a = X0 - A sin w t0, b = V0 - A w cos w t0 (Eq. (3)'s
        // particular and free responses); the event is -dir (slip - offset).
        let ball = dir * (force_amplitude / setup.m_eff - amplitude * w * w);
        let free_cos = dir * (s0.v - amplitude * w * self.cos_wt0);
        let free_sin = dir * (s0.x - amplitude * self.sin_wt0) * omega;
        let swing = (free_cos * free_cos + free_sin * free_sin).sqrt();
        let fourth = ball.abs() * w * w * w + omega.powi(4) * swing;
        let curvature = ball.abs() * w + omega * omega * swing;
        Some(SlipSums {
            slip0: setup.slip(s0),
            v0: s0.v,
            impulse0: dir * force_amplitude * self.cos_wt0 / (w * setup.m_eff),
            terms: SlipTerms::new(
                (self.sin_wt0, self.cos_wt0),
                (w, omega),
                [ball, free_cos, free_sin],
            ),
            dir,
            curvature: curvature * (1.0 + 1e-9),
            fourth: fourth * (1.0 + 1e-9),
        })
    }

    /// The cart's response to the constant string friction.
    #[inline]
    fn push_response(&self, s: f64, c: f64, omega: f64, tau: f64) -> (f64, f64) {
        if self.push == 0.0 {
            return (0.0, 0.0);
        }
        let (x, v) = step(s, c, omega, tau);
        (self.push * x, self.push * v)
    }

    /// The cart's acceleration V' = (F - k X)/M less the string friction, given the friction `f`.
    #[inline]
    pub fn cart_acceleration(&self, setup: &Setup, s: &State, f: f64) -> f64 {
        match self.cart {
            Cart::Stuck => 0.0,
            Cart::Moving(_) => (f - setup.k * s.x) / setup.cart_mass + self.push,
        }
    }

    /// The cart's V', V'' and V''' given the friction `f` at `s` and its rate: V' = (F - k X)/M less
    /// the string friction, V'' = (F' - k V)/M, V''' = (F'' - k V')/M with F'' = -w² F (all 0 when
    /// stuck).
    #[inline]
    pub fn cart_derivatives(&self, setup: &Setup, s: &State, (f, rate): (f64, f64)) -> [f64; 3] {
        match self.cart {
            Cart::Stuck => [0.0; 3],
            Cart::Moving(_) => {
                let accel = self.cart_acceleration(setup, s, f);
                let big_m = setup.cart_mass;
                [
                    accel,
                    (rate - setup.k * s.v) / big_m,
                    (-setup.w * setup.w * f - setup.k * accel) / big_m,
                ]
            }
        }
    }

    /// The event that ends the slide, the slip reaching zero, as a function that rises through zero:
    /// -dir (slip - `offset`) with its first three derivatives, given the friction `f` at `s` and its
    /// rate (slip' = -F/m_eff - V', and F'' = -w² F). The offset is the slip at the start when the
    /// slide begins on zero slip, so rounding cannot fake a crossing there.
    #[inline]
    pub fn slip_event(
        &self,
        setup: &Setup,
        s: &State,
        (f, rate): (f64, f64),
        offset: f64,
    ) -> (f64, f64, f64, f64) {
        let [_, jerk, snap] = self.cart_derivatives(setup, s, (f, rate));
        let second = -setup.w * setup.w * f;
        (
            -self.dir * (setup.slip(s) - offset),
            -self.dir * self.slip_rate(setup, s, f),
            self.dir * (rate / setup.m_eff + jerk),
            self.dir * (second / setup.m_eff + snap),
        )
    }

    /// d(slip)/dt = -F/m_eff - V', given the friction `f` at `s`.
    #[inline]
    pub fn slip_rate(&self, setup: &Setup, s: &State, f: f64) -> f64 {
        -f / setup.m_eff - self.cart_acceleration(setup, s, f)
    }

    /// The size of the terms the cart's velocity is computed from, for the rounding floor of its
    /// event: the start velocity, the free swing, the response to the friction and to the string
    /// friction over the rest of the contact.
    pub fn cart_speed_scale(&self, setup: &Setup) -> f64 {
        let s0 = &self.start;
        let remaining = setup.duration - s0.t;
        let drive = setup.peak_friction() / setup.cart_mass;
        let particular = match self.response {
            CartResponse::Detuned { amplitude } => amplitude.abs() * setup.w,
            _ => 0.0,
        };
        s0.v.abs()
            + s0.x.abs() * setup.omega_slide
            + (drive + self.push.abs()) * remaining
            + particular
    }

    /// Bounds, from the start of the phase to the end of contact, on the second derivatives of the
    /// phase's event functions: the slip, and the cart's velocity (moving) or the force that would
    /// unstick it, F - k X (stuck).
    ///
    /// slip'' = -F'/m_eff - V''. The ball's part is at most mu N0 w / m_eff. The cart's V'' = (F' - kV)/M
    /// is bounded two ways, and the smaller is taken: from the amplitudes of the closed form (a free
    /// oscillation, the particular response A sin(w t), A = F0 / (M (k/M - w²)), and the step response
    /// to the string friction), tight except near resonance; and from |V| <= sqrt(2 E0 / M) +
    /// (mu N0 + F_c)(T - t0) / M (the forces can feed the cart no faster), valid everywhere.
    pub fn curvature(&self, setup: &Setup) -> (f64, f64) {
        let s0 = &self.start;
        let (w, omega, big_m) = (setup.w, setup.omega_slide, setup.cart_mass);
        let force = setup.peak_friction();
        let ball = force * w / setup.m_eff;
        if self.cart == Cart::Stuck {
            return (ball, force * w * w);
        }
        let push = self.push.abs();
        let remaining = setup.duration - s0.t;
        let v_max =
            (2.0 * setup.cart_energy(s0) / big_m).sqrt() + (force / big_m + push) * remaining;
        let crude = (force * w + setup.k * v_max) / big_m;
        let detuning = omega * omega - w * w;
        let amplitudes = if detuning == 0.0 {
            f64::INFINITY
        } else {
            let a = self.dir * force / (big_m * detuning);
            let x_free = s0.x - a * self.sin_wt0;
            let v_free = s0.v - a * w * self.cos_wt0;
            omega * omega * ((omega * x_free).powi(2) + v_free * v_free).sqrt()
                + a.abs() * w * w * w
                + push * omega
        };
        let cart = crude.min(amplitudes);
        (ball + cart, cart)
    }
}

/// The slip event of a slide whose cart's response is detuned, on a spring and without string friction,
/// as fixed combinations of sin and cos of w t and Ωτ: with P = dir (F0/m_eff - A w²), B = dir b and
/// Q = dir a Ω (see [`Slide::slip_sums`]), the event -dir (slip - offset) is
/// dir (offset - slip0 - V0 + F0 cos(w t0)/(w m_eff)) - (P/w) cos w t + B cos Ωτ - Q sin Ωτ,
/// and each derivative turns each oscillation a quarter and scales it by its frequency.
#[derive(Clone, Copy, Debug)]
pub struct SlipSums {
    slip0: f64,
    /// The cart's velocity at the start, part of slip0.
    v0: f64,
    /// dir F0 cos(w t0)/(w m_eff).
    impulse0: f64,
    terms: SlipTerms,
    dir: f64,
    /// A bound on the event's second derivative over the whole phase, |P| w + Ω² sqrt(B² + Q²) (with
    /// room for rounding): the sums' own amplitudes, no looser than the amplitudes' bound of
    /// [`Slide::curvature`], which takes the ball's and the cart's terms apart (|P| <= F0/m_eff +
    /// |A| w²), and without its two square roots.
    pub curvature: f64,
    /// A bound on the event's fourth derivative, |P| w³ + Ω⁴ sqrt(B² + Q²) (with room for rounding).
    pub fourth: f64,
}

impl SlipSums {
    /// The event's value at the phase's start, exactly dir (offset - slip0), so rounding cannot fake
    /// a crossing there when the offset is the start's slip; and its constant term.
    pub fn constants(&self, offset: f64) -> (f64, f64) {
        let start = self.dir * (offset - self.slip0);
        (
            start,
            self.dir * (offset - self.slip0 - self.v0) + self.impulse0,
        )
    }

    /// The event -dir (slip - offset) and its first three derivatives, given the phase's `Angles`
    /// and [`SlipSums::constants`].
    #[inline(always)]
    pub fn event(
        &self,
        ((sin_w_tau, cos_w_tau), (s, c)): Angles,
        (start, constant): (f64, f64),
    ) -> (f64, f64, f64, f64) {
        self.terms
            .event((sin_w_tau, cos_w_tau), (s, c), (start, constant))
    }
}
