//! One phase of a bounce: its kind, its time span and its closed-form motion, which gives the state,
//! the friction and the cart's energy at any time inside it.

use serde::Serialize;

use super::cart::CartMotion;
use super::chain::ChainMotion;
use super::compliant::CompliantMotion;
use super::contact::Cart;
use super::setup::{Setup, State};

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

/// The closed forms of every contact model: one phase's motion.
#[derive(Clone, Debug)]
pub enum Motion {
    /// A phase on the single cart (sliding or gripping).
    Cart(CartMotion),
    /// A phase on a chain of masses (sliding or gripping).
    Chain(ChainMotion),
    /// A phase of a compliant ball, on the single cart or on a chain.
    Compliant(Box<CompliantMotion>),
}

impl From<CartMotion> for Motion {
    fn from(motion: CartMotion) -> Self {
        Motion::Cart(motion)
    }
}

impl From<ChainMotion> for Motion {
    fn from(motion: ChainMotion) -> Self {
        Motion::Chain(motion)
    }
}

impl From<CompliantMotion> for Motion {
    fn from(motion: CompliantMotion) -> Self {
        Motion::Compliant(Box::new(motion))
    }
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
            Motion::Cart(cart) => cart.at(setup, t),
            Motion::Chain(chain) => chain.contact(setup, t).state,
            Motion::Compliant(c) => c.at(setup, t).state,
        }
    }

    /// The friction force on the ball, positive backward, in this phase at `state`.
    pub fn friction(&self, setup: &Setup, state: &State) -> f64 {
        match &self.motion {
            Motion::Cart(cart) => cart.friction(setup, state),
            Motion::Chain(chain) => chain.contact(setup, state.t).friction,
            Motion::Compliant(c) => c.at(setup, state.t).friction,
        }
    }

    /// The state at the start of the phase.
    pub fn initial(&self) -> State {
        match &self.motion {
            Motion::Cart(cart) => cart.initial(),
            Motion::Chain(chain) => chain.start.contact(),
            Motion::Compliant(c) => c.initial(),
        }
    }

    /// A compliant ball's stretch e (m) and its patch's slip on the cart (m/s) at `t`; `None` for a rigid
    /// ball.
    pub fn patch_at(&self, setup: &Setup, t: f64) -> Option<(f64, f64)> {
        match &self.motion {
            Motion::Compliant(c) => Some(c.stretch_and_patch_slip(setup, t)),
            _ => None,
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
    pub(super) fn on_chain(&self) -> bool {
        match &self.motion {
            Motion::Chain(_) => true,
            Motion::Compliant(c) => c.chain_energy_known(),
            _ => false,
        }
    }

    /// The fastest frequency of the cart (or the chain) while the ball slides, rad/s: how densely a scan
    /// of this phase must sample to see every swing.
    pub fn fastest(&self, setup: &Setup) -> f64 {
        match &self.motion {
            Motion::Chain(chain) => chain.chain().slide.fastest,
            Motion::Compliant(c) => c.fastest(setup),
            _ => setup.omega_slide,
        }
    }

    /// The power lost to sliding friction at `t`: F times the slip at the contact (for a compliant ball,
    /// the slip of its contact patch on the cart).
    pub(super) fn friction_power(&self, setup: &Setup, t: f64) -> f64 {
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
