//! A tangentially compliant ball (issue 6, part 3), on the single cart or on a chain of masses.
//!
//! The ball's contact region is a massless tangential spring k_b with a dashpot c_b between the ball's
//! contact point (coordinate u, velocity u' = v_x - r omega, effective mass m_eff) and the contact patch
//! (position p). With the stretch e = u - p the force on the ball, positive backward, is
//! F = k_b e + c_b e'; the massless patch passes it on to the cart (the chain's first mass), which feels
//! +F (Eq. (3)).
//!
//! - Slide: the patch slides on the cart and F = dir mu N(t). The ball and the cart move exactly as for
//!   a rigid ball ([`Slide`], the single cart moving on a free frame by [`FrameMotion`], or the chain's
//!   [`ChainMotion`], built over a finished phase's storage); the stretch follows c_b e' + k_b e = F(t)
//!   (e = F/k_b without damping), solved in closed form ([`Stretch`]). The patch slips at
//!   p' - V = (v_x - r omega - V) - e'; the slide ends when that slip reaches zero, and the patch then
//!   always grips (a reversed slide would need the opposite force, which the continuous stretch and the
//!   slip's sign exclude).
//! - Grip: the patch moves with the cart. Ball, stretch and cart (or chain) form one linear, not
//!   proportionally damped system, solved in its complex modes ([`CompliantGrip`] on the single cart,
//!   [`ChainGrip`] on a chain). The grip breaks when |F| reaches mu N, into a slide the way F points.
//!
//! - String friction on the single cart (Sec. IV's first enhancement): the cart moves against -dir F_c
//!   (the rigid [`Slide`]'s push while the patch slides; while it grips, the constant push enters the
//!   grip's linear system through Duhamel's integral, or on a free cart as the uniformly accelerated
//!   particular solution) and the phase also ends when V reaches zero; or it is held still (the rigid
//!   ball's held slide; in a grip the stretch alone, a damped oscillator on a still surface) and the
//!   phase also ends when the net force on it, F - k X, reaches ±F_c. The ball's force F is
//!   continuous across every transition, so a stopped cart is held while |F - k X| <= F_c and otherwise
//!   moves the way it is pushed ([`transition::at_rest`]).
//! - String friction on a chain's first mass: sliding, the chain moves as for the rigid ball with string
//!   friction (pushed, or held with the masses behind in their clamped modes); gripping a moving first
//!   mass, the push -d F_c enters the chain's grip modes through Duhamel's integral ([`ChainGrip`]);
//!   gripping a held one, the stretch rings down on a still surface while the masses behind swing
//!   ([`HeldChainGrip`]). The events and rules are the single cart's, the first mass in the cart's place
//!   and its link spring N k (X_1 - X_2) in place of k X.
//! - String friction on the single cart tied to a free frame (issue 23): it acts between the cart and
//!   the frame, -d F_c on the cart and +d F_c on the frame while the cart moves relative to the frame in
//!   direction d. Moving, the pair is internal: each of the framed chain's modes (one mass and the
//!   frame) is pushed by (Φ_1j - Φ_fj)(-d F_c), the translation by nothing, sliding as a step forcing
//!   and gripping through Duhamel's integral ([`ChainGrip`]), and the phase also ends when V - V_f
//!   reaches zero. Held, the cart and the frame are one free body of mass M + M_t ([`HeldOnFrame`]),
//!   and the phase also ends when the push the string friction holds, M_t F/(M + M_t) - k y, reaches
//!   ±F_c; a stopping cart is held or pushed on by that push ([`transition::at_rest`]). Without a
//!   spring it is refused (`SolveError::FreeFrame`).
//! - String friction on a chain's first mass on a free frame: moving, as on the single framed cart,
//!   each of the framed chain's modes pushed by (Φ_1j - Φ_fj)(-d F_c), sliding by the rigid ball's
//!   chain and gripping through Duhamel's integral ([`ChainGrip`]). Held, the first mass and the frame
//!   are one body B of mass m_B = M/N + M_t with the links behind a ring tied to it at both ends (the
//!   rigid ball's, `chain/ring.rs`): sliding, the rigid ball's held phase in the ring's modes; gripping,
//!   the ball's spring and dashpot on B, the grip's damped modal system on the ring with its rigid
//!   translation taken out ([`HeldRingGrip`]). The phase also ends when the force the frame must give
//!   the first mass, F - T_1 - (M/N) a_B (T_1 = N k (X_1 - X_2), a_B = (F - T_1 + T_N)/m_B), reaches
//!   ±F_c, and a stopping first mass is held or pushed on by that force ([`transition::at_rest`]).
//!
//! Chatter: an undamped stiff ball may switch many times; every phase advances time and the solver stops
//! after [`super::error::MAX_TRANSITIONS`] with `SolveError::TooManyPhases`.

mod cart_grip;
mod chain_grip;
mod held_chain;
mod held_frame;
mod held_ring;
mod slip_sums;
mod stretch;

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

pub use cart_grip::{Compliance, CompliantGrip};
pub use chain_grip::{ChainGrip, GripModes, Stage};
pub use held_chain::HeldChainGrip;
pub use held_frame::{FrameHold, HeldOnFrame};
pub use held_ring::HeldRingGrip;
pub use stretch::Stretch;

use std::cell::RefCell;

use super::cart::Slide;
use super::chain::{Chain, ChainMotion, ChainState, ring};
use super::contact::{Ball, Cart, Cause, Contact, Found, Mode, PhaseMotion, ROLLING, ROUNDING};
use super::error::{MAX_RADIANS, SolveError};
use super::events::first_rise_from_tangent;
use super::frame::{FrameMotion, FrameState, FramedCart};
use super::memo::{Slot, reuse};
use super::params::Params;
use super::quadrature::integrate;
use super::recent::Recent;
use super::setup::{Setup, State};
use super::transition;
use super::units::brief;
use cart_grip::EXP_ROUNDING;

/// The ball's contact spring and dashpot.
#[derive(Clone, Copy, Debug)]
pub struct BallSpring {
    /// k_b, N/m.
    pub kb: f64,
    /// c_b = 2 zeta sqrt(k_b m_eff), N s/m.
    pub cb: f64,
}

impl BallSpring {
    pub fn new(params: &Params, setup: &Setup) -> Self {
        let kb = params.ball_stiffness;
        BallSpring {
            kb,
            cb: 2.0 * params.ball_damping * (kb * setup.m_eff).sqrt(),
        }
    }
}

/// How the ball and what it touches move while the patch slides: as for a rigid ball.
#[derive(Clone, Debug)]
pub enum Rigid {
    Cart(Slide),
    Chain(ChainMotion),
    /// The single cart on a free frame, moving relative to it: the rigid ball's [`FrameMotion`], with
    /// the frame's displacement at the start (for the whole state).
    Frame(Box<FrameMotion>, f64),
}

/// A sliding phase of the compliant ball (the ball's spring and dashpot are its stretch's).
#[derive(Clone, Debug)]
pub struct CompliantSlide {
    pub rigid: Rigid,
    pub stretch: Stretch,
}

/// A phase of the compliant ball, with its patch where it ends.
#[derive(Clone, Debug)]
pub struct CompliantMotion {
    pub phase: CompliantPhase,
    /// The patch at the phase's end, kept when the driver takes the state there.
    end: EndPatch,
}

impl From<CompliantPhase> for CompliantMotion {
    fn from(phase: CompliantPhase) -> Self {
        CompliantMotion {
            phase,
            end: EndPatch::new(),
        }
    }
}

/// (t, e, the patch's slip) where the driver took a phase's state ([`Contact::state_at`], at its end),
/// so that the bounce's final patch is not evaluated again (a whole grip's or slide's closed form);
/// any other time is evaluated. Written only by the driver, before the phase is stored and shared;
/// the atomics make it `Sync` at the cost of plain loads and stores.
#[derive(Debug)]
struct EndPatch([AtomicU64; 3]);

impl EndPatch {
    /// Nothing kept: t is NaN, equal to no time.
    fn new() -> Self {
        EndPatch([f64::NAN, 0.0, 0.0].map(|x| AtomicU64::new(x.to_bits())))
    }

