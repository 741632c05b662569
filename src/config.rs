//! The user's configuration: `config.toml` and a `presets/` folder in the platform's config directory
//! (`$XDG_CONFIG_HOME/snapback` on Linux), or in `$SNAPBACK_CONFIG_DIR` when that is set. A missing
//! file is fine; a bad one is an error naming the file, the line and the key.
//!
//! ```toml
//! marker = "dot"        # braille, dot or block
//! theme = "light"       # dark or light
//! fps = 30              # 1 to 60
//! charset = "ascii"     # ascii, unicode or auto (from the locale)
//! ```

use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use crate::input;
use crate::scenario::{PRESETS, Scenario, ScenarioError, key_at, line_of};

/// The environment variable that replaces the platform's config directory.
pub const DIR_VAR: &str = "SNAPBACK_CONFIG_DIR";

/// The chart marker a config can choose.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Marker {
    Braille,
    Dot,
    Block,
}

/// The colour theme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Theme {
    /// Colours for a dark background.
    #[default]
    Dark,
    /// Colours for a light background.
    Light,
}

/// What the screen may write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Charset {
    Ascii,
    Unicode,
    /// From the locale, as without a config.
    Auto,
}

/// The explorer's defaults; each is `None` when the config does not set it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Config {
    pub marker: Option<Marker>,
    pub theme: Option<Theme>,
    pub fps: Option<u32>,
    pub charset: Option<Charset>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    marker: Option<Marker>,
    theme: Option<Theme>,
    fps: Option<Spanned<i64>>,
    charset: Option<Charset>,
}

/// The config directory: `$SNAPBACK_CONFIG_DIR`, or the platform's (`~/.config/snapback` on Linux).
pub fn dir() -> Option<PathBuf> {
    match std::env::var_os(DIR_VAR) {
        Some(d) if !d.is_empty() => Some(PathBuf::from(d)),
        _ => {
            directories::ProjectDirs::from("", "", "snapback").map(|p| p.config_dir().to_path_buf())
        }
    }
}

/// Where the user's presets live.
pub fn presets_dir() -> Option<PathBuf> {
    dir().map(|d| d.join("presets"))
}

/// Reads `config.toml` from [`dir`]; the defaults when there is none.
pub fn load() -> Result<Config, ScenarioError> {
    let Some(path) = dir().map(|d| d.join("config.toml")) else {
        return Ok(Config::default());
    };
    if !path.exists() {
        return Ok(Config::default());
    }
    let origin = path.display().to_string();
    let text = input::read_text(&path).map_err(|source| ScenarioError::Io {
        path: origin.clone(),
        source,
    })?;
    parse(&text, &origin)
}

/// Parses config TOML; `origin` names it in errors.
pub fn parse(text: &str, origin: &str) -> Result<Config, ScenarioError> {
    let invalid = |offset: usize, message: String| ScenarioError::Invalid {
        origin: origin.to_string(),
        line: line_of(text, offset),
        key: key_at(text, offset).map(str::to_string),
        message,
    };
    let raw: RawConfig = toml::from_str(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        let message = e.message().trim_end();
        match key_at(text, offset) {
            Some(key) => invalid(offset, format!("{key}: {message}")),
            None => invalid(offset, message.to_string()),
        }
    })?;
    let fps = match raw.fps {
        Some(fps) => {
            let value = *fps.get_ref();
            if !(1..=60).contains(&value) {
                return Err(invalid(
                    fps.span().start,
                    format!("fps must be in 1..=60; got {value}"),
                ));
            }
            Some(value as u32)
        }
        None => None,
    };
    Ok(Config {
        marker: raw.marker,
        theme: raw.theme,
        fps,
        charset: raw.charset,
    })
}

/// The preset called `name`: a built-in one, or one of the user's (see [`user_presets`]). A user's
/// file that takes a built-in name is refused, naming the file.
pub fn preset(name: &str) -> Result<Scenario, ScenarioError> {
    let user = user_preset(name)?;
    if let Some(builtin) = PRESETS.iter().find(|p| p.name == name) {
        return Ok(builtin.scenario());
    }
    user.ok_or_else(|| {
        let mut known: Vec<String> = PRESETS.iter().map(|p| p.name.to_string()).collect();
        if let Ok(users) = user_presets() {
            known.extend(users.into_iter().map(|u| u.scenario.name));
        }
        ScenarioError::UnknownPreset {
            name: name.to_string(),
            known: known.join(", "),
        }
    })
}

/// A preset from the user's folder.
#[derive(Clone, Debug)]
pub struct UserPreset {
    pub path: PathBuf,
    pub scenario: Scenario,
}

/// Every `*.toml` in [`presets_dir`], sorted by name; none when the folder does not exist. A file that
/// does not parse, or that takes a built-in preset's name, is an error naming it.
pub fn user_presets() -> Result<Vec<UserPreset>, ScenarioError> {
    let Some(folder) = presets_dir() else {
        return Ok(Vec::new());
    };
    let entries = match std::fs::read_dir(&folder) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(source) => {
            return Err(ScenarioError::Io {
                path: folder.display().to_string(),
                source,
            });
        }
    };
    let mut paths: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    paths.iter().map(|p| load_user(p)).collect()
}

/// The user's preset called `name`, if its file exists.
pub fn user_preset(name: &str) -> Result<Option<Scenario>, ScenarioError> {
    let Some(folder) = presets_dir() else {
        return Ok(None);
    };
    if name.is_empty() || name.contains(['/', '\\']) || name.starts_with('.') {
        return Ok(None);
    }
    let path = folder.join(format!("{name}.toml"));
    if !path.exists() {
        return Ok(None);
    }
    load_user(&path).map(|p| Some(p.scenario))
}

fn load_user(path: &Path) -> Result<UserPreset, ScenarioError> {
    let origin = path.display().to_string();
    let text = input::read_text(path).map_err(|source| ScenarioError::Io {
        path: origin.clone(),
        source,
    })?;
    let scenario = Scenario::parse(&text, &origin)?;
    if PRESETS.iter().any(|p| p.name == scenario.name) {
        return Err(ScenarioError::Shadows {
            path: origin,
            name: scenario.name,
        });
    }
    Ok(UserPreset {
        path: path.to_path_buf(),
        scenario,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_key_and_names_a_bad_one() {
        let c = parse(
            "marker = \"dot\"\ntheme = \"light\"\nfps = 30\ncharset = \"ascii\"\n",
            "c.toml",
        )
        .unwrap();
        assert_eq!(c.marker, Some(Marker::Dot));
        assert_eq!(c.theme, Some(Theme::Light));
        assert_eq!(c.fps, Some(30));
        assert_eq!(c.charset, Some(Charset::Ascii));
        let e = parse("theme = \"dark\"\nfps = 0\n", "c.toml").unwrap_err();
        assert_eq!(e.to_string(), "c.toml:2: fps must be in 1..=60; got 0");
        let e = parse("\nmarker = \"round\"\n", "c.toml").unwrap_err();
        assert!(e.to_string().starts_with("c.toml:2: marker:"), "{e}");
        let e = parse("colour = 1\n", "c.toml").unwrap_err();
        assert!(e.to_string().starts_with("c.toml:1: colour:"), "{e}");
    }
}
