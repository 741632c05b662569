//! The fuzz campaign (issue 17): seeded random command lines over every headless subcommand, with
//! hostile values, hostile scenario files and hostile output paths, each run through the binary with a
//! time limit. Every case must end without a panic, with exit status 0 or 2 (or 1 for `reproduce`, as
//! its --help documents), a one-line `error:` on status 2, no NaN, inf or stray null where a number
//! belongs, and within the limits.
//!
//! `FUZZ_CASES=1500 cargo test --release --test cli fuzz -- --nocapture` runs a longer campaign (300 by
//! default) and prints its figures; `FUZZ_SEED` picks another seed.

use crate::support::bin;

use crate::support::rng;

use std::fs::{self, File};
use std::os::unix::fs::{PermissionsExt, symlink};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use rng::Rng;

const DEFAULT_CASES: usize = 300;
const DEFAULT_SEED: u64 = 0x0f22_c0de_1717;
/// CPU time (user + system, every thread) above which a case counts as a hang: CPU time, not wall
/// time, so that a loaded machine does not make a case look hung.
const HANG_CPU: Duration = Duration::from_secs(20);
/// Wall time after which a case is killed: a case blocked without using the CPU is a hang too.
const KILL_AFTER: Duration = Duration::from_secs(120);

/// What one run of the binary did.
struct Run {
    /// The exit status, `None` when killed.
    status: Option<i32>,
    stdout: String,
    stderr: String,
    cpu: Duration,
    wall: Duration,
}

