//! The grip of a compliant ball on a chain of masses: one damped modal system (issue 6, parts 2 and 3
//! together).
//!
//! The ball's contact point u (effective mass m_eff) is joined to the chain's first mass by the ball's
//! spring k_b and dashpot c_b, while the contact patch moves with that mass. The chain is written in its
//! own normal modes (those of the slide, `chain.slide`, mass-normalised):
//!
//! m_eff u'' = -F,  Q_j'' + Ω_j² Q_j = Φ_1j F,  F = k_b e + c_b e',  e = u - X_1,  X_1 = Σ Φ_1j Q_j.
//!
//! A motion e^{s t} that carries the unit force F = 1 has u = -1/(m_eff s²) and Q_j = Φ_1j/(s² + Ω_j²);
//! it exists where g(s) = 1 + (k_b + c_b s) R(s) = 0, with R(s) = 1/(m_eff s²) + Σ Φ_1j²/(s² + Ω_j²)
//! the receptance between the ball and the first mass. g has 2(N + 1) roots. They start from the
//! undamped modes (c_b = 0: one root ω² of 1 + k_b R(iω) = 0 between each pair of neighbouring Ω_j²,
//! found by bisection), damped in proportion to the dashpot's share of each mode, and are then found
//! by Newton's method on the polynomial with Maehly's deflation (so that no root is found twice), or from
//! the Schur form of the state matrix when that fails. The damping is not proportional, but the system
//! is symmetric (mass D, damping C, stiffness K), so its modes w = (y, s y) are orthogonal under
//! [[C, D], [D, 0]]: the coefficient of mode i in a state z0 is w_iᵀ [[C, D], [D, 0]] z0 over
//! w_iᵀ [[C, D], [D, 0]] w_i, O(N) each. Every state of the grip is then Σ c_i e^{s_i τ} w_i, and the
//! friction force simply Σ c_i e^{s_i τ}.
//!
//! The modes are used where they reproduce the grip's start state to rounding without cancellation;
//! otherwise (near-double roots) the grip is evaluated through the matrix exponential of its state
//! matrix, exactly but slowly.
//!
//! String friction on a moving first mass adds the constant push P = -d F_c to its equation, a forcing
//! b = (0, 0, 0, Φ_1j P) of z' = A z + b. By Duhamel's integral each mode gains β_i (e^{s_i τ} - 1)/s_i,
//! β_i the push's coefficient by the same orthogonality (accepted by the same checks as the start
//! state's); the fallback exponentiates the state matrix augmented with the push's column.
//!
//! On a free frame (issue 23) the chain's modes include the rigid translation of chain and frame (Ω = 0,
//! Φ_i0 = c = 1/sqrt(M) with M the chain's and the frame's mass), so K above is singular. That mode and
//! the ball's u are written instead as the centre of mass G of ball, chain and frame, which moves
//! uniformly (the grip's force is internal), and the ball's position relative to the rigid translation
//! Y = c Q_0, r = u - Y: from m_eff u'' = -F and Y'' = c² F, μ r'' = -F with the reduced mass
//! 1/μ = 1/m_eff + 1/M, and e = r - Σ' Φ_1j Q_j over the other modes. The grip is then the clamped
//! chain's system with μ for m_eff and the flexible modes alone, solved as above; u = G + (M/(m_eff + M)) r
//! and Y = G - (m_eff/(m_eff + M)) r give the ball and the chain back.
//!
//! By job: this file holds the modes and a grip's evaluation; [`roots`] finds the roots, [`coefficients`]
//! writes a start state in the modes, [`search`] bounds |F''| and |F''''| for the event search (and
//! searches a wall grip's break), and [`fallback`] is the matrix exponential.

use std::sync::{Arc, Mutex, OnceLock};

use super::super::trig::{exp as fast_exp, sin_cos, sin_cos_each};
use nalgebra::{Cholesky, Complex, DMatrix, DVector};

mod coefficients;
mod fallback;
mod roots;
mod search;
pub use search::Stage;
#[cfg(test)]
mod tests;

use super::super::chain::modes::MAX;
use super::super::chain::{Chain, ChainState};
use super::super::setup::{Setup, State};
use super::cart_grip::exp_and_m1;
use super::{BallSpring, Point};
use coefficients::coefficients;

type C64 = Complex<f64>;

/// A root counts as real when its imaginary part is below this fraction of its size.
const REAL: f64 = 1e-10;
/// Two roots closer than this (relative) are the same root found twice.
const SAME: f64 = 1e-9;
/// A root must satisfy g(s) = 0 to this fraction of the size of g's terms.
const RESIDUAL: f64 = 1e-11;
/// The modes must reproduce a grip's start state to this fraction of its size (energy norm)...
const RECONSTRUCTION: f64 = 1e-12;
/// ...and the force to this fraction of its terms...
const FORCE_RECONSTRUCTION: f64 = 1e-10;
/// ...and the sum of the sizes of the modal terms may exceed the state's size by at most this factor
/// (the cancellation that multiplies the roots' rounding).
const CANCELLATION: f64 = 1e3;
/// A mode whose share of the bound on |F''| is below this fraction sets no step for the event search.
const NEGLIGIBLE: f64 = 1e-6;
/// A chain mode whose Φ_1j is at most this fraction of the largest leaves the first mass still: a
/// rounding of zero (a ring's mirror modes come out of the eigensolver at about 1e-16).
const UNSEEN: f64 = 1e-12;

