//! The sliding phase, Eqs. (1)-(3): friction of magnitude mu N opposing the slip.

use super::oscillator::{forced, free, sinc};
use super::setup::{Setup, State};

/// A sliding phase from `start`, with the slip's sign `dir` (+1: the contact point moves forward
/// relative to the cart and the friction on the ball, F = dir mu N, acts backward).
#[derive(Clone, Copy, Debug)]
pub struct Slide {
    pub start: State,
    pub dir: f64,
    sin_wt0: f64,
    cos_wt0: f64,
}

impl Slide {
    pub fn new(setup: &Setup, start: State, dir: f64) -> Self {
        let (sin_wt0, cos_wt0) = (setup.w * start.t).sin_cos();
        Slide {
            start,
            dir,
            sin_wt0,
            cos_wt0,
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
        let s0 = &self.start;
        let tau = t - s0.t;
        let force_amplitude = self.dir * setup.mu * setup.n0;
        // ∫ sin(w u) du over [t0, t] = (cos w t0 - cos w t)/w, written without cancellation.
        let sine_integral = (setup.w * (s0.t + 0.5 * tau)).sin() * tau * sinc(0.5 * setup.w * tau);
        let impulse = force_amplitude * sine_integral;
        let (x_free, v_free) = free(s0.x, s0.v, setup.omega_slide, tau);
        let (g, dg) = forced(setup.omega_slide, setup.w, self.sin_wt0, self.cos_wt0, tau);
        let drive = force_amplitude / setup.cart_mass;
        State {
            t,
            vx: s0.vx - impulse / setup.m,
            omega: s0.omega + impulse * setup.r / setup.inertia,
            x: x_free + drive * g,
            v: v_free + drive * dg,
        }
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

    /// d(slip)/dt = -F/m_eff - (F - k X)/M.
    #[inline]
    pub fn slip_rate(&self, setup: &Setup, s: &State) -> f64 {
        let f = self.friction(setup, s.t);
        -f / setup.m_eff - (f - setup.k * s.x) / setup.cart_mass
    }
}
