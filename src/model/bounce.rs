//! One whole bounce: the phases in order, the outcome, the energy budget and the time series.

use serde::Serialize;

use super::cart::Cart;
use super::chain::{ChainMotion, solve_chain_cancellable};
use super::compliant::{CompliantMotion, solve_compliant_cancellable};
use super::events::Stall;
use super::events::first_rise;
use super::grip::Grip;
use super::limits::{self, Unsolvable};
use super::params::{ParamError, Params};
use super::quadrature::integrate;
use super::setup::{Setup, State};
use super::slide::Slide;
use super::transition::{self, Ball, Cause};

/// Whether the ball slides on the cart or grips it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PhaseKind {
    Slide,
    Grip,
}

impl PhaseKind {
    pub fn name(self) -> &'static str {
        match self {
            PhaseKind::Slide => "slide",
            PhaseKind::Grip => "grip",
        }
    }
}

#[derive(Clone, Debug)]
pub(super) enum Motion {
    Slide(Slide),
    Grip(Grip),
    /// A phase on a chain of masses (sliding or gripping).
    Chain(ChainMotion),
    /// A phase of a compliant ball on the single cart.
    Compliant(Box<CompliantMotion>),
}

/// One phase of the bounce.
#[derive(Clone, Debug)]
pub struct Phase {
    pub kind: PhaseKind,
    /// The sign of the slip (and of the friction F) while sliding, +1 or -1; 0 while gripping.
    pub slip_sign: i8,
    /// What the cart does (it can only stick with string friction).
    pub cart: Cart,
    /// Start time, s.
    pub start: f64,
    /// End time, s.
    pub end: f64,
    pub(super) motion: Motion,
}

impl Phase {
    /// The exact state at `t` (meaningful for `t` in `[start, end]`).
    pub fn state_at(&self, setup: &Setup, t: f64) -> State {
        match &self.motion {
            Motion::Slide(slide) => slide.at(setup, t),
            Motion::Grip(grip) => grip.at(setup, t),
            Motion::Chain(chain) => chain.contact(setup, t).state,
            Motion::Compliant(c) => c.at(setup, t).state,
        }
    }

    /// The friction force on the ball, positive backward, in this phase at `state`.
    pub fn friction(&self, setup: &Setup, state: &State) -> f64 {
        match &self.motion {
            Motion::Slide(slide) => slide.friction(setup, state.t),
            Motion::Grip(grip) => grip.friction(setup, state.x),
            Motion::Chain(chain) => chain.contact(setup, state.t).friction,
            Motion::Compliant(c) => c.at(setup, state.t).friction,
        }
    }

    /// The state at the start of the phase.
    pub fn initial(&self) -> State {
        match &self.motion {
            Motion::Slide(slide) => slide.start,
            Motion::Grip(grip) => grip.start,
            Motion::Chain(chain) => chain.start.contact(),
            Motion::Compliant(c) => c.initial(),
        }
    }

    /// Kinetic plus spring energy of the cart, or of the whole chain, at `t`.
    pub fn cart_energy_at(&self, setup: &Setup, t: f64) -> f64 {
        match &self.motion {
            Motion::Chain(chain) => chain.chain().energy(&chain.full(setup, t)),
            Motion::Compliant(c) => c
                .chain_energy(setup, t)
                .unwrap_or_else(|| setup.cart_energy(&c.at(setup, t).state)),
            _ => setup.cart_energy(&self.state_at(setup, t)),
        }
    }

    /// True for a phase on a chain of masses.
    fn on_chain(&self) -> bool {
        match &self.motion {
            Motion::Chain(_) => true,
            Motion::Compliant(c) => c.chain_energy_known(),
            _ => false,
        }
    }

    /// The fastest frequency of the cart (or the chain) while the ball slides, rad/s.
    fn fastest(&self, setup: &Setup) -> f64 {
        match &self.motion {
            Motion::Chain(chain) => chain.chain().slide.fastest,
            Motion::Compliant(c) => c.fastest(setup),
            _ => setup.omega_slide,
        }
    }