    fn keep(&self, t: f64, e: f64, slip: f64) {
        for (slot, x) in self.0.iter().zip([t, e, slip]) {
            slot.store(x.to_bits(), Ordering::Relaxed);
        }
    }

    /// (e, the patch's slip) if they were kept at `t`.
    #[inline]
    fn at(&self, t: f64) -> Option<(f64, f64)> {
        let [kept, e, slip] = self
            .0
            .each_ref()
            .map(|x| f64::from_bits(x.load(Ordering::Relaxed)));
        (kept == t).then_some((e, slip))
    }
}

impl Clone for EndPatch {
    fn clone(&self) -> Self {
        EndPatch(
            self.0
                .each_ref()
                .map(|x| AtomicU64::new(x.load(Ordering::Relaxed))),
        )
    }
}

/// The closed form of a phase of the compliant ball.
#[derive(Clone, Debug)]
pub enum CompliantPhase {
    Slide(CompliantSlide),
    Grip(Box<CompliantGrip>),
    ChainGrip(Box<ChainGrip>),
    HeldChainGrip(Box<HeldChainGrip>),
    /// The single cart held to a free frame by string friction.
    HeldOnFrame(Box<HeldOnFrame>),
    /// The grip on a chain's first mass held to a free frame by string friction.
    HeldRingGrip(Box<HeldRingGrip>),
}

/// Everything at one instant of a compliant phase.
#[derive(Clone, Copy, Debug)]
pub struct Point {
    pub state: State,
    /// The force on the ball, positive backward, N.
    pub friction: f64,
    /// Its rate, N/s.
    pub friction_rate: f64,
    /// The stretch e, m, its rate and second derivative.
    pub e: f64,
    pub de: f64,
    pub dde: f64,
    /// While sliding, the rate of the rigid ball's slip v_x - r omega - V (0 in a grip).
    pub slip_rate: f64,
    /// The contact mass's acceleration V' (0 held still).
    pub accel: f64,
    /// The velocity and acceleration along the surface of the frame the contact mass is tied to by
    /// its spring and its string friction (0 clamped; a free frame's on a chain).
    pub frame: (f64, f64),
}

impl CompliantSlide {
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        let (e, de, dde) = self.stretch.at(setup.w, t);
        let (state, friction, friction_rate, slip_rate, accel, frame) = match &self.rigid {
            Rigid::Cart(slide) => {
                let (state, friction) = slide.evaluate(setup, t);
                let accel = slide.cart_acceleration(setup, &state, friction);
                (
                    state,
                    friction,
                    slide.dir * setup.friction_limit_rate(t),
                    slide.slip_rate(setup, &state, friction),
                    accel,
                    (0.0, 0.0),
                )
            }
            Rigid::Chain(motion) => {
                let c = motion.contact(setup, t);
                let slip_rate = -c.friction / setup.m_eff - c.accel;
                let friction_rate = motion.dir * setup.friction_limit_rate(t);
                (
                    c.state,
                    c.friction,
                    friction_rate,
                    slip_rate,
                    c.accel,
                    c.frame,
                )
            }
            // The frame's closed form carries the friction's rate.
            Rigid::Frame(motion, _) => {
                let c = motion.sliding_at(setup, t);
                let slip_rate = -c.friction / setup.m_eff - c.accel;
                (
                    c.state,
                    c.friction,
                    c.friction_rate,
                    slip_rate,
                    c.accel,
                    c.frame,
                )
            }
        };
        Point {
            state,
            friction,
            friction_rate,
            e,
            de,
            dde,
            slip_rate,
            accel,
            frame,
        }
    }

    fn dir(&self) -> f64 {
        match &self.rigid {
            Rigid::Cart(slide) => slide.dir,
            Rigid::Chain(motion) => motion.dir,
            Rigid::Frame(motion, _) => motion.dir,
        }
    }

    /// The patch's slip on the cart, (v_x - r omega - V) - e', and its rate.
    #[inline]
    fn patch_slip(&self, setup: &Setup, p: &Point) -> (f64, f64) {
        (setup.slip(&p.state) - p.de, p.slip_rate - p.dde)
    }

    /// A bound on the rigid slip's |slip''|, the size of the terms the slip is summed from beyond the
    /// speeds of the ball and the contact mass, and the fastest rate of the cart or chain.
    fn slip_bounds(&self, setup: &Setup) -> (f64, f64, f64) {
        match &self.rigid {
            Rigid::Cart(slide) => (slide.curvature(setup).0, 0.0, setup.omega_slide),
            Rigid::Chain(motion) => {
                let (curvature, terms) = motion.slip_curvature(setup);
                (curvature, terms, motion.chain().slide.fastest)
            }
            Rigid::Frame(motion, _) => {
                let (curvature, terms) = motion.slip_bounds(setup);
                (curvature, terms, motion.fastest(setup))
            }
        }
    }
}

impl CompliantMotion {
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        match &self.phase {
            CompliantPhase::Slide(s) => s.at(setup, t),
            CompliantPhase::Grip(g) => g.at(setup, t),
            CompliantPhase::ChainGrip(g) => g.at(setup, t),
            CompliantPhase::HeldChainGrip(g) => g.at(setup, t),
            CompliantPhase::HeldOnFrame(h) => h.at(t),
            CompliantPhase::HeldRingGrip(g) => g.at(setup, t),
        }
    }

    /// The slip of the patch on the cart (0 in a grip).
    pub fn patch_slip(&self, setup: &Setup, t: f64) -> f64 {
        self.stretch_and_patch_slip(setup, t).1
    }

    /// The stretch e and the patch's slip on the cart at `t`, from one evaluation (none at the
    /// phase's end, where the driver took the state).
    pub fn stretch_and_patch_slip(&self, setup: &Setup, t: f64) -> (f64, f64) {
        if let Some(kept) = self.end.at(t) {
            return kept;
        }
        match &self.phase {
            CompliantPhase::Slide(s) => {
                let p = s.at(setup, t);
                (p.e, s.patch_slip(setup, &p).0)
            }
            CompliantPhase::Grip(_)
            | CompliantPhase::ChainGrip(_)
            | CompliantPhase::HeldChainGrip(_)
            | CompliantPhase::HeldRingGrip(_) => (self.at(setup, t).e, 0.0),
            CompliantPhase::HeldOnFrame(h) => h.inner.stretch_and_patch_slip(&h.hold.body, t),
        }
    }

    pub fn initial(&self) -> State {
        match &self.phase {
            CompliantPhase::Slide(s) => match &s.rigid {
                Rigid::Cart(slide) => slide.start,
                Rigid::Chain(motion) => motion.start.contact(),
                Rigid::Frame(motion, _) => motion.start.s,
            },
            CompliantPhase::Grip(g) => g.start,
            CompliantPhase::ChainGrip(g) => g.start.contact(),
            CompliantPhase::HeldChainGrip(g) => g.ball.start,
            CompliantPhase::HeldOnFrame(h) => h.initial(),
            CompliantPhase::HeldRingGrip(g) => g.start.contact(),
        }
    }

    pub fn spring(&self) -> BallSpring {
        match &self.phase {
            CompliantPhase::Slide(s) => s.stretch.spring,
            CompliantPhase::Grip(g) => BallSpring {
                kb: g.compliance.kb,
                cb: g.compliance.cb,
            },
            CompliantPhase::HeldChainGrip(g) => BallSpring {
                kb: g.ball.compliance.kb,
                cb: g.ball.compliance.cb,
            },
            CompliantPhase::ChainGrip(g) => g.modes.spring(),
            CompliantPhase::HeldOnFrame(h) => h.inner.spring(),
            CompliantPhase::HeldRingGrip(g) => g.grip.modes.spring(),
        }
    }

    /// The kinetic and spring energy of the whole chain at `t` (`None` on the single cart).
    pub fn chain_energy(&self, setup: &Setup, t: f64) -> Option<f64> {
        match &self.phase {
            CompliantPhase::Slide(CompliantSlide {
                rigid: Rigid::Chain(motion),
                ..
            }) => Some(motion.chain().energy(&motion.full(setup, t))),
            CompliantPhase::ChainGrip(g) => Some(g.modes.chain().energy(&g.full(setup, t))),
            CompliantPhase::HeldChainGrip(g) => Some(g.chain.chain().energy(&g.full(setup, t))),
            CompliantPhase::HeldOnFrame(h) => Some(h.hold.chain.energy(&h.full(t))),
            CompliantPhase::HeldRingGrip(g) => Some(g.chain.energy(&g.full(setup, t))),
            _ => None,
        }
    }

    /// The fastest rate in the phase, rad/s (for quadrature panels).
    pub fn fastest(&self, setup: &Setup) -> f64 {
        match &self.phase {
            CompliantPhase::Slide(s) => {
                let l = if s.stretch.damped() {
                    s.stretch.lambda()
                } else {
                    0.0
                };
                l.max(s.slip_bounds(setup).2)
            }
            CompliantPhase::Grip(g) => g.compliance.fastest,
            CompliantPhase::ChainGrip(g) => g.modes.fastest,
            CompliantPhase::HeldRingGrip(g) => g.grip.modes.fastest,
            CompliantPhase::HeldChainGrip(g) => g.fastest(),
            CompliantPhase::HeldOnFrame(h) => h.inner.fastest(&h.hold.body),
        }
    }

    /// ∫ f over [start, end] by Gauss-Legendre, on panels of the transient's scale until it has died
    /// out and of the cart's after.
    pub fn integrate(&self, setup: &Setup, f: impl Fn(f64) -> f64, start: f64, end: f64) -> f64 {
        let w = setup.w;
        match &self.phase {
            CompliantPhase::Slide(s) => {
                let split = s.stretch.settled().clamp(start, end);
                let fine = 2.0 / self.fastest(setup).max(w);
                let coarse = 2.0 / s.slip_bounds(setup).2.max(w);
                integrate(&f, start, split, fine) + integrate(&f, split, end, coarse)
            }
            CompliantPhase::Grip(_)
            | CompliantPhase::ChainGrip(_)
            | CompliantPhase::HeldChainGrip(_)
            | CompliantPhase::HeldRingGrip(_) => {
                integrate(&f, start, end, 2.0 / self.fastest(setup).max(w))
            }
            CompliantPhase::HeldOnFrame(h) => h.inner.integrate(&h.hold.body, f, start, end),
        }
    }
}

