//! The heatmap view's data: the rebound spin omega2 over a grid of cart masses and spring stiffnesses
//! (log-spaced, [`MASSES`] x [`STIFFNESSES`] cells of [`super::grid`]), every other parameter as it is now.
//!
//! The grid is solved on a worker thread ([`super::worker`]), a row of stiffness at a time, so the
//! explorer keeps answering keys while it fills in. A request supersedes any older one still running (its
//! solves are cancelled), and rows that arrive from an older request are dropped, so a map never mixes two
//! sets of parameters. A job that panics stops the map where it got to ([`Heatmap::failed`]).

use std::time::Duration;

use rayon::prelude::*;

use super::grid::{MASSES, STIFFNESSES, mass, stiffness};
use super::peak::{self, Peak};
use super::worker::{Crash, Worker};
use crate::model::{ParamId, Params, SolveError, solve_cancellable};

/// omega2 along row `j` (stiffness `stiffness(j)`), for every cart mass, `None` where the core refuses;
/// `None` for the whole row once `cancelled` says so.
pub fn compute_row(
    params: &Params,
    j: usize,
    cancelled: &(impl Fn() -> bool + Sync),
) -> Option<Vec<Option<f64>>> {
    (0..MASSES)
        .into_par_iter()
        .map(|i| {
            let mut p = *params;
            p.set(ParamId::CartMass, mass(i));
            p.set(ParamId::Stiffness, stiffness(j));
            match solve_cancellable(&p, cancelled) {
                Ok(b) => Ok(Some(b.outcome.omega2)),
                Err(SolveError::Cancelled) => Err(()),
                Err(_) => Ok(None),
            }
        })
        .collect::<Result<_, ()>>()
        .ok()
}

/// The map depends on every parameter but the two on its axes.
fn key(params: &Params) -> Params {
    Params {
        cart_mass: 0.0,
        stiffness: 0.0,
        ..*params
    }
}

/// One solved row, as the worker sends it.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub generation: u64,
    pub index: usize,
    pub omega2: Vec<Option<f64>>,
}

/// The worker: a job is the parameters of a map, its results the rows as they are solved.
type RowWorker = Worker<Params, (usize, Vec<Option<f64>>)>;

fn spawn() -> RowWorker {
    Worker::spawn("heatmap", |params: Params, job| {
        for j in 0..STIFFNESSES {
            let Some(row) = compute_row(&params, j, &|| job.cancelled()) else {
                return;
            };
            if !job.send((j, row)) {
                return;
            }
        }
    })
}

/// The map as far as it has been computed.
#[derive(Debug, Default)]
pub struct Heatmap {
    /// The generation of the newest request; rows of any other are dropped.
    pub generation: u64,
    /// The parameters (axes aside) of the newest request, if any.
    requested: Option<Params>,
    /// Row by row (index 0 the softest spring), once computed.
    pub rows: Vec<Option<Vec<Option<f64>>>>,
    /// Started on the first request.
    worker: Option<RowWorker>,
    /// The best point, refined from the best cell once the map is complete ([`peak`]).
    pub peak: Option<Peak>,
    /// The refinement asked for (its generation), until it answers.
    refining: Option<u64>,
    /// Started when the first map is complete.
    refiner: Option<PeakWorker>,
    /// Why the map of the newest request stopped short: its job, or its peak's, panicked.
    pub failed: Option<Crash>,
    /// That crash, until the explorer has taken it for the status line.
    unreported: Option<Crash>,
}

/// The worker that refines the best cell: a job is the parameters and the cell.
type PeakWorker = Worker<(Params, usize, usize), Option<Peak>>;

fn spawn_refiner() -> PeakWorker {
    Worker::spawn("peak", |(params, i, j): (Params, usize, usize), job| {
        job.send(peak::refine(&params, i, j, &|| job.cancelled()));
    })
}

impl Heatmap {
    /// Asks for the map of `params`, unless it is already computed or on its way. True if a new
    /// computation started.
    pub fn request(&mut self, params: &Params) -> bool {
        let key = key(params);
        if self.requested == Some(key) {
            return false;
        }
        self.requested = Some(key);
        self.rows = vec![None; STIFFNESSES];
        self.peak = None;
        self.refining = None;
        self.failed = None;
        self.unreported = None;
        if let Some(refiner) = &self.refiner {
            refiner.cancel();
        }
        self.generation = self.worker.get_or_insert_with(spawn).submit(key);
        true
    }

    /// Takes a row if it belongs to the newest request; false (and dropped) if it is stale.
    pub fn accept(&mut self, row: Row) -> bool {
        if row.generation != self.generation || row.index >= self.rows.len() {
            return false;
        }
        self.rows[row.index] = Some(row.omega2);
        true
    }

    /// Takes every row that has arrived; true if any was for the newest request.
    pub fn poll(&mut self) -> bool {
        // The crash first: the rows its job sent before it are then all in.
        let (crash, arrived): (_, Vec<Row>) = match &self.worker {
            Some(worker) => (worker.crash(), worker.try_iter().map(row).collect()),
            None => return false,
        };
        let mut changed = crash.is_some();
        if let Some(crash) = crash {
            self.fail(crash);
        }
        for row in arrived {
            changed |= self.accept(row);
        }
        self.refine() || changed
    }