    /// The power lost to sliding friction at `t`: F times the slip at the contact (for a compliant ball,
    /// the slip of its contact patch on the cart).
    fn friction_power(&self, setup: &Setup, t: f64) -> f64 {
        let s = self.state_at(setup, t);
        let slip = match &self.motion {
            Motion::Compliant(c) => c.patch_slip(setup, t),
            _ => setup.slip(&s),
        };
        self.friction(setup, &s) * slip
    }

    pub fn duration(&self) -> f64 {
        self.end - self.start
    }
}

/// A phase of the ball, whatever the cart does meanwhile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallPhase {
    pub kind: PhaseKind,
    /// +1 or -1 while sliding, 0 while gripping.
    pub slip_sign: i8,
    /// s
    pub start: f64,
    /// s
    pub end: f64,
}

/// The ball as it leaves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Outcome {
    /// Rebound spin omega2, rad/s.
    pub omega2: f64,
    /// Rebound velocity along the surface, m/s.
    pub vx2: f64,
    /// Rebound velocity away from the surface, e_y v_y1, m/s.
    pub vy2: f64,
    /// Rebound speed, m/s.
    pub speed2: f64,
    /// Rebound angle from the surface, degrees (above 90 when the ball comes back).
    pub theta2_deg: f64,
    /// Tangential coefficient of restitution e_x = -(v_x2 - r omega2)/(v_x1 - r omega1); `None` when the
    /// ball arrives without slip.
    pub ex: Option<f64>,
    pub ey: f64,
    /// r omega2 / v_x2 (1 for rolling); `None` when v_x2 = 0.
    pub roll_ratio: Option<f64>,
}

/// Where the incoming energy went, J.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Energy {
    /// Ball kinetic energy (translation and rotation) before the bounce.
    pub initial: f64,
    /// Ball kinetic energy after.
    pub final_ball: f64,
    /// Cart kinetic plus spring energy after (on a chain, the kinetic and spring energy of all its masses
    /// and springs: the energy left in the chain).
    pub final_cart: f64,
    /// ∫ F · slip dt, integrated over the sliding phases of the exact solution.
    pub friction_loss: f64,
    /// Lost in the normal direction, m v_y1^2 (1 - e_y^2)/2.
    pub normal_loss: f64,
    /// Work against the string friction on the cart: F_c times the distance the cart travelled.
    pub cart_friction_loss: f64,
    /// Energy left in the compliant ball's tangential spring as it leaves, k_b e(T)²/2 (0 for a rigid ball).
    pub ball_spring: f64,
    /// Lost in the compliant ball's dashpot, ∫ c_b e'² dt over the contact (0 for a rigid ball).
    pub dashpot_loss: f64,
    /// (initial - final_ball - final_cart - friction_loss - normal_loss - cart_friction_loss - ball_spring
    /// - dashpot_loss) / initial.
    pub residual: f64,
}

/// One point of the time series.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Normal force N, N.
    pub normal: f64,
    /// Friction force on the ball F, N (positive backward, as in the paper's Fig. 3).
    pub friction: f64,
    /// Cart displacement X (on a chain, its first mass's), m.
    pub x: f64,
    /// Cart velocity V (on a chain, its first mass's), m/s.
    pub v: f64,
    /// Ball velocity along the surface v_x, m/s.
    pub vx: f64,
    /// Ball spin omega, rad/s.
    pub omega: f64,
    /// Slip speed v_x - r omega - V, m/s.
    pub slip: f64,
    /// Index of the phase in [`Bounce::phases`].
    pub phase: usize,
    pub kind: PhaseKind,
    /// True while string friction holds the cart still.
    pub cart_stuck: bool,
}

/// A solved bounce.
#[derive(Clone, Debug)]
pub struct Bounce {
    pub params: Params,
    pub setup: Setup,
    pub phases: Vec<Phase>,
    /// The state at t = T, when the ball leaves.
    pub final_state: State,
    pub outcome: Outcome,
}

