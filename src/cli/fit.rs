//! `snapback fit`: the free parameters that best explain measured rebounds, with their uncertainties.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use serde_json::{Map, Value, json};

use super::{Failure, ParamArgs, emit};
use crate::analysis::fit::{self, Fit, Fitted, Options, Verdict, data, free, shown, watch::Watch};
use crate::input;
use crate::model::params::{Bound, ParamId, spec};
use crate::model::{Params, SolveOptions, units};
use crate::scenario::Scenario;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The fitted parameters with standard errors and 95% intervals in the explorer's units, the verdict,
    /// the conditions assumed, any rival minimum, the correlations and every row beside the model.
    #[default]
    Table,
    /// One JSON object, SI units: `free` {key: {value, stderr, ci95, profile95, poorly_determined,
    /// unit}} for the shared parameters and `groups` {label: {key: {...}}} for those per group
    /// (`profile95` is [low, high] with null for a side left open: the interval reaches 0, infinity or
    /// the end of the parameter's range; `poorly_determined` is then true), `chi2`, `dof`, `rms`,
    /// `p_value` (null without sigmas), `verdict` (consistent, poor or unjudged), `outliers`,
    /// `minima` [{chi2, values}] best first, `assumed` {key: value} and `assumed_from` {key: source},
    /// `correlation` (in the order of `order`), `rows` (`line`, `measured`, `model`, `residual`),
    /// `converged`, `undetermined`.
    Json,
}

/// Which 95% intervals to compute and show.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Intervals {
    /// The Wald interval from the covariance (`ci95`), quick.
    Wald,
    /// The profile-likelihood interval (`profile95`): honest where the model is not linear, open where
    /// the data allow a parameter to reach 0 or infinity.
    Profile,
    /// Both; the table shows the profile interval and marks where the two differ by more than 10%.
    #[default]
    Both,
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
    /// The parameters to fit, shared by every row: comma separated flags (cart-mass,stiffness,mu); the
    /// others stay as the preset, scenario and flags set them, and their values are where the fit starts.
    #[arg(long, value_name = "PARAM[,PARAM...]", default_value = "")]
    pub free: String,
    /// The parameters to fit once for each group of rows (see --group), comma separated flags.
    #[arg(long, value_name = "PARAM[,PARAM...]", default_value = "")]
    pub free_per_group: String,
    /// A text column of the data whose labels split the rows into groups (a string bed, a material).
    #[arg(long, value_name = "COLUMN")]
    pub group: Option<String>,
    /// Columns of the data to leave unread, comma separated (labels: the string's name, the company).
    #[arg(long, value_name = "COLUMN[,COLUMN...]", value_delimiter = ',')]
    pub ignore: Vec<String>,
    /// Starting points of the global search, each given a short run of Levenberg-Marquardt (the scan
    /// scores 48 points for each): more finds a narrow minimum more surely, and takes longer.
    #[arg(long, value_name = "N", default_value_t = Options::default().starts as u32,
          value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub starts: u32,
    /// Seed of the starting points (the same seed gives the same fit).
    #[arg(long, value_name = "SEED", default_value_t = Options::default().seed)]
    pub seed: u64,
    /// The 95% intervals: wald, profile or both.
    #[arg(long, value_enum, default_value_t = Intervals::Both)]
    pub intervals: Intervals,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// Fits the data, stopped by `options`' cancellation (Ctrl-C) and counted by its work.
pub fn run(args: &FitArgs, options: &SolveOptions) -> Result<(), Failure> {
    let base = args
        .params
        .apply(Params::default())
        .map_err(Failure::usage)?;
    let layout = data::Layout {
        group: args.group.clone(),
        ignore: args.ignore.clone(),
    };
    let data = read_data_with(&args.data, &layout)?;
    let free = free::parse_lists(
        &args.free,
        &args.free_per_group,
        &data.conditions,
        data.groups.len(),
    )
    .map_err(Failure::usage)?;
    let search = Options {
        starts: args.starts as usize,
        seed: args.seed,
        profile: args.intervals != Intervals::Wald,
    };
    let fit = fit::fit_watched(&base, &free, &data, &search, &Watch::of(options))
        .map_err(Failure::usage)?;
    let sources: Vec<String> = fit
        .assumed
        .iter()
        .map(|&(id, _)| source(&args.params, id))
        .collect();
    let text = match args.format {
        Format::Table => table(&fit, &data, &sources, args.intervals),
        Format::Json => format!("{:#}\n", json(&fit, &sources, args.intervals)),
    };
    emit(&text)
}

