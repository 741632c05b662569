use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    snapback::cli::run(snapback::cli::Cli::parse())
}
