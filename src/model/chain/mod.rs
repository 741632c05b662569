//! A chain of masses and springs in place of the single cart (`--chain N`): N equal masses M/N in a line,
//! the ball touching the first, N springs of stiffness N k from the first through the last to the wall,
//! so that the static stiffness at the contact is k (N springs N k in series). N = 1 is the paper's cart.
//!
//! Each phase is solved in the chain's normal modes (nalgebra's `SymmetricEigen`), in closed form:
//! sliding, every mode is an oscillator forced through its share Φ_1j of the friction on the first mass;
//! gripping, the ball's effective mass m_eff rides on the first mass and the modes of that heavier chain
//! swing freely. Transitions follow the paper's rules (grip when |F_s| <= mu N at zero slip, else the
//! friction reverses; a broken grip slides the way F_s pulled), located by [`first_rise`] on the exact
//! expressions with curvature bounds from the modal amplitudes. A compliant ball on the chain is solved
//! by [`super::compliant`] (its grip is one damped modal system of ball and chain). String friction on the
//! cart is for the single cart only: a chain with it is refused.

pub mod modes;
pub mod motion;

use std::sync::{Arc, OnceLock};

use super::bounce::{
    Bounce, MAX_RADIANS, MAX_TRANSITIONS, Motion as PhaseMotion, Phase, PhaseKind, ROLLING,
    ROUNDING, SolveError, finish,
};
use super::cart::Cart;
use super::compliant::solve_compliant_cancellable;
use super::events::first_rise;
use super::limits;
use super::params::Params;
use super::setup::{Setup, State};
use super::transition::{Ball, Cause};
use modes::{MAX, Modes};
use motion::Motion;

/// The chain: its links, and its modes while the ball slides and while it grips.
#[derive(Clone, Debug)]
pub struct Chain {
    pub n: usize,
    /// M/N, kg.
    pub link_mass: f64,
    /// N k, N/m.
    pub link_stiffness: f64,
    pub slide: Modes,
    /// The gripping modes, computed when first needed (a compliant ball never needs them).
    grip: OnceLock<Modes>,
    m_eff: f64,
}

impl Chain {
    pub fn new(params: &Params, setup: &Setup) -> Chain {
        let n = params.chain as usize;
        let link_mass = params.cart_mass / n as f64;
        let link_stiffness = params.stiffness * n as f64;
        Chain {
            n,
            link_mass,
            link_stiffness,
            slide: Modes::new(n, link_mass, link_stiffness, 0.0),
            grip: OnceLock::new(),
            m_eff: setup.m_eff,
        }
    }

    /// The modes of the chain with the ball's m_eff riding on its first mass.
    pub fn grip(&self) -> &Modes {
        self.grip
            .get_or_init(|| Modes::new(self.n, self.link_mass, self.link_stiffness, self.m_eff))
    }

    /// The modes of a sliding (`dir` ±1) or gripping (`dir` 0) phase.
    pub fn modes(&self, dir: f64) -> &Modes {
        if dir == 0.0 { self.grip() } else { &self.slide }
    }

    /// Kinetic plus spring energy of the whole chain.
    pub fn energy(&self, s: &ChainState) -> f64 {
        let n = self.n;
        let kinetic: f64 = s.v[..n].iter().map(|v| v * v).sum::<f64>() * self.link_mass;
        let stretch: f64 = (0..n)
            .map(|i| {
                let e = if i + 1 < n {
                    s.x[i] - s.x[i + 1]
                } else {
                    s.x[i]
                };
                e * e
            })
            .sum::<f64>()
            * self.link_stiffness;
        0.5 * (kinetic + stretch)
    }
}

/// The ball and every mass of the chain at time `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainState {
    pub t: f64,
    pub vx: f64,
    pub omega: f64,
    /// Displacements of the masses, the first touching the ball (only the first `n` are used).
    pub x: [f64; MAX],
    pub v: [f64; MAX],
}

impl ChainState {
    /// The single cart as a chain: its only mass at the cart's displacement and velocity.
    pub fn from_contact(s: &State) -> ChainState {
        let mut chain = ChainState {
            t: s.t,
            vx: s.vx,
            omega: s.omega,
            x: [0.0; MAX],
            v: [0.0; MAX],
        };
        chain.x[0] = s.x;
        chain.v[0] = s.v;
        chain
    }

    /// The ball and the first mass.
    pub fn contact(&self) -> State {
        State {
            t: self.t,
            vx: self.vx,
            omega: self.omega,
            x: self.x[0],
            v: self.v[0],
        }
    }
}

/// The phase motion of a chain bounce, shared by the phase and its copies.
pub type ChainMotion = Arc<Motion>;

/// Solves one bounce on a chain of `params.chain` masses, for any N including 1 (where it reproduces the
/// single-cart solver to rounding; [`super::solve`] sends N = 1 to the single cart's own path).
pub fn solve_chain(params: &Params) -> Result<Bounce, SolveError> {
    solve_chain_cancellable(params, &|| false)
}

