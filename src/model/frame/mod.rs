//! The rigid ball on the single cart whose spring is tied to a free frame (issue 23): along the surface
//! the frame is a free mass M_t, so
//!
//! M x1'' = F - k (x1 - x_f),   M_t x_f'' = k (x1 - x_f)
//!
//! (Cross 2010, Eq. (3), with the wall replaced by the frame). Each phase is solved in closed form in two
//! coordinates: the spring's stretch y = x1 - x_f, an oscillator of the reduced mass, and the momentum
//! along the surface P of cart and frame (with the gripping ball's m_eff), which only the friction changes
//! (the frame's rigid-body mode, polynomial in t between the impulses of F). A clamped frame is the
//! paper's model, solved by [`super::cart`]; as M_t grows this one approaches it.
//!
//! - Slide: F = dir mu N(t) on the ball (Eqs. (1), (2)) and on the cart: y'' + Ω² y = F/M with
//!   Ω² = k (1/M + 1/M_t), P' = F.
//! - Grip: the ball's contact point moves with the cart (Eq. (4)); the ball's m_eff rides on it, so
//!   y'' + Ω_g² y = 0 with Ω_g² = k (1/(M + m_eff) + 1/M_t), P constant, and the static friction is
//!   F_s = -m_eff x1'' = m_eff k y/(M + m_eff) (Eq. (5) with y for X).
//!
//! String friction F_c (Sec. IV's enhancement) acts between the cart and the frame its strings cross:
//! -d F_c on the cart and +d F_c on the frame while the cart moves relative to the frame in direction d.
//! It is internal, so P is as above, and it only shifts the stretch's centre: with
//! z = y + d F_c/k, z'' + Ω² z = F/M sliding (the same with Ω_g and no drive gripping), since
//! d F_c (1/M + 1/M_t) = Ω² d F_c/k. The moving phase also ends when y' reaches zero. Held (stuck), the
//! cart and the frame move as one body: y is constant, a sliding ball's friction accelerates both at
//! F/(M + M_t) while the string friction holds the cart with M_t F/(M + M_t) - k y, and the phase also
//! ends when that reaches ±F_c; a rolling ball on a held cart needs no friction and all coast.
//!
//! Transitions follow the paper's rules ([`transition::next_on`], the cart's spring force k y, the
//! ball's friction's share M_t/(M + M_t) on the held cart), located by [`first_rise`] on the exact
//! expressions: without string friction a detuned slide's slip and a grip's margins written once per
//! phase (`sums.rs`), else the state at each probe. The cart's displacement reported is the spring's
//! stretch y, relative to the frame; its velocity is the cart's own (the slip is measured against it).
//! A compliant ball's patch slides on the moving cart by this model's slide (`sliding.rs`).

#[cfg(test)]
mod bounds;
mod sliding;
mod sums;

use super::contact::{Ball, Cart, Cause, Contact, Found, Mode, PhaseMotion, ROLLING, ROUNDING};
use super::error::{MAX_RADIANS, SolveError};
use super::events::{WithNear, first_rise, first_rise_predicted};
use super::oscillator::{detuned, forced, free_given};
use super::params::Params;
use super::probe::Probe;
use super::quadrature::integrate;
use super::recent::Recent;
use super::setup::{Setup, State};
use super::transition::{self, Touched};
use super::trig::{sin_cos, sin_cos2};
pub use sliding::{SlideSums, Sliding};
use sums::{Angles, SlipSums, force_sums};

/// The ball and the cart (`x` the spring's stretch y, `v` the cart's velocity), and the frame's velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameState {
    pub s: State,
    /// The frame's velocity along the surface, m/s.
    pub vf: f64,
}

