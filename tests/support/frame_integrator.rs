//! An independent solution of the ball on a cart whose spring is tied to a free frame (issue 23), by
//! numerical integration: classical fixed-step RK4 on (v_x, omega, x1, V, x_f, V_f, e) with each
//! transition located by bisection on the step length. It shares nothing with the exact solvers but the
//! equations and the parameters, and decides what follows each transition by its own plain rules.
//!
//! Along the surface, with the spring's stretch y = x1 - x_f and F the force on the ball (positive
//! backward, +F on the cart):
//!
//! - the cart moving relative to the frame in direction d: M x1'' = F - k y - d F_c and
//!   M_t x_f'' = k y + d F_c (the string friction F_c acts between the cart and the frame); the phase
//!   also ends when y' reaches zero (with F_c > 0);
//! - held to the frame by string friction: x1'' = x_f'' = F/(M + M_t), which needs
//!   |M_t F/(M + M_t) - k y| <= F_c; the phase also ends when that is exceeded.
//!
//! A frame mass of 0 is a clamped frame (1/M_t = 0): the clamped models, for checking this integrator.
//!
//! The ball is rigid (`ball_stiffness` 0): F = dir mu N sliding; gripping, the contact point moves with
//! the cart, F_s = m_eff (k y + d F_c)/(M + m_eff) on a moving cart and 0 on a held one (ball, cart and
//! frame coast). Or compliant: a tangential spring k_b and dashpot c_b = 2 zeta sqrt(k_b m_eff) between
//! the ball's contact point and a massless patch, stretch e, F = k_b e + c_b e'; sliding F = dir mu N and
//! c_b e' = F - k_b e (e' = F'/k_b undamped); gripping, the patch moves with the cart,
//! e' = v_x - r omega - V. The slide ends when the patch's slip (v_x - r omega - V) - e' reaches zero,
//! the grip when |F| exceeds mu N.

use snapback::model::Params;
use std::f64::consts::PI;

