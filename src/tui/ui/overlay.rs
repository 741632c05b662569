//! A box over the screen: the help and the preset picker. Centred, bordered, as tall as its wrapped lines.

use ratatui::Frame;
use ratatui::layout::{Constraint, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Wrap};

/// Rows `lines` take, wrapped at `text_width` columns.
pub fn rows(lines: &[Line], text_width: u16) -> u16 {
    let text_width = usize::from(text_width).max(1);
    lines
        .iter()
        .map(|l| l.width().max(1).div_ceil(text_width) as u16)
        .sum()
}

/// Draws `lines` in a box `width` wide centred in `area`, with `title` on the top border and `footer` on
/// the bottom one, as tall as the lines wrap to and no taller than `area`, scrolled down by `scroll` rows
/// (at most to the last row).
pub fn render(
    frame: &mut Frame,
    area: Rect,
    width: u16,
    title: Span<'static>,
    footer: String,
    lines: Vec<Line<'static>>,
    scroll: u16,
) {
    let total = rows(&lines, width.saturating_sub(2));
    let height = (total + 2).min(area.height);
    let scroll = scroll.min(total.saturating_sub(height.saturating_sub(2)));
    let popup = area.centered(Constraint::Length(width), Constraint::Length(height));
    let block = Block::bordered()
        .title(title)
        .title_bottom(Line::from(footer).right_aligned());
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(lines)
            .block(block)
            .wrap(Wrap { trim: false })
            .scroll((scroll, 0)),
        popup,
    );
}