/// [`solve_chain`], abandoned when `cancelled` returns true (asked before every phase).
pub fn solve_chain_cancellable(
    params: &Params,
    cancelled: &impl Fn() -> bool,
) -> Result<Bounce, SolveError> {
    limits::bounded(params, || solve_links(params, cancelled))
}

fn solve_links(params: &Params, cancelled: &impl Fn() -> bool) -> Result<Bounce, SolveError> {
    params.validate()?;
    if params.ball_stiffness > 0.0 {
        return solve_compliant_cancellable(params, cancelled);
    }
    if params.cart_friction > 0.0 {
        return Err(SolveError::ChainStringFriction {
            chain: params.chain as usize,
        });
    }
    let setup = Setup::new(params);
    let chain = Arc::new(Chain::new(params, &setup));
    let radians = chain.slide.fastest.max(chain.grip().fastest) * setup.duration;
    if radians > MAX_RADIANS {
        return Err(SolveError::TooFast { radians });
    }
    let end = setup.duration;
    let first = setup.initial(params.spin);
    let mut state = ChainState {
        t: 0.0,
        vx: first.vx,
        omega: first.omega,
        x: [0.0; MAX],
        v: [0.0; MAX],
    };
    let incoming = setup.vx1.abs() + setup.r * params.spin.abs();
    let slip0 = setup.slip(&first);
    let mut ball = if slip0.abs() <= ROLLING * incoming {
        next(&chain, &setup, &state, Ball::Grip, Cause::Start)
    } else {
        Ball::Slide(slip0.signum())
    };
    let mut cause = Cause::Start;
    let mut phases = Vec::with_capacity(4);
    for _ in 0..MAX_TRANSITIONS {
        if cancelled() {
            return Err(SolveError::Cancelled);
        }
        let t0 = state.t;
        let dir = match ball {
            Ball::Slide(dir) => dir,
            Ball::Grip => 0.0,
        };
        let motion = Arc::new(Motion::new(chain.clone(), &setup, state, dir));
        let event = match ball {
            Ball::Slide(dir) => {
                // A slip that starts on its zero is measured from its start value.
                let slip_offset = if matches!(cause, Cause::SlipZero | Cause::GripBreak(_)) {
                    setup.slip(&motion.contact(&setup, t0).state)
                } else {
                    0.0
                };
                let f = |t: f64| {
                    let c = motion.contact(&setup, t);
                    let rate = -c.friction / setup.m_eff - c.accel;
                    [(-dir * (setup.slip(&c.state) - slip_offset), -dir * rate)]
                };
                let (curvature, terms) = motion.slip_curvature(&setup);
                let speeds = incoming + state.vx.abs() + setup.r * state.omega.abs() + terms;
                let step = setup.event_step(chain.slide.fastest);
                first_rise(f, t0, end, step, [curvature], [ROUNDING * speeds])
                    .map(|(t, _)| (t, Cause::SlipZero))
            }
            Ball::Grip => {
                let f = |t: f64| {
                    let c = motion.contact(&setup, t);
                    setup.grip_margins(t, c.friction, c.friction_rate)
                };
                let (curvature, terms) = motion.margin_curvature(&setup);
                let noise = ROUNDING * terms;
                let step = setup.event_step(chain.grip().fastest);
                first_rise(f, t0, end, step, [curvature; 2], [noise; 2]).map(|(t, branch)| {
                    let sign = if branch == 0 { 1.0 } else { -1.0 };
                    (t, Cause::GripBreak(sign))
                })
            }
        }
        // A transition within rounding of the end changes nothing.
        .filter(|&(t, _)| t < end * (1.0 - 1e-13));
        let t1 = event.map_or(end, |(t, _)| t);
        state = motion.full(&setup, t1);
        if t1 > t0 {
            phases.push(Phase {
                kind: if dir == 0.0 {
                    PhaseKind::Grip
                } else {
                    PhaseKind::Slide
                },
                slip_sign: dir as i8,
                cart: Cart::Moving(1),
                start: t0,
                end: t1,
                motion: PhaseMotion::Chain(motion),
            });
        }
        let Some((_, next_cause)) = event else {
            return Ok(finish(params, setup, phases, state.contact()));
        };
        cause = next_cause;
        ball = next(&chain, &setup, &state, ball, cause);
    }
    Err(SolveError::TooManyPhases)
}

/// What the ball does after `cause`: the paper's rules, as `transition::next` has them without string
/// friction. A broken grip slides the way F_s pulled; at zero slip the ball grips if the static friction
/// the gripping chain needs (read from the grip phase that would start here, so that the phase starts
/// inside its own margins) is at most mu N, or else slides the way F_s pulls (the friction reverses).
fn next(chain: &Arc<Chain>, setup: &Setup, state: &ChainState, ball: Ball, cause: Cause) -> Ball {
    match cause {
        Cause::GripBreak(sign) => Ball::Slide(sign),
        Cause::Start if ball != Ball::Grip => ball,
        _ => {
            let grip = Motion::new(chain.clone(), setup, *state, 0.0);
            let static_friction = grip.contact(setup, state.t).friction;
            if static_friction.abs() <= setup.mu * setup.normal(state.t) {
                Ball::Grip
            } else {
                Ball::Slide(static_friction.signum())
            }
        }
    }
}
