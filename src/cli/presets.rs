//! `snapback presets`: the presets compiled into the binary, with their descriptions.

use std::fmt::Write;

use clap::{Args, ValueEnum};
use serde::Serialize;

use super::{Failure, emit};
use crate::model::solve;
use crate::scenario::PRESETS;

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
}

#[derive(Serialize)]
struct PresetJson {
    name: &'static str,
    description: String,
    source: String,
    params: crate::model::Params,
}

pub fn run(args: &PresetsArgs) -> Result<(), Failure> {
    let text = match args.format {
        Format::Table => {
            let mut out = String::new();
            let width = PRESETS.iter().map(|p| p.name.len()).max().unwrap_or(0);
            for preset in PRESETS {
                let scenario = preset.scenario();
                let params = scenario.apply(crate::model::Params::default());
                let spin = if scenario.is_shot() {
                    crate::shot::play(&params, false).map_or("does not play".to_string(), |s| {
                        let l = &s.strings.leaving;
                        format!(
                            "shot: launch {:.1} m/s at {:.1} deg, {:.0} rpm topspin, {}",
                            l.speed(),
                            l.angle_deg(),
                            l.topspin() * 30.0 / std::f64::consts::PI,
                            if s.is_in() { "in" } else { "out" }
                        )
                    })
                } else {
                    solve(&params).map_or("does not solve".to_string(), |b| {
                        format!("ω2 = {:.1} rad/s", b.outcome.omega2)
                    })
                };
                let _ = writeln!(out, "{:<width$}  {}", preset.name, scenario.description);
                let _ = writeln!(out, "{:<width$}  ({spin})", "");
            }
            out.push_str("\nUse one with --preset NAME on any command, e.g. `snapback simulate --preset light-1g`;\nthe shot presets with `snapback shot --preset kick-serve`.\n");
            out
        }
        Format::Json => {
            let list: Vec<PresetJson> = PRESETS
                .iter()
                .map(|preset| {
                    let scenario = preset.scenario();
                    PresetJson {
                        name: preset.name,
                        params: scenario.apply(crate::model::Params::default()),
                        description: scenario.description,
                        source: scenario.source,
                    }
                })
                .collect();
            let mut text = serde_json::to_string_pretty(&list).expect("presets serialize");
            text.push('\n');
            text
        }
    };
    emit(&text)
}
