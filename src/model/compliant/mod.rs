//! A tangentially compliant ball (issue 6, part 3), on the single cart.
//!
//! The ball's contact region is a massless tangential spring k_b with a dashpot c_b between the ball's
//! contact point (coordinate u, velocity u' = v_x - r omega, effective mass m_eff) and the contact patch
//! (position p). With the stretch e = u - p the force on the ball, positive backward, is
//! F = k_b e + c_b e'; the massless patch passes it on to the cart, which feels +F (Eq. (3)).
//!
//! - Slide: the patch slides on the cart and F = dir mu N(t). The ball and the cart move exactly as for
//!   a rigid ball ([`Slide`]); the stretch follows c_b e' + k_b e = F(t) (e = F/k_b without damping),
//!   solved in closed form. The patch slips at p' - V = (v_x - r omega - V) - e'; the slide ends when
//!   that slip reaches zero, and the patch then always grips (a reversed slide would need the opposite
//!   force, which the continuous stretch and the slip's sign exclude).
//! - Grip: the patch moves with the cart. The cart (X, V) and the stretch (e, e') form a linear system
//!   z' = A z without forcing, not proportionally damped; z(t) = exp(A (t - t0)) z0, evaluated as a sum of
//!   its complex modes (eigenvalues polished on the characteristic polynomial) where they reproduce the
//!   matrix exponential, and as the matrix exponential itself where they do not (near-double roots, a
//!   free cart's double zero). The grip breaks when |F| reaches mu N, into a slide the
//!   way F points.
//!
//! Chatter: an undamped stiff ball may switch many times; every phase advances time and the solver stops
//! after [`MAX_TRANSITIONS`] with [`SolveError::TooManyPhases`].

use nalgebra::{Complex, Matrix4, RowVector4, Vector4};

use super::bounce::{
    MAX_RADIANS, MAX_TRANSITIONS, Motion, Phase, PhaseKind, ROLLING, ROUNDING, SolveError, finish,
};
use super::cart::Cart;
use super::events::first_rise;
use super::params::Params;
use super::quadrature::integrate;
use super::setup::{Setup, State};
use super::slide::Slide;
use crate::model::Bounce;

/// The grip's event functions are computed through a matrix exponential: their rounding floor is this
/// many times [`ROUNDING`] times the bound on the force from the phase's energy (itself a generous
/// bound on the terms F is summed from).
const EXP_ROUNDING: f64 = 1.0;

