//! The grip of a compliant ball on the single cart: the cart (X, V) and the stretch (e, e') form a
//! linear system z' = A z, not proportionally damped; z(t) = exp(A (t - t0)) z0, evaluated as a sum of
//! its complex modes (eigenvalues polished on the characteristic polynomial) where they reproduce the
//! matrix exponential, and as the matrix exponential itself where they do not (near-double roots, a free
//! cart's double zero).
//!
//! With string friction (Sec. IV's enhancement) the cart either moves against the constant force
//! P = -dir F_c, z' = A z + b, solved by Duhamel's integral z = exp(A τ) z0 + ∫_0^τ exp(A s) b ds (on a
//! free cart, by the particular solution in which ball and cart accelerate together), or is held still:
//! the stretch alone is then a damped oscillator against a still surface, an infinitely heavy cart.

use std::cell::RefCell;

use nalgebra::{Complex, Matrix4, Matrix5, RowVector4, Vector4, Vector5};

use super::super::memo::{Slot, reuse};
use super::super::trig::sin_cos;
use super::Point;
use crate::model::contact::Cart;
use crate::model::params::Params;
use crate::model::setup::{Setup, State};

/// The grip's event functions are computed through a matrix exponential: their rounding floor is this
/// many times `ROUNDING` times the bound on the force from the phase's energy (itself a generous
/// bound on the terms F is summed from).
pub(super) const EXP_ROUNDING: f64 = 1.0;

/// How closely (relative, in the energy norm) the grip's modes must reproduce the matrix exponential to
/// be used in its place.
const MODAL_CHECK: f64 = 1e-10;

/// The constants of the compliant ball.
#[derive(Clone, Copy, Debug)]
pub struct Compliance {
    /// k_b, N/m.
    pub kb: f64,
    /// c_b = 2 zeta sqrt(k_b m_eff), N s/m.
    pub cb: f64,
    /// The grip's state matrix for z = (X, V, e, e').
    a: Matrix4<f64>,
    /// S for the balanced state S z, S = diag(s_X, sqrt(M), sqrt(k_b), sqrt(m_eff)) with s_X = sqrt(k),
    /// or sqrt(M) times the contact's rate for a free cart: the exponential of S A S⁻¹ keeps its
    /// rounding on the scale of the rates, not of the largest entry of A.
    scale: Vector4<f64>,
    /// S A S⁻¹.
    balanced: Matrix4<f64>,
    /// On a free cart (k = 0), the grip in closed form.
    free: Option<Free>,
    /// On a cart held by string friction, the stretch alone in closed form.
    held: Free,
    /// M, kg.
    cart_mass: f64,
    /// An upper bound on the fastest frequency in the grip, rad/s.
    pub fastest: f64,
    /// The grip's modes, when they are distinct: a sum of exponentials is much cheaper than the matrix
    /// exponential. Each grip phase checks them against the matrix exponential before using them.
    modes: Option<Modes>,
}

/// The eigenvalues s_i of the grip's matrix, its eigenvectors (columns), and their inverse.
#[derive(Clone, Copy, Debug)]
struct Modes {
    s: Vector4<Complex<f64>>,
    v: Matrix4<Complex<f64>>,
    v_inv: Matrix4<Complex<f64>>,
    /// The modes a real state is summed over, each with its partner: the system is real, so a complex
    /// eigenvalue's conjugate (exactly, eigenvector and all) carries the conjugate term, and the pair's
    /// sum is the real part of one term with the two coefficients folded into it ([`Modes::fold`]).
    terms: [(usize, Option<usize>); 4],
    /// How many of `terms` are used.
    count: usize,
}

