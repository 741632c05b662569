//! The constants of one bounce, derived once from [`Params`], and the state that evolves.

use std::f64::consts::PI;

use super::params::Params;
use super::trig::{sin, sin_cos};

/// The tangential state of ball and cart at time `t` (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    pub t: f64,
    /// Ball centre's velocity along the surface.
    pub vx: f64,
    /// Ball spin; positive is the sense sliding friction drives.
    pub omega: f64,
    /// Cart displacement from rest.
    pub x: f64,
    /// Cart velocity.
    pub v: f64,
}

/// The ball's apparent restitution on a frame of normal effective mass `frame`: the ball and the frame
/// part with relative speed e_y v_y1 and the frame takes the impulse, so
/// e_A = (e_y M_n - m)/(M_n + m) (issue 23).
pub fn apparent_restitution(ey: f64, m: f64, frame: f64) -> f64 {
    (ey * frame - m) / (frame + m)
}

/// The peak normal force N0 of an impulse m (1 + e_A) v_y1 = 2 N0 T / pi.
#[inline]
fn peak_normal_force(ey_apparent: f64, p: &Params, vy1: f64) -> f64 {
    (1.0 + ey_apparent) * PI * p.mass * vy1 / (2.0 * p.duration)
}

/// Constants of the model for one set of parameters.
#[derive(Clone, Copy, Debug)]
pub struct Setup {
    pub m: f64,
    pub r: f64,
    /// I_cm = alpha m r^2.
    pub inertia: f64,
    /// The ball's effective mass at its contact point, 1/m_eff = 1/m + r^2/I, so m_eff = m alpha/(1+alpha).
    pub m_eff: f64,
    pub cart_mass: f64,
    pub k: f64,
    pub mu: f64,
    /// String friction on the cart, N.
    pub cart_friction: f64,
    pub duration: f64,
    /// w = pi/T, the angular frequency of the normal force.
    pub w: f64,
    /// Peak normal force N0 = (1 + e_y) pi m v_y1 / (2T) (the paper's pi m v_y1 / T for e_y = 1).
    pub n0: f64,
    /// sqrt(k/M): the cart's frequency while the ball slides, Eq. (3).
    pub omega_slide: f64,
    /// sqrt(k/(M + m alpha/(1+alpha))): the cart's frequency while the ball grips, Eq. (6).
    pub omega_grip: f64,
    /// F_s / X during grip, Eq. (5): F_s = m k X / (M (1 + m/M + m r^2/I)) = k m_eff X / (M + m_eff).
    pub grip_gain: f64,
    pub vx1: f64,
    pub vy1: f64,
    /// The frame's mass M_t along the surface, kg; `None` when clamped (the wall).
    pub frame_mass: Option<f64>,
    /// The frame's effective mass M_n normal to the surface, kg (M_t unless given); `None` when clamped.
    pub frame_normal_mass: Option<f64>,
    /// The ball's apparent restitution on the frame, e_A = (e_y M_n - m)/(M_n + m) (issue 23); e_y on a
    /// clamped frame.
    pub ey_apparent: f64,
}

/// The direction of incidence, sin and cos of the complement of theta1, kept for the bounces that
/// follow at the same angle (a sweep of any other parameter computes it once).
#[derive(Clone, Copy, Debug, Default)]
pub struct Incidence {
    /// theta1's bits, and the sin and cos of its complement.
    known: Option<(u64, f64, f64)>,
    /// True when the caller vouches that the bounces it asks for differ in their incidence alone (angle,
    /// speed, spin), so that a rigid ball's constants are the last bounce's but for those of
    /// [`Setup::at_new_incidence`].
    pub only_varies: bool,
}

impl Incidence {
    /// For bounces that differ in their incidence alone ([`Incidence::only_varies`]).
    pub fn only_varying() -> Self {
        Incidence {
            only_varies: true,
            ..Incidence::default()
        }
    }

