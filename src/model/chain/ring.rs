//! String friction under a chain on a free frame (issue 23): the first mass held to the frame.
//!
//! Held, the first mass keeps its place d = X_1 - X_f on the frame, so the two are one rigid body B of
//! mass m_B = M/N + M_t, and the links behind it form a ring tied to B at both ends: N k from B (through
//! the first mass) to the second link, ..., from the last link back to B (the frame). The ball's
//! friction F acts on B. The springs' rest line is X_i = X_f + d (N + 1 - i)/N (every spring stretched
//! by d/N, their tensions k d cancelling on every mass), so the ring's coordinates y_1 = X_f and
//! y_i = X_i - d (N + 1 - i)/N for i = 2..N obey the ring's own equations, with masses [m_B, M/N, ...]
//! ([`super::modes::Modes::ring`]) and the ball's friction on y_1; gripping, the ball's m_eff joins B.
//! Each phase is then one of the chain's closed forms ([`super::motion`]) in the ring's modes.
//!
//! The string friction holds the first mass while the force the frame must give it, from the first
//! mass's own equation with B's acceleration a_B = (F - T_1 + T_N)/m_B,
//! push = F - T_1 - (M/N) a_B (T_1 = N k (X_1 - X_2), T_N = N k (X_N - X_f)), stays within ±F_c; on one
//! mass (N = 1, T_1 = T_N = k y) this is the single cart's M_t F/(M + M_t) - k y. Moving relative to the
//! frame, the first mass stops when V_1 - V_f reaches zero. What follows each event is decided by
//! [`next`], the single cart's rule ([`super::super::transition`]) with the frame's recoil and the ring's
//! springs on B.

use super::super::contact::{Ball, Cart, Cause, Mode, ROUNDING};
use super::super::events::first_rise;
use super::super::setup::Setup;
use super::modes::{MAX, Modes};
use super::motion::Motion;
use super::ring_coordinates::coordinates;
use super::{Chain, ChainState};

/// The springs on the held body: T_1 = N k (X_1 - X_2) holding the first mass back and T_N =
/// N k (X_N - X_f) pulling the frame forward, with their rates.
fn springs(chain: &Chain, s: &ChainState) -> [(f64, f64); 2] {
    let (kappa, n, f) = (chain.link_stiffness, chain.n, s.frame);
    [
        (kappa * (s.x[0] - s.x[1]), kappa * (s.v[0] - s.v[1])),
        (kappa * (s.x[n - 1] - s.x[f]), kappa * (s.v[n - 1] - s.v[f])),
    ]
}

/// The first event of a phase with the first mass held to the frame: the slip reaching zero (sliding)
/// or the grip breaking, and the push on the first mass reaching ±F_c.
pub fn first_event(
    setup: &Setup,
    motion: &Motion,
    state: &ChainState,
    ball: Ball,
    incoming: f64,
    slip_offset: f64,
) -> Option<(f64, Cause)> {
    let chain = motion.chain();
    let (t0, end) = (state.t, setup.duration);
    let dir = match ball {
        Ball::Slide(dir) => dir,
        Ball::Grip => 0.0,
    };
    let push = |t: f64| {
        let (c, full) = motion.contact_and_full(setup, t);
        let f_rate = if dir == 0.0 {
            c.friction_rate
        } else {
            dir * setup.friction_limit_rate(t)
        };
        let (push, rate) = held_push(chain, (c.friction, f_rate), c.accel, &full);
        (c, push, rate)
    };
    let (push_curvature, push_terms) = push_bounds(motion, setup);
    let forces = ROUNDING * (push_terms + setup.cart_friction);
    let step = setup.event_step(motion.modes().fastest);
    let speeds = incoming + state.vx.abs() + setup.r * state.omega.abs();
    if dir == 0.0 {
        let f = |t: f64| {
            let (c, p, rate) = push(t);
            let [forward, backward] = setup.grip_margins(t, c.friction, c.friction_rate);
            let [up, down] = setup.unstick_margins(p, rate);
            [forward, backward, up, down]
        };
        let (margin_curvature, terms) = motion.margin_curvature(setup);
        let noise = [ROUNDING * terms, ROUNDING * terms, forces, forces];
        let curvature = [
            margin_curvature,
            margin_curvature,
            push_curvature,
            push_curvature,
        ];
        first_rise(f, t0, end, step, curvature, noise).map(|(t, b)| match b {
            0 => (t, Cause::GripBreak(1.0)),
            1 => (t, Cause::GripBreak(-1.0)),
            2 => (t, Cause::Unstick(1)),
            _ => (t, Cause::Unstick(-1)),
        })
    } else {
        let f = |t: f64| {
            let (c, p, rate) = push(t);
            let slip_rate = -c.friction / setup.m_eff - c.accel;
            let [up, down] = setup.unstick_margins(p, rate);
            [
                (
                    -dir * (setup.slip(&c.state) - slip_offset),
                    -dir * slip_rate,
                ),
                up,
                down,
            ]
        };
        let (slip_curvature, terms) = motion.slip_curvature(setup);
        let noise = [ROUNDING * (speeds + terms), forces, forces];
        let curvature = [slip_curvature, push_curvature, push_curvature];
        first_rise(f, t0, end, step, curvature, noise).map(|(t, b)| match b {
            0 => (t, Cause::SlipZero),
            1 => (t, Cause::Unstick(1)),
            _ => (t, Cause::Unstick(-1)),
        })
    }
}

