//! Every case of issue 17 as a regression test: inputs that hung, took tens of seconds, printed NaN or
//! inf, destroyed what was at an output path, or echoed a huge value. Each runs the binary with a
//! generous time limit (a hang shows as a kill, never as a timing assertion).

use crate::support::bin;

use std::fs;
use std::io::Read;
use std::os::unix::fs::{FileTypeExt, PermissionsExt, symlink};
use std::path::{Path, PathBuf};
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

use snapback::model::Params;
use snapback::scenario::Scenario;

/// Far beyond any of these cases' time: reaching it means a hang.
const LIMIT: Duration = Duration::from_secs(120);

fn spawn(args: &[&str], dir: &Path) -> Child {
    bin::command()
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Waits for `child` (killed at [`LIMIT`]): its exit status, stdout and stderr.
fn finish(mut child: Child) -> (i32, String, String) {
    let mut out = child.stdout.take().unwrap();
    let mut err = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut text = Vec::new();
        let _ = out.read_to_end(&mut text);
        text
    });
    let mut stderr = String::new();
    let _ = err.read_to_string(&mut stderr);
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > LIMIT {
            let _ = child.kill();
            panic!("hung: killed after {LIMIT:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let stdout = String::from_utf8_lossy(&reader.join().unwrap()).into_owned();
    (status.code().unwrap_or(-1), stdout, stderr)
}

fn run_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    finish(spawn(args, dir))
}

fn run(args: &[&str]) -> (i32, String, String) {
    run_in(&std::env::temp_dir(), args)
}

