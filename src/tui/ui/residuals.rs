//! The outcome panel's lines on the measurements given with `--data`: how far the model at the current
//! parameters is from them (rms as `snapback fit` reports it, and chi2 per degree of freedom when the
//! data give sigmas, the degrees of freedom counting the parameters marked free), the measurement
//! furthest from the model (its line in the file, model - measured), the incoming conditions no column
//! sets (every row takes the current value), and the rows the model cannot give.
//! Dimmed while the current parameters' are solved.

use ratatui::style::Style;
use ratatui::text::{Line, Span};

use crate::analysis::fit::data::Quantity;
use crate::model::params::spec;
use crate::model::units;
use crate::tui::app::App;
use crate::tui::residuals::{Compared, Residuals};

/// How the panel names a quantity.
fn symbol(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::Omega2 | Quantity::Omega2Rpm => "ω2",
        Quantity::Vx2 => "v_x2",
        Quantity::Vy2 => "v_y2",
        Quantity::Theta2Deg => "θ2",
        Quantity::Ex => "e_x",
        Quantity::Speed2 => "v2",
    }
}

/// `value` to 3 significant digits with its sign.
fn signed(value: f64) -> String {
    let text = units::brief(value, 3);
    if value > 0.0 {
        format!("+{text}")
    } else {
        text
    }
}

/// The unit every measurement shares, if they share one.
fn common_unit(r: &Residuals) -> Option<&'static str> {
    let first = r.compared.first()?.quantity.unit();
    r.compared
        .iter()
        .all(|c| c.quantity.unit() == first)
        .then_some(first)
}

/// The rms, in sigmas with the data's sigmas and in the data's unit without.
fn rms(r: &Residuals, rms: f64) -> String {
    if r.absolute_sigma {
        return format!("rms {}σ", units::brief(rms, 3));
    }
    let unit = common_unit(r).unwrap_or_default();
    format!("rms {} {unit}", units::brief(rms, 3))
        .trim_end()
        .to_string()
}

/// chi2 per degree of freedom (the measurements less the `free` parameters) and the degrees of freedom,
/// when the data's sigmas make it meaningful.
fn chi2(r: &Residuals, free: usize) -> Option<(String, usize)> {
    let dof = r.compared.len().checked_sub(free).filter(|dof| *dof > 0)?;
    r.absolute_sigma
        .then(|| (units::brief(r.chi2() / dof as f64, 3), dof))
}

/// The worst measurement, `ω2 +4.9 rad/s (1.6σ)`, and without its unit where the sigmas say enough.
fn worst(c: &Compared) -> Vec<String> {
    let residual = format!("{} {}", symbol(c.quantity), signed(c.residual()));
    let unit = c.quantity.unit();
    let with_unit = format!("{residual} {unit}").trim_end().to_string();
    match c.sigma {
        Some(_) => {
            let sigmas = format!(" ({}σ)", units::brief(c.weighted().abs(), 2));
            vec![with_unit + &sigmas, residual + &sigmas]
        }
        None => vec![with_unit],
    }
}

/// The panel's lines on the data (none without data); labels as the panel's others, `wide` or not.
pub fn lines(app: &App, wide: bool) -> Vec<Line<'static>> {
    let Some(data) = &app.lab.data else {
        return Vec::new();
    };
    let theme = &app.theme;
    let label = |short: &str, long: &str| {
        let text = theme.words(if wide { long } else { short }).into_owned();
        Span::styled(
            format!("{text:<w$}", w = if wide { 18 } else { 9 }),
            theme.dim(),
        )
    };
    // The columns after the label on the narrowest panel of each kind (outcome.rs: 40 and 33 inside).
    let room = if wide { 22 } else { 24 };
    let rows = data.rows.len();
    let Some(r) = app.lab.residuals.as_deref() else {
        return vec![Line::from(vec![
            label(&format!("data {rows}"), &format!("data ({rows} rows)")),
            Span::styled("solving…", theme.dim()),
        ])];
    };
    // Older parameters' residuals stay, dimmed, until the current ones come.
    let style = if r.params == app.params {
        Style::new()
    } else {
        theme.dim()
    };
    let shown = |text: &str| theme.words(text).into_owned();
    // The first of `forms` that fits the room, else the last.
    let fitting = |forms: Vec<String>| {
        let last = forms.last().cloned().unwrap_or_default();
        let text = forms
            .into_iter()
            .map(|f| shown(&f))
            .find(|f| f.chars().count() <= room)
            .unwrap_or_else(|| shown(&last));
        Span::styled(text, style)
    };
    let data_label = label(&format!("data {rows}"), &format!("data ({rows} rows)"));
    let mut lines = Vec::new();
    match (r.rms(), chi2(r, app.lab.free.len())) {
        (None, _) => lines.push(Line::from(vec![
            data_label,
            fitting(vec!["no row solved".into()]),
        ])),
        (Some(x), None) => lines.push(Line::from(vec![data_label, fitting(vec![rms(r, x)])])),
        (Some(x), Some((per_dof, dof))) => {
            let one = format!("{} chi2/dof {per_dof}", rms(r, x));
            // Wide, chi2 has a line of its own, with the degrees of freedom; narrow, if it must.
            if !wide && shown(&one).chars().count() <= room {
                lines.push(Line::from(vec![data_label, fitting(vec![one])]));
            } else {
                lines.push(Line::from(vec![data_label, fitting(vec![rms(r, x)])]));
                lines.push(Line::from(vec![
                    label("chi2/dof", "chi2/dof"),
                    fitting(vec![format!("{per_dof} ({dof} dof)"), per_dof]),
                ]));
            }
        }
    }
    // The incoming conditions no column sets: every row is solved at the current value.
    let assumed = data.assumed(&app.params);
    if !assumed.is_empty() {
        let values: Vec<String> = assumed
            .iter()
            .map(|&(id, v)| format!("{} {}", spec(id).symbol, spec(id).show(v)))
            .collect();
        let names: Vec<&str> = assumed.iter().map(|&(id, _)| spec(id).symbol).collect();
        lines.push(Line::from(vec![
            label("assumed", "not in the data"),
            fitting(vec![
                format!("{} every row", values.join(", ")),
                values.join(", "),
                format!("{} as set", names.join(", ")),
            ]),
        ]));
    }
    if let Some(c) = r.worst() {
        lines.push(Line::from(vec![
            label(
                &format!("line {}", c.line),
                &format!("furthest: line {}", c.line),
            ),
            fitting(worst(c)),
        ]));
    }
    if !r.unsolved.is_empty() {
        let listed: Vec<String> = r.unsolved.iter().map(usize::to_string).collect();
        lines.push(Line::from(vec![
            label("unsolved", "rows not solved"),
            fitting(vec![format!("lines {}", listed.join(", "))]),
        ]));
    }
    lines
}