/// Runs the binary with `args` in `dir`, stdin closed, output captured in files (so that a large output
/// never blocks the child on a full pipe).
fn run(args: &[String], dir: &Path, tag: usize) -> Run {
    let out_path = dir.join(format!("stdout-{tag}"));
    let err_path = dir.join(format!("stderr-{tag}"));
    let start = Instant::now();
    // Reaped by wait4 below, which also gives the child's CPU time.
    #[allow(clippy::zombie_processes)]
    let child = bin::command()
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(File::create(&out_path).unwrap())
        .stderr(File::create(&err_path).unwrap())
        .spawn()
        .unwrap();
    let pid = child.id() as libc::pid_t;
    let mut raw = 0;
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let mut killed = false;
    loop {
        // SAFETY: waits for our own child, with pointers to locals that outlive the call.
        let done = unsafe { libc::wait4(pid, &mut raw, libc::WNOHANG, &mut usage) };
        if done == pid {
            break;
        }
        if !killed && start.elapsed() > KILL_AFTER {
            // SAFETY: our own child, not yet reaped.
            unsafe { libc::kill(pid, libc::SIGKILL) };
            killed = true;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let wall = start.elapsed();
    let time = |t: libc::timeval| Duration::new(t.tv_sec as u64, t.tv_usec as u32 * 1000);
    let status = (!killed && libc::WIFEXITED(raw)).then(|| libc::WEXITSTATUS(raw));
    let read = |p: &Path| String::from_utf8_lossy(&fs::read(p).unwrap_or_default()).into_owned();
    let run = Run {
        status: if libc::WIFSIGNALED(raw) && !killed {
            Some(128 + libc::WTERMSIG(raw))
        } else {
            status
        },
        stdout: read(&out_path),
        stderr: read(&err_path),
        cpu: time(usage.ru_utime) + time(usage.ru_stime),
        wall,
    };
    let _ = fs::remove_file(out_path);
    let _ = fs::remove_file(err_path);
    run
}

/// A hostile value for a parameter flag: ordinary, extreme, special, malformed or with a unit.
fn value(rng: &mut Rng) -> String {
    const SPECIAL: &[&str] = &[
        "0",
        "-0",
        "nan",
        "NaN",
        "inf",
        "-inf",
        "1e999",
        "-1e999",
        "4.9e-324",
        "1e-400",
        "",
        " ",
        "abc",
        "1e",
        "--",
        "0x10",
        "1_000",
        "١",
        "+5",
        "1e308",
        "-1e308",
        "2.2250738585072014e-308",
        "1.7976931348623157e308",
        "16",
        "17",
        "2.5",
        "1",
        "90",
        "90.0000001",
    ];
    const UNITS: &[&str] = &[
        "g", "kg", "mg", "kN/m", "N/m", "ms", "s", "deg", "rad", "rpm", "rad/s", "m/s", "mm", "N",
        "furlong", " kg", "km/h",
    ];
    match rng.below(10) {
        0 | 1 => {
            let x = 10f64.powf(rng.uniform(-330.0, 310.0));
            let sign = if rng.unit() < 0.3 { "-" } else { "" };
            format!("{sign}{x:e}")
        }
        2 => SPECIAL[rng.below(SPECIAL.len())].to_string(),
        3 => format!(
            "{}{}",
            rng.log_uniform(1e-3, 1e4) as f32,
            UNITS[rng.below(UNITS.len())]
        ),
        4 if rng.unit() < 0.05 => "1".repeat(100_000),
        _ => format!("{}", rng.log_uniform(1e-3, 1e4) as f32),
    }
}

/// A value that must be solved or refused cleanly: half the time near the paper's (within a factor of
/// ten of the default), else anywhere up to and past the edges of what can be solved.
fn plausible(rng: &mut Rng, flag: &str) -> String {
    let Some(spec) = snapback::model::params::spec_named(flag) else {
        return value(rng);
    };
    if flag == "chain" {
        return (1 + rng.below(16)).to_string();
    }
    if rng.unit() < 0.5 {
        let near = spec.default * rng.log_uniform(0.1, 10.0);
        let value = if spec.range.contains(near) {
            near
        } else {
            spec.range.clamp(near)
        };
        return format!("{value:e}");
    }
    let (lo, hi): (f64, f64) = match flag {
        "angle" => (0.1, 90.0),
        "speed" | "mass" | "radius" | "duration" | "cart-mass" => (1e-16, 1e16),
        "spin" => (1.0, 1e16),
        "mu" => (1e-6, 1e7),
        "ey" => (0.0, 1.0),
        "alpha" => (1e-7, 1e7),
        "stiffness" | "ball-stiffness" => (1e-3, 1e14),
        "cart-friction" => (1e-3, 1e4),
        _ => (1e-16, 10.0),
    };
    let x = if hi / lo > 1e3 {
        rng.log_uniform(lo, hi)
    } else {
        rng.uniform(lo, hi)
    };
    if flag == "spin" && rng.unit() < 0.5 {
        format!("{:e}", -x)
    } else {
        format!("{x:e}")
    }
}

const FLAGS: &[&str] = &[
    "angle",
    "speed",
    "spin",
    "mu",
    "duration",
    "ey",
    "mass",
    "radius",
    "alpha",
    "cart-mass",
    "stiffness",
    "cart-friction",
    "chain",
    "ball-stiffness",
    "ball-damping",
];

/// Parameter flags: up to four, hostile or plausible.
fn params(rng: &mut Rng, args: &mut Vec<String>) {
    for _ in 0..rng.below(5) {
        let flag = FLAGS[rng.below(FLAGS.len())];
        let text = if rng.unit() < 0.25 {
            value(rng)
        } else {
            plausible(rng, flag)
        };
        args.push(format!("--{flag}"));
        args.push(text);
    }
}

/// A hostile scenario file in `dir`.
fn scenario(rng: &mut Rng, dir: &Path, tag: usize) -> PathBuf {
    let path = dir.join(format!("s{tag}.toml"));
    let key = FLAGS[rng.below(FLAGS.len())].replace('-', "_");
    let text = match rng.below(9) {
        0 => format!(
            "[params]\n{key} = {}\n",
            plausible(rng, &key.replace('_', "-"))
        ),
        1 => format!("[params]\n{key} = \"{}\"\n", value(rng)),
        2 => format!("[params]\n{key} = 1\n{key} = 2\n"),
        3 => format!("[params]\n{key} = 5\n"),
        4 => format!("[params]\n{key} = [1, 2]\nunknown = 3\n"),
        5 => format!("[params]\n{key} = \"{}\"\n", "9".repeat(100_000)),
        6 => (0..rng.below(2000))
            .map(|_| (rng.below(256) as u8) as char)
            .collect(),
        7 => "[[[[params".repeat(rng.below(1000)),
        _ => format!(
            "description = \"{}\"\n[params]\n{key} = {}e{}\n",
            "x".repeat(rng.below(500)),
            rng.uniform(-9.0, 9.0),
            rng.below(700) as i64 - 350
        ),
    };
    fs::write(&path, text).unwrap();
    path
}

/// `--out` for `figure`: a new file, `-`, a device, a symlink, a read-only file, a missing directory.
fn out_path(rng: &mut Rng, dir: &Path, tag: usize) -> String {
    let file = dir.join(format!("f{tag}.svg"));
    match rng.below(7) {
        0 => "-".into(),
        1 => "/dev/null".into(),
        2 => {
            let link = dir.join(format!("l{tag}.svg"));
            symlink(&file, &link).unwrap();
            link.display().to_string()
        }
        3 => {
            fs::write(&file, "keep").unwrap();
            fs::set_permissions(&file, fs::Permissions::from_mode(0o444)).unwrap();
            file.display().to_string()
        }
        4 => dir.join("missing/x.svg").display().to_string(),
        _ => file.display().to_string(),
    }
}

fn pick<'a>(rng: &mut Rng, options: &[&'a str]) -> &'a str {
    options[rng.below(options.len())]
}

