//! The real binary in a real pseudo-terminal (tmux): it opens, answers keys, and quits with status 0.
//! Without a terminal it refuses with status 2. tmux must be installed (`.ci/run` installs it); a machine
//! without it fails this test rather than skipping it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use assert_cmd::Command as Cmd;
use predicates::prelude::*;
use predicates::str::contains;

const BIN: &str = env!("CARGO_BIN_EXE_snapback");
/// Generous: a loaded CI machine may be slow to start the binary, but a hung one must not hang the suite.
const PATIENCE: Duration = Duration::from_secs(30);

/// A private tmux server, killed when dropped.
struct Tmux {
    socket: String,
    dir: PathBuf,
}

impl Tmux {
    fn new(name: &str) -> Tmux {
        let socket = format!("snapback-test-{name}-{}", std::process::id());
        let dir = std::env::temp_dir().join(&socket);
        std::fs::create_dir_all(&dir).unwrap();
        Tmux { socket, dir }
    }

    fn run(&self, args: &[&str]) -> Output {
        Command::new("tmux")
            .arg("-L")
            .arg(&self.socket)
            .args(args)
            .output()
            .expect("tmux must be installed for the pseudo-terminal test (.ci/run installs it)")
    }

    fn screen(&self) -> String {
        String::from_utf8_lossy(&self.run(&["capture-pane", "-p", "-t", "explorer"]).stdout)
            .into_owned()
    }

    fn keys(&self, keys: &[&str]) {
        let mut args = vec!["send-keys", "-t", "explorer"];
        args.extend(keys);
        assert!(self.run(&args).status.success());
    }

    /// Waits until `check` holds, or fails with what was last seen.
    fn wait_for(&self, what: &str, check: impl Fn(&Tmux) -> bool) {
        let start = Instant::now();
        while !check(self) {
            assert!(
                start.elapsed() < PATIENCE,
                "timed out waiting for {what}; screen:\n{}",
                self.screen()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Tmux {
    fn drop(&mut self) {
        let _ = self.run(&["kill-server"]);
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn read(path: &Path) -> Option<String> {
    std::fs::read_to_string(path)
        .ok()
        .filter(|s| s.ends_with('\n'))
}

#[test]
fn the_binary_opens_takes_keys_and_quits_cleanly() {
    let tmux = Tmux::new("keys");
    let status_file = tmux.dir.join("status");
    let command = format!(
        "{BIN}; echo $? > '{}'",
        status_file.to_str().expect("a UTF-8 temp path")
    );
    let started = tmux.run(&[
        "new-session",
        "-d",
        "-s",
        "explorer",
        "-x",
        "120",
        "-y",
        "40",
        "sh",
        "-c",
        &command,
    ]);
    assert!(started.status.success(), "{started:?}");

    tmux.wait_for("the first frame", |t| {
        let s = t.screen();
        s.contains("parameters") && s.contains("60.0 deg")
    });
    tmux.keys(&["Right"]);
    tmux.wait_for("the angle to step to 61 degrees", |t| {
        t.screen().contains("61.0 deg")
    });
    tmux.keys(&["Tab"]);
    tmux.wait_for("the sweep view", |t| t.screen().contains("θ1 (deg)"));
    tmux.keys(&["q"]);
    tmux.wait_for("the exit status", |_| read(&status_file).is_some());
    assert_eq!(read(&status_file).unwrap().trim(), "0");
}

#[test]
fn without_a_terminal_it_points_at_simulate() {
    Cmd::new(BIN)
        .assert()
        .code(2)
        .stderr(contains("needs a terminal").and(contains("snapback simulate")));
    Cmd::new(BIN).arg("tui").assert().code(2);
}

#[test]
fn a_bad_starting_value_is_a_usage_error() {
    Cmd::new(BIN)
        .args(["tui", "--angle", "95"])
        .assert()
        .code(2)
        .stderr(contains("--angle must be in (0, 90] deg; got 95"));
    Cmd::new(BIN)
        .args(["tui", "--marker", "sparkle"])
        .assert()
        .code(2);
}
