//! The simulation core: the ball-on-cart model of Cross (2010), solved exactly phase by phase.
//! No terminal, no files, no printing: everything else calls [`solve()`] and reads the [`Bounce`].
//!
//! The way through: [`Params`] -> [`Setup`] (everything derived once) -> a contact model ([`cart`],
//! [`chain`], [`compliant`]), each implementing [`contact::Contact`] -> the phase [`driver`] ->
//! [`Bounce`] (results only).

pub mod bounce;
#[cfg(test)]
mod bound_samples;
pub mod budget;
pub mod cart;
pub mod chain;
pub mod compliant;
pub mod contact;
pub mod driver;
pub mod energy;
pub mod error;
pub mod events;
pub mod frame;
pub mod memo;
pub mod options;
pub mod oscillator;
pub mod params;
pub mod phase;
pub mod probe;
pub mod quadrature;
pub mod recent;
pub mod registry;
pub mod reportable;
pub mod setup;
pub mod solvable;
pub mod solve;
pub mod sums;
pub mod transition;
pub mod trig;
pub mod units;

pub use bounce::{Bounce, Outcome, Sample};
pub use budget::Work;
pub use contact::Cart;
pub use energy::Energy;
pub use error::{SolveError, Unsolvable};
pub use options::SolveOptions;
pub use params::{PARAMS, ParamError, ParamId, ParamSpec, Params};
pub use phase::{BallPhase, Phase, PhaseKind};
pub use registry::{BallKind, FrameKind, ModelKind, SupportKind, Words};
pub use setup::{Setup, State};
pub use solve::{Varied, solve, solve_cancellable, solve_in, solve_with};
