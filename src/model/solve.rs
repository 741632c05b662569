//! Solving a bounce: the parameters choose the contact model ([`Params::model`]), the phase driver runs
//! it within the caller's [`SolveOptions`], and the outcome is checked before it is returned.

use super::bounce::{Bounce, finish};
use super::budget::{budget, weight};
use super::cart::SingleCart;
use super::chain::ChainOfMasses;
use super::compliant::CompliantBall;
use super::driver::run;
use super::error::SolveError;
use super::events::{self, Stall};
use super::frame::FramedCart;
use super::options::SolveOptions;
use super::params::{ParamId, Params, spec};
use super::phase::Phase;
use super::registry::{BallKind, FrameKind, SupportKind};
use super::reportable::finite;
use super::setup::{Incidence, Setup, State};
use super::solvable;

/// Solves one bounce exactly (Cross 2010, Sec. II): phase by phase in closed form, each transition
/// located by root finding on the exact expressions. Under the default [`SolveOptions`]: never
/// cancelled, the default phase cap, the solve's own work budget.
pub fn solve(params: &Params) -> Result<Bounce, SolveError> {
    solve_with(params, &SolveOptions::default())
}

/// [`solve`], abandoned with [`SolveError::Cancelled`] as soon as `cancelled` returns true: it is asked
/// before every phase, so a caller (the explorer's worker) can drop a solve that is no longer wanted.
pub fn solve_cancellable(
    params: &Params,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<Bounce, SolveError> {
    solve_with(params, &SolveOptions::cancelled_by(cancelled))
}

/// [`solve`] on the caller's terms: its cancellation, phase cap and shared work ([`SolveOptions`]).
pub fn solve_with(params: &Params, options: &SolveOptions) -> Result<Bounce, SolveError> {
    bounce_of(params, options, |setup, phases| {
        // The place moved into the call (FnOnce), so the constants' reference outlives it.
        let put = move |built: Build<'_>| {
            let place = setup;
            &*place.insert(built.made())
        };
        solve_model(params, options, &mut Incidence::default(), phases, put)
    })
}

/// [`solve_with`] into `slot`, over the bounce already there: its memory (the phases') is reused and
/// no bounce is moved, so a caller that solves many bounces in turn (a sweep) allocates nothing per
/// bounce once the first is solved. An error empties the slot.
pub fn solve_in<'a>(
    params: &Params,
    options: &SolveOptions,
    slot: &'a mut Option<Bounce>,
) -> Result<&'a Bounce, SolveError> {
    let solved = match slot.as_mut() {
        Some(bounce) => {
            bounce.params = *params;
            let cost = Cost::of(&bounce.params);
            resolve(
                options,
                cost,
                whole_check,
                &mut Incidence::default(),
                bounce,
            )
        }
        None => solve_with(params, options).map(|bounce| *slot = Some(bounce)),
    };
    match solved {
        Ok(()) => Ok(slot.as_ref().expect("a solved slot holds its bounce")),
        Err(e) => {
            *slot = None;
            Err(e)
        }
    }
}

/// The bounce of `params` solved by `solve` (into the place for its constants and the phases it is
/// given) within [`bounded`], and refused when its outcome is not finite.
fn bounce_of(
    params: &Params,
    options: &SolveOptions,
    solve: impl FnOnce(&mut Option<Setup>, &mut Vec<Phase>) -> Result<State, SolveError>,
) -> Result<Bounce, SolveError> {
    let (mut setup, mut phases) = (None, Vec::with_capacity(8));
    let last = bounded(params, options, Cost::of(params), whole_check, || {
        solve(&mut setup, &mut phases)
    })?;
    let setup = setup.expect("a solved bounce has its constants");
    let bounce = finish(params, setup, phases, last);
    finite(&bounce)?;
    Ok(bounce)
}