#[allow(dead_code)] // not every test file reads every field
#[derive(Clone, Copy, Debug)]
pub struct FrameNumerical {
    pub vx2: f64,
    pub omega2: f64,
    /// The cart's velocity and the frame's at release.
    pub v2: f64,
    pub vf2: f64,
    /// The spring's stretch x1 - x_f at release.
    pub stretch2: f64,
    /// The compliant ball's stretch e at release (0 for a rigid ball).
    pub e2: f64,
    /// How many phases the ball and the cart went through.
    pub phases: usize,
    /// Whether string friction held the cart to the frame at some time.
    pub held: bool,
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Ball {
    Slide(f64),
    Grip,
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Cart {
    /// Moving relative to the frame in direction +1 or -1 (0 without string friction).
    Moving(f64),
    Held,
}

type Mode = (Ball, Cart);

struct Model {
    m: f64,
    r: f64,
    inertia: f64,
    big_m: f64,
    /// 1/M_t, 0 for a clamped frame.
    inv_frame: f64,
    k: f64,
    mu: f64,
    fc: f64,
    n0: f64,
    w: f64,
    /// k_b and c_b; k_b = 0 for a rigid ball.
    kb: f64,
    cb: f64,
}

type Y = [f64; 7]; // vx, omega, x1, V, x_f, V_f, e

impl Model {
    fn normal(&self, t: f64) -> f64 {
        self.n0 * (self.w * t).sin().max(0.0)
    }

    fn m_eff(&self) -> f64 {
        1.0 / (1.0 / self.m + self.r * self.r / self.inertia)
    }

    fn compliant(&self) -> bool {
        self.kb > 0.0
    }

    /// The part of the ball's force that pushes the held cart against the string friction.
    fn share(&self) -> f64 {
        1.0 / (1.0 + self.big_m * self.inv_frame)
    }

    /// The rigid ball's static friction while its contact point moves with a cart moving in `dir`.
    fn static_friction(&self, y: &Y, dir: f64) -> f64 {
        self.m_eff() * (self.k * (y[2] - y[4]) + dir * self.fc) / (self.big_m + self.m_eff())
    }

    /// The force on the ball (positive backward) and the rate of the compliant ball's stretch.
    fn force(&self, (ball, cart): Mode, t: f64, y: &Y) -> (f64, f64) {
        match ball {
            Ball::Slide(dir) => {
                let f = dir * self.mu * self.normal(t);
                let de = if !self.compliant() {
                    0.0
                } else if self.cb > 0.0 {
                    (f - self.kb * y[6]) / self.cb
                } else {
                    dir * self.mu * self.n0 * self.w * (self.w * t).cos() / self.kb
                };
                (f, de)
            }
            Ball::Grip if self.compliant() => {
                let de = y[0] - self.r * y[1] - y[3];
                (self.kb * y[6] + self.cb * de, de)
            }
            Ball::Grip => match cart {
                Cart::Moving(dir) => (self.static_friction(y, dir), 0.0),
                Cart::Held => (0.0, 0.0),
            },
        }
    }

    fn rate(&self, mode: Mode, t: f64, y: &Y) -> Y {
        let (f, de) = self.force(mode, t, y);
        let (dv, dvf) = match mode.1 {
            Cart::Moving(dir) => {
                let held_back = self.k * (y[2] - y[4]) + dir * self.fc;
                ((f - held_back) / self.big_m, held_back * self.inv_frame)
            }
            Cart::Held => {
                let a = f * self.inv_frame / (1.0 + self.big_m * self.inv_frame);
                (a, a)
            }
        };
        [
            -f / self.m,
            f * self.r / self.inertia,
            y[3],
            dv,
            y[5],
            dvf,
            de,
        ]
    }

    /// One RK4 step's increment of the state.
    fn rk4(&self, mode: Mode, t: f64, y: &Y, h: f64) -> Y {
        let add = |a: &Y, b: &Y, s: f64| std::array::from_fn(|i| a[i] + s * b[i]);
        let k1 = self.rate(mode, t, y);
        let k2 = self.rate(mode, t + h / 2.0, &add(y, &k1, h / 2.0));
        let k3 = self.rate(mode, t + h / 2.0, &add(y, &k2, h / 2.0));
        let k4 = self.rate(mode, t + h, &add(y, &k3, h));
        std::array::from_fn(|i| h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
    }

    /// The slip of the ball's contact point on the cart.
    fn slip(&self, y: &Y) -> f64 {
        y[0] - self.r * y[1] - y[3]
    }

    /// The net push the string friction must hold on a cart at rest relative to the frame.
    fn push(&self, mode: Mode, t: f64, y: &Y) -> f64 {
        self.share() * self.force(mode, t, y).0 - self.k * (y[2] - y[4])
    }

    /// The ball's event function (positive once its phase has ended) and the cart's.
    fn events(&self, mode: Mode, t: f64, y: &Y) -> (f64, f64) {
        let (f, de) = self.force(mode, t, y);
        let ball = match mode.0 {
            // A compliant ball's patch slips at (v_x - r omega - V) - e'.
            Ball::Slide(dir) => -dir * (self.slip(y) - de),
            Ball::Grip => f.abs() - self.mu * self.normal(t),
        };
        let cart = match mode.1 {
            _ if self.fc == 0.0 => -1.0,
            Cart::Moving(dir) => -dir * (y[3] - y[5]),
            Cart::Held => self.push(mode, t, y).abs() - self.fc,
        };
        (ball, cart)
    }

    /// The rigid ball's mode once the cart moves in `dir` and the slip is zero: grip if it can hold.
    fn ball_on_moving_cart(&self, t: f64, y: &Y, dir: f64, before: Ball) -> Ball {
        let fs = self.static_friction(y, dir);
        if fs.abs() <= self.mu * self.normal(t) {
            Ball::Grip
        } else {
            match before {
                Ball::Slide(s) => Ball::Slide(-s),
                Ball::Grip => Ball::Slide(fs.signum()),
            }
        }
    }

    /// The rigid ball's slip reached zero on a held cart, or a moving cart stopped under a gripping
    /// ball: held if the spring alone cannot move it, else moving the way the spring pulls.
    fn rigid_at_rest_gripping(&self, t: f64, y: &Y, before: Ball) -> Mode {
        let spring = self.k * (y[2] - y[4]);
        if spring.abs() <= self.fc {
            (Ball::Grip, Cart::Held)
        } else {
            let dir = (-spring).signum();
            (
                self.ball_on_moving_cart(t, y, dir, before),
                Cart::Moving(dir),
            )
        }
    }

    /// What follows the rigid ball's event (`ball_fired`) or the cart's.
    fn next_rigid(&self, (ball, cart): Mode, ball_fired: bool, t: f64, y: &Y) -> Mode {
        match (ball, cart, ball_fired) {
            (Ball::Slide(_), Cart::Moving(dir), true) => {
                (self.ball_on_moving_cart(t, y, dir, ball), cart)
            }
            (Ball::Slide(_), Cart::Held, true) => self.rigid_at_rest_gripping(t, y, ball),
            (Ball::Slide(_), _, false) => {
                let push = self.push((ball, cart), t, y);
                if cart != Cart::Held && push.abs() <= self.fc {
                    (ball, Cart::Held)
                } else {
                    (ball, Cart::Moving(push.signum()))
                }
            }
            (Ball::Grip, Cart::Moving(dir), true) => {
                (Ball::Slide(self.static_friction(y, dir).signum()), cart)
            }
            (Ball::Grip, Cart::Moving(_), false) => self.rigid_at_rest_gripping(t, y, ball),
            (Ball::Grip, Cart::Held, _) => (ball, cart),
        }
    }

    /// What follows the compliant ball's event or the cart's: the patch grips when it stops slipping
    /// and slides the way F points when the grip breaks; a cart at rest is held while the string
    /// friction can hold it, else moves the way it is pushed (F is continuous across every event).
    fn next_compliant(&self, (ball, cart): Mode, fired: (bool, bool), t: f64, y: &Y) -> Mode {
        let ball = if fired.0 {
            match ball {
                Ball::Slide(_) => Ball::Grip,
                Ball::Grip => Ball::Slide(self.force((ball, cart), t, y).0.signum()),
            }
        } else {
            ball
        };
        let cart = if fired.1 {
            let push = self.push((ball, cart), t, y);
            if cart != Cart::Held && push.abs() <= self.fc {
                Cart::Held
            } else {
                Cart::Moving(push.signum())
            }
        } else {
            cart
        };
        (ball, cart)
    }
}

/// A running sum kept with the rounding error of each addition (Kahan's compensated summation). The
/// clock and the state add up to millions of steps; added plainly, the clock drifts by up to half an ulp
/// a step, always the same way for a fixed step (1e-11 s over 1.5e7 steps of 8 ms), and the cart's and
/// the frame's positions likewise (1e-12 m): enough to move the release velocity of a 20 mg cart ringing
/// at 60 000 rad/s by 1e-7 m/s, a hundred times the agreement asked.
#[derive(Clone, Copy)]
struct Compensated<const N: usize> {
    sum: [f64; N],
    carry: [f64; N],
}

impl<const N: usize> Compensated<N> {
    fn new(sum: [f64; N]) -> Self {
        Self {
            sum,
            carry: [0.0; N],
        }
    }

    /// The sum with `step` added: the value the events are tested on is the value kept.
    fn plus(&self, step: &[f64; N]) -> Self {
        let mut next = *self;
        for (i, step) in step.iter().enumerate() {
            let z = step - self.carry[i];
            next.sum[i] = self.sum[i] + z;
            next.carry[i] = (next.sum[i] - self.sum[i]) - z;
        }
        next
    }
}

/// Integrates one bounce on a free frame of mass `p.frame_mass` (0: clamped) with steps of at most
/// `max_step` seconds: a rigid ball, or a compliant one when `p.ball_stiffness` > 0, with string
/// friction `p.cart_friction` between the cart and the frame. The frame's normal effective mass sets
/// the normal force through the apparent restitution.
pub fn integrate_frame(p: &Params, max_step: f64) -> FrameNumerical {
    assert!(max_step > 0.0, "a step of {max_step} s");
    let theta = p.angle_deg.to_radians();
    let vx1 = p.speed * theta.cos();
    let vy1 = p.speed * theta.sin();
    let normal_mass = if p.frame_normal_mass > 0.0 {
        p.frame_normal_mass
    } else {
        p.frame_mass
    };
    let ey = if normal_mass > 0.0 {
        (p.ey * normal_mass - p.mass) / (normal_mass + p.mass)
    } else {
        p.ey
    };
    let m_eff = p.mass * p.alpha / (1.0 + p.alpha);
    let model = Model {
        m: p.mass,
        r: p.radius,
        inertia: p.alpha * p.mass * p.radius * p.radius,
        big_m: p.cart_mass,
        inv_frame: if p.frame_mass > 0.0 {
            1.0 / p.frame_mass
        } else {
            0.0
        },
        k: p.stiffness,
        mu: p.mu,
        fc: p.cart_friction,
        n0: (1.0 + ey) * PI * p.mass * vy1 / (2.0 * p.duration),
        w: PI / p.duration,
        kb: p.ball_stiffness,
        cb: 2.0 * p.ball_damping * (p.ball_stiffness * m_eff).sqrt(),
    };
    let end = p.duration;
    let y: Y = [vx1, p.spin, 0.0, 0.0, 0.0, 0.0, 0.0];
    let slip0 = model.slip(&y);
    let scale = vx1.abs() + p.radius * p.spin.abs();
    // An undamped compliant ball grips at once if its spring can take up the arriving slip.
    let rolls = slip0.abs() <= 1e-12 * scale
        || (model.compliant()
            && model.cb == 0.0
            && model.kb * slip0.abs() <= model.mu * model.n0 * model.w);
    let ball = if rolls {
        Ball::Grip
    } else {
        Ball::Slide(slip0.signum())
    };
    // At first contact nothing pushes the cart: string friction holds it.
    let cart = if model.fc > 0.0 {
        Cart::Held
    } else {
        Cart::Moving(0.0)
    };
    let mut mode = (ball, cart);
    let mut held = cart == Cart::Held;
    // An event is taken once it rises 1e-13 of its scale above zero: a release of a held cart found
    // 1e-11 late (in force) starts a 20 mg cart ringing at 60 000 rad/s 3e-14 s late, enough to move its
    // release velocity by 3e-9 of its peak after a few such releases.
    let force_tolerance = 1e-13 * (model.mu * model.n0 + model.fc);
    let speed_tolerance = 1e-13 * (scale + 1.0);
    let tolerances = |(ball, cart): Mode| {
        let ball = match ball {
            Ball::Slide(_) => speed_tolerance,
            Ball::Grip => force_tolerance,
        };
        let cart = match cart {
            Cart::Moving(_) => speed_tolerance,
            Cart::Held => force_tolerance,
        };
        (ball, cart)
    };
    let fired = |mode: Mode, t: f64, y: &Y| {
        let (ball, cart) = model.events(mode, t, y);
        let (ball_tolerance, cart_tolerance) = tolerances(mode);
        (ball > ball_tolerance, cart > cart_tolerance)
    };
    let ended = |mode: Mode, t: f64, y: &Y| {
        let (ball, cart) = fired(mode, t, y);
        ball || cart
    };
    // The clock and the state are sums of up to millions of steps, each kept with its rounding error.
    let mut clock = Compensated::new([0.0]);
    let mut state = Compensated::new(y);
    let mut phases = 1;
    while clock.sum[0] < end {
        let (t, y) = (clock.sum[0], state.sum);
        let h = max_step.min(end - t);
        let next = state.plus(&model.rk4(mode, t, &y, h));
        if !ended(mode, clock.plus(&[h]).sum[0], &next.sum) {
            clock = clock.plus(&[h]);
            state = next;
            continue;
        }
        // Bisect the step for the first time an event rises above its tolerance.
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            let ym = state.plus(&model.rk4(mode, t, &y, mid));
            if ended(mode, clock.plus(&[mid]).sum[0], &ym.sum) {
                hi = mid;
            } else {
                lo = mid;
            }
            if hi - lo <= 1e-16 * end {
                break;
            }
        }
        state = state.plus(&model.rk4(mode, t, &y, hi));
        clock = clock.plus(&[hi]);
        let (t, y) = (clock.sum[0], &mut state.sum);
        if t >= end * (1.0 - 1e-12) {
            break;
        }
        let events = fired(mode, t, y);
        if events.1 && matches!(mode.1, Cart::Moving(_)) {
            // The cart stopped relative to the frame: the two move on together, momentum kept.
            let body = 1.0 + model.big_m * model.inv_frame;
            let common = (model.big_m * model.inv_frame * y[3] + y[5]) / body;
            y[3] = common;
            y[5] = common;
            state.carry[3] = 0.0;
            state.carry[5] = 0.0;
        }
        let y = &state.sum;
        mode = if model.compliant() {
            model.next_compliant(mode, events, t, y)
        } else {
            model.next_rigid(mode, events.0, t, y)
        };
        held |= mode.1 == Cart::Held;
        phases += 1;
        if phases > 100_000 {
            break;
        }
    }
    let y = state.sum;
    FrameNumerical {
        vx2: y[0],
        omega2: y[1],
        v2: y[3],
        vf2: y[5],
        stretch2: y[2] - y[4],
        e2: y[6],
        phases,
        held,
    }
}
