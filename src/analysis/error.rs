//! Why an analysis could not be run.

use crate::model::{ParamError, SolveError};

/// An analysis failure. All but [`AnalysisError::Cancelled`] come from the input, so the command line
/// reports them with status 2; each message names the flag, the allowed values and the value given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AnalysisError {
    /// A flag of the analysis itself (`--from`, `--steps`, `--objective`, ...) is unusable.
    #[error("{0}")]
    Input(String),
    /// A parameter value given to the analysis is out of its range.
    #[error("{flag}: {source}")]
    Param {
        flag: &'static str,
        source: ParamError,
    },
    /// The core could not solve one of the bounces.
    #[error("at --{flag} {value}: {source}")]
    Solve {
        flag: &'static str,
        value: String,
        source: SolveError,
    },
    /// The core could not solve one of a fixed set of cases (the paper's figures and claims).
    #[error("{case}: {source}")]
    Case { case: String, source: SolveError },
    /// The caller stopped the analysis (the explorer's fit, cancelled by a key).
    #[error("cancelled")]
    Cancelled,
}
