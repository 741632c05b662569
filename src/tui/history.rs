//! Undo and redo of parameter changes: the parameters before each change, most recent last, and the ones
//! undone, so that they can be redone until a new change is made.

use crate::model::Params;
use crate::model::params::PARAMS;

use super::values::shown;

/// The parameter changes that can be undone and redone.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct History {
    /// The parameters before each change, oldest first.
    undo: Vec<Params>,
    /// The parameters undone, most recently undone last.
    redo: Vec<Params>,
}

impl History {
    /// How many changes are kept; the oldest go first.
    pub const LIMIT: usize = 200;

    /// A change was made from `before`: it can be undone, and nothing undone can be redone any more.
    pub fn record(&mut self, before: Params) {
        self.redo.clear();
        self.undo.push(before);
        if self.undo.len() > Self::LIMIT {
            self.undo.remove(0);
        }
    }

    /// The parameters to go back to from `current`, if any change is left to undo.
    pub fn undo(&mut self, current: Params) -> Option<Params> {
        let previous = self.undo.pop()?;
        self.redo.push(current);
        Some(previous)
    }

    /// The parameters to go forward to from `current`, if an undone change is left to redo.
    pub fn redo(&mut self, current: Params) -> Option<Params> {
        let next = self.redo.pop()?;
        self.undo.push(current);
        Some(next)
    }

    /// Changes that can be undone.
    pub fn undo_len(&self) -> usize {
        self.undo.len()
    }

    /// Changes that can be redone.
    pub fn redo_len(&self) -> usize {
        self.redo.len()
    }
}

/// What changed from `from` to `to`, for the status line: `θ1 60.0 deg → 61.0 deg`, or `4 parameters`.
pub fn describe(from: &Params, to: &Params) -> String {
    let changed: Vec<_> = PARAMS
        .iter()
        .filter(|s| from.get(s.id) != to.get(s.id))
        .collect();
    match changed.as_slice() {
        [] => "no parameter".to_string(),
        [spec] => format!(
            "{} {} → {}",
            spec.symbol,
            shown(spec, from.get(spec.id)),
            shown(spec, to.get(spec.id))
        ),
        many => format!(
            "{} parameters ({})",
            many.len(),
            many.iter().map(|s| s.symbol).collect::<Vec<_>>().join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ParamId;

    fn at(angle: f64) -> Params {
        Params::default().with(ParamId::Angle, angle).unwrap()
    }

    #[test]
    fn undo_then_redo_walks_back_and_forth() {
        let mut h = History::default();
        assert_eq!(h.undo(at(60.0)), None);
        h.record(at(60.0));
        h.record(at(61.0));
        assert_eq!(h.undo(at(62.0)), Some(at(61.0)));
        assert_eq!(h.undo(at(61.0)), Some(at(60.0)));
        assert_eq!(h.undo(at(60.0)), None);
        assert_eq!(h.redo(at(60.0)), Some(at(61.0)));
        assert_eq!(h.redo(at(61.0)), Some(at(62.0)));
        assert_eq!(h.redo(at(62.0)), None);
    }

    #[test]
    fn a_new_change_drops_what_was_undone() {
        let mut h = History::default();
        h.record(at(60.0));
        assert_eq!(h.undo(at(61.0)), Some(at(60.0)));
        assert_eq!(h.redo_len(), 1);
        h.record(at(60.0));
        assert_eq!(h.redo_len(), 0);
        assert_eq!(h.redo(at(50.0)), None);
    }

    #[test]
    fn only_the_last_changes_are_kept() {
        let mut h = History::default();
        for i in 0..History::LIMIT + 50 {
            h.record(at(1.0 + i as f64 * 0.1));
        }
        assert_eq!(h.undo_len(), History::LIMIT);
        let mut oldest = None;
        while let Some(p) = h.undo(Params::default()) {
            oldest = Some(p);
        }
        assert_eq!(oldest, Some(at(1.0 + 50.0 * 0.1)));
    }

    #[test]
    fn describes_one_change_or_counts_many() {
        assert_eq!(describe(&at(60.0), &at(61.0)), "θ1 60.0 deg → 61.0 deg");
        let mut two = at(61.0);
        two.mu = 0.3;
        assert_eq!(describe(&at(60.0), &two), "2 parameters (θ1, μ)");
    }
}
