//! Which phase follows a transition: the combination of what the ball does (slide one way or the other,
//! or grip) and what the cart does (move one way or the other, or stick) that is consistent with the
//! friction laws at the contact and, with string friction, at the cart. Shared by the single cart and
//! the chain, whose first mass plays the cart: only the forces on the mass the ball touches decide.

use super::contact::{Ball, Cart, Cause};
use super::setup::Setup;
use super::trig::sin;

/// The mass the ball touches at a transition: the single cart, or a chain's first mass.
#[derive(Clone, Copy, Debug)]
pub struct Touched {
    pub t: f64,
    /// Its mass, kg (M, or M/N on a chain).
    pub mass: f64,
    /// The spring force holding it back, N: k X on the cart, N k (X_1 - X_2) on a chain's first mass.
    pub spring: f64,
    /// Its velocity, m/s.
    pub v: f64,
}

/// The ball and cart modes of the phase that starts at `touched` after `cause`, in a phase that was
/// `ball` and `cart`.
///
/// A broken grip or a cart that comes unstuck leaves only one choice. Otherwise every candidate is
/// checked, static ones first: a grip needs |F_s| <= mu N (Eq. 5), a stuck cart a net push of at most
/// F_c, and a mode that starts from rest (zero slip, a cart at rest) must move the way its friction
/// allows. Without string friction this is the paper's rule: grip if Eq. (5) can hold the ball, or
/// else the friction reverses.
pub fn next(
    setup: &Setup,
    touched: &Touched,
    ball: Ball,
    cart: Cart,
    cause: Cause,
) -> (Ball, Cart) {
    next_on(setup, touched, 1.0, ball, cart, cause)
}

/// [`next`] for a touched mass whose string friction acts against a support that recoils: `share` is
/// the part of the ball's friction that pushes the mass relative to its support, M_t/(M + M_t) on a
/// free frame of mass M_t (1 on a clamped one). Held to the frame, the cart and the frame accelerate
/// together at F/(M + M_t), so the string friction must hold M_t F/(M + M_t) - k y (a rolling ball
/// pushes nothing, and a moving cart's static friction is the clamped one's).
pub fn next_on(
    setup: &Setup,
    touched: &Touched,
    share: f64,
    ball: Ball,
    cart: Cart,
    cause: Cause,
) -> (Ball, Cart) {
    next_given(setup, touched, share, ball, cart, cause, || {
        sin(setup.w * touched.t)
    })
}

