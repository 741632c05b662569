//! Slow motion: the time cursor's steps and the playback speed.

use std::time::Duration;

/// Frames a second while playing, unless `--fps` says otherwise: smooth enough to follow the ball and
/// light enough for a slow link (about 10 KB/s at 160 x 48). Nothing is drawn on a timer while paused.
pub const DEFAULT_FPS: u32 = 12;

/// Wall time between frames while playing, at [`DEFAULT_FPS`].
pub const FRAME: Duration = Duration::from_nanos(1_000_000_000 / DEFAULT_FPS as u64);

/// What `[` and `]` move the time cursor by, s: to the previous or next multiple of 0.05 ms.
pub const STEP: f64 = 0.05e-3;

/// Playback speed: 1 ms of bounce per 2 s of wall time, doubled or halved by `+` and `-`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Speed {
    /// Doublings from the default (negative: halvings).
    doublings: i32,
}

impl Speed {
    /// Bounce seconds per wall second at the default speed: 1 ms per 2 s.
    pub const DEFAULT_RATE: f64 = 0.5e-3;
    /// From 1 ms per 32 s ...
    const SLOWEST: i32 = -4;
    /// ... to 32 ms per 1 s (a 5 ms bounce in a sixth of a second).
    const FASTEST: i32 = 6;

    /// Bounce time per wall time.
    pub fn rate(self) -> f64 {
        Self::DEFAULT_RATE * 2f64.powi(self.doublings)
    }

    /// Twice as fast (`faster`) or half as fast, within the range; false if already at its end.
    pub fn change(&mut self, faster: bool) -> bool {
        let next = if faster {
            self.doublings + 1
        } else {
            self.doublings - 1
        };
        if (Self::SLOWEST..=Self::FASTEST).contains(&next) {
            self.doublings = next;
            true
        } else {
            false
        }
    }

    /// The speed as people say it: `1 ms / 2 s`, `1 ms / 0.5 s`, `4 ms / 1 s`.
    pub fn label(self) -> String {
        if self.doublings <= 1 {
            let wall = 2f64.powi(1 - self.doublings);
            format!("1 ms / {wall} s")
        } else {
            format!("{} ms / 1 s", 1 << (self.doublings - 1))
        }
    }
}

/// The time `[` (`forward` false) or `]` moves the cursor to from `t`: the previous or next multiple of
/// [`STEP`], within `[0, duration]`.
pub fn step(t: f64, forward: bool, duration: f64) -> f64 {
    // A cursor within rounding of a multiple counts as on it.
    let k = t / STEP;
    let next = if forward {
        (k + 1e-9).floor() + 1.0
    } else {
        (k - 1e-9).ceil() - 1.0
    };
    (next * STEP).clamp(0.0, duration)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speed_labels_and_limits() {
        let mut speed = Speed::default();
        assert_eq!(speed.label(), "1 ms / 2 s");
        assert_eq!(speed.rate(), 0.5e-3);
        assert!(speed.change(true));
        assert_eq!(speed.label(), "1 ms / 1 s");
        assert!(speed.change(true));
        assert_eq!(speed.label(), "2 ms / 1 s");
        let mut speed = Speed::default();
        assert!(speed.change(false));
        assert_eq!(speed.label(), "1 ms / 4 s");
        while speed.change(false) {}
        assert_eq!(speed.label(), "1 ms / 32 s");
        while speed.change(true) {}
        assert_eq!(speed.label(), "32 ms / 1 s");
    }

    #[test]
    fn steps_go_to_multiples_of_a_twentieth_of_a_millisecond() {
        let d = 5e-3;
        assert_eq!(step(0.0, true, d), STEP);
        assert_eq!(step(0.0, false, d), 0.0);
        assert_eq!(step(d, true, d), d);
        assert!((step(1.32e-3, true, d) - 1.35e-3).abs() < 1e-15);
        assert!((step(1.32e-3, false, d) - 1.30e-3).abs() < 1e-15);
        // Twenty steps make a millisecond without drifting off the grid.
        let mut t = 0.0;
        for _ in 0..20 {
            t = step(t, true, d);
        }
        assert!((t - 1e-3).abs() < 1e-15);
        assert!((step(t, true, d) - 1.05e-3).abs() < 1e-15);
    }
}
