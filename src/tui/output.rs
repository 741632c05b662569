//! The explorer's own ratatui backend, written for a slow link: each frame goes out in one write, the
//! cursor takes the shortest move to the next changed cell (line feeds and backspaces, which raw mode
//! leaves as plain moves, relative steps, a carriage return or an absolute position, whichever is fewest
//! bytes), a style change is one SGR sequence with only what changed (and none for a blank, whose
//! foreground does not show), and the named colours are the 16 basic SGR codes (30-37, 90-97 and +10 for
//! the background), which every colour terminal knows, where crossterm would write 256-colour ones.
//!
//! With `ascii` set (a locale that is not UTF-8, or `--ascii`), every character is written as ASCII
//! ([`ascii`]): whatever the widgets drew, no byte above 0x7f leaves.

use std::fmt::Write as _;
use std::io::{self, Write};

use crossterm::terminal;
use ratatui::backend::{Backend, ClearType, TestBackend, WindowSize};
use ratatui::buffer::Cell;
use ratatui::layout::{Position, Size};
use ratatui::style::{Color, Modifier};
use ratatui::text::Span;

/// How a cell is drawn: its colours and modifiers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Pen {
    fg: Color,
    bg: Color,
    modifier: Modifier,
}

/// The backend: a writer, and what the terminal is known to show now.
#[derive(Debug)]
pub struct Output<W: Write> {
    writer: W,
    /// The frame being assembled, written whole on flush.
    pending: Vec<u8>,
    ascii: bool,
    /// Where the terminal's cursor is, if known.
    at: Option<Position>,
    /// The pen the terminal draws with, if known.
    pen: Option<Pen>,
    cursor_shown: Option<bool>,
    /// The terminal's width when last asked (ratatui asks before every frame).
    columns: std::cell::Cell<u16>,
}

impl<W: Write> Output<W> {
    pub fn new(writer: W, ascii: bool) -> Self {
        Output {
            writer,
            pending: Vec::with_capacity(16 * 1024),
            ascii,
            at: None,
            pen: None,
            cursor_shown: None,
            columns: std::cell::Cell::new(0),
        }
    }

    /// The writer, for tests that look at what was written.
    pub fn writer(&self) -> &W {
        &self.writer
    }

    fn push(&mut self, text: &str) {
        self.pending.extend_from_slice(text.as_bytes());
    }

    /// Moves the cursor to `to` in the fewest bytes.
    fn move_to(&mut self, to: Position) {
        if self.at == Some(to) {
            return;
        }
        let absolute = if to.x == 0 {
            format!("\x1b[{}H", to.y + 1)
        } else {
            format!("\x1b[{};{}H", to.y + 1, to.x + 1)
        };
        let best = match self.at {
            Some(from) => {
                // Down by line feeds (never from the last row, so they never scroll), left by backspaces.
                let vertical = match to.y.cmp(&from.y) {
                    std::cmp::Ordering::Equal => String::new(),
                    std::cmp::Ordering::Greater => {
                        shortest(steps(to.y - from.y, 'B'), '\n', to.y - from.y)
                    }
                    std::cmp::Ordering::Less => steps(from.y - to.y, 'A'),
                };
                let horizontal = if to.x == from.x {
                    String::new()
                } else if to.x == 0 {
                    "\r".to_string()
                } else if to.x > from.x {
                    steps(to.x - from.x, 'C')
                } else {
                    shortest(steps(from.x - to.x, 'D'), '\x08', from.x - to.x)
                };
                let relative = vertical + &horizontal;
                if relative.len() <= absolute.len() {
                    relative
                } else {
                    absolute
                }
            }
            None => absolute,
        };
        self.push(&best);
        self.at = Some(to);
    }

    /// Sets the pen to `pen` with one SGR sequence holding only what changed.
    fn pen(&mut self, pen: Pen) {
        if self.pen == Some(pen) {
            return;
        }
        let mut codes = String::new();
        let add = |codes: &mut String, code: &str| {
            if !codes.is_empty() {
                codes.push(';');
            }
            codes.push_str(code);
        };
        let (from, reset) = match self.pen {
            // A modifier taken away: start from nothing.
            Some(old) if old.modifier - pen.modifier == Modifier::empty() => (old, false),
            _ => (
                Pen {
                    fg: Color::Reset,
                    bg: Color::Reset,
                    modifier: Modifier::empty(),
                },
                true,
            ),
        };
        if reset {
            add(&mut codes, "0");
        }
        for (flag, code) in MODIFIERS {
            if pen.modifier.contains(flag) && !from.modifier.contains(flag) {
                add(&mut codes, code);
            }
        }
        if pen.fg != from.fg {
            add(&mut codes, &color(pen.fg, 0));
        }
        if pen.bg != from.bg {
            add(&mut codes, &color(pen.bg, 10));
        }
        self.push(&format!("\x1b[{codes}m"));
        self.pen = Some(pen);
    }
}

