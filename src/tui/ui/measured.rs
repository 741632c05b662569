//! The measurements on the charts (`--data`): omega2 measured (the `omega2` or `omega2_rpm` column) as
//! points with their sigma as error bars. In the sweep view, a row measured where the current curve is
//! (every condition but the angle within half a fine step of the current value: as close as the arrow
//! keys bring a value) is drawn on it (`●`), one measured where the comparison curve is, on that (`○`);
//! others are counted under the chart, not drawn. In the contact view, the omega2 of a row measured at
//! the current parameters, the angle included, is drawn at the end of the spin chart, where omega is
//! omega2. The explorer has no chart of the other measurable outcomes (v_x2, theta2, e_x, ...), so those
//! columns appear in the outcome panel's residuals only.
//!
//! Also the band of the sweep view: omega2's mean +/- one standard deviation over the Monte Carlo draws
//! of the inputs typed with an uncertainty.

use std::f64::consts::PI;

use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};

use super::plot::Mark;
use crate::analysis::fit::data::{Quantity, Row};
use crate::model::{ParamId, Params};
use crate::tui::app::App;
use crate::tui::lab::at_conditions;
use crate::tui::sweep::Sweep;
use crate::tui::theme::Theme;

/// One measured omega2 where a chart draws it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// The incidence angle, deg, in the sweep view; the end of the contact, ms, in the contact view.
    pub x: f64,
    /// rad/s, with its sigma if the data give one.
    pub omega2: f64,
    pub sigma: Option<f64>,
}

/// omega2 as `row` measured it (rad/s) with its sigma, if it did.
fn omega2(row: &Row) -> Option<(f64, Option<f64>)> {
    row.measured.iter().find_map(|m| match m.quantity {
        Quantity::Omega2 => Some((m.value, m.sigma)),
        Quantity::Omega2Rpm => Some((m.value * PI / 30.0, m.sigma.map(|s| s * PI / 30.0))),
        _ => None,
    })
}

/// The measured omega2 of the sweep view, sorted by curve.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OnSweep {
    /// Measured where the current curve is.
    pub current: Vec<Point>,
    /// Measured where the comparison curve is.
    pub comparison: Vec<Point>,
    /// Rows with omega2 measured elsewhere.
    pub elsewhere: usize,
}

/// The data's omega2 against the sweeps of `key` (the current spin's and the comparison's); `None`
/// without data or without an omega2 column.
pub fn on_sweep(app: &App, key: &Params) -> Option<OnSweep> {
    let data = app.lab.data.as_ref()?;
    let mut comparison = *key;
    comparison.set(ParamId::Spin, Sweep::comparison_spin(key.spin));
    let mut found = OnSweep::default();
    let mut any = false;
    for row in &data.rows {
        let Some((omega2, sigma)) = omega2(row) else {
            continue;
        };
        any = true;
        let angle_deg = row.params(&app.params).angle_deg;
        let point = Point {
            x: angle_deg,
            omega2,
            sigma,
        };
        if at_conditions(row, key, &[ParamId::Angle]) {
            found.current.push(point);
        } else if at_conditions(row, &comparison, &[ParamId::Angle]) {
            found.comparison.push(point);
        } else {
            found.elsewhere += 1;
        }
    }
    any.then_some(found)
}

/// The glyphs of measured points: on the current curve, on the comparison curve.
fn glyphs(theme: &Theme) -> (char, char) {
    if theme.ascii {
        ('*', 'o')
    } else {
        ('●', '○')
    }
}

/// `points` as error bars and glyphs.
fn marks_of(points: &[Point], glyph: char, color: Color) -> Vec<Mark> {
    let bars = points.iter().filter_map(|p| {
        let s = p.sigma?;
        Some(Mark::Path(vec![
            (p.x, p.omega2 - s, color),
            (p.x, p.omega2 + s, color),
        ]))
    });
    let dots = points
        .iter()
        .map(|p| Mark::Glyph(p.x, p.omega2, glyph, color));
    bars.chain(dots).collect()
}

/// The sweep view's marks for the measurements, drawn over the curves.
pub fn sweep_marks(found: &OnSweep, theme: &Theme) -> Vec<Mark> {
    let (here, there) = glyphs(theme);
    let mut marks = marks_of(&found.current, here, theme.measured());
    marks.extend(marks_of(&found.comparison, there, theme.comparison()));
    marks
}

