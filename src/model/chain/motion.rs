//! One phase of a chain bounce in closed form: every normal mode a forced (sliding) or free (gripping)
//! oscillator, written with the resonance- and zero-frequency-safe pieces of [`super::super::oscillator`].
//! With string friction the first mass moving in direction d also feels the constant -d F_c, a step
//! forcing Φ_1j (-d F_c) of each mode; held still by it, the first mass stays put and the masses behind
//! it swing freely in their own modes ([`Modes::clamped`]) about the straight line from it to the wall;
//! held to a free frame, first mass and frame are one body and each phase is the moving one's closed
//! form in the ring's modes ([`Modes::ring`], coordinates from `ring.rs`).

use std::sync::Arc;

use super::super::contact::Cart;
use super::super::oscillator::{detuned, forced, free_given, step};
use super::super::setup::{Setup, State};
use super::super::trig::{sin_cos, sin_cos_each, sin_cos2};
use super::modes::{MAX, Modes};
use super::{Chain, ChainState, ring_coordinates};

/// How one mode moves in a sliding phase (see `Slide`'s cart response, of which this is the modal copy).
#[derive(Clone, Copy, Debug)]
enum Response {
    /// Free oscillation (gripping: the static friction is internal to the ball-and-chain system).
    Free,
    /// Through the particular solution a sin(w t), a = Φ_1j F0 / (Ω² - w²).
    Detuned { amplitude: f64 },
    /// Through [`forced`], exact at resonance: drive = Φ_1j F0.
    Forced { drive: f64 },
}

/// The detuned form is used while a mode's particular response moves a mass at most this many times the
/// speeds at the start of the phase (the single cart's criterion).
const DETUNED_GAIN: f64 = 16.0;

/// One phase of a chain bounce from `start`: sliding with the slip's sign `dir` (friction dir mu N on the
/// ball, its reaction on the first mass), or gripping (`dir` = 0), while the first mass moves or is held
/// still (`cart`).
#[derive(Clone, Debug)]
pub struct Motion {
    chain: Arc<Chain>,
    pub dir: f64,
    pub cart: Cart,
    pub start: ChainState,
    sin_wt0: f64,
    cos_wt0: f64,
    /// The modal coordinates at the start (held: of the masses behind the first, about their rest line).
    q0: [f64; MAX],
    dq0: [f64; MAX],
    response: [Response; MAX],
    /// The string friction on the moving first mass, -d F_c (0 without string friction or when held).
    push: f64,
    /// The first mass's velocity at the start as the modal sum gives it (the grip's impulse on the ball
    /// is measured from it, so that it is exactly zero at the start).
    v1_start: f64,
    /// The contact's modal sums written out for this phase, for a moving first mass ([`Sums`], read
    /// through [`Motion::sums`]).
    store: Store,
}

/// Where the phases built in one storage write their [`Sums`]: on the wall, or on a free frame with
/// the frame's three rows after the main four. Each is kept from phase to phase (a held phase leaves
/// them unread), so that a phase writes its sums over the last one's.
#[derive(Clone, Debug, Default)]
struct Store {
    wall: Option<Sums<4, [Share<4>; MAX]>>,
    frame: Option<Sums<7, Vec<Share<7>>>>,
}

/// A moving phase's [`Sums`]: on the wall, or on a free frame.
#[derive(Clone, Copy)]
enum Written<'a> {
    Wall(&'a Sums<4, [Share<4>; MAX]>),
    Frame(&'a Sums<7, Vec<Share<7>>>),
}

impl Written<'_> {
    /// True when the sums hold S4 and its rate.
    fn has_fourth(&self) -> bool {
        match self {
            Written::Wall(sums) => sums.has_fourth,
            Written::Frame(sums) => sums.has_fourth,
        }
    }
}

/// Which rows of a phase's sums (`Sums`) an evaluation sums, a bit a row (row r: bit r), consecutive
/// rows: of the main rows X_1, V_1, S = Σ Φ_1j Ω_j² q_j and S', on a free frame followed by the
/// frame's X_f, X_N and V_f; or of S4 = Σ Φ_1j Ω_j⁴ q_j and S4'. Each row is summed on its own, so a
/// row has the same bits whichever others are summed with it.
pub type Mask = u8;

/// The main rows of [`Motion::contact`] on the wall: X_1, V_1, S and S'.
const CONTACT: Mask = 0b1111;
/// The free frame's three rows.
const FRAME: Mask = 0b111 << 4;
/// The main rows the slide's slip and its first three derivatives read: V_1, S and S' ...
pub const SLIP: Mask = 0b1110;
/// ... and of S4 and its rate: S4.
pub const SLIP_FOURTH: Mask = 0b01;
/// The main rows the grip's margins and their first three derivatives read: S and S' ...
pub const MARGINS: Mask = 0b1100;
/// ... and of S4 and its rate: both.
pub const MARGINS_FOURTH: Mask = 0b11;
/// The main rows the slide's slip and its rate read: V_1 and S.
const SLIP_RATE: Mask = 0b0110;

/// The sums [`Motion::moving_contact`] needs over the modes (rows of Φ, or Φ_1j Ω_j², against q or q'),
/// taken for a phase as fixed combinations of sin Ω_j τ, cos Ω_j τ, sin w t and cos w t. A free mode is
/// q = X cos Ωτ + (V/Ω) sin Ωτ, q' = V cos Ωτ - Ω X sin Ωτ; a detuned one adds its particular solution
/// a sin w t to the free motion from X = q0 - a sin w t0, V = q0' - a w cos w t0 (the same closed form
/// as [`detuned`], regrouped). Each evaluation is then two products a mode and row; the modes forced
/// near resonance ([`forced`]), and any of zero frequency but the rigid translation, are left to
/// `odd`, evaluated one by one, as is the string friction's step. The rigid translation of a free frame, q = X + V τ (+ a sin w t),
/// is written in the same combinations with τ and 1 in place of sin Ωτ and cos Ωτ. For a moving first
/// mass (held, the phase sums the modal coordinates of [`Motion::modal`]): on the wall the `R` = 4
/// rows X_1, V_1, Σ Φ_1j Ω_j² q_j and its rate ([`Sums::main_weights`]), on a free frame those and the
/// frame's three, X_f, X_N and V_f ([`Sums::frame_weights`]); apart from them, for the event search's
/// higher derivatives only, Σ Φ_1j Ω_j⁴ q_j and its rate. An evaluation sums the rows its [`Mask`]s
/// name.
#[derive(Clone, Debug)]
struct Sums<const R: usize, S> {
    main: Rows<R, S>,
    /// S4 = Σ Φ_1j Ω_j⁴ q_j and its rate ([`Sums::fourth_weights`]), written only for a phase searched
    /// by Taylor bounds (`has_fourth`; on the heap, empty until then, so that the phases that never
    /// write them keep their storage's size).
    fourth: Rows<2, Vec<Share<2>>>,
    has_fourth: bool,
    /// The modes left out of the combinations.
    odd: [usize; MAX],
    odd_n: usize,
    /// The rigid translation of a free frame, if the combinations hold it (with τ and 1).
    rigid: Option<usize>,
}

/// `R` sums over the modes as combinations of sin Ω_j τ, cos Ω_j τ, sin w t and cos w t.
#[derive(Clone, Debug)]
struct Rows<const R: usize, S> {
    /// Per mode in order, each row's coefficients of cos Ω_j τ and of sin Ω_j τ (zero for a mode
    /// left out), in [`Shares`].
    shares: S,
    /// Each row's coefficients of sin w t and cos w t.
    sin_wt: [f64; R],
    cos_wt: [f64; R],
}

