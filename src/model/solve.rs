//! Solving a bounce: the parameters choose the contact model, and the phase driver runs it.

use super::bounce::{Bounce, finish};
use super::cart::SingleCart;
use super::chain::ChainOfMasses;
use super::compliant::CompliantBall;
use super::driver::run;
use super::error::SolveError;
use super::limits;
use super::params::Params;
use super::registry::{BallKind, SupportKind};
use super::setup::Setup;

/// Solves one bounce exactly (Cross 2010, Sec. II): phase by phase in closed form, each transition
/// located by root finding on the exact expressions. Cancelled once the process is interrupted
/// ([`limits::interrupt`]).
pub fn solve(params: &Params) -> Result<Bounce, SolveError> {
    solve_cancellable(params, &limits::interrupted)
}

/// [`solve`], abandoned with [`SolveError::Cancelled`] as soon as `cancelled` returns true: it is asked
/// before every phase, so a caller (the explorer's worker, a headless command on Ctrl-C) can drop a solve
/// that is no longer wanted.
pub fn solve_cancellable(
    params: &Params,
    cancelled: &impl Fn() -> bool,
) -> Result<Bounce, SolveError> {
    limits::bounded(params, || solve_model(params, cancelled))
}

/// The model for `params` ([`Params::model`]), run by the driver (`limits::bounded` has validated them).
fn solve_model(params: &Params, cancelled: &impl Fn() -> bool) -> Result<Bounce, SolveError> {
    let kind = params.model();
    let (setup, phases, last) = match (kind.ball, kind.support) {
        (BallKind::Compliant, SupportKind::Cart | SupportKind::Chain) => {
            let (model, setup) = CompliantBall::new(params, params.stiffness > 0.0)?;
            let (phases, last) = run(&model, &setup, cancelled).map_err(|e| match e {
                SolveError::TooManyPhases { .. } => SolveError::TooManyPhases {
                    hint: " (a stiff, lightly damped ball chatters: raise --ball-damping, e.g. to 0.1, \
                           or lower --ball-stiffness)",
                },
                e => e,
            })?;
            (setup, phases, last)
        }
        (BallKind::Rigid, SupportKind::Chain) => {
            let setup = Setup::new(params);
            let (phases, last) = run(&ChainOfMasses::new(params, &setup)?, &setup, cancelled)?;
            (setup, phases, last)
        }
        (BallKind::Rigid, SupportKind::Cart) => {
            let setup = Setup::new(params);
            let (phases, last) = run(&SingleCart::new(params, &setup)?, &setup, cancelled)?;
            (setup, phases, last)
        }
    };
    Ok(finish(params, setup, phases, last))
}

/// The rigid ball on a chain of `params.chain` masses, for any N including 1, where it reproduces the
/// single cart to rounding (a compliant ball goes to its own model, as in [`solve`]).
pub fn solve_chain(params: &Params) -> Result<Bounce, SolveError> {
    limits::bounded(params, || solve_chain_model(params))
}

fn solve_chain_model(params: &Params) -> Result<Bounce, SolveError> {
    if params.model().compliant() {
        return solve(params);
    }
    let setup = Setup::new(params);
    let (phases, last) = run(&ChainOfMasses::new(params, &setup)?, &setup, &|| false)?;
    Ok(finish(params, setup, phases, last))
}

/// The compliant ball on the single cart (the chain's length ignored) with every grip solved by the
/// cart's own 4-state system, even with a spring: an independent check of [`solve`]'s modal grips.
pub fn solve_compliant_on_cart(params: &Params) -> Result<Bounce, SolveError> {
    let params = Params {
        chain: 1.0,
        ..*params
    };
    limits::bounded(&params, || {
        let (model, setup) = CompliantBall::new(&params, false)?;
        let (phases, last) = run(&model, &setup, &|| false)?;
        Ok(finish(&params, setup, phases, last))
    })
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use super::*;

    /// A check that says "cancel" from its `n`th call on, counting the calls.
    fn cancel_from(n: usize, calls: &Cell<usize>) -> impl Fn() -> bool + '_ {
        move || {
            calls.set(calls.get() + 1);
            calls.get() >= n
        }
    }

    #[test]
    fn cancellation_is_asked_between_phases_on_every_model() {
        let base = Params {
            cart_mass: 0.001,
            stiffness: 9554.0,
            ..Params::default()
        };
        for params in [
            base,
            Params { chain: 4.0, ..base },
            Params {
                ball_stiffness: 1e6,
                ball_damping: 0.5,
                ..base
            },
        ] {
            let whole = solve(&params).unwrap();
            assert!(whole.phases.len() >= 3);
            let calls = Cell::new(0);
            let never = solve_cancellable(&params, &cancel_from(usize::MAX, &calls)).unwrap();
            assert_eq!(never.outcome, whole.outcome);
            assert!(calls.get() >= whole.phases.len());
            let calls = Cell::new(0);
            let cancelled = solve_cancellable(&params, &cancel_from(2, &calls));
            assert_eq!(cancelled.unwrap_err(), SolveError::Cancelled);
            assert_eq!(calls.get(), 2, "stops at the first check that says so");
        }
    }
}
