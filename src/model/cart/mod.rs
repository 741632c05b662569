//! The paper's model: a rigid ball on a single cart held by a spring (Cross 2010, Sec. II), with
//! string-on-string friction on the cart (Sec. IV's proposed enhancement; F_c = 0 is the paper's model).
//! Each phase is a [`Slide`] (Eqs. (1)-(3)) or a [`Grip`] (Eqs. (4)-(6)); [`transition::next`] says
//! which follows an event.
//!
//! [`transition::next`]: super::transition::next

mod grip;
mod slide;

pub use grip::Grip;
pub use slide::Slide;
use slide::SlipSums;

use std::cell::Cell;

use super::contact::{Ball, Cart, Cause, Contact, Found, Mode, PhaseMotion, ROLLING, ROUNDING};
use super::error::{MAX_RADIANS, SolveError};
use super::events::{Event, WithNear, first_rise_predicted, first_rise_within};

#[cfg(test)]
mod bounds;
use super::params::Params;
use super::probe::Probe;
use super::quadrature::integrate;
use super::recent::Recent;
use super::setup::{Setup, State};
use super::transition::{self, Touched};
use super::trig::sin_cos;

/// A phase on the single cart.
#[derive(Clone, Copy, Debug)]
pub enum CartMotion {
    Slide(Slide),
    Grip(Grip),
}

impl CartMotion {
    /// The exact state at `t`.
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> State {
        match self {
            CartMotion::Slide(slide) => slide.at(setup, t),
            CartMotion::Grip(grip) => grip.at(setup, t),
        }
    }

    /// The friction force on the ball, positive backward, at `state`.
    pub fn friction(&self, setup: &Setup, state: &State) -> f64 {
        match self {
            CartMotion::Slide(slide) => slide.friction(setup, state.t),
            CartMotion::Grip(grip) => grip.friction(setup, state.x),
        }
    }

    /// The state at the start of the phase.
    pub fn initial(&self) -> State {
        match self {
            CartMotion::Slide(slide) => slide.start,
            CartMotion::Grip(grip) => grip.start,
        }
    }
}

impl PhaseMotion for CartMotion {
    fn state_at(&self, setup: &Setup, t: f64) -> State {
        self.at(setup, t)
    }

    fn friction(&self, setup: &Setup, state: &State) -> f64 {
        CartMotion::friction(self, setup, state)
    }

    fn initial(&self) -> State {
        CartMotion::initial(self)
    }

    /// A rigid ball has no contact patch.
    fn patch_at(&self, _: &Setup, _: f64) -> Option<(f64, f64)> {
        None
    }

    /// The cart's kinetic energy and its spring's, M V²/2 + k X²/2.
    fn surface_energy(&self, setup: &Setup, at: &State) -> f64 {
        setup.cart_energy(at)
    }

    /// ∫ F (v_x - r omega - V) dt, on panels of the cart's or the normal force's time scale.
    fn friction_work(&self, setup: &Setup, start: f64, end: f64) -> f64 {
        let power = |t: f64| {
            let s = self.at(setup, t);
            CartMotion::friction(self, setup, &s) * setup.slip(&s)
        };
        integrate(power, start, end, 2.0 / setup.omega_slide.max(setup.w))
    }

    fn fastest(&self, setup: &Setup) -> f64 {
        setup.omega_slide
    }

    /// A rigid ball holds no tangential energy.
    fn ball_spring_energy(&self, _: &Setup, _: f64) -> f64 {
        0.0
    }

    fn dashpot_loss(&self, _: &Setup, _: f64, _: f64) -> f64 {
        0.0
    }

    /// The strings are tied to a clamped frame.
    fn frame_velocity(&self, _: &Setup, _: f64) -> f64 {
        0.0
    }
}

/// The rigid ball on the single cart.
pub struct SingleCart {
    /// The spin at first contact, rad/s.
    spin: f64,
    /// |v_x1| + r |omega1|: the scale of the speeds, for the event functions' rounding.
    incoming: f64,
    /// sin and cos of w t at the last time t they were taken ([`SingleCart::normal_angle`]), with t.
    normal_angle: Cell<(f64, (f64, f64))>,
}

impl SingleCart {
    /// The model for `params`, refused when the cart oscillates too fast to resolve.
    pub fn new(params: &Params, setup: &Setup) -> Result<Self, SolveError> {
        let radians = setup.omega_slide.max(setup.omega_grip) * setup.duration;
        if radians > MAX_RADIANS {
            return Err(SolveError::TooFast { radians });
        }
        Ok(SingleCart {
            spin: params.spin,
            incoming: setup.vx1.abs() + setup.r * params.spin.abs(),
            normal_angle: Cell::new((f64::NAN, (0.0, 1.0))),
        })
    }

