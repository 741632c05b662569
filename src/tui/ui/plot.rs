//! A small x-y plot: round tick labels on both axes, curves coloured segment by segment, dashed guides
//! (grip limit, transitions, zero line, the current angle) and an axis title. Both chart views draw with it.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::Line;
use ratatui::widgets::canvas::{self, Canvas, Points};
use ratatui::widgets::{Block, Borders, Widget};

/// Round ticks over an axis and the bounds the axis spans.
#[derive(Clone, Debug, PartialEq)]
pub struct Scale {
    pub bounds: [f64; 2],
    pub ticks: Vec<f64>,
    /// Decimals that show the tick step exactly.
    pub decimals: usize,
}

impl Scale {
    /// Bounds widened to round values around `[low, high]`, as tight as a grid of `Scale::GRID` ticks
    /// allows, with at most `max_ticks` of the grid's ticks labelled: both ends, and zero when it can be.
    pub fn rounded(low: f64, high: f64, max_ticks: usize) -> Scale {
        let mut scale = Self::build(low, high, Self::GRID.max(max_ticks), true);
        let last = scale.ticks.len() - 1;
        let zero = scale.ticks.iter().position(|t| t.abs() < 1e-12);
        let candidates = scale.ticks.len().div_ceil(max_ticks.max(2))..=last.max(1);
        // Both ends labelled, and zero too if some spacing allows it.
        let every = candidates
            .clone()
            .find(|e| last % e == 0 && zero.is_some_and(|z| z % e == 0))
            .or_else(|| candidates.clone().find(|e| last % e == 0))
            .unwrap_or(1);
        scale.ticks = scale.ticks.iter().step_by(every).copied().collect();
        scale
    }

    /// Ticks of the grid that sets the bounds of a [`Scale::rounded`].
    const GRID: usize = 7;

    /// Bounds exactly `[low, high]` (the contact time, 0 to 90 degrees) with round ticks inside.
    pub fn exact(low: f64, high: f64, max_ticks: usize) -> Scale {
        Self::build(low, high, max_ticks, false)
    }

    fn build(low: f64, high: f64, max_ticks: usize, widen: bool) -> Scale {
        let (low, high) = if high - low > 1e-12 * (low.abs() + high.abs()) && high > low {
            (low, high)
        } else {
            // A flat curve: centre it in a band of +/- 10 % (or +/- 1 around zero).
            let pad = if low == 0.0 { 1.0 } else { low.abs() * 0.1 };
            (low - pad, high + pad)
        };
        let max_ticks = max_ticks.max(2);
        let raw = (high - low) / (max_ticks - 1) as f64;
        let mut magnitude = 10f64.powf(raw.log10().floor());
        let mut k = 0;
        loop {
            let factor = [1.0, 2.0, 2.5, 5.0][k];
            let step = factor * magnitude;
            let first = (low / step).floor();
            let last = (high / step).ceil();
            let (first, last) = if widen {
                (first, last)
            } else {
                ((low / step - 1e-9).ceil(), (high / step + 1e-9).floor())
            };
            let count = (last - first) as usize + 1;
            if count <= max_ticks {
                let ticks: Vec<f64> = (0..count).map(|i| (first + i as f64) * step).collect();
                let bounds = if widen {
                    [first * step, last * step]
                } else {
                    [low, high]
                };
                let decimals = (-(step.log10().floor()) as i64 + i64::from(factor == 2.5)).max(0);
                return Scale {
                    bounds,
                    ticks,
                    decimals: decimals as usize,
                };
            }
            k += 1;
            if k == 4 {
                k = 0;
                magnitude *= 10.0;
            }
        }
    }

    /// The tick labels, with no "-0".
    pub fn labels(&self) -> Vec<String> {
        self.ticks
            .iter()
            .map(|&t| {
                let t = if t.abs() < 1e-12 { 0.0 } else { t };
                format!("{t:.*}", self.decimals)
            })
            .collect()
    }

    /// The widest tick label.
    pub fn label_width(&self) -> u16 {
        self.labels()
            .iter()
            .map(|l| l.chars().count())
            .max()
            .unwrap_or(0) as u16
    }

    /// The cell of `value` on an axis `cells` long with `per_cell` dots in each (0 at the low end), found
    /// as the canvas finds it, so labels sit where the curves are drawn.
    pub fn cell(&self, value: f64, cells: u16, per_cell: u16, upward: bool) -> u16 {
        let [low, high] = self.bounds;
        let fraction = ((value - low) / (high - low)).clamp(0.0, 1.0);
        let dots = f64::from(cells * per_cell - 1);
        if upward {
            // The canvas counts rows down from the top.
            let from_top = ((1.0 - fraction) * dots).round() as u16 / per_cell;
            cells - 1 - from_top
        } else {
            (fraction * dots).round() as u16 / per_cell
        }
    }
}

