//! Scenarios: a set of parameter values with a description, kept as TOML. The presets ship inside the
//! binary (from `assets/presets/`); scenario files are the same format on disk.
//!
//! ```toml
//! description = "One line on what this is"
//! source = "Where the values come from, or the reasoning"
//!
//! [params]
//! cart_mass = "10 g"      # a value with a unit, as on the command line
//! stiffness = 15000       # or a bare number, in the base unit (kg, m, s, N/m, deg, rad/s)
//! ```
//! Parameters left out keep the value they had (the defaults, for a fresh start).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::input;
use crate::model::Params;
use crate::model::params::{PARAMS, ParamError, spec_named};
use crate::model::units;
use crate::output::{self, Replace};

/// A named set of parameter values.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    pub name: String,
    pub description: String,
    pub source: String,
    /// The values the scenario sets, by parameter key, in base units.
    pub values: BTreeMap<&'static str, f64>,
}

/// A preset compiled into the binary.
pub struct Preset {
    pub name: &'static str,
    text: &'static str,
}

macro_rules! presets {
    ($($name:literal),* $(,)?) => {
        &[$(Preset { name: $name, text: include_str!(concat!("../assets/presets/", $name, ".toml")) }),*]
    };
}

/// Every preset, in the order `snapback presets` lists them.
pub const PRESETS: &[Preset] = presets![
    "fig3c-soft-spring",
    "fig3b-light-cart",
    "fig3a-heavy-cart",
    "light-1g",
    "light-0.1g",
    "polyester-strings",
    "nylon-strings",
    "gut-strings",
    "billiard-cushion",
    "golf-compliant-face",
    "superball-rigid-floor",
    "flat-drive",
    "topspin-forehand",
    "slice",
    "kick-serve",
];

impl Preset {
    /// The preset's scenario.
    ///
    /// # Panics
    /// When a shipped preset does not parse: a build error caught by the tests, never user input.
    pub fn scenario(&self) -> Scenario {
        let mut scenario = Scenario::parse(self.text, self.name)
            .unwrap_or_else(|e| panic!("shipped preset {} is broken: {e}", self.name));
        // The name as it is: `light-0.1g` is no file whose extension is `.1g`.
        scenario.name = self.name.to_string();
        scenario
    }
}

/// Why a scenario cannot be used. Errors in a file name the file, the line and the key.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    #[error("unknown preset '{name}' (known: {known})")]
    UnknownPreset { name: String, known: String },
    #[error(
        "{path}: a user preset may not take the name of the built-in preset '{name}'; rename the file"
    )]
    Shadows { path: String, name: String },
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error(transparent)]
    Write(#[from] output::WriteError),
    #[error("{origin}:{line}: {message}")]
    Invalid {
        origin: String,
        line: usize,
        /// The offending key, when there is one.
        key: Option<String>,
        message: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    #[serde(default)]
    description: String,
    #[serde(default)]
    source: String,
    #[serde(default)]
    params: BTreeMap<Spanned<String>, Spanned<toml::Value>>,
}

/// The key of the line holding byte `offset` (`speed` in `speed = 5`, `params` in `[params]`), for a
/// parser's message that does not name it.
pub(crate) fn key_at(text: &str, offset: usize) -> Option<&str> {
    let start = text.get(..offset)?.rfind('\n').map_or(0, |i| i + 1);
    let line = text[start..].lines().next()?;
    let key = match line.split_once('=') {
        Some((key, _)) => key,
        None => line.trim().trim_start_matches('[').trim_end_matches(']'),
    };
    let key = key.trim().trim_matches(['"', '\'']);
    (!key.is_empty() && key.len() <= 64).then_some(key)
}

/// The parameter key a misspelt `name` most likely means: the nearest key or flag, at most two edits
/// away (or one for a name of four letters or fewer), case and `-`/`_` aside.
fn nearest_key(name: &str) -> Option<&'static str> {
    let wanted = name.to_lowercase().replace('-', "_");
    let limit = if wanted.chars().count() <= 4 { 1 } else { 2 };
    PARAMS
        .iter()
        .map(|s| (edits(&wanted, s.key), s.key))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, key)| key)
}

