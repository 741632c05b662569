//! What the solver can finish. Every value in a parameter's range is valid input, but f64 carries a
//! bounce through only while its scales stay clear of overflow, underflow and rounding. So a solve is
//! bounded ([`bounded`]): each parameter is checked against the range that can be solved, a lightly
//! damped ball against the relaxation its dashpot can resolve, the event searches run within a work
//! budget, and the outcome must be finite. A headless command can interrupt every solve of the process
//! ([`interrupt`], on Ctrl-C) and follow how many have been solved ([`solved`]).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use super::bounce::Bounce;
use super::error::SolveError;
use super::events::{self, Stall};
use super::params::{ParamId, Params, spec};
use super::units;

/// A parameter value whose bounce f64 cannot resolve: the message names the flag, the range that can
/// be solved and the value given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("--{flag} must be in {range} to be solved ({why}); got {given}")]
pub struct Unsolvable {
    pub flag: &'static str,
    pub range: String,
    pub given: String,
    pub why: &'static str,
}

/// The magnitudes a parameter can be solved with: zero where its range allows it, or between `smallest`
/// and `largest`.
struct Solvable {
    id: ParamId,
    smallest: f64,
    largest: f64,
}

/// Why the scales are bounded.
const SCALES: &str = "beyond, the bounce's forces and rates leave what f64 resolves";

/// The dimensional scales of the ball, the impact and the cart, and the pure numbers that multiply
/// them. Within these, every product the solver forms stays below 1e200 in size and above 1e-200.
const SOLVABLE: &[Solvable] = &[
    Solvable {
        id: ParamId::Speed,
        smallest: 1e-15,
        largest: 1e15,
    },
    Solvable {
        id: ParamId::Mu,
        smallest: 0.0,
        largest: 1e6,
    },
    Solvable {
        id: ParamId::Duration,
        smallest: 1e-15,
        largest: 1e15,
    },
    Solvable {
        id: ParamId::Mass,
        smallest: 1e-15,
        largest: 1e15,
    },
    Solvable {
        id: ParamId::Radius,
        smallest: 1e-15,
        largest: 1e15,
    },
    Solvable {
        id: ParamId::Alpha,
        smallest: 1e-6,
        largest: 1e6,
    },
    Solvable {
        id: ParamId::CartMass,
        smallest: 1e-15,
        largest: 1e15,
    },
    Solvable {
        id: ParamId::Stiffness,
        smallest: 0.0,
        largest: 1e30,
    },
    Solvable {
        id: ParamId::CartFriction,
        smallest: 0.0,
        largest: 1e30,
    },
    Solvable {
        id: ParamId::BallStiffness,
        smallest: 0.0,
        largest: 1e30,
    },
];

/// The most decay times 1/lambda of a damped ball's stretch (lambda = k_b/c_b) that one contact may
/// hold: the slide's event search steps on that scale while the transient lasts, and a step must stay
/// far above the rounding of t.
pub const MAX_RELAXATIONS: f64 = 1e15;

/// Event evaluations per solve on the single cart: about twice what the heaviest bounces the
/// contact-rate limits admit need (a stiff, heavily damped ball near MAX_RADIANS: 5.6 million), a few
/// seconds of work.
const BUDGET: u64 = 12_000_000;

/// The work budget of one solve: `BUDGET` evaluations on the single cart, fewer on a chain of N
/// masses, whose evaluations cost about (N + 1)/2 times as much.
pub fn budget(params: &Params) -> u64 {
    let links = params.chain.clamp(1.0, 16.0) as u64;
    BUDGET * 2 / (links + 1)
}

/// The work a command may spend on all its solves, in evaluations weighted by their cost (see
/// [`weight`]): unlimited unless the command set it ([`limit_work`]).
static WORK_LEFT: AtomicU64 = AtomicU64::new(u64::MAX);

/// The work of a command whose bounces the program fixes: about ten seconds of solving (the paper's
/// `reproduce` takes 14 million units, on a chain of 4 masses 110 million).
pub const COMMAND_WORK: u64 = 300_000_000;

/// Limits the work of all the solves this process makes from now on to `units` (evaluations times
/// `weight`): for a command whose number of bounces is fixed by the program, not by the user
/// (`reproduce`, `figure`, `critical-angle`), so that parameters that make each bounce costly cannot
/// make the whole take minutes.
pub fn limit_work(units: u64) {
    WORK_LEFT.store(units, Ordering::Relaxed);
}

