//! The outcome panel's lines on the measurements given with `--data`: how far the model at the current
//! parameters is from them (rms as `snapback fit` reports it, and chi2 per degree of freedom when the
//! data give sigmas, the degrees of freedom counting the parameters marked free), the measurement
//! furthest from the model (its line in the file, model - measured), and the rows the model cannot give.
//! Dimmed while the current parameters' are solved.

use ratatui::style::Style;
use ratatui::text::{Line, Span};

use crate::analysis::fit::data::Quantity;
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

/// The rms, in sigmas with the data's sigmas and in the data's unit without; with chi2 per degree of
/// freedom (the measurements less the `free` parameters) when the sigmas make it meaningful.
fn spread(r: &Residuals, rms: f64, free: usize) -> String {
    if !r.absolute_sigma {
        let unit = common_unit(r).unwrap_or_default();
        return format!("rms {} {unit}", units::brief(rms, 3))
            .trim_end()
            .to_string();
    }
    let rms = format!("rms {}σ", units::brief(rms, 3));
    match r.compared.len().checked_sub(free).filter(|dof| *dof > 0) {
        Some(dof) => format!("{rms} chi2/dof {}", units::brief(r.chi2() / dof as f64, 3)),
        None => rms,
    }
}

/// The worst measurement: `ω2 +4.9 rad/s (1.6σ)`; narrow, the unit goes where the sigmas say enough.
fn worst(c: &Compared, wide: bool) -> String {
    let sigmas = c.sigma.map_or(String::new(), |_| {
        format!(" ({}σ)", units::brief(c.weighted().abs(), 2))
    });
    let unit = if wide || c.sigma.is_none() {
        c.quantity.unit()
    } else {
        ""
    };
    let text = format!("{} {} {unit}", symbol(c.quantity), signed(c.residual()));
    format!("{}{sigmas}", text.trim_end())
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
    let words = |text: String| Span::styled(theme.words(&text).into_owned(), style);
    let mut lines = vec![Line::from(vec![
        label(&format!("data {rows}"), &format!("data ({rows} rows)")),
        match r.rms() {
            Some(rms) => words(spread(r, rms, app.lab.free.len())),
            None => words("no row solved".into()),
        },
    ])];
    if let Some(c) = r.worst() {
        lines.push(Line::from(vec![
            label(
                &format!("line {}", c.line),
                &format!("furthest: line {}", c.line),
            ),
            words(worst(c, wide)),
        ]));
    }
    if !r.unsolved.is_empty() {
        let listed: Vec<String> = r.unsolved.iter().map(usize::to_string).collect();
        lines.push(Line::from(vec![
            label("unsolved", "rows not solved"),
            words(format!("lines {}", listed.join(", "))),
        ]));
    }
    lines
}