/// One phase on the free frame: a slide (`dir` ±1) or a grip (`dir` 0), the cart moving relative to
/// the frame or held to it.
#[derive(Clone, Copy, Debug)]
pub struct FrameMotion {
    pub start: FrameState,
    pub dir: f64,
    /// The cart held to the frame by string friction.
    held: bool,
    /// The stretch's centre moved by the string friction on a moving cart: z = y + `string` with
    /// `string` = d F_c/k (0 held or without string friction).
    string: f64,
    sin_wt0: f64,
    cos_wt0: f64,
    /// Ω (sliding) or Ω_g (gripping), rad/s.
    omega: f64,
    /// The cart's moving mass: M sliding, M + m_eff gripping.
    cart: f64,
    /// The frame's mass M_t.
    frame: f64,
    /// The momentum along the surface of the cart (with m_eff gripping) and the frame at the start.
    p0: f64,
    /// The cart's velocity at the start as the closed form gives it (the grip's impulse on the ball is
    /// measured from it, so that it is exactly zero at the start).
    v1_start: f64,
    /// Sliding away from resonance: the particular response's amplitude F0 / (M (Ω² - w²)), which
    /// [`detuned`] scales with no trigonometry beyond the free swing's; `None` near resonance, where
    /// [`forced`] is exact (the single cart's `Slide` makes the same choice).
    amplitude: Option<f64>,
}

/// The detuned form is used while the particular response's speed A w is at most this many times the
/// speeds at the start of the phase (the single cart's criterion).
const DETUNED_GAIN: f64 = 16.0;

/// Everything at one instant of a phase.
#[derive(Clone, Copy, Debug)]
struct Point {
    state: FrameState,
    /// The friction on the ball, positive backward.
    friction: f64,
    /// Its rate (gripping).
    friction_rate: f64,
    /// The cart's acceleration.
    accel: f64,
}

impl FrameMotion {
    fn new(
        setup: &Setup,
        frame: &FramedCart,
        start: FrameState,
        dir: f64,
        cart_mode: Cart,
    ) -> Self {
        // The first phase starts at t = 0, where sin_cos gives exactly (0, 1).
        let (sin_wt0, cos_wt0) = if start.s.t == 0.0 {
            (0.0, 1.0)
        } else {
            sin_cos(setup.w * start.s.t)
        };
        let (omega, cart) = if dir == 0.0 {
            (frame.omega_grip, setup.cart_mass + setup.m_eff)
        } else {
            (frame.omega_slide, setup.cart_mass)
        };
        // Without a spring there is no string friction here (refused in `FramedCart::new`), and no
        // stretch's centre to move.
        let string = if setup.k > 0.0 {
            -cart_mode.friction(setup) / setup.k
        } else {
            0.0
        };
        let mut motion = FrameMotion {
            start,
            dir,
            held: cart_mode == Cart::Stuck,
            string,
            sin_wt0,
            cos_wt0,
            omega,
            cart,
            frame: frame.mass,
            p0: cart * start.s.v + frame.mass * start.vf,
            v1_start: start.s.v,
            amplitude: None,
        };
        if dir != 0.0 && !motion.held {
            let w = setup.w;
            let amplitude = dir * setup.peak_friction() / (cart * (omega * omega - w * w));
            let s0 = &start.s;
            let speeds = s0.vx.abs() + setup.r * s0.omega.abs() + s0.v.abs() + start.vf.abs();
            motion.amplitude =
                ((amplitude * w).abs() <= DETUNED_GAIN * speeds).then_some(amplitude);
        }
        if !motion.held {
            motion.v1_start = motion.velocities(motion.p0, start.s.v - start.vf).0;
        }
        motion
    }

    /// The ball's impulse ∫ F dt since the start of a slide, F0 (cos w t0 - cos w t)/w (Eqs. (1), (2)),
    /// the friction F and its rate F0 w cos(w t), given sin(w τ) and cos(w τ) (w t = w t0 + w τ).
    #[inline]
    fn slide_impulse(&self, setup: &Setup, (sin_w_tau, cos_w_tau): (f64, f64)) -> [f64; 3] {
        let force_amplitude = self.dir * setup.peak_friction();
        let sin_wt = self.sin_wt0 * cos_w_tau + self.cos_wt0 * sin_w_tau;
        let cos_wt = self.cos_wt0 * cos_w_tau - self.sin_wt0 * sin_w_tau;
        let impulse = force_amplitude
            * (self.cos_wt0 * (1.0 - cos_w_tau) + self.sin_wt0 * sin_w_tau)
            / setup.w;
        [
            impulse,
            force_amplitude * sin_wt.max(0.0),
            force_amplitude * setup.w * cos_wt,
        ]
    }