/// Why a bounce could not be solved.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolveError {
    #[error(transparent)]
    Params(#[from] ParamError),
    #[error(
        "the cart oscillates too fast to resolve: sqrt(k/M) T = {radians:.3e} rad exceeds {MAX_RADIANS:e} \
         (lower the stiffness, raise the cart mass or shorten the impact)"
    )]
    TooFast { radians: f64 },
    #[error("the bounce switched between sliding and gripping more than {MAX_TRANSITIONS} times")]
    TooManyPhases,
    /// The caller's cancellation check said the solve is no longer wanted.
    #[error("the solve was cancelled")]
    Cancelled,
    #[error(
        "string friction on the cart (--cart-friction) is modelled for the single cart only, not for a \
         chain of {chain} masses: set --cart-friction 0 or --chain 1"
    )]
    ChainStringFriction { chain: usize },
    #[error(
        "a compliant ball (--ball-stiffness > 0) is not modelled together with string friction on the \
         cart: set --ball-stiffness 0 (a rigid ball) or --cart-friction 0"
    )]
    StringFrictionCompliantBall,
    #[error(
        "the ball's contact spring is too stiff to resolve: its fastest rate times T = {radians:.3e} rad \
         exceeds {MAX_RADIANS:e} (lower --ball-stiffness or --ball-damping)"
    )]
    BallTooFast { radians: f64 },
    #[error(transparent)]
    Unsolvable(#[from] Unsolvable),
    #[error(transparent)]
    Stalled(#[from] Stall),
    #[error(
        "{quantity} is not a finite number: the parameters are beyond what f64 carries through"
    )]
    NotFinite { quantity: &'static str },
}

/// The largest number of cart radians per contact the solver accepts (about 16 000 oscillations).
pub const MAX_RADIANS: f64 = 1e5;
/// The largest number of slide/grip transitions in one bounce.
pub const MAX_TRANSITIONS: usize = 10_000;
/// An arriving slip below this fraction of |v_x1| + r |omega1| counts as rolling.
pub(super) const ROLLING: f64 = 1e-12;
/// Event functions are differences of terms this many times their size apart from rounding; a rise
/// smaller than that is noise (it matters near t = T, where N and with it F and F_s vanish).
pub(super) const ROUNDING: f64 = 1e-12;

/// Solves one bounce exactly (Cross 2010, Sec. II): phase by phase in closed form, each transition
/// located by root finding on the exact expressions. Cancelled once the process is interrupted
/// ([`limits::interrupt`]).
pub fn solve(params: &Params) -> Result<Bounce, SolveError> {
    solve_cancellable(params, &limits::interrupted)
}

/// [`solve`], abandoned with [`SolveError::Cancelled`] as soon as `cancelled` returns true: it is asked
/// before every phase, so a caller (the explorer's worker, a headless command on Ctrl-C) can drop a solve
/// that is no longer wanted.
pub fn solve_cancellable(
    params: &Params,
    cancelled: &impl Fn() -> bool,
) -> Result<Bounce, SolveError> {
    limits::bounded(params, || solve_single(params, cancelled))
}