/// The force the frame must give the held first mass to keep it on the frame, and its rate, given the
/// ball's force F on the body B and its rate (`friction`), B's acceleration a_B = (F - T_1 + T_N)/m_B
/// and the whole chain `full`: push = F - T_1 - (M/N) a_B.
pub fn held_push(
    chain: &Chain,
    (friction, friction_rate): (f64, f64),
    accel: f64,
    full: &ChainState,
) -> (f64, f64) {
    let (m1, body) = (
        chain.link_mass,
        chain.link_mass + chain.frame.unwrap_or(0.0),
    );
    let [(t1, t1_rate), (_, tn_rate)] = springs(chain, full);
    let accel_rate = (friction_rate - t1_rate + tn_rate) / body;
    (
        friction - t1 - m1 * accel,
        friction_rate - t1_rate - m1 * accel_rate,
    )
}

/// [`held_push`] at a transition, where the ball's force `friction` is known and B's acceleration
/// follows from it and the springs of `full`.
pub fn rest_push(chain: &Chain, friction: f64, full: &ChainState) -> f64 {
    let body = chain.link_mass + chain.frame.unwrap_or(0.0);
    let [(t1, _), (tn, _)] = springs(chain, full);
    friction - t1 - chain.link_mass * (friction - t1 + tn) / body
}

/// A bound on |push''| over a held phase, and the size of push's terms (the rigid ball's ring phase).
pub fn push_bounds(motion: &Motion, setup: &Setup) -> (f64, f64) {
    let chain = motion.chain();
    let share = chain.frame.unwrap_or(0.0) / (chain.link_mass + chain.frame.unwrap_or(0.0));
    let sliding = !motion.is_grip();
    let force_curvature = if sliding {
        share * setup.peak_friction() * setup.w * setup.w
    } else {
        share * motion.margin_curvature(setup).0
    };
    ring_push_bounds(
        chain,
        motion.modes(),
        &motion.start,
        sliding,
        force_curvature,
        setup,
    )
}

