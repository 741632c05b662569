//! A background thread that runs the newest job it is given. Each job gets a generation number; giving a
//! new job makes every older one cancelled (its [`Job::cancelled`] turns true, which the core's
//! cancellation hook asks before every phase), and jobs still queued behind it are skipped, never run.
//! Results come back tagged with their generation, so the explorer keeps only the newest.
//!
//! The UI thread never waits on a worker: it takes what has arrived ([`Worker::try_iter`]) and draws. A
//! worker stuck in a long phase does not hold up quitting either: its thread is never joined, and it ends
//! with the process (or on its own once the explorer has dropped its end of the channels).

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::thread;
use std::time::Duration;

/// One job as the worker's function sees it: whether it is still wanted, and where its results go.
pub struct Job<'a, R> {
    generation: u64,
    latest: &'a AtomicU64,
    results: &'a Sender<(u64, R)>,
}

impl<R> Job<'_, R> {
    /// True once a newer job has been given: stop and send nothing more.
    pub fn cancelled(&self) -> bool {
        self.latest.load(Ordering::Relaxed) != self.generation
    }

    /// Sends one result (a job may send several, e.g. the heatmap's rows); false once the explorer is gone.
    pub fn send(&self, result: R) -> bool {
        self.results.send((self.generation, result)).is_ok()
    }
}

/// The explorer's ends of a worker thread.
#[derive(Debug)]
pub struct Worker<J, R> {
    jobs: Sender<(u64, J)>,
    results: Receiver<(u64, R)>,
    latest: Arc<AtomicU64>,
}

impl<J: Send + 'static, R: Send + 'static> Worker<J, R> {
    /// Starts a thread that runs `work` on the newest job given.
    pub fn spawn(name: &str, work: impl Fn(J, &Job<R>) + Send + 'static) -> Self {
        let (jobs, job_rx) = mpsc::channel::<(u64, J)>();
        let (result_tx, results) = mpsc::channel();
        let latest = Arc::new(AtomicU64::new(0));
        let seen = Arc::clone(&latest);
        let spawned = thread::Builder::new()
            .name(name.to_string())
            .spawn(move || {
                // Ends when the explorer drops its end of the jobs.
                while let Ok(mut next) = job_rx.recv() {
                    // Only the newest of the jobs queued meanwhile is run.
                    while let Ok(newer) = job_rx.try_recv() {
                        next = newer;
                    }
                    let (generation, job) = next;
                    let handle = Job {
                        generation,
                        latest: &seen,
                        results: &result_tx,
                    };
                    if !handle.cancelled() {
                        work(job, &handle);
                    }
                }
            });
        // A thread that cannot start leaves the jobs unanswered: the explorer then shows "solving…".
        drop(spawned);
        Worker {
            jobs,
            results,
            latest,
        }
    }

    /// Gives the worker a job, cancelling any older one; its generation number.
    pub fn submit(&self, job: J) -> u64 {
        let generation = self.latest.fetch_add(1, Ordering::Relaxed) + 1;
        // A worker that is gone (a panic in the core) answers nothing; the job then stays pending.
        let _ = self.jobs.send((generation, job));
        generation
    }

    /// Cancels the current job without giving a new one.
    pub fn cancel(&self) {
        self.latest.fetch_add(1, Ordering::Relaxed);
    }

    /// The generation of the newest job given.
    pub fn latest(&self) -> u64 {
        self.latest.load(Ordering::Relaxed)
    }

    /// The results that have arrived, without waiting.
    pub fn try_iter(&self) -> impl Iterator<Item = (u64, R)> + '_ {
        self.results.try_iter()
    }

    /// Waits up to `timeout` for one result (for tests and benchmarks, which settle before each step).
    pub fn wait(&self, timeout: Duration) -> Option<(u64, R)> {
        self.results.recv_timeout(timeout).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;

    #[test]
    fn a_newer_job_cancels_the_running_one_and_only_its_result_counts() {
        let started = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&started);
        let worker = Worker::spawn("test", move |n: u32, job: &Job<u32>| {
            if n == 1 {
                flag.store(true, Ordering::Relaxed);
                // A slow job that stops when cancelled.
                while !job.cancelled() {
                    thread::sleep(Duration::from_millis(1));
                }
                return;
            }
            job.send(n * 10);
        });
        let first = worker.submit(1);
        while !started.load(Ordering::Relaxed) {
            thread::sleep(Duration::from_millis(1));
        }
        let second = worker.submit(2);
        assert!(second > first);
        let (generation, result) = worker.wait(Duration::from_secs(30)).unwrap();
        assert_eq!((generation, result), (second, 20));
        assert_eq!(worker.latest(), second);
    }
}
