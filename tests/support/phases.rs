//! A solved bounce's phases read for what the string friction did to the cart, and a model run phase by
//! phase as the driver runs it.

use snapback::model::Phase;
use snapback::model::contact::{Cart, Cause, Contact, Mode};
use snapback::model::setup::Setup;

/// Whether the cart (on a chain, its first mass) came unstuck, and whether it stopped and was held again.
pub fn regimes(phases: &[Phase]) -> (bool, bool) {
    let freed = phases
        .windows(2)
        .any(|w| w[0].cart == Cart::Stuck && w[1].cart != Cart::Stuck);
    let stopped = phases
        .windows(2)
        .any(|w| w[0].cart != Cart::Stuck && w[1].cart == Cart::Stuck);
    (freed, stopped)
}

/// Runs `model` from first contact phase by phase (at most 1000) and shows `visit` each phase: its
/// mode, its motion, the state it starts from and the time it ends.
pub fn each_phase<C: Contact>(
    model: &C,
    setup: &Setup,
    mut visit: impl FnMut(Mode, &C::Motion, &C::State, f64),
) {
    let (mut state, mut mode) = model.start(setup);
    let mut cause = Cause::Start;
    for _ in 0..1000 {
        let motion = model.motion(setup, &state, mode);
        let found = model.first_event(setup, &motion, &state, mode, cause);
        let end = found.event.map_or(setup.duration, |(t, _)| t);
        visit(mode, &motion, &state, end);
        let Some((t, next_cause)) = found.event else {
            return;
        };
        state = model.state_at(setup, &motion, t, found.last);
        mode = model.next(setup, &mut state, mode, next_cause);
        cause = next_cause;
    }
}
