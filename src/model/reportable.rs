//! The checks on a solved bounce before it is reported: its outcome must be finite, and the figures a
//! report prints (the spin in rpm, the energy budget) must not overflow f64.

use super::bounce::{Bounce, Outcome};
use super::error::{SolveError, Unsolvable};
use super::params::{PARAMS, ParamId, Solvable, spec};
use super::solvable::refusal;

/// The spin a report can print: the solve carries any spin, but its rpm and its energy overflow beyond.
const SPIN: Solvable = Solvable {
    smallest: 0.0,
    largest: 1e15,
};

/// Refuses a bounce whose printed figures overflow f64: the spin in rpm and the energy budget (its
/// terms are squares: I omega² overflows long before omega). The message names the parameter furthest
/// from the paper's value, in ratio, as the one that drives the overflow.
pub fn reportable(bounce: &Bounce) -> Result<(), Unsolvable> {
    let e = bounce.energy();
    let figures = [
        bounce.outcome.omega2 * 30.0 / std::f64::consts::PI,
        e.initial,
        e.final_ball,
        e.final_cart,
        e.friction_loss,
        e.normal_loss,
        e.cart_friction_loss,
        e.ball_spring,
        e.dashpot_loss,
        e.residual,
    ];
    if figures.iter().all(|x| x.is_finite()) {
        return Ok(());
    }
    let far = |(id, _): &(ParamId, Solvable)| {
        let value = bounce.params.get(*id).abs();
        let default = spec(*id).default.abs();
        if value == 0.0 || default == 0.0 {
            0.0
        } else {
            (value / default).ln().abs()
        }
    };
    let (id, limit) = PARAMS
        .iter()
        .filter_map(|row| row.solvable.map(|limit| (row.id, limit)))
        .chain(std::iter::once((ParamId::Spin, SPIN)))
        .max_by(|a, b| far(a).total_cmp(&far(b)))
        .expect("the table has rows");
    Err(Unsolvable {
        why: "beyond, the rebound's energy or its spin in rpm overflows f64",
        ..refusal(spec(id), &limit, bounce.params.get(id))
    })
}

/// Refuses an outcome that is not a finite number, naming its first quantity that is not.
#[inline]
pub(super) fn finite(bounce: &Bounce) -> Result<(), SolveError> {
    let o = &bounce.outcome;
    // Every value tested without a branch each; the name looked for only when one fails. The speed,
    // whose hypot is taken only then, is finite where both its components are and neither nears
    // f64::MAX (where one does, `not_finite` decides).
    let speed_finite = o.vx2.abs().max(o.vy2.abs()) < f64::MAX / 2.0;
    if quantities(o, 0.0)
        .iter()
        .fold(speed_finite, |all, (_, v)| all & v.is_finite())
    {
        Ok(())
    } else {
        not_finite(o)
    }
}

/// The refusal of an outcome that is not finite.
#[cold]
#[inline(never)]
fn not_finite(o: &Outcome) -> Result<(), SolveError> {
    match quantities(o, o.speed2())
        .iter()
        .find(|(_, v)| !v.is_finite())
    {
        Some(&(quantity, _)) => Err(SolveError::NotFinite { quantity }),
        None => Ok(()),
    }
}

/// The outcome's quantities by the names a refusal gives them, with its rebound `speed` (taken apart,
/// so that the check of every bounce need not compute it).
#[inline(always)]
fn quantities(o: &Outcome, speed: f64) -> [(&'static str, f64); 7] {
    [
        ("the rebound spin", o.omega2),
        ("the rebound velocity along the surface", o.vx2),
        ("the rebound velocity away from the surface", o.vy2),
        ("the rebound speed", speed),
        ("the rebound angle", o.theta2_deg),
        ("e_x", o.ex.unwrap_or(0.0)),
        ("the roll ratio", o.roll_ratio.unwrap_or(0.0)),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Params;

    #[test]
    fn an_overflowing_report_names_the_parameter_furthest_from_the_paper() {
        let p = Params {
            spin: -1e308,
            ..Params::default()
        };
        let bounce = crate::model::solve(&p).unwrap();
        let message = reportable(&bounce).unwrap_err().to_string();
        assert!(
            message.starts_with("--spin must be in [-1e15, 1e15] rad/s to be solved"),
            "{message}"
        );
        assert_eq!(
            reportable(&crate::model::solve(&Params::default()).unwrap()),
            Ok(())
        );
    }
}