    /// sin and cos of w t, the normal force's angle, as `sin_cos` gives them, taken once for the times
    /// where one phase ends and the next begins: a transition measures N(t) there, and the grip that
    /// follows starts its search there; a grip's search ends on an evaluation that took them, and the
    /// slide that follows starts there.
    #[inline]
    fn normal_angle(&self, setup: &Setup, t: f64) -> (f64, f64) {
        let (at, angle) = self.normal_angle.get();
        if at.to_bits() == t.to_bits() {
            return angle;
        }
        let angle = sin_cos(setup.w * t);
        self.normal_angle.set((t, angle));
        angle
    }
}

impl Contact for SingleCart {
    type State = State;
    type Motion = CartMotion;
    type Probe = State;

    fn start(&self, setup: &Setup) -> (State, Mode) {
        let state = setup.initial(self.spin);
        let slip0 = setup.slip(&state);
        // A ball that arrives rolling grips at once (N(0) = 0 and F_s = 0, so the grip holds on the
        // boundary).
        let arriving = if slip0.abs() <= ROLLING * self.incoming {
            Ball::Grip
        } else {
            Ball::Slide(slip0.signum())
        };
        let mode = transition::next(
            setup,
            &touched(setup, &state),
            arriving,
            Cart::Moving(1),
            Cause::Start,
        );
        (state, mode)
    }

    fn time(state: &State) -> f64 {
        state.t
    }

    fn contact(state: &State) -> State {
        *state
    }

    fn motion(&self, setup: &Setup, state: &State, (ball, cart): Mode) -> CartMotion {
        match ball {
            // The first slide starts at t = 0, where sin_cos gives exactly (0, 1).
            Ball::Slide(dir) => CartMotion::Slide(Slide::at_angle(
                setup,
                *state,
                dir,
                cart,
                if state.t == 0.0 {
                    (0.0, 1.0)
                } else {
                    self.normal_angle(setup, state.t)
                },
            )),
            Ball::Grip => CartMotion::Grip(Grip {
                start: *state,
                cart,
            }),
        }
    }