/// What one evaluation costs, in work units: a chain of N masses costs about (N + 1)/2 times the
/// single cart's, which costs 2.
fn weight(params: &Params) -> u64 {
    params.chain.clamp(1.0, 16.0) as u64 + 1
}

/// Set once the process is told to stop (Ctrl-C in a headless command).
static INTERRUPTED: AtomicBool = AtomicBool::new(false);
/// Bounces solved by this process.
static SOLVED: AtomicU64 = AtomicU64::new(0);

/// Makes every solve of this process, running or to come, end with [`SolveError::Cancelled`] at its
/// next check. Async-signal-safe (one atomic store), so a signal handler may call it.
pub fn interrupt() {
    INTERRUPTED.store(true, Ordering::Relaxed);
}

/// True once [`interrupt`] was called: the cancellation check of [`super::solve()`].
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// How many bounces this process has solved (or refused) so far.
pub fn solved() -> u64 {
    SOLVED.load(Ordering::Relaxed)
}

/// Runs `solve` for `params` bounded: refused up front when a parameter is outside what can be solved,
/// within its work budget, and refused when the outcome is not finite.
pub fn bounded(
    params: &Params,
    solve: impl FnOnce() -> Result<Bounce, SolveError>,
) -> Result<Bounce, SolveError> {
    let outermost = !events::metering();
    let bounce = checked(params, solve);
    if outermost {
        SOLVED.fetch_add(1, Ordering::Relaxed);
    }
    bounce
}

fn checked(
    params: &Params,
    solve: impl FnOnce() -> Result<Bounce, SolveError>,
) -> Result<Bounce, SolveError> {
    params.validate()?;
    check(params)?;
    let weight = weight(params);
    let allowed = WORK_LEFT.load(Ordering::Relaxed) / weight;
    if allowed == 0 {
        return Err(SolveError::CommandBudget);
    }
    let solved = events::metered(budget(params).min(allowed), solve);
    let spent = events::spent().saturating_mul(weight);
    let _ = WORK_LEFT.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |left| {
        Some(left.saturating_sub(spent))
    });
    let bounce = solved.map_err(|stall| match stall {
        Stall::Budget { .. } if allowed < budget(params) => SolveError::CommandBudget,
        stall => SolveError::Stalled {
            stall,
            hint: advice(params),
        },
    })??;
    finite(&bounce)?;
    Ok(bounce)
}

/// What helps a solve that ran out of work.
fn advice(params: &Params) -> &'static str {
    if params.ball_stiffness > 0.0 && params.ball_damping < 0.1 {
        " (a stiff, lightly damped ball chatters: raise --ball-damping, e.g. to 0.1, or lower \
         --ball-stiffness)"
    } else if params.ball_stiffness > 0.0 {
        " (a softer ball is solved with less work)"
    } else if params.chain > 1.0 {
        " (fewer --chain masses solve faster)"
    } else {
        ""
    }
}

/// Checks every parameter against the range that can be solved, and a damped ball's relaxation.
pub fn check(params: &Params) -> Result<(), Unsolvable> {
    for limit in SOLVABLE {
        let value = params.get(limit.id);
        let size = value.abs();
        let zero_ok = spec(limit.id).range.contains(0.0);
        let ok = (size == 0.0 && zero_ok) || (size >= limit.smallest && size <= limit.largest);
        if !ok {
            return Err(refusal(limit, value));
        }
    }
    relaxation(params)
}

/// The message for `value` outside `limit`.
fn refusal(limit: &Solvable, value: f64) -> Unsolvable {
    let spec = spec(limit.id);
    let unit = spec.dimension.base_symbol();
    let largest = number(limit.largest);
    let range = if spec.range.contains(-1.0) {
        format!("[-{largest}, {largest}]")
    } else if limit.smallest == 0.0 {
        format!("[0, {largest}]")
    } else {
        format!("[{}, {largest}]", number(limit.smallest))
    };
    Unsolvable {
        flag: spec.flag,
        range: format!("{range} {unit}").trim_end().to_string(),
        given: format!("{} {unit}", number(value)).trim_end().to_string(),
        why: SCALES,
    }
}

