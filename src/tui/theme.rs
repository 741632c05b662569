//! Colours and plot markers. Only the 16 basic named colours are used, so any colour terminal shows them;
//! with colour off (NO_COLOR) every colour is the terminal's own and the charts tell phases apart by
//! labels and markers instead.

use std::borrow::Cow;

use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;

use crate::model::PhaseKind;

/// How the explorer looks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Theme {
    /// False under NO_COLOR.
    pub color: bool,
    /// The marker the charts draw with (braille, dot or block).
    pub marker: Marker,
    /// True when the terminal gets ASCII only: key names are written as words (`Space`, `hjkl`).
    pub ascii: bool,
    /// True for a light terminal background (`--theme light`): the colours that wash out on white
    /// (yellow, cyan, grey) are swapped for darker ones.
    pub light: bool,
}

impl Default for Theme {
    fn default() -> Self {
        Theme {
            color: true,
            marker: Marker::Braille,
            ascii: false,
            light: false,
        }
    }
}

/// The dark theme's colour as the light theme draws it: yellow, cyan and the greys, which wash out on a
/// white background, become darker ones; the rest read well on both.
fn light(color: Color) -> Color {
    match color {
        Color::Yellow => Color::Magenta,
        Color::Magenta => Color::Black,
        Color::Cyan => Color::Blue,
        Color::Blue => Color::Cyan,
        Color::Gray => Color::DarkGray,
        Color::DarkGray => Color::Gray,
        other => other,
    }
}

/// What the ASCII screen writes for the symbols of the Unicode one, longest first: key pairs as the
/// letters that do the same (`↑↓` as `jk`), key symbols and Greek letters as words.
const WORDS: [(&str, &str); 19] = [
    ("↑↓", "jk"),
    ("←→", "hl"),
    ("␣", "Space"),
    ("⏎", "Enter"),
    ("↑", "Up"),
    ("↓", "Down"),
    ("←", "Left"),
    ("→", "->"),
    ("ω", "omega"),
    ("θ", "theta"),
    ("μ", "mu"),
    ("δ", "delta"),
    ("ψ", "psi"),
    ("φ", "phi"),
    ("σ", "sd"),
    ("Δ", "d"),
    ("±", "+-"),
    ("°", " deg"),
    ("…", "..."),
];

impl Theme {
    /// `text` for the screen: as it is, or in ASCII with the symbols spelt out (`WORDS`); what is
    /// left beyond ASCII the output replaces character by character.
    pub fn words<'a>(&self, text: &'a str) -> Cow<'a, str> {
        if !self.ascii || text.is_ascii() {
            return Cow::Borrowed(text);
        }
        let mut out = text.to_string();
        for (symbol, word) in WORDS {
            out = out.replace(symbol, word);
        }
        Cow::Owned(out)
    }

    /// Colour unless colour is off; on a light background, the light theme's counterpart.
    fn pick(&self, color: Color) -> Color {
        if !self.color {
            Color::Reset
        } else if self.light {
            light(color)
        } else {
            color
        }
    }

    /// The colour of a phase's curves and labels.
    pub fn phase(&self, kind: PhaseKind) -> Color {
        self.pick(match kind {
            PhaseKind::Slide => Color::Yellow,
            PhaseKind::Grip => Color::Cyan,
        })
    }

    /// The cart's displacement while string friction holds it still.
    pub fn stuck(&self) -> Color {
        self.pick(Color::Blue)
    }

    /// The grip limit +/- mu N.
    pub fn limit(&self) -> Color {
        self.pick(Color::Red)
    }

    /// Transitions, zero lines and other guides.
    pub fn guide(&self) -> Color {
        self.pick(Color::DarkGray)
    }

    /// The time cursor on the charts, and the rotation mark on the ball in the schematic.
    pub fn cursor(&self) -> Color {
        self.pick(Color::Magenta)
    }

    /// The comparison curve (the other incident spin) in the sweep view.
    pub fn comparison(&self) -> Color {
        self.pick(Color::Magenta)
    }

    /// The ball and the cart in the schematic: the terminal's own colour.
    pub fn body(&self) -> Color {
        Color::Reset
    }

    /// The spring in the schematic.
    pub fn spring(&self) -> Color {
        self.pick(Color::Gray)
    }

    /// The current incidence angle in the sweep view.
    pub fn current(&self) -> Color {
        self.pick(Color::Green)
    }

    /// Panel titles.
    pub fn title(&self) -> Style {
        Style::new()
            .fg(self.pick(Color::Cyan))
            .add_modifier(Modifier::BOLD)
    }

    /// The highlighted parameter row.
    pub fn selected(&self) -> Style {
        if self.color {
            Style::new()
                .fg(if self.light {
                    Color::White
                } else {
                    Color::Black
                })
                .bg(self.pick(Color::Cyan))
                .add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        }
    }

    /// Secondary text: units, axis labels, hints.
    pub fn dim(&self) -> Style {
        if self.color {
            Style::new().fg(self.pick(Color::Gray))
        } else {
            Style::new()
        }
    }

    /// Key names in hints and help.
    pub fn key(&self) -> Style {
        Style::new()
            .fg(self.pick(Color::Yellow))
            .add_modifier(Modifier::BOLD)
    }

    /// Numbers that matter most (the rebound spin).
    pub fn emphasis(&self) -> Style {
        Style::new()
            .fg(self.pick(Color::Green))
            .add_modifier(Modifier::BOLD)
    }

    /// Error messages.
    pub fn error(&self) -> Style {
        Style::new()
            .fg(self.pick(Color::Red))
            .add_modifier(Modifier::BOLD)
    }
    /// Measured points drawn on the charts (`--data`).
    pub fn measured(&self) -> Color {
        self.pick(Color::Red)
    }

    /// The uncertainty band of the sweep view.
    pub fn band(&self) -> Color {
        self.pick(Color::Blue)
    }

    /// The pinned baseline's curves, under the current ones. Without colour they are drawn dotted
    /// instead (see `ui::charts`).
    pub fn baseline(&self) -> Color {
        self.pick(Color::DarkGray)
    }
}
