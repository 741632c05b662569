//! `snapback tui` (and `snapback` alone): the full-screen explorer, started from the given parameters. A
//! shot preset, a scenario with a shot in it or any shot flag starts it exploring that shot, from the
//! same parameters `snapback shot` would play.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use ratatui::symbols::Marker;

use super::fit::read_data;
use super::{Failure, ShotParamArgs, shot};
pub use crate::config::Theme as ThemeArg;
use crate::config::{self, Charset};
use crate::model::Params;
use crate::model::params::spec;
use crate::scenario::Scenario;
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

impl From<config::Marker> for MarkerArg {
    fn from(marker: config::Marker) -> MarkerArg {
        match marker {
            config::Marker::Braille => MarkerArg::Braille,
            config::Marker::Dot => MarkerArg::Dot,
            config::Marker::Block => MarkerArg::Block,
        }
    }
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
    pub params: ShotParamArgs,
    /// Chart marker: braille (default), or dot or block for fonts without braille.
    #[arg(long, value_enum)]
    pub marker: Option<MarkerArg>,
    /// Colours for a dark (default) or a light terminal background.
    #[arg(long, value_enum)]
    pub theme: Option<ThemeArg>,
    /// Frames a second while the bounce plays (fewer send fewer bytes over a slow link; default 12).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=60))]
    pub fps: Option<u32>,
    /// Write ASCII only (the default when the locale is not UTF-8: LC_ALL, LC_CTYPE, LANG).
    #[arg(long, conflicts_with = "unicode")]
    pub ascii: bool,
    /// Write Unicode (braille, box drawing, Greek letters) whatever the locale says.
    #[arg(long)]
    pub unicode: bool,
    /// Measurements to show beside the model, and to fit with f and F: CSV as for `snapback fit`
    /// (- reads standard input; the keys are then read from the terminal).
    #[arg(long, value_name = "FILE")]
    pub data: Option<PathBuf>,
}

/// Where the explorer starts, and whether it explores a shot: refused as `snapback shot` refuses them,
/// the incidence flags and a racquet that never meets the ball.
fn start(args: &ShotParamArgs) -> Result<(Params, bool), Failure> {
    let params = args.apply(Params::default()).map_err(Failure::usage)?;
    // Both load: `apply` has read them without error.
    let shot = args.given.iter().any(|(id, _)| spec(*id).group.is_shot())
        || args
            .preset
            .as_deref()
            .is_some_and(|name| config::preset(name).is_ok_and(|s| s.is_shot()))
        || args
            .scenario
            .as_deref()
            .is_some_and(|path| Scenario::load(path).is_ok_and(|s| s.is_shot()));
    if !shot {
        return Ok((params, false));
    }
    shot::refuse_bounce_incidence(&args.given, None)?;
    let params = args.apply(shot::base()).map_err(Failure::usage)?;
    tui::shot::strings_params(&params).map_err(Failure::usage)?;
    Ok((params, true))
}

pub fn run(args: &TuiArgs) -> Result<(), Failure> {
    let (params, shot) = start(&args.params)?;
    // The user's config gives the defaults; a flag on the command line wins.
    let config = config::load().map_err(Failure::usage)?;
    let marker = args
        .marker
        .or(config.marker.map(MarkerArg::from))
        .unwrap_or_default();
    let ascii = if args.ascii {
        true
    } else if args.unicode {
        false
    } else {
        match config.charset {
            Some(Charset::Ascii) => true,
            Some(Charset::Unicode) => false,
            Some(Charset::Auto) | None => !tui::locale::utf8_here(),
        }
    };
    let data = args.data.as_deref().map(read_data).transpose()?;
    let options = Options {
        params,
        marker: marker.into(),
        color: !tui::no_color_requested(),
        light: args.theme.or(config.theme).unwrap_or_default() == ThemeArg::Light,
        ascii,
        fps: args.fps.or(config.fps).unwrap_or(playback::DEFAULT_FPS),
        shot,
        data,
        notes: args.params.notes(),
    };
    tui::open(options).map_err(|e| match e {
        OpenError::NotATerminal | OpenError::Solve(_) => Failure::usage(e),
        OpenError::Io(_) => Failure {
            message: e.to_string(),
            status: 1,
        },
    })
}
