//! `snapback presets`: the presets compiled into the binary and the user's own (see [`crate::config`]),
//! with their descriptions; `--path` prints the folder the user's live in.

use std::fmt::Write;

use clap::{Args, ValueEnum};
use serde::Serialize;

use super::{Failure, emit};
use crate::config;
use crate::model::{SolveOptions, solve_with};
use crate::scenario::{PRESETS, Scenario};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Name, description and the rebound spin, one preset per block.
    #[default]
    Table,
    /// An array of objects with `name`, `description`, `source` and `params`.
    Json,
}

#[derive(Clone, Debug, Default, Args)]
pub struct PresetsArgs {
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Print the folder your own presets live in (`*.toml` there are listed as `(user)`), and nothing else.
    #[arg(long, conflicts_with = "format")]
    pub path: bool,
}

#[derive(Serialize)]
struct PresetJson {
    name: String,
    /// True for the user's own presets.
    user: bool,
    description: String,
    source: String,
    params: crate::model::Params,
}

/// Lists the presets, each solved (or its shot played) on `options`' terms.
pub fn run(args: &PresetsArgs, options: &SolveOptions) -> Result<(), Failure> {
    if args.path {
        let dir = config::presets_dir().ok_or_else(|| {
            Failure::usage(format!(
                "no config directory here (no home directory); set {}",
                config::DIR_VAR
            ))
        })?;
        return emit(&format!("{}\n", dir.display()));
    }
    let users = config::user_presets().map_err(Failure::usage)?;
    let all: Vec<(Scenario, bool)> = PRESETS
        .iter()
        .map(|p| (p.scenario(), false))
        .chain(users.into_iter().map(|u| (u.scenario, true)))
        .collect();
    let text = match args.format {
        Format::Table => {
            let mut out = String::new();
            let label = |s: &Scenario, user: bool| {
                if user {
                    format!("{} (user)", s.name)
                } else {
                    s.name.clone()
                }
            };
            let width = all
                .iter()
                .map(|(s, user)| label(s, *user).len())
                .max()
                .unwrap_or(0);
            for (scenario, user) in &all {
                let params = scenario.apply(crate::model::Params::default());
                let spin = if scenario.is_shot() {
                    crate::shot::play_with(&params, false, options).map_or(
                        "does not play".to_string(),
                        |s| {
                            let l = &s.strings.leaving;
                            let rpm = l.topspin() * 30.0 / std::f64::consts::PI;
                            format!(
                                "shot: launch {:.1} m/s at {:.1} deg, {:.0} rpm {}, {}",
                                l.speed(),
                                l.angle_deg(),
                                rpm.abs(),
                                if rpm < 0.0 { "backspin" } else { "topspin" },
                                if s.is_in() { "in" } else { "out" }
                            )
                        },
                    )
                } else {
                    solve_with(&params, options).map_or("does not solve".to_string(), |b| {
                        format!("ω2 = {:.1} rad/s", b.outcome.omega2)
                    })
                };
                let name = label(scenario, *user);
                let _ = writeln!(out, "{name:<width$}  {}", scenario.description);
                let _ = writeln!(out, "{:<width$}  ({spin})", "");
            }
            out.push_str("\nUse one with --preset NAME on any command, e.g. `snapback simulate --preset light-1g`;\nthe shot presets with `snapback shot --preset kick-serve`.\n");
            out
        }
        Format::Json => {
            let list: Vec<PresetJson> = all
                .into_iter()
                .map(|(scenario, user)| PresetJson {
                    name: scenario.name.clone(),
                    user,
                    params: scenario.apply(crate::model::Params::default()),
                    description: scenario.description,
                    source: scenario.source,
                })
                .collect();
            let mut text = serde_json::to_string_pretty(&list).expect("presets serialize");
            text.push('\n');
            text
        }
    };
    emit(&text)
}