impl PhaseMotion for CompliantMotion {
    fn state_at(&self, setup: &Setup, t: f64) -> State {
        self.at(setup, t).state
    }

    fn friction(&self, setup: &Setup, state: &State) -> f64 {
        self.at(setup, state.t).friction
    }

    fn initial(&self) -> State {
        CompliantMotion::initial(self)
    }

    fn patch_at(&self, setup: &Setup, t: f64) -> Option<(f64, f64)> {
        Some(self.stretch_and_patch_slip(setup, t))
    }

    /// The whole chain's energy on a chain, the cart's and its spring's on the single cart.
    fn surface_energy(&self, setup: &Setup, at: &State) -> f64 {
        self.chain_energy(setup, at.t)
            .unwrap_or_else(|| setup.cart_energy(at))
    }

    /// ∫ F (p' - V) dt: the friction works against the patch's slip on the surface, not the contact
    /// point's (the stretch takes the rest, and gives it back or loses it in the dashpot).
    fn friction_work(&self, setup: &Setup, start: f64, end: f64) -> f64 {
        let power = |t: f64| {
            let (_, slip) = self.stretch_and_patch_slip(setup, t);
            self.at(setup, t).friction * slip
        };
        self.integrate(setup, power, start, end)
    }

    fn fastest(&self, setup: &Setup) -> f64 {
        CompliantMotion::fastest(self, setup)
    }

    /// k_b e²/2.
    fn ball_spring_energy(&self, setup: &Setup, t: f64) -> f64 {
        let e = self.at(setup, t).e;
        0.5 * self.spring().kb * e * e
    }

    /// ∫ c_b e'² dt (nothing without a dashpot).
    fn dashpot_loss(&self, setup: &Setup, start: f64, end: f64) -> f64 {
        let cb = self.spring().cb;
        if cb > 0.0 {
            let power = |t: f64| {
                let de = self.at(setup, t).de;
                cb * de * de
            };
            self.integrate(setup, power, start, end)
        } else {
            0.0
        }
    }

    /// The frame's velocity along the surface: the last entry of a chain on a free frame (the single
    /// cart on one is such a chain), 0 clamped.
    fn frame_velocity(&self, setup: &Setup, t: f64) -> f64 {
        let full = match &self.phase {
            CompliantPhase::Slide(CompliantSlide {
                rigid: Rigid::Frame(motion, _),
                ..
            }) => return motion.sliding_at(setup, t).frame.0,
            CompliantPhase::Slide(CompliantSlide {
                rigid: Rigid::Chain(chain),
                ..
            }) => chain.full(setup, t),
            CompliantPhase::ChainGrip(grip) => grip.full(setup, t),
            CompliantPhase::HeldChainGrip(grip) => grip.full(setup, t),
            CompliantPhase::HeldOnFrame(h) => h.full(t),
            CompliantPhase::HeldRingGrip(grip) => grip.full(setup, t),
            CompliantPhase::Slide(_) | CompliantPhase::Grip(_) => return 0.0,
        };
        match full.frame {
            0 => 0.0,
            frame => full.v[frame],
        }
    }
}

thread_local! {
    /// The grip's modes of the last bounce on this thread, by its chain and the ball's spring and
    /// dashpot.
    static LAST_GRIP_MODES: Slot<([u64; 5], u64, u64), Arc<GripModes>> =
        const { RefCell::new(None) };
    /// The same for the ball gripping the ring of a first mass held to a free frame.
    static LAST_RING_MODES: Slot<([u64; 5], u64, u64), Arc<GripModes>> =
        const { RefCell::new(None) };
}

/// What the ball touches: the single cart, or a chain with the modes of the ball gripping it (and, with
/// string friction, the cart's constants for the ball's stretch on a held first mass).
enum Support {
    Cart(Box<Compliance>),
    Chain {
        chain: Arc<Chain>,
        modes: Arc<GripModes>,
        held: Option<Box<Compliance>>,
    },
}

/// What the compliant ball carries from phase to phase: the ball and the contact mass, the whole chain
/// (on the single cart only its first mass is used), and the stretch e.
#[derive(Clone, Copy, Debug)]
pub struct CompliantState {
    contact: State,
    full: ChainState,
    e: f64,
}

impl CompliantState {
    /// The ball and every mass (on the single cart, its only mass; the frame's entry where it is free).
    pub fn full(&self) -> &ChainState {
        &self.full
    }
}

/// The tangentially compliant ball on the single cart or on a chain, with or without string friction.
/// With a spring (k > 0) every grip on a moving contact mass is solved by [`ChainGrip`], the single cart
/// without string friction being a chain of one mass (which slides by the rigid ball's [`Slide`]), and a grip on a held first mass of a chain by
/// [`HeldChainGrip`] ([`HeldRingGrip`] on a free frame); a free cart (k = 0) has a double zero root
/// there, and its grips are solved by [`CompliantGrip`], as are all grips on the single cart with
/// string friction (on a free frame, held, on the body of cart and frame, [`HeldOnFrame`]).
pub struct CompliantBall {
    support: Support,
    /// On a free frame with string friction, the single cart held to the frame.
    hold: Option<Arc<FrameHold>>,
    /// On a free frame, the single cart moving relative to it (its slides are the rigid ball's).
    framed: Option<FramedCart>,
    /// On a free frame with string friction on a chain, the grip's modes of the ball on the ring of a
    /// first mass held to the frame ([`HeldRingGrip`]).
    ring: Option<Arc<GripModes>>,
    /// The part of the ball's force that pushes the contact mass relative to what holds it: M_t/m_B
    /// on a free frame (m_B the contact mass and the frame), 1 on the wall.
    share: f64,
    spring: BallSpring,
    spin: f64,
    /// |v_x1| + r |omega1|: the scale of the speeds, for the event functions' rounding.
    incoming: f64,
}

