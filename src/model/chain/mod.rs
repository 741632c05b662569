//! A chain of masses and springs in place of the single cart (`--chain N`): N equal masses M/N in a line,
//! the ball touching the first, N springs of stiffness N k from the first through the last to the wall,
//! so that the static stiffness at the contact is k (N springs N k in series). N = 1 is the paper's cart.
//!
//! Each phase is solved in the chain's normal modes (nalgebra's `SymmetricEigen`), in closed form:
//! sliding, every mode is an oscillator forced through its share Φ_1j of the friction on the first mass;
//! gripping, the ball's effective mass m_eff rides on the first mass and the modes of that heavier chain
//! swing freely. Transitions follow the paper's rules (grip when |F_s| <= mu N at zero slip, else the
//! friction reverses; a broken grip slides the way F_s pulled), located by [`super::events`] on the exact
//! expressions with curvature bounds from the modal amplitudes. A compliant ball on the chain is its own
//! model, [`super::compliant`] (its grip is one damped modal system of ball and chain).
//!
//! String friction (Sec. IV's proposed enhancement) acts on the first mass, the one the ball touches:
//! a constant -d F_c while it moves in direction d, and while the net push on it (the ball's friction
//! less the link spring N k (X_1 - X_2)) stays within F_c, it holds it still (`string.rs`). The modes
//! that follow each event are chosen by the single cart's rules ([`super::transition`]), the first mass
//! (with the ball's m_eff while it grips) in the cart's place. On a free frame the string friction acts
//! between the first mass and the frame, and a first mass held to the frame makes one body with it, the
//! links behind forming a ring (`ring.rs`).

#[cfg(test)]
mod bounds;
pub mod modes;
pub mod motion;
pub mod ring;
pub mod ring_coordinates;
mod search;
mod spare;
mod string;

use std::cell::RefCell;
use std::sync::{Arc, OnceLock};

use super::contact::{Ball, Cart, Cause, Contact, Found, Mode, PhaseMotion, ROLLING};
use super::error::{MAX_RADIANS, SolveError};
use super::memo::{Slot, reuse};
use super::params::Params;
use super::quadrature::integrate;
use super::setup::{Setup, State};
use modes::{MAX, Modes};
use motion::Motion;
pub use spare::ChainMotion;

/// The chain: its links, and its modes while the ball slides and while it grips.
#[derive(Clone, Debug)]
pub struct Chain {
    pub n: usize,
    /// M/N, kg.
    pub link_mass: f64,
    /// N k, N/m.
    pub link_stiffness: f64,
    /// The frame's mass M_t when the last spring is tied to a free frame (`None`: the wall). The frame
    /// is then the last of the modes' masses, after the links.
    pub frame: Option<f64>,
    pub slide: Modes,
    /// The gripping modes, computed when first needed (a compliant ball never needs them).
    grip: OnceLock<Modes>,
    /// The modes of the masses behind a first mass held by string friction, when first needed.
    clamped: OnceLock<Modes>,
    /// On a free frame, the ring's modes of a first mass held to the frame, sliding and gripping.
    ring: [OnceLock<Modes>; 2],
    m_eff: f64,
}

thread_local! {
    static LAST_CHAIN: Slot<[u64; 5], Arc<Chain>> = const { RefCell::new(None) };
}

impl Chain {
    /// The chain for `params`, shared with the last bounce solved on this thread if it had the same one.
    pub fn shared(params: &Params, setup: &Setup) -> Arc<Chain> {
        reuse(&LAST_CHAIN, Chain::key(params, setup), || {
            Arc::new(Chain::new(params, setup))
        })
    }

    /// Everything a chain is built from, exactly.
    pub fn key(params: &Params, setup: &Setup) -> [u64; 5] {
        [
            params.chain.to_bits(),
            params.cart_mass.to_bits(),
            params.stiffness.to_bits(),
            setup.m_eff.to_bits(),
            params.frame_mass.to_bits(),
        ]
    }

    pub fn new(params: &Params, setup: &Setup) -> Chain {
        let n = params.chain as usize;
        let link_mass = params.cart_mass / n as f64;
        let link_stiffness = params.stiffness * n as f64;
        // Without springs the frame never moves: the chain is then solved as on the wall.
        let frame = setup.frame_mass.filter(|_| params.stiffness > 0.0);
        Chain {
            n,
            link_mass,
            link_stiffness,
            frame,
            slide: Chain::modes_with(n, link_mass, link_stiffness, 0.0, frame),
            grip: OnceLock::new(),
            clamped: OnceLock::new(),
            ring: [OnceLock::new(), OnceLock::new()],
            m_eff: setup.m_eff,
        }
    }

