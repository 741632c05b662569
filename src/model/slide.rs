//! The sliding phase, Eqs. (1)-(3): friction of magnitude mu N opposing the slip.

use super::oscillator::{forced, free, sin_over};
use super::setup::{Setup, State};

/// A sliding phase from `start`, with the slip's sign `dir` (+1: the contact point moves forward
/// relative to the cart and the friction on the ball, F = dir mu N, acts backward).
#[derive(Clone, Copy, Debug)]
pub struct Slide {
    pub start: State,
    pub dir: f64,
    sin_wt0: f64,
    cos_wt0: f64,
    cart: CartResponse,
}

/// How the cart's motion is written. Detuned: the response to the friction through the particular
/// solution A sin(w t), A = F0 / (M (Ω² - w²)), two `sin_cos` per evaluation. Otherwise through
/// [`forced`], which has no 1/(Ω² - w²) and stays exact at resonance and for very light carts, where
/// the particular and free responses are huge and cancel.
#[derive(Clone, Copy, Debug)]
enum CartResponse {
    Detuned { amplitude: f64 },
    Forced,
}

/// The detuned form is used while the particular response's speed A w is at most this many times the
/// speeds at the start of the phase (so that cancellation costs at most about one digit).
const DETUNED_GAIN: f64 = 16.0;

impl Slide {
    pub fn new(setup: &Setup, start: State, dir: f64) -> Self {
        let (sin_wt0, cos_wt0) = (setup.w * start.t).sin_cos();
        let (w, omega) = (setup.w, setup.omega_slide);
        let amplitude = dir * setup.mu * setup.n0 / (setup.cart_mass * (omega * omega - w * w));
        let speeds = start.vx.abs() + setup.r * start.omega.abs() + start.v.abs();
        let cart = if (amplitude * w).abs() <= DETUNED_GAIN * speeds {
            CartResponse::Detuned { amplitude }
        } else {
            CartResponse::Forced
        };
        Slide {
            start,
            dir,
            sin_wt0,
            cos_wt0,
            cart,
        }
    }

    /// Friction on the ball, positive when it acts backward: F = dir mu N(t).
    #[inline]
    pub fn friction(&self, setup: &Setup, t: f64) -> f64 {
        self.dir * setup.mu * setup.normal(t)
    }

    /// The state at `t`: Eq. (1) for v_x, Eq. (2) for omega, and Eq. (3), M X'' = F - k X, solved in
    /// closed form (free response plus the response to the sinusoidal friction).
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> State {
        self.evaluate(setup, t).0
    }

    /// The state at `t` and the friction F there.
    #[inline]
    pub fn evaluate(&self, setup: &Setup, t: f64) -> (State, f64) {
        let s0 = &self.start;
        let tau = t - s0.t;
        let (w, omega) = (setup.w, setup.omega_slide);
        let force_amplitude = self.dir * setup.mu * setup.n0;
        let (sin_w_tau, cos_w_tau) = (w * tau).sin_cos();
        let sin_wt = self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau;
        // Eqs. (1), (2): the impulse ∫ F dt = F0 (cos w t0 - cos w t)/w.
        let impulse =
            force_amplitude * (self.cos_wt0 * (1.0 - cos_w_tau) + self.sin_wt0 * sin_w_tau) / w;
        let (x, v) = match self.cart {
            CartResponse::Detuned { amplitude } => {
                // Free response from the start state, plus A (sin w t - its free continuation from t0).
                let (s, c) = (omega * tau).sin_cos();
                let sin_over_omega = sin_over(s, omega, tau);
                let cos_diff = cos_w_tau - c;
                let x_forced =
                    self.sin_wt0 * cos_diff + self.cos_wt0 * (sin_w_tau - w * sin_over_omega);
                let v_forced =
                    w * self.cos_wt0 * cos_diff - self.sin_wt0 * (w * sin_w_tau - omega * s);
                (
                    s0.x * c + s0.v * sin_over_omega + amplitude * x_forced,
                    -s0.x * omega * s + s0.v * c + amplitude * v_forced,
                )
            }
            CartResponse::Forced => {
                let (x_free, v_free) = free(s0.x, s0.v, omega, tau);
                let (g, dg) = forced(omega, w, self.sin_wt0, self.cos_wt0, tau);
                let drive = force_amplitude / setup.cart_mass;
                (x_free + drive * g, v_free + drive * dg)
            }
        };
        let state = State {
            t,
            vx: s0.vx - impulse / setup.m,
            omega: s0.omega + impulse * setup.r / setup.inertia,
            x,
            v,
        };
        (state, force_amplitude * sin_wt.max(0.0))
    }

    /// A bound on |d²(slip)/dt²| from the start of the phase to the end of contact.
    ///
    /// slip'' = -F'/m_eff - V''. The ball's part is at most mu N0 w / m_eff. The cart's V'' = (F' - kV)/M
    /// is bounded two ways, and the smaller is taken: from the amplitudes of the closed form (a free
    /// oscillation plus the particular response A sin(w t), A = F0 / (M (k/M - w²))), tight except near
    /// resonance; and from |V| <= sqrt(2 E0 / M) + mu N0 (T - t0) / M (friction can feed the cart no
    /// faster), valid everywhere.
    pub fn slip_curvature(&self, setup: &Setup) -> f64 {
        let s0 = &self.start;
        let (w, omega, big_m) = (setup.w, setup.omega_slide, setup.cart_mass);
        let force = setup.mu * setup.n0;
        let ball = force * w / setup.m_eff;
        let v_max =
            (2.0 * setup.cart_energy(s0) / big_m).sqrt() + force * (setup.duration - s0.t) / big_m;
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
        };
        ball + crude.min(amplitudes)
    }

    /// d(slip)/dt = -F/m_eff - (F - k X)/M, given the friction `f` at `s`.
    #[inline]
    pub fn slip_rate(setup: &Setup, s: &State, f: f64) -> f64 {
        -f / setup.m_eff - (f - setup.k * s.x) / setup.cart_mass
    }
}