    /// Inlined into the driver's loop, so that its answer is not returned through memory (Fig. 3(c)'s
    /// sweep row: 2% less time, 110 fewer instructions).
    #[inline(always)]
    fn first_event(
        &self,
        setup: &Setup,
        motion: &CartMotion,
        state: &State,
        (_, cart): Mode,
        cause: Cause,
    ) -> Found<State> {
        let (t0, end) = (state.t, setup.duration);
        // Event functions that start on their own zero (the slip after a grip broke or the friction
        // reversed, the cart's velocity after it stopped) are measured from their start value, so
        // rounding can never fake a crossing at the start.
        let slip_offset = if matches!(cause, Cause::SlipZero | Cause::GripBreak(_)) {
            setup.slip(state)
        } else {
            0.0
        };
        let v_offset = if matches!(cause, Cause::Start | Cause::CartStop | Cause::Unstick(_)) {
            state.v
        } else {
            0.0
        };
        // The scales of the speeds and forces, for the event functions' rounding (each taken only
        // where a branch needs it).
        let speeds =
            || self.incoming + state.vx.abs() + setup.r * state.omega.abs() + state.v.abs();
        let forces = || setup.peak_friction() + setup.k * state.x.abs() + setup.cart_friction;
        let (event, last) = match (motion, cart) {
            (CartMotion::Slide(slide), Cart::Moving(cart_dir)) => {
                let slip_noise = ROUNDING * speeds();
                let step = setup.event_step(setup.omega_slide);
                if setup.cart_friction > 0.0 {
                    let (slip_curvature, cart_curvature) = slide.curvature(setup);
                    let [slip_fourth, cart_fourth] = slide_fourth(setup, cart_curvature);
                    recorded(state, end, |last| {
                        let cart_dir = f64::from(cart_dir);
                        let f = |t: f64| {
                            let (s, friction) = slide.sample(setup, t);
                            last.record(s.t, s);
                            let slip = slide.slip_event(setup, &s, friction, slip_offset);
                            let [accel, jerk, snap] = slide.cart_derivatives(setup, &s, friction);
                            let stop = (
                                -cart_dir * (s.v - v_offset),
                                -cart_dir * accel,
                                -cart_dir * jerk,
                                -cart_dir * snap,
                            );
                            [slip, stop]
                        };
                        let noise = [slip_noise, ROUNDING * slide.cart_speed_scale(setup)];
                        let curvature = [slip_curvature, cart_curvature];
                        searched(
                            Regime::within("slide, string friction"),
                            f,
                            t0,
                            end,
                            step,
                            [curvature, [slip_fourth, cart_fourth]],
                            noise,
                        )
                        .map(|(t, branch)| {
                            let cause = if branch == 0 {
                                Cause::SlipZero
                            } else {
                                Cause::CartStop
                            };
                            (t, cause)
                        })
                    })
                } else if let Some(sums) = slide.slip_sums(setup) {
                    // Without string friction the cart's stopping changes nothing: the slip alone is
                    // watched, here by its sums; the state is computed only where the search ends.
                    let constants = sums.constants(slip_offset);
                    let probe = Cell::new(Probe::NONE);
                    let f = SlideBySums {
                        slide,
                        setup,
                        sums: &sums,
                        constants,
                        probe: &probe,
                    };
                    let bounds = [[sums.curvature], [sums.fourth]];
                    let event = searched(
                        Regime::predicted("slide by its sums"),
                        f,
                        t0,
                        end,
                        step,
                        bounds,
                        [slip_noise],
                    );
                    let t = event.map_or(end, |(t, _)| t);
                    let angles = probe.get().at(t).unwrap_or_else(|| slide.angles(setup, t));
                    // A slide from first contact measures its time from t = 0, so its first angle is
                    // the normal force's at t, the one the transition asks for (the same bits).
                    if slide.start.t == 0.0 {
                        self.normal_angle.set((t, angles.0));
                    }
                    let event = event.map(|(t, _)| (t, Cause::SlipZero));
                    (event, slide.sample_given(setup, t, angles).0)
                } else {
                    // Without string friction the cart's stopping changes nothing: the slip alone is
                    // watched.
                    let (slip_curvature, cart_curvature) = slide.curvature(setup);
                    let [slip_fourth, _] = slide_fourth(setup, cart_curvature);
                    recorded(state, end, |last| {
                        let f = |t: f64| {
                            let (s, friction) = slide.sample(setup, t);
                            last.record(s.t, s);
                            [slide.slip_event(setup, &s, friction, slip_offset)]
                        };
                        searched(
                            Regime::within("slide"),
                            f,
                            t0,
                            end,
                            step,
                            [[slip_curvature], [slip_fourth]],
                            [slip_noise],
                        )
                        .map(|(t, _)| (t, Cause::SlipZero))
                    })
                }
            }
            (CartMotion::Slide(slide), Cart::Stuck) => recorded(state, end, |last| {
                let f = |t: f64| {
                    let (s, friction) = slide.sample(setup, t);
                    last.record(s.t, s);
                    let slip = slide.slip_event(setup, &s, friction, slip_offset);
                    let push = friction.0 - setup.k * s.x;
                    let push_rate = slide.dir * setup.friction_limit_rate(t);
                    let [up, down] = setup.unstick_margins(push, push_rate);
                    // The still cart's X is fixed: push'' = F'' = -w² F, push''' = -w² F'.
                    let w2 = setup.w * setup.w;
                    let (second, third) = (-w2 * friction.0, -w2 * friction.1);
                    [
                        slip,
                        (up.0, up.1, second, third),
                        (down.0, down.1, -second, -third),
                    ]
                };
                let (slip_curvature, push_curvature) = slide.curvature(setup);
                // The still cart: slip'''' = -F'''/m_eff, push'''' = F''''.
                let [slip_fourth, _] = slide_fourth(setup, 0.0);
                let push_fourth = setup.peak_friction() * setup.w.powi(4) * (1.0 + 1e-9);
                let noise = [
                    ROUNDING * speeds(),
                    ROUNDING * forces(),
                    ROUNDING * forces(),
                ];
                let step = setup.event_step(0.0);
                let curvature = [slip_curvature, push_curvature, push_curvature];
                searched(
                    Regime::within("slide on a still cart"),
                    f,
                    t0,
                    end,
                    step,
                    [curvature, [slip_fourth, push_fourth, push_fourth]],
                    noise,
                )
                .map(|(t, branch)| (t, Cause::of_held(branch)))
            }),
            (CartMotion::Grip(grip), Cart::Moving(cart_dir)) => {
                let margin_noise = ROUNDING * forces();
                let step = setup.event_step(setup.omega_grip);
                let broke = |branch: usize| Cause::GripBreak(if branch == 0 { 1.0 } else { -1.0 });
                if setup.cart_friction > 0.0 {
                    let (margin_curvature, cart_curvature) = grip.curvature(setup);
                    let [margin_fourth, cart_fourth] = grip_fourth(setup, cart_curvature);
                    recorded(state, end, |last| {
                        let cart_dir = f64::from(cart_dir);
                        let f = |t: f64| {
                            let (s, [forward, backward]) = grip.evaluate(setup, t);
                            last.record(s.t, s);
                            let [accel, jerk, snap] = grip.cart_derivatives(setup, &s);
                            let stop = (
                                -cart_dir * (s.v - v_offset),
                                -cart_dir * accel,
                                -cart_dir * jerk,
                                -cart_dir * snap,
                            );
                            [forward, backward, stop]
                        };
                        let cart_noise = ROUNDING * grip.cart_speed_scale(setup);
                        let noise = [margin_noise, margin_noise, cart_noise];
                        let curvature = [margin_curvature, margin_curvature, cart_curvature];
                        searched(
                            Regime::within("grip, string friction"),
                            f,
                            t0,
                            end,
                            step,
                            [curvature, [margin_fourth, margin_fourth, cart_fourth]],
                            noise,
                        )
                        .map(|(t, branch)| {
                            let cause = if branch == 2 {
                                Cause::CartStop
                            } else {
                                broke(branch)
                            };
                            (t, cause)
                        })
                    })
                } else if let Some(sums) = grip.force_sums(setup) {
                    // Without string friction only the margins are watched, here by their sums; the
                    // state is computed only where the search ends.
                    // The normal force's angle at the start is the transition's.
                    let angles = |t: f64| {
                        if t == t0 {
                            ((0.0, 1.0), self.normal_angle(setup, t))
                        } else {
                            grip.angles(setup, t)
                        }
                    };
                    let probe = Cell::new(Probe::NONE);
                    let f = WithNear(
                        |t: f64| {
                            let angles = angles(t);
                            probe.set(Probe::fresh(t, angles));
                            sums.margins(setup, angles)
                        },
                        |t: f64| {
                            let rates = (setup.omega_grip, setup.w);
                            let near = probe.get().near(t, t0, rates, || angles(t));
                            probe.set(near);
                            sums.margins(setup, near.angles)
                        },
                    );
                    let bounds = [[sums.curvature; 2], [sums.fourth; 2]];
                    let event = searched(
                        Regime::predicted("grip by its sums"),
                        f,
                        t0,
                        end,
                        step,
                        bounds,
                        [margin_noise; 2],
                    );
                    let t = event.map_or(end, |(t, _)| t);
                    let angles = probe.get().at(t).unwrap_or_else(|| angles(t));
                    // The slide that follows starts from this normal force's angle.
                    self.normal_angle.set((t, angles.1));
                    let event = event.map(|(t, branch)| (t, broke(branch)));
                    (event, grip.state_given(setup, t, angles))
                } else {
                    // Without string friction only the margins are watched.
                    let (margin_curvature, cart_curvature) = grip.curvature(setup);
                    let [margin_fourth, _] = grip_fourth(setup, cart_curvature);
                    recorded(state, end, |last| {
                        let f = |t: f64| {
                            let (s, margins) = grip.evaluate(setup, t);
                            last.record(s.t, s);
                            margins
                        };
                        let curvature = [margin_curvature; 2];
                        searched(
                            Regime::within("grip"),
                            f,
                            t0,
                            end,
                            step,
                            [curvature, [margin_fourth; 2]],
                            [margin_noise; 2],
                        )
                        .map(|(t, branch)| (t, broke(branch)))
                    })
                }
            }
            // Rolling on a still cart: nothing changes until the ball leaves.
            (CartMotion::Grip(_), Cart::Stuck) => (None, *state),
        };
        Found {
            event,
            last: Some(last),
        }
    }