impl Modes {
    /// For an eigenvalue s, z = (X, s X, e, s e) with (M s² + k) X = (k_b + c_b s) e.
    fn new(a: &Matrix4<f64>, kb: f64, cb: f64, big_m: f64, k: f64, me: f64) -> Option<Self> {
        // The eigenvalues from the Schur form are accurate to rounding of |A| (~ s²); Newton's method
        // on the characteristic polynomial
        // p(s) = (M s² + k)(m_eff M s² + (k_b + c_b s)(M + m_eff)) - m_eff k (k_b + c_b s)
        // brings them to rounding of s.
        let mut s = a.complex_eigenvalues();
        let total = big_m + me;
        for si in s.iter_mut() {
            for _ in 0..3 {
                let x = *si;
                let spring = x * x * big_m + k;
                let contact = x * x * (me * big_m) + (x * cb + kb) * total;
                let p = spring * contact - (x * cb + kb) * (me * k);
                let dp = x * (2.0 * big_m) * contact
                    + spring * (x * (2.0 * me * big_m) + cb * total)
                    - cb * me * k;
                if dp.norm() == 0.0 {
                    break;
                }
                let step = p / dp;
                if !(step.re.is_finite() && step.im.is_finite()) {
                    break;
                }
                *si = x - step;
            }
        }
        let mut v = Matrix4::<Complex<f64>>::zeros();
        for (i, &si) in s.iter().enumerate() {
            let x = Complex::new(kb, 0.0) + si * cb;
            let e = si * si * big_m + k;
            let norm =
                (x.norm_sqr() + (si * x).norm_sqr() + e.norm_sqr() + (si * e).norm_sqr()).sqrt();
            if norm == 0.0 || !norm.is_finite() {
                return None;
            }
            let column = Vector4::new(x, si * x, e, si * e) / Complex::new(norm, 0.0);
            v.set_column(i, &column);
        }
        let v_inv = v.try_inverse()?;
        let (mut terms, mut count, mut carried) = ([(0, None); 4], 0, [false; 4]);
        for i in 0..4 {
            if carried[i] {
                continue;
            }
            let conjugate =
                (i + 1..4).find(|&j| !carried[j] && s[i].im != 0.0 && s[j] == s[i].conj());
            if let Some(j) = conjugate {
                carried[j] = true;
            }
            terms[count] = (i, conjugate);
            count += 1;
        }
        v_inv
            .iter()
            .all(|c| c.re.is_finite() && c.im.is_finite())
            .then_some(Modes {
                s,
                v,
                v_inv,
                terms,
                count,
            })
    }

    /// The coefficients `c` of a real state (or forcing) folded onto the modes summed over: a pair's
    /// terms Re(v c_i e^{s τ}) + Re(v̄ c_j e^{s̄ τ}) = Re(v (c_i + c̄_j) e^{s τ}).
    fn fold(&self, c: &Vector4<Complex<f64>>) -> Vector4<Complex<f64>> {
        let mut folded = Vector4::zeros();
        for &(i, partner) in &self.terms[..self.count] {
            folded[i] = partner.map_or(c[i], |j| c[i] + c[j].conj());
        }
        folded
    }

    /// z and z' after `tau` from the folded modal coefficients `c`.
    #[inline]
    fn at(&self, c: &Vector4<Complex<f64>>, tau: f64) -> (Vector4<f64>, Vector4<f64>) {
        let mut z = Vector4::zeros();
        let mut dz = Vector4::zeros();
        for &(i, _) in &self.terms[..self.count] {
            let w = c[i] * (self.s[i] * tau).exp();
            let dw = w * self.s[i];
            for j in 0..4 {
                let vj = self.v[(j, i)];
                z[j] += (vj * w).re;
                dz[j] += (vj * dw).re;
            }
        }
        (z, dz)
    }

    /// z and z' after `tau` from the folded modal coefficients `c`, with the constant forcing whose
    /// folded modal coefficients are `beta`: each mode gains β_i (e^{s_i τ} - 1)/s_i.
    #[inline]
    fn at_forced(
        &self,
        c: &Vector4<Complex<f64>>,
        beta: &Vector4<Complex<f64>>,
        tau: f64,
    ) -> (Vector4<f64>, Vector4<f64>) {
        let mut z = Vector4::zeros();
        let mut dz = Vector4::zeros();
        for &(i, _) in &self.terms[..self.count] {
            let s = self.s[i];
            let (grow, grow_m1) = exp_and_m1(s * tau);
            let integral = if s == Complex::new(0.0, 0.0) {
                Complex::new(tau, 0.0)
            } else {
                grow_m1 / s
            };
            let w = c[i] * grow + beta[i] * integral;
            let dw = (c[i] * s + beta[i]) * grow;
            for j in 0..4 {
                let vj = self.v[(j, i)];
                z[j] += (vj * w).re;
                dz[j] += (vj * dw).re;
            }
        }
        (z, dz)
    }
}

impl Compliance {
    /// exp(A τ) z, through the balanced matrix.
    fn exp(&self, tau: f64, z: &Vector4<f64>) -> Vector4<f64> {
        let balanced = (self.balanced * tau).exp() * z.component_mul(&self.scale);
        balanced.component_div(&self.scale)
    }

    /// The forcing of a push P on the cart, b = P (0, 1/M, 0, -1/M).
    fn forcing(&self, push: f64) -> Vector4<f64> {
        Vector4::new(0.0, push, 0.0, -push) / self.cart_mass
    }

    /// exp(A τ) z + ∫_0^τ exp(A s) b ds for the push P, from the exponential of the balanced augmented
    /// matrix [[S A S⁻¹, S b / P], [0, 0]] applied to (S z, P).
    fn exp_forced(&self, tau: f64, z: &Vector4<f64>, push: f64) -> Vector4<f64> {
        self.reduce(&(self.exp_step(tau, push) * self.augment(z, push)))
    }

