//! The heatmap's best point: not the best grid cell but the largest omega2 near it, refined by Brent's
//! method along the cart mass and the stiffness in turn (on log scales, within the cells on either side
//! of the best one), as `optimize` refines its scan.

use std::cell::Cell;

use crate::analysis::brent;
use crate::model::{Params, SolveError, solve_cancellable};

use super::grid::{MASSES, STIFFNESSES, mass, stiffness};

/// The best point found: cart mass (kg), stiffness (N/m) and omega2 (rad/s) there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peak {
    pub mass: f64,
    pub stiffness: f64,
    pub omega2: f64,
}

/// Rounds of one search along each axis.
const ROUNDS: usize = 3;

/// The peak near the grid cell (`i`, `j`) for the other parameters in `params`; `None` if `cancelled`
/// says so or the core refuses the cell itself.
pub fn refine(
    params: &Params,
    i: usize,
    j: usize,
    cancelled: &(impl Fn() -> bool + Sync),
) -> Option<Peak> {
    let stopped = Cell::new(false);
    let omega2 = |ln_mass: f64, ln_k: f64| {
        let p = Params {
            cart_mass: ln_mass.exp(),
            stiffness: ln_k.exp(),
            ..*params
        };
        match solve_cancellable(&p, cancelled) {
            Ok(b) => b.outcome.omega2,
            Err(SolveError::Cancelled) => {
                stopped.set(true);
                f64::NEG_INFINITY
            }
            Err(_) => f64::NEG_INFINITY,
        }
    };
    // Minimise -omega2; a refused point counts as the worst.
    let cost = |w: f64| if w.is_finite() { -w } else { f64::MAX };
    let span = |value: fn(usize) -> f64, k: usize, n: usize| {
        (
            value(k.saturating_sub(1)).ln(),
            value((k + 1).min(n - 1)).ln(),
        )
    };
    let (mass_low, mass_high) = span(mass, i, MASSES);
    let (k_low, k_high) = span(stiffness, j, STIFFNESSES);
    let (mut u, mut v) = (mass(i).ln(), stiffness(j).ln());
    let mut best = omega2(u, v);
    if !best.is_finite() {
        return None;
    }
    for _ in 0..ROUNDS {
        let (x, f) = brent::minimize(|x| cost(omega2(x, v)), mass_low, mass_high, u, 1e-4);
        u = x;
        best = best.max(-f);
        let (y, f) = brent::minimize(|y| cost(omega2(u, y)), k_low, k_high, v, 1e-4);
        v = y;
        best = best.max(-f);
        if stopped.get() {
            return None;
        }
    }
    Some(Peak {
        mass: u.exp(),
        stiffness: v.exp(),
        omega2: best,
    })
}
