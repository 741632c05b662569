//! Bytes from the terminal into key and mouse events. A stray or truncated escape sequence (`ESC[?`,
//! `ESC[<`, `ESC[200~` arriving alone) never swallows the keys after it: a byte that cannot continue a
//! sequence ends it (the partial sequence is dropped and the byte read afresh), a complete sequence the
//! explorer has no use for is dropped whole, and a sequence left incomplete when the input goes quiet is
//! dropped by [`Decoder::flush`] (a lone ESC is the Esc key), so `q` and Ctrl-C always act.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};

/// What the front of the input holds.
enum Step {
    /// An event, and the bytes it took.
    Event(Event, usize),
    /// Bytes to drop: a sequence of no use, or one broken off.
    Skip(usize),
    /// The start of a sequence whose end has not arrived.
    Incomplete,
}

/// The bytes read but not decoded yet.
#[derive(Debug, Default)]
pub struct Decoder {
    pending: Vec<u8>,
}

impl Decoder {
    /// Decodes what `bytes` complete; an unfinished sequence waits for more.
    pub fn feed(&mut self, bytes: &[u8]) -> Vec<Event> {
        self.pending.extend_from_slice(bytes);
        let mut events = Vec::new();
        let mut at = 0;
        while at < self.pending.len() {
            match step(&self.pending[at..]) {
                Step::Event(event, used) => {
                    events.push(event);
                    at += used;
                }
                Step::Skip(used) => at += used,
                Step::Incomplete => break,
            }
        }
        self.pending.drain(..at);
        events
    }

    /// True while an unfinished sequence waits.
    pub fn waiting(&self) -> bool {
        !self.pending.is_empty()
    }

    /// The input went quiet: a lone ESC is the Esc key, anything else unfinished is dropped.
    pub fn flush(&mut self) -> Option<Event> {
        let lone_escape = self.pending == [0x1b];
        self.pending.clear();
        lone_escape.then(|| key(KeyCode::Esc, KeyModifiers::NONE))
    }
}

fn key(code: KeyCode, modifiers: KeyModifiers) -> Event {
    Event::Key(KeyEvent::new(code, modifiers))
}

/// The first event of `bytes`.
fn step(bytes: &[u8]) -> Step {
    match bytes[0] {
        0x1b => escape(bytes),
        byte => match plain(bytes) {
            Some((code, modifiers, used)) => Step::Event(key(code, modifiers), used),
            None if byte >= 0xc0 && bytes.len() < utf8_len(byte) => Step::Incomplete,
            None => Step::Skip(1),
        },
    }
}

/// The length of the UTF-8 character that `lead` starts.
fn utf8_len(lead: u8) -> usize {
    match lead {
        0xc0..=0xdf => 2,
        0xe0..=0xef => 3,
        _ => 4,
    }
}

/// A key that is not an escape sequence: a control byte or a character. `None` for a broken or
/// unfinished character.
fn plain(bytes: &[u8]) -> Option<(KeyCode, KeyModifiers, usize)> {
    let none = KeyModifiers::NONE;
    let (code, modifiers) = match bytes[0] {
        b'\r' | b'\n' => (KeyCode::Enter, none),
        b'\t' => (KeyCode::Tab, none),
        0x7f | 0x08 => (KeyCode::Backspace, none),
        0x00 => (KeyCode::Char(' '), KeyModifiers::CONTROL),
        byte @ 0x01..=0x1a => (
            KeyCode::Char(char::from(b'a' + byte - 1)),
            KeyModifiers::CONTROL,
        ),
        byte @ 0x1c..=0x1f => (
            KeyCode::Char(char::from(b'4' + byte - 0x1c)),
            KeyModifiers::CONTROL,
        ),
        byte @ 0x20..=0x7e => {
            let c = char::from(byte);
            let shift = if c.is_ascii_uppercase() {
                KeyModifiers::SHIFT
            } else {
                none
            };
            (KeyCode::Char(c), shift)
        }
        lead => {
            let len = utf8_len(lead);
            let c = std::str::from_utf8(bytes.get(..len)?)
                .ok()?
                .chars()
                .next()?;
            return Some((KeyCode::Char(c), none, len));
        }
    };
    Some((code, modifiers, 1))
}

