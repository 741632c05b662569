//! The documents' captures of the explorer (README.md's and `docs/*.md`'s) are the explorer's screens:
//! each `text` block after a comment
//! `<!-- screen WIDTHxHEIGHT [no-colour] [data=FILE] [preset=NAME] keys: KEY ... -->` must be what the
//! explorer draws on a screen of that size (with the measurements in FILE, as `--data FILE`, started from
//! the preset, as `--preset NAME`, in shot mode for a shot) after those keys (`]x14`
//! presses `]` fourteen times; `Tab`, `}` and other characters as named), once the heatmap, if shown,
//! has filled in. `README_BLESS=1 cargo test --release --test tui readme_screens` rewrites each stale
//! capture with what the explorer draws.

use std::io;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::Terminal;
use ratatui::backend::TestBackend;
use snapback::analysis::fit::data;
use snapback::model::Params;
use snapback::tui::theme::Theme;
use snapback::tui::{App, EventSource, Input, run};

use crate::support::screen;

/// The documents that may hold captures, relative to the repository: README.md and the guide.
fn documents() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut all: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/ is readable")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    all.sort();
    all.insert(0, root.join("README.md"));
    all
}

/// A screen capture: where it is, how to draw it, and what it shows.
struct Capture {
    /// The line of its comment (1-based), and the lines of its text (0-based, end excluded).
    line: usize,
    text: (usize, usize),
    size: (u16, u16),
    colour: bool,
    /// The measurements' file, relative to the repository.
    data: Option<String>,
    /// The preset the explorer starts from.
    preset: Option<String>,
    keys: Vec<Input>,
    shown: String,
}

fn key(name: &str) -> Input {
    let code = match name {
        "Tab" => KeyCode::Tab,
        _ => {
            let mut chars = name.chars();
            let c = chars.next().expect("a key");
            assert!(chars.next().is_none(), "unknown key {name}");
            KeyCode::Char(c)
        }
    };
    Input::Event(Event::Key(KeyEvent::new(code, KeyModifiers::NONE)))
}

/// The keys of `spec`, e.g. `} ]x14`.
fn keys(spec: &str) -> Vec<Input> {
    spec.split_whitespace()
        .flat_map(|word| {
            let (name, times) = match word.rsplit_once('x') {
                Some((name, n)) if !name.is_empty() && n.parse::<usize>().is_ok() => {
                    (name, n.parse().unwrap())
                }
                _ => (word, 1),
            };
            std::iter::repeat_n(key(name), times)
        })
        .collect()
}

fn captures(document: &str) -> Vec<Capture> {
    let lines: Vec<&str> = document.lines().collect();
    let mut found = Vec::new();
    for (n, line) in lines.iter().enumerate() {
        let Some(spec) = line
            .strip_prefix("<!-- screen ")
            .and_then(|s| s.strip_suffix(" -->"))
        else {
            continue;
        };
        let (head, key_spec) = spec.split_once("keys:").expect("`keys:` in the comment");
        let mut words = head.split_whitespace();
        let (w, h) = words.next().unwrap().split_once('x').unwrap();
        let options: Vec<&str> = words.collect();
        let colour = !options.contains(&"no-colour");
        let data = options
            .iter()
            .find_map(|o| o.strip_prefix("data="))
            .map(String::from);
        let preset = options
            .iter()
            .find_map(|o| o.strip_prefix("preset="))
            .map(String::from);
        let start = n + 1 + lines[n + 1..].iter().position(|l| *l == "```text").unwrap();
        let end = start + 1 + lines[start + 1..].iter().position(|l| *l == "```").unwrap();
        found.push(Capture {
            line: n + 1,
            text: (start + 1, end),
            size: (w.parse().unwrap(), h.parse().unwrap()),
            colour,
            data,
            preset,
            keys: keys(key_spec),
            shown: lines[start + 1..end].join("\n"),
        });
    }
    found
}

/// The scripted keys; then, while the loop asks for frames (the heatmap filling in), real time passes.
struct Keys {
    keys: Vec<Input>,
    started: Instant,
}

impl EventSource for Keys {
    fn next_input(&mut self, frame: Option<Duration>) -> io::Result<Option<Input>> {
        if !self.keys.is_empty() {
            return Ok(Some(self.keys.remove(0)));
        }
        let Some(frame) = frame else {
            return Ok(None);
        };
        assert!(
            self.started.elapsed() < Duration::from_secs(120),
            "the screen never settled"
        );
        std::thread::sleep(frame);
        Ok(Some(Input::Tick(frame)))
    }

    /// Each key sees the answers to the ones before (the bounce is solved on a worker).
    fn settles(&self) -> bool {
        true
    }
}

fn draw(capture: &Capture) -> String {
    let theme = Theme {
        color: capture.colour,
        ..Theme::default()
    };
    let mut terminal = Terminal::new(TestBackend::new(capture.size.0, capture.size.1)).unwrap();
    let scenario = capture
        .preset
        .as_deref()
        .map(|name| snapback::config::preset(name).unwrap());
    let params = scenario
        .as_ref()
        .map_or_else(Params::default, |s| s.apply(Params::default()));
    let mut app = App::new(params, theme).unwrap();
    if scenario.is_some_and(|s| s.is_shot()) {
        app.explore_shot();
    }
    if let Some(file) = &capture.data {
        let text = std::fs::read_to_string(file).unwrap();
        app.load_data(data::parse(&text, file).unwrap());
    }
    let mut keys = Keys {
        keys: capture.keys.clone(),
        started: Instant::now(),
    };
    run(&mut terminal, &mut app, &mut keys).unwrap();
    let text = screen::text(&terminal);
    text.lines()
        .map(str::trim_end)
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn every_screen_capture_is_the_explorers_screen() {
    let bless = std::env::var_os("README_BLESS").is_some();
    let mut stale = Vec::new();
    let mut count = 0;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for path in documents() {
        let name = path.strip_prefix(root).unwrap().display().to_string();
        let document = std::fs::read_to_string(&path).unwrap();
        let captures = captures(&document);
        if name == "README.md" {
            assert_eq!(captures.len(), 1, "README.md shows one screen");
        }
        count += captures.len();
        let mut lines: Vec<String> = document.lines().map(str::to_string).collect();
        let mut changed = false;
        // From the end, so that earlier line numbers still hold when one is rewritten.
        for capture in captures.iter().rev() {
            let drawn = draw(capture);
            let shown: Vec<&str> = capture.shown.lines().map(str::trim_end).collect();
            if drawn == shown.join("\n") {
                continue;
            }
            if bless {
                let (from, to) = capture.text;
                lines.splice(from..to, drawn.lines().map(str::to_string));
                changed = true;
            } else {
                stale.push(format!(
                    "{name}:{}: the explorer draws\n{drawn}",
                    capture.line
                ));
            }
        }
        if changed {
            std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        }
    }
    assert!(
        count >= 6,
        "{count} captures: README.md's, and the guide's contact, sweep and heatmap views, lab and shot"
    );
    assert!(
        stale.is_empty(),
        "stale screen captures (README_BLESS=1 rewrites them):\n\n{}",
        stale.join("\n\n")
    );
}
