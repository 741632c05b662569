//! Random rigid-ball bounces on a chain, and the agreement test, shared by the chain's tests with and
//! without string friction.

use snapback::model::Params;

use super::rng::Rng;

/// Random bounces, as the single cart's numerical test draws them (no string friction).
pub fn random_chain(rng: &mut Rng, chain: f64) -> Params {
    Params {
        angle_deg: rng.uniform(3.0, 90.0),
        speed: rng.uniform(2.0, 40.0),
        spin: rng.uniform(-300.0, 300.0),
        mu: rng.uniform(0.05, 0.8),
        duration: rng.uniform(2e-3, 8e-3),
        ey: rng.uniform(0.3, 1.0),
        mass: rng.uniform(0.04, 0.2),
        radius: rng.uniform(0.02, 0.05),
        alpha: rng.uniform(0.4, 0.67),
        cart_mass: if rng.unit() < 0.5 {
            rng.log_uniform(1e-5, 2e-3)
        } else {
            rng.log_uniform(2e-3, 10.0)
        },
        stiffness: if rng.unit() < 0.1 {
            0.0
        } else {
            rng.log_uniform(1e3, 1e5)
        },
        cart_friction: 0.0,
        chain,
        ball_stiffness: 0.0,
        ball_damping: 0.0,
        ..Params::default()
    }
}

/// `a` and `b` agree to `tol` relative to the larger of them and `scale`.
pub fn close(a: f64, b: f64, scale: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(scale)
}