/// [`solve_with`] of the bounce's own parameters (set before) over `bounce`, in place (its constants
/// written where the last bounce's were, its phases over theirs), checked by `check`, at `incidence`;
/// `cost` is theirs.
fn resolve(
    options: &SolveOptions,
    cost: Cost,
    check: impl FnOnce(&Params) -> Result<(), SolveError>,
    incidence: &mut Incidence,
    bounce: &mut Bounce,
) -> Result<(), SolveError> {
    let Bounce {
        params,
        setup,
        phases,
        final_state,
        ..
    } = bounce;
    let put = move |built: Build<'_>| -> &Setup {
        let place = setup;
        built.over(place);
        place
    };
    *final_state = bounded(params, options, cost, check, || {
        solve_model(params, options, incidence, phases, put)
    })?;
    bounce.refinish();
    finite(bounce)
}

/// Bounces of one set of parameters with one of them varied, solved one after another into the same
/// memory ([`solve_in`]): a sweep's. The other values are checked once, when it begins; each bounce
/// checks its own value and the damped ball's relaxation (which several values decide), and is refused
/// with the error the whole check gives. Each answer is [`solve_with`]'s of the parameters with the
/// varied one at its value.
pub struct Varied<'a> {
    /// The parameters, the varied one at its last value.
    base: Params,
    id: ParamId,
    /// True when every value but the varied one is in range and can be solved.
    others_checked: bool,
    /// True when the damped ball's relaxation was checked with the others: the varied value takes no
    /// part in it ([`relaxes_by`]).
    relaxation_checked: bool,
    options: SolveOptions<'a>,
    /// The direction of incidence, while the angle stays (and in a sweep of the incidence, the
    /// constants that do not depend on it).
    incidence: Incidence,
    /// The solves' cost, taken once unless the chain's length is what varies.
    cost: Option<Cost>,
    /// The last bounce, whose parameters are `base`'s but for the varied value.
    slot: Option<Bounce>,
}

impl<'a> Varied<'a> {
    /// The bounces of `base` with the parameter `id` varied, on the caller's terms.
    pub fn new(base: &Params, id: ParamId, options: &SolveOptions<'a>) -> Self {
        // The varied value at its default (in range, and solvable), so that only the others can fail.
        let mut others = *base;
        others.set(id, spec(id).default);
        let others_checked = others.validate().is_ok() && solvable::magnitudes(&others).is_ok();
        let relaxation_checked =
            others_checked && !relaxes_by(id) && solvable::relaxation(&others).is_ok();
        Varied {
            base: *base,
            id,
            others_checked,
            relaxation_checked,
            options: *options,
            // A sweep of the incidence keeps the rigid ball's constants that do not depend on it.
            incidence: if matches!(id, ParamId::Angle | ParamId::Speed | ParamId::Spin) {
                Incidence::only_varying()
            } else {
                Incidence::default()
            },
            cost: (id != ParamId::Chain).then(|| Cost::of(base)),
            slot: None,
        }
    }

    /// The bounce with the varied parameter at `value`; an error empties the memory.
    pub fn solve(&mut self, value: f64) -> Result<&Bounce, SolveError> {
        let (id, options, incidence) = (self.id, &self.options, &mut self.incidence);
        let relaxation_checked = self.relaxation_checked;
        let cost = |params: &Params| self.cost.unwrap_or_else(|| Cost::of(params));
        let solved = match self.slot.as_mut() {
            // The last bounce's parameters differ from these in the varied value alone.
            Some(bounce) if self.others_checked => {
                bounce.params.set(id, value);
                let row = spec(id);
                let check = |params: &Params| -> Result<(), SolveError> {
                    row.check_value(value)?;
                    solvable::magnitude(row, value)?;
                    if relaxation_checked {
                        return Ok(());
                    }
                    Ok(solvable::relaxation(params)?)
                };
                resolve(options, cost(&bounce.params), check, incidence, bounce)
            }
            Some(bounce) => {
                bounce.params.set(id, value);
                resolve(
                    options,
                    cost(&bounce.params),
                    whole_check,
                    incidence,
                    bounce,
                )
            }
            None => {
                self.base.set(id, value);
                solve_with(&self.base, options).map(|bounce| self.slot = Some(bounce))
            }
        };
        match solved {
            Ok(()) => Ok(self.slot.as_ref().expect("a solved slot holds its bounce")),
            Err(e) => {
                self.slot = None;
                Err(e)
            }
        }
    }
}