    /// The exponential of the balanced augmented matrix over `tau`: it carries (S z, P) to
    /// (S z(τ), P); without a push, that of S A S⁻¹ alone, the push's column unused.
    fn exp_step(&self, tau: f64, push: f64) -> Matrix5<f64> {
        if push == 0.0 {
            let exp = (self.balanced * tau).exp();
            Matrix5::from_fn(|i, j| if i < 4 && j < 4 { exp[(i, j)] } else { 0.0 })
        } else {
            let unit = self.forcing(1.0).component_mul(&self.scale);
            let augmented = Matrix5::from_fn(|i, j| match (i, j) {
                (4, _) => 0.0,
                (_, 4) => unit[i],
                _ => self.balanced[(i, j)],
            });
            (augmented * tau).exp()
        }
    }

    /// The balanced augmented state (S z, P).
    fn augment(&self, z: &Vector4<f64>, push: f64) -> Vector5<f64> {
        let scaled = z.component_mul(&self.scale);
        Vector5::new(scaled[0], scaled[1], scaled[2], scaled[3], push)
    }

    /// z from the balanced augmented state.
    fn reduce(&self, balanced: &Vector5<f64>) -> Vector4<f64> {
        Vector4::new(balanced[0], balanced[1], balanced[2], balanced[3]).component_div(&self.scale)
    }

    /// The constants for `params` on `setup`: those of the last bounce on this thread when they were
    /// built from the same inputs (a sweep over the angle, the speed or the spin keeps them), else built
    /// (their eigenvalues by a Schur decomposition, polished, and the eigenvectors' inverse).
    pub fn new(params: &Params, setup: &Setup) -> Self {
        thread_local! {
            static LAST: Slot<[u64; 5], Compliance> = const { RefCell::new(None) };
        }
        let key = [
            params.ball_stiffness,
            params.ball_damping,
            setup.m_eff,
            setup.cart_mass,
            setup.k,
        ]
        .map(f64::to_bits);
        reuse(&LAST, key, || Self::build(params, setup))
    }

    fn build(params: &Params, setup: &Setup) -> Self {
        let kb = params.ball_stiffness;
        let cb = 2.0 * params.ball_damping * (kb * setup.m_eff).sqrt();
        let (big_m, k, me) = (setup.cart_mass, setup.k, setup.m_eff);
        let both = 1.0 / me + 1.0 / big_m;
        #[rustfmt::skip]
        let a = Matrix4::new(
            0.0, 1.0, 0.0, 0.0,
            -k / big_m, 0.0, kb / big_m, cb / big_m,
            0.0, 0.0, 0.0, 1.0,
            k / big_m, 0.0, -kb * both, -cb * both,
        );
        let fastest = (kb * both + k / big_m).sqrt() + cb * both;
        let modes = Modes::new(&a, kb, cb, big_m, k, me);
        let contact = (kb * both).sqrt();
        let s_x = if k > 0.0 {
            k.sqrt()
        } else {
            big_m.sqrt() * contact
        };
        let scale = Vector4::new(s_x, big_m.sqrt(), kb.sqrt(), me.sqrt());
        let balanced = Matrix4::from_fn(|i, j| scale[i] * a[(i, j)] / scale[j]);
        let free = (k == 0.0).then(|| Free::new(cb * both, kb * both, big_m * both, big_m));
        // A held cart is an infinitely heavy one: m_eff e'' = -(k_b e + c_b e'), and X, V stay put.
        let held = Free::new(cb / me, kb / me, f64::INFINITY, f64::INFINITY);
        Compliance {
            kb,
            cb,
            a,
            scale,
            balanced,
            free,
            held,
            cart_mass: big_m,
            fastest,
            modes,
        }
    }
}

/// The grip on a free cart (k = 0) in closed form. The stretch alone is a damped oscillator,
/// e'' + c e' + κ e = 0 with c = c_b (1/m_eff + 1/M) and κ = k_b (1/m_eff + 1/M), and momentum gives the
/// cart: V = V0 - (e' - e0') / (M (1/m_eff + 1/M)).
#[derive(Clone, Copy, Debug)]
struct Free {
    /// c/2.
    a: f64,
    /// a² - κ (negative: underdamped).
    d2: f64,
    c: f64,
    kappa: f64,
    /// M (1/m_eff + 1/M).
    share: f64,
    /// M.
    big_m: f64,
}

impl Free {
    /// The oscillator e'' + c e' + κ e = 0 on a cart whose share is `share` = M (1/m_eff + 1/M) and whose
    /// mass is `big_m` (both infinite for a held cart).
    fn new(c: f64, kappa: f64, share: f64, big_m: f64) -> Self {
        Free {
            a: 0.5 * c,
            d2: 0.25 * c * c - kappa,
            c,
            kappa,
            share,
            big_m,
        }
    }