/// The legend under the sweep chart, `width` columns: what the glyphs are and how many rows are not
/// drawn, the longest form that fits.
pub fn sweep_legend(found: &OnSweep, theme: &Theme, other_spin: f64, width: u16) -> Line<'static> {
    let (here, there) = glyphs(theme);
    let (n_here, n_there) = (found.current.len(), found.comparison.len());
    let bars = found
        .current
        .iter()
        .chain(&found.comparison)
        .any(|p| p.sigma.is_some());
    let forms = [
        (
            format!(" {here} {n_here} measured here"),
            format!("  {there} {n_there} at ω1 = {other_spin:.0} rad/s"),
            [" elsewhere, not drawn", "bars ± 1σ"],
        ),
        (
            format!(" {here} {n_here} here"),
            format!("  {there} {n_there} at ω1={other_spin:.0}"),
            [" not drawn", "bars ±1σ"],
        ),
        (
            format!(" {here} {n_here}"),
            format!("  {there} {n_there}"),
            [" off", "±1σ"],
        ),
    ];
    let lines = forms.map(|(current, comparison, [elsewhere, sigma])| {
        let mut notes = Vec::new();
        if found.elsewhere > 0 {
            notes.push(format!("{}{elsewhere}", found.elsewhere));
        }
        if bars {
            notes.push(sigma.to_string());
        }
        let mut spans = vec![
            Span::styled(current, Style::new().fg(theme.measured())),
            Span::styled(comparison, Style::new().fg(theme.comparison())),
        ];
        if !notes.is_empty() {
            spans.push(Span::styled(
                format!("  · {}", notes.join(" · ")),
                theme.dim(),
            ));
        }
        words(spans, theme)
    });
    fitting(lines, width)
}

/// The first of `lines` that fits `width` columns, else the last.
fn fitting<const N: usize>(lines: [Line<'static>; N], width: u16) -> Line<'static> {
    let mut lines = lines.into_iter().peekable();
    while let Some(line) = lines.next() {
        if line.width() <= usize::from(width) || lines.peek().is_none() {
            return line;
        }
    }
    Line::default()
}

/// `spans` with their text as the theme writes it (ASCII spelt out).
fn words(spans: Vec<Span<'static>>, theme: &Theme) -> Line<'static> {
    Line::from(
        spans
            .into_iter()
            .map(|s| Span::styled(theme.words(&s.content).into_owned(), s.style))
            .collect::<Vec<_>>(),
    )
}

/// The band of the sweep view as two curves, omega2's mean - sd and mean + sd.
pub fn band_marks(app: &App, key: &Params) -> Vec<Mark> {
    let Some(band) = app.lab.band_for(key) else {
        return Vec::new();
    };
    let color = app.theme.band();
    [-1.0, 1.0]
        .into_iter()
        .map(|side| {
            Mark::Path(
                band.points
                    .iter()
                    .map(|p| (p.angle_deg, p.mean + side * p.sd, color))
                    .collect(),
            )
        })
        .collect()
}

/// The band's legend, `width` columns: the inputs' uncertainties, or that it is being computed; `None`
/// without any.
pub fn band_legend(app: &App, key: &Params, width: u16) -> Option<Line<'static>> {
    let spreads = &app.lab.spreads;
    if spreads.is_empty() {
        return None;
    }
    let theme = &app.theme;
    let inputs: Vec<String> = spreads
        .iter()
        .map(|s| {
            let spec = crate::model::params::spec(s.id);
            format!("{} ± {}", spec.symbol, spec.show(s.sigma))
        })
        .collect();
    let inputs = inputs.join(", ");
    let forms = match app.lab.band_for(key) {
        Some(_) => [
            format!(
                " ━ band: ω2 ± 1 sd over {} draws, for {inputs}",
                crate::tui::band::SAMPLES
            ),
            format!(" ━ ±1 sd band for {inputs}"),
        ],
        None => [
            format!(" ━ band: computing… for {inputs}"),
            " ━ band: computing…".to_string(),
        ],
    };
    let style = Style::new().fg(theme.band());
    let lines = forms.map(|text| words(vec![Span::styled(text, style)], theme));
    Some(fitting(lines, width))
}

/// The contact view's spin chart: the omega2 of rows measured at `params` (the angle included), at the
/// end of the contact, `t_end` in ms.
pub fn contact_marks(app: &App, params: &Params, t_end: f64) -> Vec<Mark> {
    let Some(data) = &app.lab.data else {
        return Vec::new();
    };
    let points: Vec<Point> = data
        .rows
        .iter()
        .filter(|row| at_conditions(row, params, &[]))
        .filter_map(|row| {
            let (omega2, sigma) = omega2(row)?;
            Some(Point {
                x: t_end,
                omega2,
                sigma,
            })
        })
        .collect();
    marks_of(&points, glyphs(&app.theme).0, app.theme.measured())
}