/// After this many decay times 1/lambda the stretch's transient has fallen by e^-40 (4e-18): the slide's
/// event search and quadrature use steps and panels on the transient's scale before, and on the cart's
/// after (a lightly damped ball has lambda = sqrt(k_b/m_eff)/(2 zeta) huge, and a whole phase on its
/// scale would never end).
const SETTLED: f64 = 40.0;

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
        v_inv
            .iter()
            .all(|c| c.re.is_finite() && c.im.is_finite())
            .then_some(Modes { s, v, v_inv })
    }

    /// z and z' after `tau` from the modal coefficients `c`.
    #[inline]
    fn at(&self, c: &Vector4<Complex<f64>>, tau: f64) -> (Vector4<f64>, Vector4<f64>) {
        let mut z = Vector4::zeros();
        let mut dz = Vector4::zeros();
        for i in 0..4 {
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
}

impl Compliance {
    pub fn new(params: &Params, setup: &Setup) -> Self {
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
        Compliance {
            kb,
            cb,
            a,
            fastest,
            modes,
        }
    }

    /// The decay rate k_b / c_b of the stretch while sliding (infinite without damping).
    fn lambda(&self) -> f64 {
        self.kb / self.cb
    }
}

/// The stretch of the ball's spring during a slide: e = C e^{-lambda tau} + P(t), with the particular
/// response P(t) = a (lambda sin wt - w cos wt), a = dir mu N0 / (c_b (lambda² + w²)); without damping
/// e = F/k_b.
#[derive(Clone, Copy, Debug)]
pub struct Stretch {
    t0: f64,
    /// C, m (0 without damping).
    transient: f64,
    /// a, m (dir mu N0 / k_b without damping).
    amplitude: f64,
    lambda: f64,
    damped: bool,
}

impl Stretch {
    fn new(c: &Compliance, setup: &Setup, dir: f64, t0: f64, e0: f64) -> Self {
        let force = dir * setup.mu * setup.n0;
        if c.cb > 0.0 {
            let lambda = c.lambda();
            let w = setup.w;
            let amplitude = force / (c.cb * (lambda * lambda + w * w));
            let (s, co) = (w * t0).sin_cos();
            let p0 = amplitude * (lambda * s - w * co);
            Stretch {
                t0,
                transient: e0 - p0,
                amplitude,
                lambda,
                damped: true,
            }
        } else {
            Stretch {
                t0,
                transient: 0.0,
                amplitude: force / c.kb,
                lambda: f64::INFINITY,
                damped: false,
            }
        }
    }

    /// (e, e', e'') at `t`.
    #[inline]
    fn at(&self, w: f64, t: f64) -> (f64, f64, f64) {
        let (s, co) = (w * t).sin_cos();
        if self.damped {
            let l = self.lambda;
            let decay = self.transient * (-l * (t - self.t0)).exp();
            let p = self.amplitude * (l * s - w * co);
            let dp = self.amplitude * w * (l * co + w * s);
            (decay + p, -l * decay + dp, l * l * decay - w * w * p)
        } else {
            let s = s.max(0.0);
            let e = self.amplitude * s;
            (e, self.amplitude * w * co, -w * w * e)
        }
    }

    /// Where the transient has died out (t0 without damping).
    fn settled(&self) -> f64 {
        if self.damped {
            self.t0 + SETTLED / self.lambda
        } else {
            self.t0
        }
    }

    /// A bound on |e'''| from `from` (at or after t0) on.
    fn third(&self, w: f64, from: f64) -> f64 {
        if self.damped {
            let l = self.lambda;
            let decay = (-l * (from - self.t0)).exp();
            l * l * l * self.transient.abs() * decay + self.amplitude.abs() * w.powi(3) * l.hypot(w)
        } else {
            self.amplitude.abs() * w.powi(3)
        }
    }

    /// A bound on |e'| from t0 on.
    fn speed(&self, w: f64) -> f64 {
        if self.damped {
            self.lambda * self.transient.abs() + self.amplitude.abs() * w * self.lambda.hypot(w)
        } else {
            self.amplitude.abs() * w
        }
    }
}

/// A sliding phase of the compliant ball.
#[derive(Clone, Copy, Debug)]
pub struct CompliantSlide {
    pub slide: Slide,
    pub stretch: Stretch,
    pub compliance: Compliance,
}

/// A grip phase of the compliant ball.
#[derive(Clone, Copy, Debug)]
pub struct CompliantGrip {
    pub start: State,
    /// (X, V, e, e') at the start.
    z0: Vector4<f64>,
    pub compliance: Compliance,
    /// The modal coefficients of z0, when the modes reproduce the matrix exponential.
    coefficients: Option<Vector4<Complex<f64>>>,
}

/// A phase of the compliant ball.
#[derive(Clone, Copy, Debug)]
pub enum CompliantMotion {
    Slide(CompliantSlide),
    Grip(CompliantGrip),
}

/// Everything at one instant of a compliant phase.
#[derive(Clone, Copy, Debug)]
pub struct Point {
    pub state: State,
    /// The force on the ball, positive backward, N.
    pub friction: f64,
    /// Its rate, N/s.
    pub friction_rate: f64,
    /// The stretch e, m, its rate and second derivative.
    pub e: f64,
    pub de: f64,
    pub dde: f64,
}

impl CompliantGrip {
    fn new(compliance: Compliance, start: State, e: f64, setup: &Setup) -> Self {
        let de = setup.slip(&start);
        let mut grip = CompliantGrip {
            start,
            z0: Vector4::new(start.x, start.v, e, de),
            compliance,
            coefficients: None,
        };
        // The modes are used only where they reproduce the matrix exponential, in the energy norm, to
        // MODAL_CHECK at the middle and the end of the rest of the contact (near-double roots, as for a
        // critically damped ball on a very heavy cart, or a free cart's double zero, fail it).
        if let Some(modes) = &compliance.modes {
            let z0 = grip.z0.map(|x| Complex::new(x, 0.0));
            let c = modes.v_inv * z0;
            let size = grip.size(setup);
            let remaining = setup.duration - start.t;
            let agrees = [0.0, 0.5 * remaining, remaining].iter().all(|&tau| {
                let exact = if tau == 0.0 {
                    grip.z0
                } else {
                    (compliance.a * tau).exp() * grip.z0
                };
                let (modal, _) = modes.at(&c, tau);
                grip.energy_norm(setup, &(modal - exact)) <= MODAL_CHECK * size
            });
            if agrees && size > 0.0 {
                grip.coefficients = Some(c);
            }
        }
        grip
    }

    /// z and z' at `t`.
    #[inline]
    fn propagate(&self, t: f64) -> (Vector4<f64>, Vector4<f64>) {
        let tau = t - self.start.t;
        match (&self.compliance.modes, &self.coefficients) {
            (Some(modes), Some(c)) => modes.at(c, tau),
            _ => {
                let z = (self.compliance.a * tau).exp() * self.z0;
                (z, self.compliance.a * z)
            }
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
        // m_eff (u' - u0') = -∫F dt, u' = e' + V.
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
        }
    }

    /// The energy-norm size of the start state, sqrt(2 E) with E = k X²/2 + M V²/2 + k_b e²/2 +
    /// m_eff u'²/2, which the dashpot can only lower.
    fn size(&self, setup: &Setup) -> f64 {
        self.energy_norm(setup, &self.z0)
    }

    /// |g · z| <= |g T⁻¹| sqrt(2E) for a row g in z-coordinates (Cauchy-Schwarz in the energy norm).
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
        norm * self.size(setup)
    }

    /// A bound on |F''| over the phase, and the size of F (for the rounding floor).
    fn force_bounds(&self, setup: &Setup) -> (f64, f64) {
        let c = &self.compliance;
        let g = RowVector4::new(0.0, 0.0, c.kb, c.cb);
        (
            self.bound(setup, g * c.a * c.a),
            self.bound(setup, RowVector4::new(0.0, 0.0, c.kb, 0.0))
                + self.bound(setup, RowVector4::new(0.0, 0.0, 0.0, c.cb)),
        )
    }
}