    /// sin and cos of 90 degrees - `angle_deg`, computed when the angle differs from the last one's.
    #[inline]
    pub fn at(&mut self, angle_deg: f64) -> (f64, f64) {
        match self.known {
            Some((bits, sin, cos)) if bits == angle_deg.to_bits() => (sin, cos),
            _ => {
                // cos and sin through the complement, so 90 degrees gives exactly vx1 = 0.
                let complement = (90.0 - angle_deg).to_radians();
                let (sin, cos) = (complement.sin(), complement.cos());
                self.known = Some((angle_deg.to_bits(), sin, cos));
                (sin, cos)
            }
        }
    }
}

impl Setup {
    pub fn new(p: &Params) -> Self {
        Setup::at_incidence(p, &mut Incidence::default())
    }

    /// [`Setup::new`], the direction of incidence taken from `incidence` when it knows the angle.
    #[inline]
    pub fn at_incidence(p: &Params, incidence: &mut Incidence) -> Self {
        let inertia = p.alpha * p.mass * p.radius * p.radius;
        let m_eff = p.mass * p.alpha / (1.0 + p.alpha);
        let w = PI / p.duration;
        let (sin, cos) = incidence.at(p.angle_deg);
        let vx1 = p.speed * sin;
        let vy1 = p.speed * cos;
        let frame_mass = (p.frame_mass > 0.0).then_some(p.frame_mass);
        let frame_normal_mass = if p.frame_normal_mass > 0.0 {
            Some(p.frame_normal_mass)
        } else {
            frame_mass
        };
        let ey_apparent =
            frame_normal_mass.map_or(p.ey, |mn| apparent_restitution(p.ey, p.mass, mn));
        Setup {
            m: p.mass,
            r: p.radius,
            inertia,
            m_eff,
            cart_mass: p.cart_mass,
            k: p.stiffness,
            mu: p.mu,
            cart_friction: p.cart_friction,
            duration: p.duration,
            w,
            n0: peak_normal_force(ey_apparent, p, vy1),
            omega_slide: (p.stiffness / p.cart_mass).sqrt(),
            omega_grip: (p.stiffness / (p.cart_mass + m_eff)).sqrt(),
            grip_gain: p.stiffness * m_eff / (p.cart_mass + m_eff),
            vx1,
            vy1,
            frame_mass,
            frame_normal_mass,
            ey_apparent,
        }
    }

    /// These constants for `p`, whose parameters are those they were made of but for the incidence
    /// (angle, speed, spin): the same bits as [`Setup::at_incidence`]'s, only v_x1, v_y1 and N0
    /// computed again.
    #[inline]
    pub fn at_new_incidence(&mut self, p: &Params, incidence: &mut Incidence) {
        let (sin, cos) = incidence.at(p.angle_deg);
        self.vx1 = p.speed * sin;
        self.vy1 = p.speed * cos;
        self.n0 = peak_normal_force(self.ey_apparent, p, self.vy1);
    }

    /// The ball's velocity away from the surface as it leaves, e_A v_y1.
    pub fn vy2(&self) -> f64 {
        self.ey_apparent * self.vy1
    }

    /// The frame's velocity normal to the surface after the impact, m (1 + e_A) v_y1 / M_n (0 clamped).
    pub fn frame_normal_velocity(&self) -> f64 {
        self.frame_normal_mass
            .map_or(0.0, |mn| self.m * (1.0 + self.ey_apparent) * self.vy1 / mn)
    }

    /// The frame's kinetic energy at tangential velocity `v` (and its normal velocity after the impact);
    /// 0 when clamped.
    pub fn frame_energy(&self, v: f64) -> f64 {
        let normal = self
            .frame_normal_mass
            .map_or(0.0, |mn| 0.5 * mn * self.frame_normal_velocity().powi(2));
        let along = self.frame_mass.map_or(0.0, |mt| 0.5 * mt * v * v);
        normal + along
    }

    /// N(t) = N0 sin(pi t / T) during contact: the normal-force law, written here once. The phases' closed
    /// forms (`cart/slide.rs`, `chain/motion.rs`, `compliant/stretch.rs`) are exact responses to the
    /// friction it drives, mu N0 sin(w t), and take its amplitude from [`Setup::peak_friction`].
    #[inline]
    pub fn normal(&self, t: f64) -> f64 {
        if (0.0..=self.duration).contains(&t) {
            self.n0 * sin(self.w * t)
        } else {
            0.0
        }
    }

