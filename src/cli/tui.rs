//! `snapback tui` (and `snapback` alone): the full-screen explorer, started from the given parameters.

use clap::{Args, ValueEnum};
use ratatui::symbols::Marker;

use super::{Failure, ParamArgs};
use crate::model::Params;
use crate::tui::{self, OpenError, Options, playback};

/// How the charts draw their curves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum MarkerArg {
    /// Braille dots: the finest curves.
    #[default]
    Braille,
    /// One dot per cell, for fonts without braille.
    Dot,
    /// One block per cell, for fonts without braille.
    Block,
}

impl From<MarkerArg> for Marker {
    fn from(arg: MarkerArg) -> Marker {
        match arg {
            MarkerArg::Braille => Marker::Braille,
            MarkerArg::Dot => Marker::Dot,
            MarkerArg::Block => Marker::Block,
        }
    }
}

#[derive(Clone, Debug, Default, Args)]
pub struct TuiArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    /// Chart marker: braille (default), or dot or block for fonts without braille.
    #[arg(long, value_enum, default_value_t = MarkerArg::Braille)]
    pub marker: MarkerArg,
    /// Frames a second while the bounce plays (fewer send fewer bytes over a slow link).
    #[arg(long, default_value_t = playback::DEFAULT_FPS, value_parser = clap::value_parser!(u32).range(1..=60))]
    pub fps: u32,
    /// Write ASCII only (the default when the locale is not UTF-8: LC_ALL, LC_CTYPE, LANG).
    #[arg(long, conflicts_with = "unicode")]
    pub ascii: bool,
    /// Write Unicode (braille, box drawing, Greek letters) whatever the locale says.
    #[arg(long)]
    pub unicode: bool,
}

pub fn run(args: &TuiArgs) -> Result<(), Failure> {
    let params = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let options = Options {
        params,
        marker: args.marker.into(),
        color: !tui::no_color_requested(),
        ascii: args.ascii || !(args.unicode || tui::locale::utf8_here()),
        fps: args.fps,
    };
    tui::open(options).map_err(|e| match e {
        OpenError::NotATerminal | OpenError::Solve(_) => Failure::usage(e),
        OpenError::Io(_) => Failure {
            message: e.to_string(),
            status: 1,
        },
    })
}