/// Where the value of `id` came from: its flag, the scenario file, the preset or the default.
fn source(args: &ParamArgs, id: ParamId) -> String {
    let key = spec(id).key;
    if args.given.iter().any(|(given, _)| *given == id) {
        return format!("from --{}", spec(id).flag);
    }
    if let Some(path) = &args.scenario
        && (input::is_stdin(path) || Scenario::load(path).is_ok_and(|s| s.values.contains_key(key)))
    {
        return format!("from the scenario {}", path.display());
    }
    if let Some(name) = &args.preset
        && crate::config::preset(name).is_ok_and(|s| s.values.contains_key(key))
    {
        return format!("from the preset {name}");
    }
    "from the default".to_string()
}

/// The measurements in `path` (standard input for `-`): a file that cannot be read, or a bad cell, is an
/// error naming file, line and column. The explorer's `--data` reads them so too.
pub(super) fn read_data(path: &Path) -> Result<data::Dataset, Failure> {
    read_data_with(path, &data::Layout::default())
}

/// [`read_data`] with a group column and ignored columns.
fn read_data_with(path: &Path, layout: &data::Layout) -> Result<data::Dataset, Failure> {
    let origin = if input::is_stdin(path) {
        input::STDIN_NAME.to_string()
    } else {
        path.display().to_string()
    };
    let text = input::read_text(path).map_err(|e| Failure::usage(format!("{origin}: {e}")))?;
    data::parse_with(&text, &origin, layout).map_err(Failure::usage)
}

/// An optional number as JSON (`null` for none).
fn maybe(x: Option<f64>) -> Value {
    x.map_or(Value::Null, Value::from)
}

/// One fitted parameter as JSON, with the intervals asked for.
fn fitted_json(f: &Fitted, intervals: Intervals) -> Value {
    let mut p = Map::new();
    p.insert("value".into(), f.value.into());
    p.insert("stderr".into(), maybe(f.stderr));
    if intervals != Intervals::Profile {
        p.insert(
            "ci95".into(),
            f.ci95.map_or(Value::Null, |(lo, hi)| json!([lo, hi])),
        );
    }
    if intervals != Intervals::Wald {
        p.insert(
            "profile95".into(),
            f.profile95
                .map_or(Value::Null, |(lo, hi)| json!([maybe(lo), maybe(hi)])),
        );
    }
    p.insert("poorly_determined".into(), f.poorly_determined().into());
    p.insert("unit".into(), spec(f.id).dimension.base_symbol().into());
    Value::Object(p)
}

/// The values of one minimum (or any list in the order of `fit.free`): shared ones under their keys,
/// and per group under `groups`.
fn by_group(fit: &Fit, values: &[Value]) -> (Map<String, Value>, Map<String, Value>) {
    let mut shared = Map::new();
    let mut groups = Map::new();
    for (f, v) in fit.free.iter().zip(values) {
        let key = spec(f.id).key.to_string();
        match f.group {
            None => {
                shared.insert(key, v.clone());
            }
            Some(g) => {
                let entry = groups
                    .entry(fit.groups[g].clone())
                    .or_insert_with(|| Value::Object(Map::new()));
                if let Value::Object(m) = entry {
                    m.insert(key, v.clone());
                }
            }
        }
    }
    (shared, groups)
}

/// The fit as JSON, SI units, parameters under their scenario keys; `sources` says where each assumed
/// condition came from.
pub fn json(fit: &Fit, sources: &[String], intervals: Intervals) -> Value {
    let params: Vec<Value> = fit.free.iter().map(|f| fitted_json(f, intervals)).collect();
    let (free, groups) = by_group(fit, &params);
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
                "standardised": pick(&|c| c.standardised),
            })
        })
        .collect();
    let minima: Vec<Value> = fit
        .minima
        .iter()
        .map(|m| {
            let values: Vec<Value> = m.values.iter().map(|&v| v.into()).collect();
            let (shared, groups) = by_group(fit, &values);
            let mut entry = json!({"chi2": m.chi2, "values": shared});
            if !groups.is_empty() {
                entry["groups"] = Value::Object(groups);
            }
            entry
        })
        .collect();
    let outliers: Vec<Value> = fit
        .outliers()
        .iter()
        .map(|(line, q, z)| json!({"line": line, "quantity": q.name(), "standardised": z}))
        .collect();
    let order: Vec<String> = fit.free.iter().map(|f| label(fit, f)).collect();
    let undetermined: Vec<String> = fit
        .free
        .iter()
        .filter(|f| f.stderr.is_none())
        .map(|f| label(fit, f))
        .collect();
    json!({
        "free": free,
        "groups": groups,
        "order": order,
        "chi2": fit.chi2,
        "dof": fit.dof,
        "rms": fit.rms,
        "absolute_sigma": fit.absolute_sigma,
        "p_value": maybe(fit.p_value),
        "verdict": fit.verdict.name(),
        "outliers": outliers,
        "minima": minima,
        "assumed": fit.assumed.iter()
            .map(|&(id, v)| (spec(id).key.to_string(), Value::from(v)))
            .collect::<Map<_, _>>(),
        "assumed_from": fit.assumed.iter().zip(sources)
            .map(|(&(id, _), s)| (spec(id).key.to_string(), Value::from(s.as_str())))
            .collect::<Map<_, _>>(),
        "correlation": fit.correlation.iter()
            .map(|r| r.iter().map(|&c| maybe(c)).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
        "rows": rows,
        "converged": fit.converged,
        "undetermined": undetermined,
    })
}

