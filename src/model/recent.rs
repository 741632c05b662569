//! The states at the last few evaluations of a phase's event functions, so that the state at the event
//! the search found (usually among its last evaluations: the crossing Newton's method found, before the
//! evaluations that proved nothing rose earlier) is not computed again.

use std::cell::Cell;

/// The last four states recorded, each with its time.
pub struct Recent<S: Copy> {
    slots: [Cell<(f64, S)>; SLOTS],
    next: Cell<usize>,
}

/// How many evaluations are kept.
const SLOTS: usize = 4;

impl<S: Copy> Recent<S> {
    /// Every slot holds `start`, at `t`, until evaluations replace it.
    pub fn new(t: f64, start: S) -> Self {
        Recent {
            slots: std::array::from_fn(|_| Cell::new((t, start))),
            next: Cell::new(0),
        }
    }

    /// Records the state `s` at `t`.
    #[inline]
    pub fn record(&self, t: f64, s: S) {
        let next = self.next.get();
        self.slots[next % SLOTS].set((t, s));
        self.next.set(next.wrapping_add(1));
    }

    /// The latest state recorded.
    #[inline]
    pub fn latest(&self) -> S {
        self.slots[self.next.get().wrapping_sub(1) % SLOTS].get().1
    }

    /// The latest state recorded at `t`, or else the latest recorded.
    pub fn at(&self, t: f64) -> S {
        let next = self.next.get();
        let latest = |back: usize| self.slots[next.wrapping_sub(back) % SLOTS].get();
        (1..=SLOTS)
            .map(latest)
            .find(|&(at, _)| at == t)
            .unwrap_or_else(|| latest(1))
            .1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_latest_state_at_a_time_among_the_last_four() {
        let recent = Recent::new(0.0, 'a');
        assert_eq!(recent.at(0.0), 'a');
        for (t, s) in [(1.0, 'b'), (2.0, 'c'), (1.0, 'd'), (3.0, 'e'), (4.0, 'f')] {
            recent.record(t, s);
        }
        assert_eq!(recent.at(1.0), 'd');
        assert_eq!(recent.at(2.0), 'c');
        assert_eq!(recent.at(3.0), 'e');
        // The start and 'b' have been pushed out by four later records: the latest stands in.
        assert_eq!(recent.at(0.0), 'f');
        recent.record(5.0, 'g');
        assert_eq!(recent.at(2.0), 'g');
        assert_eq!(recent.at(1.0), 'd');
    }
}
