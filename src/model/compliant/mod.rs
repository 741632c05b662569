//! A tangentially compliant ball (issue 6, part 3), on the single cart or on a chain of masses.
//!
//! The ball's contact region is a massless tangential spring k_b with a dashpot c_b between the ball's
//! contact point (coordinate u, velocity u' = v_x - r omega, effective mass m_eff) and the contact patch
//! (position p). With the stretch e = u - p the force on the ball, positive backward, is
//! F = k_b e + c_b e'; the massless patch passes it on to the cart (the chain's first mass), which feels
//! +F (Eq. (3)).
//!
//! - Slide: the patch slides on the cart and F = dir mu N(t). The ball and the cart move exactly as for
//!   a rigid ball ([`Slide`], or the chain's [`ChainMotion`]); the stretch follows c_b e' + k_b e = F(t)
//!   (e = F/k_b without damping), solved in closed form ([`Stretch`]). The patch slips at
//!   p' - V = (v_x - r omega - V) - e'; the slide ends when that slip reaches zero, and the patch then
//!   always grips (a reversed slide would need the opposite force, which the continuous stretch and the
//!   slip's sign exclude).
//! - Grip: the patch moves with the cart. Ball, stretch and cart (or chain) form one linear, not
//!   proportionally damped system, solved in its complex modes ([`CompliantGrip`] on the single cart,
//!   [`ChainGrip`] on a chain). The grip breaks when |F| reaches mu N, into a slide the way F points.
//!
//! Chatter: an undamped stiff ball may switch many times; every phase advances time and the solver stops
//! after [`MAX_TRANSITIONS`] with [`SolveError::TooManyPhases`].

mod cart_grip;
mod chain_grip;
mod stretch;

use std::sync::Arc;

pub use cart_grip::{Compliance, CompliantGrip};
pub use chain_grip::{ChainGrip, GripModes};
pub use stretch::Stretch;

use super::bounce::{
    MAX_RADIANS, MAX_TRANSITIONS, Motion, Phase, PhaseKind, ROLLING, ROUNDING, SolveError, finish,
};
use super::cart::Cart;
use super::chain::motion::Motion as ChainMotion;
use super::chain::{Chain, ChainState};
use super::events::first_rise_from_tangent;
use super::limits;
use super::params::Params;
use super::quadrature::integrate;
use super::setup::{Setup, State};
use super::slide::Slide;
use crate::model::Bounce;
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
    Chain(Arc<ChainMotion>),
}

/// A sliding phase of the compliant ball.
#[derive(Clone, Debug)]
pub struct CompliantSlide {
    pub rigid: Rigid,
    pub stretch: Stretch,
    pub spring: BallSpring,
}

/// A phase of the compliant ball.
#[derive(Clone, Debug)]
pub enum CompliantMotion {
    Slide(CompliantSlide),
    Grip(Box<CompliantGrip>),
    ChainGrip(ChainGrip),
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
}

impl CompliantSlide {
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        let (e, de, dde) = self.stretch.at(setup.w, t);
        let (state, friction, slip_rate) = match &self.rigid {
            Rigid::Cart(slide) => {
                let (state, friction) = slide.evaluate(setup, t);
                (state, friction, slide.slip_rate(setup, &state, friction))
            }
            Rigid::Chain(motion) => {
                let c = motion.contact(setup, t);
                (c.state, c.friction, -c.friction / setup.m_eff - c.accel)
            }
        };
        Point {
            state,
            friction,
            friction_rate: self.dir() * setup.mu * setup.n0 * setup.w * (setup.w * t).cos(),
            e,
            de,
            dde,
            slip_rate,
        }
    }

    fn dir(&self) -> f64 {
        match &self.rigid {
            Rigid::Cart(slide) => slide.dir,
            Rigid::Chain(motion) => motion.dir,
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
        }
    }
}

