//! One phase of a bounce: its kind, its time span and its closed-form motion, which the model that solved
//! it answers for ([`PhaseMotion`]): the state, the friction and the surface's energy at any time inside it.

use serde::Serialize;

use super::contact::{Cart, PhaseMotion};
use super::registry::Motion;
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
    /// The model's closed form of this phase, which answers every query about it.
    pub fn motion(&self) -> &dyn PhaseMotion {
        self.motion.get()
    }

    /// The exact state at `t` (meaningful for `t` in `[start, end]`).
    pub fn state_at(&self, setup: &Setup, t: f64) -> State {
        self.motion().state_at(setup, t)
    }

    /// The friction force on the ball, positive backward, in this phase at `state`.
    pub fn friction(&self, setup: &Setup, state: &State) -> f64 {
        self.motion().friction(setup, state)
    }

    /// The state at the start of the phase.
    pub fn initial(&self) -> State {
        self.motion().initial()
    }

    /// A compliant ball's stretch e (m) and its patch's slip on the cart (m/s) at `t`; `None` for a rigid
    /// ball.
    pub fn patch_at(&self, setup: &Setup, t: f64) -> Option<(f64, f64)> {
        self.motion().patch_at(setup, t)
    }

    /// Kinetic plus spring energy of the cart, or of the whole chain, at `t`.
    pub fn cart_energy_at(&self, setup: &Setup, t: f64) -> f64 {
        self.motion()
            .surface_energy(setup, &self.state_at(setup, t))
    }

    /// The fastest angular frequency of the surface in this phase, rad/s: how densely a scan of the phase
    /// must sample to see every swing.
    pub fn fastest(&self, setup: &Setup) -> f64 {
        self.motion().fastest(setup)
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
