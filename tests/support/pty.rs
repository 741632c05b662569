//! The real binary in a pseudo-terminal (portable-pty), its output kept byte for byte with the time each
//! piece arrived and fed to a terminal emulator (vt100), so tests read both the bytes written and the
//! screen a person would see. No tmux needed.

use std::io::{Read, Write};
use std::num::NonZeroU16;
use std::process::Command;
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::{Duration, Instant};

use portable_pty::{Child, CommandBuilder, ExitStatus, PtySize, native_pty_system};

pub use super::bin::BIN;

/// Generous: a loaded CI machine may be slow to start the binary, but a hung one must not hang the suite.
pub const PATIENCE: Duration = Duration::from_secs(30);

/// Everything the program wrote, as it came.
struct Output {
    bytes: Vec<u8>,
    screen: vt100::Parser,
    /// When the last piece arrived.
    last: Instant,
}

/// A program running in a pseudo-terminal.
pub struct Pty {
    child: Box<dyn Child + Send + Sync>,
    writer: Box<dyn Write + Send>,
    output: Arc<Mutex<Output>>,
}

impl Pty {
    /// Starts the explorer with `args` on a `cols` x `rows` terminal, `env` added to a plain
    /// environment (TERM xterm-256color, a UTF-8 locale and an empty config folder unless `env` says
    /// otherwise).
    pub fn spawn(args: &[&str], env: &[(&str, &str)], cols: u16, rows: u16) -> Pty {
        let pair = native_pty_system()
            .openpty(PtySize {
                rows,
                cols,
                pixel_width: 0,
                pixel_height: 0,
            })
            .expect("a pseudo-terminal");
        let mut command = CommandBuilder::new(BIN);
        command.args(args);
        command.env_clear();
        command.env("PATH", std::env::var("PATH").unwrap_or_default());
        command.env("HOME", std::env::temp_dir());
        command.env("TERM", "xterm-256color");
        command.env("LANG", "C.UTF-8");
        command.env("SNAPBACK_CONFIG_DIR", super::bin::empty_config());
        for (key, value) in env {
            command.env(key, value);
        }
        command.cwd(std::env::temp_dir());
        let child = pair
            .slave
            .spawn_command(command)
            .expect("the explorer starts");
        // The child holds the terminal now; the master sees the end once the child is gone.
        drop(pair.slave);
        let mut reader = pair.master.try_clone_reader().unwrap();
        let writer = pair.master.take_writer().unwrap();
        let output = Arc::new(Mutex::new(Output {
            bytes: Vec::new(),
            screen: vt100::Parser::new(
                NonZeroU16::new(rows).unwrap(),
                NonZeroU16::new(cols).unwrap(),
                0,
            ),
            last: Instant::now(),
        }));
        let sink = Arc::clone(&output);
        thread::spawn(move || {
            // Keeps the master open for as long as the child may write.
            let _master = pair.master;
            let mut buf = [0u8; 8192];
            while let Ok(n) = reader.read(&mut buf) {
                if n == 0 {
                    break;
                }
                let mut out = sink.lock().unwrap();
                out.bytes.extend_from_slice(&buf[..n]);
                out.screen.process(&buf[..n]);
                out.last = Instant::now();
            }
        });
        Pty {
            child,
            writer,
            output,
        }
    }

    /// Types `bytes` in one write, as a terminal sends a key or a paste.
    pub fn send(&mut self, bytes: &[u8]) {
        self.writer.write_all(bytes).unwrap();
        self.writer.flush().unwrap();
    }

    /// The screen as the terminal shows it.
    pub fn screen(&self) -> String {
        self.output.lock().unwrap().screen.screen().contents()
    }

    /// True while the program keeps the terminal in the alternate screen.
    pub fn alternate_screen(&self) -> bool {
        self.output
            .lock()
            .unwrap()
            .screen
            .screen()
            .alternate_screen()
    }

    /// How many bytes the program has written so far.
    pub fn written(&self) -> usize {
        self.output.lock().unwrap().bytes.len()
    }

    /// The bytes written from `from` on.
    pub fn bytes_since(&self, from: usize) -> Vec<u8> {
        self.output.lock().unwrap().bytes[from..].to_vec()
    }

    /// Waits until the screen satisfies `check`; how long that took. Fails with the screen if it never does.
    pub fn wait_for(&self, what: &str, check: impl Fn(&str) -> bool) -> Duration {
        let start = Instant::now();
        loop {
            if check(&self.screen()) {
                return start.elapsed();
            }
            assert!(
                start.elapsed() < PATIENCE,
                "timed out waiting for {what}; screen:\n{}",
                self.screen()
            );
            thread::sleep(Duration::from_millis(2));
        }
    }

    /// Waits until nothing has been written for `quiet`.
    pub fn settle(&self, quiet: Duration) {
        let start = Instant::now();
        while self.output.lock().unwrap().last.elapsed() < quiet {
            assert!(start.elapsed() < PATIENCE, "the output never went quiet");
            thread::sleep(Duration::from_millis(5));
        }
    }

    /// Sends a signal (`TERM`, `HUP`, ...) to the program.
    pub fn signal(&self, name: &str) {
        let pid = self.child.process_id().expect("a running child");
        let sent = Command::new("kill")
            .arg(format!("-{name}"))
            .arg(pid.to_string())
            .status()
            .unwrap();
        assert!(sent.success());
    }

    /// The CPU time the program has used so far: its main thread (the explorer's UI) alone, or all its
    /// threads.
    pub fn cpu(&self, main_thread: bool) -> Duration {
        let pid = self.child.process_id().expect("a running child");
        super::cpu::process(pid, main_thread)
            .expect("the program is running")
            .0
    }

    /// Waits for the program to end (without reaping it: see [`Pty::exit`]) and returns the CPU time
    /// it used in all.
    pub fn cpu_at_exit(&self) -> Duration {
        let pid = self.child.process_id().expect("a running child");
        let start = Instant::now();
        loop {
            let (cpu, ended) = super::cpu::process(pid, false).expect("the program is not reaped");
            if ended {
                return cpu;
            }
            assert!(start.elapsed() < PATIENCE, "the program never ended");
            thread::sleep(Duration::from_millis(2));
        }
    }

    /// Waits for the program to end, up to `patience`; its exit status, or `None` if it is still running
    /// (it is then killed).
    pub fn exit(&mut self, patience: Duration) -> Option<ExitStatus> {
        let start = Instant::now();
        while start.elapsed() < patience {
            if let Some(status) = self.child.try_wait().unwrap() {
                return Some(status);
            }
            thread::sleep(Duration::from_millis(2));
        }
        let _ = self.child.kill();
        None
    }
}

impl Drop for Pty {
    fn drop(&mut self) {
        let _ = self.child.kill();
    }
}