impl CompliantBall {
    /// The single cart on the wall, solved as a chain of one mass: its only mass is the contact's cart,
    /// so the contact state is the whole state.
    fn single_on_wall(&self) -> bool {
        matches!(&self.support, Support::Chain { chain, .. } if chain.n == 1 && chain.frame_index() == 0)
    }

    /// The model for `params` and the setup it runs on, refused when the cart or the ball's spring is
    /// too fast to resolve. `modal` solves every grip as a chain's (with a spring; on the single cart
    /// without string friction); otherwise by the cart's own 4-state system, the chain's length ignored.
    pub fn new(params: &Params, modal: bool) -> Result<(Self, Setup), SolveError> {
        let links = params.chain.max(1.0);
        let string = params.cart_friction > 0.0;
        // Without springs (k = 0) the chain's other masses never move: the ball meets its first mass
        // alone.
        let setup = if links > 1.0 && params.stiffness == 0.0 {
            Setup::new(&Params {
                cart_mass: params.cart_mass / links,
                chain: 1.0,
                ..*params
            })
        } else {
            Setup::new(params)
        };
        Chain::solvable_on_frame(params, &setup, true)?;
        let framed = setup.frame_mass.is_some();
        let spring = BallSpring::new(params, &setup);
        let (mut hold, mut ring, mut share) = (None, None, 1.0);
        let support = if modal && (!string || links > 1.0 || framed) {
            let chain = Chain::shared(params, &setup);
            let key = (
                Chain::key(params, &setup),
                spring.kb.to_bits(),
                spring.cb.to_bits(),
            );
            let modes = reuse(&LAST_GRIP_MODES, key, || {
                Arc::new(GripModes::new(chain.clone(), &setup, spring.kb, spring.cb))
            });
            let held = (string && !framed).then(|| Box::new(Compliance::new(params, &setup)));
            if let (true, Some(frame)) = (string, setup.frame_mass) {
                if let Some(on_ring) = chain.held_ring() {
                    share = frame / (chain.link_mass + frame);
                    ring = Some(reuse(&LAST_RING_MODES, key, || {
                        Arc::new(GripModes::new(
                            Arc::new(on_ring),
                            &setup,
                            spring.kb,
                            spring.cb,
                        ))
                    }));
                } else {
                    let frame_hold = FrameHold::new(params, &setup, frame, chain.clone());
                    share = frame_hold.share;
                    hold = Some(Arc::new(frame_hold));
                }
            }
            Support::Chain { chain, modes, held }
        } else {
            Support::Cart(Box::new(Compliance::new(params, &setup)))
        };
        let (mut cart_fastest, mut ball_fastest) = match &support {
            Support::Cart(c) => (setup.omega_slide.max(setup.omega_grip), c.fastest),
            Support::Chain { chain, modes, .. } => (chain.slide.fastest, modes.fastest),
        };
        if let (Some(ring), Support::Chain { chain, .. }) = (&ring, &support) {
            cart_fastest = cart_fastest.max(chain.held(1.0).fastest);
            ball_fastest = ball_fastest.max(ring.fastest);
        }
        let radians = cart_fastest * setup.duration;
        if radians > MAX_RADIANS {
            return Err(SolveError::TooFast { radians });
        }
        let ball_radians = ball_fastest * setup.duration;
        if ball_radians > MAX_RADIANS {
            return Err(too_fast_ball(params, &setup, &spring, ball_radians));
        }
        // The single cart on a free frame slides as the rigid ball's (whose own refusals are the chain's
        // above: where it would refuse, the chain's modes stand in).
        let framed = match (&support, setup.frame_mass) {
            (Support::Chain { chain, .. }, Some(frame)) if chain.n == 1 => {
                FramedCart::new(params, &setup, frame).ok()
            }
            _ => None,
        };
        let model = CompliantBall {
            support,
            hold,
            framed,
            ring,
            share,
            spring,
            spin: params.spin,
            incoming: setup.vx1.abs() + setup.r * params.spin.abs(),
        };
        Ok((model, setup))
    }
}

impl CompliantBall {
    /// The phase of `ball` from `state` with the cart held to the free frame: the ball on the body of
    /// cart and frame.
    fn held_on_frame(
        &self,
        hold: &Arc<FrameHold>,
        state: &CompliantState,
        ball: Ball,
    ) -> CompliantMotion {
        let body = &hold.body;
        let start = HeldOnFrame::body_start(&state.full);
        let inner = match ball {
            Ball::Slide(dir) => CompliantPhase::Slide(CompliantSlide {
                rigid: Rigid::Cart(Slide::new(body, start, dir, Cart::Moving(1))),
                stretch: Stretch::new(&self.spring, body, dir, start.t, state.e),
            }),
            Ball::Grip => CompliantPhase::Grip(Box::new(CompliantGrip::new(
                hold.compliance,
                start,
                state.e,
                body,
                Cart::Moving(1),
            ))),
        };
        let frame_x = state.full.x[state.full.frame];
        CompliantPhase::HeldOnFrame(Box::new(HeldOnFrame::new(
            hold.clone(),
            inner.into(),
            state.contact.x,
            frame_x,
        )))
        .into()
    }

    /// The first event of a phase held to the free frame: the ball's on the body, or the push the string
    /// friction must hold, share F - k y, reaching ±F_c.
    fn held_event(
        &self,
        setup: &Setup,
        held: &HeldOnFrame,
        state: &CompliantState,
        ball: Ball,
        cause: Cause,
    ) -> Option<(f64, Cause)> {
        let body = &held.hold.body;
        let inner_state = CompliantState {
            contact: held.inner.initial(),
            full: ChainState::from_contact(&held.inner.initial()),
            e: state.e,
        };
        let mode = (ball, Cart::Moving(1));
        let ball_event = self
            .first_event(body, &held.inner, &inner_state, mode, cause)
            .event;
        let (t0, until) = (state.contact.t, ball_event.map_or(setup.duration, |e| e.0));
        let share = held.hold.share;
        let spring = setup.k * held.y;
        let (w, peak) = (setup.w, setup.peak_friction());
        let (curvature, size) = match &held.inner.phase {
            CompliantPhase::Grip(grip) => grip.force_bounds(body),
            _ => (peak * w * w, 0.0),
        };
        let noise = ROUNDING * (peak + spring.abs() + setup.cart_friction + EXP_ROUNDING * size);
        let f = |t: f64| {
            let p = held.inner.at(body, t);
            let (push, rate) = (share * p.friction - spring, share * p.friction_rate);
            setup.unstick_margins(push, rate)
        };
        let step = setup.event_step(held.inner.fastest(body));
        let unstick =
            first_rise_from_tangent(f, t0, until, step, [share * curvature; 2], [noise; 2]).map(
                |(t, branch)| {
                    (
                        t,
                        if branch == 0 {
                            Cause::Unstick(1)
                        } else {
                            Cause::Unstick(-1)
                        },
                    )
                },
            );
        unstick.or(ball_event)
    }
}

/// A branch that never rises: the event of a cart without string friction.
const STAND_IN: (f64, f64) = (-1.0, 0.0);

/// The events at the single cart with string friction, as two branches that rise through zero: moving in
/// direction d, its velocity -d (V - `v_offset`) (it stops; the second branch is a stand-in); held, the
/// net force ±(F - k X) - F_c (it is pushed free either way). Without string friction both are stand-ins.
struct CartEvents {
    cart: Cart,
    v_offset: f64,
    /// The size of the forces on the cart at the start, mu N0 + k |X| + F_c.
    forces: f64,
}

impl CartEvents {
    #[inline]
    fn at(&self, setup: &Setup, p: &Point) -> [(f64, f64); 2] {
        if setup.cart_friction == 0.0 {
            return [STAND_IN; 2];
        }
        let push = p.friction - setup.k * p.state.x;
        match self.cart {
            Cart::Moving(d) => {
                let d = f64::from(d);
                let accel = (push + self.cart.friction(setup)) / setup.cart_mass;
                [(-d * (p.state.v - self.v_offset), -d * accel), STAND_IN]
            }
            // X is fixed: the push changes as F does.
            Cart::Stuck => setup.unstick_margins(push, p.friction_rate),
        }
    }