/// One mode's free motion X cos Ωτ + Y sin Ωτ, rate V cos Ωτ - Ω X sin Ωτ (Y = V/Ω), its particular
/// solution's amplitude a, and w.
#[derive(Clone, Copy)]
struct Swing {
    x: f64,
    y: f64,
    v: f64,
    omega_x: f64,
    amplitude: f64,
    w: f64,
}

/// A mode's coefficients of cos Ω_j τ and of sin Ω_j τ in each of `R` rows.
type Share<const R: usize> = ([f64; R], [f64; R]);

/// Where [`Rows`] keeps its shares: the wall's four rows in place for every possible mode, the free
/// frame's seven on the heap for the phase's modes only (in place they would make every phase's
/// storage 2 KB larger). Either is written over from phase to phase, only the phase's modes' entries.
trait Shares<const R: usize>: AsRef<[Share<R>]> + AsMut<[Share<R>]> {
    /// Zero shares for `n` modes.
    fn zeros(n: usize) -> Self;

    /// Room for `n` modes' shares (their values are written next).
    fn fit(&mut self, n: usize);
}

impl<const R: usize> Shares<R> for [Share<R>; MAX] {
    fn zeros(_: usize) -> Self {
        [([0.0; R], [0.0; R]); MAX]
    }

    fn fit(&mut self, _: usize) {}
}

impl<const R: usize> Shares<R> for Vec<Share<R>> {
    fn zeros(n: usize) -> Self {
        vec![([0.0; R], [0.0; R]); n]
    }

    fn fit(&mut self, n: usize) {
        self.resize(n, ([0.0; R], [0.0; R]));
    }
}

impl<const R: usize, S: Shares<R>> Rows<R, S> {
    fn new(n: usize) -> Rows<R, S> {
        Rows {
            shares: S::zeros(n),
            sin_wt: [0.0; R],
            cos_wt: [0.0; R],
        }
    }

    /// Ready to be filled for `n` modes: room for their shares, no sin w t or cos w t terms.
    fn reset(&mut self, n: usize) {
        self.shares.fit(n);
        self.sin_wt = [0.0; R];
        self.cos_wt = [0.0; R];
    }

    /// Mode j left out of every row.
    fn clear(&mut self, j: usize) {
        self.shares.as_mut()[j] = ([0.0; R], [0.0; R]);
    }

    /// Mode j's share, each row weighing it by `weights` (and summing its rate where marked).
    fn fill(&mut self, j: usize, weights: [(f64, bool); R], m: Swing) {
        for (r, (weight, rate)) in weights.into_iter().enumerate() {
            let (cos, sin) = &mut self.shares.as_mut()[j];
            if rate {
                cos[r] = weight * m.v;
                sin[r] = -(weight * m.omega_x);
                self.cos_wt[r] += weight * m.amplitude * m.w;
            } else {
                cos[r] = weight * m.x;
                sin[r] = weight * m.y;
                self.sin_wt[r] += weight * m.amplitude;
            }
        }
    }

    /// The rows `mask` names given sin and cos of the modes' angles and (sin w t, cos w t) (sliding
    /// only); the others are left 0. Each row is summed on its own, so a row has the same bits
    /// whichever others are summed.
    #[inline(always)]
    fn at<const MASK: Mask>(
        &self,
        n: usize,
        (sin, cos): (&[f64], &[f64]),
        wt: Option<(f64, f64)>,
    ) -> [f64; R] {
        let mut rows = [0.0; R];
        let Some((from, to)) = span::<R>(MASK) else {
            return rows;
        };
        let shares = self.shares.as_ref()[..n].iter();
        for ((cos_share, sin_share), (&c, &s)) in shares.zip(cos.iter().zip(sin)) {
            let terms = rows[from..to]
                .iter_mut()
                .zip(&cos_share[from..to])
                .zip(&sin_share[from..to]);
            for ((row, a), b) in terms {
                *row += a * c + b * s;
            }
        }
        if let Some((sin_wt, cos_wt)) = wt {
            let terms = rows[from..to]
                .iter_mut()
                .zip(&self.sin_wt[from..to])
                .zip(&self.cos_wt[from..to]);
            for ((row, a), b) in terms {
                *row += a * sin_wt + b * cos_wt;
            }
        }
        rows
    }
}

/// The rows a [`Mask`] names, from and to (past the last), of `R`; `None` for none. A mask names
/// consecutive rows.
#[inline(always)]
const fn span<const R: usize>(mask: Mask) -> Option<(usize, usize)> {
    if mask == 0 {
        return None;
    }
    let from = mask.trailing_zeros() as usize;
    let to = (Mask::BITS - mask.leading_zeros()) as usize;
    debug_assert!(mask >> from == (1 << (to - from)) - 1);
    Some((from, if to < R { to } else { R }))
}

/// Adds `weights` times a mode's coordinate and rate `(q, dq)` to the rows of `rows` that `MASK`
/// names.
#[inline]
fn add<const R: usize, const MASK: Mask>(
    rows: &mut [f64; R],
    weights: [(f64, bool); R],
    (q, dq): (f64, f64),
) {
    let Some((from, to)) = span::<R>(MASK) else {
        return;
    };
    for (row, &(weight, rate)) in rows[from..to].iter_mut().zip(&weights[from..to]) {
        *row += weight * if rate { dq } else { q };
    }
}

impl<const R: usize, S: Shares<R>> Sums<R, S> {
    /// Sums for `n` modes, all zero.
    fn empty(n: usize) -> Sums<R, S> {
        Sums {
            main: Rows::new(n),
            fourth: Rows::new(0),
            has_fourth: false,
            odd: [0; MAX],
            odd_n: 0,
            rigid: None,
        }
    }

    /// The sums for modes `modes` from q0, q0' with the responses `response`, each row weighing mode
    /// j by `weights(j)`, written over these; S4 and its rate too if `fourth`.
    fn write(
        &mut self,
        modes: &Modes,
        w: f64,
        (q0, dq0): (&[f64; MAX], &[f64; MAX]),
        response: &[Response; MAX],
        ((sin_wt0, cos_wt0), fourth): ((f64, f64), bool),
        weights: impl Fn(usize) -> [(f64, bool); R],
    ) {
        let sums = self;
        sums.main.reset(modes.n);
        sums.has_fourth = fourth;
        if fourth {
            sums.fourth.reset(modes.n);
        }
        sums.odd_n = 0;
        sums.rigid = None;
        for j in 0..modes.n {
            let omega = modes.omega[j];
            let rigid = modes.rigid == Some(j);
            let amplitude = match response[j] {
                Response::Free if omega > 0.0 || rigid => 0.0,
                Response::Detuned { amplitude } if omega > 0.0 || rigid => amplitude,
                _ => {
                    sums.odd[sums.odd_n] = j;
                    sums.odd_n += 1;
                    sums.main.clear(j);
                    if fourth {
                        sums.fourth.clear(j);
                    }
                    continue;
                }
            };
            let (x, v) = if amplitude == 0.0 {
                (q0[j], dq0[j])
            } else {
                (
                    q0[j] - amplitude * sin_wt0,
                    dq0[j] - amplitude * w * cos_wt0,
                )
            };
            // The rigid translation's X + V τ, rate V: τ and 1 stand for sin Ωτ and cos Ωτ.
            let (y, omega_x) = if rigid {
                sums.rigid = Some(j);
                (v, 0.0)
            } else {
                (v / omega, omega * x)
            };
            let swing = Swing {
                x,
                y,
                v,
                omega_x,
                amplitude,
                w,
            };
            sums.main.fill(j, weights(j), swing);
            if fourth {
                sums.fourth.fill(j, Sums::fourth_weights(modes, j), swing);
            }
        }
    }
}

impl Sums<4, [Share<4>; MAX]> {
    /// The main rows' weights on mode j and whether each sums the rates.
    #[inline]
    fn main_weights(modes: &Modes, j: usize) -> [(f64, bool); 4] {
        let (phi, stiff) = (modes.shape[0][j], modes.first_stiff[j]);
        [(phi, false), (phi, true), (stiff, false), (stiff, true)]
    }

