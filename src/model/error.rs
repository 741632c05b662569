//! Why a bounce could not be solved, and the limits behind the refusals.

use super::events::Stall;
use super::params::ParamError;

/// The largest number of cart radians per contact the solver accepts (about 16 000 oscillations).
pub const MAX_RADIANS: f64 = 1e5;
/// The largest number of slide/grip transitions in one bounce, unless the caller sets its own
/// ([`super::options::SolveOptions::max_phases`]).
pub const MAX_TRANSITIONS: usize = 10_000;

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

/// Why a bounce could not be solved.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolveError {
    #[error(transparent)]
    Params(#[from] ParamError),
    #[error(
        "the cart oscillates too fast to resolve: sqrt(k/M) T = {radians:.3e} rad exceeds {MAX_RADIANS:e} \
         (lower the stiffness, raise the cart mass or shorten the impact)"
    )]
    TooFast { radians: f64 },
    #[error("the bounce switched between sliding and gripping more than {limit} times{hint}")]
    TooManyPhases {
        /// The phase cap the solve ran under.
        limit: usize,
        /// What would calm it, where the model knows (empty otherwise).
        hint: &'static str,
    },
    /// The caller's cancellation check said the solve is no longer wanted.
    #[error("the solve was cancelled")]
    Cancelled,
    #[error(
        "the ball's contact {part} is too fast to resolve: the grip's fastest rate times T = {radians:.3e} \
         rad exceeds {MAX_RADIANS:e} ({advice})"
    )]
    BallTooFast {
        radians: f64,
        /// `spring` or `dashpot`: the larger share of the rate.
        part: &'static str,
        /// The parameters that would make the bounce solvable.
        advice: String,
    },
    #[error(transparent)]
    Unsolvable(#[from] Unsolvable),
    #[error("{stall}{hint}")]
    Stalled {
        stall: Stall,
        /// What would help, where the parameters say (empty otherwise).
        hint: &'static str,
    },
    #[error(
        "the command used up its work budget: under these parameters its bounces are too costly to \
         solve them all (parameters nearer the paper's take seconds)"
    )]
    CommandBudget,
    /// A combination not yet solved on a free frame (`--frame-mass`).
    #[error("{what} on a free frame is not solved yet (use --frame-mass clamped)")]
    FreeFrame { what: &'static str },
    #[error(
        "{quantity} is not a finite number: the parameters are beyond what f64 carries through"
    )]
    NotFinite { quantity: &'static str },
}