    /// The same on a chain's first mass, given the link force N k (X_1 - X_2) and its rate where it is
    /// held: moving, its velocity V_1 (relative to a free frame, V_1 - V_f); held, the net push
    /// F - N k (X_1 - X_2).
    #[inline]
    fn at_chain(&self, setup: &Setup, p: &Point, (link, link_rate): (f64, f64)) -> [(f64, f64); 2] {
        if setup.cart_friction == 0.0 {
            return [STAND_IN; 2];
        }
        match self.cart {
            Cart::Moving(d) => {
                let d = f64::from(d);
                let (v, accel) = (p.state.v - p.frame.0, p.accel - p.frame.1);
                [(-d * (v - self.v_offset), -d * accel), STAND_IN]
            }
            Cart::Stuck => {
                let (push, rate) = (p.friction - link, p.friction_rate - link_rate);
                setup.unstick_margins(push, rate)
            }
        }
    }

    /// The branches' curvature bound and rounding floor, given a bound on |V''| and the size of the terms
    /// V is summed from (for a moving cart), or a bound on |F''| and the size of F's terms (held).
    fn bounds(
        &self,
        setup: &Setup,
        (speed_curvature, speeds): (f64, f64),
        force_curvature: f64,
        force_terms: f64,
    ) -> (f64, f64) {
        match self.cart {
            _ if setup.cart_friction == 0.0 => (0.0, 0.0),
            Cart::Moving(_) => (speed_curvature, ROUNDING * (self.v_offset.abs() + speeds)),
            Cart::Stuck => (
                force_curvature,
                ROUNDING * (self.forces + EXP_ROUNDING * force_terms),
            ),
        }
    }

    /// The cause of a rise of branch 0 or 1.
    fn cause(&self, branch: usize) -> Cause {
        match (self.cart, branch) {
            (Cart::Moving(_), _) => Cause::CartStop,
            (Cart::Stuck, 0) => Cause::Unstick(1),
            (Cart::Stuck, _) => Cause::Unstick(-1),
        }
    }
}

/// The grip breaking forward (margin branch 0) or backward (1).
fn grip_break(branch: usize) -> Cause {
    if branch == 0 {
        Cause::GripBreak(1.0)
    } else {
        Cause::GripBreak(-1.0)
    }
}

/// The refusal of a ball whose grip is too fast to resolve, naming what would help. The grip's fastest
/// rate is bounded by sqrt(X + k_b r) + c_b r, r = 1/m_eff + 1/m_1 the inverse reduced mass of the ball
/// and the mass it touches (the cart, or the chain's first link), X the cart's or chain's own squared
/// rate. The advice names the values that bring it within [`MAX_RADIANS`]: a softer ball (c_b =
/// 2 zeta sqrt(k_b m_eff) falls with it), less damping, or a heavier light mass where even an infinite
/// one would do. A stiffer or more damped ball never helps.
fn too_fast_ball(params: &Params, setup: &Setup, spring: &BallSpring, radians: f64) -> SolveError {
    let links = params.chain.max(1.0);
    // The mass the ball touches (the setup's cart is already one link where the chain's springs are off).
    let first = if setup.cart_mass == params.cart_mass {
        setup.cart_mass / links
    } else {
        setup.cart_mass
    };
    let r = 1.0 / setup.m_eff + 1.0 / first;
    let (kb, cb, t) = (spring.kb, spring.cb, setup.duration);
    let limit = 0.999 * MAX_RADIANS / t;
    let own = ((radians / t - cb * r).powi(2) - kb * r).max(0.0);
    let rate = |kb: f64, cb: f64, r: f64| (own + kb * r).sqrt() + cb * r;
    let mut advice = Vec::new();
    if own.sqrt() < limit {
        // The largest k_b at this zeta: the rate rises with sqrt(k_b), so bisect on it.
        let per_root = 2.0 * params.ball_damping * setup.m_eff.sqrt();
        let (mut low, mut high) = (0.0, kb.sqrt());
        for _ in 0..200 {
            let mid = 0.5 * (low + high);
            if rate(mid * mid, per_root * mid, r) < limit {
                low = mid;
            } else {
                high = mid;
            }
        }
        let share = (kb * r).sqrt();
        advice.push((
            share,
            format!("--ball-stiffness below {:.2e} N/m", low * low),
        ));
        let spring_only = (own + kb * r).sqrt();
        if cb > 0.0 && spring_only < limit {
            let zeta = params.ball_damping * (limit - spring_only) / (cb * r);
            advice.push((cb * r, format!("--ball-damping below {}", brief(zeta, 3))));
        }
    }
    // With the lighter mass infinite, only the other remains in r.
    let (lighter, other) = if first < setup.m_eff {
        (first, setup.m_eff)
    } else {
        (setup.m_eff, first)
    };
    if rate(kb, cb, 1.0 / other) < limit {
        let heavier = if lighter == first && links > 1.0 {
            "a heavier --cart-mass or fewer --chain links"
        } else if lighter == first {
            "a heavier --cart-mass"
        } else {
            "a heavier ball (--mass)"
        };
        advice.push((0.0, heavier.to_string()));
    }
    let part = if cb * r >= (kb * r).sqrt() {
        "dashpot"
    } else {
        "spring"
    };
    // The larger share first.
    advice.sort_by(|a, b| b.0.total_cmp(&a.0));
    let advice = if advice.is_empty() {
        "shorten the impact (--duration)".to_string()
    } else {
        let names: Vec<String> = advice.into_iter().map(|(_, text)| text).collect();
        names.join(", or ")
    };
    SolveError::BallTooFast {
        radians,
        part,
        advice: format!("try {advice}"),
    }
}

impl Contact for CompliantBall {
    type State = CompliantState;
    type Motion = CompliantMotion;
    type Probe = Point;

    fn start(&self, setup: &Setup) -> (CompliantState, Mode) {
        let state = setup.initial(self.spin);
        let slip0 = setup.slip(&state);
        let spring = &self.spring;
        // How the contact starts: rolling grips; with a dashpot the patch takes the whole slip at once;
        // without, the spring's rate k_b slip0 must beat the friction limit's rate mu N0 w.
        let ball = if slip0.abs() <= ROLLING * self.incoming
            || (spring.cb == 0.0 && spring.kb * slip0.abs() <= setup.peak_friction() * setup.w)
        {
            Ball::Grip
        } else {
            Ball::Slide(slip0.signum())
        };
        let mut full = ChainState::from_contact(&state);
        if let Support::Chain { chain, .. } = &self.support {
            full.frame = chain.frame_index();
        }
        let carried = CompliantState {
            contact: state,
            full,
            e: 0.0,
        };
        // With string friction the cart starts at rest under the ball's first force (0 sliding, as
        // N(0) = 0; the dashpot's on the arriving slip gripping).
        let cart = if setup.cart_friction > 0.0 {
            let force = match ball {
                Ball::Slide(_) => 0.0,
                Ball::Grip => spring.cb * slip0,
            };
            transition::at_rest(setup, self.share * force)
        } else {
            Cart::Moving(1)
        };
        (carried, (ball, cart))
    }

    fn time(state: &CompliantState) -> f64 {
        state.contact.t
    }

    fn contact(state: &CompliantState) -> State {
        state.contact
    }

