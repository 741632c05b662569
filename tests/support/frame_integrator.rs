//! An independent solution of the ball on a cart whose spring is tied to a free frame (issue 23), by
//! numerical integration: classical fixed-step RK4 on (v_x, omega, x1, V, x_f, V_f) with each transition
//! located by bisection on the step length. It shares nothing with the exact solver but the equations:
//! M x1'' = F - k (x1 - x_f), M_t x_f'' = k (x1 - x_f), the ball's Eqs. (1), (2), and the paper's rules
//! (grip while |F_s| <= mu N, else slide the way F_s pulls). No string friction.

use snapback::model::Params;

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
    pub phases: usize,
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Ball {
    Slide(f64),
    Grip,
}

struct Model {
    m: f64,
    r: f64,
    inertia: f64,
    big_m: f64,
    frame: f64,
    k: f64,
    mu: f64,
    n0: f64,
    w: f64,
}

type Y = [f64; 6]; // vx, omega, x1, V, x_f, V_f

impl Model {
    fn normal(&self, t: f64) -> f64 {
        self.n0 * (self.w * t).sin()
    }

    fn m_eff(&self) -> f64 {
        1.0 / (1.0 / self.m + self.r * self.r / self.inertia)
    }

    /// The static friction that keeps the contact point on the cart: the cart (with the ball's m_eff on
    /// it) accelerates at -k y/(M + m_eff), and the ball's contact point with it.
    fn static_friction(&self, y: &Y) -> f64 {
        self.m_eff() * self.k * (y[2] - y[4]) / (self.big_m + self.m_eff())
    }

    fn friction(&self, ball: Ball, t: f64, y: &Y) -> f64 {
        match ball {
            Ball::Slide(dir) => dir * self.mu * self.normal(t),
            Ball::Grip => self.static_friction(y),
        }
    }

    fn rate(&self, ball: Ball, t: f64, y: &Y) -> Y {
        let f = self.friction(ball, t, y);
        let spring = self.k * (y[2] - y[4]);
        [
            -f / self.m,
            f * self.r / self.inertia,
            y[3],
            (f - spring) / self.big_m,
            y[5],
            spring / self.frame,
        ]
    }

    fn rk4(&self, ball: Ball, t: f64, y: &Y, h: f64) -> Y {
        let add = |a: &Y, b: &Y, s: f64| std::array::from_fn(|i| a[i] + s * b[i]);
        let k1 = self.rate(ball, t, y);
        let k2 = self.rate(ball, t + h / 2.0, &add(y, &k1, h / 2.0));
        let k3 = self.rate(ball, t + h / 2.0, &add(y, &k2, h / 2.0));
        let k4 = self.rate(ball, t + h, &add(y, &k3, h));
        std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
    }

    fn slip(&self, y: &Y) -> f64 {
        y[0] - self.r * y[1] - y[3]
    }

    fn ended(&self, ball: Ball, t: f64, y: &Y) -> bool {
        match ball {
            Ball::Slide(dir) => -dir * self.slip(y) > 0.0,
            Ball::Grip => self.static_friction(y).abs() > self.mu * self.normal(t),
        }
    }

    fn next(&self, ball: Ball, t: f64, y: &Y) -> Ball {
        let fs = self.static_friction(y);
        match ball {
            Ball::Grip => Ball::Slide(fs.signum()),
            Ball::Slide(s) if fs.abs() > self.mu * self.normal(t) => Ball::Slide(-s),
            Ball::Slide(_) => Ball::Grip,
        }
    }
}

/// Integrates one bounce on a free frame with steps of at most `max_step` seconds. The frame's normal
/// effective mass sets the normal force through the apparent restitution.
pub fn integrate_frame(p: &Params, max_step: f64) -> FrameNumerical {
    let theta = p.angle_deg.to_radians();
    let vx1 = p.speed * theta.cos();
    let vy1 = p.speed * theta.sin();
    let normal_mass = if p.frame_normal_mass > 0.0 {
        p.frame_normal_mass
    } else {
        p.frame_mass
    };
    let ey = (p.ey * normal_mass - p.mass) / (normal_mass + p.mass);
    let model = Model {
        m: p.mass,
        r: p.radius,
        inertia: p.alpha * p.mass * p.radius * p.radius,
        big_m: p.cart_mass,
        frame: p.frame_mass,
        k: p.stiffness,
        mu: p.mu,
        n0: (1.0 + ey) * std::f64::consts::PI * p.mass * vy1 / (2.0 * p.duration),
        w: std::f64::consts::PI / p.duration,
    };
    let end = p.duration;
    let mut y: Y = [vx1, p.spin, 0.0, 0.0, 0.0, 0.0];
    let slip0 = model.slip(&y);
    let mut ball = if slip0 == 0.0 {
        Ball::Grip
    } else {
        Ball::Slide(slip0.signum())
    };
    let mut t = 0.0;
    let mut phases = 1;
    // An event function right after a transition sits on zero; ignore it for a few nanoseconds.
    let mut guard_until = 0.0;
    while t < end {
        let h = max_step.min(end - t);
        let next = model.rk4(ball, t, &y, h);
        if !(t + h > guard_until && model.ended(ball, t + h, &next)) {
            t += h;
            y = next;
            continue;
        }
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            let ym = model.rk4(ball, t, &y, mid);
            if t + mid > guard_until && model.ended(ball, t + mid, &ym) {
                hi = mid;
            } else {
                lo = mid;
            }
            if hi - lo < 1e-16 {
                break;
            }
        }
        y = model.rk4(ball, t, &y, hi);
        t += hi;
        if t >= end * (1.0 - 1e-12) {
            break;
        }
        ball = model.next(ball, t, &y);
        phases += 1;
        guard_until = t + 1e-9;
    }
    FrameNumerical {
        vx2: y[0],
        omega2: y[1],
        v2: y[3],
        vf2: y[5],
        stretch2: y[2] - y[4],
        phases,
    }
}