/// One mode of the gripping ball and chain, scaled to carry the unit force.
#[derive(Clone, Debug)]
struct Mode {
    s: C64,
    /// |s|.
    rate: f64,
    /// 2 for one of a complex pair (its conjugate is implied), 1 for a real root.
    weight: f64,
    /// u of the mode, -1/(m_eff s²).
    u: C64,
    /// Q_j of the mode, Φ_1j/(s² + Ω_j²).
    q: [C64; MAX],
    /// e = u - X_1 of the mode (1/(k_b + c_b s) at the root).
    e: C64,
    /// F = k_b e + c_b s e of the mode (1 at the root).
    force: C64,
    /// w_iᵀ [[C, D], [D, 0]] w_i.
    norm: C64,
    /// The energy-norm size of the mode's state, sqrt(2 E).
    size: f64,
}

/// A flexible mode of the chain that leaves its first mass still (Φ_1j = 0 to rounding): on a ring
/// through a held body ([`super::HeldRingGrip`]), every mode the ring's mirror symmetry keeps the body
/// still in. The ball's spring neither moves it nor feels it, so it is no root of the grip's system (in
/// which it would be a root on a pole of R(s), found twice or not at all): it swings on its own,
/// Q_j'' + Ω_j² Q_j = p_j, p_j its share of the string friction's push.
#[derive(Clone, Copy, Debug)]
struct Still {
    /// Its index among the chain's slide modes.
    index: usize,
    omega: f64,
    /// Φ_fj, the frame's share of it on a free frame (0 on the wall).
    frame: f64,
    /// Its unit push, Φ_1j - Φ_fj (as [`GripModes::push_row`]'s).
    push: f64,
}

/// The rigid translation of a chain on a free frame, taken out of the grip's system.
#[derive(Clone, Copy, Debug)]
struct Translation {
    /// Its index among the chain's slide modes.
    index: usize,
    /// Φ_i0 = c = 1/sqrt(M).
    c: f64,
    /// M/(m_eff + M), r's share of u.
    ball_share: f64,
    /// m_eff/(m_eff + M), r's share of -Y.
    chain_share: f64,
}

/// The modes of the ball gripping a chain: computed once per bounce and shared by its grip phases.
#[derive(Debug)]
pub struct GripModes {
    chain: Arc<Chain>,
    /// The flexible modes (all of the chain's on the wall; all but the translation on a free frame).
    n: usize,
    kb: f64,
    cb: f64,
    /// The mass the ball's spring pulls: m_eff, or on a free frame the reduced mass μ.
    m_eff: f64,
    /// Φ_1j of the chain's flexible slide modes.
    phi1: [f64; MAX],
    /// Ω_j² of the chain's flexible slide modes.
    omega2: [f64; MAX],
    /// Which slide mode each flexible one is.
    flexible: [usize; MAX],
    /// The slide modes the ball's spring cannot see, apart from the grip's system.
    still: Vec<Still>,
    /// On a free frame: the translation, and the frame's Φ_fj over the flexible modes.
    translation: Option<Translation>,
    frame_row: [f64; MAX],
    /// The string friction's unit push on each flexible mode: Φ_1j on the wall; on a free frame
    /// Φ_1j - Φ_fj, the push on the first mass and its reaction on the frame (the pair is internal, so
    /// the translation and the centre of mass feel nothing).
    push_row: [f64; MAX],
    /// On a free frame, per grip mode, X_f - Y of the mode, Σ' Φ_fj Q_j (for X_1 - X_f).
    frame_shares: Vec<C64>,
    /// `None` where the roots could not all be found distinct: the grips then use the exponential.
    modes: Option<Vec<Mode>>,
    /// The state matrix in energy coordinates z̃ = T z, T = blockdiag(Lᵀ, D^(1/2)) with K = L Lᵀ, where
    /// |z̃|² = 2E: [[0, Lᵀ D^(-1/2)], [-D^(-1/2) L, -D^(-1/2) C D^(-1/2)]], skew but for the dashpot, so
    /// its size is that of the rates (for the Schur fallback and the exponential).
    a: DMatrix<f64>,
    /// L, the Cholesky factor of K (`None` if K is not positive definite, as for k = 0).
    lower: Option<DMatrix<f64>>,
    /// For the exponential: a step h with |Ã h|₁ <= 1 and exp(Ã h), made when a grip first needs it.
    checkpoint: OnceLock<(f64, DMatrix<f64>)>,
    /// The same for a grip pushed by string friction: the augmented matrix [[Ã, b̃], [0, 0]] of the unit
    /// push b̃, a step for it and its exponential.
    forced_checkpoint: OnceLock<(DMatrix<f64>, f64, DMatrix<f64>)>,
    /// An upper bound on the fastest rate in the grip, rad/s.
    pub fastest: f64,
}

