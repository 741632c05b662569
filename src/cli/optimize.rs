//! `snapback optimize`: the value of one parameter that maximises an outcome, and the bounce there.

use std::fmt::Write;

use clap::{Args, ValueEnum};

use super::{Failure, ShotParamArgs, emit, shot};
use crate::analysis::optimize::{self, DEFAULT_SCAN, Objective};
use crate::analysis::shots::{self, ShotObjective};
use crate::analysis::{Span, span};
use crate::export;
use crate::model::units;
use crate::model::{Params, SolveOptions};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The optimum, then the bounce there as `simulate` prints it.
    #[default]
    Table,
    /// One JSON object: `vary`, `value`, `unit`, `objective`, `objective_value`, `objective_unit`,
    /// `minimize`, `scan`, `log`, `exhaustive`, `bounce`. For a whole-number parameter (chain) every
    /// whole number is solved: `exhaustive` is true, `scan` is how many, `log` false.
    Json,
}

#[derive(Clone, Debug, Args)]
pub struct OptimizeArgs {
    #[command(flatten)]
    pub params: ShotParamArgs,
    /// The parameter to vary: a parameter flag without dashes (stiffness, cart-mass, angle, ...).
    #[arg(long, value_name = "PARAM")]
    pub vary: String,
    /// One end of the range (a unit suffix is allowed: 1kN/m).
    #[arg(long, value_name = "A", allow_hyphen_values = true)]
    pub from: String,
    /// The other end.
    #[arg(long, value_name = "B", allow_hyphen_values = true)]
    pub to: String,
    /// What to maximise: omega2 (rad/s), ex, vx2 (m/s) or theta2 (deg) of one bounce; or of a shot on
    /// court (`snapback shot`): kick_height, net_clearance, landing (m), launch_speed (m/s) or
    /// launch_topspin (rpm), among the shots that land in.
    #[arg(long, value_name = "NAME", default_value = "omega2")]
    pub objective: String,
    /// With a shot objective, count the shots that land out too.
    #[arg(long)]
    pub allow_out: bool,
    /// Minimise instead of maximise.
    #[arg(long)]
    pub minimize: bool,
    /// Scan geometrically (automatic when the range spans two decades or more).
    #[arg(long)]
    pub log: bool,
    /// Points of the scan that precedes Brent's method (at least 3); a whole-number parameter (chain)
    /// is not scanned: every whole number from A to B is solved.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_SCAN.to_string(), allow_hyphen_values = true)]
    pub scan: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

pub fn run(args: &OptimizeArgs, options: &SolveOptions) -> Result<(), Failure> {
    let span = Span::parse(&args.vary, &args.from, &args.to, args.log).map_err(Failure::usage)?;
    let scan = span::parse_count("--scan", &args.scan, 3).map_err(Failure::usage)?;
    if let Some(objective) = ShotObjective::named(&args.objective) {
        return run_shot(args, &span, objective, scan, options);
    }
    let fix = "choose a shot objective (kick_height, net_clearance, landing, launch_speed, launch_topspin)";
    shot::refuse_shot_flags(&args.params.given, Some(span.spec), fix)?;
    if args.allow_out {
        return Err(Failure::usage(format!(
            "--allow-out needs a shot objective: {fix}"
        )));
    }
    let base = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let objective = Objective::parse(&args.objective).map_err(Failure::usage)?;
    let best = optimize::optimize_with(&base, &span, objective, args.minimize, scan, options)
        .map_err(Failure::usage)?;
    crate::model::reportable::reportable(&best.bounce).map_err(Failure::usage)?;
    let spec = span.spec;
    let unit = spec.dimension.base_symbol();
    // What was solved: the scan points, or every whole number of the range.
    let solved = if best.exhaustive {
        (best.span.to - best.span.from).abs() as usize + 1
    } else {
        scan
    };
    let text = match args.format {
        Format::Json => {
            let doc = serde_json::json!({
                "vary": spec.flag,
                "value": best.value,
                "unit": unit,
                "objective": objective.name(),
                "objective_value": best.objective_value,
                "objective_unit": objective.unit(),
                "minimize": args.minimize,
                "scan": solved,
                "log": best.span.log,
                "exhaustive": best.exhaustive,
                "bounce": export::json::value(&best.bounce),
            });
            let mut text =
                serde_json::to_string_pretty(&doc).expect("JSON values always serialize");
            text.push('\n');
            text
        }
        Format::Table => {
            let mut out = String::new();
            let goal = if args.minimize {
                "minimises"
            } else {
                "maximises"
            };
            let how = if best.exhaustive {
                format!(
                    "every whole number from {} to {}: {solved} solved",
                    units::brief(best.span.from, 10),
                    units::brief(best.span.to, 10)
                )
            } else {
                format!(
                    "{scan} scan points{}, then Brent's method",
                    if best.span.log { ", geometric" } else { "" }
                )
            };
            let _ = writeln!(
                out,
                "The {} that {} {} ({how})",
                spec.label,
                goal,
                objective.name(),
            );
            // The value in its base unit, and as people read it where that differs.
            let base = format!("{} {unit}", units::brief(best.value, 10))
                .trim_end()
                .to_string();
            let shown = spec.show(best.value).to_string();
            let _ = writeln!(
                out,
                "  {:<24}{}",
                format!("{} {}", spec.label, spec.symbol),
                if shown.trim() == base.trim() {
                    base
                } else {
                    format!("{base} ({shown})")
                }
            );
            let _ = writeln!(
                out,
                "  {:<24}{} {}\n",
                objective.name(),
                units::brief(best.objective_value, 8),
                objective.unit()
            );
            out.push_str(&export::table::summary(&best.bounce));
            out
        }
    };
    emit(&text)
}

/// The value that maximises a shot outcome, and the shot there (as `snapback shot` prints it).
fn run_shot(
    args: &OptimizeArgs,
    span: &Span,
    objective: ShotObjective,
    scan: usize,
    options: &SolveOptions,
) -> Result<(), Failure> {
    shot::refuse_bounce_incidence(&args.params.given, Some(span.spec))?;
    if span.spec.integer {
        return Err(Failure::usage(format!(
            "--vary {} takes whole numbers; a shot objective needs a continuous parameter",
            span.spec.flag
        )));
    }
    let base = args.params.apply(shot::base()).map_err(Failure::usage)?;
    let best = shots::optimize(
        &base,
        span,
        objective,
        args.minimize,
        args.allow_out,
        scan,
        options,
    )
    .map_err(Failure::usage)?;
    let spec = span.spec;
    let text = match args.format {
        Format::Json => {
            let doc = serde_json::json!({
                "vary": spec.flag,
                "value": best.value,
                "unit": spec.dimension.base_symbol(),
                "objective": objective.name(),
                "objective_value": best.objective_value,
                "objective_unit": objective.unit(),
                "minimize": args.minimize,
                "allow_out": args.allow_out,
                "scan": scan,
                "log": best.span.log,
                "exhaustive": false,
                "shot": export::shot::value(&best.shot),
            });
            let mut text =
                serde_json::to_string_pretty(&doc).expect("JSON values always serialize");
            text.push('\n');
            text
        }
        Format::Table => {
            let goal = if args.minimize {
                "minimises"
            } else {
                "maximises"
            };
            let among = if args.allow_out {
                ""
            } else {
                " among the shots that land in"
            };
            let mut out = format!(
                "The {} that {goal} {}{among} ({scan} scan points{}, then Brent's method)\n",
                spec.label,
                objective.name(),
                if best.span.log { ", geometric" } else { "" }
            );
            let _ = writeln!(
                out,
                "  {:<24}{}",
                format!("{} {}", spec.label, spec.symbol),
                spec.show(best.value)
            );
            let _ = writeln!(
                out,
                "  {:<24}{} {}\n",
                objective.name(),
                units::brief(best.objective_value, 8),
                objective.unit()
            );
            out.push_str(&export::shot::table(&best.shot));
            out
        }
    };
    emit(&text)
}