/// The Levenshtein distance between `a` and `b`: the fewest insertions, deletions and substitutions of
/// one character that turn one into the other.
fn edits(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

/// 1-based line of byte `offset` in `text`.
pub(crate) fn line_of(text: &str, offset: usize) -> usize {
    1 + text[..offset.min(text.len())]
        .bytes()
        .filter(|&b| b == b'\n')
        .count()
}

impl Scenario {
    /// Parses scenario TOML; `origin` (a path or preset name) names it in errors.
    pub fn parse(text: &str, origin: &str) -> Result<Self, ScenarioError> {
        let invalid = |offset: usize, key: Option<&str>, message: String| ScenarioError::Invalid {
            origin: origin.to_string(),
            line: line_of(text, offset),
            key: key.map(str::to_string),
            message,
        };
        let raw: RawScenario = toml::from_str(text).map_err(|e| {
            let offset = e.span().map_or(0, |s| s.start);
            let message = e.message().trim_end();
            match key_at(text, offset) {
                Some(key) => invalid(offset, Some(key), format!("{key}: {message}")),
                None => invalid(offset, None, message.to_string()),
            }
        })?;
        let mut values = BTreeMap::new();
        for (key, value) in &raw.params {
            let name = key.get_ref().as_str();
            // The key (`cart_mass`) or the flag's spelling (`cart-mass`), as in a data file's header.
            let spec = spec_named(name).ok_or_else(|| {
                let known: Vec<&str> = PARAMS.iter().map(|s| s.key).collect();
                let hint =
                    nearest_key(name).map_or(String::new(), |k| format!("; did you mean '{k}'?"));
                invalid(
                    key.span().start,
                    Some(name),
                    format!(
                        "unknown parameter '{name}'{hint} (known: {})",
                        known.join(", ")
                    ),
                )
            })?;
            if values.contains_key(spec.key) {
                return Err(invalid(
                    key.span().start,
                    Some(name),
                    format!(
                        "{name}: {} is given twice (as {} and {})",
                        spec.key, spec.key, spec.flag
                    ),
                ));
            }
            let text_value = match value.get_ref() {
                toml::Value::String(s) => s.clone(),
                toml::Value::Integer(i) => i.to_string(),
                toml::Value::Float(f) => f.to_string(),
                other => {
                    return Err(invalid(
                        value.span().start,
                        Some(name),
                        format!(
                            "{name} must be a number or a string with a unit, not {}",
                            other.type_str()
                        ),
                    ));
                }
            };
            let parsed = spec.parse(&text_value).map_err(|e| {
                let reason = match e {
                    ParamError::OutOfRange { range, given, .. } => {
                        format!("{name} must be in {range}; got {given}")
                    }
                    ParamError::Unparsable { source, given, .. } => {
                        format!("{name}: {source}; got {given}")
                    }
                };
                invalid(value.span().start, Some(name), reason)
            })?;
            values.insert(spec.key, parsed);
        }
        Ok(Scenario {
            name: Path::new(origin)
                .file_stem()
                .map_or(origin.to_string(), |s| s.to_string_lossy().into_owned()),
            description: raw.description,
            source: raw.source,
            values,
        })
    }

    /// Reads a scenario file, or standard input for `-` (named `<stdin>` in errors); see
    /// [`input::read_text`] for the bounds.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let origin = if input::is_stdin(path) {
            input::STDIN_NAME.to_string()
        } else {
            path.display().to_string()
        };
        let text = input::read_text(path).map_err(|source| ScenarioError::Io {
            path: origin.clone(),
            source,
        })?;
        Self::parse(&text, &origin)
    }

    /// A scenario that sets every parameter to its value in `params`.
    pub fn from_params(name: &str, description: &str, params: &Params) -> Self {
        Scenario {
            name: name.to_string(),
            description: description.to_string(),
            source: String::new(),
            values: PARAMS.iter().map(|s| (s.key, params.get(s.id))).collect(),
        }
    }

    /// True when the scenario sets a shot parameter (a stroke on court, for `snapback shot`), unless it
    /// lists every parameter with the shot's at their defaults: the explorer saved every bounce so before
    /// it had shot mode (a shot it saves now leaves out the incidence, which the shot sets).
    pub fn is_shot(&self) -> bool {
        let shot_keys = || {
            self.values
                .iter()
                .filter_map(|(key, value)| Some((spec_named(key)?, *value)))
                .filter(|(spec, _)| spec.group.is_shot())
        };
        let every_key_at_defaults = self.values.len() == PARAMS.len()
            && shot_keys().all(|(spec, value)| value == spec.default);
        shot_keys().next().is_some() && !every_key_at_defaults
    }

    /// `base` with the scenario's values set.
    pub fn apply(&self, mut base: Params) -> Params {
        for (key, value) in &self.values {
            if let Some(spec) = spec_named(key) {
                base.set(spec.id, *value);
            }
        }
        base
    }

    /// The scenario as TOML. Values are written in base units with every digit they need, so loading
    /// the text back gives identical parameters; the people unit follows as a comment.
    pub fn to_toml(&self) -> String {
        let quote = |s: &str| toml::Value::String(s.to_string()).to_string();
        let mut out = String::from("# snapback scenario\n");
        let _ = writeln!(out, "description = {}", quote(&self.description));
        if !self.source.is_empty() {
            let _ = writeln!(out, "source = {}", quote(&self.source));
        }
        out.push_str("\n[params]\n");
        for spec in PARAMS {
            if let Some(value) = self.values.get(spec.key) {
                let unit = spec.dimension.base_symbol();
                let text = if unit.is_empty() {
                    format!("{value}")
                } else {
                    format!("{value} {unit}")
                };
                let _ = writeln!(
                    out,
                    "{:<10}= {:<26}# {}",
                    spec.key,
                    quote(&text),
                    spec.show(*value)
                );
            }
        }
        out
    }

    /// Writes the scenario to `path` through [`output::write`]: never replacing a read-only file, a
    /// device or a symlink, and never leaving a half-written file.
    pub fn save(&self, path: &Path) -> Result<(), ScenarioError> {
        Ok(output::write(
            path,
            self.to_toml().as_bytes(),
            Replace::Writable,
        )?)
    }
}