fn solve_single(params: &Params, cancelled: &impl Fn() -> bool) -> Result<Bounce, SolveError> {
    params.validate()?;
    if params.ball_stiffness > 0.0 {
        return solve_compliant_cancellable(params, cancelled);
    }
    if params.chain > 1.0 {
        return solve_chain_cancellable(params, cancelled);
    }
    let setup = Setup::new(params);
    let radians = setup.omega_slide.max(setup.omega_grip) * setup.duration;
    if radians > MAX_RADIANS {
        return Err(SolveError::TooFast { radians });
    }
    let end = setup.duration;
    let mut state = setup.initial(params.spin);
    let incoming = setup.vx1.abs() + setup.r * params.spin.abs();
    let slip0 = setup.slip(&state);
    // A ball that arrives rolling grips at once (N(0) = 0 and F_s = 0, so the grip holds on the boundary).
    let arriving = if slip0.abs() <= ROLLING * incoming {
        Ball::Grip
    } else {
        Ball::Slide(slip0.signum())
    };
    let (mut ball, mut cart) =
        transition::next(&setup, &state, arriving, Cart::Moving(1), Cause::Start);
    let mut cause = Cause::Start;
    let mut phases = Vec::with_capacity(8);
    for _ in 0..MAX_TRANSITIONS {
        if cancelled() {
            return Err(SolveError::Cancelled);
        }
        let t0 = state.t;
        let motion = match ball {
            Ball::Slide(dir) => Motion::Slide(Slide::new(&setup, state, dir, cart)),
            Ball::Grip => Motion::Grip(Grip { start: state, cart }),
        };
        // Event functions that start on their own zero (the slip after a grip broke or the friction
        // reversed, the cart's velocity after it stopped) are measured from their start value, so
        // rounding can never fake a crossing at the start.
        let slip_offset = if matches!(cause, Cause::SlipZero | Cause::GripBreak(_)) {
            setup.slip(&state)
        } else {
            0.0
        };
        let v_offset = if matches!(cause, Cause::Start | Cause::CartStop | Cause::Unstick(_)) {
            state.v
        } else {
            0.0
        };
        let speeds = incoming + state.vx.abs() + setup.r * state.omega.abs() + state.v.abs();
        let forces = setup.mu * setup.n0 + setup.k * state.x.abs() + setup.cart_friction;
        // The state at the last time an event function was evaluated.
        let last = std::cell::Cell::new(state);
        let event = match (&motion, cart) {
            (Motion::Slide(slide), Cart::Moving(cart_dir)) => {
                let cart_dir = f64::from(cart_dir);
                let string = setup.cart_friction > 0.0;
                let f = |t: f64| {
                    let (s, friction) = slide.evaluate(&setup, t);
                    last.set(s);
                    let slip = slide.slip_event(&setup, &s, friction, slip_offset);
                    // Without string friction the cart's stopping changes nothing.
                    let stop = if string {
                        (
                            -cart_dir * (s.v - v_offset),
                            -cart_dir * slide.cart_acceleration(&setup, &s, friction),
                        )
                    } else {
                        (-1.0, 0.0)
                    };
                    [slip, stop]
                };
                let (slip_curvature, cart_curvature) = slide.curvature(&setup);
                // The stand-in for a cart that cannot stick is a constant: no curvature.
                let cart_curvature = if string { cart_curvature } else { 0.0 };
                let noise = [ROUNDING * speeds, ROUNDING * slide.cart_speed_scale(&setup)];
                let step = setup.event_step(setup.omega_slide);
                first_rise(f, t0, end, step, [slip_curvature, cart_curvature], noise).map(
                    |(t, branch)| {
                        (
                            t,
                            if branch == 0 {
                                Cause::SlipZero
                            } else {
                                Cause::CartStop
                            },
                        )
                    },
                )
            }
            (Motion::Slide(slide), Cart::Stuck) => {
                let f = |t: f64| {
                    let (s, friction) = slide.evaluate(&setup, t);
                    last.set(s);
                    let slip = slide.slip_event(&setup, &s, friction, slip_offset);
                    let push = friction - setup.k * s.x;
                    let push_rate = slide.dir * setup.mu * setup.n0 * setup.w * (setup.w * t).cos();
                    [
                        slip,
                        (push - setup.cart_friction, push_rate),
                        (-push - setup.cart_friction, -push_rate),
                    ]
                };
                let (slip_curvature, push_curvature) = slide.curvature(&setup);
                let noise = [ROUNDING * speeds, ROUNDING * forces, ROUNDING * forces];
                let step = setup.event_step(0.0);
                first_rise(
                    f,
                    t0,
                    end,
                    step,
                    [slip_curvature, push_curvature, push_curvature],
                    noise,
                )
                .map(|(t, branch)| {
                    let cause = match branch {
                        0 => Cause::SlipZero,
                        1 => Cause::Unstick(1),
                        _ => Cause::Unstick(-1),
                    };
                    (t, cause)
                })
            }
            (Motion::Grip(grip), Cart::Moving(cart_dir)) => {
                let cart_dir = f64::from(cart_dir);
                let string = setup.cart_friction > 0.0;
                let f = |t: f64| {
                    let s = grip.at(&setup, t);
                    last.set(s);
                    let [forward, backward] = grip.margins(&setup, &s);
                    let stop = if string {
                        (
                            -cart_dir * (s.v - v_offset),
                            -cart_dir * grip.cart_acceleration(&setup, &s),
                        )
                    } else {
                        (-1.0, 0.0)
                    };
                    [forward, backward, stop]
                };
                let (margin_curvature, cart_curvature) = grip.curvature(&setup);
                let cart_curvature = if string { cart_curvature } else { 0.0 };
                let cart_noise = ROUNDING * grip.cart_speed_scale(&setup);
                let noise = [ROUNDING * forces, ROUNDING * forces, cart_noise];
                let step = setup.event_step(setup.omega_grip);
                first_rise(
                    f,
                    t0,
                    end,
                    step,
                    [margin_curvature, margin_curvature, cart_curvature],
                    noise,
                )
                .map(|(t, branch)| {
                    let cause = match branch {
                        0 => Cause::GripBreak(1.0),
                        1 => Cause::GripBreak(-1.0),
                        _ => Cause::CartStop,
                    };
                    (t, cause)
                })
            }
            // Rolling on a still cart: nothing changes until the ball leaves.
            (Motion::Grip(_), Cart::Stuck) => None,
            (Motion::Chain(_) | Motion::Compliant(_), _) => {
                unreachable!("the rigid single-cart loop builds no chain or compliant phase")
            }
        }
        // A transition within rounding of the end changes nothing.
        .filter(|&(t, _)| t < end * (1.0 - 1e-13));
        let t1 = event.map_or(end, |(t, _)| t);
        let phase = Phase {
            kind: if ball == Ball::Grip {
                PhaseKind::Grip
            } else {
                PhaseKind::Slide
            },
            slip_sign: if let Ball::Slide(dir) = ball {
                dir as i8
            } else {
                0
            },
            cart,
            start: t0,
            end: t1,
            motion,
        };
        // The event search's last evaluation is usually at the transition itself.
        state = if last.get().t == t1 {
            last.get()
        } else {
            phase.state_at(&setup, t1)
        };
        if t1 > t0 {
            phases.push(phase);
        }
        let Some((_, next_cause)) = event else {
            return Ok(finish(params, setup, phases, state));
        };
        if next_cause == Cause::CartStop {
            state.v = 0.0;
        }
        cause = next_cause;
        (ball, cart) = transition::next(&setup, &state, ball, cart, cause);
    }
    Err(SolveError::TooManyPhases)
}

