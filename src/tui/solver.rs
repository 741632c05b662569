//! What the explorer asks of the core, off the UI thread: the bounce (with its series, travel and energy)
//! on one worker, the two Fig. 2 sweeps on another, each newest request first (an older one still running
//! is cancelled), and the answers kept by parameters, so that going back to parameters seen recently
//! (undo, a step back) costs nothing. A job that panics answers with the [`Crash`]: the bounce as a
//! refusal, the sweeps as an [`Arrival::Crash`]; neither is asked for again.

use std::sync::Arc;
use std::time::Duration;

use super::solved::Solved;
use super::sweep::Sweeps;
use super::worker::{Crash, Worker};
use crate::model::{Params, SolveError};

/// A bounce, or why the core refused it.
pub type Answer = Result<Arc<Solved>, String>;

/// The latest answers, newest last, at most `CAPACITY` of them.
#[derive(Debug)]
pub(super) struct Recent<T> {
    entries: Vec<(Params, T)>,
}

impl<T: Clone> Recent<T> {
    const CAPACITY: usize = 32;

    pub(super) fn get(&self, key: &Params) -> Option<T> {
        self.entries
            .iter()
            .rev()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.clone())
    }

    pub(super) fn put(&mut self, key: Params, value: T) {
        self.entries.retain(|(k, _)| *k != key);
        if self.entries.len() == Self::CAPACITY {
            self.entries.remove(0);
        }
        self.entries.push((key, value));
    }
}

impl<T> Default for Recent<T> {
    fn default() -> Self {
        Recent {
            entries: Vec::new(),
        }
    }
}

/// Something that arrived from a worker.
#[derive(Debug)]
pub enum Arrival {
    /// Boxed: the parameters are the largest part (clippy's large_enum_variant).
    Bounce(Box<Params>, Answer),
    Sweeps(Arc<Sweeps>),
    /// The sweeps' job panicked.
    Crash(Crash),
}

/// The workers and what they have answered.
#[derive(Debug)]
pub struct Solver {
    bounces: Worker<Params, (Params, Answer)>,
    sweeps: Worker<Params, Arc<Sweeps>>,
    bounce_cache: Recent<Answer>,
    sweep_cache: Recent<Arc<Sweeps>>,
    /// The parameters of the bounce and of the sweeps asked for last, until answered.
    bounce_wanted: Option<Params>,
    sweeps_wanted: Option<Params>,
    /// The sweeps whose job panicked: not asked for again.
    sweeps_crashed: Option<Params>,
}

impl Default for Solver {
    fn default() -> Self {
        Solver {
            bounces: Worker::spawn("bounce", |params: Params, job| {
                let answer = match Solved::compute(&params, &|| job.cancelled()) {
                    Ok(solved) => Ok(Arc::new(solved)),
                    Err(SolveError::Cancelled) => return,
                    Err(e) => Err(e.to_string()),
                };
                job.send((params, answer));
            }),
            sweeps: Worker::spawn("sweeps", |key: Params, job| {
                if let Some(sweeps) = Sweeps::compute(&key, &|| job.cancelled()) {
                    job.send(Arc::new(sweeps));
                }
            }),
            bounce_cache: Recent::default(),
            sweep_cache: Recent::default(),
            bounce_wanted: None,
            sweeps_wanted: None,
            sweeps_crashed: None,
        }
    }
}

impl Solver {
    /// The bounce for `params` if it is known; otherwise it is asked for (cancelling any other) and
    /// comes later as an [`Arrival`].
    pub fn bounce(&mut self, params: &Params) -> Option<Answer> {
        let known = self.bounce_cache.get(params);
        if known.is_some() {
            if self.bounce_wanted.take().is_some() {
                self.bounces.cancel();
            }
        } else if self.bounce_wanted != Some(*params) {
            self.bounce_wanted = Some(*params);
            self.bounces.submit(*params);
        }
        known
    }

    /// Both sweeps for `params` (the angle aside) if they are known; otherwise as [`Solver::bounce`].
    pub fn sweeps(&mut self, params: &Params) -> Option<Arc<Sweeps>> {
        let key = Sweeps::key(params);
        let known = self.sweep_cache.get(&key);
        if known.is_some() {
            if self.sweeps_wanted.take().is_some() {
                self.sweeps.cancel();
            }
        } else if self.sweeps_wanted != Some(key) && self.sweeps_crashed != Some(key) {
            self.sweeps_wanted = Some(key);
            self.sweeps.submit(key);
        }
        known
    }

    /// The sweeps for `params` if they are known, asking for nothing.
    pub fn known_sweeps(&self, params: &Params) -> Option<Arc<Sweeps>> {
        self.sweep_cache.get(&Sweeps::key(params))
    }

    /// True while an answer is awaited.
    pub fn busy(&self) -> bool {
        self.bounce_wanted.is_some() || self.sweeps_wanted.is_some()
    }

    /// What has arrived for the newest requests, now kept.
    pub fn collect(&mut self) -> Vec<Arrival> {
        let bounces: Vec<_> = self.bounces.try_iter().collect();
        let sweeps: Vec<_> = self.sweeps.try_iter().collect();
        self.take(bounces, sweeps)
    }

    /// Waits up to `timeout` for an answer, then as [`Solver::collect`] (for tests and benchmarks,
    /// which settle before each step).
    pub fn wait(&mut self, timeout: Duration) -> Vec<Arrival> {
        let mut bounces = Vec::new();
        let mut sweeps = Vec::new();
        if self.bounce_wanted.is_some() {
            bounces.extend(self.bounces.wait(timeout));
        } else if self.sweeps_wanted.is_some() {
            sweeps.extend(self.sweeps.wait(timeout));
        }
        let mut arrived = self.take(bounces, sweeps);
        arrived.extend(self.collect());
        arrived
    }

    fn take(
        &mut self,
        bounces: Vec<(u64, (Params, Answer))>,
        sweeps: Vec<(u64, Arc<Sweeps>)>,
    ) -> Vec<Arrival> {
        let mut arrived = Vec::new();
        if let Some(crash) = self.bounces.crash()
            && let Some(params) = self.bounce_wanted.take()
        {
            let answer: Answer = Err(crash.to_string());
            self.bounce_cache.put(params, answer.clone());
            arrived.push(Arrival::Bounce(Box::new(params), answer));
        }
        if let Some(crash) = self.sweeps.crash()
            && let Some(key) = self.sweeps_wanted.take()
        {
            self.sweeps_crashed = Some(key);
            arrived.push(Arrival::Crash(crash));
        }
        for (generation, (params, answer)) in bounces {
            if generation == self.bounces.latest() && self.bounce_wanted == Some(params) {
                self.bounce_wanted = None;
                self.bounce_cache.put(params, answer.clone());
                arrived.push(Arrival::Bounce(Box::new(params), answer));
            }
        }
        for (generation, sweeps) in sweeps {
            if generation == self.sweeps.latest() && self.sweeps_wanted == Some(sweeps.key) {
                self.sweeps_wanted = None;
                self.sweep_cache.put(sweeps.key, Arc::clone(&sweeps));
                arrived.push(Arrival::Sweeps(sweeps));
            }
        }
        arrived
    }
}