/// A short text for a value of parameter `key` in its people unit, e.g. `10.00 g`.
pub fn show_value(key: &str, value: f64) -> String {
    spec_named(key).map_or_else(|| units::brief(value, 6), |s| s.show(value).to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_parses_and_is_valid() {
        for p in PRESETS {
            let scenario = p.scenario();
            assert!(
                !scenario.description.is_empty(),
                "{} has no description",
                p.name
            );
            assert!(!scenario.source.is_empty(), "{} has no source", p.name);
            assert!(
                scenario.apply(Params::default()).validate().is_ok(),
                "{}",
                p.name
            );
        }
    }

    #[test]
    fn a_key_takes_the_flag_spelling_and_a_near_miss_gets_a_suggestion() {
        let both = Scenario::parse(
            "[params]\ncart-mass = \"1 g\"\nball_stiffness = 1e6\n",
            "s.toml",
        );
        let both = both.unwrap();
        assert_eq!(both.values.get("cart_mass"), Some(&1e-3));
        assert_eq!(both.values.get("ball_stiffness"), Some(&1e6));
        let near = |text: &str| Scenario::parse(text, "s.toml").unwrap_err().to_string();
        let e = near("[params]\ncart_mas = 1\n");
        assert!(
            e.starts_with(
                "s.toml:2: unknown parameter 'cart_mas'; did you mean 'cart_mass'? (known: "
            ),
            "{e}"
        );
        assert!(near("[params]\nAngel = 1\n").contains("did you mean 'angle'?"));
        assert!(near("[params]\nball-stifness = 1\n").contains("did you mean 'ball_stiffness'?"));
        assert!(!near("[params]\nfriction = 1\n").contains("did you mean"));
        let e = near("[params]\ncart-mass = 1\ncart_mass = 2\n");
        assert!(e.contains("cart_mass is given twice"), "{e}");
    }

    #[test]
    fn line_numbers_count_from_one() {
        assert_eq!(line_of("a\nb\nc", 0), 1);
        assert_eq!(line_of("a\nb\nc", 2), 2);
        assert_eq!(line_of("a\nb\nc", 4), 3);
    }
}
