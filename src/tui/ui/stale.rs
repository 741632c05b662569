//! Panels whose answer is pending on the worker: what they showed stays, with `solving…` on their top
//! row until the answer comes, and the outcome's numbers dimmed (only those: dimming the charts would
//! repaint every cell of them twice, a burden on a slow link); before any answer, the mark alone in a
//! bordered box.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

use crate::tui::app::App;

/// The mark on a pending panel.
pub const SOLVING: &str = " solving… ";

/// Dims what `area` shows and marks it.
pub fn dim(frame: &mut Frame, area: Rect, app: &App) {
    frame
        .buffer_mut()
        .set_style(area, Style::new().add_modifier(Modifier::DIM));
    mark(frame, area, app);
}

/// Writes the mark at the right of the top row of `area`.
pub fn mark(frame: &mut Frame, area: Rect, app: &App) {
    let buf = frame.buffer_mut();
    let text = app.theme.words(SOLVING);
    let width = text.chars().count() as u16;
    if area.width > width + 2 {
        buf.set_span(
            area.right() - width - 1,
            area.y,
            &Span::styled(text, app.theme.key()),
            width,
        );
    }
}

/// What a box says when the core refused the bounce and there is none to show.
pub const REFUSED: &str = " refused: the status line says why ";

/// A box titled `title` with the mark, where nothing has been solved yet (or, once the core has refused
/// the bounce, that it did).
pub fn pending(frame: &mut Frame, area: Rect, app: &App, title: &str) {
    let text = if app.solving() { SOLVING } else { REFUSED };
    let block = Block::bordered().title(Span::styled(
        format!(" {} ", app.theme.words(title)),
        app.theme.title(),
    ));
    frame.render_widget(
        Paragraph::new(Line::styled(app.theme.words(text), app.theme.key())).block(block),
        area,
    );
}
