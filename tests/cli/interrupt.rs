//! Ctrl-C stops every long-running command promptly, with `error: interrupted` and status 130: the
//! signal reaches each command's solves through their options, so a command stops at the next phase
//! instead of finishing its work first. Promptness is measured in the CPU time the command spends
//! after the signal (a loaded machine does not stretch it as it stretches the wall clock), against
//! the seconds the rest of the work would take. The cases chatter through many short phases: the
//! solver asks for cancellation between phases, so one long phase still runs to its end.

use std::fs::{self, File};
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

use crate::support::{bin, cpu};

/// CPU time the command has spent before it is interrupted: well into its work.
const BUSY: Duration = Duration::from_millis(300);
/// The most CPU time a command may spend after Ctrl-C; each case below would spend 2 s or more.
const PROMPT: Duration = Duration::from_millis(500);
/// Far beyond any case's time: reaching it means a hang.
const LIMIT: Duration = Duration::from_secs(300);

/// Runs `args` (configured from `config`), interrupts it with SIGINT once it has spent [`BUSY`], and
/// returns its exit status, its stderr and the CPU time it spent after the signal.
fn interrupt(args: &[&str], config: Option<&Path>) -> (i32, String, Duration) {
    let err_path = std::env::temp_dir().join(format!(
        "snapback-interrupt-{}-{}",
        std::process::id(),
        args[0]
    ));
    let mut command = bin::command();
    if let Some(dir) = config {
        command.env("SNAPBACK_CONFIG_DIR", dir);
    }
    // Reaped by wait4 below, which also gives the child's CPU time.
    #[allow(clippy::zombie_processes)]
    let child = command
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(File::create(&err_path).unwrap())
        .spawn()
        .unwrap();
    let pid = child.id();
    let start = Instant::now();
    let at_signal = loop {
        let (used, ended) = cpu::process(pid, false).expect("the command is running");
        assert!(!ended, "ended before it was interrupted: {args:?}");
        if used >= BUSY {
            break used;
        }
        assert!(start.elapsed() < LIMIT, "never got busy: {args:?}");
        std::thread::sleep(Duration::from_millis(5));
    };
    // SAFETY: signals our own child, not yet reaped.
    unsafe { libc::kill(pid as libc::pid_t, libc::SIGINT) };
    let mut raw = 0;
    // SAFETY: an all-zero rusage is a valid value for wait4 to overwrite.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    loop {
        // SAFETY: waits for our own child, with pointers to locals that outlive the call.
        let done = unsafe { libc::wait4(pid as libc::pid_t, &mut raw, libc::WNOHANG, &mut usage) };
        if done == pid as libc::pid_t {
            break;
        }
        if start.elapsed() > LIMIT {
            // SAFETY: our own child, not yet reaped.
            unsafe { libc::kill(pid as libc::pid_t, libc::SIGKILL) };
            panic!("hung after Ctrl-C: {args:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let time = |t: libc::timeval| Duration::new(t.tv_sec as u64, t.tv_usec as u32 * 1000);
    let total = time(usage.ru_utime) + time(usage.ru_stime);
    let stderr = fs::read_to_string(&err_path).unwrap();
    let _ = fs::remove_file(err_path);
    let status = if libc::WIFEXITED(raw) {
        libc::WEXITSTATUS(raw)
    } else {
        -1
    };
    (status, stderr, total.saturating_sub(at_signal))
}

/// `args` stops promptly on Ctrl-C, saying so, with status 130.
fn stops_promptly(args: &[&str], config: Option<&Path>) {
    let (status, stderr, after) = interrupt(args, config);
    assert_eq!(status, 130, "{args:?}: {stderr}");
    assert_eq!(stderr, "error: interrupted\n", "{args:?}");
    assert!(after < PROMPT, "{args:?} ran on for {after:?} of CPU");
}

#[test]
fn a_fit_stops_promptly_on_ctrl_c() {
    // Uninterrupted: about 38 s of CPU.
    stops_promptly(
        &[
            "fit",
            "--data",
            "assets/data/synthetic-strings.csv",
            "--free",
            "cart-mass,stiffness,mu",
            "--starts",
            "4096",
        ],
        None,
    );
}

#[test]
fn a_shot_stops_promptly_on_ctrl_c() {
    // A stiff ball on clamped strings, swung steeply upwards: it chatters through 10 000 phases and is
    // refused, after about 2 s of CPU.
    stops_promptly(
        &[
            "shot",
            "--racquet-mass",
            "clamped",
            "--ball-stiffness",
            "1e12",
            "--swing-path",
            "70",
        ],
        None,
    );
}

#[test]
fn a_sweep_and_an_optimisation_of_shots_stop_promptly_on_ctrl_c() {
    // Eight shots of about 1 s of CPU each (a stiff ball chattering on clamped strings), differing
    // only in the height they are struck from.
    let shots = [
        "--vary",
        "height",
        "--from",
        "0.9",
        "--to",
        "1.1",
        "--racquet-mass",
        "clamped",
        "--ball-stiffness",
        "1e11",
        "--swing-path",
        "70",
    ];
    let mut sweep = vec!["sweep", "--shot", "--steps", "8"];
    sweep.extend(shots);
    stops_promptly(&sweep, None);
    let mut optimize = vec!["optimize", "--objective", "launch_speed", "--scan", "8"];
    optimize.extend(shots);
    stops_promptly(&optimize, None);
}

#[test]
fn presets_stop_promptly_on_ctrl_c() {
    // Three user presets of a stiff ball chattering on the paper's Fig. 3(c) cart: each is refused
    // after 10 000 phases, about 2 s of CPU.
    let dir =
        std::env::temp_dir().join(format!("snapback-interrupt-presets-{}", std::process::id()));
    fs::create_dir_all(dir.join("presets")).unwrap();
    for name in ["chatter-1", "chatter-2", "chatter-3"] {
        fs::write(
            dir.join(format!("presets/{name}.toml")),
            "description = \"chatters\"\nsource = \"a test\"\n\n[params]\nball-stiffness = \"1e12\"\n",
        )
        .unwrap();
    }
    stops_promptly(&["presets"], Some(&dir));
}