    /// Refuses on a free frame what is not solved there: string friction without a spring (but under
    /// the rigid ball on a chain), or (`compliant` false) under the rigid ball on one mass here (the
    /// single cart's is [`super::frame::FramedCart`]'s).
    pub fn solvable_on_frame(
        params: &Params,
        setup: &Setup,
        compliant: bool,
    ) -> Result<(), SolveError> {
        if setup.frame_mass.is_none() {
            return Ok(());
        }
        if params.cart_friction > 0.0 {
            // The rigid ball's chain without springs is solved as on the wall; the compliant ball's
            // meets its first mass alone, as on one.
            let what = if params.stiffness == 0.0 && (compliant || params.chain <= 1.0) {
                Some("string friction (--cart-friction) without a spring (--stiffness 0)")
            } else if params.chain > 1.0 {
                None
            } else {
                (!compliant).then_some("string friction (--cart-friction)")
            };
            if let Some(what) = what {
                return Err(SolveError::FreeFrame { what });
            }
        }
        Ok(())
    }

    /// The modes of `n` links with `extra` on the first, tied to the wall or to a free `frame`.
    fn modes_with(n: usize, link: f64, kappa: f64, extra: f64, frame: Option<f64>) -> Modes {
        match frame {
            None => Modes::new(n, link, kappa, extra),
            Some(frame) => Modes::framed(n, link, kappa, extra, frame),
        }
    }

    /// The modes of the chain with the ball's m_eff riding on its first mass.
    pub fn grip(&self) -> &Modes {
        self.grip.get_or_init(|| {
            Chain::modes_with(
                self.n,
                self.link_mass,
                self.link_stiffness,
                self.m_eff,
                self.frame,
            )
        })
    }

    /// Where the frame's displacement and velocity sit in a [`ChainState`]: after the links (0 when
    /// the chain is tied to the wall, which has no entry).
    pub fn frame_index(&self) -> usize {
        if self.frame.is_some() { self.n } else { 0 }
    }

    /// The modes of a phase with the first mass held by string friction, sliding (`dir` ±1) or gripping
    /// (`dir` 0): on the wall those of the masses behind it ([`Chain::clamped`]); on a free frame the
    /// ring's ([`Modes::ring`]: the first mass and the frame one body, with m_eff while the ball grips).
    pub fn held(&self, dir: f64) -> &Modes {
        let Some(frame) = self.frame else {
            return self.clamped();
        };
        let grip = usize::from(dir == 0.0);
        self.ring[grip].get_or_init(|| {
            let extra = if grip == 1 { self.m_eff } else { 0.0 };
            let body = self.link_mass + frame;
            Modes::ring(self.n, self.link_mass, self.link_stiffness, body, extra)
        })
    }

    /// On a free frame, the ring of a first mass held to the frame, sliding ([`Chain::held`]: the body
    /// B first, the links behind), written as the chain a compliant ball's grip is solved on
    /// ([`super::compliant::GripModes`]): its slide modes are the ring's, with the rigid translation,
    /// and the ball's spring pulls on B, their first mass. Laid out as a framed chain of N - 1 links
    /// (N masses, the last link in the frame's place); only its modes and its link mass (the lighter,
    /// for the grip's rate bound) are read. `None` on the wall or for one mass.
    pub fn held_ring(&self) -> Option<Chain> {
        self.frame.filter(|_| self.n > 1)?;
        Some(Chain {
            n: self.n - 1,
            link_mass: self.link_mass,
            link_stiffness: self.link_stiffness,
            frame: self.frame,
            slide: self.held(1.0).clone(),
            grip: OnceLock::new(),
            clamped: OnceLock::new(),
            ring: [OnceLock::new(), OnceLock::new()],
            m_eff: self.m_eff,
        })
    }

    /// The modes of the masses behind a held first mass.
    pub fn clamped(&self) -> &Modes {
        self.clamped
            .get_or_init(|| Modes::clamped(self.n - 1, self.link_mass, self.link_stiffness))
    }

