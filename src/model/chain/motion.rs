//! One phase of a chain bounce in closed form: every normal mode a forced (sliding) or free (gripping)
//! oscillator, written with the resonance- and zero-frequency-safe pieces of [`super::super::oscillator`].

use std::sync::Arc;

use super::super::oscillator::{detuned, forced, free, free_given};
use super::super::setup::{Setup, State};
use super::modes::{MAX, Modes};
use super::{Chain, ChainState};

/// How one mode moves in a sliding phase (see `Slide`'s cart response, of which this is the modal copy).
#[derive(Clone, Copy, Debug)]
enum Response {
    /// Free oscillation (gripping: the static friction is internal to the ball-and-chain system).
    Free,
    /// Through the particular solution a sin(w t), a = Φ_1j F0 / (Ω² - w²).
    Detuned { amplitude: f64 },
    /// Through [`forced`], exact at resonance: drive = Φ_1j F0.
    Forced { drive: f64 },
}

/// The detuned form is used while a mode's particular response moves a mass at most this many times the
/// speeds at the start of the phase (the single cart's criterion).
const DETUNED_GAIN: f64 = 16.0;

/// One phase of a chain bounce from `start`: sliding with the slip's sign `dir` (friction dir mu N on the
/// ball, its reaction on the first mass), or gripping (`dir` = 0).
#[derive(Clone, Debug)]
pub struct Motion {
    chain: Arc<Chain>,
    pub dir: f64,
    pub start: ChainState,
    sin_wt0: f64,
    cos_wt0: f64,
    q0: [f64; MAX],
    dq0: [f64; MAX],
    response: [Response; MAX],
    /// The first mass's velocity at the start as the modal sum gives it (the grip's impulse on the ball
    /// is measured from it, so that it is exactly zero at the start).
    v1_start: f64,
}

/// The state of the ball and the first mass at one time, with the friction and the first mass's
/// acceleration there.
#[derive(Clone, Copy, Debug)]
pub struct Contact {
    pub state: State,
    /// Friction on the ball, positive backward.
    pub friction: f64,
    /// Its rate (gripping; the sliding one is dir mu N').
    pub friction_rate: f64,
    /// The first mass's acceleration V_1'.
    pub accel: f64,
}

impl Motion {
    pub fn new(chain: Arc<Chain>, setup: &Setup, start: ChainState, dir: f64) -> Motion {
        let (sin_wt0, cos_wt0) = (setup.w * start.t).sin_cos();
        let modes = chain.modes(dir);
        let q0 = modes.project(&start.x);
        let dq0 = modes.project(&start.v);
        let v1_start = (0..modes.n).map(|j| modes.shape[0][j] * dq0[j]).sum();
        let force = dir * setup.peak_friction();
        let speeds = start.vx.abs()
            + setup.r * start.omega.abs()
            + start.v[..modes.n].iter().map(|v| v.abs()).sum::<f64>();
        let w = setup.w;
        let mut response = [Response::Free; MAX];
        if dir != 0.0 {
            for (j, r) in response.iter_mut().enumerate().take(modes.n) {
                let omega = modes.omega[j];
                let drive = modes.shape[0][j] * force;
                let amplitude = drive / (omega * omega - w * w);
                *r = if (amplitude * w * modes.largest[j]).abs() <= DETUNED_GAIN * speeds {
                    Response::Detuned { amplitude }
                } else {
                    Response::Forced { drive }
                };
            }
        }
        Motion {
            chain,
            dir,
            start,
            sin_wt0,
            cos_wt0,
            q0,
            dq0,
            response,
            v1_start,
        }
    }

    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    pub fn modes(&self) -> &Modes {
        self.chain.modes(self.dir)
    }

    pub fn is_grip(&self) -> bool {
        self.dir == 0.0
    }

    /// The modal coordinates and their rates at `t`, with sin(w τ) and cos(w τ), τ = t - t0.
    #[inline]
    fn modal(&self, setup: &Setup, t: f64) -> ([f64; MAX], [f64; MAX], f64, f64) {
        let modes = self.modes();
        let tau = t - self.start.t;
        let w = setup.w;
        let (sin_w_tau, cos_w_tau) = if self.is_grip() {
            (0.0, 1.0)
        } else {
            (w * tau).sin_cos()
        };
        let (mut q, mut dq) = ([0.0; MAX], [0.0; MAX]);
        for j in 0..modes.n {
            let omega = modes.omega[j];
            let (x0, v0) = (self.q0[j], self.dq0[j]);
            (q[j], dq[j]) = match self.response[j] {
                Response::Free => free(x0, v0, omega, tau),
                Response::Detuned { amplitude } => {
                    let (s, c) = (omega * tau).sin_cos();
                    let (x_free, v_free) = free_given(x0, v0, omega, tau, s, c);
                    let phase0 = (self.sin_wt0, self.cos_wt0);
                    let (x_forced, v_forced) =
                        detuned(omega, w, tau, phase0, (sin_w_tau, cos_w_tau), (s, c));
                    (x_free + amplitude * x_forced, v_free + amplitude * v_forced)
                }
                Response::Forced { drive } => {
                    let (x_free, v_free) = free(x0, v0, omega, tau);
                    let (g, dg) = forced(omega, w, self.sin_wt0, self.cos_wt0, tau);
                    (x_free + drive * g, v_free + drive * dg)
                }
            };
        }
        (q, dq, sin_w_tau, cos_w_tau)
    }