    fn motion(&self, setup: &Setup, state: &CompliantState, (ball, cart): Mode) -> CompliantMotion {
        let t0 = state.contact.t;
        if let (Some(hold), Cart::Stuck) = (&self.hold, cart) {
            return self.held_on_frame(hold, state, ball);
        }
        let phase = match ball {
            Ball::Slide(dir) => {
                let rigid = match (&self.support, &self.framed, cart) {
                    // The single cart moving on a free frame slides as the rigid ball's.
                    (_, Some(framed), Cart::Moving(d)) => {
                        let index = state.full.frame;
                        let start = FrameState {
                            s: state.contact,
                            vf: state.full.v[index],
                        };
                        let motion = FrameMotion::slide(setup, framed, start, dir, d);
                        Rigid::Frame(Box::new(motion), state.full.x[index])
                    }
                    (Support::Cart(_), ..) => {
                        Rigid::Cart(Slide::new(setup, state.contact, dir, cart))
                    }
                    // The single cart on the wall, a chain of one mass for its grips: it slides as
                    // the rigid ball's cart, the same closed form in fewer operations.
                    (Support::Chain { .. }, ..) if self.single_on_wall() => {
                        Rigid::Cart(Slide::new(setup, state.contact, dir, cart))
                    }
                    (Support::Chain { chain, .. }, ..) => {
                        Rigid::Chain(ChainMotion::new(chain, setup, &state.full, dir, cart))
                    }
                };
                CompliantPhase::Slide(CompliantSlide {
                    rigid,
                    stretch: Stretch::new(&self.spring, setup, dir, t0, state.e),
                })
            }
            Ball::Grip => {
                if let (Some(ring), Support::Chain { chain, .. }, Cart::Stuck) =
                    (&self.ring, &self.support, cart)
                {
                    return CompliantPhase::HeldRingGrip(Box::new(HeldRingGrip::new(
                        ring.clone(),
                        chain.clone(),
                        setup,
                        state.full,
                        state.e,
                    )))
                    .into();
                }
                match &self.support {
                    Support::Cart(compliance) => CompliantPhase::Grip(Box::new(
                        CompliantGrip::new(**compliance, state.contact, state.e, setup, cart),
                    )),
                    Support::Chain {
                        chain,
                        held: Some(compliance),
                        ..
                    } if cart == Cart::Stuck => CompliantPhase::HeldChainGrip(Box::new(
                        HeldChainGrip::new(**compliance, chain.clone(), setup, state.full, state.e),
                    )),
                    Support::Chain { modes, .. } => {
                        CompliantPhase::ChainGrip(Box::new(ChainGrip::new(
                            modes.clone(),
                            state.full,
                            state.e,
                            setup,
                            cart.friction(setup),
                        )))
                    }
                }
            }
        };
        phase.into()
    }