/// [`next_on`] for a model that may have sin(w t) at the transition at hand: `sin_wt` gives it, and is
/// asked only where the modes must be measured against mu N(t) (and N(t) is not the first contact's
/// or past the end).
pub fn next_given(
    setup: &Setup,
    touched: &Touched,
    share: f64,
    ball: Ball,
    cart: Cart,
    cause: Cause,
    sin_wt: impl FnOnce() -> f64,
) -> (Ball, Cart) {
    match cause {
        Cause::GripBreak(sign) => return (Ball::Slide(sign), cart),
        Cause::Unstick(dir) => return (ball, Cart::Moving(dir)),
        _ => {}
    }
    let any_ball = [Ball::Grip, Ball::Slide(1.0), Ball::Slide(-1.0)];
    let any_cart = [Cart::Stuck, Cart::Moving(1), Cart::Moving(-1)];
    // A gripping ball is at zero slip too, so a cart that stops under it may let it slide.
    let slip_at_rest = cause == Cause::SlipZero || ball == Ball::Grip;
    let cart_at_rest = setup.cart_friction > 0.0 && (touched.v == 0.0 || cause == Cause::CartStop);
    let balls: &[Ball] = if slip_at_rest {
        &any_ball
    } else {
        std::slice::from_ref(&ball)
    };
    let carts: &[Cart] = if cart_at_rest {
        &any_cart
    } else if setup.cart_friction == 0.0 {
        &[Cart::Moving(1)]
    } else {
        std::slice::from_ref(&cart)
    };
    // A sole candidate follows whatever its violation, so nothing need be measured (a slide goes on
    // after first contact, or a moving cart's ball keeps its mode).
    if let ([b], [c]) = (balls, carts) {
        return (*b, *c);
    }
    let at = At {
        limit: setup.mu * normal(setup, touched.t, sin_wt),
        mass: touched.mass,
        spring: touched.spring,
        share,
        slip_at_rest,
        cart_at_rest,
    };
    let mut best = (f64::INFINITY, balls[0], carts[0]);
    for &b in balls {
        for &c in carts {
            let violation = violation(setup, &at, b, c);
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

/// N(t) as [`Setup::normal`] gives it, N0 sin(w t) in contact and 0 after, with sin(w t) from `sin_wt`;
/// at first contact (t = +0), the first transition of every bounce, N0 x +0 without the series (sin(+0)
/// is +0, so the same bits).
#[inline]
fn normal(setup: &Setup, t: f64, sin_wt: impl FnOnce() -> f64) -> f64 {
    if t.to_bits() == 0 {
        setup.n0 * 0.0
    } else if (0.0..=setup.duration).contains(&t) {
        setup.n0 * sin_wt()
    } else {
        0.0
    }
}

/// The forces at a transition: mu N, the touched mass and the spring force on it, the part of the
/// ball's friction that pushes it relative to its support, and which contacts are at rest.
struct At {
    limit: f64,
    mass: f64,
    spring: f64,
    share: f64,
    slip_at_rest: bool,
    cart_at_rest: bool,
}

/// How far (in newtons) the modes `ball` and `cart` are from consistent: 0 when they are.
fn violation(setup: &Setup, at: &At, ball: Ball, cart: Cart) -> f64 {
    let At {
        limit,
        mass,
        spring,
        share,
        slip_at_rest,
        cart_at_rest,
    } = *at;
    let gripped_mass = mass + setup.m_eff;
    match (ball, cart) {
        // Rolling on a still cart needs no friction; the spring alone must not move the cart.
        (Ball::Grip, Cart::Stuck) => (spring.abs() - setup.cart_friction).max(0.0),
        (Ball::Grip, Cart::Moving(dir)) => {
            let string = f64::from(dir) * setup.cart_friction;
            // Eq. (5) with the string friction beside the spring force.
            let static_friction = setup.m_eff * (spring + string) / gripped_mass;
            let mut v = (static_friction.abs() - limit).max(0.0);
            if cart_at_rest {
                // (M + m_eff) V' = -k X - dir F_c must start the cart moving in `dir`.
                v += (f64::from(dir) * (spring + string)).max(0.0);
            }
            v
        }
        (Ball::Slide(dir), Cart::Stuck) => {
            let friction = dir * limit;
            let mut v = ((share * friction - spring).abs() - setup.cart_friction).max(0.0);
            if slip_at_rest {
                // On a still cart the friction only ever brings the slip back to zero.
                v += limit;
            }
            v
        }
        (Ball::Slide(dir), Cart::Moving(cart_dir)) => {
            let friction = dir * limit;
            let string = f64::from(cart_dir) * setup.cart_friction;
            let push = friction - spring - string;
            let mut v = 0.0;
            if cart_at_rest {
                // Relative to its support: M_t/(M + M_t) times M y'' on a free frame.
                v += (-f64::from(cart_dir) * (share * friction - spring - string)).max(0.0);
            }
            if slip_at_rest {
                // slip' = -F/m_eff - V' must carry the slip the way `dir` says.
                let slip_rate = -friction / setup.m_eff - push / mass;
                v += (-dir * slip_rate * setup.m_eff).max(0.0);
            }
            v
        }
    }
}

/// What a cart at rest does under the net force `push` on it (N, forward positive) besides its string
/// friction: held while |push| <= F_c, else moving the way it is pushed. A compliant ball's force on the
/// cart is continuous across every transition (it is carried by the ball's spring and dashpot), so this
/// is the whole rule at its cart: only the cart's stopping leaves a choice.
pub fn at_rest(setup: &Setup, push: f64) -> Cart {
    if push.abs() <= setup.cart_friction {
        Cart::Stuck
    } else if push > 0.0 {
        Cart::Moving(1)
    } else {
        Cart::Moving(-1)
    }
}
