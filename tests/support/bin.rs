//! The binary under test, isolated from the user's configuration: `SNAPBACK_CONFIG_DIR` names an empty
//! folder, so a user's `config.toml` or presets never change what a test sees.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

pub const BIN: &str = env!("CARGO_BIN_EXE_snapback");

/// An empty folder for the binary's configuration, made once per test binary.
pub fn empty_config() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("snapback-no-config-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    })
}

/// `snapback` as std's `Command`, isolated.
#[allow(dead_code)] // not every test binary runs it this way
pub fn command() -> std::process::Command {
    let mut cmd = std::process::Command::new(BIN);
    cmd.env("SNAPBACK_CONFIG_DIR", empty_config());
    cmd
}

/// `snapback` as assert_cmd's `Command`, isolated.
pub fn snapback() -> assert_cmd::Command {
    let mut cmd = assert_cmd::Command::new(BIN);
    cmd.env("SNAPBACK_CONFIG_DIR", empty_config());
    cmd
}