    /// (ψ, ψ', φ, φ') at τ: the solutions with (ψ, ψ') = (1, -a) and (φ, φ') = (0, 1) at 0, so that
    /// e = e0 ψ + (e0' + a e0) φ. Overdamped, through the slow root -κ/(a + d) and expm1, so that
    /// nothing overflows or cancels.
    fn basis(&self, tau: f64) -> (f64, f64, f64, f64) {
        let (a, d2) = (self.a, self.d2);
        let (psi, phi) = if d2 < 0.0 {
            let w = (-d2).sqrt();
            let (s, c) = sin_cos(w * tau);
            let decay = (-a * tau).exp();
            (decay * c, decay * s / w)
        } else {
            let d = d2.sqrt();
            let slow = (-self.kappa / (a + d) * tau).exp();
            let m = (-2.0 * d * tau).exp_m1();
            let phi = if d > 0.0 {
                slow * -m / (2.0 * d)
            } else {
                slow * tau
            };
            (slow * (2.0 + m) / 2.0, phi)
        };
        (psi, d2 * phi - a * psi, phi, psi - a * phi)
    }

    /// A bound on |φ| over τ >= 0 (|ψ| <= 1).
    fn phi_max(&self) -> f64 {
        let (a, d2) = (self.a, self.d2);
        let e = std::f64::consts::E;
        if d2 < 0.0 {
            let w = (-d2).sqrt();
            if a > 0.0 {
                (1.0 / w).min(1.0 / (e * a))
            } else {
                1.0 / w
            }
        } else {
            let d = d2.sqrt();
            let slow = self.kappa / (a + d);
            let by_d = if d > 0.0 {
                1.0 / (2.0 * d)
            } else {
                f64::INFINITY
            };
            by_d.min(1.0 / (e * slow))
        }
    }

    /// z = (X, V, e, e') and z' at τ from z0.
    fn at(&self, z0: &Vector4<f64>, tau: f64, kb: f64, cb: f64) -> [Vector4<f64>; 2] {
        let (x0, v0, e0, de0) = (z0[0], z0[1], z0[2], z0[3]);
        let (psi, dpsi, phi, dphi) = self.basis(tau);
        let lead = de0 + self.a * e0;
        let e = e0 * psi + lead * phi;
        let de = e0 * dpsi + lead * dphi;
        let dde = -self.c * de - self.kappa * e;
        let v = v0 - (de - de0) / self.share;
        let x = x0 + v0 * tau - (e - e0 - de0 * tau) / self.share;
        let force = kb * e + cb * de;
        [
            Vector4::new(x, v, e, de),
            Vector4::new(v, force / self.big_m, de, dde),
        ]
    }

    /// A bound on |F''| over the phase and on the size of F's terms k_b |e| + c_b |e'|. Both F and e
    /// solve the oscillator, so y(τ) = y0 ψ + (y0' + a y0) φ bounds each by |y0| + |y0' + a y0| φ_max.
    fn bounds(&self, z0: &Vector4<f64>, kb: f64, cb: f64) -> (f64, f64) {
        let (a, c, kappa) = (self.a, self.c, self.kappa);
        let reach = |y: f64, dy: f64| y.abs() + (dy + a * y).abs() * self.phi_max();
        let (e, de) = (z0[2], z0[3]);
        let dde = -c * de - kappa * e;
        let f = kb * e + cb * de;
        let df = kb * de + cb * dde;
        let ddf = -c * df - kappa * f;
        let dddf = -c * ddf - kappa * df;
        (reach(ddf, dddf), kb * reach(e, de) + cb * reach(de, dde))
    }

    /// A bound on the cart's |V''| over the phase and on the size of the terms V is summed from besides
    /// V0 (which the caller adds): V = V0 - (e' - e0')/share, so V'' = -e'''/share, and e''' solves the
    /// oscillator too.
    fn cart_bounds(&self, z0: &Vector4<f64>) -> (f64, f64) {
        let (a, c, kappa) = (self.a, self.c, self.kappa);
        let reach = |y: f64, dy: f64| y.abs() + (dy + a * y).abs() * self.phi_max();
        let (e, de) = (z0[2], z0[3]);
        let dde = -c * de - kappa * e;
        let ddde = -c * dde - kappa * de;
        let dddde = -c * ddde - kappa * dde;
        (
            reach(ddde, dddde) / self.share,
            (de.abs() + reach(de, dde)) / self.share,
        )
    }
}

