//! `snapback shot`: a stroke on court, from the strings to the opponent's baseline.

use clap::{Args, ValueEnum};

use super::{Failure, ShotParamArgs, emit};
use crate::export;
use crate::model::params::{ParamSpec, spec};
use crate::model::{ParamId, SolveOptions};
use crate::shot;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The contact on the strings, the launch, the flight, the court bounce and the kick.
    #[default]
    Table,
    /// One JSON object: `contact`, `launch`, `net_clearance_m`, `landing_m`, `landing_x_m`,
    /// `flight_time_s`, `in`, `court_bounce`, `kick_height_m` (and `trajectory` with --trajectory).
    Json,
}

#[derive(Clone, Debug, Default, Args)]
pub struct ShotArgs {
    #[command(flatten)]
    pub params: ShotParamArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// With --format json, add the sampled path: `trajectory`, an array of {t (s), x, y (m), vx, vy (m/s)}.
    #[arg(long)]
    pub trajectory: bool,
}

pub use crate::shot::base;

/// Refuses the flags (and a varied parameter) that the frame change and the racquet set on the strings,
/// naming the shot's own.
pub fn refuse_bounce_incidence(
    given: &[(ParamId, String)],
    varied: Option<&ParamSpec>,
) -> Result<(), Failure> {
    let set = [ParamId::Speed, ParamId::Angle, ParamId::Spin];
    let frame = [ParamId::FrameMass, ParamId::FrameNormalMass];
    let ids = || given.iter().map(|(id, _)| *id).chain(varied.map(|s| s.id));
    if let Some(id) = ids().find(|id| set.contains(id)) {
        return Err(Failure::usage(format!(
            "{} is what the strings see, set by the frame change in a shot: give the incoming ball \
             with --ball-speed, --ball-descent, --ball-topspin and the racquet with --racquet-speed, \
             --swing-path, --face-angle",
            spec(id).long_flag()
        )));
    }
    match ids().find(|id| frame.contains(id)) {
        Some(id) => Err(Failure::usage(format!(
            "{} is the racquet's effective mass at the impact point in a shot: give the racquet with \
             --racquet-mass (clamped for an immovable one), --balance, --swing-weight, --twist-weight, \
             --impact",
            spec(id).long_flag()
        ))),
        None => Ok(()),
    }
}

/// Refuses the shot's flags (and a varied shot parameter) where no shot is played; `fix` says how to
/// play one.
pub fn refuse_shot_flags(
    given: &[(ParamId, String)],
    varied: Option<&ParamSpec>,
    fix: &str,
) -> Result<(), Failure> {
    let shot = given
        .iter()
        .map(|(id, _)| spec(*id))
        .chain(varied)
        .find(|s| s.group.is_shot());
    match shot {
        Some(s) => Err(Failure::usage(format!(
            "{} is a shot parameter and only a shot uses it: {fix}",
            s.long_flag()
        ))),
        None => Ok(()),
    }
}

pub fn run(args: &ShotArgs, options: &SolveOptions) -> Result<(), Failure> {
    refuse_bounce_incidence(&args.params.given, None)?;
    let params = args.params.apply(base()).map_err(Failure::usage)?;
    let shot = shot::play_with(&params, args.trajectory, options).map_err(Failure::usage)?;
    let text = match args.format {
        Format::Table => export::shot::table(&shot),
        Format::Json => export::shot::json(&shot),
    };
    emit(&text)
}