impl GripModes {
    pub fn new(chain: Arc<Chain>, setup: &Setup, kb: f64, cb: f64) -> GripModes {
        let modes = &chain.slide;
        let frame = chain.frame_index();
        let translation = (frame > 0).then(|| {
            let index = (0..modes.n)
                .find(|&j| modes.omega[j] == 0.0)
                .expect("a chain on a free frame has its translation");
            let total: f64 = modes.mass[..modes.n].iter().sum();
            Translation {
                index,
                c: modes.shape[0][index],
                ball_share: total / (setup.m_eff + total),
                chain_share: setup.m_eff / (setup.m_eff + total),
            }
        });
        // The flexible modes the ball's spring sees, and those it cannot (Φ_1j zero to rounding).
        let moving = |j: &usize| translation.is_none_or(|tr| tr.index != *j);
        let seen = (0..modes.n)
            .filter(moving)
            .map(|j| modes.shape[0][j].abs())
            .fold(0.0, f64::max);
        let mut flexible = [0; MAX];
        let mut n = 0;
        let mut still = Vec::new();
        for j in (0..modes.n).filter(moving) {
            if modes.shape[0][j].abs() > UNSEEN * seen {
                flexible[n] = j;
                n += 1;
            } else {
                let push = modes.shape[0][j]
                    - if frame > 0 {
                        modes.shape[frame][j]
                    } else {
                        0.0
                    };
                still.push(Still {
                    index: j,
                    omega: modes.omega[j],
                    frame: if frame > 0 {
                        modes.shape[frame][j]
                    } else {
                        0.0
                    },
                    push,
                });
            }
        }
        let m_eff = match translation {
            None => setup.m_eff,
            Some(tr) => setup.m_eff * tr.ball_share,
        };
        let mut phi1 = [0.0; MAX];
        let mut omega2 = [0.0; MAX];
        let mut frame_row = [0.0; MAX];
        for (k, &j) in flexible.iter().enumerate().take(n) {
            phi1[k] = modes.shape[0][j];
            omega2[k] = modes.omega[j] * modes.omega[j];
            frame_row[k] = modes.shape[frame][j];
        }
        let mut push_row = phi1;
        if translation.is_some() {
            for k in 0..n {
                push_row[k] -= frame_row[k];
            }
        }
        let dof = n + 1;
        // K = diag(0, Ω²) + k_b g gᵀ and C = c_b g gᵀ with g = (1, -Φ_1j): e = g · y.
        let mut g = DVector::<f64>::zeros(dof);
        g[0] = 1.0;
        for j in 0..n {
            g[j + 1] = -phi1[j];
        }
        let mut stiffness = &g * g.transpose() * kb;
        for j in 0..n {
            stiffness[(j + 1, j + 1)] += omega2[j];
        }
        let lower = Cholesky::new(stiffness).map(|c| c.l());
        let mut a = DMatrix::<f64>::zeros(2 * dof, 2 * dof);
        if let Some(l) = &lower {
            let root_mass = |i: usize| if i == 0 { m_eff.sqrt() } else { 1.0 };
            for i in 0..dof {
                for j in 0..dof {
                    a[(i, dof + j)] = l[(j, i)] / root_mass(j);
                    a[(dof + i, j)] = -l[(i, j)] / root_mass(i);
                    a[(dof + i, dof + j)] = -cb * g[i] * g[j] / (root_mass(i) * root_mass(j));
                }
            }
        }
        let contact = 1.0 / m_eff + 1.0 / chain.link_mass;
        let top = still
            .iter()
            .map(|m| m.omega * m.omega)
            .fold(omega2[..n].iter().fold(0.0f64, |a, &b| a.max(b)), f64::max);
        let fastest = (top + kb * contact).sqrt() + cb * contact;
        let mut grip = GripModes {
            chain,
            n,
            kb,
            cb,
            m_eff,
            phi1,
            omega2,
            flexible,
            still,
            translation,
            frame_row,
            push_row,
            frame_shares: Vec::new(),
            modes: None,
            a,
            lower,
            checkpoint: OnceLock::new(),
            forced_checkpoint: OnceLock::new(),
            fastest,
        };
        if grip.lower.is_some() {
            grip.modes = grip.find_modes();
        }
        if grip.translation.is_some()
            && let Some(list) = &grip.modes
        {
            grip.frame_shares = list
                .iter()
                .map(|mode| (0..n).map(|k| mode.q[k] * grip.frame_row[k]).sum())
                .collect();
        }
        grip
    }

    pub fn spring(&self) -> BallSpring {
        BallSpring {
            kb: self.kb,
            cb: self.cb,
        }
    }

    pub fn chain(&self) -> &Chain {
        &self.chain
    }
}