    /// Asks for the peak once the map is complete, and takes it when it comes; true if it came.
    fn refine(&mut self) -> bool {
        let (Some(params), Some((i, j, _))) = (self.requested, self.best()) else {
            return false;
        };
        if self.failed.is_some() || self.rows.iter().any(Option::is_none) {
            return false;
        }
        let refiner = self.refiner.get_or_insert_with(spawn_refiner);
        match self.refining {
            None if self.peak.is_none() => {
                self.refining = Some(refiner.submit((params, i, j)));
                false
            }
            Some(generation) => {
                if let Some(crash) = refiner.crash() {
                    self.refining = None;
                    self.fail(crash);
                    return true;
                }
                let answer = refiner.try_iter().filter(|(g, _)| *g == generation).last();
                match answer {
                    Some((_, peak)) => {
                        self.refining = None;
                        // A cell the core refuses has no peak: the cell stands.
                        self.peak = Some(peak.unwrap_or(Peak {
                            mass: mass(i),
                            stiffness: stiffness(j),
                            omega2: self.at(i, j).unwrap_or(f64::NAN),
                        }));
                        true
                    }
                    None => false,
                }
            }
            None => false,
        }
    }

    /// Waits up to `timeout` for a row, and takes it and any others that have arrived; true if the map
    /// changed.
    pub fn wait(&mut self, timeout: Duration) -> bool {
        let first = match &self.worker {
            Some(worker) => worker.wait(timeout).map(row),
            None => return false,
        };
        let changed = first.is_some_and(|r| self.accept(r));
        self.poll() || changed
    }

    /// The newest request's job panicked: the map stays as far as it got.
    fn fail(&mut self, crash: Crash) {
        self.failed = Some(crash.clone());
        self.unreported = Some(crash);
    }

    /// A crash not yet shown in the status line.
    pub fn take_crash(&mut self) -> Option<Crash> {
        self.unreported.take()
    }

    /// True while a requested map, or its peak, is not complete (and nothing has failed).
    pub fn pending(&self) -> bool {
        self.requested.is_some()
            && self.failed.is_none()
            && (self.rows.iter().any(Option::is_none) || self.peak.is_none())
    }

    /// How many rows are in.
    pub fn done(&self) -> usize {
        self.rows.iter().filter(|r| r.is_some()).count()
    }

    /// omega2 at column `i`, row `j`, if computed and solved.
    pub fn at(&self, i: usize, j: usize) -> Option<f64> {
        self.rows.get(j)?.as_ref()?.get(i).copied().flatten()
    }

    /// The cell with the largest omega2 so far: (column, row, omega2).
    pub fn best(&self) -> Option<(usize, usize, f64)> {
        (0..STIFFNESSES)
            .flat_map(|j| (0..MASSES).map(move |i| (i, j)))
            .filter_map(|(i, j)| self.at(i, j).map(|w| (i, j, w)))
            .filter(|c| c.2.is_finite())
            .max_by(|a, b| a.2.total_cmp(&b.2))
    }

    /// The smallest and largest omega2 so far.
    pub fn range(&self) -> Option<(f64, f64)> {
        self.rows
            .iter()
            .flatten()
            .flatten()
            .flatten()
            .filter(|w| w.is_finite())
            .fold(None, |acc: Option<(f64, f64)>, &w| {
                Some(acc.map_or((w, w), |(lo, hi)| (lo.min(w), hi.max(w))))
            })
    }
}

/// A row as the worker sent it.
fn row((generation, (index, omega2)): (u64, (usize, Vec<Option<f64>>))) -> Row {
    Row {
        generation,
        index,
        omega2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, Instant};

    #[test]
    fn stale_rows_are_dropped() {
        let mut map = Heatmap {
            generation: 3,
            rows: vec![None; STIFFNESSES],
            ..Heatmap::default()
        };
        let row = |generation| Row {
            generation,
            index: 2,
            omega2: vec![Some(1.0); MASSES],
        };
        assert!(!map.accept(row(2)));
        assert_eq!(map.done(), 0);
        assert!(map.accept(row(3)));
        assert_eq!(map.done(), 1);
        assert_eq!(map.at(5, 2), Some(1.0));
    }

    #[test]
    fn the_worker_fills_the_map_for_the_newest_request() {
        let mut map = Heatmap::default();
        let first = Params::default();
        let second = Params { spin: 0.0, ..first };
        assert!(map.request(&first));
        assert!(!map.request(&first));
        // The same map whatever the cart and spring.
        assert!(!map.request(&Params {
            cart_mass: 1.0,
            ..first
        }));
        assert!(map.request(&second));
        assert_eq!(map.generation, 2);
        let start = Instant::now();
        while map.pending() {
            map.poll();
            assert!(start.elapsed() < Duration::from_secs(60), "timed out");
            std::thread::sleep(Duration::from_millis(5));
        }
        for j in [0, 13, STIFFNESSES - 1] {
            assert_eq!(
                map.rows[j].as_ref().unwrap(),
                &compute_row(&second, j, &|| false).unwrap()
            );
        }
        let (i, j, best) = map.best().unwrap();
        assert_eq!(map.at(i, j), Some(best));
        let (low, high) = map.range().unwrap();
        assert!(low <= best && best == high);
    }
}
