//! The compliant ball gripping a chain's first mass held to a free frame by string friction (issue 23).
//!
//! Held, the first mass keeps its place d on the frame, so the two are one body B of mass
//! m_B = M/N + M_t, and the links behind form a ring tied to B at both ends ([`ring`]). The ball's
//! spring and dashpot pull on B: ball, stretch and ring are the compliant ball's grip on a chain whose
//! modes are the ring's, B first ([`Chain::held_ring`]), with the rigid translation taken out as on any
//! free frame ([`ChainGrip`]), in the ring's coordinates (`ring_coordinates::coordinates`, `ring_coordinates::place`). The
//! phase ends when |F| reaches mu N, or when the force the frame must give the first mass,
//! push = F - T_1 - (M/N) a_B ([`ring::held_push`]), reaches ±F_c.

use std::sync::Arc;

use super::super::chain::{Chain, ChainState};
use super::super::chain::{ring, ring_coordinates};
use super::super::setup::Setup;
use super::{ChainGrip, GripModes, Point};

/// A grip on a first mass held to a free frame.
#[derive(Clone, Debug)]
pub struct HeldRingGrip {
    /// The ball on the ring, in the ring's coordinates.
    pub grip: ChainGrip,
    /// The chain and the frame (not the ring).
    pub chain: Arc<Chain>,
    /// The whole chain at the start.
    pub start: ChainState,
}

impl HeldRingGrip {
    /// The grip from `start` with stretch `e`, on the ring's grip `modes`.
    pub fn new(
        modes: Arc<GripModes>,
        chain: Arc<Chain>,
        setup: &Setup,
        start: ChainState,
        e: f64,
    ) -> Self {
        let (x, v) = ring_coordinates::coordinates(&chain, &start);
        // The ring as its grip's chain: a framed chain of N - 1 links, its frame the last entry.
        let on_ring = ChainState {
            x,
            v,
            frame: chain.n - 1,
            ..start
        };
        HeldRingGrip {
            grip: ChainGrip::new(modes, on_ring, e, setup, 0.0),
            chain,
            start,
        }
    }

    /// The ball and the held first mass at `t`: at its place d on the frame, moving with B.
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        let mut p = self.grip.at(setup, t);
        p.state.x = self.start.x[0] - self.start.x[self.start.frame];
        p.frame = (p.state.v, p.accel);
        p
    }

    /// The ball, the whole chain and the frame at `t`.
    pub fn full(&self, setup: &Setup, t: f64) -> ChainState {
        let on_ring = self.grip.full(setup, t);
        let (x, v) = ring_coordinates::place(&self.chain, &self.start, &on_ring.x, &on_ring.v);
        ChainState {
            x,
            v,
            frame: self.start.frame,
            ..on_ring
        }
    }

    /// The push the string friction must hold, and its rate, at the point `p` of time `t`.
    pub fn push(&self, setup: &Setup, p: &Point) -> (f64, f64) {
        let full = self.full(setup, p.state.t);
        ring::held_push(&self.chain, (p.friction, p.friction_rate), p.accel, &full)
    }

    /// A bound on |push''| over the phase given a bound on |F''|, and the size of push's terms: the
    /// ring is driven through B by the ball's force, at most mu N ([`ring::ring_push_bounds`]).
    pub fn push_bounds(&self, setup: &Setup, force_curvature: f64) -> (f64, f64) {
        let chain = &self.chain;
        let frame = chain.frame.unwrap_or(0.0);
        let share = frame / (chain.link_mass + frame);
        ring::ring_push_bounds(
            chain,
            chain.held(1.0),
            &self.start,
            true,
            share * force_curvature,
            setup,
        )
    }
}