/// Dots per cell (across, up) that `marker` draws with.
pub fn resolution(marker: Marker) -> (u16, u16) {
    match marker {
        Marker::Braille | Marker::Octant => (2, 4),
        Marker::Sextant => (2, 3),
        Marker::Quadrant => (2, 2),
        Marker::HalfBlock => (1, 2),
        _ => (1, 1),
    }
}

/// How many ticks fit along `cells` cells when each needs `spacing`.
pub fn tick_budget(cells: u16, spacing: u16) -> usize {
    usize::from(cells / spacing.max(1)).clamp(2, 11)
}

/// Something drawn in the plot.
#[derive(Clone, Debug)]
pub enum Mark {
    /// A curve through the points; each segment has the colour of the point it ends at.
    Path(Vec<(f64, f64, Color)>),
    /// A dashed curve through the points (sorted by x).
    Dashed(Vec<(f64, f64)>, Color),
    /// A dashed vertical line.
    Vertical(f64, Color),
    /// A dashed horizontal line (drawn only inside the bounds).
    Horizontal(f64, Color),
    /// A dot at one point.
    Dot(f64, f64, Color),
    /// A solid vertical line over everything else: the time cursor.
    Cursor(f64, Color),
    /// A character written over everything in the cell of a point: a measurement.
    Glyph(f64, f64, char, Color),
}

impl Mark {
    /// The y values the bounds must include.
    fn ys(&self) -> Vec<f64> {
        match self {
            Mark::Path(points) => points.iter().map(|p| p.1).collect(),
            Mark::Dashed(points, _) => points.iter().map(|p| p.1).collect(),
            Mark::Dot(_, y, _) | Mark::Glyph(_, y, ..) => vec![*y],
            Mark::Vertical(..) | Mark::Horizontal(..) | Mark::Cursor(..) => Vec::new(),
        }
    }
}

/// The smallest and largest y of the marks (`(0, 0)` when there are none).
pub fn y_extent(marks: &[Mark]) -> (f64, f64) {
    let ys = marks.iter().flat_map(Mark::ys).filter(|y| y.is_finite());
    ys.fold(None, |acc: Option<(f64, f64)>, y| {
        Some(acc.map_or((y, y), |(lo, hi)| (lo.min(y), hi.max(y))))
    })
    .unwrap_or((0.0, 0.0))
}

/// Rows a plot of `height` rows spends outside its drawing area: the title, the x axis and its labels.
pub const FRAME_ROWS: u16 = 3;

/// A titled plot. The y labels take `label_width` columns plus the axis, so plots stacked with the same
/// width line up.
pub struct Plot<'a> {
    pub title: Line<'a>,
    /// Written at the right of the title row: e.g. the values at the time cursor.
    pub readout: Option<Line<'a>>,
    pub x: Scale,
    pub y: Scale,
    /// Written under the y labels, at the end of the x axis: e.g. `t (ms)`.
    pub x_title: &'a str,
    pub marks: Vec<Mark>,
    pub label_width: u16,
    pub marker: Marker,
    pub axis_style: Style,
}