/// A grip phase of the compliant ball on a chain.
#[derive(Clone, Debug)]
pub struct ChainGrip {
    pub modes: Arc<GripModes>,
    pub start: ChainState,
    /// z0 = (u, Q, u', Q') at the start, u = X_1 + e (on a free frame (r, Q', r', Q'') of the
    /// flexible modes).
    z0: Vec<f64>,
    /// The contact point's velocity u' at the start.
    du0: f64,
    /// On a free frame, the centre of mass's position and velocity at the start, G0 and G'.
    centre: Option<(f64, f64)>,
    /// The weighted modal coefficients of z0, when the modes reproduce it.
    coefficients: Option<Vec<C64>>,
    /// The string friction's push on the moving first mass, P = -d F_c (0 without).
    push: f64,
    /// The weighted modal coefficients β of the push's forcing b (where P != 0 and the modes reproduce
    /// it): by Duhamel's integral each mode gains β_i (e^{s_i τ} - 1)/s_i.
    beta: Option<Vec<C64>>,
    /// Without them, z̃ at the start and after every step h of the exponential, as far as asked for.
    checkpoints: Arc<Mutex<Vec<DVector<f64>>>>,
    /// Without a push, each mode's [`Shares`] of the contact's sums.
    shares: Option<Vec<Shares>>,
    /// With them on a free frame, each mode's shares of r'', X_f - Y and its two rates.
    frame_shares: Option<Vec<Shares<4>>>,
    /// Each still mode's Q and Q' at the start (`GripModes::still`).
    still: Vec<(f64, f64)>,
}

/// How many modes [`ChainGrip::at`] takes the sines of at once (small arrays, set up without a call).
const CHUNK: usize = 10;

/// Room for a grip's state (u, Q, u', Q').
const STATE: usize = 2 * MAX + 2;

/// The contact's sums u, u', e, e', e'', X_1'' (= u'' - e''), F and F', and F'' and F''' (the event
/// search's, for its Taylor polynomials): the state takes the first 8, the search the last 4.
const SUMS: usize = 10;

/// One mode's weighted coefficient c_i times what the mode carries into each of [`SUMS`] (u_i, s_i u_i,
/// e_i, s_i e_i, s_i² e_i, s_i² (u_i - e_i), F_i, s_i F_i, s_i² F_i, s_i³ F_i), real and imaginary parts
/// apart: each sum at τ is then Re Σ_i e^{s_i τ} (c_i X_i), two products a mode and sum. Taken once per
/// grip.
#[derive(Clone, Debug)]
struct Shares<const N: usize = SUMS> {
    re: [f64; N],
    im: [f64; N],
}

impl Shares {
    fn new(mode: &Mode, ci: C64) -> Shares {
        let rate = ci * mode.s;
        let sums = [
            ci * mode.u,
            rate * mode.u,
            ci * mode.e,
            rate * mode.e,
            rate * mode.s * mode.e,
            rate * mode.s * (mode.u - mode.e),
            ci * mode.force,
            rate * mode.force,
            rate * mode.s * mode.force,
            rate * mode.s * mode.s * mode.force,
        ];
        Shares {
            re: sums.map(|z| z.re),
            im: sums.map(|z| z.im),
        }
    }
}

impl Shares<4> {
    /// On a free frame, c_i times the mode's s_i² u_i (r''), and its X_f - Y (`frame`, Σ' Φ_fj Q_j)
    /// times 1, s_i and s_i².
    fn frame(mode: &Mode, ci: C64, frame: C64) -> Shares<4> {
        let rate = ci * mode.s;
        let sums = [
            rate * mode.s * mode.u,
            ci * frame,
            rate * frame,
            rate * mode.s * frame,
        ];
        Shares {
            re: sums.map(|z| z.re),
            im: sums.map(|z| z.im),
        }
    }
}