/// On a free cart (k = 0) moving against the constant string friction P, the particular solution in
/// which ball and cart accelerate together: z_p(τ) = (a τ²/2, a τ, e_p, 0), a = P/(M + m_eff), the ball's
/// spring carrying F = -m_eff a, e_p = F/k_b. (With a spring, the equilibrium P/k would serve, but for a
/// heavy cart on a soft spring it lies far from the motion and its cancellation would cost digits: the
/// push then enters through Duhamel's integral instead, see [`Drive::Pushed`].)
#[derive(Clone, Copy, Debug)]
struct Drift {
    accel: f64,
    e: f64,
}

impl Drift {
    fn new(setup: &Setup, kb: f64, push: f64) -> Self {
        let accel = push / (setup.cart_mass + setup.m_eff);
        Drift {
            accel,
            e: -setup.m_eff * accel / kb,
        }
    }

    /// z_p and z_p' after τ.
    fn at(&self, tau: f64) -> (Vector4<f64>, Vector4<f64>) {
        let a = self.accel;
        (
            Vector4::new(0.5 * a * tau * tau, a * tau, self.e, 0.0),
            Vector4::new(a * tau, a, 0.0, 0.0),
        )
    }
}

/// What the cart does under a grip.
#[derive(Clone, Copy, Debug)]
enum Drive {
    /// Moving without string friction: z' = A z.
    Unforced,
    /// A free cart moving against the string friction: z = z_p + z_h, z_h' = A z_h.
    Drift(Drift),
    /// A cart on a spring moving against the string friction P: z' = A z + b, b = P (0, 1/M, 0, -1/M)
    /// (the cart feels P, and e'' = u'' - V''), so z(τ) = exp(A τ) z0 + ∫_0^τ exp(A s) b ds: in the modes,
    /// each term gains β_i (e^{s_i τ} - 1)/s_i with β = V⁻¹ b; through the exponential of the augmented
    /// matrix [[A, b], [0, 0]] otherwise.
    Pushed { push: f64 },
    /// Held by string friction: X and V stay put, the stretch is the held oscillator.
    Held,
}

/// (e^x, e^x - 1) for complex x, the second without cancellation for small |x|, from one `sin_cos`:
/// Re(e^x - 1) = (e^a - 1) cos b - (1 - cos b), with 1 - cos b = sin² b / (1 + cos b) where cos b > 0.
#[inline]
pub(super) fn exp_and_m1(x: Complex<f64>) -> (Complex<f64>, Complex<f64>) {
    let (sin, cos) = sin_cos(x.im);
    let size = x.re.exp();
    let versine = if cos > 0.0 {
        sin * sin / (1.0 + cos)
    } else {
        1.0 - cos
    };
    (
        Complex::new(size * cos, size * sin),
        Complex::new(x.re.exp_m1() * cos - versine, size * sin),
    )
}

/// The coefficients of a state (or a forcing) in the grip's modes.
type Coefficients = Vector4<Complex<f64>>;

/// A grip phase of the compliant ball.
#[derive(Clone, Copy, Debug)]
pub struct CompliantGrip {
    pub start: State,
    /// (X, V, e, e') at the start, less the particular solution there on a drifting free cart: the state
    /// the unforced system (or, pushed, the forced one) carries from the start.
    z0: Vector4<f64>,
    pub compliance: Compliance,
    drive: Drive,
    /// The modal coefficients of z0 and of the push's forcing, when the modes reproduce the matrix
    /// exponential.
    coefficients: Option<(Coefficients, Coefficients)>,
    /// The same folded onto the modes summed over ([`Modes::fold`]), zero when unused.
    folded: (Coefficients, Coefficients),
}

