//! What every contact model shares: the vocabulary of a phase (what the ball does, what the cart does,
//! why a phase ended), the [`Contact`] trait that the phase driver ([`super::driver`]) runs, and the
//! [`PhaseMotion`] trait through which a solved phase answers every query about itself.

use serde::Serialize;

use super::setup::{Setup, State};

/// An arriving slip below this fraction of |v_x1| + r |omega1| counts as rolling.
pub const ROLLING: f64 = 1e-12;
/// Event functions are differences of terms this many times their size apart from rounding; a rise
/// smaller than that is noise (it matters near t = T, where N and with it F and F_s vanish).
pub const ROUNDING: f64 = 1e-12;

/// What the ball does in a phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ball {
    /// Sliding with the slip's sign (+1 or -1).
    Slide(f64),
    Grip,
}

/// What the cart does in a phase: moves, with string-on-string friction F_c against its motion, or
/// sticks, held by that friction (Sec. IV's proposed enhancement; F_c = 0 is the paper's model).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Cart {
    /// Moving in direction +1 or -1; with no string friction the direction plays no part.
    Moving(i8),
    /// Held still by string friction.
    Stuck,
}

impl Cart {
    /// The string friction on the moving cart, -dir F_c (zero when stuck: the holding force is not a
    /// driving term of the motion).
    pub fn friction(self, setup: &Setup) -> f64 {
        match self {
            Cart::Moving(dir) => -f64::from(dir) * setup.cart_friction,
            Cart::Stuck => 0.0,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Cart::Moving(_) => "moving",
            Cart::Stuck => "stuck",
        }
    }
}

/// Why a phase ended (or, at first contact, that none has yet).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cause {
    /// First contact.
    Start,
    /// The slip reached zero.
    SlipZero,
    /// The static friction reached mu N; the sign of F_s.
    GripBreak(f64),
    /// The moving cart came to rest.
    CartStop,
    /// The force on a stuck cart exceeded the string friction; the direction it pushes.
    Unstick(i8),
}

impl Cause {
    /// What ended a phase on a held cart (or first mass) whose event search watches, in this order, the
    /// ball's slip and the push on the held cart reaching +F_c and -F_c: the cause of `branch`.
    pub fn of_held(branch: usize) -> Cause {
        match branch {
            0 => Cause::SlipZero,
            1 => Cause::Unstick(1),
            _ => Cause::Unstick(-1),
        }
    }
}

/// The mode of a phase: what the ball and the cart do.
pub type Mode = (Ball, Cart);

/// The first event of a phase, and the model's state at the last time its event function was
/// evaluated (usually the event itself, which then need not be evaluated again).
pub struct Found<P> {
    pub event: Option<(f64, Cause)>,
    pub last: Option<P>,
}

/// A contact model: what the ball touches, and how ball and surface move in each phase, in closed form.
/// The driver asks it for the phase's motion, the first event after the phase starts (located by root
/// finding on the closed form), the state there, and the mode that follows.
pub trait Contact {
    /// Everything the model carries from one phase to the next.
    type State: Copy;
    /// One phase's closed-form motion (answering for itself through [`PhaseMotion`]).
    type Motion;
    /// What the event search last evaluated.
    type Probe: Copy;

    /// The state and mode at first contact.
    fn start(&self, setup: &Setup) -> (Self::State, Mode);
    /// The time of a state.
    fn time(state: &Self::State) -> f64;
    /// The ball and the surface where the ball touches it.
    fn contact(state: &Self::State) -> State;
    /// The closed-form motion of the phase in `mode` from `state`.
    fn motion(&self, setup: &Setup, state: &Self::State, mode: Mode) -> Self::Motion;
    /// The first event of the phase in `(t0, end]`; `cause` is why the phase began.
    fn first_event(
        &self,
        setup: &Setup,
        motion: &Self::Motion,
        state: &Self::State,
        mode: Mode,
        cause: Cause,
    ) -> Found<Self::Probe>;
    /// The state at `t` in the phase, `last` the search's last evaluation.
    fn state_at(
        &self,
        setup: &Setup,
        motion: &Self::Motion,
        t: f64,
        last: Option<Self::Probe>,
    ) -> Self::State;
    /// The mode after `cause` at `state` (which it may settle, e.g. a stopped cart's velocity to zero).
    fn next(&self, setup: &Setup, state: &mut Self::State, mode: Mode, cause: Cause) -> Mode;
}

/// What one phase's closed-form motion answers about itself: the state and friction at any time, the
/// energy in the surface, the work of the sliding friction, and the ball's own energy terms. Each model
/// implements it for its motion, so a solved bounce ([`super::phase`], [`super::energy`]) asks the model
/// instead of deciding the physics itself.
pub trait PhaseMotion {
    /// The ball and the surface where the ball touches it at `t` (exact for `t` in the phase).
    fn state_at(&self, setup: &Setup, t: f64) -> State;
    /// The friction force on the ball, positive backward, at `state` (a state of this phase).
    fn friction(&self, setup: &Setup, state: &State) -> f64;
    /// The state at the start of the phase.
    fn initial(&self) -> State;
    /// The stretch e (m) of a compliant ball and the slip (m/s) of its contact patch on the surface at
    /// `t`; `None` for a model without a contact patch.
    fn patch_at(&self, setup: &Setup, t: f64) -> Option<(f64, f64)>;
    /// Kinetic plus spring energy of the surface (the cart and its spring, or every mass and spring of a
    /// chain) at the time of `at`, a state of this phase.
    fn surface_energy(&self, setup: &Setup, at: &State) -> f64;
    /// The energy the sliding friction takes over `[start, end]`, the integral of F times the slip it
    /// works against (the ball's contact point's, or a compliant ball's patch's) on the exact solution.
    fn friction_work(&self, setup: &Setup, start: f64, end: f64) -> f64;
    /// The fastest angular frequency of the surface's motion in this phase (the cart's, or the chain's
    /// fastest mode), rad/s.
    fn fastest(&self, setup: &Setup) -> f64;
    /// The energy held in the ball's own tangential spring at `t` (a compliant ball's k_b e²/2).
    fn ball_spring_energy(&self, setup: &Setup, t: f64) -> f64;
    /// The energy lost in the ball's own dashpot over `[start, end]` (a compliant ball's ∫ c_b e'² dt).
    fn dashpot_loss(&self, setup: &Setup, start: f64, end: f64) -> f64;
    /// The velocity along the surface of the frame the strings are tied to, at `t` (0 when clamped).
    fn frame_velocity(&self, setup: &Setup, t: f64) -> f64;
}