    fn first_event(
        &self,
        setup: &Setup,
        motion: &CompliantMotion,
        state: &CompliantState,
        (ball, cart): Mode,
        cause: Cause,
    ) -> Found<Point> {
        let (t0, end) = (state.contact.t, setup.duration);
        let (w, peak) = (setup.w, setup.peak_friction());
        let s = &state.contact;
        // The points the search measured last: the one at the event, when among them, is the state
        // there (not evaluated again).
        let recent = Recent::new(t0, None::<Point>);
        let speeds = self.incoming + s.vx.abs() + setup.r * s.omega.abs() + s.v.abs();
        // The cart's velocity starts on its own zero after it stopped or came unstuck (and at first
        // contact): measured from its start value, so rounding cannot fake a stop there. On a free frame,
        // its velocity relative to the frame.
        let v_offset = if matches!(cause, Cause::Start | Cause::CartStop | Cause::Unstick(_)) {
            match state.full.frame {
                0 => s.v,
                frame => s.v - state.full.v[frame],
            }
        } else {
            0.0
        };
        let events = CartEvents {
            cart,
            v_offset,
            forces: peak + setup.k * s.x.abs() + setup.cart_friction,
        };
        let event = match &motion.phase {
            CompliantPhase::HeldOnFrame(held) => self.held_event(setup, held, state, ball, cause),
            CompliantPhase::Slide(slide) => {
                let dir = slide.dir();
                // A detuned, damped slide without string friction searches the patch's slip written
                // once for the phase: the rigid slip by the sums of the single cart, of a chain on the
                // wall or of a free frame, e' by the stretch's ([`slip_sums`]). Its point is computed
                // only where the search ends; other slides evaluate theirs.
                let sums = slip_sums::slip_sums(slide, setup, t0);
                // The patch's slip at the start, and the point there where the search evaluates
                // points.
                let (start_slip, start) = match &sums {
                    Some(sums) => (sums.start_slip(setup, t0), None),
                    None => {
                        let p = slide.at(setup, t0);
                        (slide.patch_slip(setup, &p).0, Some(p))
                    }
                };
                // After a grip broke, the patch starts from rest on the cart (with a dashpot) or with
                // the jump of e' (without): a start slip against `dir` is rounding, and counts as zero,
                // so rounding can never fake a crossing at the start.
                let offset = if cause != Cause::Start && dir * start_slip < 0.0 {
                    start_slip
                } else {
                    0.0
                };
                let by_sums = sums
                    .as_ref()
                    .map(|sums| sums.event(setup, t0, dir, start_slip, offset));
                // The patch's slip against `dir`, with the point it was measured at (the search's
                // first, at t0, is the one above).
                let slip = |t: f64| {
                    let p = match start {
                        Some(p) if t == t0 => p,
                        _ => slide.at(setup, t),
                    };
                    recent.record(t, Some(p));
                    let (slip, rate) = slide.patch_slip(setup, &p);
                    (p, (-dir * (slip - offset), -dir * rate))
                };
                let f = |t: f64| {
                    let (p, slip) = slip(t);
                    let [first, second] = match &slide.rigid {
                        Rigid::Cart(_) => events.at(setup, &p),
                        // Held to a free frame: the ring's push on the first mass.
                        Rigid::Chain(motion) if motion.is_held() && state.full.frame > 0 => {
                            let full = motion.full(setup, t);
                            let friction = (p.friction, p.friction_rate);
                            let (push, rate) =
                                ring::held_push(motion.chain(), friction, p.accel, &full);
                            setup.unstick_margins(push, rate)
                        }
                        Rigid::Chain(motion) if motion.is_held() => {
                            events.at_chain(setup, &p, motion.link(setup, t))
                        }
                        Rigid::Chain(_) | Rigid::Frame(..) => {
                            events.at_chain(setup, &p, (0.0, 0.0))
                        }
                    };
                    [slip, first, second]
                };
                let (slip_curvature, terms, fastest) = slide.slip_bounds(setup);
                let noise = ROUNDING * (speeds + terms + slide.stretch.speed(w));
                let (cart_curvature, cart_noise) = match &slide.rigid {
                    // Without string friction the cart has no event.
                    _ if setup.cart_friction == 0.0 => (0.0, 0.0),
                    // The rigid slide's bound is on V'' moving, on F'' = (F - k X)'' held.
                    Rigid::Cart(rigid) => {
                        let curvature = rigid.curvature(setup).1;
                        let speeds = rigid.cart_speed_scale(setup);
                        events.bounds(setup, (curvature, speeds), curvature, 0.0)
                    }
                    // Held to a free frame, the ring's push (its bound has the friction's share).
                    Rigid::Chain(motion) if motion.is_held() && state.full.frame > 0 => {
                        let (curvature, terms) = ring::push_bounds(motion, setup);
                        (curvature, ROUNDING * (terms + setup.cart_friction))
                    }
                    // Held, the push's F = dir mu N(t) and the link force; moving, V_1.
                    Rigid::Chain(motion) if motion.is_held() => {
                        let (curvature, terms) = motion.link_curvature();
                        (
                            peak * w * w + curvature,
                            ROUNDING * (peak + terms + setup.cart_friction),
                        )
                    }
                    Rigid::Chain(motion) => {
                        let (curvature, terms) = match state.full.frame {
                            0 => motion.cart_curvature(setup),
                            _ => motion.relative_curvature(setup),
                        };
                        (curvature, ROUNDING * (v_offset.abs() + terms))
                    }
                    // Moving relative to the free frame: V - V_f.
                    Rigid::Frame(motion, _) => {
                        let (curvature, terms) = motion.stop_bounds(setup);
                        (curvature, ROUNDING * (v_offset.abs() + terms))
                    }
                };
                // Without string friction the cart has no event: the slip alone is searched.
                let search = |from: f64, to: f64, step: f64, curvature: f64| {
                    if let Some(by_sums) = &by_sums {
                        by_sums.first_rise(from, to, step, curvature, noise)
                    } else if setup.cart_friction == 0.0 {
                        let slip_only = |t: f64| [slip(t).1];
                        first_rise_from_tangent(slip_only, from, to, step, [curvature], [noise])
                    } else {
                        let curvature = [curvature, cart_curvature, cart_curvature];
                        let noise = [noise, cart_noise, cart_noise];
                        first_rise_from_tangent(f, from, to, step, curvature, noise)
                    }
                };
                // While the stretch's transient lasts, on its scale; after, on the cart's.
                let split = slide.stretch.settled().clamp(t0, end);
                let early = if slide.stretch.damped() {
                    let curvature = slip_curvature + slide.stretch.third(w, t0);
                    let step = setup.event_step(fastest.max(slide.stretch.lambda()));
                    search(t0, split, step, curvature)
                } else {
                    None
                };
                early
                    .or_else(|| {
                        let curvature = slip_curvature + slide.stretch.third(w, split);
                        search(split, end, setup.event_step(fastest), curvature)
                    })
                    .map(|(t, branch)| {
                        let cause = match branch {
                            0 => Cause::SlipZero,
                            _ => events.cause(branch - 1),
                        };
                        (t, cause)
                    })
            }
            CompliantPhase::ChainGrip(grip) if setup.cart_friction > 0.0 => {
                // The grip on a first mass moving against its string friction: also its stopping.
                let margin_curvature = peak * w * w;
                let (stages, size) = grip.search_stages(setup);
                let noise = ROUNDING * (peak + size);
                let (stop_curvature, speeds) = grip.first_mass_bounds(setup);
                let stop_noise = ROUNDING * (v_offset.abs() + speeds);
                let f = |t: f64| {
                    let p = grip.at(setup, t);
                    recent.record(t, Some(p));
                    let [forward, backward] = setup.grip_margins(t, p.friction, p.friction_rate);
                    [forward, backward, events.at_chain(setup, &p, (0.0, 0.0))[0]]
                };
                stages
                    .into_iter()
                    .map(Stage::plain)
                    .find_map(|(from, to, curvature, step)| {
                        let curvature = curvature + margin_curvature;
                        let curvature = [curvature, curvature, stop_curvature];
                        let noise = [noise, noise, stop_noise];
                        first_rise_from_tangent(f, from, to, step, curvature, noise)
                    })
                    .map(|(t, branch)| match branch {
                        0 | 1 => (t, grip_break(branch)),
                        _ => (t, Cause::CartStop),
                    })
            }
            CompliantPhase::HeldRingGrip(held) => {
                // The grip on a first mass held to a free frame: also the push on it reaching ±F_c.
                let margin_curvature = peak * w * w;
                let (stages, size) = held.grip.search_stages(setup);
                let noise = ROUNDING * (peak + size);
                let f = |t: f64| {
                    let p = held.at(setup, t);
                    recent.record(t, Some(p));
                    let [forward, backward] = setup.grip_margins(t, p.friction, p.friction_rate);
                    let (push, rate) = held.push(setup, &p);
                    let [up, down] = setup.unstick_margins(push, rate);
                    [forward, backward, up, down]
                };
                stages
                    .into_iter()
                    .map(Stage::plain)
                    .find_map(|(from, to, curvature, step)| {
                        let (push_curvature, push_terms) = held.push_bounds(setup, curvature);
                        let push_noise = ROUNDING * (push_terms + size + setup.cart_friction);
                        let margin = curvature + margin_curvature;
                        let curvature = [margin, margin, push_curvature, push_curvature];
                        let noise = [noise, noise, push_noise, push_noise];
                        first_rise_from_tangent(f, from, to, step, curvature, noise)
                    })
                    .map(|(t, branch)| match branch {
                        0 | 1 => (t, grip_break(branch)),
                        2 => (t, Cause::Unstick(1)),
                        _ => (t, Cause::Unstick(-1)),
                    })
            }
            CompliantPhase::HeldChainGrip(held) => {
                let margin_curvature = peak * w * w;
                let (curvature, size) = held.ball.force_bounds(setup);
                let (link_curvature, link_terms) = held.chain.link_curvature();
                let step = setup.event_step(held.fastest());
                let noise = ROUNDING * (peak + EXP_ROUNDING * size);
                let push_noise = ROUNDING * (peak + size + link_terms + setup.cart_friction);
                let f = |t: f64| {
                    let p = held.at(setup, t);
                    recent.record(t, Some(p));
                    let [forward, backward] = setup.grip_margins(t, p.friction, p.friction_rate);
                    let [first, second] = events.at_chain(setup, &p, held.chain.link(setup, t));
                    [forward, backward, first, second]
                };
                let push_curvature = curvature + link_curvature;
                let curvature = [
                    curvature + margin_curvature,
                    curvature + margin_curvature,
                    push_curvature,
                    push_curvature,
                ];
                let noise = [noise, noise, push_noise, push_noise];
                first_rise_from_tangent(f, t0, end, step, curvature, noise).map(|(t, branch)| {
                    let cause = match branch {
                        0 | 1 => grip_break(branch),
                        _ => events.cause(branch - 2),
                    };
                    (t, cause)
                })
            }
            // The state at the break comes with it, summed from the search's last exponentials.
            CompliantPhase::ChainGrip(grip) => grip.first_break(setup).map(|(t, branch, point)| {
                recent.record(t, Some(point));
                (t, grip_break(branch))
            }),
            CompliantPhase::Grip(grip) => {
                let margin_curvature = peak * w * w;
                let (curvature, size) = grip.force_bounds(setup);
                let step = setup.event_step(grip.compliance.fastest);
                let noise = ROUNDING * (peak + EXP_ROUNDING * size);
                let (cart_curvature, cart_noise) =
                    events.bounds(setup, grip.cart_bounds(setup), curvature, size);
                let f = |t: f64| {
                    let p = grip.at(setup, t);
                    recent.record(t, Some(p));
                    let [forward, backward] = setup.grip_margins(t, p.friction, p.friction_rate);
                    let [first, second] = events.at(setup, &p);
                    [forward, backward, first, second]
                };
                let curvature = [
                    curvature + margin_curvature,
                    curvature + margin_curvature,
                    cart_curvature,
                    cart_curvature,
                ];
                let noise = [noise, noise, cart_noise, cart_noise];
                first_rise_from_tangent(f, t0, end, step, curvature, noise).map(|(t, branch)| {
                    let cause = match branch {
                        0 | 1 => grip_break(branch),
                        _ => events.cause(branch - 2),
                    };
                    (t, cause)
                })
            }
        };
        Found {
            event,
            last: recent.at(event.map_or(end, |(t, _)| t)),
        }
    }

    fn state_at(
        &self,
        setup: &Setup,
        motion: &CompliantMotion,
        t: f64,
        last: Option<Point>,
    ) -> CompliantState {
        let point = match last {
            Some(p) if p.state.t == t => p,
            _ => motion.at(setup, t),
        };
        // The patch there, as `stretch_and_patch_slip` takes it from the same point (held to a free
        // frame, the ball's point is on the body of cart and frame, and is evaluated when asked).
        let slip = match &motion.phase {
            CompliantPhase::Slide(slide) => Some(slide.patch_slip(setup, &point).0),
            CompliantPhase::HeldOnFrame(_) => None,
            CompliantPhase::Grip(_)
            | CompliantPhase::ChainGrip(_)
            | CompliantPhase::HeldChainGrip(_)
            | CompliantPhase::HeldRingGrip(_) => Some(0.0),
        };
        if let Some(slip) = slip {
            motion.end.keep(t, point.e, slip);
        }
        let full = match &motion.phase {
            CompliantPhase::Slide(CompliantSlide {
                rigid: Rigid::Chain(chain),
                ..
            }) => chain.full(setup, t),
            CompliantPhase::Slide(CompliantSlide {
                rigid: Rigid::Frame(motion, x0),
                ..
            }) => {
                // The cart at the frame's displacement plus the stretch, the frame's entry after it.
                let y = point.state.x;
                let frame = motion.frame_displacement(setup, t, y, *x0);
                let mut full = ChainState::from_contact(&point.state);
                full.frame = 1;
                (full.x[0], full.x[1]) = (frame + y, frame);
                full.v[1] = point.frame.0;
                full
            }
            // The single cart on the wall, gripped as a chain of one mass: that mass is the contact
            // point's cart, which the point already holds (no second propagation of the grip).
            CompliantPhase::ChainGrip(grip) if !self.single_on_wall() => grip.full(setup, t),
            CompliantPhase::HeldChainGrip(grip) => grip.full(setup, t),
            CompliantPhase::HeldOnFrame(held) => held.full(t),
            CompliantPhase::HeldRingGrip(grip) => grip.full(setup, t),
            _ => ChainState::from_contact(&point.state),
        };
        CompliantState {
            contact: point.state,
            full,
            e: point.e,
        }
    }

