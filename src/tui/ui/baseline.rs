//! How the pinned baseline is drawn: under the current curves, dark grey, or dotted without colour (where
//! dashes already mean the grip limit and the guides).

use ratatui::style::Style;
use ratatui::text::Span;

use super::plot::Mark;
use crate::tui::theme::Theme;

/// The baseline's curve through `points` (sorted by x) in a plot about `columns` wide.
pub fn curve(points: &[(f64, f64)], theme: &Theme, columns: u16) -> Vec<Mark> {
    if theme.color {
        let color = theme.baseline();
        vec![Mark::Path(
            points.iter().map(|&(x, y)| (x, y, color)).collect(),
        )]
    } else {
        // A dot about every third column: sparser than the dashed guides.
        let wanted = usize::from(columns / 3).max(2);
        let stride = points.len().div_ceil(wanted).max(1);
        points
            .iter()
            .step_by(stride)
            .map(|&(x, y)| Mark::Dot(x, y, theme.baseline()))
            .collect()
    }
}

/// The legend for a chart title: `━ baseline`, or `· baseline` without colour.
pub fn legend(theme: &Theme) -> Span<'static> {
    let text = if theme.color {
        "━ baseline "
    } else {
        "· baseline "
    };
    Span::styled(text, Style::new().fg(theme.baseline()))
}
