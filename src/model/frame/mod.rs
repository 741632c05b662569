//! The rigid ball on the single cart whose spring is tied to a free frame (issue 23): along the surface
//! the frame is a free mass M_t, so
//!
//! M x1'' = F - k (x1 - x_f),   M_t x_f'' = k (x1 - x_f)
//!
//! (Cross 2010, Eq. (3), with the wall replaced by the frame). Each phase is solved in closed form in two
//! coordinates: the spring's stretch y = x1 - x_f, an oscillator of the reduced mass, and the momentum
//! along the surface P of cart and frame (with the gripping ball's m_eff), which only the friction changes
//! (the frame's rigid-body mode, polynomial in t between the impulses of F). A clamped frame is the
//! paper's model, solved by [`super::cart`]; as M_t grows this one approaches it.
//!
//! - Slide: F = dir mu N(t) on the ball (Eqs. (1), (2)) and on the cart: y'' + Ω² y = F/M with
//!   Ω² = k (1/M + 1/M_t), P' = F.
//! - Grip: the ball's contact point moves with the cart (Eq. (4)); the ball's m_eff rides on it, so
//!   y'' + Ω_g² y = 0 with Ω_g² = k (1/(M + m_eff) + 1/M_t), P constant, and the static friction is
//!   F_s = -m_eff x1'' = m_eff k y/(M + m_eff) (Eq. (5) with y for X).
//!
//! Transitions follow the paper's rules ([`transition::next`], the cart's spring force k y), located by
//! [`first_rise`] on the exact expressions. The cart's displacement reported is the spring's stretch y,
//! relative to the frame; its velocity is the cart's own (the slip is measured against it).

use std::cell::Cell;

use super::contact::{Ball, Cart, Cause, Contact, Found, Mode, PhaseMotion, ROLLING, ROUNDING};
use super::error::{MAX_RADIANS, SolveError};
use super::events::first_rise;
use super::oscillator::{detuned, forced, free_given};
use super::params::Params;
use super::quadrature::integrate;
use super::setup::{Setup, State};
use super::transition::{self, Touched};

/// The ball and the cart (`x` the spring's stretch y, `v` the cart's velocity), and the frame's velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameState {
    pub s: State,
    /// The frame's velocity along the surface, m/s.
    pub vf: f64,
}

/// One phase on the free frame: a slide (`dir` ±1) or a grip (`dir` 0).
#[derive(Clone, Copy, Debug)]
pub struct FrameMotion {
    pub start: FrameState,
    pub dir: f64,
    sin_wt0: f64,
    cos_wt0: f64,
    /// Ω (sliding) or Ω_g (gripping), rad/s.
    omega: f64,
    /// The cart's moving mass: M sliding, M + m_eff gripping.
    cart: f64,
    /// The frame's mass M_t.
    frame: f64,
    /// The momentum along the surface of the cart (with m_eff gripping) and the frame at the start.
    p0: f64,
    /// The cart's velocity at the start as the closed form gives it (the grip's impulse on the ball is
    /// measured from it, so that it is exactly zero at the start).
    v1_start: f64,
    /// Sliding away from resonance: the particular response's amplitude F0 / (M (Ω² - w²)), which
    /// [`detuned`] scales with no trigonometry beyond the free swing's; `None` near resonance, where
    /// [`forced`] is exact (the single cart's `Slide` makes the same choice).
    amplitude: Option<f64>,
}

/// The detuned form is used while the particular response's speed A w is at most this many times the
/// speeds at the start of the phase (the single cart's criterion).
const DETUNED_GAIN: f64 = 16.0;

/// Everything at one instant of a phase.
#[derive(Clone, Copy, Debug)]
struct Point {
    state: FrameState,
    /// The friction on the ball, positive backward.
    friction: f64,
    /// Its rate (gripping).
    friction_rate: f64,
    /// The cart's acceleration.
    accel: f64,
}

