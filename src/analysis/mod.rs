//! Analyses built on the simulation core's public API: parameter sweeps, the critical angle of
//! Eq. (7), one-parameter optimisation, the paper's figures as data, and the check of every number the
//! paper prints (`assets/claims.md`). Nothing here prints or draws; the command line and the exports do.

pub mod brent;
pub mod cases;
pub mod claims;
pub mod critical;
pub mod error;
pub mod figures;
pub mod fit;
pub mod optimize;
pub mod reproduce;
pub mod retune;
pub mod shots;
pub mod span;
pub mod sweep;
pub mod timeline;
pub mod uncertainty;

pub use error::AnalysisError;
pub use span::Span;
