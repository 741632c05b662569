//! The documents cannot go stale: every `console` block's commands in README.md, CONTRIBUTING.md and
//! `docs/*.md` are run against the current binary and must print what the block shows; the parameter flag
//! table in `docs/commands.md` must be the one the parameter table gives; the install block's manual pages
//! name every subcommand; and every relative link names a file of the repository.
//!
//! A `console` block holds commands, each on a line starting with `$ `, each followed by the output it
//! prints (stdout only: a capture that shows stderr redirects it). In the output, a line `...` stands for
//! any number of lines and `[..]` for any text within a line. The commands of one block run in `sh`, in
//! order, in one fresh directory that links the repository's `assets/`, with the binary first on `PATH`,
//! in the C locale, with an empty configuration folder.
//!
//! `README_BLESS=1 cargo test --release --test cli readme` rewrites each stale capture with what the
//! binary prints (its `...` and `[..]` are lost there: put them back where the output varies).

use std::path::{Path, PathBuf};
use std::process::Command;

use clap::CommandFactory;
use snapback::model::PARAMS;

use crate::support::bin;

/// The repository's root.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The documents whose captures are checked, relative to the root: README.md, CONTRIBUTING.md and the
/// guide in `docs/`.
fn documents() -> Vec<PathBuf> {
    let mut guide: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .expect("docs/ is readable")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .map(|p| p.strip_prefix(root()).unwrap().to_path_buf())
        .collect();
    guide.sort();
    let mut all = vec![PathBuf::from("README.md"), PathBuf::from("CONTRIBUTING.md")];
    all.extend(guide);
    all
}

fn read(document: &Path) -> String {
    std::fs::read_to_string(root().join(document))
        .unwrap_or_else(|e| panic!("{}: {e}", document.display()))
}

/// One command of a block and the output the document shows for it.
struct Capture {
    /// The document's line of the command (1-based).
    line: usize,
    /// The indent of the block's fence, which every line of the block carries.
    indent: String,
    command: String,
    expected: Vec<String>,
}

/// The commands of every `console` block, grouped by block. A block may be indented (in a list item):
/// its lines lose the indent of its opening fence.
fn console_blocks(name: &str, text: &str) -> Vec<Vec<Capture>> {
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
        let indent_text = indent.to_string();
        let line = line.strip_prefix(*indent).unwrap_or(line);
        if line == "```" {
            blocks.push(current.take().unwrap().0);
        } else if let Some(command) = line.strip_prefix("$ ") {
            block.push(Capture {
                line: n + 1,
                indent: indent_text,
                command: command.to_string(),
                expected: Vec::new(),
            });
        } else {
            match block.last_mut() {
                Some(capture) => capture.expected.push(line.to_string()),
                None => panic!("{name}:{}: output before any `$ ` command", n + 1),
            }
        }
    }
    assert!(current.is_none(), "{name}: a console block is not closed");
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
    Path::new(bin::BIN).parent().unwrap().to_path_buf()
}