impl CompliantMotion {
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        match self {
            CompliantMotion::Slide(s) => s.at(setup, t),
            CompliantMotion::Grip(g) => g.at(setup, t),
            CompliantMotion::ChainGrip(g) => g.at(setup, t),
        }
    }

    /// The slip of the patch on the cart (0 in a grip).
    pub fn patch_slip(&self, setup: &Setup, t: f64) -> f64 {
        match self {
            CompliantMotion::Slide(s) => s.patch_slip(setup, &s.at(setup, t)).0,
            CompliantMotion::Grip(_) | CompliantMotion::ChainGrip(_) => 0.0,
        }
    }

    pub fn initial(&self) -> State {
        match self {
            CompliantMotion::Slide(s) => match &s.rigid {
                Rigid::Cart(slide) => slide.start,
                Rigid::Chain(motion) => motion.start.contact(),
            },
            CompliantMotion::Grip(g) => g.start,
            CompliantMotion::ChainGrip(g) => g.start.contact(),
        }
    }

    pub fn spring(&self) -> BallSpring {
        match self {
            CompliantMotion::Slide(s) => s.spring,
            CompliantMotion::Grip(g) => BallSpring {
                kb: g.compliance.kb,
                cb: g.compliance.cb,
            },
            CompliantMotion::ChainGrip(g) => g.modes.spring(),
        }
    }

    /// The kinetic and spring energy of the whole chain at `t` (`None` on the single cart).
    pub fn chain_energy(&self, setup: &Setup, t: f64) -> Option<f64> {
        match self {
            CompliantMotion::Slide(CompliantSlide {
                rigid: Rigid::Chain(motion),
                ..
            }) => Some(motion.chain().energy(&motion.full(setup, t))),
            CompliantMotion::ChainGrip(g) => Some(g.modes.chain().energy(&g.full(setup, t))),
            _ => None,
        }
    }

    /// True on a chain (where [`Self::chain_energy`] is known).
    pub fn chain_energy_known(&self) -> bool {
        matches!(
            self,
            CompliantMotion::Slide(CompliantSlide {
                rigid: Rigid::Chain(_),
                ..
            }) | CompliantMotion::ChainGrip(_)
        )
    }

    /// The fastest rate in the phase, rad/s (for quadrature panels).
    pub fn fastest(&self, setup: &Setup) -> f64 {
        match self {
            CompliantMotion::Slide(s) => {
                let l = if s.stretch.damped {
                    s.stretch.lambda
                } else {
                    0.0
                };
                l.max(s.slip_bounds(setup).2)
            }
            CompliantMotion::Grip(g) => g.compliance.fastest,
            CompliantMotion::ChainGrip(g) => g.modes.fastest,
        }
    }

    /// ∫ f over [start, end] by Gauss-Legendre, on panels of the transient's scale until it has died
    /// out and of the cart's after.
    pub fn integrate(&self, setup: &Setup, f: impl Fn(f64) -> f64, start: f64, end: f64) -> f64 {
        let w = setup.w;
        match self {
            CompliantMotion::Slide(s) => {
                let split = s.stretch.settled().clamp(start, end);
                let fine = 2.0 / self.fastest(setup).max(w);
                let coarse = 2.0 / s.slip_bounds(setup).2.max(w);
                integrate(&f, start, split, fine) + integrate(&f, split, end, coarse)
            }
            CompliantMotion::Grip(_) | CompliantMotion::ChainGrip(_) => {
                integrate(&f, start, end, 2.0 / self.fastest(setup).max(w))
            }
        }
    }
}

/// What the ball touches: the single cart, or a chain with the modes of the ball gripping it.
enum Support {
    Cart(Box<Compliance>),
    Chain {
        chain: Arc<Chain>,
        modes: Arc<GripModes>,
    },
}

/// Solves one bounce of a compliant ball on the single cart or on a chain (no string friction). With a
/// spring (k > 0) every grip is solved by [`ChainGrip`], the single cart being a chain of one mass; a
/// free cart (k = 0) has a double zero root there, and its grips are solved by [`CompliantGrip`].
pub fn solve_compliant(params: &Params) -> Result<Bounce, SolveError> {
    solve_compliant_cancellable(params, &|| false)
}

/// [`solve_compliant`], abandoned when `cancelled` returns true (asked before every phase).
pub fn solve_compliant_cancellable(
    params: &Params,
    cancelled: &impl Fn() -> bool,
) -> Result<Bounce, SolveError> {
    solve_on(params, params.stiffness > 0.0, cancelled)
}