impl CompliantSlide {
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        let (state, friction) = self.slide.evaluate(setup, t);
        let (e, de, dde) = self.stretch.at(setup.w, t);
        Point {
            state,
            friction,
            friction_rate: self.slide.dir * setup.mu * setup.n0 * setup.w * (setup.w * t).cos(),
            e,
            de,
            dde,
        }
    }

    /// The patch's slip on the cart, (v_x - r omega - V) - e', and its rate.
    #[inline]
    fn patch_slip(&self, setup: &Setup, p: &Point) -> (f64, f64) {
        (
            setup.slip(&p.state) - p.de,
            self.slide.slip_rate(setup, &p.state, p.friction) - p.dde,
        )
    }
}

impl CompliantMotion {
    #[inline]
    pub fn at(&self, setup: &Setup, t: f64) -> Point {
        match self {
            CompliantMotion::Slide(s) => s.at(setup, t),
            CompliantMotion::Grip(g) => g.at(setup, t),
        }
    }

    /// The slip of the patch on the cart (0 in a grip).
    pub fn patch_slip(&self, setup: &Setup, t: f64) -> f64 {
        match self {
            CompliantMotion::Slide(s) => s.patch_slip(setup, &s.at(setup, t)).0,
            CompliantMotion::Grip(_) => 0.0,
        }
    }

    pub fn initial(&self) -> State {
        match self {
            CompliantMotion::Slide(s) => s.slide.start,
            CompliantMotion::Grip(g) => g.start,
        }
    }

    pub fn compliance(&self) -> &Compliance {
        match self {
            CompliantMotion::Slide(s) => &s.compliance,
            CompliantMotion::Grip(g) => &g.compliance,
        }
    }

    /// The fastest rate in the phase, rad/s (for quadrature panels).
    pub fn fastest(&self, setup: &Setup) -> f64 {
        match self {
            CompliantMotion::Slide(s) => {
                let l = if s.stretch.damped {
                    s.stretch.lambda
                } else {
                    0.0
                };
                l.max(setup.omega_slide)
            }
            CompliantMotion::Grip(g) => g.compliance.fastest,
        }
    }

    /// ∫ f over [start, end] by Gauss-Legendre, on panels of the transient's scale until it has died
    /// out and of the cart's after.
    pub fn integrate(&self, setup: &Setup, f: impl Fn(f64) -> f64, start: f64, end: f64) -> f64 {
        let w = setup.w;
        match self {
            CompliantMotion::Slide(s) => {
                let split = s.stretch.settled().clamp(start, end);
                let fine = 2.0 / self.fastest(setup).max(w);
                let coarse = 2.0 / setup.omega_slide.max(w);
                integrate(&f, start, split, fine) + integrate(&f, split, end, coarse)
            }
            CompliantMotion::Grip(g) => {
                integrate(&f, start, end, 2.0 / g.compliance.fastest.max(w))
            }
        }
    }
}