impl ChainGrip {
    /// The grip from `start` with stretch `e`, the first mass pushed by `push` (the string friction
    /// -d F_c on a first mass moving in direction d, or 0).
    pub fn new(
        modes: Arc<GripModes>,
        start: ChainState,
        e: f64,
        setup: &Setup,
        push: f64,
    ) -> ChainGrip {
        let n = modes.n;
        let slide = &modes.chain.slide;
        let (mut q, mut dq) = ([0.0; MAX], [0.0; MAX]);
        slide.project_both((&start.x, &start.v), (&mut q, &mut dq));
        let mut z0 = vec![0.0; 2 * n + 2];
        let (u0, du0) = (start.x[0] + e, start.vx - setup.r * start.omega);
        z0[0] = u0;
        z0[n + 1] = du0;
        for (k, &j) in modes.flexible.iter().enumerate().take(n) {
            (z0[1 + k], z0[n + 2 + k]) = (q[j], dq[j]);
        }
        let mut centre = None;
        if let Some(tr) = modes.translation {
            let (y, dy) = (tr.c * q[tr.index], tr.c * dq[tr.index]);
            // G = u - (M/(m_eff + M)) r.
            centre = Some((
                u0 - tr.ball_share * (u0 - y),
                du0 - tr.ball_share * (du0 - dy),
            ));
            (z0[0], z0[n + 1]) = (u0 - y, du0 - dy);
        }
        let still = modes
            .still
            .iter()
            .map(|m| (q[m.index], dq[m.index]))
            .collect();
        let mut coefficients = modes
            .modes
            .as_ref()
            .and_then(|list| coefficients(&modes, list, &z0));
        // The push P on the first mass is the forcing b = (0, 0, 0, Φ_1j P) of z' = A z + b (on a free
        // frame (Φ_1j - Φ_fj) P, with the frame's reaction); its coefficients come from the same orthogonality (and the same checks) as the state's.
        let beta = match (&modes.modes, push != 0.0 && coefficients.is_some()) {
            (Some(list), true) => {
                let mut b = vec![0.0; 2 * n + 2];
                for j in 0..n {
                    b[n + 2 + j] = modes.push_row[j] * push;
                }
                coefficients::coefficients(&modes, list, &b)
            }
            _ => None,
        };
        if push != 0.0 && beta.is_none() {
            coefficients = None;
        }
        let shares: Option<Vec<Shares>> = match (&modes.modes, &coefficients) {
            (Some(list), Some(c)) if push == 0.0 => Some(
                list.iter()
                    .zip(c)
                    .map(|(mode, &ci)| Shares::new(mode, ci))
                    .collect(),
            ),
            _ => None,
        };
        let frame_shares = match (&modes.modes, &coefficients) {
            (Some(list), Some(c)) if shares.is_some() && modes.translation.is_some() => Some(
                list.iter()
                    .zip(c)
                    .zip(&modes.frame_shares)
                    .map(|((mode, &ci), &frame)| Shares::frame(mode, ci, frame))
                    .collect(),
            ),
            _ => None,
        };
        ChainGrip {
            modes,
            start,
            z0,
            du0,
            centre,
            coefficients,
            push,
            beta,
            checkpoints: Arc::new(Mutex::new(Vec::new())),
            shares,
            frame_shares,
            still,
        }
    }

    /// Still mode `k` after `tau`: Q, Q' and Q'' of Q'' + Ω² Q = p (p = p_k P), from its start.
    #[inline]
    fn still(&self, k: usize, tau: f64) -> (f64, f64, f64) {
        let mode = &self.modes.still[k];
        let (q0, dq0) = self.still[k];
        let w = mode.omega;
        let rest = mode.push * self.push / (w * w);
        let (sin, cos) = sin_cos(w * tau);
        let swing = q0 - rest;
        let q = rest + swing * cos + dq0 / w * sin;
        let dq = dq0 * cos - swing * w * sin;
        (q, dq, -(w * w) * (q - rest))
    }

    /// A bound on the second derivative of Σ h_k Q_k' over the still modes k, and on its size: each
    /// swings at its Ω about its rest with speed at most sqrt(((Q0 - p/Ω²) Ω)² + Q0'²).
    fn still_bounds(&self, row: impl Fn(&Still) -> f64) -> (f64, f64) {
        let (mut curvature, mut size) = (0.0, 0.0);
        for (mode, &(q0, dq0)) in self.modes.still.iter().zip(&self.still) {
            let w = mode.omega;
            let swing = (q0 - mode.push * self.push / (w * w)) * w;
            let speed = row(mode).abs() * swing.hypot(dq0);
            curvature += speed * w * w;
            size += speed;
        }
        (curvature, size)
    }

    /// (u, Q, u', Q') and, if `rates`, its rate at `t` (the first 2N + 2 entries of each).
    fn propagate(&self, t: f64, rates: bool) -> ([f64; STATE], [f64; STATE]) {
        let tau = t - self.start.t;
        let g = &self.modes;
        let n = g.n;
        let len = 2 * n + 2;
        let (mut z, mut dz) = ([0.0; STATE], [0.0; STATE]);
        match (&g.modes, &self.coefficients) {
            (Some(list), Some(c)) => {
                // The positions and the rates, as slices of N + 1 (no index checks in the loops).
                let (position, rate) = z[..len].split_at_mut(n + 1);
                let (_, acceleration) = dz[..len].split_at_mut(n + 1);
                for (i, (mode, &ci)) in list.iter().zip(c).enumerate() {
                    let (a, da) = self.term(mode, ci, i, tau);
                    let q = &mode.q[..n];
                    position[0] += (a * mode.u).re;
                    rate[0] += (da * mode.u).re;
                    for ((x, v), q) in position[1..].iter_mut().zip(&mut rate[1..]).zip(q) {
                        *x += (a * q).re;
                        *v += (da * q).re;
                    }
                    if rates {
                        let dda = da * mode.s;
                        acceleration[0] += (dda * mode.u).re;
                        for (w, q) in acceleration[1..].iter_mut().zip(q) {
                            *w += (dda * q).re;
                        }
                    }
                }
                if rates {
                    dz[..=n].copy_from_slice(&z[n + 1..len]);
                }
            }
            _ if self.push != 0.0 => {
                let dof = n + 1;
                let (augmented, _, _) = g.forced_checkpoint();
                let zt = self.exponential(tau);
                let dzt = augmented * &zt;
                z[..len].copy_from_slice(&g.energy_to_state(&zt.rows(0, 2 * dof).into_owned()));
                dz[..len].copy_from_slice(&g.energy_to_state(&dzt.rows(0, 2 * dof).into_owned()));
            }
            _ => {
                let zt = self.exponential(tau);
                let dzt = &g.a * &zt;
                z[..len].copy_from_slice(&g.energy_to_state(&zt));
                dz[..len].copy_from_slice(&g.energy_to_state(&dzt));
            }
        }
        (z, dz)
    }