/// One random command line.
fn case(rng: &mut Rng, dir: &Path, tag: usize) -> Vec<String> {
    let command = pick(
        rng,
        &[
            "simulate",
            "simulate",
            "simulate",
            "sweep",
            "sweep",
            "critical-angle",
            "optimize",
            "reproduce",
            "figure",
            "presets",
        ],
    );
    let mut args = vec![command.to_string()];
    let formats: &[&str] = match command {
        "simulate" => &["table", "json", "csv"],
        "sweep" => &["csv", "json"],
        "figure" => &[],
        _ => &["table", "json"],
    };
    if !formats.is_empty() && rng.unit() < 0.7 {
        args.push("--format".into());
        args.push(pick(rng, formats).into());
    }
    if command == "presets" {
        return args;
    }
    match rng.below(8) {
        0 => {
            args.push("--preset".into());
            args.push(pick(rng, &["light-1g", "paper-fig3c", "nope", ""]).into());
        }
        1 => {
            args.push("--scenario".into());
            args.push(scenario(rng, dir, tag).display().to_string());
        }
        _ => {}
    }
    params(rng, &mut args);
    let vary = |rng: &mut Rng, args: &mut Vec<String>| {
        let flag = if rng.unit() < 0.9 {
            FLAGS[rng.below(FLAGS.len())]
        } else {
            "bogus"
        };
        args.push("--vary".into());
        args.push(flag.into());
        for end in ["--from", "--to"] {
            args.push(end.into());
            args.push(if rng.unit() < 0.6 {
                plausible(rng, flag)
            } else {
                value(rng)
            });
        }
        if rng.unit() < 0.3 {
            args.push("--log".into());
        }
    };
    match command {
        "simulate" if rng.unit() < 0.3 => {
            args.push("--samples".into());
            args.push(pick(rng, &["2", "1", "0", "50000", "-3", "x"]).into());
        }
        "sweep" => {
            vary(rng, &mut args);
            args.push("--steps".into());
            args.push(pick(rng, &["2", "3", "10", "40", "1", "0", "1e3", "-1"]).into());
        }
        "optimize" => {
            vary(rng, &mut args);
            if rng.unit() < 0.5 {
                args.push("--objective".into());
                args.push(pick(rng, &["omega2", "ex", "vx2", "theta2", "x"]).into());
            }
            if rng.unit() < 0.3 {
                args.push("--minimize".into());
            }
            if rng.unit() < 0.3 {
                args.push("--scan".into());
                args.push(pick(rng, &["3", "10", "2", "100"]).into());
            }
        }
        "figure" => {
            args.push(pick(rng, &["fig2", "fig3", "fig3", "fig9"]).into());
            args.push("--out".into());
            args.push(out_path(rng, dir, tag));
            if rng.unit() < 0.3 {
                args.push("--force".into());
            }
        }
        _ => {}
    }
    args
}

/// The words of `text` that are a non-finite number.
fn non_finite(text: &str) -> Option<String> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-' || c == '+'))
        .map(|w| w.trim_start_matches(['-', '+']))
        .find(|w| {
            w.eq_ignore_ascii_case("nan")
                || w.eq_ignore_ascii_case("inf")
                || w.eq_ignore_ascii_case("infinity")
        })
        .map(str::to_string)
}

/// Keys whose null means "there is none": as the --help of their command says, or (`stretch`,
/// `patch_slip`) a compliant ball's figures for a rigid one.
const NULLABLE: &[&str] = &[
    "ex",
    "roll_ratio",
    "eq7_deg",
    "full_model_deg",
    "computed",
    "difference",
    "first_grip_deg",
    "stretch",
    "patch_slip",
];

/// A null in `json` under a key that is not [`NULLABLE`].
fn stray_null(json: &serde_json::Value, key: &str) -> Option<String> {
    match json {
        serde_json::Value::Null if !NULLABLE.contains(&key) => Some(key.to_string()),
        serde_json::Value::Array(items) => items.iter().find_map(|v| stray_null(v, key)),
        serde_json::Value::Object(map) => map.iter().find_map(|(k, v)| stray_null(v, k)),
        _ => None,
    }
}