/// Solves one bounce of a compliant ball on the single cart (no string friction).
pub fn solve_compliant(params: &Params) -> Result<Bounce, SolveError> {
    if params.chain > 1.0 {
        return Err(SolveError::ChainCompliantBall {
            chain: params.chain as usize,
        });
    }
    if params.cart_friction > 0.0 {
        return Err(SolveError::StringFrictionCompliantBall);
    }
    let setup = Setup::new(params);
    let compliance = Compliance::new(params, &setup);
    let radians = setup.omega_slide.max(setup.omega_grip) * setup.duration;
    if radians > MAX_RADIANS {
        return Err(SolveError::TooFast { radians });
    }
    let ball_radians = compliance.fastest * setup.duration;
    if ball_radians > MAX_RADIANS {
        return Err(SolveError::BallTooFast {
            radians: ball_radians,
        });
    }
    let end = setup.duration;
    let (w, mu, n0) = (setup.w, setup.mu, setup.n0);
    let mut state = setup.initial(params.spin);
    let mut e = 0.0;
    let incoming = setup.vx1.abs() + setup.r * params.spin.abs();
    let slip0 = setup.slip(&state);
    // How the contact starts: rolling grips; with a dashpot the patch takes the whole slip at once;
    // without, the spring's rate k_b slip0 must beat the friction limit's rate mu N0 w.
    let mut slide_dir = if slip0.abs() <= ROLLING * incoming
        || (compliance.cb == 0.0 && compliance.kb * slip0.abs() <= mu * n0 * w)
    {
        None
    } else {
        Some(slip0.signum())
    };
    let mut from_zero = false;
    let mut phases = Vec::with_capacity(8);
    for _ in 0..MAX_TRANSITIONS {
        let t0 = state.t;
        let last = std::cell::Cell::new(None::<Point>);
        let speeds = incoming + state.vx.abs() + setup.r * state.omega.abs() + state.v.abs();
        let (motion, event) = match slide_dir {
            Some(dir) => {
                let slide = CompliantSlide {
                    slide: Slide::new(&setup, state, dir, Cart::Moving(1)),
                    stretch: Stretch::new(&compliance, &setup, dir, t0, e),
                    compliance,
                };
                // After a grip broke, the patch starts from rest on the cart (with a dashpot) or with
                // the jump of e' (without): a start slip against `dir` is rounding, and counts as zero,
                // so rounding can never fake a crossing at the start.
                let start_slip = slide.patch_slip(&setup, &slide.at(&setup, t0)).0;
                let offset = if from_zero && dir * start_slip < 0.0 {
                    start_slip
                } else {
                    0.0
                };
                let f = |t: f64| {
                    let p = slide.at(&setup, t);
                    last.set(Some(p));
                    let (slip, rate) = slide.patch_slip(&setup, &p);
                    [(-dir * (slip - offset), -dir * rate)]
                };
                let (slip_curvature, _) = slide.slide.curvature(&setup);
                let noise = ROUNDING * (speeds + slide.stretch.speed(w));
                // While the stretch's transient lasts, on its scale; after, on the cart's.
                let split = slide.stretch.settled().clamp(t0, end);
                let early = if slide.stretch.damped {
                    let curvature = slip_curvature + slide.stretch.third(w, t0);
                    let step = setup.event_step(setup.omega_slide.max(slide.stretch.lambda));
                    first_rise(f, t0, split, step, [curvature], [noise])
                } else {
                    None
                };
                let event = early
                    .or_else(|| {
                        let curvature = slip_curvature + slide.stretch.third(w, split);
                        let step = setup.event_step(setup.omega_slide);
                        first_rise(f, split, end, step, [curvature], [noise])
                    })
                    .map(|(t, _)| (t, 0.0));
                (CompliantMotion::Slide(slide), event)
            }
            None => {
                let grip = CompliantGrip::new(compliance, state, e, &setup);
                let f = |t: f64| {
                    let p = grip.at(&setup, t);
                    last.set(Some(p));
                    setup.grip_margins(t, p.friction, p.friction_rate)
                };
                let (force_curvature, force_size) = grip.force_bounds(&setup);
                let curvature = force_curvature + mu * n0 * w * w;
                let noise = ROUNDING * (mu * n0 + EXP_ROUNDING * force_size);
                let step = setup.event_step(compliance.fastest);
                let event = first_rise(f, t0, end, step, [curvature; 2], [noise; 2])
                    .map(|(t, branch)| (t, if branch == 0 { 1.0 } else { -1.0 }));
                (CompliantMotion::Grip(grip), event)
            }
        };
        // A transition within rounding of the end changes nothing.
        let event = event.filter(|&(t, _)| t < end * (1.0 - 1e-13));
        let t1 = event.map_or(end, |(t, _)| t);
        let point = match last.get() {
            Some(p) if p.state.t == t1 => p,
            _ => motion.at(&setup, t1),
        };
        state = point.state;
        e = point.e;
        if t1 > t0 {
            phases.push(Phase {
                kind: if slide_dir.is_some() {
                    PhaseKind::Slide
                } else {
                    PhaseKind::Grip
                },
                slip_sign: slide_dir.map_or(0, |d| d as i8),
                cart: Cart::Moving(1),
                start: t0,
                end: t1,
                motion: Motion::Compliant(Box::new(motion)),
            });
        }
        let Some((_, next)) = event else {
            return Ok(finish(params, setup, phases, state));
        };
        // A slide ends in a grip; a grip breaks into a slide the way the force points.
        slide_dir = if slide_dir.is_some() {
            None
        } else {
            Some(next)
        };
        from_zero = true;
    }
    Err(SolveError::TooManyPhases)
}
