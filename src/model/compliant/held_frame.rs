//! The compliant ball on the single cart held to a free frame by string friction (issue 23). Held, the
//! cart and the frame move as one body of mass M + M_t and the spring's stretch y = X - X_f stays as it
//! is: the ball meets a free cart of that mass (k = 0, the body's own [`Setup`]). Sliding, its friction
//! F = dir mu N(t) accelerates the body at F/(M + M_t) (the rigid [`Slide`]); gripping, the ball's
//! stretch rings against the body with the reduced mass 1/μ = 1/m_eff + 1/(M + M_t) ([`CompliantGrip`]
//! on the free cart). To move the cart with the frame the string friction must hold
//! M_t F/(M + M_t) - k y on it, and the phase also ends when that reaches ±F_c
//! ([`super::transition::next_on`]'s friction share M_t/(M + M_t)).
//!
//! [`Slide`]: super::super::cart::Slide

use std::sync::Arc;

use super::super::chain::{Chain, ChainState};
use super::super::params::Params;
use super::super::setup::{Setup, State};
use super::{Compliance, CompliantMotion, Point};

/// What a held phase on a free frame needs: the body's setup and grip constants, and the share of the
/// ball's force that pushes the cart relative to the frame.
#[derive(Debug)]
pub struct FrameHold {
    /// The cart and the frame as one free cart of mass M + M_t, without spring or string friction.
    pub body: Setup,
    pub compliance: Compliance,
    /// M_t/(M + M_t).
    pub share: f64,
    /// The cart and the frame as a chain of one mass on the frame (for the whole state and its energy).
    pub chain: Arc<Chain>,
}

impl FrameHold {
    /// For `params` with a free frame of mass `frame` and the `chain` they make.
    pub fn new(params: &Params, setup: &Setup, frame: f64, chain: Arc<Chain>) -> Self {
        let body_params = Params {
            cart_mass: params.cart_mass + frame,
            stiffness: 0.0,
            cart_friction: 0.0,
            frame_mass: 0.0,
            // The normal impulse stays the framed one.
            frame_normal_mass: setup.frame_normal_mass.unwrap_or(0.0),
            chain: 1.0,
            ..*params
        };
        let body = Setup::new(&body_params);
        FrameHold {
            compliance: Compliance::new(&body_params, &body),
            body,
            share: frame / (params.cart_mass + frame),
            chain,
        }
    }
}

/// One phase of the ball on the cart held to the free frame.
#[derive(Clone, Debug)]
pub struct HeldOnFrame {
    pub hold: Arc<FrameHold>,
    /// The ball on the body, whose displacement is measured from the phase's start.
    pub inner: CompliantMotion,
    /// The spring's stretch y, fixed.
    pub y: f64,
    /// The frame's displacement at the start.
    frame_x: f64,
}

impl HeldOnFrame {
    pub fn new(hold: Arc<FrameHold>, inner: CompliantMotion, y: f64, frame_x: f64) -> Self {
        HeldOnFrame {
            hold,
            inner,
            y,
            frame_x,
        }
    }

    /// The body's contact state at `start`: the cart's velocity (the frame's), displaced by nothing yet.
    pub fn body_start(start: &ChainState) -> State {
        State {
            t: start.t,
            vx: start.vx,
            omega: start.omega,
            x: 0.0,
            v: start.v[start.frame],
        }
    }

    /// The ball and the cart at `t`: the cart at the stretch y, moving with the frame.
    #[inline]
    pub fn at(&self, t: f64) -> Point {
        let mut p = self.inner.at(&self.hold.body, t);
        p.frame = (p.state.v, p.accel);
        p.state.x = self.y;
        p
    }

    /// The ball, the cart and the frame at `t`.
    pub fn full(&self, t: f64) -> ChainState {
        let p = self.inner.at(&self.hold.body, t);
        let frame = self.frame_x + p.state.x;
        let mut full = ChainState::from_contact(&p.state);
        full.frame = self.hold.chain.frame_index();
        (full.x[0], full.x[full.frame]) = (frame + self.y, frame);
        (full.v[0], full.v[full.frame]) = (p.state.v, p.state.v);
        full
    }

    pub fn initial(&self) -> State {
        State {
            x: self.y,
            ..self.inner.initial()
        }
    }
}
