//! `snapback figure fig2|fig3 --out FILE.svg`: the paper's Fig. 2 or Fig. 3 as SVG.

use std::path::PathBuf;

use clap::Args;

use super::{Failure, ParamArgs, emit};
use crate::analysis::figures::Which;
use crate::export::svg;
use crate::model::Params;

#[derive(Clone, Debug, Args)]
pub struct FigureArgs {
    /// The ball, speed, friction and impact (default: the paper's Sec. III); the figure sets each curve's cart, angle and spin.
    #[command(flatten)]
    pub params: ParamArgs,
    /// fig2 (omega2 against theta1, six curves) or fig3 (F, X and omega against t at 60 deg).
    #[arg(value_name = "FIGURE")]
    pub which: String,
    /// The SVG file to write.
    #[arg(long, value_name = "FILE.svg")]
    pub out: PathBuf,
}

pub fn run(args: &FigureArgs) -> Result<(), Failure> {
    let which = Which::parse(&args.which).map_err(Failure::usage)?;
    let base = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let figure = which.data(&base).map_err(Failure::usage)?;
    svg::write(&figure, &args.out).map_err(Failure::usage)?;
    emit(&format!("wrote {}\n", args.out.display()))
}
