//! The grip of a compliant ball on a chain's first mass held still by string friction: the two sides
//! of the held mass no longer feel each other. The ball's stretch rings down against a still surface
//! (the single cart's held grip, m_eff e'' = -(k_b e + c_b e')), while the masses behind swing in their
//! own clamped modes about the straight line from the held mass to the wall (the rigid ball's held
//! phase). The phase ends when |F| reaches mu N, or when the net push on the held mass,
//! F - N k (X_1 - X_2), reaches ±F_c.

use std::sync::Arc;

use super::super::chain::{Chain, ChainMotion, ChainState};
use super::super::contact::Cart;
use super::super::setup::Setup;
use super::{Compliance, CompliantGrip, Point};

/// A grip on a held first mass.
#[derive(Clone, Debug)]
pub struct HeldChainGrip {
    /// The ball's stretch on the held mass.
    pub ball: CompliantGrip,
    /// The masses behind it.
    pub chain: ChainMotion,
}

impl HeldChainGrip {
    pub fn new(
        compliance: Compliance,
        chain: Arc<Chain>,
        setup: &Setup,
        start: ChainState,
        e: f64,
    ) -> Self {
        HeldChainGrip {
            ball: CompliantGrip::new(compliance, start.contact(), e, setup, Cart::Stuck),
            chain: ChainMotion::new(&chain, setup, &start, 0.0, Cart::Stuck),
        }
    }

    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        self.ball.at(setup, t)
    }

    /// The ball and the whole chain at `t`.
    pub fn full(&self, setup: &Setup, t: f64) -> ChainState {
        let ball = self.ball.at(setup, t).state;
        ChainState {
            vx: ball.vx,
            omega: ball.omega,
            ..self.chain.full(setup, t)
        }
    }

    /// The fastest rate in the phase: the ball's grip (bounded as on the cart) or the chain behind.
    pub fn fastest(&self) -> f64 {
        self.ball
            .compliance
            .fastest
            .max(self.chain.chain().clamped().fastest)
    }
}