pub(super) fn finish(params: &Params, setup: Setup, phases: Vec<Phase>, last: State) -> Bounce {
    let vy2 = params.ey * setup.vy1;
    let r = setup.r;
    let incoming_slip = setup.vx1 - r * params.spin;
    let scale = setup.vx1.abs() + r * params.spin.abs();
    let ex = (incoming_slip.abs() > ROLLING * scale)
        .then(|| -(last.vx - r * last.omega) / incoming_slip);
    let outcome = Outcome {
        omega2: last.omega,
        vx2: last.vx,
        vy2,
        speed2: last.vx.hypot(vy2),
        theta2_deg: vy2.atan2(last.vx).to_degrees(),
        ex,
        ey: params.ey,
        roll_ratio: (last.vx != 0.0).then(|| r * last.omega / last.vx),
    };
    Bounce {
        params: *params,
        setup,
        phases,
        final_state: last,
        outcome,
    }
}

/// The energy budget of a solved bounce (see [`Bounce::energy`]).
fn energy_budget(params: &Params, setup: &Setup, phases: &[Phase], last: &State) -> Energy {
    let first = setup.initial(params.spin);
    let vy2 = params.ey * setup.vy1;
    let initial = setup.ball_tangential_energy(&first) + 0.5 * setup.m * setup.vy1 * setup.vy1;
    let final_ball = setup.ball_tangential_energy(last) + 0.5 * setup.m * vy2 * vy2;
    let final_cart = match phases.last() {
        Some(p) if p.on_chain() => p.cart_energy_at(setup, p.end),
        _ => setup.cart_energy(last),
    };
    let normal_loss = 0.5 * setup.m * (setup.vy1 * setup.vy1 - vy2 * vy2);
    // The cart never reverses within a phase (its stopping ends the phase), so the distance it
    // travels in a phase is |X(end) - X(start)|.
    let cart_friction_loss = setup.cart_friction
        * phases
            .iter()
            .filter(|p| p.cart != Cart::Stuck)
            .map(|p| (p.state_at(setup, p.end).x - p.initial().x).abs())
            .sum::<f64>();
    let friction_loss = phases
        .iter()
        .filter(|p| p.kind == PhaseKind::Slide)
        .map(|p| match &p.motion {
            Motion::Compliant(c) => {
                c.integrate(setup, |t| p.friction_power(setup, t), p.start, p.end)
            }
            _ => {
                let panel = 2.0 / p.fastest(setup).max(setup.w);
                integrate(|t| p.friction_power(setup, t), p.start, p.end, panel)
            }
        })
        .sum();
    fn compliant(p: &Phase) -> Option<&CompliantMotion> {
        match &p.motion {
            Motion::Compliant(c) => Some(c.as_ref()),
            _ => None,
        }
    }
    let dashpot_loss = phases
        .iter()
        .filter_map(|p| compliant(p).map(|c| (p, c)))
        .filter(|(_, c)| c.spring().cb > 0.0)
        .map(|(p, c)| {
            let cb = c.spring().cb;
            c.integrate(
                setup,
                |t| {
                    let de = c.at(setup, t).de;
                    cb * de * de
                },
                p.start,
                p.end,
            )
        })
        .sum();
    let ball_spring = phases
        .last()
        .and_then(|p| compliant(p).map(|c| (p, c)))
        .map_or(0.0, |(p, c)| {
            let e = c.at(setup, p.end).e;
            0.5 * c.spring().kb * e * e
        });
    Energy {
        initial,
        final_ball,
        final_cart,
        friction_loss,
        normal_loss,
        cart_friction_loss,
        ball_spring,
        dashpot_loss,
        residual: (initial
            - final_ball
            - final_cart
            - friction_loss
            - normal_loss
            - cart_friction_loss
            - ball_spring
            - dashpot_loss)
            / initial,
    }
}

