//! CPU time, which a loaded machine does not stretch as it stretches the wall clock: a bound on time in
//! a test is a bound on CPU time.

use std::time::Duration;

/// The CPU time the calling thread has used so far.
#[allow(dead_code)] // the tests of the binary watch its process instead
pub fn thread() -> Duration {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime only writes the timespec it is given.
    let status = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    assert_eq!(status, 0, "the thread's CPU clock");
    Duration::new(t.tv_sec as u64, t.tv_nsec as u32)
}

/// The CPU time process `pid` has used (its main thread alone, or all its threads), and whether it has
/// ended (a zombie not yet reaped); `None` once it is gone.
#[allow(dead_code)] // only the pseudo-terminal's tests watch a process
pub fn process(pid: u32, main_thread: bool) -> Option<(Duration, bool)> {
    let path = if main_thread {
        format!("/proc/{pid}/task/{pid}/stat")
    } else {
        format!("/proc/{pid}/stat")
    };
    let text = std::fs::read_to_string(path).ok()?;
    // After the parenthesised name: the state (field 3), ..., utime (14) and stime (15) in clock ticks.
    let fields: Vec<&str> = text
        .get(text.rfind(')')? + 1..)?
        .split_whitespace()
        .collect();
    let ticks = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    // SAFETY: sysconf has no preconditions.
    let per_second = unsafe { libc::sysconf(libc::_SC_CLK_TCK) } as u64;
    Some((
        Duration::from_nanos(ticks * 1_000_000_000 / per_second),
        fields[0] == "Z",
    ))
}