    /// The cart held to the frame at `t`: the stretch stays, and cart and frame move as one body of
    /// mass M + M_t, pushed by a sliding ball's friction (a rolling ball's is zero).
    #[inline]
    fn held_at(&self, setup: &Setup, t: f64) -> Point {
        let s0 = &self.start.s;
        if self.dir == 0.0 {
            let state = FrameState {
                s: State { t, ..*s0 },
                vf: s0.v,
            };
            return Point {
                state,
                friction: 0.0,
                friction_rate: 0.0,
                accel: 0.0,
            };
        }
        let tau = t - s0.t;
        let w_tau = if tau == 0.0 {
            (0.0, 1.0)
        } else {
            sin_cos(setup.w * tau)
        };
        let [impulse, friction, friction_rate] = self.slide_impulse(setup, w_tau);
        let body = self.cart + self.frame;
        let v = s0.v + impulse / body;
        Point {
            state: FrameState {
                s: State {
                    t,
                    vx: s0.vx - impulse / setup.m,
                    omega: s0.omega + impulse * setup.r / setup.inertia,
                    x: s0.x,
                    v,
                },
                vf: v,
            },
            friction,
            friction_rate,
            accel: friction / body,
        }
    }

    /// The cart's velocity and the frame's from the momentum `p` and the stretch's rate `dy`:
    /// (P + M_t y')/(M + M_t) and (P - M y')/(M + M_t). Each is taken from P and y' directly, not as the
    /// other less y', which would lose the lighter body's velocity to the heavier's rounding.
    #[inline]
    fn velocities(&self, p: f64, dy: f64) -> (f64, f64) {
        let body = self.cart + self.frame;
        ((p + self.frame * dy) / body, (p - self.cart * dy) / body)
    }

    /// Everything at `t`.
    #[inline]
    fn at(&self, setup: &Setup, t: f64) -> Point {
        if self.held {
            return self.held_at(setup, t);
        }
        self.moving_at(setup, t).0
    }

    /// sin and cos of the stretch's angle Ωτ and of the normal force's (w t gripping, w τ sliding) at `t`,
    /// computed together; at the phase's start, where the event search begins, they are known.
    #[inline(always)]
    fn angles(&self, setup: &Setup, t: f64) -> Angles {
        let tau = t - self.start.s.t;
        let grip = self.dir == 0.0;
        if tau == 0.0 {
            let normal = if grip {
                (self.sin_wt0, self.cos_wt0)
            } else {
                (0.0, 1.0)
            };
            ((0.0, 1.0), normal)
        } else if grip {
            sin_cos2(self.omega * tau, setup.w * t)
        } else {
            sin_cos2(self.omega * tau, setup.w * tau)
        }
    }

    /// Everything at `t` on a moving cart, the stretch solved as z = y + `string` (see the module), and
    /// sin(w t), cos(w t) while the ball grips (for the margins of its grip; sliding, (0, 1) in their
    /// place).
    #[inline]
    fn moving_at(&self, setup: &Setup, t: f64) -> (Point, (f64, f64)) {
        self.moving_given(setup, t, self.angles(setup, t))
    }

