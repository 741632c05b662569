//! README.md cannot go stale: every `console` block's commands are run against the current binary and
//! must print what the block shows, and the parameter flag table must be the one the parameter table
//! gives.
//!
//! A `console` block holds commands, each on a line starting with `$ `, each followed by the output it
//! prints (stdout and stderr together). In the output, a line `...` stands for any number of lines and
//! `[..]` for any text within a line. The commands of one block run in `sh`, in order, in one fresh
//! directory that links the repository's `assets/`, with the binary first on `PATH`, in the C locale.

use crate::support::bin;

use std::path::{Path, PathBuf};
use std::process::Command;

use snapback::model::PARAMS;

const README: &str = include_str!("../../README.md");

/// One command of a block and the output the README shows for it.
struct Capture {
    /// The README's line of the command.
    line: usize,
    command: String,
    expected: Vec<String>,
}

/// The commands of every `console` block, grouped by block. A block may be indented (in a list item):
/// its lines lose the indent of its opening fence.
fn console_blocks(text: &str) -> Vec<Vec<Capture>> {
    let mut blocks = Vec::new();
    // The block being read, and its indent.
    let mut current: Option<(Vec<Capture>, &str)> = None;
    for (n, line) in text.lines().enumerate() {
        let Some((block, indent)) = &mut current else {
            if line.trim_start() == "```console" {
                current = Some((Vec::new(), &line[..line.len() - "```console".len()]));
            }
            continue;
        };
        let line = line.strip_prefix(*indent).unwrap_or(line);
        if line == "```" {
            blocks.push(current.take().unwrap().0);
        } else if let Some(command) = line.strip_prefix("$ ") {
            block.push(Capture {
                line: n + 1,
                command: command.to_string(),
                expected: Vec::new(),
            });
        } else {
            match block.last_mut() {
                Some(capture) => capture.expected.push(line.to_string()),
                None => panic!("README.md:{}: output before any `$ ` command", n + 1),
            }
        }
    }
    assert!(
        current.is_none(),
        "README.md: a console block is not closed"
    );
    blocks
}

/// Whether `actual` matches the pattern `line`, where `[..]` stands for any text.
fn line_matches(pattern: &str, actual: &str) -> bool {
    let mut pieces = pattern.split("[..]");
    let first = pieces.next().unwrap_or("");
    let Some(mut rest) = actual.strip_prefix(first) else {
        return false;
    };
    let pieces: Vec<&str> = pieces.collect();
    for (k, piece) in pieces.iter().enumerate() {
        if k + 1 == pieces.len() {
            return rest.ends_with(piece);
        }
        match rest.find(piece) {
            Some(at) => rest = &rest[at + piece.len()..],
            None => return false,
        }
    }
    rest.is_empty()
}

/// Whether the lines of `actual` match the lines of `expected`, where a line `...` stands for any
/// number of lines.
fn lines_match(expected: &[String], actual: &[&str]) -> bool {
    match expected.split_first() {
        None => actual.is_empty(),
        Some((first, rest)) if first == "..." => {
            (0..=actual.len()).any(|skip| lines_match(rest, &actual[skip..]))
        }
        Some((first, rest)) => {
            !actual.is_empty() && line_matches(first, actual[0]) && lines_match(rest, &actual[1..])
        }
    }
}

fn binary_dir() -> PathBuf {
    Path::new(env!("CARGO_BIN_EXE_snapback"))
        .parent()
        .unwrap()
        .to_path_buf()
}

#[test]
fn every_console_capture_matches_the_binary() {
    let blocks = console_blocks(README);
    assert!(
        blocks.len() >= 5,
        "README.md has {} console blocks",
        blocks.len()
    );
    let path = std::env::join_paths(std::iter::once(binary_dir()).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .unwrap();
    let mut stale = Vec::new();
    for (k, block) in blocks.iter().enumerate() {
        let dir = std::env::temp_dir().join(format!("snapback-readme-{}-{k}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let assets = dir.join("assets");
        if !assets.exists() {
            std::os::unix::fs::symlink(
                Path::new(env!("CARGO_MANIFEST_DIR")).join("assets"),
                &assets,
            )
            .unwrap();
        }
        for capture in block {
            let out = Command::new("sh")
                .arg("-c")
                .arg(format!("{} 2>&1", capture.command))
                .current_dir(&dir)
                .env("PATH", &path)
                .env("NO_COLOR", "1")
                .env("SNAPBACK_CONFIG_DIR", bin::empty_config())
                // Numbers as the README prints them (a point, not a comma), whatever the machine's locale.
                .env("LC_ALL", "C")
                .output()
                .expect("sh runs");
            let actual = String::from_utf8_lossy(&out.stdout);
            let lines: Vec<&str> = actual.lines().collect();
            if !lines_match(&capture.expected, &lines) {
                stale.push(format!(
                    "README.md:{}: $ {}\n--- README shows\n{}\n--- the binary prints\n{}",
                    capture.line,
                    capture.command,
                    capture.expected.join("\n"),
                    actual.trim_end()
                ));
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(
        stale.is_empty(),
        "stale captures:\n\n{}",
        stale.join("\n\n")
    );
}

/// The flag table README.md must hold, from the parameter table.
fn flag_table() -> String {
    let mut table = String::from(
        "| flag | parameter | bare unit | other units | range | default |\n|---|---|---|---|---|---|\n",
    );
    for spec in PARAMS {
        let or_dash = |s: &str| {
            if s.is_empty() {
                "-".to_string()
            } else {
                s.to_string()
            }
        };
        table.push_str(&format!(
            "| `--{}` | {} {} | {} | {} | {} | {} |\n",
            spec.flag,
            spec.symbol,
            spec.label,
            or_dash(spec.bare_symbol()),
            or_dash(&spec.other_symbols().join(", ")),
            spec.range_text(),
            spec.show(spec.default),
        ));
    }
    table
}

#[test]
fn the_flag_table_is_the_parameter_table() {
    let table = flag_table();
    assert!(
        README.contains(&table),
        "README.md's flag table is stale; it should read:\n\n{table}"
    );
}

#[test]
fn the_matcher_tells_captures_apart() {
    let lines = |s: &[&str]| s.iter().map(|l| l.to_string()).collect::<Vec<_>>();
    assert!(lines_match(
        &lines(&["a", "...", "d"]),
        &["a", "b", "c", "d"]
    ));
    assert!(lines_match(&lines(&["a", "...", "d"]), &["a", "d"]));
    assert!(!lines_match(&lines(&["a", "...", "d"]), &["a", "b", "c"]));
    assert!(!lines_match(&lines(&["a", "b"]), &["a", "b", "c"]));
    assert!(line_matches(
        "residual [..] (relative)",
        "residual 1.2e-16 (relative)"
    ));
    assert!(line_matches("[..]", "anything"));
    assert!(!line_matches(
        "residual [..] (relative)",
        "residual 1.2e-16 (absolute)"
    ));
    assert!(!line_matches("ω2 160.8", "ω2 160.9"));
}
