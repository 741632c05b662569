//! Watching a fit from outside: where it has got to, and a way to stop it. The fit tells a [`Watch`]
//! after every evaluation of the model; the watch counts the bounces solved, and its cancellation hook is
//! asked before every phase of every bounce, so a stopped fit ends within one phase. Watching changes
//! no number of the fit.

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The steps of a fit, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Scoring the starting points.
    Scan,
    /// Short runs of Levenberg-Marquardt from the best starting points.
    Refine,
    /// The best of them run to convergence.
    Converge,
}

/// Where a fit has got to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    pub stage: Stage,
    /// Starting points scored, or short runs finished, of `of` (0 of 1 until the final run ends).
    pub done: usize,
    pub of: usize,
    /// Bounces solved so far.
    pub solves: usize,
}

/// What the fit asks and tells as it goes.
pub struct Watch<'a> {
    /// True stops the fit: it then returns [`super::AnalysisError::Cancelled`].
    pub cancelled: &'a (dyn Fn() -> bool + Sync),
    /// Told where the fit has got to after each evaluation of the model.
    pub progress: &'a (dyn Fn(Progress) + Sync),
}

impl Watch<'_> {
    /// A watch that never stops the fit and is told nothing.
    pub fn none() -> Watch<'static> {
        Watch {
            cancelled: &|| false,
            progress: &|_| {},
        }
    }
}

/// A watch with the fit's count of solves and its stage.
pub struct Tally<'a> {
    watch: &'a Watch<'a>,
    solves: AtomicUsize,
    stage: Mutex<(Stage, usize, usize)>,
}

impl<'a> Tally<'a> {
    pub fn new(watch: &'a Watch<'a>) -> Self {
        Tally {
            watch,
            solves: AtomicUsize::new(0),
            stage: Mutex::new((Stage::Scan, 0, 1)),
        }
    }

    pub fn cancelled(&self) -> bool {
        (self.watch.cancelled)()
    }

    /// One more bounce solved (or tried).
    pub fn solved(&self) {
        self.solves.fetch_add(1, Ordering::Relaxed);
    }

    /// The fit is at `stage`, `done` of `of`; the watch is told.
    pub fn at(&self, stage: Stage, done: usize, of: usize) {
        if let Ok(mut s) = self.stage.lock() {
            *s = (stage, done, of);
        }
        self.report();
    }

    /// Tells the watch where the fit is.
    pub fn report(&self) {
        let (stage, done, of) = self.stage.lock().map_or((Stage::Scan, 0, 1), |s| *s);
        (self.watch.progress)(Progress {
            stage,
            done,
            of,
            solves: self.solves.load(Ordering::Relaxed),
        });
    }
}
