//! `snapback completions SHELL`: the shell's completion script, on standard output.

use clap::{Args, CommandFactory};
use clap_complete::Shell;

use super::{Cli, Failure, emit};

#[derive(Clone, Debug, Args)]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum, value_name = "SHELL")]
    pub shell: Shell,
}

pub fn run(args: &CompletionsArgs) -> Result<(), Failure> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut Cli::command(), "snapback", &mut script);
    emit(&String::from_utf8_lossy(&script))
}
