//! The user's configuration and presets (`SNAPBACK_CONFIG_DIR` points every test at its own temporary
//! folder, so none touches the real home): the config's defaults reach the explorer and a flag beats
//! them; a bad config names file, line and key with status 2; a user preset is listed as the user's,
//! solves with `--preset`, may not take a built-in name, and a bad one names file, line and key;
//! `presets --path` prints the folder.

use std::path::PathBuf;

use assert_cmd::Command as Cmd;
use predicates::prelude::*;
use predicates::str::contains;

use crate::support::pty;
use pty::{BIN, Pty};

/// A fresh, empty config folder for one test.
fn config_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("snapback-config-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("presets")).unwrap();
    dir
}

fn snapback(dir: &PathBuf) -> Cmd {
    let mut cmd = Cmd::new(BIN);
    cmd.env("SNAPBACK_CONFIG_DIR", dir);
    cmd
}

const MY_PRESET: &str = "description = \"My softer strings\"\nsource = \"my own measurement\"\n\n\
                         [params]\nstiffness = \"8 kN/m\"\n";

#[test]
fn presets_path_prints_the_folder() {
    let dir = config_dir("path");
    snapback(&dir)
        .args(["presets", "--path"])
        .assert()
        .success()
        .stdout(format!("{}\n", dir.join("presets").display()));
}

#[test]
fn a_user_preset_is_listed_as_the_users_and_solves() {
    let dir = config_dir("user-preset");
    std::fs::write(dir.join("presets/my-soft.toml"), MY_PRESET).unwrap();
    snapback(&dir).arg("presets").assert().success().stdout(
        contains("my-soft (user) ")
            .and(contains("My softer strings"))
            .and(contains("light-1g")),
    );
    let out = snapback(&dir)
        .args(["presets", "--format", "json"])
        .output()
        .unwrap();
    let list: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let mine = list
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "my-soft")
        .expect("listed");
    assert_eq!(mine["user"], true);
    assert_eq!(mine["params"]["stiffness"], 8000.0);
    // The preset solves, and gives what the same flag gives.
    let with_preset = snapback(&dir)
        .args(["simulate", "--preset", "my-soft", "--format", "json"])
        .output()
        .unwrap();
    assert!(with_preset.status.success());
    let with_flag = snapback(&dir)
        .args(["simulate", "--stiffness", "8kN/m", "--format", "json"])
        .output()
        .unwrap();
    assert_eq!(with_preset.stdout, with_flag.stdout);
}

#[test]
fn a_bad_user_preset_names_file_line_and_key() {
    let dir = config_dir("bad-preset");
    let file = dir.join("presets/broken.toml");
    std::fs::write(
        &file,
        "description = \"x\"\n[params]\nstiffness = \"lots\"\n",
    )
    .unwrap();
    let expected = format!("error: {}:3: stiffness:", file.display());
    snapback(&dir)
        .arg("presets")
        .assert()
        .code(2)
        .stderr(contains(expected.clone()));
    snapback(&dir)
        .args(["simulate", "--preset", "broken"])
        .assert()
        .code(2)
        .stderr(contains(expected));
}

#[test]
fn a_user_preset_may_not_take_a_built_in_name() {
    let dir = config_dir("shadow");
    let file = dir.join("presets/slice.toml");
    std::fs::write(&file, MY_PRESET).unwrap();
    for args in [&["presets"][..], &["simulate", "--preset", "slice"]] {
        snapback(&dir)
            .args(args)
            .assert()
            .code(2)
            .stderr(contains(format!(
                "{}: a user preset may not take the name of the built-in preset 'slice'",
                file.display()
            )));
    }
}

#[test]
fn a_bad_config_names_file_line_and_key() {
    let dir = config_dir("bad-config");
    let file = dir.join("config.toml");
    for (text, line, key) in [
        ("theme = \"light\"\nfps = 0\n", 2, "fps"),
        ("marker = \"sparkle\"\n", 1, "marker"),
        ("\n\ncolour = true\n", 3, "colour"),
        ("theme = 3\n", 1, "theme"),
    ] {
        std::fs::write(&file, text).unwrap();
        snapback(&dir)
            .arg("tui")
            .assert()
            .code(2)
            .stderr(contains(format!("error: {}:{line}: {key}", file.display())));
    }
    // Without a config file, or with a good one, the explorer only misses its terminal.
    std::fs::write(
        &file,
        "theme = \"light\"\nfps = 12\nmarker = \"dot\"\ncharset = \"ascii\"\n",
    )
    .unwrap();
    snapback(&dir)
        .arg("tui")
        .assert()
        .code(2)
        .stderr(contains("needs a terminal"));
    std::fs::remove_file(&file).unwrap();
    snapback(&dir)
        .arg("tui")
        .assert()
        .code(2)
        .stderr(contains("needs a terminal"));
}

#[test]
fn the_configs_defaults_reach_the_explorer_and_a_flag_wins() {
    let dir = config_dir("defaults");
    std::fs::write(
        dir.join("config.toml"),
        "charset = \"ascii\"\ntheme = \"light\"\n",
    )
    .unwrap();
    let dir_text = dir.display().to_string();
    let env = [("SNAPBACK_CONFIG_DIR", dir_text.as_str())];
    // A UTF-8 locale, yet the config asks for ASCII: omega is spelt out.
    let mut pty = Pty::spawn(&[], &env, 160, 48);
    pty.wait_for("the ASCII screen", |s| {
        s.contains("omega") && s.contains("60.0 deg")
    });
    assert!(!pty.screen().contains('ω'), "{}", pty.screen());
    pty.send(b"q");
    assert!(pty.exit(pty::PATIENCE).expect("it quits").success());
    // --unicode on the command line beats the config.
    let mut pty = Pty::spawn(&["--unicode", "--theme", "dark"], &env, 160, 48);
    pty.wait_for("the Unicode screen", |s| {
        s.contains('ω') && s.contains("60.0 deg")
    });
    pty.send(b"q");
    assert!(pty.exit(pty::PATIENCE).expect("it quits").success());
}

#[test]
fn the_explorers_picker_lists_a_user_preset_and_applies_it() {
    let dir = config_dir("picker");
    std::fs::write(dir.join("presets/my-soft.toml"), MY_PRESET).unwrap();
    let dir_text = dir.display().to_string();
    let mut pty = Pty::spawn(&[], &[("SNAPBACK_CONFIG_DIR", dir_text.as_str())], 160, 48);
    pty.wait_for("the first frame", |s| s.contains("60.0 deg"));
    pty.send(b"p");
    pty.wait_for("the picker with the user's preset", |s| {
        s.contains("my-soft (user)") && s.contains("light-1g")
    });
    // The user's presets come last: up from the first wraps to it.
    pty.send(b"\x1b[A");
    std::thread::sleep(std::time::Duration::from_millis(100));
    pty.send(b"\r");
    pty.wait_for("the preset applied", |s| {
        s.contains("preset my-soft: My softer strings")
    });
    pty.send(b"q");
    assert!(pty.exit(pty::PATIENCE).is_some());
}