    /// [`FrameMotion::moving_at`] with the phase's `Angles` at `t` at hand.
    #[inline]
    fn moving_given(
        &self,
        setup: &Setup,
        t: f64,
        ((sin_omega_tau, cos_omega_tau), normal): Angles,
    ) -> (Point, (f64, f64)) {
        let s0 = &self.start.s;
        let tau = t - s0.t;
        let grip = self.dir == 0.0;
        let (z0, dy0) = (s0.x + self.string, s0.v - self.start.vf);
        let (z_free, dy_free) = free_given(z0, dy0, self.omega, tau, sin_omega_tau, cos_omega_tau);
        if grip {
            let (v, vf) = self.velocities(self.p0, dy_free);
            let impulse = -setup.m_eff * (v - self.v1_start);
            // Eq. (5) with the string friction beside the spring force: m_eff (k y + d F_c)/(M + m_eff).
            let gain = setup.m_eff * setup.k / self.cart;
            let accel = -setup.k * z_free / self.cart;
            let point = Point {
                state: FrameState {
                    s: State {
                        t,
                        vx: s0.vx - impulse / setup.m,
                        omega: s0.omega + impulse * setup.r / setup.inertia,
                        x: z_free - self.string,
                        v,
                    },
                    vf,
                },
                friction: gain * z_free,
                friction_rate: gain * dy_free,
                accel,
            };
            return (point, normal);
        }
        let w = setup.w;
        let force_amplitude = self.dir * setup.peak_friction();
        let (sin_w_tau, cos_w_tau) = normal;
        // The ball's impulse is also what the cart and the frame together gain.
        let [impulse, friction, friction_rate] = self.slide_impulse(setup, (sin_w_tau, cos_w_tau));
        let (z, dy) = match self.amplitude {
            Some(amplitude) => {
                let (g, dg) = detuned(
                    self.omega,
                    w,
                    tau,
                    (self.sin_wt0, self.cos_wt0),
                    (sin_w_tau, cos_w_tau),
                    (sin_omega_tau, cos_omega_tau),
                );
                (z_free + amplitude * g, dy_free + amplitude * dg)
            }
            None => {
                let (g, dg) = forced(self.omega, w, self.sin_wt0, self.cos_wt0, tau);
                let drive = force_amplitude / self.cart;
                (z_free + drive * g, dy_free + drive * dg)
            }
        };
        let (v, vf) = self.velocities(self.p0 + impulse, dy);
        let accel = (friction - setup.k * z) / self.cart;
        let point = Point {
            state: FrameState {
                s: State {
                    t,
                    vx: s0.vx - impulse / setup.m,
                    omega: s0.omega + impulse * setup.r / setup.inertia,
                    x: z - self.string,
                    v,
                },
                vf,
            },
            friction,
            friction_rate,
            accel,
        };
        (point, (0.0, 1.0))
    }

    /// A bound on |y'| over the rest of the contact: the oscillator's energy, in velocity units, grows at
    /// most by the drive's impulse per unit mass; away from resonance, also the free swing about the
    /// particular response A sin(w t) plus that response's speed |A| w, whichever is smaller.
    fn stretch_speed(&self, setup: &Setup) -> f64 {
        if self.held {
            return 0.0;
        }
        let s0 = &self.start.s;
        let (z0, dy0) = (s0.x + self.string, s0.v - self.start.vf);
        let free = (dy0 * dy0 + (self.omega * z0).powi(2)).sqrt();
        if self.dir == 0.0 {
            return free;
        }
        let fed = free + setup.peak_friction() * (setup.duration - s0.t) / self.cart;
        self.amplitude.map_or(fed, |a| {
            let w = setup.w;
            let swing = ((dy0 - a * w * self.cos_wt0).powi(2)
                + (self.omega * (z0 - a * self.sin_wt0)).powi(2))
            .sqrt();
            fed.min(swing + a.abs() * w)
        })
    }

    /// A bound on |slip''| over the rest of a slide on a moving cart, given [`Self::stretch_speed`]:
    /// slip'' = -F'/m_eff - V'' with V'' = (F' - k y')/M. Away from resonance also, and whichever is
    /// smaller, the amplitudes of the slip's sums ([`SlipSums`]: slip'' is
    /// -dir (P w cos w t - B' Ω² cos Ωτ + Q Ω² sin Ωτ)), |P| w + (M_t/B) Ω² sqrt(b² + a² Ω²), with
    /// P = F0 (1/m_eff + 1/B) - dir (M_t/B) A w², b = y0' - A w cos w t0, a = z0 - A sin w t0.
    fn slip_curvature(&self, setup: &Setup, stretch_speed: f64) -> f64 {
        let (w, peak) = (setup.w, setup.peak_friction());
        let force_rate = peak * w;
        let crude = force_rate / setup.m_eff + (force_rate + setup.k * stretch_speed) / self.cart;
        self.amplitude.map_or(crude, |a| {
            let s0 = &self.start.s;
            let (z0, dy0) = (s0.x + self.string, s0.v - self.start.vf);
            let body = self.cart + self.frame;
            let share = self.frame / body;
            let ball =
                (peak * (1.0 / setup.m_eff + 1.0 / body) - self.dir * share * a * w * w).abs();
            let omega = self.omega;
            let swing = ((dy0 - a * w * self.cos_wt0).powi(2)
                + (omega * (z0 - a * self.sin_wt0)).powi(2))
            .sqrt();
            crude.min(ball * w + share * omega * omega * swing)
        })
    }
}