/// A fitted parameter's key, with its group for one per group: `cart_friction[nylon]`.
fn label(fit: &Fit, f: &Fitted) -> String {
    let key = spec(f.id).key;
    match f.group {
        Some(g) => format!("{key}[{}]", fit.groups[g]),
        None => key.to_string(),
    }
}

/// The widths of the first columns of `rows`: each its widest cell (in characters), at least `least`.
fn column_widths<const N: usize, const M: usize>(
    rows: &[[String; M]],
    least: [usize; N],
) -> [usize; N] {
    let mut widths = least;
    for row in rows {
        for (width, cell) in widths.iter_mut().zip(row) {
            *width = (*width).max(cell.chars().count());
        }
    }
    widths
}

/// `n` and the noun, singular for one.
fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// An interval's end in the display unit; an open end says where it goes (0, infinity or the end of
/// the range).
fn end_text(f: &Fitted, end: Option<f64>, high: bool) -> String {
    let s = spec(f.id);
    match end {
        Some(x) => shown(f.id, x, f.stderr),
        None => {
            let bound = if high { s.range.high } else { s.range.low };
            match bound {
                Bound::Open(b) | Bound::Closed(b) => {
                    format!("{} (open)", shown(f.id, b, None))
                }
                Bound::Unbounded if high => "inf (open)".into(),
                Bound::Unbounded => "-inf (open)".into(),
            }
        }
    }
}

/// True when the Wald and profile intervals differ by more than 10% of the profile interval's width at
/// either end (an open profile end always differs).
fn differ(f: &Fitted) -> bool {
    match (f.ci95, f.profile95) {
        (Some((wl, wh)), Some((Some(pl), Some(ph)))) => {
            let width = ph - pl;
            (wl - pl).abs() > 0.1 * width || (wh - ph).abs() > 0.1 * width
        }
        (_, Some(_)) => true,
        _ => false,
    }
}