/// `sequence`, or `n` times `byte` if that is shorter.
fn shortest(sequence: String, byte: char, n: u16) -> String {
    if usize::from(n) < sequence.len() {
        std::iter::repeat_n(byte, usize::from(n)).collect()
    } else {
        sequence
    }
}

/// Modifiers that show on a blank cell.
const SHOW_ON_BLANK: Modifier = Modifier::REVERSED
    .union(Modifier::UNDERLINED)
    .union(Modifier::CROSSED_OUT);

/// `n` steps of the cursor in direction `letter`: `ESC[C` for one, `ESC[5C` for five.
fn steps(n: u16, letter: char) -> String {
    if n == 1 {
        format!("\x1b[{letter}")
    } else {
        format!("\x1b[{n}{letter}")
    }
}

/// The SGR codes of the modifiers.
const MODIFIERS: [(Modifier, &str); 9] = [
    (Modifier::BOLD, "1"),
    (Modifier::DIM, "2"),
    (Modifier::ITALIC, "3"),
    (Modifier::UNDERLINED, "4"),
    (Modifier::SLOW_BLINK, "5"),
    (Modifier::RAPID_BLINK, "6"),
    (Modifier::REVERSED, "7"),
    (Modifier::HIDDEN, "8"),
    (Modifier::CROSSED_OUT, "9"),
];

/// The SGR code of a foreground colour (`offset` 0) or a background one (`offset` 10).
fn color(color: Color, offset: u8) -> String {
    let basic = |code: u8| (code + offset).to_string();
    match color {
        Color::Reset => basic(39),
        Color::Black => basic(30),
        Color::Red => basic(31),
        Color::Green => basic(32),
        Color::Yellow => basic(33),
        Color::Blue => basic(34),
        Color::Magenta => basic(35),
        Color::Cyan => basic(36),
        Color::Gray => basic(37),
        Color::DarkGray => basic(90),
        Color::LightRed => basic(91),
        Color::LightGreen => basic(92),
        Color::LightYellow => basic(93),
        Color::LightBlue => basic(94),
        Color::LightMagenta => basic(95),
        Color::LightCyan => basic(96),
        Color::White => basic(97),
        Color::Indexed(i) => format!("{};5;{i}", 38 + offset),
        Color::Rgb(r, g, b) => format!("{};2;{r};{g};{b}", 38 + offset),
    }
}

/// `symbol` in ASCII: box drawing as `-|+`, arrows as `<>^v`, shades and blocks as `.:+#@`, braille as
/// `.`, Greek letters by their Latin look-alikes; anything else `?`.
pub fn ascii(symbol: &str) -> String {
    symbol
        .chars()
        .map(|c| match c {
            ' '..='~' => c,
            '─' | '━' | '┄' | '╌' | '┈' => '-',
            '│' | '┃' | '┆' | '▏' | '╎' => '|',
            '┌' | '┐' | '└' | '┘' | '┬' | '┴' | '├' | '┤' | '┼' => '+',
            '╱' => '/',
            '╲' => '\\',
            '→' | '▶' | '▸' => '>',
            '←' | '◀' => '<',
            '↑' | '▲' => '^',
            '↓' | '▼' => 'v',
            '·' | '…' | '•' => '.',
            '░' => ':',
            '▒' => '+',
            '▓' => '#',
            '█' | '▀' | '▄' | '●' => '@',
            '⠀' => ' ',
            '\u{2801}'..='\u{28ff}' => '.',
            'ω' => 'w',
            'θ' => 't',
            'μ' | 'µ' => 'u',
            'Δ' => 'd',
            'α' => 'a',
            'ζ' => 'z',
            'δ' => 'd',
            'ψ' => 'y',
            'φ' => 'f',
            '±' => '+',
            '°' => 'o',
            '×' => 'x',
            '²' => '2',
            '␣' => '_',
            '⏎' => '<',
            _ => '?',
        })
        .collect()
}

impl<W: Write> Backend for Output<W> {
    type Error = io::Error;