impl CompliantGrip {
    /// The grip from `start` with stretch `e`, the cart doing `cart` (held, or moving against its string
    /// friction, if any).
    pub(super) fn new(
        compliance: Compliance,
        start: State,
        e: f64,
        setup: &Setup,
        cart: Cart,
    ) -> Self {
        let de = setup.slip(&start);
        let push = cart.friction(setup);
        let drive = match cart {
            Cart::Stuck => Drive::Held,
            Cart::Moving(_) if push == 0.0 => Drive::Unforced,
            Cart::Moving(_) if setup.k == 0.0 => {
                Drive::Drift(Drift::new(setup, compliance.kb, push))
            }
            Cart::Moving(_) => Drive::Pushed { push },
        };
        let mut z0 = Vector4::new(start.x, start.v, e, de);
        if let Drive::Drift(d) = &drive {
            z0 -= d.at(0.0).0;
        }
        let mut grip = CompliantGrip {
            start,
            z0,
            compliance,
            drive,
            coefficients: None,
            folded: (Coefficients::zeros(), Coefficients::zeros()),
        };
        // The modes are used only where they reproduce the matrix exponential, in the energy norm, to
        // MODAL_CHECK at the middle and the end of the rest of the contact (near-double roots, as for a
        // critically damped ball on a very heavy cart, fail it). A free cart and a held one have their
        // closed forms.
        if let (Some(modes), None, false) = (
            &compliance.modes,
            &compliance.free,
            matches!(drive, Drive::Held),
        ) {
            let z0 = grip.z0.map(|x| Complex::new(x, 0.0));
            let c = modes.v_inv * z0;
            let push = grip.push();
            let beta = modes.v_inv * compliance.forcing(push).map(|x| Complex::new(x, 0.0));
            let (folded_c, folded_beta) = (modes.fold(&c), modes.fold(&beta));
            let remaining = setup.duration - start.t;
            let size = grip.reach(setup, remaining);
            // One matrix exponential, over half the rest, carries the start to the middle and the
            // middle to the end.
            let half = compliance.exp_step(0.5 * remaining, push);
            let mut exact = compliance.augment(&grip.z0, push);
            let agrees = [0.0, 0.5 * remaining, remaining].iter().all(|&tau| {
                if tau > 0.0 {
                    exact = half * exact;
                }
                let (modal, _) = if push == 0.0 {
                    modes.at(&folded_c, tau)
                } else {
                    modes.at_forced(&folded_c, &folded_beta, tau)
                };
                let error = modal - compliance.reduce(&exact);
                grip.energy_norm(setup, &error) <= MODAL_CHECK * size
            });
            if agrees && size > 0.0 {
                grip.coefficients = Some((c, beta));
                grip.folded = (folded_c, folded_beta);
            }
        }
        grip
    }

    /// The push on the cart carried by Duhamel's integral (0 otherwise).
    fn push(&self) -> f64 {
        match self.drive {
            Drive::Pushed { push } => push,
            _ => 0.0,
        }
    }

    /// z and z' at `t`.
    #[inline]
    fn propagate(&self, t: f64) -> (Vector4<f64>, Vector4<f64>) {
        let tau = t - self.start.t;
        let c = &self.compliance;
        // A drift is only made on a free cart (k = 0), which always has its closed form.
        match (&self.drive, &c.free) {
            (Drive::Held, _) => {
                let [z, dz] = c.held.at(&self.z0, tau, c.kb, c.cb);
                (z, dz)
            }
            (Drive::Drift(d), Some(free)) => {
                let [z, dz] = free.at(&self.z0, tau, c.kb, c.cb);
                let (zp, dzp) = d.at(tau);
                (z + zp, dz + dzp)
            }
            (Drive::Unforced, Some(free)) => {
                let [z, dz] = free.at(&self.z0, tau, c.kb, c.cb);
                (z, dz)
            }
            (Drive::Pushed { push }, _) => match (&c.modes, &self.coefficients) {
                (Some(modes), Some(_)) => {
                    let (coefficients, beta) = &self.folded;
                    modes.at_forced(coefficients, beta, tau)
                }
                _ => {
                    let z = c.exp_forced(tau, &self.z0, *push);
                    (z, c.a * z + c.forcing(*push))
                }
            },
            (Drive::Unforced | Drive::Drift(_), None) => match (&c.modes, &self.coefficients) {
                (Some(modes), Some(_)) => modes.at(&self.folded.0, tau),
                _ => {
                    let z = c.exp(tau, &self.z0);
                    (z, c.a * z)
                }
            },
        }
    }

