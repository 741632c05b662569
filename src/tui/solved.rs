//! A solved bounce with everything the explorer derives from it: the time series of the contact charts,
//! the ball's travel for the schematic and the energy budget of the outcome panel. All of it is computed
//! on the worker, so drawing only reads.

use crate::model::{Bounce, Energy, Params, Sample, SolveError, solve_cancellable};

use super::travel::Travel;

/// Evenly spaced samples of the time series behind the contact charts (transitions are added by the core).
pub const SERIES_SAMPLES: usize = 400;

/// The bounce for `params` and what is drawn from it.
#[derive(Clone, Debug)]
pub struct Solved {
    pub params: Params,
    pub bounce: Bounce,
    pub series: Vec<Sample>,
    pub travel: Travel,
    pub energy: Energy,
}

impl Solved {
    /// Solves `params` and derives the rest; [`SolveError::Cancelled`] once `cancelled` says so.
    pub fn compute(
        params: &Params,
        cancelled: &(impl Fn() -> bool + Sync),
    ) -> Result<Solved, SolveError> {
        let bounce = solve_cancellable(params, cancelled)?;
        Ok(Solved {
            params: *params,
            series: bounce.series(SERIES_SAMPLES),
            travel: Travel::compute(&bounce),
            energy: bounce.energy(),
            bounce,
        })
    }

    /// The contact time T, s.
    pub fn duration(&self) -> f64 {
        self.bounce.setup.duration
    }

    /// The core's sample at `t`; at a transition, that of the phase that begins there.
    pub fn sample_at(&self, t: f64) -> Sample {
        self.bounce.sample_at(t)
    }

    /// When `t` is exactly on a transition, the sample at the end of the phase before it (the friction
    /// force jumps there; every other value is continuous).
    pub fn sample_before(&self, t: f64) -> Option<Sample> {
        let index = self.bounce.phase_index_at(t);
        (index > 0 && self.bounce.phases[index].start == t)
            .then(|| self.bounce.sample_in(index - 1, t))
    }

    /// The transitions the time cursor can jump to: 0, the start of every phase after the first, and T.
    pub fn stops(&self) -> impl Iterator<Item = f64> + '_ {
        std::iter::once(0.0)
            .chain(self.bounce.phases.iter().skip(1).map(|p| p.start))
            .chain(std::iter::once(self.duration()))
    }
}
