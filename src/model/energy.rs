//! Where the incoming energy went: ball, cart (or chain), friction, the normal loss, string friction and
//! the compliant ball's spring and dashpot. The friction loss is integrated over the exact solution, so
//! the residual checks the solution.

use serde::Serialize;

use super::contact::Cart;
use super::params::Params;
use super::phase::{Phase, PhaseKind};
use super::setup::{Setup, State};

/// Where the incoming energy went, J.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Energy {
    /// Ball kinetic energy (translation and rotation) before the bounce.
    pub initial: f64,
    /// Ball kinetic energy after.
    pub final_ball: f64,
    /// Cart kinetic plus spring energy after (on a chain, the kinetic and spring energy of all its masses
    /// and springs: the energy left in the chain).
    pub final_cart: f64,
    /// ∫ F · slip dt, integrated over the sliding phases of the exact solution.
    pub friction_loss: f64,
    /// Lost in the normal direction, m v_y1^2 (1 - e_y^2)/2 on a clamped frame; on a frame of normal mass
    /// M_n, what the ball loses less the frame's normal kinetic energy, mu_n v_y1^2 (1 - e_y^2)/2 with
    /// mu_n = m M_n/(m + M_n).
    pub normal_loss: f64,
    /// Work against the string friction on the cart: F_c times the distance the cart (on a chain, its
    /// first mass) travelled.
    pub cart_friction_loss: f64,
    /// Energy left in the compliant ball's tangential spring as it leaves, k_b e(T)²/2 (0 for a rigid ball).
    pub ball_spring: f64,
    /// Lost in the compliant ball's dashpot, ∫ c_b e'² dt over the contact (0 for a rigid ball).
    pub dashpot_loss: f64,
    /// The frame's kinetic energy after the impact, normal and along the surface (0 on a clamped
    /// frame).
    pub frame: f64,
    /// (initial - final_ball - final_cart - friction_loss - normal_loss - cart_friction_loss - ball_spring
    /// - dashpot_loss - frame) / initial.
    pub residual: f64,
}

/// A sum from +0.0: nothing lost prints as 0, never -0 (Rust's float `sum` starts from -0.0).
fn add(sum: f64, x: f64) -> f64 {
    sum + x
}

/// The energy budget of a solved bounce (see [`Bounce::energy`]).
pub(super) fn energy_budget(
    params: &Params,
    setup: &Setup,
    phases: &[Phase],
    last: &State,
) -> Energy {
    let first = setup.initial(params.spin);
    let vy2 = setup.vy2();
    let initial = setup.ball_tangential_energy(&first) + 0.5 * setup.m * setup.vy1 * setup.vy1;
    let final_ball = setup.ball_tangential_energy(last) + 0.5 * setup.m * vy2 * vy2;
    let final_cart = phases.last().map_or_else(
        || setup.cart_energy(last),
        |p| p.motion().surface_energy(setup, last),
    );
    let frame = setup.frame_energy(
        phases
            .last()
            .map_or(0.0, |p| p.motion().frame_velocity(setup, p.end)),
    );
    let normal_loss = match setup.frame_normal_mass {
        None => 0.5 * setup.m * (setup.vy1 * setup.vy1 - vy2 * vy2),
        Some(mn) => {
            let reduced = setup.m * mn / (setup.m + mn);
            0.5 * reduced * (1.0 - params.ey * params.ey) * setup.vy1 * setup.vy1
        }
    };
    // The cart never reverses within a phase (its stopping ends the phase), so the distance it
    // travels in a phase is |X(end) - X(start)|.
    let cart_friction_loss = setup.cart_friction
        * phases
            .iter()
            .filter(|p| p.cart != Cart::Stuck)
            .map(|p| (p.state_at(setup, p.end).x - p.initial().x).abs())
            .fold(0.0, add);
    let friction_loss = phases
        .iter()
        .filter(|p| p.kind == PhaseKind::Slide)
        .map(|p| p.motion().friction_work(setup, p.start, p.end))
        .fold(0.0, add);
    let dashpot_loss = phases
        .iter()
        .map(|p| p.motion().dashpot_loss(setup, p.start, p.end))
        .fold(0.0, add);
    let ball_spring = phases
        .last()
        .map_or(0.0, |p| p.motion().ball_spring_energy(setup, p.end));
    Energy {
        initial,
        final_ball,
        final_cart,
        friction_loss,
        normal_loss,
        cart_friction_loss,
        ball_spring,
        dashpot_loss,
        frame,
        residual: (initial
            - final_ball
            - final_cart
            - friction_loss
            - normal_loss
            - cart_friction_loss
            - ball_spring
            - dashpot_loss
            - frame)
            / initial,
    }
}
