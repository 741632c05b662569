//! `snapback man [COMMAND]`: the manual page, as roff on standard output: snapback(1), or
//! snapback-COMMAND(1) for one command.

use clap::{Args, CommandFactory};

use super::{Cli, Failure, emit};

#[derive(Clone, Debug, Args)]
pub struct ManArgs {
    /// A command (simulate, sweep, ...) for its own page, snapback-COMMAND(1).
    #[arg(value_name = "COMMAND")]
    pub command: Option<String>,
}

pub fn run(args: &ManArgs) -> Result<(), Failure> {
    let mut cli = Cli::command().disable_help_subcommand(true);
    cli.build();
    let page = match &args.command {
        None => cli,
        Some(name) => cli.find_subcommand(name).cloned().ok_or_else(|| {
            let names: Vec<&str> = cli.get_subcommands().map(|c| c.get_name()).collect();
            Failure::usage(format!(
                "COMMAND must be one of {}; got {name}",
                names.join(", ")
            ))
        })?,
    };
    let mut roff = Vec::new();
    clap_mangen::Man::new(page)
        .source(concat!("snapback ", env!("CARGO_PKG_VERSION")))
        .render(&mut roff)
        .map_err(|e| Failure {
            message: format!("cannot render the manual page: {e}"),
            status: 1,
        })?;
    emit(&String::from_utf8_lossy(&roff))
}
