//! The parameter flags (`--angle`, `--cart-mass`, ...), generated from the parameter table so that
//! every command takes the same flags with the same help. A command takes the bounce's flags
//! ([`BounceFlags`]) or, if it can play a shot on court, those and the shot's too ([`ShotFlags`]).

use std::fmt::Debug;
use std::marker::PhantomData;
use std::path::PathBuf;

use clap::{Arg, ArgMatches, Args, Command, FromArgMatches};

use crate::analysis::uncertainty::{Spread, UncertainError, parse_uncertain, split_uncertainty};
use crate::config;
use crate::model::params::{BOUNCE_PARAMS, PARAMS, ParamError, ParamId, ParamSpec, Params, spec};
use crate::model::units;
use crate::scenario::{Scenario, ScenarioError};

/// Which rows of the parameter table a command takes as flags.
pub trait FlagSet: Clone + Debug + Default + Send + Sync + 'static {
    const SPECS: &'static [ParamSpec];
}

/// The flags of one bounce: every group but the shot's.
#[derive(Clone, Copy, Debug, Default)]
pub struct BounceFlags;

impl FlagSet for BounceFlags {
    const SPECS: &'static [ParamSpec] = BOUNCE_PARAMS;
}

/// Every flag, the shot's included.
#[derive(Clone, Copy, Debug, Default)]
pub struct ShotFlags;

impl FlagSet for ShotFlags {
    const SPECS: &'static [ParamSpec] = PARAMS;
}

/// The starting point given on the command line: a preset, a scenario file, and parameter values as
/// typed (units are parsed by [`FlagArgs::apply`]), for the flags of `F`.
#[derive(Clone, Debug, Default)]
pub struct FlagArgs<F: FlagSet> {
    pub preset: Option<String>,
    pub scenario: Option<PathBuf>,
    pub given: Vec<(ParamId, String)>,
    flags: PhantomData<F>,
}

/// The bounce's flags: `simulate`, the explorer, `critical-angle`, `figure`, `reproduce`.
pub type ParamArgs = FlagArgs<BounceFlags>;
/// Every flag, the shot's included: `shot`, `sweep`, `optimize`.
pub type ShotParamArgs = FlagArgs<ShotFlags>;

/// A bad starting point: a parameter value or a scenario.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    #[error(transparent)]
    Param(#[from] ParamError),
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// An uncertainty (`50±1`) that cannot be read, or given to a command that takes none.
    #[error("{0}")]
    Uncertainty(String),
}

impl<F: FlagSet> FlagArgs<F> {
    /// `base`, then the preset, then the scenario file, then each flag given (flags override the
    /// scenario), every value parsed and checked; the first bad one is the error.
    pub fn apply(&self, base: Params) -> Result<Params, InputError> {
        if let Some((id, _)) = self
            .given
            .iter()
            .find(|(_, text)| split_uncertainty(text).1.is_some())
        {
            return Err(InputError::Uncertainty(format!(
                "--{}: an uncertainty (±) is taken by simulate and sweep only",
                spec(*id).flag
            )));
        }
        Ok(self.apply_uncertain(base)?.0)
    }

    /// A note for each value given as a bare number far outside its parameter's usual range
    /// ([`ParamSpec::bare_note`]): `--cart-mass 10 is read as 10 kg; write 10g for grams`.
    pub fn notes(&self) -> Vec<String> {
        self.given
            .iter()
            .filter_map(|(id, text)| {
                let spec = spec(*id);
                spec.bare_note(&spec.long_flag(), text)
            })
            .collect()
    }

    /// [`ParamArgs::apply`] where a value may carry a standard uncertainty, `50±1` or `50+-1`
    /// (`-3820rpm±200`: a bare uncertainty is in the value's unit); returns the uncertain parameters with
    /// their uncertainties in the base unit.
    pub fn apply_uncertain(&self, mut base: Params) -> Result<(Params, Vec<Spread>), InputError> {
        let mut spreads = Vec::new();
        if let Some(name) = &self.preset {
            base = config::preset(name)?.apply(base);
        }
        if let Some(path) = &self.scenario {
            base = Scenario::load(path)?.apply(base);
        }
        for (id, text) in &self.given {
            let (value, sigma) = parse_uncertain(spec(*id), text).map_err(|e| match e {
                UncertainError::Value(e) => InputError::Param(e),
                spread => InputError::Uncertainty(spread.to_string()),
            })?;
            base.set(*id, value);
            if let Some(sigma) = sigma {
                spreads.push(Spread { id: *id, sigma });
            }
        }
        Ok((base, spreads))
    }
}

fn help_for(spec: &ParamSpec) -> String {
    let unit = spec.bare_symbol();
    let default = units::brief(units::in_unit(spec.default, spec.dimension, unit), 6);
    if unit.is_empty() {
        format!(
            "{} [range {}; default {default}]",
            spec.help,
            spec.range_text()
        )
    } else {
        format!(
            "{} [bare number in {unit}; also {}; range {}; default {default} {unit}]",
            spec.help,
            spec.other_symbols().join(", "),
            spec.range_text()
        )
    }
}

impl<F: FlagSet> Args for FlagArgs<F> {
    fn augment_args(mut cmd: Command) -> Command {
        cmd = cmd
            .arg(
                Arg::new("preset")
                    .long("preset")
                    .value_name("NAME")
                    .help_heading("Scenario")
                    .help("start from a preset (list them with `snapback presets`)"),
            )
            .arg(
                Arg::new("scenario")
                    .long("scenario")
                    .value_name("FILE")
                    .value_parser(clap::value_parser!(PathBuf))
                    .help_heading("Scenario")
                    .help("start from a scenario file (TOML; - reads standard input); parameter flags override its values"),
            );
        for spec in F::SPECS {
            cmd = cmd.arg(
                Arg::new(spec.key)
                    .long(spec.flag)
                    .value_name("VALUE")
                    .allow_hyphen_values(true)
                    .help_heading("Parameters")
                    .help(help_for(spec)),
            );
        }
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl<F: FlagSet> FromArgMatches for FlagArgs<F> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut args = Self::default();
        args.update_from_arg_matches(matches)?;
        Ok(args)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        if let Some(name) = matches.get_one::<String>("preset") {
            self.preset = Some(name.clone());
        }
        if let Some(path) = matches.get_one::<PathBuf>("scenario") {
            self.scenario = Some(path.clone());
        }
        for spec in F::SPECS {
            if let Some(text) = matches.get_one::<String>(spec.key) {
                self.given.retain(|(id, _)| *id != spec.id);
                self.given.push((spec.id, text.clone()));
            }
        }
        Ok(())
    }
}

/// The remedy when a command line fails to parse because a parameter's unit was typed after a space
/// (`--cart-mass 10 g`): `--cart-mass 10 g: write 10g, without a space`.
pub fn spaced_unit(args: &[String]) -> Option<String> {
    args.windows(3).find_map(|w| {
        let flag = w[0].strip_prefix("--")?;
        let spec = PARAMS.iter().find(|s| s.flag == flag)?;
        let remedy = units::spaced_unit(&w[1], &w[2], spec.dimension)?;
        Some(format!("{} {} {}: {remedy}", w[0], w[1], w[2]))
    })
}