/// Asserts a refusal: status 2 and one `error:` line holding every fragment.
fn refused(args: &[&str], fragments: &[&str]) {
    let (code, _, stderr) = run(args);
    assert_eq!(code, 2, "{args:?}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
    for f in fragments {
        assert!(stderr.contains(f), "{args:?}: {f} not in {stderr}");
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("snapback-hostile-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_inputs_that_hung_are_refused_naming_the_solvable_range() {
    for (args, flag) in [
        (
            &["--ball-stiffness", "100kN/m", "--ball-damping", "1e-20"][..],
            "--ball-damping must be in {0} or [",
        ),
        (
            &["--speed", "1e160"],
            "--speed must be in [1e-15, 1e15] m/s",
        ),
        (&["--mu", "1e300"], "--mu must be in [0, 1000000]"),
        (&["--mass", "1e300"], "--mass must be in [1e-15, 1e15] kg"),
        (&["--mass", "4.9e-324"], "--mass must be in"),
        (&["--duration", "1e-120"], "--duration must be in"),
        (&["--radius", "1e-180"], "--radius must be in"),
        (&["--alpha", "1e-308"], "--alpha must be in [1e-6, 1000000]"),
    ] {
        let mut line = vec!["simulate"];
        line.extend_from_slice(args);
        refused(&line, &[flag, "to be solved"]);
    }
}

#[test]
fn the_hangs_are_refused_by_every_command() {
    refused(&["critical-angle", "--speed", "1e160"], &["--speed"]);
    refused(
        &[
            "sweep", "--vary", "angle", "--from", "10", "--to", "80", "--steps", "3", "--mu",
            "1e300",
        ],
        &["--mu"],
    );
    refused(
        &[
            "optimize", "--vary", "angle", "--from", "10", "--to", "80", "--mass", "1e300",
        ],
        &["--mass"],
    );
    refused(
        &["figure", "fig3", "--out", "-", "--duration", "1e-120"],
        &["--duration"],
    );
    refused(&["reproduce", "--radius", "1e-180"], &["--radius"]);
}

#[test]
#[ignore = "slow"]
fn the_slow_solves_are_refused_within_their_work_budget_or_phase_cap() {
    refused(
        &["simulate", "--chain", "16", "--ball-stiffness", "1e11"],
        &["budget", "evaluations", "raise --ball-damping"],
    );
    refused(
        &["simulate", "--ball-stiffness", "1e12"],
        &["10000 times", "raise --ball-damping"],
    );
}

#[test]
fn a_long_reproduce_stops_cleanly_on_ctrl_c() {
    let child = spawn(&["reproduce", "--chain", "16"], &std::env::temp_dir());
    std::thread::sleep(Duration::from_millis(500));
    // SAFETY: signals our own child.
    unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) };
    let (code, _, stderr) = finish(child);
    assert_eq!(code, 130, "{stderr}");
    assert_eq!(stderr, "error: interrupted\n");
}

#[test]
fn an_outcome_that_would_overflow_is_refused_naming_the_parameter() {
    refused(
        &["simulate", "--spin", "1e308", "--format", "json"],
        &["--spin must be in [-1e15, 1e15] rad/s"],
    );
    refused(
        &["simulate", "--radius", "1e308", "--format", "csv"],
        &["--radius"],
    );
}

#[test]
fn reproduce_far_from_the_paper_says_which_claims_it_cannot_compute() {
    let (code, table, stderr) = run(&["reproduce", "--mu", "0"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(!table.contains("NaN") && !table.contains("inf"), "{table}");
    assert!(table.contains("not computed"), "{table}");
    assert!(
        stderr.contains("not computed under these parameters"),
        "{stderr}"
    );
    let (_, json, _) = run(&["reproduce", "--mu", "0", "--format", "json"]);
    let rows: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    let (_, paper, _) = run(&["reproduce", "--format", "json"]);
    let paper_rows: Vec<serde_json::Value> = serde_json::from_str(&paper).unwrap();
    assert_eq!(rows.len(), paper_rows.len(), "every claim keeps its row");
    for row in &rows {
        if row["computed"].is_null() {
            assert_eq!(row["status"], "not-computed", "{row}");
            assert!(row["note"].as_str().unwrap().starts_with("not computed"));
        }
    }
    let (_, help, _) = run(&["reproduce", "--help"]);
    assert!(
        help.contains("Exit status: 0") && help.contains("1 when"),
        "{help}"
    );
}

#[test]
fn a_figure_is_written_through_a_symlink_into_a_device_and_to_stdout() {
    let dir = scratch("figure");
    let link = dir.join("link.svg");
    symlink("target.svg", &link).unwrap();
    let (code, _, stderr) = run_in(&dir, &["figure", "fig3", "--out", "link.svg"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        fs::read_to_string(dir.join("target.svg"))
            .unwrap()
            .starts_with("<svg")
    );

    let (code, _, stderr) = run_in(&dir, &["figure", "fig3", "--out", "/dev/null"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );

    for out in ["-", "/dev/stdout"] {
        let (code, svg, stderr) = run_in(&dir, &["figure", "fig2", "--out", out]);
        assert_eq!(code, 0, "{stderr}");
        assert!(svg.starts_with("<svg"), "{out}");
    }
    assert!(
        !dir.join("-").exists(),
        "--out - is standard output, not a file"
    );
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_read_only_file_is_kept_unless_forced() {
    let dir = scratch("readonly");
    let path = dir.join("kept.svg");
    fs::write(&path, "keep").unwrap();
    fs::set_permissions(&path, fs::Permissions::from_mode(0o444)).unwrap();
    let (code, _, stderr) = run_in(&dir, &["figure", "fig3", "--out", "kept.svg"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("read-only") && stderr.contains("--force"),
        "{stderr}"
    );
    assert_eq!(fs::read_to_string(&path).unwrap(), "keep");

    let saved = Scenario::from_params("kept", "", &Params::default()).save(&path);
    assert!(saved.unwrap_err().to_string().contains("read-only"));
    assert_eq!(fs::read_to_string(&path).unwrap(), "keep");

    let (code, _, stderr) = run_in(&dir, &["figure", "fig3", "--out", "kept.svg", "--force"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(fs::read_to_string(&path).unwrap().starts_with("<svg"));
    assert!(fs::metadata(&path).unwrap().permissions().readonly());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn scenario_errors_name_their_key() {
    let dir = scratch("scenario");
    for (text, fragment) in [
        ("[params]\nspeed = 1\nspeed = 2\n", "speed: duplicate key"),
        (
            "description = 5\n",
            "description: invalid type: integer `5`",
        ),
    ] {
        fs::write(dir.join("s.toml"), text).unwrap();
        let (code, _, stderr) = run_in(&dir, &["simulate", "--scenario", "s.toml"]);
        assert_eq!(code, 2, "{stderr}");
        assert!(stderr.contains(fragment), "{fragment} not in {stderr}");
    }
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_huge_value_is_echoed_cut_short() {
    let digits = "1".repeat(100_000);
    let (code, _, stderr) = run(&["simulate", "--speed", &digits]);
    assert_eq!(code, 2);
    assert!(stderr.len() < 400, "{} bytes", stderr.len());
    assert!(stderr.contains("(100000 characters)"), "{stderr}");
}

#[test]
fn csv_numbers_stay_short() {
    let (code, csv, stderr) = run(&["simulate", "--format", "csv", "--speed", "1e15"]);
    assert_eq!(code, 0, "{stderr}");
    let longest = csv.split([',', '\n']).map(str::len).max().unwrap();
    assert!(longest <= 24, "a field of {longest} characters");
}
