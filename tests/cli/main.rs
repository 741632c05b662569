//! The headless commands run as a user runs them: formats, units, exit statuses and errors, scenarios
//! and the user's configuration, fitting, the fuzz campaign and its regressions, and README.md's commands.

#[path = "../support"]
mod support {
    pub mod bin;
    pub mod cpu;
    #[allow(dead_code)] // config.rs uses only some of the pseudo-terminal helpers
    pub mod pty;
    pub mod rng;
}

mod cli;
mod cli_analysis;
mod cli_conventions;
mod config;
mod figure_params;
mod fit;
mod fuzz;
mod hostile;
mod interrupt;
mod readme;
mod scenario;
mod scenario_input;
mod sweep_stream;
mod uncertainty;