/// True when the parameter `id` takes part in the damped ball's relaxation ([`solvable::relaxation`]:
/// its stiffness and damping, the ball's mass and inertia, the impact's duration), so that a sweep of
/// it checks the relaxation every bounce; any other is checked once for the whole sweep.
fn relaxes_by(id: ParamId) -> bool {
    matches!(
        id,
        ParamId::BallStiffness
            | ParamId::BallDamping
            | ParamId::Mass
            | ParamId::Alpha
            | ParamId::Duration
    )
}

/// Every value in range ([`Params::validate`]) and solvable ([`solvable::check`]).
#[inline]
fn whole_check(params: &Params) -> Result<(), SolveError> {
    params.validate()?;
    Ok(solvable::check(params)?)
}

/// What a solve's evaluations cost and how many it may spend ([`weight`], [`budget`]): they depend on
/// the chain's length alone, so a sweep of anything else takes them once.
#[derive(Clone, Copy)]
struct Cost {
    weight: u64,
    budget: u64,
    /// The evaluations allowed without shared work: `u64::MAX / weight`.
    unshared: u64,
}

impl Cost {
    fn of(params: &Params) -> Cost {
        let weight = weight(params);
        Cost {
            weight,
            budget: budget(params),
            unshared: u64::MAX / weight,
        }
    }
}

/// Runs `solve` for `params` bounded: refused up front when `check` refuses them (a parameter outside
/// what can be solved), within its work budget (`cost`, theirs) and the caller's shared work. Counted
/// in the shared work's tally unless nested in another solve.
fn bounded<T>(
    params: &Params,
    options: &SolveOptions,
    cost: Cost,
    check: impl FnOnce(&Params) -> Result<(), SolveError>,
    solve: impl FnOnce() -> Result<T, SolveError>,
) -> Result<T, SolveError> {
    let outermost = !events::metering();
    let solved = checked(params, options, cost, check, solve);
    if let (true, Some(work)) = (outermost, options.work) {
        work.count();
    }
    solved
}

fn checked<T>(
    params: &Params,
    options: &SolveOptions,
    Cost {
        weight,
        budget,
        unshared,
    }: Cost,
    check: impl FnOnce(&Params) -> Result<(), SolveError>,
    solve: impl FnOnce() -> Result<T, SolveError>,
) -> Result<T, SolveError> {
    check(params)?;
    let allowed = options.work.map_or(unshared, |work| work.left() / weight);
    if allowed == 0 {
        return Err(SolveError::CommandBudget);
    }
    let solved = events::metered(budget.min(allowed), solve);
    if let Some(work) = options.work {
        work.spend(events::spent().saturating_mul(weight));
    }
    solved.map_err(|stall| match stall {
        Stall::Budget { .. } if allowed < budget => SolveError::CommandBudget,
        stall => SolveError::Stalled {
            stall,
            hint: advice(params),
        },
    })?
}

/// What helps a solve that ran out of work.
fn advice(params: &Params) -> &'static str {
    let kind = params.model();
    match (kind.ball, kind.support) {
        (BallKind::Compliant, _) if params.ball_damping < 0.1 => {
            " (a stiff, lightly damped ball chatters: raise --ball-damping, e.g. to 0.1, or lower \
             --ball-stiffness)"
        }
        (BallKind::Compliant, _) => " (a softer ball is solved with less work)",
        (BallKind::Rigid, SupportKind::Chain) => " (fewer --chain masses solve faster)",
        (BallKind::Rigid, SupportKind::Cart) => "",
    }
}

/// The constants of a bounce, as [`solve_model`] hands them to its caller to place.
enum Build<'b> {
    /// The compliant ball's, which its model makes (lent, so that it is copied once, into its place).
    Made(&'b Setup),
    /// The rigid ball's, of these parameters at this incidence.
    Rigid(&'b Params, &'b mut Incidence),
}