impl PhaseMotion for FrameMotion {
    fn state_at(&self, setup: &Setup, t: f64) -> State {
        self.at(setup, t).state.s
    }

    fn friction(&self, setup: &Setup, state: &State) -> f64 {
        self.at(setup, state.t).friction
    }

    fn initial(&self) -> State {
        self.start.s
    }

    /// A rigid ball has no contact patch.
    fn patch_at(&self, _: &Setup, _: f64) -> Option<(f64, f64)> {
        None
    }

    /// The cart's kinetic energy and its spring's, M V²/2 + k y²/2 (the frame's is apart).
    fn surface_energy(&self, setup: &Setup, at: &State) -> f64 {
        setup.cart_energy(at)
    }

    /// ∫ F (v_x - r omega - V) dt, on panels of the faster of the stretch and the normal force.
    fn friction_work(&self, setup: &Setup, start: f64, end: f64) -> f64 {
        let power = |t: f64| {
            let p = self.at(setup, t);
            p.friction * setup.slip(&p.state.s)
        };
        integrate(power, start, end, 2.0 / self.omega.max(setup.w))
    }

    /// A rigid ball holds no tangential energy.
    fn ball_spring_energy(&self, _: &Setup, _: f64) -> f64 {
        0.0
    }

    fn dashpot_loss(&self, _: &Setup, _: f64, _: f64) -> f64 {
        0.0
    }

    fn frame_velocity(&self, setup: &Setup, t: f64) -> f64 {
        self.at(setup, t).state.vf
    }

    fn fastest(&self, _: &Setup) -> f64 {
        self.omega
    }
}

/// The rigid ball on the single cart, its spring tied to a free frame of mass M_t.
pub struct FramedCart {
    mass: f64,
    /// Ω = sqrt(k (1/M + 1/M_t)), the stretch's frequency while the ball slides.
    omega_slide: f64,
    /// Ω_g = sqrt(k (1/(M + m_eff) + 1/M_t)), while it grips.
    omega_grip: f64,
    spin: f64,
    /// |v_x1| + r |omega1|: the scale of the speeds, for the event functions' rounding.
    incoming: f64,
}

impl FramedCart {
    /// The model for `params` on a frame of mass `frame` (kg), refused when the cart oscillates too fast
    /// to resolve, or when string friction acts without a spring (the stretch's centre d F_c/k is not
    /// defined; the compliant ball refuses the same).
    pub fn new(params: &Params, setup: &Setup, frame: f64) -> Result<Self, SolveError> {
        if setup.k == 0.0 && setup.cart_friction > 0.0 {
            return Err(SolveError::FreeFrame {
                what: "string friction (--cart-friction) without a spring (--stiffness 0)",
            });
        }
        let omega_slide = (setup.k * (1.0 / setup.cart_mass + 1.0 / frame)).sqrt();
        let omega_grip = (setup.k * (1.0 / (setup.cart_mass + setup.m_eff) + 1.0 / frame)).sqrt();
        let radians = omega_slide.max(omega_grip) * setup.duration;
        if radians > MAX_RADIANS {
            return Err(SolveError::TooFast { radians });
        }
        Ok(FramedCart {
            mass: frame,
            omega_slide,
            omega_grip,
            spin: params.spin,
            incoming: setup.vx1.abs() + setup.r * params.spin.abs(),
        })
    }
}

