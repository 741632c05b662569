//! String friction on the chain's first mass: the events that end a phase and the mode that follows.
//!
//! Moving in direction d, the first mass feels -d F_c besides the ball's friction, and the phase also
//! ends when its velocity V_1 reaches zero. Held still, the ball slides on (Eqs. (1), (2) with V = 0) or
//! rolls on a still surface, and the phase ends when the net push on the first mass, F - N k (X_1 - X_2),
//! reaches ±F_c (F = 0 for a rolling ball). What follows is decided by [`transition::next`] with the
//! first mass in the cart's place. On a free frame the first mass's velocity is measured relative to the
//! frame, and a first mass held to it is the ring's (`ring.rs`, which also decides what follows).

use super::super::contact::{Ball, Cart, Cause, Mode, ROUNDING};
use super::super::events::first_rise;
use super::super::setup::Setup;
use super::super::transition::{self, Touched};
use super::{Chain, ChainMotion, ChainOfMasses, ChainState, ring};

/// The mode after `cause` at `state`, in a phase that was `ball` and `cart`.
pub fn next(
    chain: &Chain,
    setup: &Setup,
    state: &ChainState,
    ball: Ball,
    cart: Cart,
    cause: Cause,
) -> Mode {
    if state.frame > 0 {
        return ring::next(chain, setup, state, ball, cart, cause);
    }
    let touched = Touched {
        t: state.t,
        mass: chain.link_mass,
        spring: chain.link_force(state),
        v: state.v[0],
    };
    transition::next(setup, &touched, ball, cart, cause)
}

/// The first event of a phase with string friction: the slip reaching zero or the grip breaking, and
/// the first mass stopping (moving) or being pushed free (held).
pub fn first_event(
    model: &ChainOfMasses,
    setup: &Setup,
    motion: &ChainMotion,
    state: &ChainState,
    (ball, cart): Mode,
    cause: Cause,
) -> Option<(f64, Cause)> {
    let (t0, end) = (state.t, setup.duration);
    // Event functions that start on their own zero are measured from their start value.
    let start = motion.contact(setup, t0);
    let slip_offset = if matches!(cause, Cause::SlipZero | Cause::GripBreak(_)) {
        setup.slip(&start.state)
    } else {
        0.0
    };
    // The first mass's velocity and acceleration relative to the frame (to the wall).
    let relative = |c: &super::motion::Contact| (c.state.v - c.frame.0, c.accel - c.frame.1);
    let v_offset = if matches!(cause, Cause::Start | Cause::CartStop | Cause::Unstick(_)) {
        relative(&start).0
    } else {
        0.0
    };
    let framed = state.frame > 0;
    if framed && cart == Cart::Stuck {
        return ring::first_event(setup, motion, state, ball, model.incoming, slip_offset);
    }
    let speeds = model.incoming + state.vx.abs() + setup.r * state.omega.abs();
    match (ball, cart) {
        (Ball::Slide(dir), Cart::Moving(d)) => {
            let d = f64::from(d);
            let f = |t: f64| {
                let c = motion.contact(setup, t);
                let rate = -c.friction / setup.m_eff - c.accel;
                let (v, accel) = relative(&c);
                [
                    (-dir * (setup.slip(&c.state) - slip_offset), -dir * rate),
                    (-d * (v - v_offset), -d * accel),
                ]
            };
            let (slip_curvature, terms) = motion.slip_curvature(setup);
            let (cart_curvature, cart_terms) = if framed {
                motion.relative_curvature(setup)
            } else {
                motion.cart_curvature(setup)
            };
            let noise = [
                ROUNDING * (speeds + terms),
                ROUNDING * (v_offset.abs() + cart_terms),
            ];
            let step = setup.event_step(model.chain.slide.fastest);
            first_rise(f, t0, end, step, [slip_curvature, cart_curvature], noise).map(
                |(t, branch)| {
                    let cause = if branch == 0 {
                        Cause::SlipZero
                    } else {
                        Cause::CartStop
                    };
                    (t, cause)
                },
            )
        }
        (Ball::Grip, Cart::Moving(d)) => {
            let d = f64::from(d);
            let f = |t: f64| {
                let c = motion.contact(setup, t);
                let [forward, backward] = setup.grip_margins(t, c.friction, c.friction_rate);
                let (v, accel) = relative(&c);
                [forward, backward, (-d * (v - v_offset), -d * accel)]
            };
            let (margin_curvature, terms) = motion.margin_curvature(setup);
            let (cart_curvature, cart_terms) = if framed {
                ring::grip_relative_curvature(motion, setup)
            } else {
                motion.cart_curvature(setup)
            };
            let noise = [
                ROUNDING * terms,
                ROUNDING * terms,
                ROUNDING * (v_offset.abs() + cart_terms),
            ];
            let curvature = [margin_curvature, margin_curvature, cart_curvature];
            let step = setup.event_step(model.chain.grip().fastest);
            first_rise(f, t0, end, step, curvature, noise).map(|(t, branch)| {
                let cause = match branch {
                    0 => Cause::GripBreak(1.0),
                    1 => Cause::GripBreak(-1.0),
                    _ => Cause::CartStop,
                };
                (t, cause)
            })
        }
        (ball, Cart::Stuck) => {
            // A rolling ball needs no friction on a still surface: its branch is a constant stand-in.
            let dir = match ball {
                Ball::Slide(dir) => dir,
                Ball::Grip => 0.0,
            };
            let f = |t: f64| {
                let c = motion.contact(setup, t);
                let slip = if dir == 0.0 {
                    (-1.0, 0.0)
                } else {
                    let rate = -c.friction / setup.m_eff;
                    (-dir * (setup.slip(&c.state) - slip_offset), -dir * rate)
                };
                let (spring, spring_rate) = motion.link(setup, t);
                let push = c.friction - spring;
                let push_rate = dir * setup.friction_limit_rate(t) - spring_rate;
                let [up, down] = setup.unstick_margins(push, push_rate);
                [slip, up, down]
            };
            let (link_curvature, link_terms) = motion.link_curvature();
            let friction = dir.abs() * setup.peak_friction();
            let slip_curvature = friction * setup.w / setup.m_eff;
            let push_curvature = friction * setup.w * setup.w + link_curvature;
            let forces = ROUNDING * (friction + link_terms + setup.cart_friction);
            let noise = [ROUNDING * speeds, forces, forces];
            let step = setup.event_step(model.chain.clamped().fastest);
            let curvature = [slip_curvature, push_curvature, push_curvature];
            first_rise(f, t0, end, step, curvature, noise)
                .map(|(t, branch)| (t, Cause::of_held(branch)))
        }
    }
}
