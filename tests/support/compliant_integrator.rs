//! An independent numerical solution of the compliant ball on the single cart: RK4 on the equations of
//! motion, with every event located by bisection of the step. Shares nothing with the solver but the
//! parameters.
//!
//! State y = (v_x, omega, X, V, e), e = u - p the stretch of the ball's spring. The force on the ball,
//! positive backward, is F; the cart feels +F.
//! - slide (dir): F = dir mu N(t); e' = (F - k_b e)/c_b (e' = F'/k_b without damping);
//! - grip: e' = v_x - r omega - V (the patch moves with the cart); F = k_b e + c_b e'.
//!
//! The slide ends when the patch's slip (v_x - r omega - V) - e' reaches zero (then grip); the grip
//! ends when |F| reaches mu N (then slide the way F points).
//!
//! String friction F_c on the cart (`cart_friction`): moving in direction d, M V' = F - k X - d F_c,
//! until V reaches zero; then the cart is held (X' = V' = 0) while |F - k X| <= F_c, and otherwise moves
//! the way F - k X pushes it. The cart starts held when F_c > 0.

use snapback::model::Params;
use std::f64::consts::PI;

#[allow(dead_code)] // not every test file reads every field
#[derive(Clone, Copy, Debug)]
pub struct Reference {
    pub vx2: f64,
    pub omega2: f64,
    pub x: f64,
    pub v: f64,
    pub e: f64,
    pub phases: usize,
    /// Whether string friction held the cart at some time.
    pub stuck: bool,
}

struct Model {
    m: f64,
    r: f64,
    inertia: f64,
    big_m: f64,
    k: f64,
    mu: f64,
    n0: f64,
    w: f64,
    kb: f64,
    cb: f64,
    fc: f64,
}

type Y = [f64; 5];

/// What the cart does: moving in direction +1 or -1 (0 without string friction), or held (`None`).
type Cart = Option<f64>;

impl Model {
    fn normal(&self, t: f64) -> f64 {
        self.n0 * (self.w * t).sin().max(0.0)
    }
    /// (F, e') in mode `dir` (0 = grip).
    fn force(&self, dir: f64, t: f64, y: &Y) -> (f64, f64) {
        if dir == 0.0 {
            let de = y[0] - self.r * y[1] - y[3];
            (self.kb * y[4] + self.cb * de, de)
        } else {
            let f = dir * self.mu * self.normal(t);
            let de = if self.cb > 0.0 {
                (f - self.kb * y[4]) / self.cb
            } else {
                dir * self.mu * self.n0 * self.w * (self.w * t).cos() / self.kb
            };
            (f, de)
        }
    }
    fn rate(&self, (dir, cart): (f64, Cart), t: f64, y: &Y) -> Y {
        let (f, de) = self.force(dir, t, y);
        let (dx, dv) = match cart {
            Some(d) => (y[3], (f - self.k * y[2] - d * self.fc) / self.big_m),
            None => (0.0, 0.0),
        };
        [-f / self.m, self.r * f / self.inertia, dx, dv, de]
    }
    fn rk4(&self, mode: (f64, Cart), t: f64, y: &Y, h: f64) -> Y {
        let add = |a: &Y, b: &Y, s: f64| -> Y { std::array::from_fn(|i| a[i] + s * b[i]) };
        let k1 = self.rate(mode, t, y);
        let k2 = self.rate(mode, t + h / 2.0, &add(y, &k1, h / 2.0));
        let k3 = self.rate(mode, t + h / 2.0, &add(y, &k2, h / 2.0));
        let k4 = self.rate(mode, t + h, &add(y, &k3, h));
        std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
    }
    /// The ball's event function in mode `dir`: positive once the phase has ended; and the direction
    /// of the next slide (0 = grip).
    fn event(&self, dir: f64, t: f64, y: &Y) -> (f64, f64) {
        let (f, de) = self.force(dir, t, y);
        if dir == 0.0 {
            let limit = self.mu * self.normal(t);
            (f.abs() - limit, f.signum())
        } else {
            let slip = y[0] - self.r * y[1] - y[3] - de;
            (-dir * slip, 0.0)
        }
    }
    /// The cart's event function: positive once a moving cart has reversed or a held one is pushed
    /// harder than F_c (never without string friction).
    fn cart_event(&self, (dir, cart): (f64, Cart), t: f64, y: &Y) -> f64 {
        if self.fc == 0.0 {
            return -1.0;
        }
        match cart {
            Some(d) => -d * y[3],
            None => (self.force(dir, t, y).0 - self.k * y[2]).abs() - self.fc,
        }
    }
    /// A held cart, or one moving the way the net force pushes it.
    fn cart_at_rest(&self, dir: f64, t: f64, y: &Y) -> Cart {
        let push = self.force(dir, t, y).0 - self.k * y[2];
        (push.abs() > self.fc).then(|| push.signum())
    }
}

