//! The conventions of a command-line tool: shell completions, manual pages, and the package's licence.

use crate::support::bin;

use std::process::{Command, Output};

fn snapback(args: &[&str]) -> Output {
    bin::command().args(args).output().expect("the binary runs")
}

fn stdout(out: &Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).expect("UTF-8")
}

#[test]
fn completions_cover_every_shell_command_and_parameter_flag() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let script = stdout(&snapback(&["completions", shell]));
        for word in [
            "sweep",
            "critical-angle",
            "cart-mass",
            "ball-stiffness",
            "completions",
        ] {
            assert!(script.contains(word), "{shell} completion lacks {word}");
        }
    }
}

#[test]
fn bash_completion_parses_and_completes_a_flag() {
    let script = stdout(&snapback(&["completions", "bash"]));
    let dir = std::env::temp_dir().join(format!("snapback-completion-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("snapback.bash");
    std::fs::write(&path, script).unwrap();
    let run = Command::new("bash")
        .arg("-c")
        .arg(format!(
            "source {}; COMP_WORDS=(snapback sweep --cart-m); COMP_CWORD=2; \
             _snapback snapback --cart-m sweep; echo \"${{COMPREPLY[@]}}\"",
            path.display()
        ))
        .output()
        .expect("bash runs");
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(stdout(&run).trim(), "--cart-mass");
}

#[test]
fn an_unknown_shell_exits_2() {
    let out = snapback(&["completions", "tcsh"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("'tcsh'") && err.contains("bash"), "{err}");
}

#[test]
fn man_pages_are_roff_with_every_flag() {
    let page = stdout(&snapback(&["man"]));
    assert!(page.contains(".TH snapback 1"), "{page}");
    for flag in [r"\-\-cart\-mass", r"\-\-scenario", "completions", "sweep"] {
        assert!(page.contains(flag), "snapback(1) lacks {flag}");
    }
    let sweep = stdout(&snapback(&["man", "sweep"]));
    assert!(sweep.contains(".TH snapback-sweep 1"), "{sweep}");
    for flag in [r"\-\-vary", r"\-\-steps", "jsonl"] {
        assert!(sweep.contains(flag), "snapback-sweep(1) lacks {flag}");
    }
}

#[test]
fn man_for_an_unknown_command_names_the_choices() {
    let out = snapback(&["man", "simulat"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: COMMAND must be one of simulate, tui, presets, sweep, critical-angle, optimize, \
         reproduce, fit, figure, shot, completions, man; got simulat\n"
    );
}

#[test]
fn the_licence_matches_the_manifest() {
    let manifest = include_str!("../../Cargo.toml");
    let licence = include_str!("../../LICENSE");
    assert!(manifest.contains("license = \"MIT\""));
    assert!(licence.starts_with("MIT License\n\nCopyright (c) 2026 the snapback developers\n"));
    for key in ["description", "keywords", "categories", "rust-version"] {
        assert!(
            manifest.contains(&format!("\n{key} = ")),
            "Cargo.toml lacks {key}"
        );
    }
}