/// A damped ball's stretch relaxes at lambda = k_b/c_b = sqrt(k_b/m_eff)/(2 zeta); lambda T must stay
/// within [`MAX_RELAXATIONS`], which bounds zeta from below (zero, an undamped ball, is solved apart).
fn relaxation(params: &Params) -> Result<(), Unsolvable> {
    let zeta = params.ball_damping;
    if params.ball_stiffness == 0.0 || zeta == 0.0 {
        return Ok(());
    }
    let m_eff = params.mass * params.alpha / (1.0 + params.alpha);
    let smallest =
        (params.ball_stiffness / m_eff).sqrt() * params.duration / (2.0 * MAX_RELAXATIONS);
    if zeta >= smallest {
        return Ok(());
    }
    let spec = spec(ParamId::BallDamping);
    Err(Unsolvable {
        flag: spec.flag,
        range: format!("{{0}} or [{}, 10]", units::brief(smallest, 3)),
        given: number(zeta),
        why: "a lighter damping relaxes the ball's stretch faster than the impact's time can resolve",
    })
}

/// The shortest text that reads back as `value`, in exponent form outside ordinary magnitudes.
fn number(value: f64) -> String {
    if value == 0.0 || (1e-4..1e9).contains(&value.abs()) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

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
    let far = |limit: &&Solvable| {
        let value = bounce.params.get(limit.id).abs();
        let default = spec(limit.id).default.abs();
        if value == 0.0 || default == 0.0 {
            0.0
        } else {
            (value / default).ln().abs()
        }
    };
    let spin = Solvable {
        id: ParamId::Spin,
        smallest: 0.0,
        largest: 1e15,
    };
    let culprit = SOLVABLE
        .iter()
        .chain(std::iter::once(&spin))
        .max_by(|a, b| far(a).total_cmp(&far(b)))
        .expect("the table has rows");
    Err(Unsolvable {
        why: "beyond, the rebound's energy or its spin in rpm overflows f64",
        ..refusal(culprit, bounce.params.get(culprit.id))
    })
}

/// Refuses an outcome that is not a finite number.
fn finite(bounce: &Bounce) -> Result<(), SolveError> {
    let o = &bounce.outcome;
    let values = [
        ("the rebound spin", o.omega2),
        ("the rebound velocity along the surface", o.vx2),
        ("the rebound velocity away from the surface", o.vy2),
        ("the rebound speed", o.speed2),
        ("the rebound angle", o.theta2_deg),
        ("e_x", o.ex.unwrap_or(0.0)),
        ("the roll ratio", o.roll_ratio.unwrap_or(0.0)),
    ];
    match values.iter().find(|(_, v)| !v.is_finite()) {
        Some(&(quantity, _)) => Err(SolveError::NotFinite { quantity }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_and_the_paper_are_solvable() {
        assert_eq!(check(&Params::default()), Ok(()));
    }

    #[test]
    fn a_value_beyond_the_scales_is_refused_with_its_range() {
        let p = Params {
            speed: 1e160,
            ..Params::default()
        };
        assert_eq!(
            check(&p).unwrap_err().to_string(),
            format!("--speed must be in [1e-15, 1e15] m/s to be solved ({SCALES}); got 1e160 m/s")
        );
        // The solve carries any spin; its energy overflows, which a report refuses.
        let p = Params {
            spin: -1e308,
            ..Params::default()
        };
        assert_eq!(check(&p), Ok(()));
        let bounce = crate::model::solve(&p).unwrap();
        let message = reportable(&bounce).unwrap_err().to_string();
        assert!(
            message.starts_with("--spin must be in [-1e15, 1e15] rad/s to be solved"),
            "{message}"
        );
    }

    #[test]
    fn a_lightly_damped_ball_is_refused_but_an_undamped_one_is_not() {
        let ball = Params {
            ball_stiffness: 1e5,
            ..Params::default()
        };
        assert_eq!(check(&ball), Ok(()));
        let light = Params {
            ball_damping: 1e-20,
            ..ball
        };
        let message = check(&light).unwrap_err().to_string();
        assert!(
            message.starts_with("--ball-damping must be in {0} or [5.56e-15, 10]"),
            "{message}"
        );
        let enough = Params {
            ball_damping: 1e-14,
            ..ball
        };
        assert_eq!(check(&enough), Ok(()));
    }

    #[test]
    fn a_chain_gets_a_smaller_budget() {
        let chain = Params {
            chain: 16.0,
            ..Params::default()
        };
        assert_eq!(budget(&Params::default()), BUDGET);
        assert!(budget(&chain) < BUDGET / 8);
    }
}