    /// F and F' at `t`, with F'' and F''' where the grip sums its modes by their shares of the contact's
    /// sums (on the wall without a push: four sums alone, the same bits as [`ChainGrip::at`]'s F and F';
    /// `None` otherwise), for the event search's Taylor polynomials.
    #[inline]
    pub fn force_with_higher(&self, setup: &Setup, t: f64) -> ([f64; 2], Option<(f64, f64)>) {
        self.force_keeping(setup, t, None)
    }

    /// [`ChainGrip::force_with_higher`], keeping the modes' e^{s_i τ} in `keep` where it sums the
    /// shares (so that the state at `t` needs no sine or exponential more: [`ChainGrip::at_turns`]).
    #[inline(always)]
    fn force_keeping(
        &self,
        setup: &Setup,
        t: f64,
        keep: Option<&mut Turns>,
    ) -> ([f64; 2], Option<(f64, f64)>) {
        match (&self.modes.modes, &self.coefficients, &self.shares) {
            (Some(list), Some(_), Some(shares)) => {
                let tau = t - self.start.t;
                let [f, df, ddf, dddf] = match keep {
                    Some(keep) => {
                        keep.t = t;
                        share_sums::<6, 4>(list, shares, tau, Some(&mut keep.values))
                    }
                    None => share_sums::<6, 4>(list, shares, tau, None),
                };
                ([f, df], Some((ddf, dddf)))
            }
            _ => {
                let p = self.at(setup, t);
                ([p.friction, p.friction_rate], None)
            }
        }
    }

    /// The state at `t` where [`ChainGrip::force_keeping`] kept the modes' e^{s_i τ} there: the
    /// shares' first 8 sums from them, the same bits as [`ChainGrip::at`]'s (`None` where they were
    /// kept at another time, or where the grip does not sum shares or is on a free frame).
    pub(super) fn at_turns(&self, setup: &Setup, t: f64, turns: &Turns) -> Option<Point> {
        let shares = self.shares.as_ref()?;
        (turns.t == t && t != self.start.t && self.frame_shares.is_none())
            .then(|| self.shared_point(setup, t, turned_sums::<0, 8, SUMS>(&turns.values, shares)))
    }

    /// The point at `t` from the shares' first 8 sums there (F'' and F''' are the search's): on the
    /// wall, without a push or still modes, as [`ChainGrip::at`] takes it from them.
    #[inline]
    fn shared_point(&self, setup: &Setup, t: f64, sums: [f64; 8]) -> Point {
        let [u, du, e, de, dde, a1, f, df] = sums;
        let (vx, omega) = self.ball(setup, du);
        Point {
            state: State {
                t,
                vx,
                omega,
                x: u - e,
                v: du - de,
            },
            friction: f,
            friction_rate: df,
            e,
            de,
            dde,
            slip_rate: 0.0,
            accel: a1,
            frame: (0.0, 0.0),
        }
    }

