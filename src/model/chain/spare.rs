//! A chain phase's storage, reused: a [`Motion`] holds a few kilobytes (the start state, the modal
//! coordinates, the contact's sums written out per mode), too large for the allocator's fast path, so
//! every phase built afresh would cost an allocation, a free and copies of the whole. A phase's motion
//! is instead built in place in the storage of a finished one: when the last copy of a [`ChainMotion`]
//! drops (the driver clears the last bounce's phases before it builds the next's), its storage goes to
//! this thread's spares, and the next phase is written over it ([`Motion::rebuild`]). The physics is
//! untouched: every field a phase reads is written by the phase.

use std::cell::RefCell;
use std::ops::Deref;
use std::sync::Arc;

use super::super::contact::Cart;
use super::super::setup::Setup;
use super::motion::Motion;
use super::{Chain, ChainState};

/// The most finished phases' storage a thread keeps for the next bounce's phases (a bounce has rarely
/// more; the rest are freed).
const SPARES: usize = 16;

thread_local! {
    static SPARE: RefCell<Vec<Arc<Motion>>> = const { RefCell::new(Vec::new()) };
}

/// The phase motion of a chain bounce, shared by the phase and its copies; when the last copy drops,
/// its storage is kept for the next phase built on this thread.
#[derive(Clone, Debug)]
pub struct ChainMotion(Arc<Motion>);

impl ChainMotion {
    /// The phase from `start` (see [`Motion::new`]), written over a finished phase's storage when
    /// this thread has one.
    pub fn new(
        chain: &Arc<Chain>,
        setup: &Setup,
        start: &ChainState,
        dir: f64,
        cart: Cart,
    ) -> ChainMotion {
        ChainMotion::build(chain, setup, start, (dir, cart), false)
    }

    /// [`ChainMotion::new`] for a phase searched by Taylor bounds: its sums also hold S4 and its rate
    /// ([`Motion::probe`]).
    pub fn searched(
        chain: &Arc<Chain>,
        setup: &Setup,
        start: &ChainState,
        dir: f64,
        cart: Cart,
    ) -> ChainMotion {
        ChainMotion::build(chain, setup, start, (dir, cart), true)
    }

    fn build(
        chain: &Arc<Chain>,
        setup: &Setup,
        start: &ChainState,
        (dir, cart): (f64, Cart),
        fourth: bool,
    ) -> ChainMotion {
        let spare = SPARE
            .try_with(|spare| spare.try_borrow_mut().ok().and_then(|mut s| s.pop()))
            .ok()
            .flatten();
        if let Some(mut storage) = spare
            && let Some(motion) = Arc::get_mut(&mut storage)
        {
            motion.rebuild(chain, setup, start, (dir, cart), fourth);
            return ChainMotion(storage);
        }
        ChainMotion(Arc::new(Motion::with(
            chain.clone(),
            setup,
            *start,
            (dir, cart),
            fourth,
        )))
    }
}

impl Deref for ChainMotion {
    type Target = Motion;

    #[inline]
    fn deref(&self) -> &Motion {
        &self.0
    }
}

impl AsRef<Motion> for ChainMotion {
    #[inline]
    fn as_ref(&self) -> &Motion {
        &self.0
    }
}

impl Drop for ChainMotion {
    /// The last copy gives its storage to this thread's spares (unless they are full, or the thread is
    /// ending).
    fn drop(&mut self) {
        if Arc::get_mut(&mut self.0).is_none() {
            return;
        }
        let storage = &self.0;
        let _ = SPARE.try_with(|spare| {
            if let Ok(mut spare) = spare.try_borrow_mut()
                && spare.len() < SPARES
            {
                spare.push(Arc::clone(storage));
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::params::Params;
    use super::*;

    /// Every kind of phase written over storage that held every other kind (on the wall and on a free
    /// frame, sliding and gripping, the first mass moving and held) is the phase built afresh, bit for
    /// bit, and a dropped phase's storage is the next one's.
    #[test]
    fn a_phase_written_over_another_is_the_phase_built_afresh() {
        let modes = [
            (1.0, Cart::Moving(1)),
            (0.0, Cart::Moving(-1)),
            (-1.0, Cart::Stuck),
            (0.0, Cart::Stuck),
            (-1.0, Cart::Moving(1)),
        ];
        for frame_mass in [0.0, 0.188] {
            let params = Params {
                chain: 4.0,
                cart_friction: 30.0,
                frame_mass,
                ..Params::default()
            };
            let setup = Setup::new(&params);
            let chain = Chain::shared(&params, &setup);
            let n = chain.n + usize::from(chain.frame.is_some());
            let start = |k: usize| {
                let mut s = ChainState::from_contact(&setup.initial(params.spin));
                s.t = setup.duration * (0.1 + 0.15 * k as f64);
                s.frame = chain.frame_index();
                for i in 0..n {
                    s.x[i] = 1e-4 * ((i + k) as f64).sin();
                    s.v[i] = 0.3 * ((2 * i + k) as f64).cos();
                }
                s
            };
            let mut storage = Arc::new(Motion::new(
                chain.clone(),
                &setup,
                start(9),
                1.0,
                Cart::Moving(1),
            ));
            for round in 0..2 {
                for (k, &(dir, cart)) in modes.iter().enumerate() {
                    let s = start(k + round);
                    let fresh = Motion::new(chain.clone(), &setup, s, dir, cart);
                    let motion = Arc::get_mut(&mut storage).expect("one owner");
                    motion.rebuild(&chain, &setup, &s, (dir, cart), false);
                    for step in 0..5 {
                        let t = s.t + (setup.duration - s.t) * step as f64 / 4.0;
                        let what = format!("frame {frame_mass} round {round} phase {k} t {t}");
                        assert_eq!(motion.full(&setup, t), fresh.full(&setup, t), "{what}");
                        let (a, b) = (motion.contact(&setup, t), fresh.contact(&setup, t));
                        let bits = |c: super::super::motion::Contact| {
                            [c.friction, c.friction_rate, c.accel, c.frame.0, c.frame.1]
                                .map(f64::to_bits)
                        };
                        assert_eq!(a.state, b.state, "{what}");
                        assert_eq!(bits(a), bits(b), "{what}");
                    }
                }
            }
            let first = ChainMotion::new(&chain, &setup, &start(0), 1.0, Cart::Moving(1));
            let storage = Arc::as_ptr(&first.0);
            drop(first);
            let next = ChainMotion::new(&chain, &setup, &start(1), 0.0, Cart::Moving(1));
            assert_eq!(Arc::as_ptr(&next.0), storage, "frame {frame_mass}");
        }
    }
}
