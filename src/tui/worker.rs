//! A background thread that runs the newest job it is given. Each job gets a generation number; giving a
//! new job makes every older one cancelled (its [`Job::cancelled`] turns true, which the core's
//! cancellation hook asks before every phase), and jobs still queued behind it are skipped, never run.
//! Results come back tagged with their generation, so the explorer keeps only the newest.
//!
//! The UI thread never waits on a worker: it takes what has arrived ([`Worker::try_iter`]) and draws. A
//! worker stuck in a long phase does not hold up quitting either: its thread is never joined, and it ends
//! with the process (or on its own once the explorer has dropped its end of the channels).
//!
//! A job that panics does not take the worker with it: the panic is caught, and its message comes back
//! as a [`Crash`] ([`Worker::crash`]), which the explorer shows in place of the answer; the next job runs
//! as usual. For tests, the environment variable `SNAPBACK_PANIC_WORKER` set to a worker's name makes
//! every job of that worker panic.

use std::any::Any;
use std::fmt;
use std::panic::{self, AssertUnwindSafe, Location};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::Duration;

/// The environment variable that makes the worker it names panic on every job (for tests).
pub const PANIC_WORKER: &str = "SNAPBACK_PANIC_WORKER";

/// A job that panicked: what the panic said, and where, if known.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Crash(pub String);

impl fmt::Display for Crash {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "internal error in the solver: {} (please report)",
            self.0
        )
    }
}

/// Where the last panic off the main thread happened, as the explorer's panic hook saw it: a job's own
/// thread, or a thread of the pool a job fans out to, whose panic the job takes up.
static PANICKED_AT: Mutex<Option<String>> = Mutex::new(None);

/// Notes where a panic off the main thread happened, for the [`Crash`] its worker reports.
pub fn remember_panic(location: Option<&Location<'_>>) {
    let at = location.map(|l| format!("{}:{}", l.file(), l.line()));
    if let Ok(mut last) = PANICKED_AT.lock() {
        *last = at;
    }
}

/// What a caught panic said: its message, and where it happened if the hook noted it.
fn crash_of(payload: &(dyn Any + Send)) -> Crash {
    let message = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic".to_string());
    match PANICKED_AT.lock().ok().and_then(|mut last| last.take()) {
        Some(at) => Crash(format!("{message} at {at}")),
        None => Crash(message),
    }
}

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
    crashes: Receiver<(u64, Crash)>,
    latest: Arc<AtomicU64>,
}

impl<J: Send + 'static, R: Send + 'static> Worker<J, R> {
    /// Starts a thread that runs `work` on the newest job given.
    pub fn spawn(name: &str, work: impl Fn(J, &Job<R>) + Send + 'static) -> Self {
        let (jobs, job_rx) = mpsc::channel::<(u64, J)>();
        let (result_tx, results) = mpsc::channel();
        let (crash_tx, crashes) = mpsc::channel();
        let panic_asked = std::env::var_os(PANIC_WORKER).is_some_and(|w| w == name);
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
                    if handle.cancelled() {
                        continue;
                    }
                    let run = panic::catch_unwind(AssertUnwindSafe(|| {
                        if panic_asked {
                            panic!("{PANIC_WORKER} asked this worker to panic");
                        }
                        work(job, &handle)
                    }));
                    if let Err(payload) = run {
                        let _ = crash_tx.send((generation, crash_of(payload.as_ref())));
                    }
                }
            });
        // A thread that cannot start leaves the jobs unanswered: the explorer then shows "solving…".
        drop(spawned);
        Worker {
            jobs,
            results,
            crashes,
            latest,
        }
    }

    /// Gives the worker a job, cancelling any older one; its generation number.
    pub fn submit(&self, job: J) -> u64 {
        let generation = self.latest.fetch_add(1, Ordering::Relaxed) + 1;
        // A worker whose thread never started answers nothing; the job then stays pending.
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

    /// The crash of the newest job, if it panicked (older jobs' crashes are dropped, as their results
    /// are).
    pub fn crash(&self) -> Option<Crash> {
        let latest = self.latest();
        self.crashes
            .try_iter()
            .filter(|(generation, _)| *generation == latest)
            .map(|(_, crash)| crash)
            .last()
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

    #[test]
    fn a_job_that_panics_is_a_crash_and_the_next_job_runs() {
        let worker = Worker::spawn("test", |n: u32, job: &Job<u32>| {
            if n == 0 {
                let divisor = n;
                panic!("dividing by {divisor}");
            }
            job.send(100 / n);
        });
        worker.submit(0);
        let crash = loop {
            if let Some(crash) = worker.crash() {
                break crash;
            }
            thread::sleep(Duration::from_millis(1));
        };
        assert!(crash.0.starts_with("dividing by 0"), "{crash:?}");
        assert_eq!(
            crash.to_string(),
            format!("internal error in the solver: {} (please report)", crash.0)
        );
        let next = worker.submit(4);
        assert_eq!(worker.wait(Duration::from_secs(30)), Some((next, 25)));
        assert_eq!(worker.crash(), None);
    }

    #[test]
    fn an_older_jobs_crash_is_dropped() {
        let started = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&started);
        let (go_tx, go) = mpsc::channel::<()>();
        let go = std::sync::Mutex::new(go);
        let worker = Worker::spawn("test", move |n: u32, job: &Job<u32>| {
            if n == 0 {
                flag.store(true, Ordering::Relaxed);
                go.lock().unwrap().recv().unwrap();
                panic!("no zero");
            }
            job.send(n);
        });
        worker.submit(0);
        while !started.load(Ordering::Relaxed) {
            thread::sleep(Duration::from_millis(1));
        }
        // The job that will panic is running; a newer one is given before it does.
        let newer = worker.submit(3);
        go_tx.send(()).unwrap();
        assert_eq!(worker.wait(Duration::from_secs(30)), Some((newer, 3)));
        assert_eq!(worker.crash(), None);
    }
}