/// The compliant ball on the single cart (the chain's length ignored) with every grip solved by
/// [`CompliantGrip`], the cart's own 4-state system, even with a spring: an independent check of
/// [`solve_compliant`].
pub fn solve_compliant_on_cart(params: &Params) -> Result<Bounce, SolveError> {
    solve_on(
        &Params {
            chain: 1.0,
            ..*params
        },
        false,
        &|| false,
    )
}

fn solve_on(
    params: &Params,
    modal: bool,
    cancelled: &impl Fn() -> bool,
) -> Result<Bounce, SolveError> {
    limits::bounded(params, || solve_modal(params, modal, cancelled))
}

fn solve_modal(
    params: &Params,
    modal: bool,
    cancelled: &impl Fn() -> bool,
) -> Result<Bounce, SolveError> {
    if params.cart_friction > 0.0 {
        return Err(SolveError::StringFrictionCompliantBall);
    }
    let links = params.chain.max(1.0);
    // Without springs (k = 0) the chain's other masses never move: the ball meets its first mass alone.
    let setup = if links > 1.0 && params.stiffness == 0.0 {
        Setup::new(&Params {
            cart_mass: params.cart_mass / links,
            chain: 1.0,
            ..*params
        })
    } else {
        Setup::new(params)
    };
    let spring = BallSpring::new(params, &setup);
    let support = if modal {
        let chain = Arc::new(Chain::new(params, &setup));
        let modes = Arc::new(GripModes::new(chain.clone(), &setup, spring.kb, spring.cb));
        Support::Chain { chain, modes }
    } else {
        Support::Cart(Box::new(Compliance::new(params, &setup)))
    };
    let (cart_fastest, ball_fastest) = match &support {
        Support::Cart(c) => (setup.omega_slide.max(setup.omega_grip), c.fastest),
        Support::Chain { chain, modes } => (chain.slide.fastest, modes.fastest),
    };
    let radians = cart_fastest * setup.duration;
    if radians > MAX_RADIANS {
        return Err(SolveError::TooFast { radians });
    }
    let ball_radians = ball_fastest * setup.duration;
    if ball_radians > MAX_RADIANS {
        return Err(SolveError::BallTooFast {
            radians: ball_radians,
        });
    }
    let end = setup.duration;
    let (w, mu, n0) = (setup.w, setup.mu, setup.n0);
    let mut state = setup.initial(params.spin);
    // The whole chain (on the single cart, only its first mass is used).
    let mut full = ChainState::from_contact(&state);
    let mut e = 0.0;
    let incoming = setup.vx1.abs() + setup.r * params.spin.abs();
    let slip0 = setup.slip(&state);
    // How the contact starts: rolling grips; with a dashpot the patch takes the whole slip at once;
    // without, the spring's rate k_b slip0 must beat the friction limit's rate mu N0 w.
    let mut slide_dir = if slip0.abs() <= ROLLING * incoming
        || (spring.cb == 0.0 && spring.kb * slip0.abs() <= mu * n0 * w)
    {
        None
    } else {
        Some(slip0.signum())
    };
    let mut from_zero = false;
    let mut phases = Vec::with_capacity(8);
    for _ in 0..MAX_TRANSITIONS {
        if cancelled() {
            return Err(SolveError::Cancelled);
        }
        let t0 = state.t;
        let last = std::cell::Cell::new(None::<Point>);
        let speeds = incoming + state.vx.abs() + setup.r * state.omega.abs() + state.v.abs();
        let (motion, event) = match slide_dir {
            Some(dir) => {
                let rigid = match &support {
                    Support::Cart(_) => {
                        Rigid::Cart(Slide::new(&setup, state, dir, Cart::Moving(1)))
                    }
                    Support::Chain { chain, .. } => {
                        Rigid::Chain(Arc::new(ChainMotion::new(chain.clone(), &setup, full, dir)))
                    }
                };
                let slide = CompliantSlide {
                    rigid,
                    stretch: Stretch::new(&spring, &setup, dir, t0, e),
                    spring,
                };
                // After a grip broke, the patch starts from rest on the cart (with a dashpot) or with
                // the jump of e' (without): a start slip against `dir` is rounding, and counts as zero,
                // so rounding can never fake a crossing at the start.
                let start_slip = slide.patch_slip(&setup, &slide.at(&setup, t0)).0;
                let offset = if from_zero && dir * start_slip < 0.0 {
                    start_slip
                } else {
                    0.0
                };
                let f = |t: f64| {
                    let p = slide.at(&setup, t);
                    last.set(Some(p));
                    let (slip, rate) = slide.patch_slip(&setup, &p);
                    [(-dir * (slip - offset), -dir * rate)]
                };
                let (slip_curvature, terms, fastest) = slide.slip_bounds(&setup);
                let noise = ROUNDING * (speeds + terms + slide.stretch.speed(w));
                // While the stretch's transient lasts, on its scale; after, on the cart's.
                let split = slide.stretch.settled().clamp(t0, end);
                let early = if slide.stretch.damped {
                    let curvature = slip_curvature + slide.stretch.third(w, t0);
                    let step = setup.event_step(fastest.max(slide.stretch.lambda));
                    first_rise_from_tangent(f, t0, split, step, [curvature], [noise])
                } else {
                    None
                };
                let event = early
                    .or_else(|| {
                        let curvature = slip_curvature + slide.stretch.third(w, split);
                        let step = setup.event_step(fastest);
                        first_rise_from_tangent(f, split, end, step, [curvature], [noise])
                    })
                    .map(|(t, _)| (t, 0.0));
                (CompliantMotion::Slide(slide), event)
            }
            None => {
                let margin_curvature = mu * n0 * w * w;
                // Stages of the search: (from, to, curvature, step).
                let (grip, noise, stages) = match &support {
                    Support::Cart(compliance) => {
                        let grip = CompliantGrip::new(**compliance, state, e, &setup);
                        let (curvature, size) = grip.force_bounds(&setup);
                        let noise = ROUNDING * (mu * n0 + EXP_ROUNDING * size);
                        let step = setup.event_step(compliance.fastest);
                        let stage = (t0, end, curvature + margin_curvature, step);
                        (CompliantMotion::Grip(Box::new(grip)), noise, vec![stage])
                    }
                    Support::Chain { modes, .. } => {
                        let grip = ChainGrip::new(modes.clone(), full, e, &setup);
                        let (stages, size) = grip.search_stages(&setup);
                        let stages = stages
                            .into_iter()
                            .map(|(from, to, curvature, step)| {
                                (from, to, curvature + margin_curvature, step)
                            })
                            .collect();
                        let noise = ROUNDING * (mu * n0 + size);
                        (CompliantMotion::ChainGrip(grip), noise, stages)
                    }
                };
                let f = |t: f64| {
                    let p = grip.at(&setup, t);
                    last.set(Some(p));
                    setup.grip_margins(t, p.friction, p.friction_rate)
                };
                let event = stages
                    .iter()
                    .find_map(|&(from, to, curvature, step)| {
                        first_rise_from_tangent(f, from, to, step, [curvature; 2], [noise; 2])
                    })
                    .map(|(t, branch)| (t, if branch == 0 { 1.0 } else { -1.0 }));
                (grip, event)
            }
        };
        // A transition within rounding of the end changes nothing.
        let event = event.filter(|&(t, _)| t < end * (1.0 - 1e-13));
        let t1 = event.map_or(end, |(t, _)| t);
        let point = match last.get() {
            Some(p) if p.state.t == t1 => p,
            _ => motion.at(&setup, t1),
        };
        state = point.state;
        e = point.e;
        full = match &motion {
            CompliantMotion::Slide(CompliantSlide {
                rigid: Rigid::Chain(chain),
                ..
            }) => chain.full(&setup, t1),
            CompliantMotion::ChainGrip(grip) => grip.full(&setup, t1),
            _ => ChainState::from_contact(&state),
        };
        if t1 > t0 {
            phases.push(Phase {
                kind: if slide_dir.is_some() {
                    PhaseKind::Slide
                } else {
                    PhaseKind::Grip
                },
                slip_sign: slide_dir.map_or(0, |d| d as i8),
                cart: Cart::Moving(1),
                start: t0,
                end: t1,
                motion: Motion::Compliant(Box::new(motion)),
            });
        }
        let Some((_, next)) = event else {
            return Ok(finish(params, setup, phases, state));
        };
        // A slide ends in a grip; a grip breaks into a slide the way the force points.
        slide_dir = if slide_dir.is_some() {
            None
        } else {
            Some(next)
        };
        from_zero = true;
    }
    Err(SolveError::TooManyPhases)
}