/// What starts with ESC: a CSI or SS3 sequence, Alt with a key, or Esc itself.
fn escape(bytes: &[u8]) -> Step {
    match bytes.get(1) {
        None => Step::Incomplete,
        Some(b'[') => csi(bytes),
        Some(b'O') => match bytes.get(2) {
            None => Step::Incomplete,
            Some(&last @ 0x40..=0x7e) => match cursor_key(last) {
                Some(code) => Step::Event(key(code, KeyModifiers::NONE), 3),
                None => Step::Skip(3),
            },
            // Broken off: drop `ESC O` and read the byte afresh.
            Some(_) => Step::Skip(2),
        },
        // ESC before a control byte or another ESC is the Esc key, then that byte.
        Some(&next) if next < 0x20 || next == 0x7f => {
            Step::Event(key(KeyCode::Esc, KeyModifiers::NONE), 1)
        }
        Some(_) => match plain(&bytes[1..]) {
            Some((code, modifiers, used)) => {
                Step::Event(key(code, modifiers | KeyModifiers::ALT), used + 1)
            }
            None if bytes.len() < 1 + utf8_len(bytes[1]) => Step::Incomplete,
            None => Step::Skip(2),
        },
    }
}

/// The key of a cursor-key final byte (`A` up ... `H` home, `F` end).
fn cursor_key(last: u8) -> Option<KeyCode> {
    Some(match last {
        b'A' => KeyCode::Up,
        b'B' => KeyCode::Down,
        b'C' => KeyCode::Right,
        b'D' => KeyCode::Left,
        b'H' => KeyCode::Home,
        b'F' => KeyCode::End,
        b'Z' => KeyCode::BackTab,
        _ => return None,
    })
}

/// Modifiers from a CSI modifier parameter (1 + shift 1, alt 2, ctrl 4).
fn modifiers(param: Option<u16>) -> KeyModifiers {
    let bits = param.unwrap_or(1).saturating_sub(1);
    let mut m = KeyModifiers::NONE;
    for (bit, flag) in [
        (1, KeyModifiers::SHIFT),
        (2, KeyModifiers::ALT),
        (4, KeyModifiers::CONTROL),
    ] {
        if bits & bit != 0 {
            m |= flag;
        }
    }
    m
}

/// `ESC [` parameters, intermediates, a final byte. A byte outside those ranges breaks it off.
fn csi(bytes: &[u8]) -> Step {
    let mut end = 2;
    loop {
        match bytes.get(end) {
            None => return Step::Incomplete,
            Some(0x20..=0x3f) => end += 1,
            Some(0x40..=0x7e) => break,
            Some(_) => return Step::Skip(end),
        }
    }
    let last = bytes[end];
    let body = &bytes[2..end];
    // X10 mouse (a terminal without SGR reports): `ESC [ M` and three bytes.
    if last == b'M' && body.is_empty() {
        return match bytes.get(end + 1..end + 4) {
            Some(&[b, x, y]) => match mouse(
                u16::from(b.saturating_sub(32)),
                u16::from(x.saturating_sub(33)),
                u16::from(y.saturating_sub(33)),
                true,
            ) {
                Some(event) => Step::Event(event, end + 4),
                None => Step::Skip(end + 4),
            },
            _ => Step::Incomplete,
        };
    }
    let used = end + 1;
    let text = String::from_utf8_lossy(body);
    if let Some(sgr) = text.strip_prefix('<') {
        let numbers: Vec<u16> = sgr.split(';').filter_map(|n| n.parse().ok()).collect();
        return match (numbers.as_slice(), last) {
            (&[b, x, y], b'M' | b'm') => {
                match mouse(b, x.saturating_sub(1), y.saturating_sub(1), last == b'M') {
                    Some(event) => Step::Event(event, used),
                    None => Step::Skip(used),
                }
            }
            _ => Step::Skip(used),
        };
    }
    let params: Vec<Option<u16>> = text.split(';').map(|n| n.parse().ok()).collect();
    let code = match (last, params.first().copied().flatten()) {
        (b'~', Some(1 | 7)) => Some(KeyCode::Home),
        (b'~', Some(4 | 8)) => Some(KeyCode::End),
        (b'~', Some(2)) => Some(KeyCode::Insert),
        (b'~', Some(3)) => Some(KeyCode::Delete),
        (b'~', Some(5)) => Some(KeyCode::PageUp),
        (b'~', Some(6)) => Some(KeyCode::PageDown),
        (b'~', _) => None,
        (last, _) => cursor_key(last),
    };
    match code {
        Some(code) => Step::Event(key(code, modifiers(params.get(1).copied().flatten())), used),
        None => Step::Skip(used),
    }
}

