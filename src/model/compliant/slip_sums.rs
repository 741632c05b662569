//! A damped slide's patch slip searched by sums: where the rigid ball's motion writes its slip once for
//! the phase (detuned, without string friction: the single cart, a chain on the wall, the single cart
//! on a free frame), the event -dir (slip - e' - offset) is the rigid slip by those sums less e' by the
//! stretch's ([`StretchRates`]) at the same sin and cos of w τ, one `exp` more an evaluation, and the
//! slide's point is computed only where the search ends.

use super::super::cart::Slide;
use super::super::chain::ChainMotion;
use super::super::events::{Event, first_rise_from_tangent};
use super::super::frame::SlideSums;
use super::super::setup::{Setup, State};
use super::stretch::StretchRates;
use super::{CompliantSlide, Rigid};

/// Where a slide's rigid slip is written as sums.
pub(super) enum SlipSums<'a> {
    /// The single cart (`Rigid::Cart`): the rigid slip by the cart's sums, one `sin_cos2` an
    /// evaluation (the sums are written where the event is: their type is the cart's own).
    Cart {
        rigid: &'a Slide,
        rates: StretchRates,
    },
    /// A chain sliding on the wall (`Rigid::Chain`): the rigid slip from the chain's sums (its rows but
    /// the last), e' by the stretch's at the chain's sin and cos of w τ, one `exp` more an evaluation;
    /// with the slip, its rate and sin, cos of w τ at the start.
    Chain {
        motion: &'a ChainMotion,
        start: (f64, f64, (f64, f64)),
        rates: StretchRates,
    },
    /// The single cart on a free frame (`Rigid::Frame`): the same by the frame's sums.
    Frame {
        sums: SlideSums<'a>,
        start: &'a State,
        rates: StretchRates,
    },
}

/// The slide's sums, where it has them: damped, without string friction, the rigid motion's written
/// (else `None`).
pub(super) fn slip_sums<'a>(
    slide: &'a CompliantSlide,
    setup: &Setup,
    t0: f64,
) -> Option<SlipSums<'a>> {
    if setup.cart_friction != 0.0 {
        return None;
    }
    let rates = || slide.stretch.rates(setup.w);
    match &slide.rigid {
        Rigid::Cart(rigid) => {
            let rates = rigid.slip_sums(setup).and(rates())?;
            Some(SlipSums::Cart { rigid, rates })
        }
        Rigid::Chain(motion) => {
            let rates = rates()?;
            let start = motion.slip_by_sums(setup, t0)?;
            Some(SlipSums::Chain {
                motion,
                start,
                rates,
            })
        }
        Rigid::Frame(motion, _) => {
            let (sums, rates) = motion.slide_sums(setup).zip(rates())?;
            Some(SlipSums::Frame {
                sums,
                start: &motion.start.s,
                rates,
            })
        }
    }
}

impl SlipSums<'_> {
    /// The patch's slip at t0: the rigid slip less e'.
    pub(super) fn start_slip(&self, setup: &Setup, t0: f64) -> f64 {
        match self {
            SlipSums::Cart { rigid, rates } => {
                setup.slip(&rigid.start) - rates.at(t0, (0.0, 1.0)).0
            }
            SlipSums::Chain {
                start: (slip, _, w_tau),
                rates,
                ..
            } => slip - rates.at(t0, *w_tau).0,
            SlipSums::Frame { start, rates, .. } => setup.slip(start) - rates.at(t0, (0.0, 1.0)).0,
        }
    }

    /// The event -dir (slip - e' - offset) and its rate, for a slide the way `dir` points whose patch
    /// slipped `start_slip` at t0: there, that slip taken exactly (not evaluated again).
    pub(super) fn event<'s>(
        &'s self,
        setup: &'s Setup,
        t0: f64,
        dir: f64,
        start_slip: f64,
        offset: f64,
    ) -> SlipEvent<
        impl Event<(f64, f64), 1> + use<'s>,
        impl Event<(f64, f64), 1> + use<'s>,
        impl Event<(f64, f64), 1> + use<'s>,
    > {
        let value = -dir * (start_slip - offset);
        match self {
            SlipSums::Cart { rigid, rates } => {
                let sums = rigid
                    .slip_sums(setup)
                    .expect("the phase's sums were written at its start");
                let constants = sums.constants(offset);
                // At t0 the event is the start's slip taken exactly, as the points' are.
                let level = ((0.0, 1.0), (0.0, 1.0));
                let at_start = (
                    value,
                    sums.event(level, constants).1 + dir * rates.at(t0, (0.0, 1.0)).1,
                );
                SlipEvent::Cart(move |t: f64| {
                    if t == t0 {
                        return [at_start];
                    }
                    let angles = rigid.angles(setup, t);
                    let (value, rate, _, _) = sums.event(angles, constants);
                    let (de, dde) = rates.at(t, angles.0);
                    [(value + dir * de, rate + dir * dde)]
                })
            }
            // At t0, the start's slip and rate (the same sums, not evaluated again).
            SlipSums::Chain {
                motion,
                start: (_, rate, w_tau),
                rates,
            } => {
                let at_start = (value, -dir * (rate - rates.at(t0, *w_tau).1));
                SlipEvent::Chain(move |t: f64| {
                    if t == t0 {
                        return [at_start];
                    }
                    let (slip, rate, w_tau) = motion
                        .slip_by_sums(setup, t)
                        .expect("the phase's sums gave the slip at t0");
                    let (de, dde) = rates.at(t, w_tau);
                    [(-dir * ((slip - de) - offset), -dir * (rate - dde))]
                })
            }
            SlipSums::Frame { sums, rates, .. } => {
                let constants = sums.constants(offset);
                let ((_, rate), _) = sums.at(setup, t0, constants);
                let at_start = (value, rate + dir * rates.at(t0, (0.0, 1.0)).1);
                SlipEvent::Frame(move |t: f64| {
                    if t == t0 {
                        return [at_start];
                    }
                    let ((value, rate), angle) = sums.at(setup, t, constants);
                    let (de, dde) = rates.at(t, angle);
                    [(value + dir * de, rate + dir * dde)]
                })
            }
        }
    }
}

/// The patch's slip event by each source's sums ([`SlipSums::event`]).
pub(super) enum SlipEvent<C, H, F> {
    Cart(C),
    Chain(H),
    Frame(F),
}

impl<C, H, F> SlipEvent<C, H, F>
where
    C: Event<(f64, f64), 1>,
    H: Event<(f64, f64), 1>,
    F: Event<(f64, f64), 1>,
{
    /// The slip's first zero from `from` to `to` ([`first_rise_from_tangent`]), by each source's own
    /// search (monomorphic: no dynamic call an evaluation).
    pub(super) fn first_rise(
        &self,
        from: f64,
        to: f64,
        step: f64,
        curvature: f64,
        noise: f64,
    ) -> Option<(f64, usize)> {
        let (curvature, noise) = ([curvature], [noise]);
        match self {
            SlipEvent::Cart(f) => {
                first_rise_from_tangent(|t| f.at(t), from, to, step, curvature, noise)
            }
            SlipEvent::Chain(f) => {
                first_rise_from_tangent(|t| f.at(t), from, to, step, curvature, noise)
            }
            SlipEvent::Frame(f) => {
                first_rise_from_tangent(|t| f.at(t), from, to, step, curvature, noise)
            }
        }
    }
}
