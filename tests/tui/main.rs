//! The explorer: on ratatui's TestBackend through the real event loop with scripted keys, in a real
//! pseudo-terminal, and README.md's captures redrawn.

#[path = "../support"]
mod support {
    pub mod bin;
    pub mod cpu;
    pub mod pty;
    pub mod screen;
}

mod readme_screens;
mod tui;
mod tui_heatmap;
mod tui_help;
mod tui_lab;
mod tui_motion;
mod tui_panel;
mod tui_pty;
mod tui_scenarios;
mod tui_shot;