    /// S4's and its rate's weights on mode j, Φ_1j Ω_j⁴.
    #[inline]
    fn fourth_weights(modes: &Modes, j: usize) -> [(f64, bool); 2] {
        let omega = modes.omega[j];
        let fourth = modes.first_stiff[j] * omega * omega;
        [(fourth, false), (fourth, true)]
    }

    /// The frame's rows' weights on mode j.
    #[inline]
    fn frame_weights(modes: &Modes, frame: usize, j: usize) -> [(f64, bool); 3] {
        let (f, last) = (modes.shape[frame][j], modes.shape[frame - 1][j]);
        [(f, false), (last, false), (f, true)]
    }

    /// The main rows' and then the frame's rows' weights on mode j.
    #[inline]
    fn framed_weights(modes: &Modes, frame: usize, j: usize) -> [(f64, bool); 7] {
        let ([a, b, c, d], [e, f, g]) = (
            Sums::main_weights(modes, j),
            Sums::frame_weights(modes, frame, j),
        );
        [a, b, c, d, e, f, g]
    }

    /// The rows from every mode's coordinate and rate.
    fn from_modal(
        modes: &Modes,
        frame: usize,
        (q, dq): (&[f64; MAX], &[f64; MAX]),
    ) -> ([f64; 4], [f64; 3]) {
        let (mut main, mut framed) = ([0.0; 4], [0.0; 3]);
        for j in 0..modes.n {
            add::<4, CONTACT>(&mut main, Sums::main_weights(modes, j), (q[j], dq[j]));
            if frame > 0 {
                let weights = Sums::frame_weights(modes, frame, j);
                add::<3, 0b111>(&mut framed, weights, (q[j], dq[j]));
            }
        }
        (main, framed)
    }
}

/// Rows of [`Sums`] at one time: the main four (X_1, V_1, S, S'), the frame's three (X_f, X_N,
/// V_f; 0 on the wall), S4 and S4', and sin(w τ), cos(w τ).
struct Summed {
    main: [f64; 4],
    framed: [f64; 3],
    fourth: [f64; 2],
    w_tau: (f64, f64),
}

/// What the event search reads at one time ([`Motion::probe`]): the contact, S' = Σ Φ_1j Ω_j² q_j',
/// S4 = Σ Φ_1j Ω_j⁴ q_j and its rate, and cos w t (sliding; 1 gripping).
#[derive(Clone, Copy, Debug)]
pub struct Probe {
    pub contact: Contact,
    pub stiff_rate: f64,
    pub fourth: [f64; 2],
    pub cos_wt: f64,
}

/// The state of the ball and the first mass at one time, with the friction and the first mass's
/// acceleration there.
#[derive(Clone, Copy, Debug)]
pub struct Contact {
    pub state: State,
    /// Friction on the ball, positive backward.
    pub friction: f64,
    /// Its rate (gripping; the sliding one is dir mu N').
    pub friction_rate: f64,
    /// The first mass's acceleration V_1'.
    pub accel: f64,
    /// The free frame's velocity and acceleration along the surface (0 on the wall).
    pub frame: (f64, f64),
}

impl Motion {
    /// The phase from `start`: sliding with the slip's sign `dir` or gripping (`dir` 0), while the
    /// first mass moves or is held (`cart`).
    pub fn new(
        chain: Arc<Chain>,
        setup: &Setup,
        start: ChainState,
        dir: f64,
        cart: Cart,
    ) -> Motion {
        Motion::with(chain, setup, start, (dir, cart), false)
    }

    /// [`Motion::new`]; with `fourth`, a moving first mass's sums also hold S4 and its rate, for
    /// [`Motion::probe`].
    pub fn with(
        chain: Arc<Chain>,
        setup: &Setup,
        start: ChainState,
        (dir, cart): (f64, Cart),
        fourth: bool,
    ) -> Motion {
        let mut motion = Motion {
            chain,
            dir,
            cart,
            start,
            sin_wt0: 0.0,
            cos_wt0: 1.0,
            q0: [0.0; MAX],
            dq0: [0.0; MAX],
            response: [Response::Free; MAX],
            push: 0.0,
            v1_start: 0.0,
            store: Store::default(),
        };
        motion.write(setup, dir, cart, fourth);
        motion
    }

    /// [`Motion::new`] written over this phase's storage (see `spare.rs`): every field the new phase
    /// reads is written, the sums' storage kept. With `fourth`, a moving first mass's sums also hold
    /// S4 and its rate, for [`Motion::probe`].
    pub fn rebuild(
        &mut self,
        chain: &Arc<Chain>,
        setup: &Setup,
        start: &ChainState,
        (dir, cart): (f64, Cart),
        fourth: bool,
    ) {
        if !Arc::ptr_eq(&self.chain, chain) {
            self.chain = Arc::clone(chain);
        }
        self.start = *start;
        self.write(setup, dir, cart, fourth);
    }

    /// Writes the phase from `self.start` with `dir` and `cart` ([`Motion::new`]) over this one,
    /// the sums with S4 and its rate if `fourth`.
    fn write(&mut self, setup: &Setup, dir: f64, cart: Cart, fourth: bool) {
        (self.sin_wt0, self.cos_wt0) = sin_cos(setup.w * self.start.t);
        (self.dir, self.cart, self.push) = (dir, cart, cart.friction(setup));
        let chain = &*self.chain;
        let start = &self.start;
        let held = cart == Cart::Stuck;
        if held && start.frame == 0 {
            // The masses behind a first mass held still swing freely about their rest line
            // X_i = X_1 (N + 1 - i)/N.
            let modes = chain.clamped();
            let (mut x, mut v) = ([0.0; MAX], [0.0; MAX]);
            for i in 0..modes.n {
                x[i] = start.x[i + 1] - rest_line(chain, start, i + 1);
                v[i] = start.v[i + 1];
            }
            modes.project_both((&x, &v), (&mut self.q0, &mut self.dq0));
            self.response[..modes.n].fill(Response::Free);
            self.v1_start = 0.0;
            return;
        }
        // Held to a free frame, the ring of first mass and frame and the links behind ([`ring`]).
        let modes = if held {
            let (x, v) = ring_coordinates::coordinates(chain, start);
            let modes = chain.held(dir);
            modes.project_both((&x, &v), (&mut self.q0, &mut self.dq0));
            modes
        } else {
            let modes = chain.modes(dir);
            modes.project_both((&start.x, &start.v), (&mut self.q0, &mut self.dq0));
            modes
        };
        let (q0, dq0) = (&self.q0, &self.dq0);
        self.v1_start = (0..modes.n).map(|j| modes.shape[0][j] * dq0[j]).sum();
        let force = dir * setup.peak_friction();
        let speeds = start.vx.abs()
            + setup.r * start.omega.abs()
            + start.v[..modes.n].iter().map(|v| v.abs()).sum::<f64>();
        let w = setup.w;
        let response = &mut self.response;
        for (j, r) in response.iter_mut().enumerate().take(modes.n) {
            *r = if dir == 0.0 {
                Response::Free
            } else {
                let omega = modes.omega[j];
                let drive = modes.shape[0][j] * force;
                let amplitude = drive / (omega * omega - w * w);
                if (amplitude * w * modes.largest[j]).abs() <= DETUNED_GAIN * speeds {
                    Response::Detuned { amplitude }
                } else {
                    Response::Forced { drive }
                }
            };
        }
        let start_wt = (self.sin_wt0, self.cos_wt0);
        let n = modes.n;
        match start.frame {
            _ if held => {}
            0 => {
                let weights = |j| Sums::main_weights(modes, j);
                let sums = self.store.wall.get_or_insert_with(|| Sums::empty(n));
                sums.write(modes, w, (q0, dq0), response, (start_wt, fourth), weights);
            }
            frame => {
                let weights = |j| Sums::framed_weights(modes, frame, j);
                let sums = self.store.frame.get_or_insert_with(|| Sums::empty(n));
                sums.write(modes, w, (q0, dq0), response, (start_wt, fourth), weights);
            }
        }
    }