/// Runs the captures of one document's blocks; the stale ones, with what the binary printed.
fn run_captures(name: &str, blocks: &[Vec<Capture>]) -> Vec<(usize, Vec<String>, String)> {
    let path = std::env::join_paths(std::iter::once(binary_dir()).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .unwrap();
    let mut stale = Vec::new();
    for (k, block) in blocks.iter().enumerate() {
        let dir = std::env::temp_dir().join(format!(
            "snapback-docs-{}-{}-{k}",
            std::process::id(),
            name.replace('/', "-")
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let assets = dir.join("assets");
        if !assets.exists() {
            std::os::unix::fs::symlink(root().join("assets"), &assets).unwrap();
        }
        for (index, capture) in block.iter().enumerate() {
            let out = Command::new("sh")
                .arg("-c")
                .arg(format!("{} 2>&1", capture.command))
                .current_dir(&dir)
                .env("PATH", &path)
                .env("NO_COLOR", "1")
                .env("SNAPBACK_CONFIG_DIR", bin::empty_config())
                // Numbers as the documents print them (a point, not a comma), whatever the locale.
                .env("LC_ALL", "C")
                .output()
                .expect("sh runs");
            let actual = String::from_utf8_lossy(&out.stdout);
            let lines: Vec<&str> = actual.lines().collect();
            if !lines_match(&capture.expected, &lines) {
                stale.push((
                    k * 1000 + index,
                    lines.iter().map(|l| l.to_string()).collect(),
                    format!(
                        "{name}:{}: $ {}\n--- the document shows\n{}\n--- the binary prints\n{}",
                        capture.line,
                        capture.command,
                        capture.expected.join("\n"),
                        actual.trim_end()
                    ),
                ));
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
    stale
}

/// `text` with each stale capture's output replaced by what the binary printed.
fn blessed(text: &str, blocks: &[Vec<Capture>], stale: &[(usize, Vec<String>, String)]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut replacements: Vec<(&Capture, &Vec<String>)> = stale
        .iter()
        .map(|(id, actual, _)| (&blocks[id / 1000][id % 1000], actual))
        .collect();
    // From the end, so that earlier line numbers still hold.
    replacements.sort_by_key(|(capture, _)| std::cmp::Reverse(capture.line));
    for (capture, actual) in replacements {
        let first = capture.line; // the line after the command, 0-based
        let shown: Vec<String> = actual
            .iter()
            .map(|l| {
                if l.is_empty() {
                    String::new()
                } else {
                    format!("{}{l}", capture.indent)
                }
            })
            .collect();
        lines.splice(first..first + capture.expected.len(), shown);
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}

#[test]
fn every_console_capture_matches_the_binary() {
    let bless = std::env::var_os("README_BLESS").is_some();
    let mut stale_all = Vec::new();
    let mut count = 0;
    for document in documents() {
        let name = document.display().to_string();
        let text = read(&document);
        let blocks = console_blocks(&name, &text);
        count += blocks.len();
        let stale = run_captures(&name, &blocks);
        if stale.is_empty() {
            continue;
        }
        if bless {
            std::fs::write(root().join(&document), blessed(&text, &blocks, &stale)).unwrap();
        } else {
            stale_all.extend(stale.into_iter().map(|(_, _, message)| message));
        }
    }
    assert!(count >= 15, "the documents have {count} console blocks");
    assert!(
        stale_all.is_empty(),
        "stale captures (README_BLESS=1 rewrites them):\n\n{}",
        stale_all.join("\n\n")
    );
}

/// The flag table `docs/commands.md` must hold, from the parameter table.
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
        read(Path::new("docs/commands.md")).contains(&table),
        "docs/commands.md's flag table is stale; it should read:\n\n{table}"
    );
}

#[test]
fn the_install_block_writes_every_subcommands_manual_page() {
    let readme = read(Path::new("README.md"));
    let listed: Vec<&str> = readme
        .lines()
        .find_map(|l| l.strip_prefix("for c in ")?.strip_suffix("; do"))
        .expect("README.md's install block loops over the subcommands")
        .split_whitespace()
        .collect();
    let commands = snapback::cli::Cli::command();
    let every: Vec<&str> = commands
        .get_subcommands()
        .map(|c| c.get_name())
        .filter(|name| *name != "help")
        .collect();
    assert_eq!(listed, every, "the install block's manual pages");
    for dir in [
        "~/.local/share/bash-completion/completions",
        "~/.zfunc",
        "~/.config/fish/completions",
        "~/.local/share/man/man1",
    ] {
        assert!(
            readme.contains(&format!(" {dir}")) && readme.contains("mkdir -p"),
            "README.md's install block makes {dir}"
        );
    }
}

/// Every relative link of a Markdown file (`[text](target)`), without its `#anchor`.
fn relative_links(text: &str) -> Vec<String> {
    let mut links = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("](") {
        rest = &rest[at + 2..];
        let Some(end) = rest.find(')') else { break };
        let target = &rest[..end];
        if !target.contains("://") && !target.starts_with('#') && !target.starts_with("mailto:") {
            links.push(target.split('#').next().unwrap().to_string());
        }
    }
    links
}

#[test]
fn every_link_names_a_file_of_the_repository() {
    let mut documents = documents();
    documents.extend(["CHANGELOG.md", "ARCHITECTURE.md"].map(PathBuf::from));
    let root = root().canonicalize().unwrap();
    let mut broken = Vec::new();
    for document in documents {
        let text = read(&document);
        let folder = root.join(&document).parent().unwrap().to_path_buf();
        for link in relative_links(&text) {
            let target = folder.join(&link);
            let inside = target.canonicalize().is_ok_and(|t| t.starts_with(&root));
            if !inside {
                broken.push(format!("{}: {link}", document.display()));
            }
        }
        // Nothing points outside the repository, in a link or in the text.
        for outside in ["../shared", "/work/"] {
            if text.contains(outside) {
                broken.push(format!("{}: names {outside}", document.display()));
            }
        }
    }
    assert!(
        broken.is_empty(),
        "links outside the repository:\n{}",
        broken.join("\n")
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