impl Plot<'_> {
    /// The columns (first, count) where the data are drawn, for a plot in `area` with these labels.
    pub fn data_columns(area: Rect, label_width: u16) -> (u16, u16) {
        let first = area.x + label_width + 1;
        (first, area.right().saturating_sub(first))
    }

    fn paint(&self, ctx: &mut canvas::Context, data: Rect) {
        let [x0, x1] = self.x.bounds;
        let [y0, y1] = self.y.bounds;
        // Dashes: a dot every other column (every row upright), so they read as dashed with any marker.
        let dx = (x1 - x0) / f64::from(data.width.max(2) - 1) * 2.0;
        let dy = (y1 - y0) / f64::from(data.height.max(2) - 1);
        let guides: Vec<&Mark> = self
            .marks
            .iter()
            .filter(|m| matches!(m, Mark::Vertical(..) | Mark::Horizontal(..)))
            .collect();
        for mark in guides {
            match mark {
                Mark::Vertical(x, color) => {
                    let dots: Vec<(f64, f64)> = (0..)
                        .map(|i| y0 + dy * f64::from(i))
                        .take_while(|y| *y <= y1)
                        .map(|y| (*x, y))
                        .collect();
                    ctx.draw(&Points::new(&dots, *color));
                }
                Mark::Horizontal(y, color) if (y0..=y1).contains(y) => {
                    let dots: Vec<(f64, f64)> = (0..)
                        .map(|i| x0 + dx * f64::from(i))
                        .take_while(|x| *x <= x1)
                        .map(|x| (x, *y))
                        .collect();
                    ctx.draw(&Points::new(&dots, *color));
                }
                _ => {}
            }
        }
        ctx.layer();
        for mark in &self.marks {
            match mark {
                Mark::Dashed(points, color) => {
                    let dots: Vec<(f64, f64)> = (0..)
                        .map(|i| x0 + dx * f64::from(i))
                        .take_while(|x| *x <= x1)
                        .filter_map(|x| interpolate(points, x).map(|y| (x, y)))
                        .collect();
                    ctx.draw(&Points::new(&dots, *color));
                }
                Mark::Path(points) => {
                    for pair in points.windows(2) {
                        let (a, b) = (pair[0], pair[1]);
                        ctx.draw(&canvas::Line::new(a.0, a.1, b.0, b.1, b.2));
                    }
                }
                Mark::Dot(x, y, color) => ctx.draw(&Points::new(&[(*x, *y)], *color)),
                Mark::Vertical(..) | Mark::Horizontal(..) | Mark::Cursor(..) | Mark::Glyph(..) => {}
            }
        }
        ctx.layer();
        for mark in &self.marks {
            if let Mark::Cursor(x, color) = mark {
                ctx.draw(&canvas::Line::new(*x, y0, *x, y1, *color));
            }
        }
        // The canvas puts text in the cell its position falls in, counting down from the top-left corner;
        // half a cell on, it lands in the cell nearest the point, where the curves' dots are.
        let (half_x, half_y) = (dx / 4.0, dy / 2.0);
        for mark in &self.marks {
            if let Mark::Glyph(x, y, glyph, color) = mark {
                let at = ((x + half_x).min(x1), (y - half_y).max(y0));
                let text = Line::styled(glyph.to_string(), Style::new().fg(*color));
                ctx.print(at.0, at.1, text);
            }
        }
    }

    /// The y labels, the axis lines with their ticks, and the x labels.
    fn axes(&self, inner: Rect, data: Rect, buf: &mut Buffer) {
        let axis_x = data.x - 1;
        let axis_y = data.bottom();
        let (across, up) = resolution(self.marker);
        let style = self.axis_style;
        for row in data.top()..axis_y {
            buf.set_string(axis_x, row, "│", style);
        }
        for (tick, label) in self.y.ticks.iter().zip(self.y.labels()) {
            let row = axis_y - 1 - self.y.cell(*tick, data.height, up, true);
            buf.set_string(axis_x, row, "┤", style);
            let width = label.chars().count() as u16;
            // A space before the axis, unless the label is as wide as the column: it stays inside the plot.
            let start = axis_x.saturating_sub(width + 1).max(inner.x);
            buf.set_string(start, row, &label, style);
        }
        buf.set_string(axis_x, axis_y, "└", style);
        buf.set_string(data.x, axis_y, "─".repeat(usize::from(data.width)), style);
        // x labels, centred on their ticks, left to right, skipping any that would touch the one before.
        let labels_row = axis_y + 1;
        let mut free_from = data.x;
        for (tick, label) in self.x.ticks.iter().zip(self.x.labels()) {
            let col = data.x + self.x.cell(*tick, data.width, across, false);
            buf.set_string(col, axis_y, "┬", style);
            let width = label.chars().count() as u16;
            let start = col
                .saturating_sub(width / 2)
                .clamp(data.x, data.right().saturating_sub(width));
            if start >= free_from {
                buf.set_string(start, labels_row, &label, style);
                free_from = start + width + 1;
            }
        }
        let title_width = self.x_title.chars().count() as u16;
        if title_width <= axis_x - inner.x {
            buf.set_string(axis_x - title_width, labels_row, self.x_title, style);
        }
    }
}

/// One labelled stretch of a [`Band`].
#[derive(Clone, Debug)]
pub struct Segment {
    pub from: f64,
    pub to: f64,
    pub label: String,
    pub color: Color,
}

/// One row of labelled stretches over the x axis of plots laid out with the same `label_width`, e.g. the
/// phases over the contact: `phases ━━ slide ━━┃━━━━ grip ━━━━┃━ slide ━`.
pub struct Band<'a> {
    /// Written in the label column.
    pub title: &'a str,
    pub x: &'a Scale,
    pub segments: Vec<Segment>,
    pub label_width: u16,
    pub title_style: Style,
    /// The marker of the plots below, whose columns the band follows.
    pub marker: Marker,
}