    /// The static friction F_s = m_eff Σ Φ_1j Ω_j² q_j (Eq. (5) on the chain) that a grip starting
    /// from `start` with the first mass moving and no string friction needs at its start: what
    /// [`Motion::contact`] of that grip gives at t0 (each mode's sum at τ = 0 is its X), without
    /// building the phase.
    pub fn grip_friction(chain: &Chain, setup: &Setup, start: &ChainState) -> f64 {
        let modes = chain.modes(0.0);
        // The rigid translation of a free frame (Φ_1j Ω_j² = 0) adds a zero, which changes no bit of
        // the sum from +0: its coordinate is not taken.
        let stiff = (0..modes.n)
            .filter(|&j| modes.rigid != Some(j))
            .fold(0.0, |sum, j| {
                sum + modes.first_stiff[j] * modes.project_one(j, &start.x)
            });
        setup.m_eff * stiff
    }

    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// The modes of this phase (held: those of the masses behind the first, or on a free frame the
    /// ring's, [`Chain::held`]).
    pub fn modes(&self) -> &Modes {
        match self.cart {
            Cart::Stuck => self.chain.held(self.dir),
            Cart::Moving(_) => self.chain.modes(self.dir),
        }
    }

    /// The phase's sums, written for a moving first mass (`None` held).
    #[inline]
    fn sums(&self) -> Option<Written<'_>> {
        if self.is_held() {
            return None;
        }
        match self.start.frame {
            0 => self.store.wall.as_ref().map(Written::Wall),
            _ => self.store.frame.as_ref().map(Written::Frame),
        }
    }

    pub fn is_held(&self) -> bool {
        self.cart == Cart::Stuck
    }

    pub fn is_grip(&self) -> bool {
        self.dir == 0.0
    }

    /// sin and cos of every Ω_j τ into `sin` and `cos`, two at a time, and of w τ while sliding (in
    /// the last place, returned; (0, 1) gripping). The rigid translation on a free frame, whose motion
    /// is polynomial in t, turns through no angle: its (0, 1) is exact and is not computed.
    #[inline(always)]
    fn angles(
        &self,
        modes: &Modes,
        w: f64,
        tau: f64,
        (sin, cos): (&mut [f64; MAX + 1], &mut [f64; MAX + 1]),
    ) -> (f64, f64) {
        let n = modes.n;
        let count = if self.is_grip() { n } else { n + 1 };
        let angle = |j: usize| if j < n { modes.omega[j] * tau } else { w * tau };
        match modes.rigid {
            Some(r) => {
                (sin[r], cos[r]) = (0.0, 1.0);
                let index = |i: usize| if i < r { i } else { i + 1 };
                turn((sin, cos), count - 1, index, angle);
            }
            None => turn((sin, cos), count, |i| i, angle),
        }
        if self.is_grip() {
            (0.0, 1.0)
        } else {
            (sin[n], cos[n])
        }
    }

    /// sin and cos of every Ω_j τ, and of w τ while sliding (in the last place), into `sin` and
    /// `cos` by [`sin_cos_each`] (to about 2 ulp, for [`Motion::rows`]); sin(w τ), cos(w τ) ((0, 1)
    /// gripping). The rigid translation on a free frame turns through no angle: it is left out of
    /// the batch (whose every angle goes to the same method, so that leaving out a zero changes no
    /// other's bits: the batch's last angle takes its lane) and given `rigid`, its exact (0, 1), or
    /// (τ, 1) where the sums write its X + V τ in their place.
    #[inline(always)]
    fn angles_each(
        &self,
        (modes, w, tau): (&Modes, f64, f64),
        (sin, cos): (&mut [f64; MAX + 1], &mut [f64; MAX + 1]),
        rigid: (f64, f64),
    ) -> (f64, f64) {
        let n = modes.n;
        let count = if self.is_grip() { n } else { n + 1 };
        if tau == 0.0 {
            // The phase's start (the search's first probe): every angle is 0, whose sin and cos
            // `sin_cos_each` gives exactly, (0, 1), as `rigid` is there.
            sin[..count].fill(0.0);
            cos[..count].fill(1.0);
            return (0.0, 1.0);
        }
        let mut angle = [0.0; MAX + 1];
        for (a, omega) in angle.iter_mut().zip(&modes.omega[..n]) {
            *a = omega * tau;
        }
        angle[n] = w * tau;
        match modes.rigid {
            Some(r) if r < count => {
                let last = count - 1;
                angle[r] = angle[last];
                sin_cos_each(&angle[..last], &mut sin[..last], &mut cos[..last]);
                (sin[last], cos[last]) = (sin[r], cos[r]);
                (sin[r], cos[r]) = rigid;
            }
            _ => sin_cos_each(&angle[..count], &mut sin[..count], &mut cos[..count]),
        }
        if self.is_grip() {
            (0.0, 1.0)
        } else {
            (sin[n], cos[n])
        }
    }

    /// Mode j's coordinate and rate at τ without the string friction, given sin and cos of Ω_j τ and
    /// of w τ.
    #[inline]
    fn mode_at(
        &self,
        modes: &Modes,
        w: f64,
        (j, tau): (usize, f64),
        (s, c): (f64, f64),
        w_tau: (f64, f64),
    ) -> (f64, f64) {
        let omega = modes.omega[j];
        let (x_free, v_free) = free_given(self.q0[j], self.dq0[j], omega, tau, s, c);
        match self.response[j] {
            Response::Free => (x_free, v_free),
            Response::Detuned { amplitude } => {
                let phase0 = (self.sin_wt0, self.cos_wt0);
                let (x_forced, v_forced) = detuned(omega, w, tau, phase0, w_tau, (s, c));
                (x_free + amplitude * x_forced, v_free + amplitude * v_forced)
            }
            Response::Forced { drive } => {
                let (g, dg) = forced(omega, w, self.sin_wt0, self.cos_wt0, tau);
                (x_free + drive * g, v_free + drive * dg)
            }
        }
    }

    /// The string friction's share of mode j at τ (switched on at t0: Φ_1j push (1 - cos Ωτ)/Ω²).
    #[inline(always)]
    fn pushed(&self, modes: &Modes, (j, tau): (usize, f64), (s, c): (f64, f64)) -> (f64, f64) {
        let (x_step, v_step) = step(s, c, modes.omega[j], tau);
        let drive = self.push_shape(j) * self.push;
        (drive * x_step, drive * v_step)
    }

    /// The modal coordinates and their rates at `t`, written into `q` and `dq` (each of the modes' entries;
    /// filled in place rather than returned, which would copy the arrays), with sin(w τ) and cos(w τ),
    /// τ = t - t0.
    #[inline]
    fn modal(&self, setup: &Setup, t: f64, q: &mut [f64; MAX], dq: &mut [f64; MAX]) -> (f64, f64) {
        let modes = self.modes();
        let tau = t - self.start.t;
        let w = setup.w;
        let (mut sin, mut cos) = ([0.0; MAX + 1], [0.0; MAX + 1]);
        let w_tau = self.angles(modes, w, tau, (&mut sin, &mut cos));
        for j in 0..modes.n {
            (q[j], dq[j]) = self.mode_at(modes, w, (j, tau), (sin[j], cos[j]), w_tau);
        }
        if self.push != 0.0 {
            for j in 0..modes.n {
                let (x, v) = self.pushed(modes, (j, tau), (sin[j], cos[j]));
                q[j] += x;
                dq[j] += v;
            }
        }
        w_tau
    }

    /// The rows of [`Sums`] that `mask` names at `t` through the phase's combinations `sums`, with
    /// sin(w τ) and cos(w τ), for the phase's `modes` (the others are left 0).
    #[inline(always)]
    fn rows<const R: usize, S: Shares<R>, const MASK: Mask, const FOURTH: Mask>(
        &self,
        (modes, sums): (&Modes, &Sums<R, S>),
        weights: impl Fn(usize) -> [(f64, bool); R],
        (setup, t): (&Setup, f64),
    ) -> ([f64; R], [f64; 2], (f64, f64)) {
        let tau = t - self.start.t;
        let w = setup.w;
        let n = modes.n;
        let (mut sin, mut cos) = ([0.0; MAX + 1], [0.0; MAX + 1]);
        let rigid = if sums.rigid.is_some() {
            (tau, 1.0)
        } else {
            (0.0, 1.0)
        };
        let w_tau = self.angles_each((modes, w, tau), (&mut sin, &mut cos), rigid);
        let wt = (!self.is_grip()).then(|| {
            let (sin_w_tau, cos_w_tau) = w_tau;
            (
                self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau,
                self.cos_wt0 * cos_w_tau - self.sin_wt0 * sin_w_tau,
            )
        });
        let mut rows = sums.main.at::<MASK>(n, (&sin, &cos), wt);
        let mut fourth = sums.fourth.at::<FOURTH>(n, (&sin, &cos), wt);
        for &j in &sums.odd[..sums.odd_n] {
            let motion = self.mode_at(modes, w, (j, tau), (sin[j], cos[j]), w_tau);
            add::<R, MASK>(&mut rows, weights(j), motion);
            if FOURTH != 0 {
                add::<2, FOURTH>(&mut fourth, Sums::fourth_weights(modes, j), motion);
            }
        }
        if self.push != 0.0 {
            for j in 0..n {
                let motion = self.pushed(modes, (j, tau), (sin[j], cos[j]));
                add::<R, MASK>(&mut rows, weights(j), motion);
                if FOURTH != 0 {
                    add::<2, FOURTH>(&mut fourth, Sums::fourth_weights(modes, j), motion);
                }
            }
        }
        (rows, fourth, w_tau)
    }

    /// The rows of the phase's [`Sums`] (`written`) that `MASK` (of the main and the frame's) and
    /// `FOURTH` (of S4 and its rate) name at `t`, for the phase's `modes`, with sin(w τ) and cos(w τ).
    #[inline(always)]
    fn summed<const MASK: Mask, const FOURTH: Mask>(
        &self,
        (modes, written): (&Modes, Written<'_>),
        setup: &Setup,
        t: f64,
    ) -> Summed {
        match written {
            Written::Wall(sums) => {
                let weights = |j| Sums::main_weights(modes, j);
                let (main, fourth, w_tau) =
                    self.rows::<4, _, MASK, FOURTH>((modes, sums), weights, (setup, t));
                Summed {
                    main,
                    framed: [0.0; 3],
                    fourth,
                    w_tau,
                }
            }
            Written::Frame(sums) => {
                let frame = self.start.frame;
                let weights = |j| Sums::framed_weights(modes, frame, j);
                let ([a, b, c, d, e, f, g], fourth, w_tau) =
                    self.rows::<7, _, MASK, FOURTH>((modes, sums), weights, (setup, t));
                Summed {
                    main: [a, b, c, d],
                    framed: [e, f, g],
                    fourth,
                    w_tau,
                }
            }
        }
    }

    /// The ball's impulse ∫ F dt since t0 and the friction F at t0 + τ while it slides, Eqs. (1), (2):
    /// F0 (cos w t0 - cos w t)/w and F0 sin(w t), given sin(w τ) and cos(w τ).
    #[inline]
    fn sliding(&self, setup: &Setup, sin_w_tau: f64, cos_w_tau: f64) -> (f64, f64) {
        let force = self.dir * setup.peak_friction();
        let impulse =
            force * (self.cos_wt0 * (1.0 - cos_w_tau) + self.sin_wt0 * sin_w_tau) / setup.w;
        let sin_wt = self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau;
        (impulse, force * sin_wt.max(0.0))
    }

    /// The ball, the first mass and the friction at `t`. (One body for every caller: inlined into
    /// the event functions it made the chain with string friction 3% slower.)
    #[inline(never)]
    pub fn contact(&self, setup: &Setup, t: f64) -> Contact {
        let frame = self.start.frame;
        if self.is_held() && frame == 0 {
            return self.held_contact(setup, t);
        }
        let modes = self.modes();
        if let Some(written) = self.sums() {
            let r = self.summed::<{ CONTACT | FRAME }, 0>((modes, written), setup, t);
            return self.moving_contact(modes, setup, t, (&r.main, &r.framed), r.w_tau);
        }
        let (mut q, mut dq) = ([0.0; MAX], [0.0; MAX]);
        let (sin_w_tau, cos_w_tau) = self.modal(setup, t, &mut q, &mut dq);
        let moving_frame = if self.is_held() { 0 } else { frame };
        let (main, framed) = Sums::from_modal(modes, moving_frame, (&q, &dq));
        self.moving_contact(modes, setup, t, (&main, &framed), (sin_w_tau, cos_w_tau))
    }

    /// For the event search of a first mass moving without string friction (the phase has its sums):
    /// [`Motion::contact`] from the main rows `MASK` names ([`SLIP`] or [`MARGINS`]; a row left out
    /// reads 0, so the contact holds only what they give), with what the event's higher derivatives
    /// read ([`Probe`], S4 and its rate as `FOURTH` names them, [`SLIP_FOURTH`] or
    /// [`MARGINS_FOURTH`]; 0 where it does not). Its bits are `contact`'s where it reads the same rows; the frame's rows are
    /// not summed, nor the frame's motion taken from them. (One body for its callers, as `contact` is.)
    #[inline(never)]
    pub fn probe<const MASK: Mask, const FOURTH: Mask>(&self, setup: &Setup, t: f64) -> Probe {
        let modes = self.modes();
        let Some(written) = self.sums().filter(Written::has_fourth) else {
            // Not reached (a first mass is held only by string friction, and the phases searched so
            // are built with S4); the NaNs prove nothing.
            return Probe {
                contact: self.contact(setup, t),
                stiff_rate: f64::NAN,
                fourth: [f64::NAN; 2],
                cos_wt: f64::NAN,
            };
        };
        let r = self.summed::<MASK, FOURTH>((modes, written), setup, t);
        let rows = (&r.main, &r.framed);
        let contact = self.moving_contact_of::<false>(modes, setup, t, rows, r.w_tau);
        let (sin_w_tau, cos_w_tau) = r.w_tau;
        Probe {
            contact,
            stiff_rate: r.main[3],
            fourth: r.fourth,
            cos_wt: self.cos_wt0 * cos_w_tau - self.sin_wt0 * sin_w_tau,
        }
    }

    /// [`Motion::contact`] of a moving first mass given the phase's `modes`, the rows of [`Sums`] at
    /// `t` (the main and the frame's) and sin(w τ), cos(w τ) there.
    #[inline]
    fn moving_contact(
        &self,
        modes: &Modes,
        setup: &Setup,
        t: f64,
        rows: (&[f64; 4], &[f64; 3]),
        w_tau: (f64, f64),
    ) -> Contact {
        self.moving_contact_of::<true>(modes, setup, t, rows, w_tau)
    }

    /// [`Motion::moving_contact`]; without `FRAME_ROWS` (the event search's probes, which sum none of
    /// the frame's rows) the first mass's displacement is X_1 itself and the frame's motion is left
    /// 0 on a free frame, every other field the same.
    #[inline]
    fn moving_contact_of<const FRAME_ROWS: bool>(
        &self,
        modes: &Modes,
        setup: &Setup,
        t: f64,
        (main, framed): (&[f64; 4], &[f64; 3]),
        (sin_w_tau, cos_w_tau): (f64, f64),
    ) -> Contact {
        let frame = self.start.frame;
        let ([mut x, v, stiff, stiff_rate], [xf, last, vf]) = (*main, *framed);
        let mut frame_motion = (0.0, 0.0);
        if FRAME_ROWS && frame > 0 && !self.is_held() {
            // The first mass's displacement is reported relative to the free frame.
            x -= xf;
            // The frame feels the last link's spring and the string friction's reaction -push.
            let spring = self.chain.link_stiffness * (last - xf);
            frame_motion = (vf, (spring - self.push) / modes.mass[frame]);
        }
        let s0 = &self.start;
        // The spring and string forces on the first mass over its mass: Σ Φ_1j Ω_j² q_j less push/m_1.
        let held_back = if self.push == 0.0 {
            stiff
        } else {
            stiff - self.push / modes.mass[0]
        };
        let (impulse, friction, friction_rate, accel) = if self.is_grip() {
            // F_s = -m_eff V_1', V_1' = -(Σ Φ_1j Ω_j² q_j - push/m_1) (Eq. (5) on the chain); the
            // impulse on the ball is -m_eff (V_1 - V_1(t0)).
            let m_eff = setup.m_eff;
            (
                -m_eff * (v - self.v1_start),
                m_eff * held_back,
                m_eff * stiff_rate,
                -held_back,
            )
        } else {
            let (impulse, friction) = self.sliding(setup, sin_w_tau, cos_w_tau);
            (impulse, friction, 0.0, friction / modes.mass[0] - held_back)
        };
        if frame > 0 && self.is_held() {
            // Held to the frame: the first mass keeps its place on it and moves with it.
            x = s0.x[0] - s0.x[frame];
            frame_motion = (v, accel);
        }
        Contact {
            state: State {
                t,
                vx: s0.vx - impulse / setup.m,
                omega: s0.omega + impulse * setup.r / setup.inertia,
                x,
                v,
            },
            friction,
            friction_rate,
            accel,
            frame: frame_motion,
        }
    }

    /// The ball and the held first mass at `t`: the ball slides on a still surface (Eqs. (1), (2)) or
    /// rolls on it with no friction.
    fn held_contact(&self, setup: &Setup, t: f64) -> Contact {
        let s0 = &self.start;
        let (impulse, friction) = if self.is_grip() {
            (0.0, 0.0)
        } else {
            let (sin_w_tau, cos_w_tau) = sin_cos(setup.w * (t - s0.t));
            self.sliding(setup, sin_w_tau, cos_w_tau)
        };
        Contact {
            state: State {
                t,
                vx: s0.vx - impulse / setup.m,
                omega: s0.omega + impulse * setup.r / setup.inertia,
                x: s0.x[0],
                v: 0.0,
            },
            friction,
            friction_rate: 0.0,
            accel: 0.0,
            frame: (0.0, 0.0),
        }
    }

    /// The spring force on the held first mass, N k (X_1 - X_2), and its rate, at `t`. On the rest line
    /// X_1 - X_2 = X_1/N; the masses' swing Σ Φ_1j q_j about it adds the rest.
    pub fn link(&self, setup: &Setup, t: f64) -> (f64, f64) {
        let modes = self.modes();
        let (mut q, mut dq) = ([0.0; MAX], [0.0; MAX]);
        self.modal(setup, t, &mut q, &mut dq);
        let (mut x2, mut v2) = (0.0, 0.0);
        for j in 0..modes.n {
            x2 += modes.shape[0][j] * q[j];
            v2 += modes.shape[0][j] * dq[j];
        }
        let chain = &self.chain;
        let kappa = chain.link_stiffness;
        (kappa * (self.start.x[0] / chain.n as f64 - x2), -kappa * v2)
    }

    /// The whole chain at `t`.
    pub fn full(&self, setup: &Setup, t: f64) -> ChainState {
        self.contact_and_full(setup, t).1
    }

    /// [`Motion::contact`] and [`Motion::full`] at `t`, the modal coordinates taken once for both (the
    /// held ring's search reads both at every evaluation): the contact is the one `contact` gives, bit
    /// for bit (the same rows from the same sums or modal coordinates).
    #[inline(always)]
    pub fn contact_and_full(&self, setup: &Setup, t: f64) -> (Contact, ChainState) {
        let modes = self.modes();
        let (mut q, mut dq) = ([0.0; MAX], [0.0; MAX]);
        let (sin_w_tau, cos_w_tau) = self.modal(setup, t, &mut q, &mut dq);
        // The first mass and the frame as the event search saw them (the phase's sums), so that the
        // next phase starts where this one's events were measured.
        let mut searched = None;
        let contact = if self.is_held() && self.start.frame == 0 {
            self.held_contact(setup, t)
        } else if let Some(written) = self.sums() {
            let r = self.summed::<{ CONTACT | FRAME }, 0>((modes, written), setup, t);
            if let Written::Frame(_) = written {
                searched = Some((r.main, r.framed));
            }
            self.moving_contact(modes, setup, t, (&r.main, &r.framed), r.w_tau)
        } else {
            let frame = if self.is_held() { 0 } else { self.start.frame };
            let (main, framed) = Sums::from_modal(modes, frame, (&q, &dq));
            self.moving_contact(modes, setup, t, (&main, &framed), (sin_w_tau, cos_w_tau))
        };
        let state = &contact.state;
        let frame = self.start.frame;
        let (mut x, mut v) = ([0.0; MAX], [0.0; MAX]);
        // Where the sums give the first mass (and the frame), its row (and the frame's) of Φ q is
        // not summed only to be written over.
        let rows = match (self.sums(), searched) {
            (Some(Written::Wall(_)), _) => 1..modes.n,
            (_, Some(_)) => 1..frame,
            _ => 0..modes.n,
        };
        modes.expand_rows((&q, &dq), (&mut x, &mut v), rows);
        if self.is_held() && frame > 0 {
            (x, v) = ring_coordinates::place(&self.chain, &self.start, &x, &v);
        } else if self.is_held() {
            // Behind the held mass: its rest line plus the swing.
            for i in (1..self.chain.n).rev() {
                x[i] = rest_line(&self.chain, &self.start, i) + x[i - 1];
                v[i] = v[i - 1];
            }
            (x[0], v[0]) = (state.x, 0.0);
        } else if let Some(Written::Wall(_)) = self.sums() {
            (x[0], v[0]) = (state.x, state.v);
        } else if let Some(([x1, v1, ..], [xf, _, vf])) = searched {
            (x[0], v[0], x[frame], v[frame]) = (x1, v1, xf, vf);
        }
        let full = ChainState {
            t,
            vx: state.vx,
            omega: state.omega,
            x,
            v,
            frame,
        };
        (contact, full)
    }

    /// A bound on |q_j'| over the rest of the contact, per mode, for a sliding phase: the smaller of the
    /// energy bound d/dt sqrt(q'² + Ω² q²) <= |Φ_1j (F + push)| integrated (the friction's remaining
    /// impulse is at most mu N0 (1 + cos w t0)/w) and the amplitudes of the closed form: |a| w, the free
    /// swing and the string friction's step |Φ_1j push|/Ω.
    fn speed_bounds(&self, setup: &Setup) -> [f64; MAX] {
        let modes = self.modes();
        let w = setup.w;
        let force = setup.peak_friction();
        let remaining_impulse = force * (1.0 + self.cos_wt0) / w;
        let mut bounds = [0.0; MAX];
        for (j, bound) in bounds.iter_mut().enumerate().take(modes.n) {
            let (omega, q0, dq0) = (modes.omega[j], self.q0[j], self.dq0[j]);
            let phi = modes.shape[0][j].abs();
            let mut energy = (dq0 * dq0 + (omega * q0).powi(2)).sqrt() + phi * remaining_impulse;
            let detuning = omega * omega - w * w;
            let mut amplitudes = if detuning == 0.0 || self.is_grip() {
                f64::INFINITY
            } else {
                let a = self.dir * modes.shape[0][j] * force / detuning;
                let x_free = q0 - a * self.sin_wt0;
                let v_free = dq0 - a * w * self.cos_wt0;
                a.abs() * w + ((omega * x_free).powi(2) + v_free * v_free).sqrt()
            };
            let push = self.pushing(j).abs();
            if push > 0.0 {
                energy += push * (setup.duration - self.start.t);
                amplitudes += if omega > 0.0 {
                    push / omega
                } else {
                    f64::INFINITY
                };
            }
            *bound = energy.min(amplitudes);
        }
        bounds
    }

    /// A bound on |q_j'| over a grip phase. Each mode swings freely about its equilibrium under the
    /// string friction, q_e = Φ_1j push / Ω², so sqrt(q'² + Ω² (q - q_e)²) stays at its start value; a
    /// mode of zero frequency instead gains speed at the rate Φ_1j push.
    fn grip_swing(&self, setup: &Setup, j: usize) -> f64 {
        let modes = self.modes();
        let (omega, q0, dq0) = (modes.omega[j], self.q0[j], self.dq0[j]);
        let push = self.pushing(j);
        if push == 0.0 {
            (dq0.powi(2) + (omega * q0).powi(2)).sqrt()
        } else if omega == 0.0 {
            dq0.abs() + push.abs() * (setup.duration - self.start.t)
        } else {
            (dq0.powi(2) + (omega * q0 - push / omega).powi(2)).sqrt()
        }
    }

    /// The slide's bound on |slip''| and the size of the terms of the slip (for its rounding floor).
    ///
    /// slip'' = -F' (1/m_eff + 1/m_1) + Σ Φ_1j Ω_j² q_j', with |F'| <= mu N0 w.
    pub fn slip_curvature(&self, setup: &Setup) -> (f64, f64) {
        let [curvature, terms, _] = self.slip_bounds_of::<false>(setup);
        (curvature, terms)
    }

    /// [`Motion::slip_curvature`]'s bound and terms, and a bound on |slip''''|, for a slide of a moving
    /// first mass. slip'''' = -F''' (1/m_eff + 1/m_1) + Σ Φ_1j Ω_j² q_j''' with |F'''| <= mu N0 w³
    /// and q_j''' = -Ω_j² q_j' + Φ_1j F' (the string friction is constant), so |slip''''| <=
    /// mu N0 w³ (1/m_eff + 1/m_1) + Σ |Φ_1j| Ω_j² (Ω_j² |q_j'| + |Φ_1j| mu N0 w), with the same bound
    /// on |q_j'| as the curvature's.
    pub fn slip_bounds(&self, setup: &Setup) -> [f64; 3] {
        self.slip_bounds_of::<true>(setup)
    }

    /// [`Motion::slip_bounds`], the fourth derivative's bound only `WITH_FOURTH` (else 0).
    #[inline(always)]
    fn slip_bounds_of<const WITH_FOURTH: bool>(&self, setup: &Setup) -> [f64; 3] {
        let modes = self.modes();
        let bounds = self.speed_bounds(setup);
        let (force, w) = (setup.peak_friction(), setup.w);
        let inverse = 1.0 / setup.m_eff + 1.0 / modes.mass[0];
        let mut curvature = force * w * inverse;
        let mut fourth = force * w.powi(3) * inverse;
        let mut terms = 0.0;
        for (j, bound) in bounds.iter().enumerate().take(modes.n) {
            let (stiff, phi, omega) = (
                modes.first_stiff[j].abs(),
                modes.shape[0][j].abs(),
                modes.omega[j],
            );
            curvature += stiff * bound;
            terms += phi * bound;
            if WITH_FOURTH {
                fourth += stiff * (omega * omega * bound + phi * force * w);
            }
        }
        [curvature, terms, if WITH_FOURTH { fourth } else { 0.0 }]
    }

    /// The grip's bound on the second derivative of its margins ±F_s - mu N, and the size of the terms
    /// of F_s. Each mode swings about its equilibrium with sqrt(q'² + Ω² (q - q_e)²) = E_j fixed, so
    /// |F_s''| = m_eff |Σ Φ_1j Ω_j⁴ (q_j - q_e)| <= m_eff Σ |Φ_1j| Ω_j³ E_j; mu N'' is at most mu N0 w².
    pub fn margin_curvature(&self, setup: &Setup) -> (f64, f64) {
        let [curvature, terms, _] = self.margin_bounds_of::<false>(setup);
        (curvature, terms)
    }

    /// [`Motion::margin_curvature`]'s bound and terms, and a bound on the fourth derivative of the
    /// margins: F_s'''' = m_eff Σ Φ_1j Ω_j⁶ (q_j - q_e), so |F_s''''| <= m_eff Σ |Φ_1j| Ω_j⁵ E_j, and
    /// |mu N''''| <= mu N0 w⁴.
    pub fn margin_bounds(&self, setup: &Setup) -> [f64; 3] {
        self.margin_bounds_of::<true>(setup)
    }

    /// [`Motion::margin_bounds`], the fourth derivative's bound only `WITH_FOURTH` (else 0).
    #[inline(always)]
    fn margin_bounds_of<const WITH_FOURTH: bool>(&self, setup: &Setup) -> [f64; 3] {
        let modes = self.modes();
        let mut curvature = setup.peak_friction() * setup.w * setup.w;
        let mut fourth = curvature * setup.w * setup.w;
        let mut terms = setup.peak_friction();
        for j in 0..modes.n {
            let omega = modes.omega[j];
            // The rigid translation of a free frame (Ω = 0) reaches nothing: its swing is not taken.
            let reach = if omega == 0.0 {
                0.0
            } else {
                setup.m_eff * modes.shape[0][j].abs() * omega * self.grip_swing(setup, j)
            };
            curvature += reach * omega * omega;
            if WITH_FOURTH {
                fourth += reach * omega.powi(4);
            }
            terms += reach;
        }
        if self.push != 0.0 {
            // The string friction's share of F_s, m_eff push/m_1, and the equilibria's Σ Φ_1j Ω_j² q_e.
            terms += 2.0 * setup.m_eff * (self.push / modes.mass[0]).abs();
        }
        [curvature, terms, if WITH_FOURTH { fourth } else { 0.0 }]
    }

    /// The constant forcing of S'' = Σ Φ_1j Ω_j² q_j'' = drive - S4: each mode obeys
    /// q_j'' = Φ_1j F + s_j push - Ω_j² q_j (F the ball's friction while it slides, s_j the string
    /// friction's share, `Motion::push_shape`), so drive = F Σ Φ_1j² Ω_j² + push Σ Φ_1j Ω_j² s_j:
    /// the two sums, the second times push, for a phase of a moving first mass.
    pub fn drives(&self) -> [f64; 2] {
        let modes = self.modes();
        let (mut friction, mut push) = (0.0, 0.0);
        for j in 0..modes.n {
            friction += modes.first_stiff[j] * modes.shape[0][j];
            if self.push != 0.0 {
                push += modes.first_stiff[j] * self.push_shape(j);
            }
        }
        [friction, push * self.push]
    }

    /// slip'' and slip''' of a slide of a moving first mass at a probe `p` ([`Motion::probe`] with
    /// [`SLIP`]), given its [`Motion::drives`]: with slip' = -F/m_eff - V_1' and
    /// V_1' = (F + push)/m_1 - S, slip'' = S' - F' (1/m_eff + 1/m_1) and
    /// slip''' = w² F (1/m_eff + 1/m_1) + drive - S4 (F = dir mu N0 sin w t, F'' = -w² F).
    pub fn slip_higher(
        &self,
        setup: &Setup,
        p: &Probe,
        [on_friction, on_push]: [f64; 2],
    ) -> (f64, f64) {
        let inverse = 1.0 / setup.m_eff + 1.0 / self.modes().mass[0];
        let friction = p.contact.friction;
        let friction_rate = self.dir * setup.peak_friction() * setup.w * p.cos_wt;
        let drive = on_friction * friction + on_push;
        (
            p.stiff_rate - inverse * friction_rate,
            inverse * setup.w * setup.w * friction - p.fourth[0] + drive,
        )
    }

    /// F_s and its first three derivatives at a probe `p` of a grip of a moving first mass
    /// ([`Motion::probe`] with [`MARGINS`]), given its [`Motion::drives`]: F_s = m_eff (S - push/m_1)
    /// (Eq. (5) on the chain), F_s' = m_eff S', F_s'' = m_eff (drive - S4), F_s''' = -m_eff S4'.
    pub fn grip_force(&self, setup: &Setup, p: &Probe, [_, on_push]: [f64; 2]) -> [f64; 4] {
        let m_eff = setup.m_eff;
        let [fourth, fourth_rate] = p.fourth;
        [
            p.contact.friction,
            p.contact.friction_rate,
            m_eff * (on_push - fourth),
            -(m_eff * fourth_rate),
        ]
    }

    /// A bound on |V_1''| over the phase of a moving first mass, and the size of the terms of V_1.
    /// Sliding, V_1'' = F'/m_1 - Σ Φ_1j Ω_j² q_j'; gripping, each mode's q_j' swings as q_j does, its
    /// second derivative -Ω_j² q_j', so |V_1''| <= Σ |Φ_1j| Ω_j² E_j.
    pub fn cart_curvature(&self, setup: &Setup) -> (f64, f64) {
        let modes = self.modes();
        let (mut curvature, mut terms) = (0.0, 0.0);
        if self.is_grip() {
            for j in 0..modes.n {
                let swing = self.grip_swing(setup, j);
                curvature += modes.shape[0][j].abs() * modes.omega[j].powi(2) * swing;
                terms += modes.shape[0][j].abs() * swing;
            }
        } else {
            curvature = setup.peak_friction() * setup.w / modes.mass[0];
            for (j, bound) in self.speed_bounds(setup).iter().enumerate().take(modes.n) {
                curvature += modes.first_stiff[j].abs() * bound;
                terms += modes.shape[0][j].abs() * bound;
            }
        }
        (curvature, terms)
    }

    /// The string friction's push on mode j per newton: Φ_1j on the wall; on a free frame Φ_1j - Φ_fj,
    /// the push on the first mass with its reaction on the frame (0 for the rigid translation).
    #[inline(always)]
    fn push_shape(&self, j: usize) -> f64 {
        let modes = self.modes();
        match self.start.frame {
            0 => modes.shape[0][j],
            frame => modes.shape[0][j] - modes.shape[frame][j],
        }
    }

    /// The string friction's push on mode j, [`Motion::push_shape`] times push: 0 without it, where
    /// the shape is not looked up.
    #[inline(always)]
    fn pushing(&self, j: usize) -> f64 {
        if self.push == 0.0 {
            0.0
        } else {
            self.push_shape(j) * self.push
        }
    }

    /// On a free frame, for a sliding phase of a moving first mass: a bound on |(V_1 - V_f)''|, the
    /// first mass relative to the frame, and the size of the terms it is summed from. V_1 - V_f =
    /// Σ (Φ_1j - Φ_fj) q_j' with q_j''' = Φ_1j F' - Ω_j² q_j' (the push is constant), |F'| <= mu N0 w.
    pub fn relative_curvature(&self, setup: &Setup) -> (f64, f64) {
        let modes = self.modes();
        let rate = setup.peak_friction() * setup.w;
        let (mut curvature, mut terms) = (0.0, 0.0);
        for (j, bound) in self.speed_bounds(setup).iter().enumerate().take(modes.n) {
            let share = self.push_shape(j).abs();
            curvature += share * (modes.shape[0][j].abs() * rate + modes.omega[j].powi(2) * bound);
            terms += share * bound;
        }
        (curvature, terms)
    }

    /// For a held first mass: a bound on the second derivative of the spring force N k (X_1 - X_2) on
    /// it, and the size of its terms. Each mode behind it swings freely, |q_j''| <= Ω_j E_j with
    /// E_j = sqrt(q_j'² + Ω_j² q_j²) fixed, so |S''| <= N k Σ |Φ_1j| Ω_j E_j.
    pub fn link_curvature(&self) -> (f64, f64) {
        let chain = &self.chain;
        let kappa = chain.link_stiffness;
        if kappa == 0.0 {
            return (0.0, 0.0);
        }
        let modes = self.modes();
        let mut curvature = 0.0;
        let mut terms = kappa * self.start.x[0].abs() / chain.n as f64;
        for j in 0..modes.n {
            let omega = modes.omega[j];
            let swing = (self.dq0[j].powi(2) + (omega * self.q0[j]).powi(2)).sqrt();
            let phi = modes.shape[0][j].abs();
            curvature += kappa * phi * omega * swing;
            terms += kappa * phi * swing / omega;
        }
        (curvature, terms)
    }
}

