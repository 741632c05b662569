//! The simulation core: the ball-on-cart model of Cross (2010), solved exactly phase by phase.
//! No terminal, no files, no printing: everything else calls [`solve`] and reads the [`Bounce`].

pub mod bounce;
pub mod cart;
pub mod chain;
pub mod compliant;
pub mod events;
pub mod grip;
pub mod limits;
pub mod oscillator;
pub mod params;
pub mod quadrature;
pub mod setup;
pub mod slide;
pub mod transition;
pub mod units;

pub use bounce::{
    BallPhase, Bounce, Energy, Outcome, Phase, PhaseKind, Sample, SolveError, solve,
    solve_cancellable,
};
pub use cart::Cart;
pub use params::{PARAMS, ParamError, ParamId, ParamSpec, Params};
pub use setup::State;
