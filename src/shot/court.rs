//! The court: its lines (ITF rules, in the vertical plane of the shot) and the bounce on it, which is the
//! paper's model on a rigid surface, taken as the limit of a heavy free cart through the core.

use crate::model::{Bounce, Params, SolveError, SolveOptions, solve_with};

use super::frame::Incidence;

/// The net, m from the hitter's baseline.
pub const NET_X: f64 = 11.885;
/// The net's height at the centre, m.
pub const NET_HEIGHT: f64 = 0.914;
/// The opponent's baseline, m from the hitter's.
pub const BASELINE_X: f64 = 23.77;
/// The service lines stand this far from the net, m.
pub const SERVICE_LINE_FROM_NET: f64 = 6.40;

/// The court as the paper's cart: a free cart of 1000 t, so that the ball's pull moves it by a part in
/// 1e7 or less of the ball's own change (m/M = 6e-8 for a tennis ball): the rigid limit to that precision.
pub const COURT_MASS: f64 = 1e6;

/// The bounce on the court of a ball arriving at `incidence`: the ball of `p` (its mass, radius,
/// inertia and compliance), the court's friction, restitution and contact time, a heavy free cart on no
/// frame (the racquet's is the strings').
pub fn bounce(p: &Params, incidence: &Incidence) -> Result<Bounce, SolveError> {
    bounce_with(p, incidence, &SolveOptions::default())
}

/// [`bounce`] solved on `options`' terms.
pub fn bounce_with(
    p: &Params,
    incidence: &Incidence,
    options: &SolveOptions,
) -> Result<Bounce, SolveError> {
    let court = Params {
        angle_deg: incidence.theta1_deg,
        speed: incidence.speed,
        spin: incidence.spin,
        mu: p.court_mu,
        ey: p.court_ey,
        duration: p.court_duration,
        cart_mass: COURT_MASS,
        stiffness: 0.0,
        cart_friction: 0.0,
        chain: 1.0,
        frame_mass: 0.0,
        frame_normal_mass: 0.0,
        ..*p
    };
    solve_with(&court, options)
}