impl Bounce {
    /// Where the incoming energy went. The friction loss is integrated from the exact solution (Gauss-
    /// Legendre, to about 1e-14), independently of the end states, so the residual checks the solution.
    /// Computed on request: a sweep of outcomes does not pay for it.
    pub fn energy(&self) -> Energy {
        energy_budget(&self.params, &self.setup, &self.phases, &self.final_state)
    }

    /// The phase in force at `t`; at a transition, the one that begins there.
    pub fn phase_index_at(&self, t: f64) -> usize {
        self.phases.iter().rposition(|p| p.start <= t).unwrap_or(0)
    }

    /// The sample at `t` in phase `index`.
    pub fn sample_in(&self, index: usize, t: f64) -> Sample {
        let phase = &self.phases[index];
        let s = phase.state_at(&self.setup, t);
        Sample {
            t,
            normal: self.setup.normal(t),
            friction: phase.friction(&self.setup, &s),
            x: s.x,
            v: s.v,
            vx: s.vx,
            omega: s.omega,
            slip: self.setup.slip(&s),
            phase: index,
            kind: phase.kind,
            cart_stuck: phase.cart == Cart::Stuck,
        }
    }

    /// The sample at `t` (clamped to the contact); at a transition, the side of the phase that begins there.
    pub fn sample_at(&self, t: f64) -> Sample {
        let t = t.clamp(0.0, self.setup.duration);
        self.sample_in(self.phase_index_at(t), t)
    }