/// The fit as text in the explorer's units.
pub fn table(fit: &Fit, data: &data::Dataset, sources: &[String], intervals: Intervals) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "fit to {}: {}, {}, {}",
        data.origin,
        count(data.rows.len(), "row"),
        count(data.measurements(), "measurement"),
        count(fit.free.len(), "free parameter")
    );
    for (&(id, value), from) in fit.assumed.iter().zip(sources) {
        let s = spec(id);
        let _ = writeln!(
            out,
            "{} not in the data: {} {} for every row, {from}",
            s.flag,
            units::brief(units::in_unit(value, s.dimension, s.display_unit), 6),
            s.display_unit
        );
    }
    let profile = intervals != Intervals::Wald;
    let heading = if profile {
        "95% interval (profile)"
    } else {
        "95% interval (Wald)"
    };
    let name_of = |f: &Fitted| {
        let s = spec(f.id);
        match f.group {
            Some(g) => format!("{} ({}) [{}]", s.flag, s.symbol, fit.groups[g]),
            None => format!("{} ({})", s.flag, s.symbol),
        }
    };
    let mut differing = Vec::new();
    let rows: Vec<[String; 5]> = fit
        .free
        .iter()
        .map(|f| {
            let stderr = f.stderr.map_or("-".into(), |se| shown(f.id, se, Some(se)));
            let mut interval = match (profile, f.profile95, f.ci95) {
                (true, Some((lo, hi)), _) => {
                    format!("[{}, {}]", end_text(f, lo, false), end_text(f, hi, true))
                }
                (false, _, Some((lo, hi))) => format!(
                    "[{}, {}]",
                    shown(f.id, lo, f.stderr),
                    shown(f.id, hi, f.stderr)
                ),
                _ => "not determined by the data".into(),
            };
            if intervals == Intervals::Both && differ(f) && f.ci95.is_some() {
                interval.push_str(" *");
                differing.push(f);
            }
            let note = if f.poorly_determined() && f.stderr.is_some() {
                "  poorly determined"
            } else {
                ""
            };
            [
                name_of(f),
                shown(f.id, f.value, f.stderr),
                stderr,
                interval,
                format!("{}{note}", spec(f.id).display_unit),
            ]
        })
        .collect();
    // Each column as wide as its widest cell, and at least as wide as usual.
    let widths = column_widths(&rows, [22, 12, 10, 28]);
    let [name, value, stderr, interval] = widths;
    let _ = writeln!(
        out,
        "\n  {:<name$} {:>value$} {:>stderr$}  {heading:<interval$} unit",
        "parameter", "value", "stderr"
    );
    for [n, v, e, i, unit] in &rows {
        let line = format!("  {n:<name$} {v:>value$} {e:>stderr$}  {i:<interval$} {unit}");
        let _ = writeln!(out, "{}", line.trim_end());
    }
    for f in differing {
        if let Some((lo, hi)) = f.ci95 {
            let line = format!(
                "  * differs from the Wald interval by more than 10%: {} [{}, {}] {}",
                label(fit, f),
                shown(f.id, lo, f.stderr),
                shown(f.id, hi, f.stderr),
                spec(f.id).display_unit
            );
            let _ = writeln!(out, "{}", line.trim_end());
        }
    }
    if fit
        .free
        .iter()
        .any(|f| f.poorly_determined() && f.stderr.is_some())
    {
        let _ = writeln!(
            out,
            "  poorly determined: the data allow the parameter to reach an end of its range (open)"
        );
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
    let verdict = match (fit.verdict, fit.p_value) {
        (Verdict::Consistent, Some(p)) => format!(
            "consistent: p = {} (chi2 this large or larger by chance); the model describes the data within their sigmas",
            units::brief(p, 2)
        ),
        (Verdict::Poor, Some(p)) => format!(
            "poor: p = {} < {}; the model does not describe the data within their sigmas (or the sigmas are understated, or some rows are outliers)",
            units::brief(p, 2),
            fit::P_POOR
        ),
        _ => "unjudged: the data give no sigmas, so the scatter was estimated from the residuals and nothing can be judged; add sigma_ columns".into(),
    };
    let _ = writeln!(out, "verdict: {verdict}");
    let outliers = fit.outliers();
    if !outliers.is_empty() {
        let list: Vec<String> = outliers
            .iter()
            .map(|(line, q, z)| format!("line {line} ({q} {z:+.1})"))
            .collect();
        let _ = writeln!(
            out,
            "likely outliers (standardised residual beyond ±{}): {}",
            fit::OUTLIER,
            list.join(", ")
        );
    }
    if let Some(rival) = fit.rival() {
        let values: Vec<String> = fit
            .free
            .iter()
            .zip(&rival.values)
            .map(|(f, &v)| {
                let s = spec(f.id);
                let group = f
                    .group
                    .map_or(String::new(), |g| format!("[{}]", fit.groups[g]));
                format!(
                    "{}{group} {} {}",
                    s.symbol,
                    shown(f.id, v, f.stderr),
                    s.display_unit
                )
                .trim_end()
                .to_string()
            })
            .collect();
        let _ = writeln!(
            out,
            "a second minimum at {} with chi2 {} (within {} of the best): the data do not decide between them",
            values.join(", "),
            units::brief(rival.chi2, 4),
            fit::AMBIGUOUS
        );
    }
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
        let width = fit
            .free
            .iter()
            .map(|f| label(fit, f).chars().count())
            .fold(14, usize::max);
        for (f, row) in fit.free.iter().zip(&fit.correlation) {
            let _ = write!(out, "  {:<width$}", label(fit, f));
            for c in row {
                let _ = write!(out, " {:>6}", c.map_or("-".into(), |c| format!("{c:.2}")));
            }
            out.push('\n');
        }
    }
    let measured: Vec<[String; 5]> = fit
        .rows
        .iter()
        .flat_map(|row| {
            row.values.iter().map(move |c| {
                let label = match c.quantity.unit() {
                    "" => c.quantity.name().to_string(),
                    unit => format!("{} {unit}", c.quantity.name()),
                };
                [
                    row.line.to_string(),
                    label,
                    units::brief(c.measured, 5),
                    units::brief(c.model, 5),
                    units::brief(c.model - c.measured, 3),
                ]
            })
        })
        .collect();
    let [line, quantity, value, model, residual] = column_widths(&measured, [5, 11, 10, 10, 9]);
    let _ = writeln!(
        out,
        "\n  {:>line$}  {:<quantity$} {:>value$} {:>model$} {:>residual$} {:>7}",
        "line", "quantity", "measured", "model", "residual", "z"
    );
    let z = fit.rows.iter().flat_map(|row| &row.values);
    for ([l, q, m, y, r], c) in measured.iter().zip(z) {
        let _ = writeln!(
            out,
            "  {l:>line$}  {q:<quantity$} {m:>value$} {y:>model$} {r:>residual$} {:>7.2}",
            c.standardised
        );
    }
    out
}