    /// The spring force holding the first mass back, N k (X_1 - X_2) (k X_1 for one mass on the wall,
    /// k (X_1 - X_f) for one on a frame).
    pub fn link_force(&self, s: &ChainState) -> f64 {
        let behind = if self.slide.n > 1 { s.x[1] } else { 0.0 };
        self.link_stiffness * (s.x[0] - behind)
    }

    /// The modes of a sliding (`dir` ±1) or gripping (`dir` 0) phase.
    pub fn modes(&self, dir: f64) -> &Modes {
        if dir == 0.0 { self.grip() } else { &self.slide }
    }

    /// Kinetic plus spring energy of the whole chain (the last spring's stretch measured from the
    /// frame when it is free; the frame's own kinetic energy is apart, [`Setup::frame_energy`]).
    pub fn energy(&self, s: &ChainState) -> f64 {
        let n = self.n;
        let anchor = if self.frame.is_some() { s.x[n] } else { 0.0 };
        let kinetic: f64 = s.v[..n].iter().map(|v| v * v).sum::<f64>() * self.link_mass;
        let stretch: f64 = (0..n)
            .map(|i| {
                let e = if i + 1 < n {
                    s.x[i] - s.x[i + 1]
                } else {
                    s.x[i] - anchor
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
    /// Displacements of the masses, the first touching the ball (only the first `n` are used), and
    /// after them the free frame's.
    pub x: [f64; MAX],
    pub v: [f64; MAX],
    /// Where the frame's entry is in `x` and `v` ([`Chain::frame_index`]; 0: tied to the wall).
    pub frame: usize,
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
            frame: 0,
        };
        chain.x[0] = s.x;
        chain.v[0] = s.v;
        chain
    }

    /// The ball and the first mass: its displacement relative to the frame, its own velocity.
    pub fn contact(&self) -> State {
        let anchor = if self.frame > 0 {
            self.x[self.frame]
        } else {
            0.0
        };
        State {
            t: self.t,
            vx: self.vx,
            omega: self.omega,
            x: self.x[0] - anchor,
            v: self.v[0],
        }
    }
}

impl PhaseMotion for Motion {
    fn state_at(&self, setup: &Setup, t: f64) -> State {
        self.contact(setup, t).state
    }

    fn friction(&self, setup: &Setup, state: &State) -> f64 {
        self.contact(setup, state.t).friction
    }

    fn initial(&self) -> State {
        self.start.contact()
    }

    /// A rigid ball has no contact patch.
    fn patch_at(&self, _: &Setup, _: f64) -> Option<(f64, f64)> {
        None
    }

    /// Every mass's kinetic energy and every spring's.
    fn surface_energy(&self, setup: &Setup, at: &State) -> f64 {
        self.chain().energy(&self.full(setup, at.t))
    }

    /// ∫ F (v_x - r omega - V_1) dt, on panels of the chain's fastest mode or the normal force.
    fn friction_work(&self, setup: &Setup, start: f64, end: f64) -> f64 {
        let power = |t: f64| {
            let c = self.contact(setup, t);
            c.friction * setup.slip(&c.state)
        };
        integrate(
            power,
            start,
            end,
            2.0 / self.chain().slide.fastest.max(setup.w),
        )
    }

    fn fastest(&self, _: &Setup) -> f64 {
        self.chain().slide.fastest
    }

    /// A rigid ball holds no tangential energy.
    fn ball_spring_energy(&self, _: &Setup, _: f64) -> f64 {
        0.0
    }

    fn dashpot_loss(&self, _: &Setup, _: f64, _: f64) -> f64 {
        0.0
    }

    /// The frame's velocity along the surface (0 clamped).
    fn frame_velocity(&self, setup: &Setup, t: f64) -> f64 {
        match self.chain().frame_index() {
            0 => 0.0,
            frame => self.full(setup, t).v[frame],
        }
    }
}

/// The rigid ball on a chain of `params.chain` masses, for any N including 1 (where it reproduces the
/// single cart to rounding; [`super::solve()`] sends N = 1 to the single cart's own model).
pub struct ChainOfMasses {
    chain: Arc<Chain>,
    /// True with string friction on the first mass.
    string: bool,
    spin: f64,
    /// |v_x1| + r |omega1|: the scale of the speeds, for the event functions' rounding.
    incoming: f64,
}

impl ChainOfMasses {
    /// The model for `params`, refused when the chain oscillates too fast to resolve, and on a free
    /// frame where [`Chain::solvable_on_frame`] says so.
    pub fn new(params: &Params, setup: &Setup) -> Result<Self, SolveError> {
        Chain::solvable_on_frame(params, setup, false)?;
        let chain = Chain::shared(params, setup);
        let mut fastest = chain.slide.fastest.max(chain.grip().fastest);
        if params.cart_friction > 0.0 && chain.frame.is_some() {
            fastest = fastest
                .max(chain.held(1.0).fastest)
                .max(chain.held(0.0).fastest);
        }
        let radians = fastest * setup.duration;
        if radians > MAX_RADIANS {
            return Err(SolveError::TooFast { radians });
        }
        Ok(ChainOfMasses {
            chain,
            string: params.cart_friction > 0.0,
            spin: params.spin,
            incoming: setup.vx1.abs() + setup.r * params.spin.abs(),
        })
    }
}

impl Contact for ChainOfMasses {
    type State = ChainState;
    type Motion = ChainMotion;
    type Probe = ();

    fn start(&self, setup: &Setup) -> (ChainState, Mode) {
        let first = setup.initial(self.spin);
        let state = ChainState {
            t: 0.0,
            vx: first.vx,
            omega: first.omega,
            x: [0.0; MAX],
            v: [0.0; MAX],
            frame: self.chain.frame_index(),
        };
        let slip0 = setup.slip(&first);
        let rolling = slip0.abs() <= ROLLING * self.incoming;
        if self.string {
            let arriving = if rolling {
                Ball::Grip
            } else {
                Ball::Slide(slip0.signum())
            };
            let mode = string::next(
                &self.chain,
                setup,
                &state,
                arriving,
                Cart::Moving(1),
                Cause::Start,
            );
            return (state, mode);
        }
        let ball = if rolling {
            next(&self.chain, setup, &state, Ball::Grip, Cause::Start)
        } else {
            Ball::Slide(slip0.signum())
        };
        (state, (ball, Cart::Moving(1)))
    }

    fn time(state: &ChainState) -> f64 {
        state.t
    }

    fn contact(state: &ChainState) -> State {
        state.contact()
    }

    fn motion(&self, setup: &Setup, state: &ChainState, (ball, cart): Mode) -> ChainMotion {
        let dir = match ball {
            Ball::Slide(dir) => dir,
            Ball::Grip => 0.0,
        };
        if self.string {
            ChainMotion::new(&self.chain, setup, state, dir, cart)
        } else {
            // Searched by Taylor bounds (`search.rs`).
            ChainMotion::searched(&self.chain, setup, state, dir, cart)
        }
    }

    #[inline(always)]
    fn first_event(
        &self,
        setup: &Setup,
        motion: &ChainMotion,
        state: &ChainState,
        (ball, cart): Mode,
        cause: Cause,
    ) -> Found<()> {
        if self.string {
            let event = string::first_event(self, setup, motion, state, (ball, cart), cause);
            return Found { event, last: None };
        }
        let event = match ball {
            Ball::Slide(dir) => {
                let speeds = self.incoming + state.vx.abs() + setup.r * state.omega.abs();
                search::slide(setup, motion, (state.t, dir, cause), speeds)
            }
            Ball::Grip => search::grip(setup, motion, state.t),
        };
        Found { event, last: None }
    }

    fn state_at(&self, setup: &Setup, motion: &ChainMotion, t: f64, _: Option<()>) -> ChainState {
        motion.full(setup, t)
    }

    fn next(
        &self,
        setup: &Setup,
        state: &mut ChainState,
        (ball, cart): Mode,
        cause: Cause,
    ) -> Mode {
        if self.string {
            if cause == Cause::CartStop {
                // The first mass joins the frame (stops on the wall).
                state.v[0] = if state.frame > 0 {
                    state.v[state.frame]
                } else {
                    0.0
                };
            }
            return string::next(&self.chain, setup, state, ball, cart, cause);
        }
        (next(&self.chain, setup, state, ball, cause), cart)
    }
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
            let static_friction = Motion::grip_friction(chain, setup, state);
            if static_friction.abs() <= setup.mu * setup.normal(state.t) {
                Ball::Grip
            } else {
                Ball::Slide(static_friction.signum())
            }
        }
    }
}