    /// `n` (at least 2) evenly spaced samples over [0, T], plus both sides of every transition, in time
    /// order, so that a force that jumps at a transition draws as a vertical step.
    pub fn series(&self, n: usize) -> Vec<Sample> {
        let n = n.max(2);
        let duration = self.setup.duration;
        let grid = |i: usize| {
            if i + 1 == n {
                duration
            } else {
                duration * i as f64 / (n - 1) as f64
            }
        };
        let last = self.phases.len() - 1;
        let mut out = Vec::with_capacity(n + 2 * last);
        let mut i = 0;
        for (index, phase) in self.phases.iter().enumerate() {
            if index > 0 {
                out.push(self.sample_in(index, phase.start));
            }
            while i < n && (grid(i) < phase.end || index == last) {
                let t = grid(i);
                if t > phase.start || index == 0 {
                    out.push(self.sample_in(index, t));
                }
                i += 1;
            }
            if index < last {
                out.push(self.sample_in(index, phase.end));
            }
        }
        out
    }

    /// The ball's phases: consecutive phases that differ only in what the cart does (it sticks, starts
    /// or turns) are one phase of the ball.
    pub fn ball_phases(&self) -> Vec<BallPhase> {
        let mut merged: Vec<BallPhase> = Vec::with_capacity(self.phases.len());
        for p in &self.phases {
            match merged.last_mut() {
                Some(last) if last.kind == p.kind && last.slip_sign == p.slip_sign => {
                    last.end = p.end
                }
                _ => merged.push(BallPhase {
                    kind: p.kind,
                    slip_sign: p.slip_sign,
                    start: p.start,
                    end: p.end,
                }),
            }
        }
        merged
    }

    /// The ball's phase kinds joined, e.g. `slide-grip-slide`.
    pub fn phase_summary(&self) -> String {
        self.ball_phases()
            .iter()
            .map(|p| p.kind.name())
            .collect::<Vec<_>>()
            .join("-")
    }

    /// True when the ball slides for the whole contact.
    pub fn slides_throughout(&self) -> bool {
        self.phases.iter().all(|p| p.kind == PhaseKind::Slide)
    }
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use super::*;

    /// A check that says "cancel" from its `n`th call on, counting the calls.
    fn cancel_from(n: usize, calls: &Cell<usize>) -> impl Fn() -> bool + '_ {
        move || {
            calls.set(calls.get() + 1);
            calls.get() >= n
        }
    }

    #[test]
    fn cancellation_is_asked_between_phases_on_every_model() {
        let base = Params {
            cart_mass: 0.001,
            stiffness: 9554.0,
            ..Params::default()
        };
        for params in [
            base,
            Params { chain: 4.0, ..base },
            Params {
                ball_stiffness: 1e6,
                ball_damping: 0.5,
                ..base
            },
        ] {
            let whole = solve(&params).unwrap();
            assert!(whole.phases.len() >= 3);
            let calls = Cell::new(0);
            let never = solve_cancellable(&params, &cancel_from(usize::MAX, &calls)).unwrap();
            assert_eq!(never.outcome, whole.outcome);
            assert!(calls.get() >= whole.phases.len());
            let calls = Cell::new(0);
            let cancelled = solve_cancellable(&params, &cancel_from(2, &calls));
            assert_eq!(cancelled.unwrap_err(), SolveError::Cancelled);
            assert_eq!(calls.get(), 2, "stops at the first check that says so");
        }
    }
}