impl FrameMotion {
    fn new(setup: &Setup, frame: &FramedCart, start: FrameState, dir: f64) -> Self {
        let (sin_wt0, cos_wt0) = (setup.w * start.s.t).sin_cos();
        let (omega, cart) = if dir == 0.0 {
            (frame.omega_grip, setup.cart_mass + setup.m_eff)
        } else {
            (frame.omega_slide, setup.cart_mass)
        };
        let mut motion = FrameMotion {
            start,
            dir,
            sin_wt0,
            cos_wt0,
            omega,
            cart,
            frame: frame.mass,
            p0: cart * start.s.v + frame.mass * start.vf,
            v1_start: start.s.v,
            amplitude: None,
        };
        if dir != 0.0 {
            let w = setup.w;
            let amplitude = dir * setup.peak_friction() / (cart * (omega * omega - w * w));
            let s0 = &start.s;
            let speeds = s0.vx.abs() + setup.r * s0.omega.abs() + s0.v.abs() + start.vf.abs();
            motion.amplitude =
                ((amplitude * w).abs() <= DETUNED_GAIN * speeds).then_some(amplitude);
        }
        motion.v1_start = motion.cart_velocity(motion.p0, start.s.v - start.vf);
        motion
    }

    /// The cart's velocity from the momentum `p` and the stretch's rate `dy`: (P + M_t y')/(M + M_t).
    #[inline]
    fn cart_velocity(&self, p: f64, dy: f64) -> f64 {
        (p + self.frame * dy) / (self.cart + self.frame)
    }

    #[inline]
    fn at(&self, setup: &Setup, t: f64) -> Point {
        let s0 = &self.start.s;
        let tau = t - s0.t;
        let (y0, dy0) = (s0.x, s0.v - self.start.vf);
        let (sin_omega_tau, cos_omega_tau) = (self.omega * tau).sin_cos();
        let (y_free, dy_free) = free_given(y0, dy0, self.omega, tau, sin_omega_tau, cos_omega_tau);
        if self.dir == 0.0 {
            let v = self.cart_velocity(self.p0, dy_free);
            let impulse = -setup.m_eff * (v - self.v1_start);
            let gain = setup.m_eff * setup.k / self.cart;
            return Point {
                state: FrameState {
                    s: State {
                        t,
                        vx: s0.vx - impulse / setup.m,
                        omega: s0.omega + impulse * setup.r / setup.inertia,
                        x: y_free,
                        v,
                    },
                    vf: v - dy_free,
                },
                friction: gain * y_free,
                friction_rate: gain * dy_free,
                accel: -setup.k * y_free / self.cart,
            };
        }
        let w = setup.w;
        let force_amplitude = self.dir * setup.peak_friction();
        let (sin_w_tau, cos_w_tau) = (w * tau).sin_cos();
        let sin_wt = self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau;
        // Eqs. (1), (2): the impulse ∫ F dt = F0 (cos w t0 - cos w t)/w, which is also what the cart
        // and the frame together gain.
        let impulse =
            force_amplitude * (self.cos_wt0 * (1.0 - cos_w_tau) + self.sin_wt0 * sin_w_tau) / w;
        let (y, dy) = match self.amplitude {
            Some(amplitude) => {
                let (g, dg) = detuned(
                    self.omega,
                    w,
                    tau,
                    (self.sin_wt0, self.cos_wt0),
                    (sin_w_tau, cos_w_tau),
                    (sin_omega_tau, cos_omega_tau),
                );
                (y_free + amplitude * g, dy_free + amplitude * dg)
            }
            None => {
                let (g, dg) = forced(self.omega, w, self.sin_wt0, self.cos_wt0, tau);
                let drive = force_amplitude / self.cart;
                (y_free + drive * g, dy_free + drive * dg)
            }
        };
        let v = self.cart_velocity(self.p0 + impulse, dy);
        let friction = force_amplitude * sin_wt.max(0.0);
        Point {
            state: FrameState {
                s: State {
                    t,
                    vx: s0.vx - impulse / setup.m,
                    omega: s0.omega + impulse * setup.r / setup.inertia,
                    x: y,
                    v,
                },
                vf: v - dy,
            },
            friction,
            friction_rate: self.dir * setup.friction_limit_rate(t),
            accel: (friction - setup.k * y) / self.cart,
        }
    }