    fn draw<'a, I>(&mut self, content: I) -> io::Result<()>
    where
        I: Iterator<Item = (u16, u16, &'a Cell)>,
    {
        let columns = self.columns.get();
        for (x, y, cell) in content {
            self.move_to(Position { x, y });
            let symbol = cell.symbol();
            let pen = Pen {
                fg: cell.fg,
                bg: cell.bg,
                modifier: cell.modifier,
            };
            // A blank looks the same in any foreground and boldness: keep the pen if it would.
            let blank_as_is = symbol == " "
                && self.pen.is_some_and(|now| {
                    now.bg == pen.bg && !(now.modifier | pen.modifier).intersects(SHOW_ON_BLANK)
                });
            if !blank_as_is {
                self.pen(pen);
            }
            let width = if self.ascii {
                let text = ascii(symbol);
                self.push(&text);
                1
            } else {
                self.push(symbol);
                Span::raw(symbol).width().max(1) as u16
            };
            // At the right margin the cursor's place depends on the terminal: ask for it anew.
            self.at = (x + width < columns).then_some(Position { x: x + width, y });
        }
        Ok(())
    }

    fn hide_cursor(&mut self) -> io::Result<()> {
        if self.cursor_shown != Some(false) {
            self.push("\x1b[?25l");
            self.cursor_shown = Some(false);
        }
        Ok(())
    }

    fn show_cursor(&mut self) -> io::Result<()> {
        if self.cursor_shown != Some(true) {
            self.push("\x1b[?25h");
            self.cursor_shown = Some(true);
        }
        Ok(())
    }

    fn get_cursor_position(&mut self) -> io::Result<Position> {
        Ok(self.at.unwrap_or_default())
    }

    fn set_cursor_position<P: Into<Position>>(&mut self, position: P) -> io::Result<()> {
        self.move_to(position.into());
        Ok(())
    }

    fn clear(&mut self) -> io::Result<()> {
        self.pen(Pen {
            fg: Color::Reset,
            bg: Color::Reset,
            modifier: Modifier::empty(),
        });
        self.push("\x1b[2J");
        Ok(())
    }

    fn clear_region(&mut self, clear_type: ClearType) -> io::Result<()> {
        let code = match clear_type {
            ClearType::All => "2J",
            ClearType::AfterCursor => "J",
            ClearType::BeforeCursor => "1J",
            ClearType::CurrentLine => "2K",
            ClearType::UntilNewLine => "K",
        };
        let mut text = String::new();
        let _ = write!(text, "\x1b[{code}");
        self.push(&text);
        Ok(())
    }

    fn size(&self) -> io::Result<Size> {
        let (width, height) = terminal::size()?;
        self.columns.set(width);
        Ok(Size { width, height })
    }

    fn window_size(&mut self) -> io::Result<WindowSize> {
        let size = terminal::window_size()?;
        Ok(WindowSize {
            columns_rows: Size {
                width: size.columns,
                height: size.rows,
            },
            pixels: Size {
                width: size.width,
                height: size.height,
            },
        })
    }

    fn flush(&mut self) -> io::Result<()> {
        if !self.pending.is_empty() {
            self.writer.write_all(&self.pending)?;
            self.pending.clear();
        }
        self.writer.flush()
    }
}

/// A backend that can bracket each frame so that a slow link never shows half of one.
pub trait FrameSync {
    fn begin_frame(&mut self) -> io::Result<()>;
    fn end_frame(&mut self) -> io::Result<()>;
}

/// Frames in memory need no bracket.
impl FrameSync for TestBackend {
    fn begin_frame(&mut self) -> io::Result<()> {
        Ok(())
    }

    fn end_frame(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// Synchronized updates (DEC mode 2026): the terminal shows the frame once it is complete. Terminals
/// without the mode ignore it.
impl<W: Write> FrameSync for Output<W> {
    fn begin_frame(&mut self) -> io::Result<()> {
        self.push("\x1b[?2026h");
        Ok(())
    }

    fn end_frame(&mut self) -> io::Result<()> {
        self.push("\x1b[?2026l");
        self.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_leaves_no_byte_above_0x7f() {
        let all: String = (0x20..0x3000u32).filter_map(char::from_u32).collect();
        assert!(ascii(&all).is_ascii());
        assert_eq!(ascii("┌ θ1 ─ ω2 ┐"), "+ t1 - w2 +");
    }

    #[test]
    fn colours_are_basic_sgr_codes_and_moves_are_short() {
        let mut out = Output::new(Vec::new(), false);
        out.pen(Pen {
            fg: Color::DarkGray,
            bg: Color::Reset,
            modifier: Modifier::BOLD,
        });
        out.pen(Pen {
            fg: Color::Yellow,
            bg: Color::Blue,
            modifier: Modifier::BOLD,
        });
        out.pen(Pen {
            fg: Color::Yellow,
            bg: Color::Blue,
            modifier: Modifier::empty(),
        });
        out.move_to(Position { x: 5, y: 3 });
        out.move_to(Position { x: 6, y: 4 });
        out.move_to(Position { x: 0, y: 4 });
        let written = String::from_utf8(out.pending.clone()).unwrap();
        assert_eq!(
            written,
            "\x1b[0;1;90m\x1b[33;44m\x1b[0;33;44m\x1b[4;6H\n\x1b[C\r"
        );
        // Down two rows and back two columns: line feeds and backspaces.
        out.pending.clear();
        out.move_to(Position { x: 8, y: 4 });
        out.move_to(Position { x: 6, y: 6 });
        assert_eq!(out.pending, b"\x1b[8C\n\n\x08\x08");
    }

    #[test]
    fn a_frame_goes_out_in_one_write_in_ascii_when_asked() {
        /// Counts the writes.
        #[derive(Default)]
        struct Writes(Vec<Vec<u8>>);
        impl Write for Writes {
            fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
                self.0.push(buf.to_vec());
                Ok(buf.len())
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let mut out = Output::new(Writes::default(), true);
        let cell = Cell::new("ω");
        out.draw([(0, 0, &cell)].into_iter()).unwrap();
        out.end_frame().unwrap();
        assert_eq!(out.writer().0.len(), 1);
        assert!(out.writer().0[0].is_ascii());
    }
}
