//! The parameter flags (`--angle`, `--cart-mass`, ...), generated from the parameter table so that
//! every command takes the same flags with the same help.

use clap::{Arg, ArgMatches, Args, Command, FromArgMatches};

use crate::model::params::{PARAMS, ParamError, ParamId, Params, spec};
use crate::model::units;

/// The parameter values given on the command line, as typed (units are parsed by [`ParamArgs::apply`]).
#[derive(Clone, Debug, Default)]
pub struct ParamArgs {
    pub given: Vec<(ParamId, String)>,
}

impl ParamArgs {
    /// `base` with every given value parsed and checked; the first bad one is the error.
    pub fn apply(&self, mut base: Params) -> Result<Params, ParamError> {
        for (id, text) in &self.given {
            base.set(*id, spec(*id).parse(text)?);
        }
        Ok(base)
    }
}

fn help_for(spec: &crate::model::params::ParamSpec) -> String {
    let unit = spec.dimension.base_symbol();
    let default = units::brief(spec.default, 6);
    let accepted: Vec<&str> = spec
        .dimension
        .units()
        .iter()
        .flat_map(|u| u.symbols.iter().copied())
        .collect();
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
            accepted[1..].join(", "),
            spec.range_text()
        )
    }
}

impl Args for ParamArgs {
    fn augment_args(mut cmd: Command) -> Command {
        for spec in PARAMS {
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

impl FromArgMatches for ParamArgs {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut args = ParamArgs::default();
        args.update_from_arg_matches(matches)?;
        Ok(args)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        for spec in PARAMS {
            if let Some(text) = matches.get_one::<String>(spec.key) {
                self.given.retain(|(id, _)| *id != spec.id);
                self.given.push((spec.id, text.clone()));
            }
        }
        Ok(())
    }
}
