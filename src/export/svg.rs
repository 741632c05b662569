//! Figures as SVG, drawn with plotters: one chart per panel, axis titles with units, a legend per
//! panel placed where the curves leave room. Files are written by [`output::write`].

use std::path::Path;

use plotters::prelude::*;

use crate::analysis::figures::{Figure, Panel};
use crate::output::{self, Replace, WriteError};

/// Why a figure could not be drawn or written.
#[derive(Debug, thiserror::Error)]
pub enum SvgError {
    #[error("cannot draw the figure: {0}")]
    Draw(String),
    #[error("cannot write the figure: {0}")]
    Write(#[from] WriteError),
}

/// Line colours, one per curve of a panel.
const COLORS: [RGBColor; 6] = [
    RGBColor(0, 90, 180),
    RGBColor(220, 80, 20),
    RGBColor(0, 150, 70),
    RGBColor(140, 60, 170),
    RGBColor(120, 120, 120),
    RGBColor(200, 160, 0),
];

const FONT: &str = "sans-serif";

/// The data range of a panel, padded by 5 % (and never empty).
fn bounds(panel: &Panel) -> ((f64, f64), (f64, f64)) {
    let points = panel.curves.iter().flat_map(|c| c.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in points.filter(|(x, y)| x.is_finite() && y.is_finite()) {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if x0 > x1 {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let pad = |lo: f64, hi: f64| {
        let d = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
        (lo - d, hi + d)
    };
    let (x0, x1) = if x1 > x0 { (x0, x1) } else { pad(x0, x1) };
    ((x0, x1), pad(y0, y1))
}

/// The legend corner that covers the fewest data points (the legend takes about 40 % of the width
/// and 25 % of the height).
fn legend_place(panel: &Panel, (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> SeriesLabelPosition {
    let places = [
        (SeriesLabelPosition::UpperRight, (0.6, 1.0), (0.75, 1.0)),
        (SeriesLabelPosition::UpperLeft, (0.0, 0.4), (0.75, 1.0)),
        (SeriesLabelPosition::LowerRight, (0.6, 1.0), (0.0, 0.25)),
        (SeriesLabelPosition::LowerLeft, (0.0, 0.4), (0.0, 0.25)),
        (SeriesLabelPosition::LowerMiddle, (0.3, 0.7), (0.0, 0.25)),
        (SeriesLabelPosition::UpperMiddle, (0.3, 0.7), (0.75, 1.0)),
    ];
    let covered = |(u0, u1): (f64, f64), (v0, v1): (f64, f64)| {
        panel
            .curves
            .iter()
            .flat_map(|c| c.points.iter())
            .filter(|(x, y)| {
                let u = (x - x0) / (x1 - x0);
                let v = (y - y0) / (y1 - y0);
                (u0..=u1).contains(&u) && (v0..=v1).contains(&v)
            })
            .count()
    };
    places
        .into_iter()
        .min_by_key(|(_, u, v)| covered(*u, *v))
        .map(|(place, _, _)| place)
        .unwrap_or(SeriesLabelPosition::UpperRight)
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    panel: &Panel,
) -> Result<(), String> {
    let (xr, yr) = bounds(panel);
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, (FONT, 18))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(70)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .axis_desc_style((FONT, 16))
        .label_style((FONT, 13))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| e.to_string())?;
    for (i, curve) in panel.curves.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        chart
            .draw_series(LineSeries::new(
                curve.points.iter().copied(),
                color.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?
            .label(curve.label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .position(legend_place(panel, xr, yr))
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(())
}

/// The figure as an SVG document.
pub fn render(figure: &Figure) -> Result<String, SvgError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, figure.size).into_drawing_area();
        let draw = |e: String| SvgError::Draw(e);
        root.fill(&WHITE).map_err(|e| draw(e.to_string()))?;
        let body = root
            .titled(&figure.title, (FONT, 20))
            .map_err(|e| draw(e.to_string()))?;
        let columns = figure.columns.max(1);
        let rows = figure.panels.len().div_ceil(columns);
        for (panel, area) in figure
            .panels
            .iter()
            .zip(body.split_evenly((rows, columns)).iter())
        {
            draw_panel(area, panel).map_err(draw)?;
        }
        root.present().map_err(|e| draw(e.to_string()))?;
    }
    Ok(svg)
}

/// Draws the figure into `path` (`-`: standard output) through [`output::write`].
pub fn write(figure: &Figure, path: &Path, replace: Replace) -> Result<(), SvgError> {
    let svg = render(figure)?;
    Ok(output::write(path, svg.as_bytes(), replace)?)
}