/// A bound on |push''| over a held phase from `start` in the ring's `modes`, and the size of push's
/// terms, given the ball's part of it, `force_curvature` >= (M_t/m_B) |F''|; `forced` when the ball's
/// force F (at most mu N) drives the ring through B, false when the ring swings freely (the rigid
/// ball's grip, its m_eff riding on B).
///
/// push = (M_t/m_B) (F - T_1) - (M/N / m_B) T_N. |F''| <= mu N0 w² sliding, and gripping the margins'
/// bound (which holds F_s''); each spring is N k Σ_j (Φ_aj - Φ_bj) q_j with |q_j''| <= |Φ_1j| |F| +
/// Ω_j E_j, E_j = sqrt(q_j'² + Ω_j² q_j²) at most its start value plus |Φ_1j| times the friction's
/// remaining impulse 2 mu N0 / w (forced; swinging freely, E_j fixed).
pub fn ring_push_bounds(
    chain: &Chain,
    modes: &Modes,
    start: &ChainState,
    forced: bool,
    force_curvature: f64,
    setup: &Setup,
) -> (f64, f64) {
    let n = chain.n;
    let body = chain.link_mass + chain.frame.unwrap_or(0.0);
    let share = chain.frame.unwrap_or(0.0) / body;
    let tail = chain.link_mass / body;
    let peak = setup.peak_friction();
    let (y, v) = coordinates(chain, start);
    let (mut q0, mut dq0) = ([0.0; MAX], [0.0; MAX]);
    modes.project_both((&y, &v), (&mut q0, &mut dq0));
    let (second, last) = (1 % n, n - 1);
    let mut curvature = force_curvature;
    let d = start.x[0] - start.x[start.frame];
    let mut terms = peak + chain.link_stiffness * d.abs() / n as f64;
    for j in 0..modes.n {
        let omega = modes.omega[j];
        let phi = modes.shape[0][j];
        let mut energy = (dq0[j] * dq0[j] + (omega * q0[j]).powi(2)).sqrt();
        let mut accel = omega * energy;
        if forced {
            energy += phi.abs() * 2.0 * peak / setup.w;
            accel = phi.abs() * peak + omega * energy;
        }
        let front = (phi - modes.shape[second][j]).abs();
        let back = (modes.shape[last][j] - phi).abs();
        let reach = chain.link_stiffness * (share * front + tail * back);
        curvature += reach * accel;
        if omega > 0.0 {
            terms += chain.link_stiffness * (front + back) * energy / omega;
        }
    }
    (curvature, terms)
}

/// A bound on |(V_1 - V_f)''| over a grip phase of a first mass moving relative to the frame, and the
/// size of its terms: V_1 - V_f = Σ (Φ_1j - Φ_fj) q_j', each mode swinging freely about its equilibrium
/// under the string friction q_e = (Φ_1j - Φ_fj) push/Ω_j², so |q_j'''| <= Ω_j² E_j with E_j =
/// sqrt(q_j'² + Ω_j² (q_j - q_e)²) fixed (the rigid translation has Φ_1j = Φ_fj and drops out).
pub fn grip_relative_curvature(motion: &Motion, setup: &Setup) -> (f64, f64) {
    let modes = motion.modes();
    let start = &motion.start;
    let frame = start.frame;
    let (mut q0, mut dq0) = ([0.0; MAX], [0.0; MAX]);
    modes.project_both((&start.x, &start.v), (&mut q0, &mut dq0));
    let push = motion.cart.friction(setup);
    let (mut curvature, mut terms) = (0.0, 0.0);
    for j in 0..modes.n {
        let omega = modes.omega[j];
        let share = modes.shape[0][j] - modes.shape[frame][j];
        if share == 0.0 || omega == 0.0 {
            continue;
        }
        let swing = (dq0[j].powi(2) + (omega * q0[j] - share * push / omega).powi(2)).sqrt();
        curvature += share.abs() * omega * omega * swing;
        terms += share.abs() * swing;
    }
    (curvature, terms)
}

