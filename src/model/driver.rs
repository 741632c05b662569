//! The phase driver: runs any [`Contact`] model phase by phase, from first contact to t = T.
//!
//! Each phase is the model's closed form; the driver asks for its first event, records the phase, and
//! asks the model which phase follows. It enforces the caller's phase cap and checks its cancellation
//! between phases ([`SolveOptions`]). Generic over the model, so every model's loop is compiled for it (no dynamic calls).

use super::contact::{Ball, Cause, Contact, Found};
use super::error::SolveError;
use super::options::SolveOptions;
use super::phase::{Phase, PhaseKind};
use super::registry::Motion;
use super::setup::{Setup, State};

/// The phases of one bounce, written over `phases` (the caller's memory, reused from bounce to bounce),
/// and the state of ball and surface as the ball leaves. On an error `phases` holds the phases solved
/// before it.
pub fn run<C: Contact>(
    model: &C,
    setup: &Setup,
    options: &SolveOptions,
    phases: &mut Vec<Phase>,
) -> Result<State, SolveError>
where
    C::Motion: Into<Motion>,
{
    let mut written = 0;
    let solved = run_over(model, setup, options, phases, &mut written);
    phases.truncate(written);
    solved
}

/// [`run`], each phase written over the last bounce's phase at its place while there is one (its
/// fields one by one: no phase is built aside and moved in, and none is dropped in bulk first), and
/// pushed after them; `written` counts the phases of this bounce.
fn run_over<C: Contact>(
    model: &C,
    setup: &Setup,
    options: &SolveOptions,
    phases: &mut Vec<Phase>,
    written: &mut usize,
) -> Result<State, SolveError>
where
    C::Motion: Into<Motion>,
{
    let end = setup.duration;
    let (mut state, mut mode) = model.start(setup);
    let mut cause = Cause::Start;
    for _ in 0..options.max_phases {
        if (options.cancelled)() {
            return Err(SolveError::Cancelled);
        }
        let t0 = C::time(&state);
        let motion = model.motion(setup, &state, mode);
        let Found { event, last } = model.first_event(setup, &motion, &state, mode, cause);
        // A transition within rounding of the end changes nothing.
        let event = event.filter(|&(t, _)| t < end * (1.0 - 1e-13));
        let t1 = event.map_or(end, |(t, _)| t);
        state = model.state_at(setup, &motion, t1, last);
        if t1 > t0 {
            let (ball, cart) = mode;
            let (kind, slip_sign) = match ball {
                Ball::Slide(dir) => (PhaseKind::Slide, dir as i8),
                Ball::Grip => (PhaseKind::Grip, 0),
            };
            match phases.get_mut(*written) {
                Some(phase) => {
                    phase.kind = kind;
                    phase.slip_sign = slip_sign;
                    phase.cart = cart;
                    phase.start = t0;
                    phase.end = t1;
                    phase.motion = motion.into();
                }
                None => phases.push(Phase {
                    kind,
                    slip_sign,
                    cart,
                    start: t0,
                    end: t1,
                    motion: motion.into(),
                }),
            }
            *written += 1;
        }
        let Some((_, next_cause)) = event else {
            return Ok(C::contact(&state));
        };
        cause = next_cause;
        mode = model.next(setup, &mut state, mode, cause);
    }
    Err(SolveError::TooManyPhases {
        limit: options.max_phases,
        hint: "",
    })
}
