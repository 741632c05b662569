//! The sines and cosines of an event search's last probe, for the state where the search ends and for
//! the refinement's next probe, a few millionths of an oscillation away, which turns them by angle
//! addition ([`turned2`]) rather than computing its own afresh ([`super::events::Event::near`]).

use super::trig::turned2;

/// sin and cos of a phase's two angles (its oscillation's and the normal force's).
pub type Angles = ((f64, f64), (f64, f64));

/// A probe's time and angles, and whether they were computed afresh: only fresh ones are turned, so
/// that the turns' rounding never adds up over a long refinement (a creeping one of an ill-conditioned
/// slip drifted 30-40 ulp that way).
#[derive(Clone, Copy)]
pub struct Probe {
    pub t: f64,
    pub angles: Angles,
    fresh: bool,
}

impl Probe {
    /// No probe yet.
    pub const NONE: Probe = Probe {
        t: f64::NAN,
        angles: ((0.0, 1.0), (0.0, 1.0)),
        fresh: false,
    };

    /// The probe at `t` with its angles computed afresh.
    #[inline(always)]
    pub fn fresh(t: f64, angles: Angles) -> Self {
        Probe {
            t,
            angles,
            fresh: true,
        }
    }

    /// The probe at `t`, a refinement's step from this one, of a phase that began at `start` and whose
    /// angles advance at `rates` (rad/s): this one's angles turned, where they were computed afresh and
    /// both turns are small, else `afresh()`'s (always at the phase's start, where they are exact).
    #[inline(always)]
    pub fn near(
        self,
        t: f64,
        start: f64,
        rates: (f64, f64),
        afresh: impl FnOnce() -> Angles,
    ) -> Self {
        let turned = (self.fresh && t != start)
            .then(|| turned2(self.angles, rates, t - self.t))
            .flatten();
        match turned {
            Some(angles) => Probe {
                t,
                angles,
                fresh: false,
            },
            None => Probe::fresh(t, afresh()),
        }
    }

    /// The angles, where the probe is at `t`.
    #[inline(always)]
    pub fn at(self, t: f64) -> Option<Angles> {
        (self.t == t).then_some(self.angles)
    }
}