    fn state_at(&self, setup: &Setup, motion: &CartMotion, t: f64, last: Option<State>) -> State {
        // The event search's last evaluation is usually at the transition itself.
        match last {
            Some(s) if s.t == t => s,
            _ => motion.at(setup, t),
        }
    }

    fn next(&self, setup: &Setup, state: &mut State, (ball, cart): Mode, cause: Cause) -> Mode {
        if cause == Cause::CartStop {
            state.v = 0.0;
        }
        let t = state.t;
        transition::next_given(
            setup,
            &touched(setup, state),
            1.0,
            ball,
            cart,
            cause,
            || self.normal_angle(setup, t).0,
        )
    }
}

/// The event `search` finds, given where to record the states it evaluates (the last few are kept),
/// and the state at the event or, without one, at the end of contact `end`: usually among the
/// search's last evaluations (the crossing Newton found, before the evaluations that proved nothing
/// rose earlier), else the latest.
fn recorded(
    start: &State,
    end: f64,
    search: impl FnOnce(&Recent<State>) -> Option<(f64, Cause)>,
) -> (Option<(f64, Cause)>, State) {
    let last = Recent::new(start.t, *start);
    let event = search(&last);
    (event, last.at(event.map_or(end, |(t, _)| t)))
}

/// The slip of a slide by its sums at `t`, each probe's angles kept in `probe` for the state where the
/// search ends; evaluated in place at each of the search's calls (no call, no answer through memory).
struct SlideBySums<'a> {
    slide: &'a Slide,
    setup: &'a Setup,
    sums: &'a SlipSums,
    constants: (f64, f64),
    probe: &'a Cell<Probe>,
}