impl Build<'_> {
    fn made(self) -> Setup {
        match self {
            Build::Made(setup) => *setup,
            Build::Rigid(params, incidence) => Setup::at_incidence(params, incidence),
        }
    }

    /// Written over `place`, the last bounce's constants: only those the incidence sets when the
    /// bounces differ in it alone ([`Incidence::only_varies`]; a rigid ball's, as the model stays).
    #[inline]
    fn over(self, place: &mut Setup) {
        match self {
            Build::Rigid(params, incidence) if incidence.only_varies => {
                place.at_new_incidence(params, incidence)
            }
            built => *place = built.made(),
        }
    }
}

/// The model for `params` ([`Params::model`]), run by the driver into `phases` (`bounded` has
/// validated them): the constants of the bounce and the state as the ball leaves.
/// `put` places the bounce's constants where the caller keeps them (so that they are not moved again).
fn solve_model<'s>(
    params: &Params,
    options: &SolveOptions,
    incidence: &mut Incidence,
    phases: &mut Vec<Phase>,
    put: impl for<'b> FnOnce(Build<'b>) -> &'s Setup,
) -> Result<State, SolveError> {
    let kind = params.model();
    match (kind.ball, kind.support, kind.frame) {
        (
            BallKind::Compliant,
            SupportKind::Cart | SupportKind::Chain,
            FrameKind::Clamped | FrameKind::Free,
        ) => {
            let (model, setup) = CompliantBall::new(params, params.stiffness > 0.0)?;
            run(&model, put(Build::Made(&setup)), options, phases).map_err(|e| match e {
                SolveError::TooManyPhases { limit, .. } => SolveError::TooManyPhases {
                    limit,
                    hint: " (a stiff, lightly damped ball chatters: raise --ball-damping, e.g. to 0.1, \
                           or lower --ball-stiffness)",
                },
                e => e,
            })
        }
        (BallKind::Rigid, SupportKind::Chain, FrameKind::Clamped | FrameKind::Free) => {
            let setup = put(Build::Rigid(params, incidence));
            run(&ChainOfMasses::new(params, setup)?, setup, options, phases)
        }
        (BallKind::Rigid, SupportKind::Cart, FrameKind::Clamped) => {
            let setup = put(Build::Rigid(params, incidence));
            run(&SingleCart::new(params, setup)?, setup, options, phases)
        }
        (BallKind::Rigid, SupportKind::Cart, FrameKind::Free) => {
            let setup = put(Build::Rigid(params, incidence));
            let model = FramedCart::new(params, setup, params.frame_mass)?;
            run(&model, setup, options, phases)
        }
    }
}

/// The rigid ball on a chain of `params.chain` masses, for any N including 1, where it reproduces the
/// single cart to rounding (a compliant ball goes to its own model, as in [`solve`]).
pub fn solve_chain(params: &Params) -> Result<Bounce, SolveError> {
    let options = SolveOptions::default();
    if params.model().compliant() {
        return bounded(params, &options, Cost::of(params), whole_check, || {
            solve(params)
        });
    }
    bounce_of(params, &options, |setup, phases| {
        let setup = &*setup.insert(Setup::new(params));
        run(&ChainOfMasses::new(params, setup)?, setup, &options, phases)
    })
}

