//! Where a scenario comes from: standard input for `--scenario -`; a file read whole only when it is a
//! regular file of at most 1 MiB, so a FIFO or a device is refused at once instead of blocking.

use crate::support::bin;

use std::time::Duration;

use assert_cmd::Command;

fn snapback() -> Command {
    let mut cmd = bin::snapback();
    // A read that blocks or never ends fails the test instead of hanging the suite.
    cmd.timeout(Duration::from_secs(20));
    cmd
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("snapback-input-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The exit status and stderr of `simulate --scenario PATH --format json`; a read that blocks is killed
/// by the timeout and has no status.
fn refused(path: &str) -> (Option<i32>, String) {
    let out = snapback()
        .args(["simulate", "--format", "json", "--scenario", path])
        .output()
        .unwrap();
    assert!(out.stdout.is_empty());
    (out.status.code(), String::from_utf8(out.stderr).unwrap())
}

#[test]
fn a_dash_reads_the_scenario_from_standard_input() {
    let out = snapback()
        .args([
            "simulate",
            "--scenario",
            "-",
            "--angle",
            "45",
            "--format",
            "json",
        ])
        .write_stdin("description = \"piped\"\n[params]\ncart_mass = \"1 g\"\nangle = 30\n")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["params"]["cart_mass"].as_f64(), Some(0.001));
    // Flags override the scenario, as for a file.
    assert_eq!(json["params"]["angle_deg"].as_f64(), Some(45.0));
}

#[test]
fn a_bad_scenario_on_standard_input_names_stdin_and_the_line() {
    let out = snapback()
        .args(["simulate", "--scenario", "-"])
        .write_stdin("[params]\nstiffness = \"15 kg\"\n")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.starts_with("error: <stdin>:2: stiffness: unit 'kg' is a mass"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
}

#[test]
fn devices_and_directories_are_refused_at_once() {
    let (code, err) = refused("/dev/zero");
    assert_eq!(code, Some(2));
    assert_eq!(
        err,
        "error: /dev/zero: not a regular file but a character device; give a file, or - for \
         standard input\n"
    );
    let dir = temp_dir("directory");
    let (code, err) = refused(dir.to_str().unwrap());
    assert_eq!(code, Some(2));
    assert!(err.contains("not a regular file but a directory"), "{err}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_fifo_is_refused_without_blocking() {
    let dir = temp_dir("fifo");
    let fifo = dir.join("scenario.toml");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    // Nothing ever writes to the FIFO: opening it to read would block for good.
    let (code, err) = refused(fifo.to_str().unwrap());
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(code, Some(2));
    assert!(
        err.contains("scenario.toml: not a regular file but a FIFO"),
        "{err}"
    );
}

#[test]
fn a_file_over_one_mebibyte_is_refused_naming_it() {
    let dir = temp_dir("large");
    let path = dir.join("huge.toml");
    let mut text = String::from("[params]\n");
    while text.len() <= 1 << 20 {
        text.push_str("# padding padding padding padding padding padding padding padding\n");
    }
    std::fs::write(&path, &text).unwrap();
    let (code, err) = refused(path.to_str().unwrap());
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(code, Some(2));
    assert!(
        err.contains("huge.toml: larger than 1048576 bytes (1 MiB)"),
        "{err}"
    );
    let out = snapback()
        .args(["simulate", "--scenario", "-"])
        .write_stdin(text)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).starts_with("error: <stdin>: larger than"));
}