/// A mouse report: button code `b` (low bits the button, 32 motion, 64 wheel, 4/8/16 shift/alt/ctrl)
/// at the zero-based cell (`column`, `row`); `pressed` false for a release.
fn mouse(b: u16, column: u16, row: u16, pressed: bool) -> Option<Event> {
    let button = match b & 3 {
        0 => MouseButton::Left,
        1 => MouseButton::Middle,
        2 => MouseButton::Right,
        _ => MouseButton::Left,
    };
    let kind = if b & 64 != 0 {
        match b & 3 {
            0 => MouseEventKind::ScrollUp,
            1 => MouseEventKind::ScrollDown,
            _ => return None,
        }
    } else if b & 32 != 0 {
        if b & 3 == 3 {
            MouseEventKind::Moved
        } else {
            MouseEventKind::Drag(button)
        }
    } else if !pressed || b & 3 == 3 {
        MouseEventKind::Up(button)
    } else {
        MouseEventKind::Down(button)
    };
    let mut modifiers = KeyModifiers::NONE;
    for (bit, flag) in [
        (4, KeyModifiers::SHIFT),
        (8, KeyModifiers::ALT),
        (16, KeyModifiers::CONTROL),
    ] {
        if b & bit != 0 {
            modifiers |= flag;
        }
    }
    Some(Event::Mouse(MouseEvent {
        kind,
        column,
        row,
        modifiers,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn codes(events: &[Event]) -> Vec<(KeyCode, KeyModifiers)> {
        events
            .iter()
            .filter_map(|e| match e {
                Event::Key(k) => Some((k.code, k.modifiers)),
                _ => None,
            })
            .collect()
    }

    const NONE: KeyModifiers = KeyModifiers::NONE;

    #[test]
    fn keys_and_sequences() {
        let mut d = Decoder::default();
        let events = d.feed(b"aL\r\t\x7f\x03\x1b[A\x1bOB\x1b[1;2C\x1b[4~\x1b[H\xce\xb8");
        assert_eq!(
            codes(&events),
            vec![
                (KeyCode::Char('a'), NONE),
                (KeyCode::Char('L'), KeyModifiers::SHIFT),
                (KeyCode::Enter, NONE),
                (KeyCode::Tab, NONE),
                (KeyCode::Backspace, NONE),
                (KeyCode::Char('c'), KeyModifiers::CONTROL),
                (KeyCode::Up, NONE),
                (KeyCode::Down, NONE),
                (KeyCode::Right, KeyModifiers::SHIFT),
                (KeyCode::End, NONE),
                (KeyCode::Home, NONE),
                (KeyCode::Char('θ'), NONE),
            ]
        );
        assert!(!d.waiting());
    }

    #[test]
    fn sequences_split_across_reads_wait_for_their_end() {
        let mut d = Decoder::default();
        assert!(d.feed(b"\x1b[").is_empty());
        assert!(d.waiting());
        assert_eq!(codes(&d.feed(b"D")), vec![(KeyCode::Left, NONE)]);
        assert!(d.feed(b"\xce").is_empty());
        assert_eq!(codes(&d.feed(b"\xbc")), vec![(KeyCode::Char('μ'), NONE)]);
    }

    #[test]
    fn a_stray_sequence_swallows_no_later_key() {
        for stray in [
            &b"\x1b[?"[..],
            b"\x1b[<",
            b"\x1b[200~",
            b"\x1bO",
            b"\x1b[1;",
        ] {
            let mut d = Decoder::default();
            let mut events = d.feed(stray);
            // The input goes quiet: whatever is unfinished is dropped.
            events.extend(d.flush());
            events.extend(d.feed(b"q"));
            assert_eq!(
                codes(&events).last(),
                Some(&(KeyCode::Char('q'), NONE)),
                "{stray:?}"
            );
            // Ctrl-C right behind the stray bytes, in the same read, breaks the sequence off.
            let mut d = Decoder::default();
            let events = d.feed(&[stray, b"\x03"].concat());
            assert_eq!(
                codes(&events).last(),
                Some(&(KeyCode::Char('c'), KeyModifiers::CONTROL)),
                "{stray:?}"
            );
        }
        // A lone ESC is the Esc key once the input is quiet.
        let mut d = Decoder::default();
        assert!(d.feed(b"\x1b").is_empty());
        assert_eq!(d.flush(), Some(key(KeyCode::Esc, NONE)));
    }

    #[test]
    fn mouse_reports() {
        let mut d = Decoder::default();
        let events = d.feed(b"\x1b[<0;10;5M\x1b[<32;11;5M\x1b[<0;11;5m\x1b[M\x20\x2a\x26");
        let kinds: Vec<(MouseEventKind, u16, u16)> = events
            .iter()
            .filter_map(|e| match e {
                Event::Mouse(m) => Some((m.kind, m.column, m.row)),
                _ => None,
            })
            .collect();
        assert_eq!(
            kinds,
            vec![
                (MouseEventKind::Down(MouseButton::Left), 9, 4),
                (MouseEventKind::Drag(MouseButton::Left), 10, 4),
                (MouseEventKind::Up(MouseButton::Left), 10, 4),
                (MouseEventKind::Down(MouseButton::Left), 9, 5),
            ]
        );
    }
}
