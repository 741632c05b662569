//! The work a solve may spend. Each solve has its own budget of event evaluations ([`budget`]); a
//! command whose number of bounces the program fixes also shares one [`Work`] between all its solves,
//! which counts the bounces solved as well. Both are passed in ([`super::options::SolveOptions`]).

use std::sync::atomic::{AtomicU64, Ordering};

use super::params::Params;

/// Event evaluations per solve on the single cart: about twice what the heaviest bounces the
/// contact-rate limits admit need (a stiff, heavily damped ball near MAX_RADIANS: 5.6 million), a few
/// seconds of work.
const BUDGET: u64 = 12_000_000;

/// The work budget of one solve: `BUDGET` evaluations on the single cart, fewer on a chain of N
/// masses, whose evaluations cost about (N + 1)/2 times as much.
pub fn budget(params: &Params) -> u64 {
    let links = params.chain.clamp(1.0, 16.0) as u64;
    BUDGET * 2 / (links + 1)
}

/// What one evaluation costs, in work units: a chain of N masses costs about (N + 1)/2 times the
/// single cart's, which costs 2.
pub(super) fn weight(params: &Params) -> u64 {
    params.chain.clamp(1.0, 16.0) as u64 + 1
}

/// The work of a command whose bounces the program fixes: about ten seconds of solving (the paper's
/// `reproduce` takes 14 million units, on a chain of 4 masses 110 million).
pub const COMMAND_WORK: u64 = 300_000_000;

/// The work left to a command's solves, in evaluations weighted by their cost (`weight`), and the
/// bounces they solved (or refused). Shared by reference between threads.
#[derive(Debug)]
pub struct Work {
    left: AtomicU64,
    /// False for [`Work::unlimited`], whose solves spend nothing (no atomic update per solve).
    limited: bool,
    solved: AtomicU64,
}

impl Work {
    /// No limit beyond each solve's own budget: only the count.
    pub const fn unlimited() -> Work {
        Work {
            limited: false,
            ..Work::limited(u64::MAX)
        }
    }

    /// At most `units` (evaluations times their weight) for all the solves that share it: for a
    /// command whose number of bounces is fixed by the program, not by the user (`reproduce`,
    /// `figure`, `critical-angle`), so that parameters that make each bounce costly cannot make the
    /// whole take minutes.
    pub const fn limited(units: u64) -> Work {
        Work {
            left: AtomicU64::new(units),
            limited: true,
            solved: AtomicU64::new(0),
        }
    }

    /// How many bounces have been solved (or refused) under it.
    pub fn solved(&self) -> u64 {
        self.solved.load(Ordering::Relaxed)
    }

    pub(super) fn left(&self) -> u64 {
        self.left.load(Ordering::Relaxed)
    }

    pub(super) fn spend(&self, units: u64) {
        if !self.limited {
            return;
        }
        let _ = self
            .left
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |left| {
                Some(left.saturating_sub(units))
            });
    }

    pub(super) fn count(&self) {
        self.solved.fetch_add(1, Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chain_gets_a_smaller_budget() {
        let chain = Params {
            chain: 16.0,
            ..Params::default()
        };
        assert_eq!(budget(&Params::default()), BUDGET);
        assert!(budget(&chain) < BUDGET / 8);
    }

    #[test]
    fn shared_work_is_spent_down_to_zero() {
        let work = Work::limited(10);
        work.spend(4);
        assert_eq!(work.left(), 6);
        work.spend(40);
        assert_eq!(work.left(), 0);
        work.count();
        assert_eq!(work.solved(), 1);
    }
}