    /// A slide ends in a grip; a grip breaks into a slide the way the force points; a cart pushed free
    /// moves the way it was pushed; a cart that stops is held or pushed on by the net force on it,
    /// F - k X ([`transition::at_rest`]). The force F is continuous across each of these, so the other
    /// half of the mode stays.
    fn next(
        &self,
        setup: &Setup,
        state: &mut CompliantState,
        (ball, cart): Mode,
        cause: Cause,
    ) -> Mode {
        match cause {
            Cause::GripBreak(sign) => (Ball::Slide(sign), cart),
            Cause::Unstick(dir) => (ball, Cart::Moving(dir)),
            Cause::CartStop => {
                let s = &mut state.contact;
                s.v = 0.0;
                // The spring holding the contact mass back: k X on the cart, N k (X_1 - X_2) on a chain.
                let spring = match &self.support {
                    Support::Chain { chain, .. } => {
                        // At rest on the wall, or moving with a free frame.
                        let frame = state.full.frame;
                        let v = if frame > 0 { state.full.v[frame] } else { 0.0 };
                        (s.v, state.full.v[0]) = (v, v);
                        chain.link_force(&state.full)
                    }
                    Support::Cart(_) => {
                        state.full = ChainState::from_contact(s);
                        setup.k * s.x
                    }
                };
                let force = match ball {
                    Ball::Slide(dir) => dir * setup.mu * setup.normal(s.t),
                    // Gripping, e' is the contact point's slip on the cart.
                    Ball::Grip => self.spring.kb * state.e + self.spring.cb * setup.slip(s),
                };
                // On a chain held to a free frame, the ring's push F - T_1 - (M/N) a_B.
                let push = match (&self.ring, &self.support) {
                    (Some(_), Support::Chain { chain, .. }) => {
                        ring::rest_push(chain, force, &state.full)
                    }
                    _ => self.share * force - spring,
                };
                (ball, transition::at_rest(setup, push))
            }
            Cause::SlipZero | Cause::Start => (Ball::Grip, cart),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::registry::Motion;
    use super::super::solve::solve;
    use super::*;

    /// The patch a phase kept where the driver took its end state is the patch evaluated there afresh,
    /// bit for bit, and it is kept (but held to a free frame): every phase, slides and grips, on the
    /// single cart and a chain, on the wall and on a free frame, with and without string friction.
    #[test]
    fn the_patch_kept_at_a_phase_end_is_the_patch_evaluated_there() {
        let mut kinds = [false; 2];
        for (angle, damping, chain, cart_friction, frame_mass) in [
            (30.0, 0.3, 1.0, 0.0, 0.0),
            (30.0, 0.0, 1.0, 0.0, 0.0),
            (80.0, 1.5, 1.0, 0.0, 0.0),
            (60.0, 0.3, 1.0, 30.0, 0.0),
            (45.0, 0.3, 4.0, 0.0, 0.0),
            (45.0, 0.3, 4.0, 30.0, 0.0),
            (30.0, 0.3, 1.0, 0.0, 0.188),
            (30.0, 0.3, 1.0, 30.0, 0.188),
            (45.0, 0.3, 4.0, 30.0, 0.188),
        ] {
            let params = Params {
                angle_deg: angle,
                ball_stiffness: 1e5,
                ball_damping: damping,
                chain,
                cart_friction,
                frame_mass,
                ..Params::default()
            };
            let bounce = solve(&params).expect("solvable");
            for phase in &bounce.phases {
                let Motion::Compliant(motion) = &phase.motion else {
                    panic!("a compliant phase");
                };
                let fresh = CompliantMotion::from(motion.phase.clone());
                let kept = motion.stretch_and_patch_slip(&bounce.setup, phase.end);
                let evaluated = fresh.stretch_and_patch_slip(&bounce.setup, phase.end);
                let what = format!("{params:?} phase at {}", phase.start);
                assert_eq!(kept.0.to_bits(), evaluated.0.to_bits(), "{what}");
                assert_eq!(kept.1.to_bits(), evaluated.1.to_bits(), "{what}");
                let held = matches!(motion.phase, CompliantPhase::HeldOnFrame(_));
                assert_eq!(motion.end.at(phase.end).is_some(), !held, "{what}");
                assert!(fresh.end.at(phase.end).is_none());
                kinds[usize::from(phase.kind == super::super::phase::PhaseKind::Grip)] = true;
            }
        }
        assert_eq!(kinds, [true, true], "slides and grips");
    }

    /// The slip a chain's slide searches by its sums is the one its full evaluation gives: the rigid
    /// slip v_x - r omega - V_1 and its rate bit for bit, the patch's (less e' and its rate from the
    /// stretch's sums at the chain's angle w τ) to rounding, over random slides on chains of 1 to 12
    /// masses sliding either way, the first mass moving either way, light to heavy damping.
    #[test]
    fn a_chains_slip_by_sums_is_its_slip_evaluated() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut uniform = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..40 {
            let params = Params {
                chain: (1.0 + 12.0 * uniform()).floor(),
                stiffness: 10f64.powf(1.0 + 4.0 * uniform()),
                ball_stiffness: 10f64.powf(4.0 + 2.0 * uniform()),
                ball_damping: 0.05 + 2.0 * uniform(),
                ..Params::default()
            };
            let setup = Setup::new(&params);
            let chain = Chain::shared(&params, &setup);
            let dir = if uniform() < 0.5 { 1.0 } else { -1.0 };
            let cart = Cart::Moving(if uniform() < 0.5 { 1 } else { -1 });
            let mut start = ChainState::from_contact(&setup.initial(params.spin));
            start.t = 0.8 * setup.duration * uniform();
            for i in 0..chain.n {
                start.x[i] = 1e-4 * (2.0 * uniform() - 1.0);
                start.v[i] = 2.0 * uniform() - 1.0;
            }
            let motion = ChainMotion::new(&chain, &setup, &start, dir, cart);
            let spring = BallSpring::new(&params, &setup);
            let stretch = Stretch::new(&spring, &setup, dir, start.t, 1e-4 * uniform());
            let rates = stretch.rates(setup.w).expect("damped");
            let slide = CompliantSlide {
                rigid: Rigid::Chain(motion),
                stretch,
            };
            let Rigid::Chain(motion) = &slide.rigid else {
                unreachable!("built as a chain's slide")
            };
            let w = setup.w;
            let scale =
                (start.vx.abs() + setup.r * start.omega.abs() + slide.slip_bounds(&setup).1)
                    + stretch.speed(w) * (1.0 + stretch.lambda() / w);
            for k in 0..=12 {
                let t = start.t + (setup.duration - start.t) * (f64::from(k) + uniform()) / 13.0;
                let what = format!("case {case} {params:?} t {t}");
                let p = slide.at(&setup, t);
                let (slip, rate, w_tau) = motion.slip_by_sums(&setup, t).expect("written");
                assert_eq!(slip.to_bits(), setup.slip(&p.state).to_bits(), "{what}");
                assert_eq!(rate.to_bits(), p.slip_rate.to_bits(), "{what}");
                let (de, dde) = rates.at(t, w_tau);
                let (patch, patch_rate) = slide.patch_slip(&setup, &p);
                assert!((slip - de - patch).abs() <= 1e-13 * scale, "{what}");
                let rate_scale = scale * (stretch.lambda() + w + chain.slide.fastest);
                assert!(
                    (rate - dde - patch_rate).abs() <= 1e-13 * rate_scale,
                    "{what}"
                );
            }
        }
    }
}