    /// mu N0, the sliding friction at the peak of the normal force.
    #[inline]
    pub fn peak_friction(&self) -> f64 {
        self.mu * self.n0
    }

    /// d(mu N)/dt at `t`, mu N0 w cos(w t).
    #[inline]
    pub fn friction_limit_rate(&self, t: f64) -> f64 {
        self.peak_friction() * self.w * sin_cos(self.w * t).1
    }

    /// How far a grip held by static friction `force` (with rate `rate`) is from breaking at `t`, forward
    /// and backward: ±force - mu N(t), each with its rate. The grip breaks when either rises above zero.
    #[inline]
    pub fn grip_margins(&self, t: f64, force: f64, rate: f64) -> [(f64, f64); 2] {
        let (sin_wt, cos_wt) = sin_cos(self.w * t);
        self.grip_margins_given((sin_wt, cos_wt), force, rate)
    }

    /// [`Setup::grip_margins`] with sin(w t) and cos(w t) at hand.
    #[inline]
    pub fn grip_margins_given(
        &self,
        (sin_wt, cos_wt): (f64, f64),
        force: f64,
        rate: f64,
    ) -> [(f64, f64); 2] {
        let limit = self.peak_friction() * sin_wt.max(0.0);
        let limit_rate = self.peak_friction() * self.w * cos_wt;
        [
            (force - limit, rate - limit_rate),
            (-force - limit, -rate - limit_rate),
        ]
    }

    /// [`Setup::grip_margins_given`] with the first three derivatives of each margin, given F_s and its
    /// first three derivatives; mu N's second and third derivatives are -w² times its value and rate.
    #[inline(always)]
    pub fn grip_margins_with_derivatives(
        &self,
        normal: (f64, f64),
        [force, rate, second, third]: [f64; 4],
    ) -> [(f64, f64, f64, f64); 2] {
        let [(forward, forward_rate), (backward, backward_rate)] =
            self.grip_margins_given(normal, force, rate);
        let w2 = self.w * self.w;
        let limit = self.peak_friction() * normal.0.max(0.0);
        let limit_rate = self.peak_friction() * self.w * normal.1;
        [
            (
                forward,
                forward_rate,
                second + w2 * limit,
                third + w2 * limit_rate,
            ),
            (
                backward,
                backward_rate,
                w2 * limit - second,
                w2 * limit_rate - third,
            ),
        ]
    }

    /// How far a cart held by string friction is from coming unstuck, given the net push `push` on it
    /// (with rate `rate`): forward push - F_c and backward -push - F_c, each with its rate. The cart is
    /// pushed free the way of whichever rises above zero first (Sec. IV's enhancement).
    #[inline]
    pub fn unstick_margins(&self, push: f64, rate: f64) -> [(f64, f64); 2] {
        [
            (push - self.cart_friction, rate),
            (-push - self.cart_friction, -rate),
        ]
    }

    /// Slip speed of the ball's contact point relative to the cart: v_x - r omega - V.
    #[inline]
    pub fn slip(&self, s: &State) -> f64 {
        s.vx - self.r * s.omega - s.v
    }

    /// The state at first contact: the cart at rest.
    pub fn initial(&self, spin: f64) -> State {
        State {
            t: 0.0,
            vx: self.vx1,
            omega: spin,
            x: 0.0,
            v: 0.0,
        }
    }

    /// Ball (translation + rotation) kinetic energy in the tangential direction.
    pub fn ball_tangential_energy(&self, s: &State) -> f64 {
        0.5 * self.m * s.vx * s.vx + 0.5 * self.inertia * s.omega * s.omega
    }

    /// Cart kinetic plus spring energy.
    pub fn cart_energy(&self, s: &State) -> f64 {
        0.5 * self.cart_mass * s.v * s.v + 0.5 * self.k * s.x * s.x
    }

    /// The coarse step of the event search: half the fastest period present. Any step is
    /// correct (intervals are proved empty or split); this one lets most be proved empty at once.
    pub fn event_step(&self, omega_cart: f64) -> f64 {
        std::f64::consts::PI / omega_cart.max(self.w)
    }
}
