//! The command line: clap definitions and the headless commands. `main` only parses and dispatches.

mod completions;
mod critical_angle;
mod figure;
mod fit;
mod man;
mod optimize;
mod params_args;
mod presets;
mod progress;
mod reproduce;
mod shot;
mod simulate;
mod sweep;
mod tui;

use std::io::Write;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::model::budget::COMMAND_WORK;
use crate::model::{SolveOptions, Work};

pub use params_args::{InputError, ParamArgs, ShotParamArgs, spaced_unit};

/// Explore a ball bouncing obliquely off a surface that can move sideways (Cross, Am. J. Phys. 78, 2010).
#[derive(Debug, Parser)]
#[command(name = "snapback", version, about, long_about = None, args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Commands>,
    /// Without a command: the explorer, started from these flags (`snapback --preset light-1g`).
    #[command(flatten)]
    pub explorer: tui::TuiArgs,
}

#[derive(Debug, Subcommand)]
pub enum Commands {
    /// Solve one bounce and print the outcome, the phases and the energy budget.
    Simulate(simulate::SimulateArgs),
    /// Open the full-screen explorer (also what `snapback` alone does).
    Tui(tui::TuiArgs),
    /// List the presets (use one with --preset NAME on any command).
    Presets(presets::PresetsArgs),
    /// Solve one bounce per value of a parameter and print the outcomes as CSV, JSON or JSON Lines.
    Sweep(sweep::SweepArgs),
    /// The angle below which the ball slides one way for the whole contact (Eq. (7) and the full model), and the angle where it first grips.
    CriticalAngle(critical_angle::CriticalAngleArgs),
    /// The value of a parameter that maximises (or minimises) an outcome, and the bounce there.
    Optimize(optimize::OptimizeArgs),
    /// Check every number the paper prints (assets/claims.md) against the model.
    #[command(
        after_help = "Exit status: 0 when every claim is reproduced, close, or differs for a \
        reason shown in its note; 1 when a claim differs without a demonstrated reason or cannot be \
        computed (flags far from the paper's parameters: the rows say which claims and why); 2 on bad \
        input."
    )]
    Reproduce(reproduce::ReproduceArgs),
    /// Fit free parameters to measured rebounds (CSV): values, standard errors, 95% intervals.
    Fit(fit::FitArgs),
    /// Draw the paper's Fig. 2 or Fig. 3 as SVG, at the given parameters.
    Figure(figure::FigureArgs),
    /// Play a stroke on court: the strings in the racquet's frame, the flight with drag and Magnus
    /// lift, the bounce on the court and the kick at the opponent's baseline.
    Shot(shot::ShotArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    Completions(completions::CompletionsArgs),
    /// Print the manual page (roff): snapback(1), or snapback-COMMAND(1) for one command.
    Man(man::ManArgs),
}

/// A failure to report: the message for stderr and the exit status.
#[derive(Debug)]
pub struct Failure {
    pub message: String,
    pub status: u8,
}

impl Failure {
    /// Bad input from the user: exit status 2.
    pub fn usage(message: impl std::fmt::Display) -> Self {
        Failure {
            message: message.to_string(),
            status: 2,
        }
    }
}

/// The notes on the parameter values given (a bare number far outside its usual range), for stderr.
fn notes(cli: &Cli) -> Vec<String> {
    match &cli.command {
        Some(Commands::Simulate(args)) => args.params.notes(),
        Some(Commands::Tui(args)) => args.params.notes(),
        Some(Commands::Sweep(args)) => args.params.notes(),
        Some(Commands::CriticalAngle(args)) => args.params.notes(),
        Some(Commands::Optimize(args)) => args.params.notes(),
        Some(Commands::Reproduce(args)) => args.params.notes(),
        Some(Commands::Figure(args)) => args.params.notes(),
        Some(Commands::Fit(args)) => args.params.notes(),
        Some(Commands::Shot(args)) => args.params.notes(),
        Some(Commands::Presets(_) | Commands::Completions(_) | Commands::Man(_)) => Vec::new(),
        None => cli.explorer.params.notes(),
    }
}

/// Runs the parsed command line.
pub fn run(cli: Cli) -> ExitCode {
    let notes = notes(&cli);
    let result = match cli.command {
        Some(Commands::Simulate(args)) => headless(Work::unlimited(), |o| simulate::run(&args, o)),
        Some(Commands::Tui(args)) => tui::run(&args),
        Some(Commands::Presets(args)) => headless(Work::unlimited(), |o| presets::run(&args, o)),
        Some(Commands::Sweep(args)) => headless(Work::unlimited(), |o| sweep::run(&args, o)),
        Some(Commands::CriticalAngle(args)) => headless(Work::limited(COMMAND_WORK), |o| {
            critical_angle::run(&args, o)
        }),
        Some(Commands::Optimize(args)) => headless(Work::unlimited(), |o| optimize::run(&args, o)),
        Some(Commands::Reproduce(args)) => {
            headless(Work::limited(COMMAND_WORK), |o| reproduce::run(&args, o))
        }
        Some(Commands::Figure(args)) => {
            headless(Work::limited(COMMAND_WORK), |o| figure::run(&args, o))
        }
        Some(Commands::Fit(args)) => headless(Work::unlimited(), |o| fit::run(&args, o)),
        Some(Commands::Shot(args)) => headless(Work::unlimited(), |o| shot::run(&args, o)),
        Some(Commands::Completions(args)) => completions::run(&args),
        Some(Commands::Man(args)) => man::run(&args),
        None => tui::run(&cli.explorer),
    };
    match result {
        Ok(()) => {
            // After the output, and only when the command ran: bad input stays one line on stderr.
            for note in notes {
                let _ = writeln!(std::io::stderr(), "note: {note}");
            }
            ExitCode::SUCCESS
        }
        Err(failure) => {
            let _ = writeln!(std::io::stderr(), "error: {}", failure.message);
            ExitCode::from(failure.status)
        }
    }
}

/// A command without the explorer, watched by [`progress::watch`]: its solves share `work` (a limit
/// for a command whose bounces the program fixes) and stop at the first Ctrl-C; interrupted, it fails
/// with status 130 whatever it was doing.
fn headless(
    work: Work,
    command: impl FnOnce(&SolveOptions) -> Result<(), Failure>,
) -> Result<(), Failure> {
    let cancelled = progress::interrupted;
    let options = SolveOptions {
        work: Some(&work),
        ..SolveOptions::cancelled_by(&cancelled)
    };
    let result = progress::watch(&work, || command(&options));
    if progress::interrupted() {
        return Err(Failure {
            message: "interrupted".into(),
            status: progress::INTERRUPTED,
        });
    }
    result
}

/// Writes `text` to stdout; a closed pipe (`| head`) is not an error.
pub(crate) fn emit(text: &str) -> Result<(), Failure> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure {
            message: format!("cannot write output: {e}"),
            status: 1,
        }),
        _ => Ok(()),
    }
}