    /// The ball, the first mass, the force and the stretch at `t`.
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        let g = &self.modes;
        let tau = t - self.start.t;
        let n = g.n;
        // The contact quantities alone need only one exponential per mode.
        let framed = g.translation.is_some();
        // On a free frame also r'' and X_f - Y with its two rates (otherwise 0).
        let (du, force, dforce, e, de, dde, x1, v1, a1, ddu, (xf, dxf, ddxf)) =
            match (&g.modes, &self.coefficients) {
                (Some(list), Some(_)) if let Some(shares) = &self.shares => {
                    // The first 8 sums (F'' and F''' are the search's; as `shared_point`'s), and on
                    // a free frame the frame's 4 from the same e^{s_i τ} (1 at τ = 0).
                    let ([u, du, e, de, dde, a1, f, df], (ddu, xf, dxf, ddxf)) = match &self
                        .frame_shares
                    {
                        None => (
                            share_sums::<0, 8>(list, shares, tau, None),
                            (0.0, 0.0, 0.0, 0.0),
                        ),
                        Some(frame_shares) => {
                            let mut turns = [(1.0, 0.0); MODES];
                            let sums = share_sums::<0, 8>(list, shares, tau, Some(&mut turns));
                            let [ddu, xf, dxf, ddxf] = turned_sums::<0, 4, 4>(&turns, frame_shares);
                            (sums, (ddu, xf, dxf, ddxf))
                        }
                    };
                    (
                        du,
                        f,
                        df,
                        e,
                        de,
                        dde,
                        u - e,
                        du - de,
                        a1,
                        ddu,
                        (xf, dxf, ddxf),
                    )
                }
                (Some(list), Some(c)) => {
                    let zero = C64::new(0.0, 0.0);
                    let (mut u, mut du, mut f, mut df, mut e, mut de, mut dde, mut a1) =
                        (zero, zero, zero, zero, zero, zero, zero, zero);
                    let (mut ddu, mut xf, mut dxf, mut ddxf) = (zero, zero, zero, zero);
                    for (i, (mode, &ci)) in list.iter().zip(c).enumerate() {
                        let (a, da) = self.term(mode, ci, i, tau);
                        u += a * mode.u;
                        du += da * mode.u;
                        f += a * mode.force;
                        df += da * mode.force;
                        e += a * mode.e;
                        de += da * mode.e;
                        dde += da * mode.s * mode.e;
                        a1 += da * mode.s * (mode.u - mode.e);
                        if framed {
                            ddu += da * mode.s * mode.u;
                            xf += a * g.frame_shares[i];
                            dxf += da * g.frame_shares[i];
                            ddxf += da * mode.s * g.frame_shares[i];
                        }
                    }
                    let (u, du, e, de) = (u.re, du.re, e.re, de.re);
                    let frame = (xf.re, dxf.re, ddxf.re);
                    (
                        du,
                        f.re,
                        df.re,
                        e,
                        de,
                        dde.re,
                        u - e,
                        du - de,
                        a1.re,
                        ddu.re,
                        frame,
                    )
                }
                _ => {
                    let (z, dz) = self.propagate(t, true);
                    let x1: f64 = (0..n).map(|j| g.phi1[j] * z[j + 1]).sum();
                    let v1: f64 = (0..n).map(|j| g.phi1[j] * z[n + 2 + j]).sum();
                    let a1: f64 = (0..n).map(|j| g.phi1[j] * dz[n + 2 + j]).sum();
                    let xf: f64 = (0..n).map(|j| g.frame_row[j] * z[j + 1]).sum();
                    let dxf: f64 = (0..n).map(|j| g.frame_row[j] * z[n + 2 + j]).sum();
                    let ddxf: f64 = (0..n).map(|j| g.frame_row[j] * dz[n + 2 + j]).sum();
                    let (e, de, dde) = (z[0] - x1, z[n + 1] - v1, dz[n + 1] - a1);
                    let force = g.kb * e + g.cb * de;
                    (
                        z[n + 1],
                        force,
                        g.kb * de + g.cb * dde,
                        e,
                        de,
                        dde,
                        x1,
                        v1,
                        a1,
                        dz[n + 1],
                        (xf, dxf, ddxf),
                    )
                }
            };
        // The still modes move the frame alone.
        let (xf, dxf, ddxf) = if framed {
            (0..g.still.len()).fold((xf, dxf, ddxf), |(x, v, a), k| {
                let (q, dq, ddq) = self.still(k, tau);
                let row = g.still[k].frame;
                (x + row * q, v + row * dq, a + row * ddq)
            })
        } else {
            (xf, dxf, ddxf)
        };
        // On a free frame: X_1 - X_f = (X_1 - Y) - (X_f - Y), and the translation's rate
        // Y' = G' - (m_eff/(m_eff + M)) r' and Y'' added to the first mass's and the frame's.
        let (du, x1, v1, a1, frame) = match (g.translation, self.centre) {
            (Some(tr), Some((_, dg))) => {
                let (dy, ddy) = (dg - tr.chain_share * du, -tr.chain_share * ddu);
                (
                    dg + tr.ball_share * du,
                    x1 - xf,
                    v1 + dg - tr.chain_share * du,
                    a1 - tr.chain_share * ddu,
                    (dxf + dy, ddxf + ddy),
                )
            }
            _ => (du, x1, v1, a1, (0.0, 0.0)),
        };
        let (vx, omega) = self.ball(setup, du);
        Point {
            state: State {
                t,
                vx,
                omega,
                x: x1,
                v: v1,
            },
            friction: force,
            friction_rate: dforce,
            e,
            de,
            dde,
            slip_rate: 0.0,
            accel: a1,
            frame,
        }
    }

    /// A mode's weighted amplitude and its rate after `tau`: c_i e^{s_i τ}, plus the push's
    /// β_i (e^{s_i τ} - 1)/s_i (rate (c_i s_i + β_i) e^{s_i τ}) on a pushed first mass.
    #[inline]
    fn term(&self, mode: &Mode, ci: C64, i: usize, tau: f64) -> (C64, C64) {
        match &self.beta {
            Some(beta) => {
                let (grow, grow_m1) = exp_and_m1(mode.s * tau);
                let b = beta[i];
                (ci * grow + b * grow_m1 / mode.s, (ci * mode.s + b) * grow)
            }
            None => {
                let a = ci * exp(mode.s * tau);
                (a, a * mode.s)
            }
        }
    }

    /// The ball and the whole chain at `t`, and the stretch there.
    /// The ball's (v_x, omega) once its contact point moves at `du`: m_eff (u' - u0') = -∫F dt.
    fn ball(&self, setup: &Setup, du: f64) -> (f64, f64) {
        let impulse = -setup.m_eff * (du - self.du0);
        (
            self.start.vx - impulse / setup.m,
            self.start.omega + impulse * setup.r / setup.inertia,
        )
    }

    /// The ball and the whole chain at `t`.
    pub fn full(&self, setup: &Setup, t: f64) -> ChainState {
        let (z, _) = self.propagate(t, false);
        let n = self.modes.n;
        let slide = &self.modes.chain.slide;
        let tau = t - self.start.t;
        let (mut q, mut dq) = ([0.0; MAX], [0.0; MAX]);
        for (k, &j) in self.modes.flexible.iter().enumerate().take(n) {
            (q[j], dq[j]) = (z[1 + k], z[n + 2 + k]);
        }
        let du = match (self.modes.translation, self.centre) {
            (Some(tr), Some((g0, dg))) => {
                // Y = G - (m_eff/(m_eff + M)) r, and Q_0 = Y/c.
                let y = g0 + dg * tau - tr.chain_share * z[0];
                let dy = dg - tr.chain_share * z[n + 1];
                (q[tr.index], dq[tr.index]) = (y / tr.c, dy / tr.c);
                dg + tr.ball_share * z[n + 1]
            }
            _ => z[n + 1],
        };
        for (k, mode) in self.modes.still.iter().enumerate() {
            let (q_k, dq_k, _) = self.still(k, tau);
            (q[mode.index], dq[mode.index]) = (q_k, dq_k);
        }
        let (vx, omega) = self.ball(setup, du);
        ChainState {
            t,
            vx,
            omega,
            x: slide.expand(&q),
            v: slide.expand(&dq),
            frame: self.start.frame,
        }
    }
}

