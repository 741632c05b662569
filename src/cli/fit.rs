//! `snapback fit`: the free parameters that best explain measured rebounds, with their uncertainties.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use serde_json::{Map, Value, json};

use super::{Failure, ParamArgs, emit};
use crate::analysis::fit::{self, Fit, Options, data, free, shown};
use crate::input;
use crate::model::Params;
use crate::model::params::spec;
use crate::model::units;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The fitted parameters with standard errors and 95% intervals in the explorer's units, the fit
    /// statistics, the correlations and every row beside the model.
    #[default]
    Table,
    /// One JSON object: `free` {key: {value, stderr, ci95}} in SI units, `chi2`, `dof`, `rms`,
    /// `correlation` (in the order of `order`), `rows` (`line`, `measured`, `model`, `residual`),
    /// `converged`, `undetermined`.
    Json,
}

#[derive(Clone, Debug, Args)]
pub struct FitArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    /// The measurements: CSV with a header row; columns named by parameter flags (angle, speed, spin,
    /// ...; unit suffixes allowed in the cells) give each row's conditions, columns omega2 (rad/s),
    /// omega2_rpm, vx2, vy2, speed2 (m/s), theta2_deg, ex the measured values, sigma_<name> their
    /// standard uncertainties. - reads standard input.
    #[arg(long, value_name = "FILE")]
    pub data: PathBuf,
    /// The parameters to fit, comma separated flags (cart-mass,stiffness,mu); the others stay as the
    /// preset, scenario and flags set them, and their values are where the fit starts.
    #[arg(long, value_name = "PARAM[,PARAM...]")]
    pub free: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

pub fn run(args: &FitArgs) -> Result<(), Failure> {
    let base = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let data = read_data(&args.data)?;
    let free = free::parse_list(&args.free, &data.conditions).map_err(Failure::usage)?;
    let fit = fit::fit(&base, &free, &data, &Options::default()).map_err(Failure::usage)?;
    let text = match args.format {
        Format::Table => table(&fit, &data),
        Format::Json => format!("{:#}\n", json(&fit)),
    };
    emit(&text)
}

/// The measurements in `path` (standard input for `-`): a file that cannot be read, or a bad cell, is an
/// error naming file, line and column. The explorer's `--data` reads them so too.
pub(super) fn read_data(path: &Path) -> Result<data::Dataset, Failure> {
    let origin = if input::is_stdin(path) {
        input::STDIN_NAME.to_string()
    } else {
        path.display().to_string()
    };
    let text = input::read_text(path).map_err(|e| Failure::usage(format!("{origin}: {e}")))?;
    data::parse(&text, &origin).map_err(Failure::usage)
}

/// An optional number as JSON (`null` for none).
fn maybe(x: Option<f64>) -> Value {
    x.map_or(Value::Null, Value::from)
}

/// The fit as JSON, SI units, parameters under their scenario keys.
pub fn json(fit: &Fit) -> Value {
    let mut free = Map::new();
    for f in &fit.free {
        free.insert(
            spec(f.id).key.to_string(),
            json!({
                "value": f.value,
                "stderr": maybe(f.stderr),
                "ci95": f.ci95.map_or(Value::Null, |(lo, hi)| json!([lo, hi])),
                "unit": spec(f.id).dimension.base_symbol(),
            }),
        );
    }
    let rows: Vec<Value> = fit
        .rows
        .iter()
        .map(|row| {
            let pick = |value: &dyn Fn(&fit::Compared) -> f64| {
                row.values
                    .iter()
                    .map(|c| (c.quantity.name().to_string(), Value::from(value(c))))
                    .collect::<Map<_, _>>()
            };
            json!({
                "line": row.line,
                "measured": pick(&|c| c.measured),
                "model": pick(&|c| c.model),
                "residual": pick(&|c| c.model - c.measured),
            })
        })
        .collect();
    json!({
        "free": free,
        "order": fit.free.iter().map(|f| spec(f.id).key).collect::<Vec<_>>(),
        "chi2": fit.chi2,
        "dof": fit.dof,
        "rms": fit.rms,
        "absolute_sigma": fit.absolute_sigma,
        "correlation": fit.correlation.iter()
            .map(|r| r.iter().map(|&c| maybe(c)).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
        "rows": rows,
        "converged": fit.converged,
        "undetermined": fit.undetermined().iter().map(|&id| spec(id).key).collect::<Vec<_>>(),
    })
}

/// The fit as text in the explorer's units.
pub fn table(fit: &Fit, data: &data::Dataset) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "fit to {}: {} rows, {} measurements, {} free parameters",
        data.origin,
        data.rows.len(),
        data.measurements(),
        fit.free.len()
    );
    let _ = writeln!(
        out,
        "\n  {:<22} {:>12} {:>10}  {:<24} unit",
        "parameter", "value", "stderr", "95% interval"
    );
    for f in &fit.free {
        let s = spec(f.id);
        let name = format!("{} ({})", s.flag, s.symbol);
        let (stderr, interval) = match (f.stderr, f.ci95) {
            (Some(se), Some((lo, hi))) => (
                shown(f.id, se, Some(se)),
                format!(
                    "[{}, {}]",
                    shown(f.id, lo, Some(se)),
                    shown(f.id, hi, Some(se))
                ),
            ),
            _ => ("-".into(), "not determined by the data".into()),
        };
        let line = format!(
            "  {name:<22} {:>12} {stderr:>10}  {interval:<24} {}",
            shown(f.id, f.value, f.stderr),
            s.display_unit
        );
        let _ = writeln!(out, "{}", line.trim_end());
    }
    let scale = if fit.absolute_sigma {
        "the data's sigmas"
    } else {
        "scaled by chi2/dof"
    };
    let _ = writeln!(
        out,
        "\nchi2 {}  dof {}  rms {}  ({scale}); {}",
        units::brief(fit.chi2, 4),
        fit.dof,
        units::brief(fit.rms, 3),
        if fit.converged {
            "converged"
        } else {
            "NOT converged"
        }
    );
    let undetermined = fit.undetermined();
    if !undetermined.is_empty() {
        let names: Vec<_> = undetermined.iter().map(|&id| spec(id).flag).collect();
        let _ = writeln!(
            out,
            "the data cannot determine {}: set it with its flag, or add rows in which it changes the outcome",
            names.join(", ")
        );
    }
    if fit.free.len() > 1 {
        let _ = writeln!(out, "\ncorrelation");
        for (f, row) in fit.free.iter().zip(&fit.correlation) {
            let _ = write!(out, "  {:<14}", spec(f.id).flag);
            for c in row {
                let _ = write!(out, " {:>6}", c.map_or("-".into(), |c| format!("{c:.2}")));
            }
            out.push('\n');
        }
    }
    let _ = writeln!(
        out,
        "\n  {:>5}  {:<11} {:>10} {:>10} {:>9}",
        "line", "quantity", "measured", "model", "residual"
    );
    for row in &fit.rows {
        for c in &row.values {
            let label = match c.quantity.unit() {
                "" => c.quantity.name().to_string(),
                unit => format!("{} {unit}", c.quantity.name()),
            };
            let _ = writeln!(
                out,
                "  {:>5}  {label:<11} {:>10} {:>10} {:>9}",
                row.line,
                units::brief(c.measured, 5),
                units::brief(c.model, 5),
                units::brief(c.model - c.measured, 3)
            );
        }
    }
    out
}