/// The mode after `cause` at `state` on a free frame, in a phase that was `ball` and `cart`: every
/// candidate is checked, static ones first, as [`super::super::transition::next`] does, with the
/// forces on the first mass and the frame. A broken grip slides the way F_s pulled, a first mass pushed
/// free moves the way it was pushed.
pub fn next(
    chain: &Chain,
    setup: &Setup,
    state: &ChainState,
    ball: Ball,
    cart: Cart,
    cause: Cause,
) -> Mode {
    let any_ball = [Ball::Grip, Ball::Slide(1.0), Ball::Slide(-1.0)];
    let any_cart = [Cart::Stuck, Cart::Moving(1), Cart::Moving(-1)];
    let relative = state.v[0] - state.v[state.frame];
    let (balls, slip_at_rest): (&[Ball], bool) = match cause {
        Cause::GripBreak(sign) => (&[Ball::Slide(sign)], false),
        Cause::SlipZero => (&any_ball, true),
        _ if ball == Ball::Grip => (&any_ball, true),
        _ => (std::slice::from_ref(&ball), false),
    };
    let unstick;
    let (carts, cart_at_rest): (&[Cart], bool) = match cause {
        Cause::Unstick(dir) => {
            unstick = [Cart::Moving(dir)];
            (&unstick, false)
        }
        _ if cart == Cart::Stuck || cause == Cause::CartStop || relative == 0.0 => {
            (&any_cart, true)
        }
        _ => (std::slice::from_ref(&cart), false),
    };
    let limit = if state.t == 0.0 {
        0.0
    } else {
        setup.mu * setup.normal(state.t)
    };
    let [(t1, _), (tn, _)] = springs(chain, state);
    let forces = Forces {
        limit,
        t1,
        tn,
        slip_at_rest,
        cart_at_rest,
    };
    let mut best = (f64::INFINITY, balls[0], carts[0]);
    for &b in balls {
        for &c in carts {
            let violation = violation(chain, setup, &forces, b, c);
            if violation == 0.0 {
                return (b, c);
            }
            if violation < best.0 {
                best = (violation, b, c);
            }
        }
    }
    (best.1, best.2)
}

/// The forces at a transition: mu N, the springs on the first mass (T_1) and on the frame (T_N), and
/// which contacts are at rest.
struct Forces {
    limit: f64,
    t1: f64,
    tn: f64,
    slip_at_rest: bool,
    cart_at_rest: bool,
}

/// How far (in newtons) the modes `ball` and `cart` are from consistent: 0 when they are.
fn violation(chain: &Chain, setup: &Setup, at: &Forces, ball: Ball, cart: Cart) -> f64 {
    let Forces {
        limit,
        t1,
        tn,
        slip_at_rest,
        cart_at_rest,
    } = *at;
    let (m1, mt, m_eff, fc) = (
        chain.link_mass,
        chain.frame.unwrap_or(0.0),
        setup.m_eff,
        setup.cart_friction,
    );
    let body = m1 + mt;
    match (ball, cart) {
        (Ball::Grip, Cart::Stuck) => {
            // The ball rides on B: (m_B + m_eff) a_B = T_N - T_1, F_s = -m_eff a_B.
            let accel = (tn - t1) / (body + m_eff);
            let friction = -m_eff * accel;
            let push = friction - t1 - m1 * accel;
            (friction.abs() - limit).max(0.0) + (push.abs() - fc).max(0.0)
        }
        (Ball::Slide(dir), Cart::Stuck) => {
            let friction = dir * limit;
            let accel = (friction - t1 + tn) / body;
            let push = friction - t1 - m1 * accel;
            let mut v = (push.abs() - fc).max(0.0);
            if slip_at_rest {
                // slip' = -F/m_eff - a_B must carry the slip the way `dir` says.
                v += (-dir * (-friction / m_eff - accel) * m_eff).max(0.0);
            }
            v
        }
        (Ball::Grip, Cart::Moving(d)) => {
            let string = f64::from(d) * fc;
            let gripped = m1 + m_eff;
            let friction = m_eff * (t1 + string) / gripped;
            let mut v = (friction.abs() - limit).max(0.0);
            if cart_at_rest {
                // (V_1 - V_f)' must start the way `d` says (in newtons of the reduced mass).
                let relative = -(t1 + string) / gripped - (tn + string) / mt;
                let reduced = gripped * mt / (gripped + mt);
                v += (-f64::from(d) * relative * reduced).max(0.0);
            }
            v
        }
        (Ball::Slide(dir), Cart::Moving(d)) => {
            let friction = dir * limit;
            let string = f64::from(d) * fc;
            let accel = (friction - t1 - string) / m1;
            let mut v = 0.0;
            if cart_at_rest {
                let relative = accel - (tn + string) / mt;
                let reduced = m1 * mt / body;
                v += (-f64::from(d) * relative * reduced).max(0.0);
            }
            if slip_at_rest {
                v += (-dir * (-friction / m_eff - accel) * m_eff).max(0.0);
            }
            v
        }
    }
}