    /// A bound on |y'| over the rest of the contact: the oscillator's energy, in velocity units, grows at
    /// most by the drive's impulse per unit mass; away from resonance, also the free swing about the
    /// particular response A sin(w t) plus that response's speed |A| w, whichever is smaller.
    fn stretch_speed(&self, setup: &Setup) -> f64 {
        let s0 = &self.start.s;
        let dy0 = s0.v - self.start.vf;
        let free = dy0.hypot(self.omega * s0.x);
        if self.dir == 0.0 {
            return free;
        }
        let fed = free + setup.peak_friction() * (setup.duration - s0.t) / self.cart;
        self.amplitude.map_or(fed, |a| {
            let w = setup.w;
            let swing = (dy0 - a * w * self.cos_wt0).hypot(self.omega * (s0.x - a * self.sin_wt0));
            fed.min(swing + a.abs() * w)
        })
    }
}

impl PhaseMotion for FrameMotion {
    fn state_at(&self, setup: &Setup, t: f64) -> State {
        self.at(setup, t).state.s
    }

    fn friction(&self, setup: &Setup, state: &State) -> f64 {
        self.at(setup, state.t).friction
    }

    fn initial(&self) -> State {
        self.start.s
    }

    /// A rigid ball has no contact patch.
    fn patch_at(&self, _: &Setup, _: f64) -> Option<(f64, f64)> {
        None
    }

    /// The cart's kinetic energy and its spring's, M V²/2 + k y²/2 (the frame's is apart).
    fn surface_energy(&self, setup: &Setup, at: &State) -> f64 {
        setup.cart_energy(at)
    }

    /// ∫ F (v_x - r omega - V) dt, on panels of the faster of the stretch and the normal force.
    fn friction_work(&self, setup: &Setup, start: f64, end: f64) -> f64 {
        let power = |t: f64| {
            let p = self.at(setup, t);
            p.friction * setup.slip(&p.state.s)
        };
        integrate(power, start, end, 2.0 / self.omega.max(setup.w))
    }

    /// A rigid ball holds no tangential energy.
    fn ball_spring_energy(&self, _: &Setup, _: f64) -> f64 {
        0.0
    }

    fn dashpot_loss(&self, _: &Setup, _: f64, _: f64) -> f64 {
        0.0
    }

    fn frame_velocity(&self, setup: &Setup, t: f64) -> f64 {
        self.at(setup, t).state.vf
    }

    fn fastest(&self, _: &Setup) -> f64 {
        self.omega
    }
}

/// The rigid ball on the single cart, its spring tied to a free frame of mass M_t.
pub struct FramedCart {
    mass: f64,
    /// Ω = sqrt(k (1/M + 1/M_t)), the stretch's frequency while the ball slides.
    omega_slide: f64,
    /// Ω_g = sqrt(k (1/(M + m_eff) + 1/M_t)), while it grips.
    omega_grip: f64,
    spin: f64,
    /// |v_x1| + r |omega1|: the scale of the speeds, for the event functions' rounding.
    incoming: f64,
}

impl FramedCart {
    /// The model for `params` on a frame of mass `frame` (kg), refused with string friction (not yet
    /// solved on a free frame) and when the cart oscillates too fast to resolve.
    pub fn new(params: &Params, setup: &Setup, frame: f64) -> Result<Self, SolveError> {
        if setup.cart_friction > 0.0 {
            return Err(SolveError::FreeFrame {
                what: "string friction (--cart-friction)",
            });
        }
        let omega_slide = (setup.k * (1.0 / setup.cart_mass + 1.0 / frame)).sqrt();
        let omega_grip = (setup.k * (1.0 / (setup.cart_mass + setup.m_eff) + 1.0 / frame)).sqrt();
        let radians = omega_slide.max(omega_grip) * setup.duration;
        if radians > MAX_RADIANS {
            return Err(SolveError::TooFast { radians });
        }
        Ok(FramedCart {
            mass: frame,
            omega_slide,
            omega_grip,
            spin: params.spin,
            incoming: setup.vx1.abs() + setup.r * params.spin.abs(),
        })
    }
}

impl Contact for FramedCart {
    type State = FrameState;
    type Motion = FrameMotion;
    type Probe = FrameState;