/// What is wrong with a run, if anything.
fn verdict(args: &[String], run: &Run) -> Result<(), String> {
    if run.stderr.contains("panicked") || run.status == Some(101) {
        return Err("panic".into());
    }
    if run.status.is_none() || run.cpu > HANG_CPU {
        return Err("hang".into());
    }
    let status = run.status.unwrap_or(-1);
    let allowed = status == 0 || status == 2 || (status == 1 && args[0] == "reproduce");
    if !allowed {
        return Err(format!("bad exit {status}"));
    }
    if status == 2 {
        let lines: Vec<&str> = run.stderr.lines().collect();
        if lines.len() != 1 || !lines[0].starts_with("error: ") {
            return Err("bad exit: not one `error:` line".into());
        }
    }
    if let Some(word) = non_finite(&run.stdout) {
        return Err(format!("non-finite: {word}"));
    }
    if args.iter().any(|a| a == "json") && status != 2 {
        let json: serde_json::Value = serde_json::from_str(&run.stdout)
            .map_err(|e| format!("bad exit: JSON does not parse: {e}"))?;
        if let Some(key) = stray_null(&json, "") {
            return Err(format!("non-finite: null {key}"));
        }
    }
    Ok(())
}

/// The campaign's figures.
#[derive(Default)]
struct Figures {
    cases: usize,
    by_status: [usize; 4],
    panics: usize,
    hangs: usize,
    bad_exits: usize,
    non_finite: usize,
    slowest: Duration,
    failures: Vec<String>,
}

#[test]
#[ignore = "slow"]
fn the_seeded_campaign_finds_no_panic_hang_bad_exit_or_non_finite_number() {
    let cases: usize = std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_CASES);
    let seed: u64 = std::env::var("FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_SEED);
    let dir = std::env::temp_dir().join(format!("snapback-fuzz-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    let mut rng = Rng(seed);
    let lines: Vec<Vec<String>> = (0..cases).map(|i| case(&mut rng, &dir, i)).collect();
    let next = AtomicUsize::new(0);
    let figures = Arc::new(Mutex::new(Figures::default()));
    let started = Instant::now();
    std::thread::scope(|scope| {
        for _ in 0..2 {
            scope.spawn(|| {
                loop {
                    let tag = next.fetch_add(1, Ordering::Relaxed);
                    let Some(args) = lines.get(tag) else { break };
                    let run = run(args, &dir, tag);
                    let verdict = verdict(args, &run);
                    let mut f = figures.lock().unwrap();
                    f.cases += 1;
                    f.by_status[match run.status {
                        Some(0) => 0,
                        Some(1) => 1,
                        Some(2) => 2,
                        _ => 3,
                    }] += 1;
                    f.slowest = f.slowest.max(run.wall);
                    if let Err(what) = verdict {
                        let kind = what.split(':').next().unwrap_or("");
                        match kind {
                            "panic" => f.panics += 1,
                            "hang" => f.hangs += 1,
                            "non-finite" => f.non_finite += 1,
                            _ => f.bad_exits += 1,
                        }
                        let shown: Vec<String> =
                            args.iter().map(|a| a.chars().take(60).collect()).collect();
                        f.failures.push(format!(
                            "{what} ({:.1} s cpu): snapback {}\n    stderr: {}",
                            run.cpu.as_secs_f64(),
                            shown.join(" "),
                            run.stderr.chars().take(300).collect::<String>()
                        ));
                    }
                }
            });
        }
    });
    let _ = fs::remove_dir_all(&dir);
    let f = figures.lock().unwrap();
    eprintln!(
        "fuzz: {} cases (seed {seed:#x}) in {:.1} s: exit 0: {}, 1: {}, 2: {}, other: {}; {} panics, \
         {} hangs over {} s, {} bad exits, {} non-finite; slowest case {:.1} s",
        f.cases,
        started.elapsed().as_secs_f64(),
        f.by_status[0],
        f.by_status[1],
        f.by_status[2],
        f.by_status[3],
        f.panics,
        f.hangs,
        HANG_CPU.as_secs(),
        f.bad_exits,
        f.non_finite,
        f.slowest.as_secs_f64()
    );
    assert!(f.failures.is_empty(), "{}", f.failures.join("\n"));
}