impl Contact for FramedCart {
    type State = FrameState;
    type Motion = FrameMotion;
    type Probe = FrameState;

    fn start(&self, setup: &Setup) -> (FrameState, Mode) {
        let state = FrameState {
            s: setup.initial(self.spin),
            vf: 0.0,
        };
        let slip0 = setup.slip(&state.s);
        // A ball that arrives rolling grips at once (N(0) = 0 and F_s = 0).
        let arriving = if slip0.abs() <= ROLLING * self.incoming {
            Ball::Grip
        } else {
            Ball::Slide(slip0.signum())
        };
        let mode = transition::next_on(
            setup,
            &touched(setup, &state),
            self.mass / (setup.cart_mass + self.mass),
            arriving,
            Cart::Moving(1),
            Cause::Start,
        );
        (state, mode)
    }

    fn time(state: &FrameState) -> f64 {
        state.s.t
    }

    fn contact(state: &FrameState) -> State {
        state.s
    }

    fn motion(&self, setup: &Setup, state: &FrameState, (ball, cart): Mode) -> FrameMotion {
        let dir = match ball {
            Ball::Slide(dir) => dir,
            Ball::Grip => 0.0,
        };
        FrameMotion::new(setup, self, *state, dir, cart)
    }

    #[inline(always)]
    fn first_event(
        &self,
        setup: &Setup,
        motion: &FrameMotion,
        state: &FrameState,
        (_, cart): Mode,
        cause: Cause,
    ) -> Found<FrameState> {
        let (t0, end) = (state.s.t, setup.duration);
        let s = &state.s;
        let peak = setup.peak_friction();
        let stretch_speed = motion.stretch_speed(setup);
        // The states at the last few times an event function was evaluated.
        let last = Recent::new(s.t, *state);
        // Event functions that start on their own zero (the slip after a grip broke or the friction
        // reversed, the stretch's rate after the cart stopped or came unstuck) are measured from their
        // start value, so rounding can never fake a crossing at the start.
        let slip_offset = if matches!(cause, Cause::SlipZero | Cause::GripBreak(_)) {
            setup.slip(s)
        } else {
            0.0
        };
        let dy_offset = if matches!(cause, Cause::Start | Cause::CartStop | Cause::Unstick(_)) {
            s.v - state.vf
        } else {
            0.0
        };
        let speeds = self.incoming
            + s.vx.abs()
            + setup.r * s.omega.abs()
            + s.v.abs()
            + state.vf.abs()
            + stretch_speed;
        let forces = peak + setup.k * s.x.abs() + setup.cart_friction;
        // Without string friction the cart's stopping changes nothing: a constant stands in for it,
        // and the searches leave it out.
        let string = setup.cart_friction > 0.0;
        let stop = |p: &Point, cart_dir: f64| {
            if string {
                let dy = p.state.s.v - p.state.vf;
                // y'' = V' less the frame's acceleration k z/M_t (the spring and the string
                // friction on it).
                let z = p.state.s.x + motion.string;
                let stretch_accel = p.accel - setup.k * z / motion.frame;
                (-cart_dir * (dy - dy_offset), -cart_dir * stretch_accel)
            } else {
                (-1.0, 0.0)
            }
        };
        let event = match (motion.dir, cart) {
            (dir, Cart::Moving(cart_dir)) if dir != 0.0 => {
                let cart_dir = f64::from(cart_dir);
                let f = |t: f64| {
                    let p = motion.at(setup, t);
                    last.record(t, p.state);
                    let rate = -p.friction / setup.m_eff - p.accel;
                    let slip = (-dir * (setup.slip(&p.state.s) - slip_offset), -dir * rate);
                    [slip, stop(&p, cart_dir)]
                };
                // slip'' = -F'/m_eff - V'', V'' = (F' - k y')/M; y''' = F'/M - Ω² y'.
                let force_rate = peak * setup.w;
                let curvature = motion.slip_curvature(setup, stretch_speed);
                let stop_curvature = if string {
                    force_rate / motion.cart + motion.omega * motion.omega * stretch_speed
                } else {
                    0.0
                };
                let step = setup.event_step(motion.omega);
                let noise = ROUNDING * speeds;
                let found = if string {
                    first_rise(f, t0, end, step, [curvature, stop_curvature], [noise; 2])
                } else if let Some(sums) = SlipSums::new(motion, setup) {
                    let constants = sums.constants(slip_offset);
                    // The slip alone, by its sums; the state is computed only where the search ends.
                    let [curvature, fourth] = sums.bounds(setup, motion.omega);
                    searched_by_sums(
                        "frame slide by its sums",
                        (motion, setup, &last),
                        (t0, end, step),
                        [[curvature], [fourth]],
                        [noise],
                        |angles| [sums.event(angles, constants)],
                    )
                } else {
                    // The stand-in costs a search branch: leave it out.
                    first_rise(|t| [f(t)[0]], t0, end, step, [curvature], [noise])
                };
                found.map(|(t, branch)| {
                    let cause = if branch == 0 {
                        Cause::SlipZero
                    } else {
                        Cause::CartStop
                    };
                    (t, cause)
                })
            }
            (_, Cart::Moving(cart_dir)) => {
                let cart_dir = f64::from(cart_dir);
                let f = |t: f64| {
                    let (p, normal) = motion.moving_at(setup, t);
                    last.record(t, p.state);
                    let [forward, backward] =
                        setup.grip_margins_given(normal, p.friction, p.friction_rate);
                    [forward, backward, stop(&p, cart_dir)]
                };
                // F_s'' = m_eff k y''/(M + m_eff), |y''| = Ω_g² |z| <= Ω_g sqrt(Ω_g² z0² + y0'²);
                // mu N'' <= mu N0 w²; y''' = -Ω_g² y'.
                let gain = setup.m_eff * setup.k / motion.cart;
                let curvature = gain * motion.omega * stretch_speed + peak * setup.w * setup.w;
                let stop_curvature = if string {
                    motion.omega * motion.omega * stretch_speed
                } else {
                    0.0
                };
                let step = setup.event_step(motion.omega);
                let noise = [ROUNDING * forces, ROUNDING * forces, ROUNDING * speeds];
                let curvatures = [curvature, curvature, stop_curvature];
                let found = if string {
                    first_rise(f, t0, end, step, curvatures, noise)
                } else if let Some(sums) = force_sums(motion, setup) {
                    // The margins alone, by their sums; the state is computed only where the search
                    // ends.
                    searched_by_sums(
                        "frame grip by its sums",
                        (motion, setup, &last),
                        (t0, end, step),
                        [[sums.curvature; 2], [sums.fourth; 2]],
                        [noise[0]; 2],
                        |angles| sums.margins(setup, angles),
                    )
                } else {
                    let margins = |t| {
                        let [forward, backward, _] = f(t);
                        [forward, backward]
                    };
                    first_rise(margins, t0, end, step, [curvature; 2], [noise[0]; 2])
                };
                found.map(|(t, branch)| {
                    let cause = match branch {
                        0 => Cause::GripBreak(1.0),
                        1 => Cause::GripBreak(-1.0),
                        _ => Cause::CartStop,
                    };
                    (t, cause)
                })
            }
            (dir, Cart::Stuck) if dir != 0.0 => {
                // Held, the cart and the frame take F/(M + M_t) together; the string friction holds
                // the cart with M_t F/(M + M_t) - k y.
                let body = setup.cart_mass + self.mass;
                let share = self.mass / body;
                let f = |t: f64| {
                    let p = motion.at(setup, t);
                    last.record(t, p.state);
                    let rate = -p.friction / setup.m_eff - p.accel;
                    let slip = (-dir * (setup.slip(&p.state.s) - slip_offset), -dir * rate);
                    let push = share * p.friction - setup.k * p.state.s.x;
                    let push_rate = share * p.friction_rate;
                    let [up, down] = setup.unstick_margins(push, push_rate);
                    [slip, up, down]
                };
                let force_rate = peak * setup.w;
                let slip_curvature = force_rate * (1.0 / setup.m_eff + 1.0 / body);
                let push_curvature = share * force_rate * setup.w;
                let noise = [ROUNDING * speeds, ROUNDING * forces, ROUNDING * forces];
                let step = setup.event_step(0.0);
                let curvature = [slip_curvature, push_curvature, push_curvature];
                first_rise(f, t0, end, step, curvature, noise)
                    .map(|(t, branch)| (t, Cause::of_held(branch)))
            }
            // A rolling ball on a held cart: ball, cart and frame coast until the ball leaves.
            (_, Cart::Stuck) => None,
        };
        // The search's last evaluations usually hold the state at the event (the crossing Newton
        // found, before the evaluations that proved nothing rose earlier) or at the end of contact.
        let last = last.at(event.map_or(end, |(t, _)| t));
        Found {
            event,
            last: Some(last),
        }
    }

