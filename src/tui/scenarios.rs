//! The explorer's files: where a typed name points ([`resolve`]), completing it ([`complete`]), reading
//! a scenario file ([`load`]) and the names of exports ([`export_paths`]). The keys that use them (the
//! picker, save, open, undo, the baseline, export) are applied in `app::scenarios`.

use std::path::{Path, PathBuf};

use crate::scenario::{Scenario, ScenarioError};

pub use super::vocabulary::{FileKind, FilePrompt};

/// The file name `s` offers when no scenario file has been opened or saved yet.
pub const DEFAULT_SCENARIO_FILE: &str = "snapback-scenario.toml";

/// Evenly spaced samples in an export (both sides of every transition are added), as `simulate` writes.
pub const EXPORT_SAMPLES: usize = 501;

/// The pair of files export number `n` writes.
pub fn export_paths(dir: &Path, n: u32) -> (PathBuf, PathBuf) {
    (
        dir.join(format!("snapback-{n}.csv")),
        dir.join(format!("snapback-{n}.json")),
    )
}

/// A scenario file, with errors naming it as `name` (the name typed, not the full path).
pub fn load(path: &Path, name: &str) -> Result<Scenario, ScenarioError> {
    let text = crate::input::read_text(path).map_err(|source| ScenarioError::Io {
        path: name.to_string(),
        source,
    })?;
    Scenario::parse(&text, name)
}

/// `name` as a path: relative to `dir`, `~/` in the home directory, absolute as it is.
pub fn resolve(dir: &Path, name: &str) -> PathBuf {
    if let Some(rest) = name.strip_prefix("~/")
        && let Some(home) = std::env::var_os("HOME")
    {
        return PathBuf::from(home).join(rest);
    }
    dir.join(name)
}

/// `typed` completed as far as the files in its directory agree: the one match, with `/` after a
/// directory, or the longest prefix all matches share. Unchanged when nothing matches.
pub fn complete(dir: &Path, typed: &str) -> String {
    let (folder, prefix) = match typed.rfind('/') {
        Some(i) => (&typed[..=i], &typed[i + 1..]),
        None => ("", typed),
    };
    let Ok(entries) = std::fs::read_dir(resolve(dir, if folder.is_empty() { "." } else { folder }))
    else {
        return typed.to_string();
    };
    let mut matches: Vec<(String, bool)> = entries
        .filter_map(Result::ok)
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let hidden = name.starts_with('.') && !prefix.starts_with('.');
            (name.starts_with(prefix) && !hidden)
                .then(|| (name, e.file_type().is_ok_and(|t| t.is_dir())))
        })
        .collect();
    matches.sort();
    match matches.as_slice() {
        [] => typed.to_string(),
        [(name, is_dir)] => format!("{folder}{name}{}", if *is_dir { "/" } else { "" }),
        [(first, _), rest @ ..] => {
            let mut shared = first.clone();
            for (name, _) in rest {
                let n = shared
                    .chars()
                    .zip(name.chars())
                    .take_while(|(a, b)| a == b)
                    .count();
                shared = shared.chars().take(n).collect();
            }
            format!("{folder}{shared}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn completes_to_the_shared_prefix_then_the_one_match() {
        let dir = std::env::temp_dir().join(format!("snapback-complete-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        for f in ["what-if.toml", "what-else.toml", "other.toml"] {
            std::fs::write(dir.join(f), "").unwrap();
        }
        assert_eq!(complete(&dir, "wh"), "what-");
        assert_eq!(complete(&dir, "what-i"), "what-if.toml");
        assert_eq!(complete(&dir, "su"), "sub/");
        assert_eq!(complete(&dir, "zzz"), "zzz");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