impl Widget for Band<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (first, width) = Plot::data_columns(area, self.label_width);
        if width < 4 || area.height == 0 {
            return;
        }
        let (across, _) = resolution(self.marker);
        let title_width = self.title.chars().count() as u16;
        if title_width <= self.label_width {
            buf.set_string(
                first - 1 - title_width,
                area.y,
                self.title,
                self.title_style,
            );
        }
        for (i, seg) in self.segments.iter().enumerate() {
            let start = first + self.x.cell(seg.from, width, across, false);
            let end = first + self.x.cell(seg.to, width, across, false);
            let style = Style::new().fg(seg.color);
            let fill = "━".repeat(usize::from(end.saturating_sub(start) + 1));
            buf.set_string(start, area.y, fill, style);
            if i > 0 {
                buf.set_string(start, area.y, "┃", Style::new());
            }
            // The whole label if it fits, else its first word.
            let short = seg.label.split(' ').next().unwrap_or_default();
            let fitting = [seg.label.as_str(), short]
                .into_iter()
                .find(|l| end.saturating_sub(start) >= l.chars().count() as u16 + 3);
            if let Some(label) = fitting {
                let len = label.chars().count() as u16;
                let at = start + (end - start + 1 - len) / 2;
                buf.set_string(at - 1, area.y, format!(" {label} "), style);
            }
        }
    }
}

/// y at `x` on the polyline through `points` (sorted by x); `None` outside it.
fn interpolate(points: &[(f64, f64)], x: f64) -> Option<f64> {
    let i = points.partition_point(|p| p.0 < x);
    match (i.checked_sub(1).map(|j| points[j]), points.get(i)) {
        (_, Some(b)) if b.0 == x => Some(b.1),
        (Some(a), Some(b)) => Some(a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)),
        _ => None,
    }
}

impl Widget for Plot<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let mut block = Block::new().borders(Borders::TOP).title(self.title.clone());
        if let Some(readout) = &self.readout {
            block = block.title(readout.clone().right_aligned());
        }
        let inner = block.inner(area);
        block.render(area, buf);
        let (first, width) = Self::data_columns(inner, self.label_width);
        if inner.height < FRAME_ROWS || width < 4 {
            return;
        }
        let data = Rect::new(first, inner.y, width, inner.height - 2);
        Canvas::default()
            .x_bounds(self.x.bounds)
            .y_bounds(self.y.bounds)
            .marker(self.marker)
            .paint(|ctx| self.paint(ctx, data))
            .render(data, buf);
        self.axes(inner, data, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounded_scales_cover_the_data_with_round_ticks() {
        let s = Scale::rounded(-37.0, 112.0, 5);
        assert_eq!(s.bounds, [-50.0, 150.0]);
        assert_eq!(s.labels(), ["-50", "0", "50", "100", "150"]);
        let s = Scale::rounded(0.0, 7.7, 4);
        assert_eq!(s.bounds, [0.0, 8.0]);
        assert_eq!(s.labels(), ["0", "4", "8"]);
        let s = Scale::rounded(0.0, 0.9, 7);
        assert_eq!(s.labels(), ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        // Few rows: tight bounds still, fewer labels, both ends labelled.
        let s = Scale::rounded(-140.0, 140.0, 3);
        assert_eq!(s.bounds, [-150.0, 150.0]);
        assert_eq!(s.labels(), ["-150", "0", "150"]);
        let s = Scale::rounded(-140.0, 140.0, 4);
        assert_eq!(s.labels(), ["-150", "0", "150"]);
        let s = Scale::rounded(-100.0, 160.8, 3);
        assert_eq!(s.bounds, [-100.0, 200.0]);
        assert_eq!(s.labels(), ["-100", "50", "200"]);
    }

    #[test]
    fn exact_scales_keep_the_bounds() {
        let s = Scale::exact(0.0, 5.0, 6);
        assert_eq!(s.bounds, [0.0, 5.0]);
        assert_eq!(s.labels(), ["0", "1", "2", "3", "4", "5"]);
        let s = Scale::exact(0.0, 90.0, 4);
        assert_eq!(s.bounds, [0.0, 90.0]);
        assert_eq!(s.labels(), ["0", "25", "50", "75"]);
    }

    #[test]
    fn flat_data_still_get_an_axis() {
        let s = Scale::rounded(0.0, 0.0, 3);
        assert!(s.bounds[0] < 0.0 && s.bounds[1] > 0.0);
        let s = Scale::rounded(-100.0, -100.0, 3);
        assert!(s.bounds[0] < -100.0 && s.bounds[1] > -100.0);
    }

    #[test]
    fn interpolates_inside_only() {
        let pts = [(0.0, 0.0), (1.0, 10.0), (2.0, 0.0)];
        assert_eq!(interpolate(&pts, 0.5), Some(5.0));
        assert_eq!(interpolate(&pts, 2.0), Some(0.0));
        assert_eq!(interpolate(&pts, 0.0), Some(0.0));
        assert_eq!(interpolate(&pts, 2.5), None);
    }
}
