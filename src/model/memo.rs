//! A per-thread memo of the last value built from a key: a sweep over the angle, the speed or the spin
//! solves bounce after bounce on the same chain, whose modes (an eigen-decomposition, and for a compliant
//! ball the roots of its grip) need computing only once. Keys are the exact bits of every input, so a
//! reused value is the one that would have been built.

use std::cell::RefCell;
use std::thread::LocalKey;

/// One remembered value and the key it was built from.
pub type Slot<K, V> = RefCell<Option<(K, V)>>;

/// The value for `key`: the one remembered in `slot` if it was built from the same key, else `make()`,
/// which is then remembered.
pub fn reuse<K: PartialEq + Copy + 'static, V: Clone + 'static>(
    slot: &'static LocalKey<Slot<K, V>>,
    key: K,
    make: impl FnOnce() -> V,
) -> V {
    if let Some(value) = slot.with_borrow(|last| {
        last.as_ref()
            .filter(|(k, _)| *k == key)
            .map(|(_, v)| v.clone())
    }) {
        return value;
    }
    let value = make();
    slot.with_borrow_mut(|last| *last = Some((key, value.clone())));
    value
}
