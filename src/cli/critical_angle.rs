//! `snapback critical-angle`: the angle below which the ball slides one way for the whole contact, from
//! Eq. (7) and from the full model for the given cart, and the angle where the ball first grips.

use std::fmt::Write;

use clap::{Args, ValueEnum};

use super::{Failure, ParamArgs, emit};
use crate::analysis::critical::{self, Critical};
use crate::model::params::{ParamId, spec};
use crate::model::{Params, SolveOptions};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Readable lines.
    #[default]
    Table,
    /// One JSON object: `eq7_deg`, `full_model_deg`, `first_grip_deg` (null when there is no such angle), their regimes (`eq7`, `full_model`, `first_grip`) and the parameters.
    Json,
}

#[derive(Clone, Debug, Default, Args)]
pub struct CriticalAngleArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

fn describe(c: Critical) -> String {
    match c {
        Critical::At(deg) => format!("{deg:.2} deg"),
        Critical::AlwaysSlides => "none: the ball slides throughout at every angle".into(),
        Critical::NeverSlidesThroughout => {
            "none: the ball does not slide throughout even at glancing incidence".into()
        }
        Critical::Inapplicable => {
            "does not apply: r omega1 >= v1, the contact point never arrives moving forward".into()
        }
    }
}

fn describe_grip(c: Critical) -> String {
    match c {
        Critical::AlwaysSlides => "none: the ball grips at no angle".into(),
        Critical::NeverSlidesThroughout => "none: the ball grips even at glancing incidence".into(),
        _ => describe(c),
    }
}

pub fn run(args: &CriticalAngleArgs, options: &SolveOptions) -> Result<(), Failure> {
    if args
        .params
        .given
        .iter()
        .any(|(id, _)| *id == ParamId::Angle)
    {
        return Err(Failure::usage(
            "--angle is what critical-angle finds: give the other parameters, not the incidence angle",
        ));
    }
    let params = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let eq7 = critical::eq7(&params);
    let critical::Thresholds {
        slides_throughout: full,
        first_grip,
    } = critical::thresholds_with(&params, options).map_err(Failure::usage)?;
    let text = match args.format {
        Format::Json => {
            let doc = serde_json::json!({
                "eq7_deg": eq7.degrees(),
                "full_model_deg": full.degrees(),
                "first_grip_deg": first_grip.degrees(),
                "eq7": eq7,
                "full_model": full,
                "first_grip": first_grip,
                "params": params,
            });
            let mut text =
                serde_json::to_string_pretty(&doc).expect("JSON values always serialize");
            text.push('\n');
            text
        }
        Format::Table => {
            let shown = |id| spec(id).show(params.get(id));
            let mut out = String::new();
            let _ = writeln!(
                out,
                "Critical angle of incidence: below it the ball slides one way for the whole contact"
            );
            let _ = writeln!(
                out,
                "  v1 = {}, omega1 = {}, mu = {}, alpha = {}, e_y = {}; cart M = {}, k = {}",
                shown(ParamId::Speed),
                shown(ParamId::Spin),
                shown(ParamId::Mu),
                shown(ParamId::Alpha),
                shown(ParamId::Ey),
                shown(ParamId::CartMass),
                shown(ParamId::Stiffness)
            );
            let _ = writeln!(out, "  {:<26}{}", "Eq. (7), rigid surface", describe(eq7));
            let _ = writeln!(out, "  {:<26}{}", "full model, this cart", describe(full));
            let _ = writeln!(
                out,
                "  {:<26}{}",
                "first grip, this cart",
                describe_grip(first_grip)
            );
            if let (Some(a), Some(b)) = (eq7.degrees(), full.degrees()) {
                let _ = writeln!(out, "  {:<26}{:+.2} deg", "full model - Eq. (7)", b - a);
            }
            out
        }
    };
    emit(&text)
}