    fn state_at(
        &self,
        setup: &Setup,
        motion: &FrameMotion,
        t: f64,
        last: Option<FrameState>,
    ) -> FrameState {
        match last {
            Some(s) if s.s.t == t => s,
            _ => motion.at(setup, t).state,
        }
    }

    /// The cart that stops relative to the frame joins it (its velocity set to the frame's).
    fn next(
        &self,
        setup: &Setup,
        state: &mut FrameState,
        (ball, cart): Mode,
        cause: Cause,
    ) -> Mode {
        if cause == Cause::CartStop {
            state.s.v = state.vf;
        }
        let share = self.mass / (setup.cart_mass + self.mass);
        transition::next_on(setup, &touched(setup, state), share, ball, cart, cause)
    }
}

/// The cart as the transition rules see it: its spring force is k y, and it is at rest when it moves
/// with the frame.
fn touched(setup: &Setup, state: &FrameState) -> Touched {
    Touched {
        t: state.s.t,
        mass: setup.cart_mass,
        spring: setup.k * state.s.x,
        v: state.s.v - state.vf,
    }
}

/// A search by sums of `motion`'s event `event`, a function of the phase's angles (`regime` names it,
/// for the bounds test): their f'' and f''' are as exact as f and f', so crossings are refined from
/// predicted ones and intervals proved empty by the Taylor polynomials with `bounds` on f'' and f''''
/// ([`first_rise_predicted`]). Each probe's angles are kept (a refinement's turned from the last fresh
/// ones, [`Probe::near`]), and the state where the search ends is computed from them and recorded in
/// `last`. Under test, where the bounds test asks it, the bounds are first checked against the branches
/// they bound.
#[inline(always)]
fn searched_by_sums<const K: usize>(
    regime: &'static str,
    (motion, setup, last): (&FrameMotion, &Setup, &Recent<FrameState>),
    (t0, end, step): (f64, f64, f64),
    bounds: [[f64; K]; 2],
    noise: [f64; K],
    event: impl Fn(Angles) -> [(f64, f64, f64, f64); K],
) -> Option<(f64, usize)> {
    // The rates of the angles ([`FrameMotion::angles`]), for a refinement's probe turned from the last.
    let rates = (motion.omega, setup.w);
    let probes = Recent::new(t0, Probe::fresh(t0, motion.angles(setup, t0)));
    let f = WithNear(
        |t: f64| {
            let angles = motion.angles(setup, t);
            probes.record(t, Probe::fresh(t, angles));
            event(angles)
        },
        |t: f64| {
            let probe = (probes.latest()).near(t, t0, rates, || motion.angles(setup, t));
            probes.record(t, probe);
            event(probe.angles)
        },
    );
    let search = move |f| first_rise_predicted(f, t0, end, step, bounds, noise);
    #[cfg(test)]
    let found = super::bound_samples::search_checked(
        || regime.to_string(),
        f,
        (t0, end, step),
        bounds,
        search,
    );
    #[cfg(not(test))]
    let found = {
        let _ = regime;
        search(f)
    };
    let Probe { t, angles, .. } = probes.at(found.map_or(end, |(t, _)| t));
    last.record(t, motion.moving_given(setup, t, angles).0.state);
    found
}