/// sin and cos of `angle(index(i))` for i < `turns`, two at a time, written at `index(i)`.
#[inline(always)]
fn turn(
    (sin, cos): (&mut [f64; MAX + 1], &mut [f64; MAX + 1]),
    turns: usize,
    index: impl Fn(usize) -> usize,
    angle: impl Fn(usize) -> f64,
) {
    let mut i = 0;
    while i + 1 < turns {
        let (j, k) = (index(i), index(i + 1));
        ((sin[j], cos[j]), (sin[k], cos[k])) = sin_cos2(angle(j), angle(k));
        i += 2;
    }
    if i < turns {
        let j = index(i);
        (sin[j], cos[j]) = sin_cos(angle(j));
    }
}

/// Mass `i` (0-based) on the straight line from the held first mass to the wall, X_1 (N - i)/N: where
/// the springs behind a still first mass are at rest.
fn rest_line(chain: &Chain, start: &ChainState, i: usize) -> f64 {
    start.x[0] * (chain.n - i) as f64 / chain.n as f64
}

impl Motion {
    /// The rigid ball's slip v_x - r ω - V_1 on a first mass sliding on the wall without string
    /// friction, its rate -F/m_eff - V_1', and sin(w τ), cos(w τ) (τ = t - t0), from the phase's
    /// sums without the rate of Σ Φ_1j Ω_j² q_j, which the slip does not read: the bits
    /// [`Motion::contact`] gives them, for an event search that needs only the slip. `None` gripping,
    /// held, on a free frame or with string friction.
    #[inline(never)]
    pub fn slip_by_sums(&self, setup: &Setup, t: f64) -> Option<(f64, f64, (f64, f64))> {
        let written = self.sums().filter(|w| matches!(w, Written::Wall(_)))?;
        if self.is_grip() || self.push != 0.0 {
            return None;
        }
        let modes = self.modes();
        let r = self.summed::<SLIP_RATE, 0>((modes, written), setup, t);
        let c = self.moving_contact(modes, setup, t, (&r.main, &r.framed), r.w_tau);
        let w_tau = r.w_tau;
        let rate = -c.friction / setup.m_eff - c.accel;
        Some((setup.slip(&c.state), rate, w_tau))
    }
}