    fn start(&self, setup: &Setup) -> (FrameState, Mode) {
        let state = FrameState {
            s: setup.initial(self.spin),
            vf: 0.0,
        };
        let slip0 = setup.slip(&state.s);
        // A ball that arrives rolling grips at once (N(0) = 0 and F_s = 0).
        let arriving = if slip0.abs() <= ROLLING * self.incoming {
            Ball::Grip
        } else {
            Ball::Slide(slip0.signum())
        };
        let mode = transition::next(
            setup,
            &touched(setup, &state.s),
            arriving,
            Cart::Moving(1),
            Cause::Start,
        );
        (state, mode)
    }

    fn time(state: &FrameState) -> f64 {
        state.s.t
    }

    fn contact(state: &FrameState) -> State {
        state.s
    }

    fn motion(&self, setup: &Setup, state: &FrameState, (ball, _): Mode) -> FrameMotion {
        let dir = match ball {
            Ball::Slide(dir) => dir,
            Ball::Grip => 0.0,
        };
        FrameMotion::new(setup, self, *state, dir)
    }

    fn first_event(
        &self,
        setup: &Setup,
        motion: &FrameMotion,
        state: &FrameState,
        _: Mode,
        cause: Cause,
    ) -> Found<FrameState> {
        let (t0, end) = (state.s.t, setup.duration);
        let s = &state.s;
        let peak = setup.peak_friction();
        let stretch_speed = motion.stretch_speed(setup);
        let last = Cell::new(*state);
        let event = if motion.dir != 0.0 {
            let dir = motion.dir;
            // A slip that starts on its zero is measured from its start value.
            let offset = if matches!(cause, Cause::SlipZero | Cause::GripBreak(_)) {
                setup.slip(s)
            } else {
                0.0
            };
            let f = |t: f64| {
                let p = motion.at(setup, t);
                last.set(p.state);
                let rate = -p.friction / setup.m_eff - p.accel;
                [(-dir * (setup.slip(&p.state.s) - offset), -dir * rate)]
            };
            // slip'' = -F'/m_eff - V'', V'' = (F' - k y')/M.
            let force_rate = peak * setup.w;
            let curvature =
                force_rate / setup.m_eff + (force_rate + setup.k * stretch_speed) / motion.cart;
            let speeds = self.incoming
                + s.vx.abs()
                + setup.r * s.omega.abs()
                + s.v.abs()
                + state.vf.abs()
                + stretch_speed;
            let step = setup.event_step(motion.omega);
            first_rise(f, t0, end, step, [curvature], [ROUNDING * speeds])
                .map(|(t, _)| (t, Cause::SlipZero))
        } else {
            let f = |t: f64| {
                let p = motion.at(setup, t);
                last.set(p.state);
                setup.grip_margins(t, p.friction, p.friction_rate)
            };
            // F_s'' = m_eff k y''/(M + m_eff), |y''| <= Ω_g sqrt(Ω_g² y0² + y0'²); mu N'' <= mu N0 w².
            let gain = setup.m_eff * setup.k / motion.cart;
            let curvature = gain * motion.omega * stretch_speed + peak * setup.w * setup.w;
            let forces = peak + setup.k * s.x.abs();
            let step = setup.event_step(motion.omega);
            first_rise(f, t0, end, step, [curvature; 2], [ROUNDING * forces; 2]).map(
                |(t, branch)| {
                    let sign = if branch == 0 { 1.0 } else { -1.0 };
                    (t, Cause::GripBreak(sign))
                },
            )
        };
        Found {
            event,
            last: Some(last.get()),
        }
    }

    fn state_at(
        &self,
        setup: &Setup,
        motion: &FrameMotion,
        t: f64,
        last: Option<FrameState>,
    ) -> FrameState {
        match last {
            Some(s) if s.s.t == t => s,
            _ => motion.at(setup, t).state,
        }
    }

    fn next(
        &self,
        setup: &Setup,
        state: &mut FrameState,
        (ball, cart): Mode,
        cause: Cause,
    ) -> Mode {
        transition::next(setup, &touched(setup, &state.s), ball, cart, cause)
    }
}

/// The cart as the transition rules see it: its spring force is k y.
fn touched(setup: &Setup, state: &State) -> Touched {
    Touched {
        t: state.t,
        mass: setup.cart_mass,
        spring: setup.k * state.x,
        v: state.v,
    }
}
