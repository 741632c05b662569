//! `snapback figure fig2|fig3 --out FILE.svg`: the paper's Fig. 2 or Fig. 3 as SVG, at the given
//! parameters.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;

use super::{Failure, ParamArgs};
use crate::analysis::figures::Which;
use crate::export::svg::{self, SvgError};
use crate::model::{Params, SolveOptions};
use crate::output::{self, Replace, WriteError};

#[derive(Clone, Debug, Args)]
pub struct FigureArgs {
    /// The bounce: Fig. 3 draws it beside the paper's other carts, Fig. 2 its omega2 against theta1 for its spin and the comparison spin (default: the paper's Fig. 3(c) case).
    #[command(flatten)]
    pub params: ParamArgs,
    /// fig2 (omega2 against theta1, for omega1 = 0 and the given spin) or fig3 (F, X and omega against t).
    #[arg(value_name = "FIGURE")]
    pub which: String,
    /// The SVG file to write (SVG is the one format figure writes): a symlink is written through, a
    /// device or FIFO written into, `-` is standard output. A read-only file is kept unless --force.
    #[arg(long, value_name = "FILE.svg")]
    pub out: PathBuf,
    /// Replace --out even when it is a read-only file (it stays read-only).
    #[arg(long)]
    pub force: bool,
}

/// The extensions `--out` may end in.
const EXTENSIONS: [&str; 1] = ["svg"];

pub fn run(args: &FigureArgs, options: &SolveOptions) -> Result<(), Failure> {
    let extension = args
        .out
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase());
    // A stream (`-`, a device, a FIFO) has no name to say its format.
    if !output::is_stream(&args.out) && !extension.is_some_and(|e| EXTENSIONS.contains(&e.as_str()))
    {
        return Err(Failure::usage(format!(
            "--out must end in .{} (the one format figure writes); got {}",
            EXTENSIONS.join(", ."),
            args.out.display()
        )));
    }
    let which = Which::parse(&args.which).map_err(Failure::usage)?;
    let base = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let figure = which.data_with(&base, options).map_err(Failure::usage)?;
    let replace = if args.force {
        Replace::Any
    } else {
        Replace::Writable
    };
    match svg::write(&figure, &args.out, replace) {
        Err(e @ SvgError::Write(WriteError::ReadOnly { .. })) => {
            Err(Failure::usage(format!("{e} (--force replaces it)")))
        }
        Err(e) => Err(Failure::usage(e)),
        // Said on stderr: stdout may be where the figure went (`--out -`, `--out /dev/stdout`).
        Ok(()) => {
            let _ = writeln!(std::io::stderr(), "wrote {}", args.out.display());
            Ok(())
        }
    }
}