/// The compliant ball on the single cart (the chain's length ignored) with every grip solved by the
/// cart's own 4-state system, even with a spring: an independent check of [`solve`]'s modal grips.
pub fn solve_compliant_on_cart(params: &Params) -> Result<Bounce, SolveError> {
    let params = Params {
        chain: 1.0,
        ..*params
    };
    let options = SolveOptions::default();
    bounce_of(&params, &options, |setup, phases| {
        let (model, built) = CompliantBall::new(&params, false)?;
        run(&model, setup.insert(built), &options, phases)
    })
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::*;
    use crate::model::budget::Work;

    /// A check that says "cancel" from its `n`th call on, counting the calls.
    fn cancel_from(n: usize, calls: &AtomicUsize) -> impl Fn() -> bool + Sync + '_ {
        move || calls.fetch_add(1, Ordering::Relaxed) + 1 >= n
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
            let calls = AtomicUsize::new(0);
            let never = solve_cancellable(&params, &cancel_from(usize::MAX, &calls)).unwrap();
            assert_eq!(never.outcome, whole.outcome);
            assert!(calls.load(Ordering::Relaxed) >= whole.phases.len());
            let calls = AtomicUsize::new(0);
            let cancelled = solve_cancellable(&params, &cancel_from(2, &calls));
            assert_eq!(cancelled.unwrap_err(), SolveError::Cancelled);
            assert_eq!(
                calls.load(Ordering::Relaxed),
                2,
                "stops at the first check that says so"
            );
        }
    }

    /// A bounce solved over another in its slot is the bounce solved afresh, on every model, and a
    /// refusal empties the slot.
    #[test]
    fn a_bounce_solved_in_a_slot_is_the_same_bounce() {
        let base = Params {
            cart_mass: 0.001,
            stiffness: 9554.0,
            ..Params::default()
        };
        let cases = [
            Params::default(),
            base,
            Params { chain: 4.0, ..base },
            Params {
                ball_stiffness: 1e6,
                ball_damping: 0.5,
                ..base
            },
            Params {
                frame_mass: 0.3,
                ..Params::default()
            },
            Params {
                cart_friction: 0.5,
                ..base
            },
        ];
        let options = SolveOptions::default();
        let mut slot = None;
        for params in cases.iter().chain(cases.iter().rev()) {
            let fresh = solve(params).unwrap();
            let reused = solve_in(params, &options, &mut slot).unwrap();
            assert_eq!(reused.params, fresh.params);
            assert_eq!(reused.outcome, fresh.outcome);
            assert_eq!(reused.final_state, fresh.final_state);
            assert_eq!(reused.phases.len(), fresh.phases.len());
            for (a, b) in reused.phases.iter().zip(&fresh.phases) {
                assert_eq!((a.kind, a.slip_sign, a.cart), (b.kind, b.slip_sign, b.cart));
                assert_eq!((a.start, a.end), (b.start, b.end));
                assert_eq!(
                    a.state_at(&reused.setup, a.end),
                    b.state_at(&fresh.setup, b.end)
                );
            }
            assert_eq!(reused.series(50), fresh.series(50));
        }
        let unsolvable = Params {
            speed: 1e160,
            ..Params::default()
        };
        assert_eq!(
            solve_in(&unsolvable, &options, &mut slot).map(|_| ()),
            solve(&unsolvable).map(|_| ())
        );
        assert!(slot.is_none());
    }

    /// A varied bounce is the bounce solved afresh, and a refusal the whole check's, whether the
    /// value or another parameter fails, and with either checked once or every time.
    #[test]
    fn a_varied_bounce_is_the_bounce_and_its_refusal_the_whole_checks() {
        let options = SolveOptions::default();
        let ball = Params {
            ball_stiffness: 1e5,
            ..Params::default()
        };
        let cases = [
            (
                Params::default(),
                ParamId::Speed,
                vec![10.0, 1e160, 3.0, -1.0, f64::NAN, 12.0],
            ),
            (
                Params::default(),
                ParamId::Angle,
                vec![30.0, 95.0, 60.0, 0.0, 45.0],
            ),
            // A sweep of the incidence keeps the constants that do not depend on it: on a free frame
            // of its own normal mass, and on a chain.
            (
                Params {
                    frame_mass: 0.3,
                    frame_normal_mass: 0.2,
                    ..Params::default()
                },
                ParamId::Speed,
                vec![10.0, 3.0, 1e160, 25.0],
            ),
            (
                Params {
                    frame_mass: 0.3,
                    ..Params::default()
                },
                ParamId::Angle,
                vec![30.0, 60.0, 89.0],
            ),
            (
                Params {
                    chain: 3.0,
                    ..Params::default()
                },
                ParamId::Spin,
                vec![0.0, 200.0, -150.0],
            ),
            (
                ball,
                ParamId::BallDamping,
                vec![0.3, 1e-20, 0.0, 1e-14, 0.5],
            ),
            (ball, ParamId::BallStiffness, vec![1e5, 1e30, 1e3]),
            // A damping at the edge of the relaxation: the ball's mass decides it every bounce, the
            // angle (checked once with the others) never.
            (
                Params {
                    ball_damping: 1e-14,
                    ..ball
                },
                ParamId::Mass,
                vec![0.057, 1e-4, 0.1],
            ),
            (
                Params {
                    ball_damping: 1e-14,
                    ..ball
                },
                ParamId::Angle,
                vec![30.0, 60.0],
            ),
            (
                Params {
                    ball_damping: 1e-14,
                    mass: 1e-4,
                    ..ball
                },
                ParamId::Angle,
                vec![30.0, 60.0],
            ),
            // Another value fails: every bounce is refused for it.
            (
                Params {
                    speed: 1e160,
                    ..Params::default()
                },
                ParamId::Angle,
                vec![30.0, 60.0],
            ),
            (
                Params {
                    mu: -1.0,
                    ..Params::default()
                },
                ParamId::Speed,
                vec![10.0, 1e160],
            ),
            (
                Params {
                    chain: 4.0,
                    ..Params::default()
                },
                ParamId::Chain,
                vec![1.0, 2.5, 3.0],
            ),
        ];
        for (base, id, values) in cases {
            let mut varied = Varied::new(&base, id, &options);
            for value in values {
                let mut params = base;
                params.set(id, value);
                let fresh = solve(&params);
                if id == ParamId::Mass && value == 1e-4 {
                    let refusal = fresh.as_ref().map(|_| ()).unwrap_err().to_string();
                    assert!(refusal.contains("relaxes"), "{refusal}");
                }
                let got = varied.solve(value);
                match (got, fresh) {
                    (Ok(got), Ok(fresh)) => {
                        assert_eq!(got.params, fresh.params);
                        assert_eq!(got.outcome, fresh.outcome, "{id:?} {value}");
                        // The constants too, to the bit (Debug prints every f64 exactly).
                        assert_eq!(format!("{:?}", got.setup), format!("{:?}", fresh.setup));
                        assert_eq!(got.phases.len(), fresh.phases.len());
                    }
                    (got, fresh) => {
                        assert_eq!(got.map(|_| ()), fresh.map(|_| ()), "{id:?} {value}")
                    }
                }
            }
        }
    }

    #[test]
    fn the_phase_cap_and_the_shared_work_are_the_callers() {
        let params = Params {
            cart_mass: 0.001,
            stiffness: 9554.0,
            ..Params::default()
        };
        let phases = solve(&params).unwrap().phases.len();
        let capped = SolveOptions {
            max_phases: phases - 1,
            ..SolveOptions::default()
        };
        let err = solve_with(&params, &capped).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "the bounce switched between sliding and gripping more than {} times",
                phases - 1
            )
        );
        let enough = SolveOptions {
            max_phases: phases,
            ..SolveOptions::default()
        };
        assert!(solve_with(&params, &enough).is_ok());
        // Shared work: counted, spent, and once spent refused; a fresh solve is not affected.
        let work = Work::limited(1_000_000);
        let shared = SolveOptions {
            work: Some(&work),
            ..SolveOptions::default()
        };
        assert!(solve_with(&params, &shared).is_ok());
        assert_eq!(work.solved(), 1);
        assert!(work.left() < 1_000_000);
        let spent = Work::limited(1);
        let none_left = SolveOptions {
            work: Some(&spent),
            ..SolveOptions::default()
        };
        assert_eq!(
            solve_with(&params, &none_left).unwrap_err(),
            SolveError::CommandBudget
        );
        assert!(solve(&params).is_ok());
    }
}
