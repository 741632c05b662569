//! Watching a fit from outside: where it has got to, and a way to stop it. The fit tells a [`Watch`]
//! after every evaluation of the model; the watch counts the bounces solved, and its cancellation hook is
//! asked before every phase of every bounce, so a stopped fit ends within one phase. Watching changes
//! no number of the fit.

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::model::{SolveOptions, Work};

/// The steps of a fit, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Scoring the starting points.
    Scan,
    /// Short runs of Levenberg-Marquardt from the best starting points.
    Refine,
    /// The distinct ends of the short runs run to convergence.
    Converge,
    /// The profile-likelihood intervals walked out, two sides of each free parameter.
    Profile,
}

/// Where a fit has got to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    pub stage: Stage,
    /// Starting points scored, runs finished or profile sides walked, of `of`.
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
    /// The work the fit's solves share with the caller's, which counts them too; `None`: each solve's
    /// own budget only.
    pub work: Option<&'a Work>,
}

impl<'a> Watch<'a> {
    /// A watch that never stops the fit and is told nothing.
    pub fn none() -> Watch<'static> {
        Watch {
            cancelled: &|| false,
            progress: &|_| {},
            work: None,
        }
    }

    /// A watch on a command's terms: stopped by `options`' cancellation (its Ctrl-C), its solves under
    /// and counted by `options`' work; told nothing. The fit keeps its own phase caps.
    pub fn of(options: &SolveOptions<'a>) -> Watch<'a> {
        Watch {
            cancelled: options.cancelled,
            progress: &|_| {},
            work: options.work,
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

    /// The work the fit's solves share with the caller's.
    pub fn work(&self) -> Option<&'a Work> {
        self.watch.work
    }

    /// One more bounce solved (or tried).
    pub fn solved(&self) {
        self.solves.fetch_add(1, Ordering::Relaxed);
    }

    /// The fit is at `stage`, `done` of `of`; the watch is told.
    pub fn at(&self, stage: Stage, done: usize, of: usize) {
        if let Ok(mut s) = self.stage.lock() {
            *s = (stage, done, of);
            self.tell(*s);
        }
    }

    /// Tells the watch where the fit is.
    pub fn report(&self) {
        if let Ok(s) = self.stage.lock() {
            self.tell(*s);
        }
    }

    /// Called with the stage's lock held, so that reports from the search's threads reach the watch one
    /// at a time, in order: the count of solves a watch sees never goes back.
    fn tell(&self, (stage, done, of): (Stage, usize, usize)) {
        (self.watch.progress)(Progress {
            stage,
            done,
            of,
            solves: self.solves.load(Ordering::Relaxed),
        });
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::*;
    use crate::analysis::AnalysisError;
    use crate::analysis::fit::{Options, data, fit, fit_watched, free};
    use crate::model::Params;

    fn synthetic() -> data::Dataset {
        let text = include_str!("../../../assets/data/synthetic-strings.csv");
        data::parse(text, "synthetic").unwrap()
    }

    #[test]
    fn a_watched_fit_is_the_same_fit_and_says_where_it_is() {
        let data = synthetic();
        let free = free::parse_list("cart-mass,stiffness,mu", &data.conditions).unwrap();
        let base = Params::default();
        let seen = Mutex::new(Vec::new());
        let watch = Watch {
            cancelled: &|| false,
            progress: &|p| seen.lock().unwrap().push(p),
            work: None,
        };
        let watched = fit_watched(&base, &free, &data, &Options::default(), &watch).unwrap();
        assert_eq!(
            watched,
            fit(&base, &free, &data, &Options::default()).unwrap()
        );
        let seen = seen.into_inner().unwrap();
        // Scan, short runs, runs to convergence, profiles, in order; the count of solves never goes back.
        let stages: Vec<Stage> = seen.iter().map(|p| p.stage).collect();
        assert_eq!(stages.first(), Some(&Stage::Scan));
        assert!(stages.contains(&Stage::Refine));
        assert!(stages.is_sorted_by_key(|s| *s as u8));
        assert!(seen.windows(2).all(|w| w[0].solves <= w[1].solves));
        let last = seen.last().unwrap();
        assert_eq!((last.stage, last.done, last.of), (Stage::Profile, 1, 1));
        assert!(last.solves > data.rows.len() * 37);
    }

    #[test]
    fn a_cancelled_fit_stops_soon_and_says_so() {
        let data = synthetic();
        let free = free::parse_list("cart-mass,stiffness,mu", &data.conditions).unwrap();
        let reports = AtomicUsize::new(0);
        let solves = AtomicUsize::new(0);
        // Stopped after its fifth report: a few more solves at most, none of the later stages.
        let watch = Watch {
            cancelled: &|| reports.load(Ordering::Relaxed) >= 5,
            progress: &|p| {
                reports.fetch_add(1, Ordering::Relaxed);
                solves.store(p.solves, Ordering::Relaxed);
            },
            work: None,
        };
        let result = fit_watched(
            &Params::default(),
            &free,
            &data,
            &Options::default(),
            &watch,
        );
        assert_eq!(result, Err(AnalysisError::Cancelled));
        assert!(solves.load(Ordering::Relaxed) < 50 * data.rows.len());
    }
}