    /// sqrt(2 E) of a state z.
    fn energy_norm(&self, setup: &Setup, z: &Vector4<f64>) -> f64 {
        (setup.k * z[0] * z[0]
            + setup.cart_mass * z[1] * z[1]
            + self.compliance.kb * z[2] * z[2]
            + setup.m_eff * (z[3] + z[1]).powi(2))
        .sqrt()
    }

    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        let c = &self.compliance;
        let s0 = &self.start;
        let (z, dz) = self.propagate(t);
        let (x, v, e, de) = (z[0], z[1], z[2], z[3]);
        // m_eff (u' - u0') = -∫F dt, u' = e' + V (a drift has no V or e' at the start).
        let impulse = -setup.m_eff * ((de + v) - (self.z0[3] + self.z0[1]));
        let state = State {
            t,
            vx: s0.vx - impulse / setup.m,
            omega: s0.omega + impulse * setup.r / setup.inertia,
            x,
            v,
        };
        Point {
            state,
            friction: c.kb * e + c.cb * de,
            friction_rate: c.kb * de + c.cb * dz[3],
            e,
            de,
            dde: dz[3],
            slip_rate: 0.0,
            accel: dz[1],
            frame: (0.0, 0.0),
        }
    }

    /// A bound on the energy-norm size sqrt(2 E) of the state carried from the start over the next
    /// `tau`, E = k X²/2 + M V²/2 + k_b e²/2 + m_eff u'²/2. The dashpot only lowers E; a push P on the
    /// cart raises it at most at |P V| <= |P| sqrt(2 E / M), so sqrt(2 E) grows at most at |P|/sqrt(M).
    fn reach(&self, setup: &Setup, tau: f64) -> f64 {
        self.energy_norm(setup, &self.z0) + self.push().abs() * tau / setup.cart_mass.sqrt()
    }

    /// |g · z| <= |g T⁻¹| sqrt(2E) for a row g in z-coordinates (Cauchy-Schwarz in the energy norm),
    /// over the rest of the contact.
    fn bound(&self, setup: &Setup, g: RowVector4<f64>) -> f64 {
        let kb = self.compliance.kb;
        let gx = if setup.k > 0.0 {
            g[0] / setup.k.sqrt()
        } else {
            0.0
        };
        let norm = (gx * gx
            + ((g[1] - g[3]) / setup.cart_mass.sqrt()).powi(2)
            + (g[2] / kb.sqrt()).powi(2)
            + (g[3] / setup.m_eff.sqrt()).powi(2))
        .sqrt();
        norm * self.reach(setup, setup.duration - self.start.t)
    }

    /// A bound on |g z''| over the phase: z'' = A² z + A b, bounded in the energy norm; pushed and in
    /// its modes also by the modes' amplitudes, z'' = Σ s_i (c_i s_i + β_i) e^{s_i τ} v_i (|e^{s_i τ}| <= 1
    /// for a passive system), the smaller taken.
    fn second(&self, setup: &Setup, g: RowVector4<f64>) -> f64 {
        let c = &self.compliance;
        let energy = self.bound(setup, g * c.a * c.a) + (g * c.a * c.forcing(self.push()))[0].abs();
        let modal = match (&self.drive, &c.modes, &self.coefficients) {
            (Drive::Pushed { .. }, Some(modes), Some((coefficients, beta))) => {
                let remaining = setup.duration - self.start.t;
                (0..4)
                    .map(|i| {
                        let s = modes.s[i];
                        let row: Complex<f64> = (0..4).map(|j| modes.v[(j, i)] * g[j]).sum();
                        let growth = (s.re.max(0.0) * remaining).exp();
                        row.norm() * s.norm() * (coefficients[i] * s + beta[i]).norm() * growth
                    })
                    .sum()
            }
            _ => f64::INFINITY,
        };
        energy.min(modal)
    }

    /// A bound on |F''| over the phase, and the size of F (for the rounding floor). A drift's force,
    /// k_b e_p, is constant.
    pub(super) fn force_bounds(&self, setup: &Setup) -> (f64, f64) {
        let c = &self.compliance;
        match (&self.drive, &c.free) {
            (Drive::Held, _) => c.held.bounds(&self.z0, c.kb, c.cb),
            (Drive::Drift(d), Some(free)) => {
                let (curvature, size) = free.bounds(&self.z0, c.kb, c.cb);
                (curvature, size + c.kb * d.e.abs())
            }
            (_, Some(free)) => free.bounds(&self.z0, c.kb, c.cb),
            _ => (
                self.second(setup, RowVector4::new(0.0, 0.0, c.kb, c.cb)),
                self.bound(setup, RowVector4::new(0.0, 0.0, c.kb, 0.0))
                    + self.bound(setup, RowVector4::new(0.0, 0.0, 0.0, c.cb)),
            ),
        }
    }

    /// For the moving cart's stopping: a bound on |V''| over the phase, and the size of the terms V is
    /// summed from (for the rounding floor). A drift's V is linear.
    pub(super) fn cart_bounds(&self, setup: &Setup) -> (f64, f64) {
        let c = &self.compliance;
        let (curvature, size) = match &c.free {
            Some(free) => free.cart_bounds(&self.z0),
            None => {
                let v = RowVector4::new(0.0, 1.0, 0.0, 0.0);
                (self.second(setup, v), self.bound(setup, v))
            }
        };
        let drift = match &self.drive {
            Drive::Drift(d) => d.accel.abs() * (setup.duration - self.start.t),
            _ => 0.0,
        };
        (curvature, self.start.v.abs() + size + drift)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The free cart's closed form against the exponential of its (balanced) state matrix, under-,
    /// critically and overdamped, with its bounds holding.
    #[test]
    fn the_free_grip_is_the_exponential() {
        for damping in [0.0, 0.3, 1.0, 1.0 + 1e-9, 3.0, 40.0] {
            let params = Params {
                stiffness: 0.0,
                ball_stiffness: 1e6,
                ball_damping: damping,
                ..Params::default()
            };
            let setup = Setup::new(&params);
            let compliance = Compliance::new(&params, &setup);
            let free = compliance.free.expect("a free cart");
            let z0 = Vector4::new(1e-3, 2.0, 3e-4, -1.5);
            let (curvature, _) = free.bounds(&z0, compliance.kb, compliance.cb);
            for tau in [0.0, 1e-6, 1e-4, 1e-3, 4e-3] {
                let [z, dz] = free.at(&z0, tau, compliance.kb, compliance.cb);
                let exact = compliance.exp(tau, &z0);
                for i in 0..4 {
                    let scale = z0.abs().max() + exact.abs().max();
                    assert!(
                        (z[i] - exact[i]).abs() <= 1e-11 * scale,
                        "zeta {damping} tau {tau}"
                    );
                }
                assert!(((compliance.a * z) - dz).abs().max() <= 1e-9 * dz.abs().max().max(1.0));
                let h = 1e-9;
                let rate = |t: f64| {
                    let [_, dz] = free.at(&z0, t, compliance.kb, compliance.cb);
                    compliance.kb * dz[2] + compliance.cb * dz[3]
                };
                let f2 = (rate(tau + h) - rate(tau)) / h;
                assert!(
                    f2.abs() <= curvature * (1.0 + 1e-6),
                    "zeta {damping}: |F''| bound"
                );
            }
        }
    }

    /// A grip on a cart moving against string friction solves z' = A z + b (its modes against the
    /// exponential of the augmented matrix, and both against the equation by central differences), from a
    /// heavy cart on a soft spring (whose equilibrium P/k lies metres away) to a light stiff one and a
    /// free one; a held cart stays put while the stretch rings down.
    #[test]
    fn a_pushed_grip_solves_the_forced_system_and_a_held_one_stays_put() {
        let mut modal = 0;
        let start = State {
            t: 1e-3,
            vx: 3.0,
            omega: 40.0,
            x: 2e-3,
            v: 1.5,
        };
        for (cart_mass, stiffness, damping) in [
            (1709.0, 1.0, 1.0),
            (0.01, 15e3, 0.3),
            (0.05, 4e4, 0.0),
            (0.01, 0.0, 0.5),
        ] {
            let params = Params {
                cart_mass,
                stiffness,
                cart_friction: 20.0,
                ball_stiffness: 4e5,
                ball_damping: damping,
                ..Params::default()
            };
            let setup = Setup::new(&params);
            let compliance = Compliance::new(&params, &setup);
            let grip = CompliantGrip::new(compliance, start, 1e-4, &setup, Cart::Moving(1));
            let push = Cart::Moving(1).friction(&setup);
            let b = compliance.forcing(push);
            let scale = grip.energy_norm(&setup, &grip.z0) + 1.0;
            for tau in [1e-6, 1e-4, 1e-3, 3e-3] {
                let t = start.t + tau;
                let (z, dz) = grip.propagate(t);
                if let (Drive::Pushed { push }, Some(_)) = (&grip.drive, &grip.coefficients) {
                    modal += 1;
                    let exact = compliance.exp_forced(tau, &grip.z0, *push);
                    let error = grip.energy_norm(&setup, &(z - exact));
                    assert!(
                        error <= 1e-12 * scale,
                        "M {cart_mass}: modes off by {error}"
                    );
                }
                let rate = compliance.a * z + b;
                let h = 1e-8;
                let numerical = (grip.propagate(t + h).0 - grip.propagate(t - h).0) / (2.0 * h);
                for i in 0..4 {
                    let size = rate[i].abs() + dz[i].abs() + 1.0;
                    assert!(
                        (dz[i] - rate[i]).abs() <= 1e-9 * size,
                        "M {cart_mass} z'[{i}]"
                    );
                    assert!(
                        (numerical[i] - rate[i]).abs() <= 1e-5 * size,
                        "M {cart_mass} z'[{i}]: {} vs {}",
                        numerical[i],
                        rate[i]
                    );
                }
            }
            let held = CompliantGrip::new(
                compliance,
                State { v: 0.0, ..start },
                1e-4,
                &setup,
                Cart::Stuck,
            );
            let mut previous = f64::INFINITY;
            for tau in [0.0, 1e-4, 1e-3, 3e-3] {
                let p = held.at(&setup, start.t + tau);
                assert_eq!((p.state.x, p.state.v), (start.x, 0.0));
                // m_eff e'' = -F while the patch is held.
                assert!(
                    (setup.m_eff * p.dde + p.friction).abs() <= 1e-9 * p.friction.abs().max(1.0)
                );
                let energy = compliance.kb * p.e * p.e + setup.m_eff * p.de * p.de;
                assert!(
                    energy <= previous * (1.0 + 1e-12),
                    "the held stretch gains energy"
                );
                previous = energy;
            }
        }
        assert!(modal >= 8, "the modes were checked {modal} times");
    }
}