impl Event<(f64, f64, f64, f64), 1> for SlideBySums<'_> {
    #[inline(always)]
    fn at(&self, t: f64) -> [(f64, f64, f64, f64); 1] {
        let angles = self.slide.angles(self.setup, t);
        self.probe.set(Probe::fresh(t, angles));
        [self.sums.event(angles, self.constants)]
    }

    #[inline(always)]
    fn near(&self, t: f64) -> [(f64, f64, f64, f64); 1] {
        let (slide, setup) = (self.slide, self.setup);
        let rates = (setup.w, setup.omega_slide);
        let probe = (self.probe.get()).near(t, slide.start.t, rates, || slide.angles(setup, t));
        self.probe.set(probe);
        [self.sums.event(probe.angles, self.constants)]
    }
}

/// A search of the single cart: its name, for the test of its bounds, and whether it refines from
/// predicted crossings.
#[derive(Clone, Copy)]
struct Regime {
    name: &'static str,
    predicted: bool,
}

impl Regime {
    /// A search by [`first_rise_within`].
    fn within(name: &'static str) -> Self {
        Regime {
            name,
            predicted: false,
        }
    }

    /// A search by [`first_rise_predicted`], for the searches by sums, whose f'' and f''' are as exact
    /// as f and f'.
    fn predicted(name: &'static str) -> Self {
        Regime {
            name,
            predicted: true,
        }
    }
}

/// The search of `regime`; under test, where [`bounds`] asks it, the bounds are first checked against
/// the branches they bound.
#[inline(always)]
fn searched<const K: usize>(
    regime: Regime,
    f: impl Event<(f64, f64, f64, f64), K>,
    t0: f64,
    end: f64,
    step: f64,
    bounds: [[f64; K]; 2],
    noise: [f64; K],
) -> Option<(f64, usize)> {
    let search = move |f| {
        if regime.predicted {
            first_rise_predicted(f, t0, end, step, bounds, noise)
        } else {
            first_rise_within(f, t0, end, step, bounds, noise)
        }
    };
    #[cfg(test)]
    let found = super::bound_samples::search_checked(
        || regime.name.to_string(),
        f,
        (t0, end, step),
        bounds,
        search,
    );
    #[cfg(not(test))]
    let found = {
        let _ = regime.name;
        search(f)
    };
    found
}

/// Bounds on the fourth derivatives of a slide's slip and of its cart's velocity, given the bound
/// `cart_curvature` on |V''| over the phase (0 for a still cart): M V' = F - k X less the constant
/// string friction gives M V'''' = F''' - k V'', and slip' = -F/m_eff - V', with |F'''| <= mu N0 w³.
fn slide_fourth(setup: &Setup, cart_curvature: f64) -> [f64; 2] {
    let jerk = setup.peak_friction() * setup.w.powi(3);
    let cart = (jerk + setup.k * cart_curvature) / setup.cart_mass;
    let room = 1.0 + 1e-9;
    [(jerk / setup.m_eff + cart) * room, cart * room]
}

/// Bounds on the fourth derivatives of a moving grip's margins and of its cart's velocity, given the
/// bound `cart_curvature` = Ω³ A on |V''| over the phase: |X''''| <= Ω⁴ A and |V''''| <= Ω⁵ A, and
/// mu N'''' is at most mu N0 w⁴.
fn grip_fourth(setup: &Setup, cart_curvature: f64) -> [f64; 2] {
    let omega = setup.omega_grip;
    let margin = (setup.grip_gain * omega * cart_curvature
        + setup.peak_friction() * setup.w.powi(4))
        * (1.0 + 1e-9);
    [margin, omega * omega * cart_curvature * (1.0 + 1e-9)]
}

/// The cart as the transition rules see it.
fn touched(setup: &Setup, state: &State) -> Touched {
    Touched {
        t: state.t,
        mass: setup.cart_mass,
        spring: setup.k * state.x,
        v: state.v,
    }
}