/// Room for the grip's modes, one per root pair or real root.
const MODES: usize = 2 * MAX + 2;

/// Each mode's e^{s_i τ} (real and imaginary parts) at `t`, as the event search last took them.
pub(super) struct Turns {
    t: f64,
    values: [(f64, f64); MODES],
}

impl Turns {
    /// None taken yet.
    pub(super) fn new() -> Turns {
        Turns {
            t: f64::NAN,
            values: [(0.0, 0.0); MODES],
        }
    }
}

/// `K` of the contact's sums ([`SUMS`]) from number `FROM` at `tau`, Re Σ_i e^{s_i τ} (c_i X_i):
/// e^{s_i τ} of every mode, CHUNK at a time, the sines and cosines together, e^{Re s_i τ} inlined;
/// each kept in `keep`, if given, where τ is not 0.
#[inline(always)]
fn share_sums<const FROM: usize, const K: usize>(
    list: &[Mode],
    shares: &[Shares],
    tau: f64,
    mut keep: Option<&mut [(f64, f64); MODES]>,
) -> [f64; K] {
    let mut sums = [0.0; K];
    if tau == 0.0 {
        // At the grip's start every e^{s_i τ} is 1: the sums of the shares' real parts, to the same
        // bits, without the modes' sines, cosines and exponentials (the search's first evaluation).
        for share in shares {
            for (sum, a) in sums.iter_mut().zip(&share.re[FROM..]) {
                *sum += a;
            }
        }
        return sums;
    }
    for (chunk, (modes, shares)) in list.chunks(CHUNK).zip(shares.chunks(CHUNK)).enumerate() {
        let count = modes.len();
        let mut angle = [0.0; CHUNK];
        for (a, mode) in angle.iter_mut().zip(modes) {
            *a = mode.s.im * tau;
        }
        let (mut sin, mut cos) = ([0.0; CHUNK], [0.0; CHUNK]);
        sin_cos_each(&angle[..count], &mut sin[..count], &mut cos[..count]);
        for (i, (mode, share)) in modes.iter().zip(shares).enumerate() {
            let size = fast_exp(mode.s.re * tau);
            let (re, im) = (size * cos[i], size * sin[i]);
            if let Some(keep) = keep.as_deref_mut() {
                keep[chunk * CHUNK + i] = (re, im);
            }
            let (real, imaginary) = (&share.re[FROM..], &share.im[FROM..]);
            for ((sum, a), b) in sums.iter_mut().zip(real).zip(imaginary) {
                *sum += re * a - im * b;
            }
        }
    }
    sums
}

/// [`share_sums`] from the modes' e^{s_i τ} it kept (τ not 0): the same products in the same order,
/// so the same bits.
#[inline]
fn turned_sums<const FROM: usize, const K: usize, const N: usize>(
    turns: &[(f64, f64); MODES],
    shares: &[Shares<N>],
) -> [f64; K] {
    let mut sums = [0.0; K];
    for (&(re, im), share) in turns.iter().zip(shares) {
        let (real, imaginary) = (&share.re[FROM..], &share.im[FROM..]);
        for ((sum, a), b) in sums.iter_mut().zip(real).zip(imaginary) {
            *sum += re * a - im * b;
        }
    }
    sums
}

/// e^z, with one `sin_cos` (num_complex calls `sin` and `cos` apart).
#[inline]
fn exp(z: C64) -> C64 {
    let (sin, cos) = sin_cos(z.im);
    let size = z.re.exp();
    C64::new(size * cos, size * sin)
}
