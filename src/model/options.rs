//! How a caller runs a solve: when to abandon it, how many phases it may have, and the work it may
//! spend. Passed in, never read from process-wide state; [`SolveOptions::default`] is what
//! [`super::solve()`] uses.

use super::budget::Work;
use super::error::MAX_TRANSITIONS;

/// The caller's terms for a solve.
#[derive(Clone, Copy)]
pub struct SolveOptions<'a> {
    /// Asked before every phase: true abandons the solve with [`super::SolveError::Cancelled`] (the
    /// explorer's newer job, a command's Ctrl-C).
    pub cancelled: &'a (dyn Fn() -> bool + Sync),
    /// The most phases one bounce may have before it is refused with
    /// [`super::SolveError::TooManyPhases`].
    pub max_phases: usize,
    /// The work shared with the caller's other solves, and their count; `None`: only each solve's own
    /// budget.
    pub work: Option<&'a Work>,
}

fn never() -> bool {
    false
}

impl Default for SolveOptions<'_> {
    /// Never cancelled, [`MAX_TRANSITIONS`] phases, each solve's own budget.
    fn default() -> Self {
        SolveOptions {
            cancelled: &never,
            max_phases: MAX_TRANSITIONS,
            work: None,
        }
    }
}

impl<'a> SolveOptions<'a> {
    /// The defaults, abandoned once `cancelled` returns true.
    pub fn cancelled_by(cancelled: &'a (dyn Fn() -> bool + Sync)) -> Self {
        SolveOptions {
            cancelled,
            ..SolveOptions::default()
        }
    }
}