/// Integrates one bounce with `steps` RK4 steps over the contact.
pub fn integrate(p: &Params, steps: usize) -> Reference {
    let m_eff = p.mass * p.alpha / (1.0 + p.alpha);
    let vx1 = p.speed * (90.0 - p.angle_deg).to_radians().sin();
    let vy1 = p.speed * (90.0 - p.angle_deg).to_radians().cos();
    let model = Model {
        m: p.mass,
        r: p.radius,
        inertia: p.alpha * p.mass * p.radius * p.radius,
        big_m: p.cart_mass,
        k: p.stiffness,
        mu: p.mu,
        n0: (1.0 + p.ey) * PI * p.mass * vy1 / (2.0 * p.duration),
        w: PI / p.duration,
        kb: p.ball_stiffness,
        cb: 2.0 * p.ball_damping * (p.ball_stiffness * m_eff).sqrt(),
        fc: p.cart_friction,
    };
    let end = p.duration;
    let h = end / steps as f64;
    let mut y: Y = [vx1, p.spin, 0.0, 0.0, 0.0];
    let slip0 = vx1 - p.radius * p.spin;
    let scale = vx1.abs() + p.radius * p.spin.abs();
    let mut dir = if slip0.abs() <= 1e-12 * scale
        || (model.cb == 0.0 && model.kb * slip0.abs() <= model.mu * model.n0 * model.w)
    {
        0.0
    } else {
        slip0.signum()
    };
    let mut cart: Cart = if model.fc > 0.0 { None } else { Some(0.0) };
    let mut stuck = cart.is_none();
    let force_scale = model.mu * model.n0;
    let speed_scale = scale + 1.0;
    let tolerance = |dir: f64| {
        if dir == 0.0 {
            1e-11 * force_scale
        } else {
            1e-11 * speed_scale
        }
    };
    let cart_tolerance = |cart: Cart| match cart {
        Some(_) => 1e-11 * speed_scale,
        None => 1e-11 * (force_scale + model.fc),
    };
    let ended = |mode: (f64, Cart), t: f64, y: &Y| {
        model.event(mode.0, t, y).0 > tolerance(mode.0)
            || model.cart_event(mode, t, y) > cart_tolerance(mode.1)
    };
    let mut t = 0.0;
    let mut phases = 1;
    while t < end {
        let step = h.min(end - t);
        let next = model.rk4((dir, cart), t, &y, step);
        if !ended((dir, cart), t + step, &next) {
            y = next;
            t += step;
            continue;
        }
        // Bisect the step for the first time an event rises above its tolerance.
        let (mut lo, mut hi) = (0.0, step);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let ym = model.rk4((dir, cart), t, &y, mid);
            if ended((dir, cart), t + mid, &ym) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        y = model.rk4((dir, cart), t, &y, hi);
        t += hi;
        let (ball_event, next_dir) = model.event(dir, t, &y);
        let cart_fired = model.cart_event((dir, cart), t, &y) > cart_tolerance(cart);
        if cart_fired {
            if cart.is_some() {
                y[3] = 0.0;
            }
            cart = model.cart_at_rest(dir, t, &y);
            stuck |= cart.is_none();
        }
        if ball_event > tolerance(dir) {
            dir = next_dir;
        }
        phases += 1;
        if phases > 100_000 {
            break;
        }
    }
    Reference {
        vx2: y[0],
        omega2: y[1],
        x: y[2],
        v: y[3],
        e: y[4],
        phases,
        stuck,
    }
}