    /// The ball, the first mass and the friction at `t`.
    #[inline]
    pub fn contact(&self, setup: &Setup, t: f64) -> Contact {
        let modes = self.modes();
        let (q, dq, sin_w_tau, cos_w_tau) = self.modal(setup, t);
        let (mut x, mut v, mut stiff, mut stiff_rate) = (0.0, 0.0, 0.0, 0.0);
        for j in 0..modes.n {
            let phi = modes.shape[0][j];
            x += phi * q[j];
            v += phi * dq[j];
            stiff += modes.first_stiff[j] * q[j];
            stiff_rate += modes.first_stiff[j] * dq[j];
        }
        let s0 = &self.start;
        let (impulse, friction, friction_rate, accel) = if self.is_grip() {
            // F_s = -m_eff V_1', V_1' = -Σ Φ_1j Ω_j² q_j; the impulse on the ball is -m_eff (V_1 - V_1(t0)).
            let m_eff = setup.m_eff;
            (
                -m_eff * (v - self.v1_start),
                m_eff * stiff,
                m_eff * stiff_rate,
                -stiff,
            )
        } else {
            // Eqs. (1), (2): the impulse ∫ F dt = F0 (cos w t0 - cos w t)/w.
            let force = self.dir * setup.peak_friction();
            let impulse =
                force * (self.cos_wt0 * (1.0 - cos_w_tau) + self.sin_wt0 * sin_w_tau) / setup.w;
            let sin_wt = self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau;
            let friction = force * sin_wt.max(0.0);
            (impulse, friction, 0.0, friction / modes.mass[0] - stiff)
        };
        Contact {
            state: State {
                t,
                vx: s0.vx - impulse / setup.m,
                omega: s0.omega + impulse * setup.r / setup.inertia,
                x,
                v,
            },
            friction,
            friction_rate,
            accel,
        }
    }

    /// The whole chain at `t`.
    pub fn full(&self, setup: &Setup, t: f64) -> ChainState {
        let modes = self.modes();
        let (q, dq, _, _) = self.modal(setup, t);
        let contact = self.contact(setup, t).state;
        ChainState {
            t,
            vx: contact.vx,
            omega: contact.omega,
            x: modes.expand(&q),
            v: modes.expand(&dq),
        }
    }

    /// A bound on |q_j'| over the rest of the contact, per mode, for a sliding phase: the smaller of the
    /// energy bound d/dt sqrt(q'² + Ω² q²) <= |Φ_1j F| integrated (the friction's remaining impulse is
    /// at most mu N0 (1 + cos w t0)/w) and the amplitudes of the closed form |a| w + the free swing.
    fn speed_bounds(&self, setup: &Setup) -> [f64; MAX] {
        let modes = self.modes();
        let w = setup.w;
        let force = setup.peak_friction();
        let remaining_impulse = force * (1.0 + self.cos_wt0) / w;
        let mut bounds = [0.0; MAX];
        for (j, bound) in bounds.iter_mut().enumerate().take(modes.n) {
            let (omega, q0, dq0) = (modes.omega[j], self.q0[j], self.dq0[j]);
            let phi = modes.shape[0][j].abs();
            let energy = (dq0 * dq0 + (omega * q0).powi(2)).sqrt() + phi * remaining_impulse;
            let detuning = omega * omega - w * w;
            let amplitudes = if detuning == 0.0 || self.is_grip() {
                f64::INFINITY
            } else {
                let a = self.dir * modes.shape[0][j] * force / detuning;
                let x_free = q0 - a * self.sin_wt0;
                let v_free = dq0 - a * w * self.cos_wt0;
                a.abs() * w + ((omega * x_free).powi(2) + v_free * v_free).sqrt()
            };
            *bound = energy.min(amplitudes);
        }
        bounds
    }

    /// The slide's bound on |slip''| and the size of the terms of the slip (for its rounding floor).
    ///
    /// slip'' = -F' (1/m_eff + 1/m_1) + Σ Φ_1j Ω_j² q_j', with |F'| <= mu N0 w.
    pub fn slip_curvature(&self, setup: &Setup) -> (f64, f64) {
        let modes = self.modes();
        let bounds = self.speed_bounds(setup);
        let mut curvature =
            setup.peak_friction() * setup.w * (1.0 / setup.m_eff + 1.0 / modes.mass[0]);
        let mut terms = 0.0;
        for (j, bound) in bounds.iter().enumerate().take(modes.n) {
            curvature += modes.first_stiff[j].abs() * bound;
            terms += modes.shape[0][j].abs() * bound;
        }
        (curvature, terms)
    }

    /// The grip's bound on the second derivative of its margins ±F_s - mu N, and the size of the terms
    /// of F_s. Each mode swings freely with sqrt(q'² + Ω² q²) = E_j fixed, so
    /// |F_s''| = m_eff |Σ Φ_1j Ω_j⁴ q_j| <= m_eff Σ |Φ_1j| Ω_j³ E_j; mu N'' is at most mu N0 w².
    pub fn margin_curvature(&self, setup: &Setup) -> (f64, f64) {
        let modes = self.modes();
        let mut curvature = setup.peak_friction() * setup.w * setup.w;
        let mut terms = setup.peak_friction();
        for j in 0..modes.n {
            let omega = modes.omega[j];
            let swing = (self.dq0[j].powi(2) + (omega * self.q0[j]).powi(2)).sqrt();
            let reach = setup.m_eff * modes.shape[0][j].abs() * omega * swing;
            curvature += reach * omega * omega;
            terms += reach;
        }
        (curvature, terms)
    }
}
