//! An independent solution of the ball-on-cart model by numerical integration: classical fixed-step RK4
//! on the equations of motion (vx, omega, X, V), with each transition located by bisection on the step
//! length. It shares nothing with the exact solver but the equations of the paper.

use snapback::model::Params;

#[derive(Clone, Copy, Debug)]
pub struct Numerical {
    pub vx2: f64,
    pub omega2: f64,
    pub x2: f64,
    pub v2: f64,
    /// "slide" / "grip" per phase.
    pub phases: usize,
}

#[derive(Clone, Copy, PartialEq)]
enum Mode {
    Slide(f64),
    Grip,
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
}

type Y = [f64; 4]; // vx, omega, X, V

impl Model {
    fn normal(&self, t: f64) -> f64 {
        self.n0 * (self.w * t).sin()
    }

    /// Static friction that keeps the contact point moving with the cart, Eq. (5).
    fn static_friction(&self, x: f64) -> f64 {
        self.m * self.k * x
            / (self.big_m * (1.0 + self.m / self.big_m + self.m * self.r * self.r / self.inertia))
    }

    fn friction(&self, mode: Mode, t: f64, y: &Y) -> f64 {
        match mode {
            Mode::Slide(dir) => dir * self.mu * self.normal(t),
            Mode::Grip => self.static_friction(y[2]),
        }
    }

    /// Eqs. (1)-(3) while sliding; while gripping the ball obeys the same Newton laws with F_s.
    fn rate(&self, mode: Mode, t: f64, y: &Y) -> Y {
        let f = self.friction(mode, t, y);
        [
            -f / self.m,
            f * self.r / self.inertia,
            y[3],
            (f - self.k * y[2]) / self.big_m,
        ]
    }

    fn rk4(&self, mode: Mode, t: f64, y: &Y, h: f64) -> Y {
        let add = |a: &Y, b: &Y, s: f64| {
            [
                a[0] + s * b[0],
                a[1] + s * b[1],
                a[2] + s * b[2],
                a[3] + s * b[3],
            ]
        };
        let k1 = self.rate(mode, t, y);
        let k2 = self.rate(mode, t + h / 2.0, &add(y, &k1, h / 2.0));
        let k3 = self.rate(mode, t + h / 2.0, &add(y, &k2, h / 2.0));
        let k4 = self.rate(mode, t + h, &add(y, &k3, h));
        let mut out = *y;
        for i in 0..4 {
            out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        out
    }

    fn slip(&self, y: &Y) -> f64 {
        y[0] - self.r * y[1] - y[3]
    }

    /// Positive once the phase must end.
    fn event(&self, mode: Mode, t: f64, y: &Y) -> f64 {
        match mode {
            Mode::Slide(dir) => -dir * self.slip(y),
            Mode::Grip => self.static_friction(y[2]).abs() - self.mu * self.normal(t),
        }
    }
}

/// Integrates one bounce with steps of at most `max_step` seconds.
pub fn integrate(p: &Params, max_step: f64) -> Numerical {
    let theta = p.angle_deg.to_radians();
    let vx1 = p.speed * theta.cos();
    let vy1 = p.speed * theta.sin();
    let model = Model {
        m: p.mass,
        r: p.radius,
        inertia: p.alpha * p.mass * p.radius * p.radius,
        big_m: p.cart_mass,
        k: p.stiffness,
        mu: p.mu,
        n0: (1.0 + p.ey) * std::f64::consts::PI * p.mass * vy1 / (2.0 * p.duration),
        w: std::f64::consts::PI / p.duration,
    };
    let end = p.duration;
    let mut y: Y = [vx1, p.spin, 0.0, 0.0];
    let slip0 = model.slip(&y);
    let mut mode = if slip0 == 0.0 {
        Mode::Grip
    } else {
        Mode::Slide(slip0.signum())
    };
    let mut t = 0.0;
    let mut phases = 1;
    // The event function right after a transition sits on zero; ignore it for a few nanoseconds.
    let mut guard_until = 0.0;
    while t < end {
        let h = max_step.min(end - t);
        let next = model.rk4(mode, t, &y, h);
        let crossed = t + h > guard_until && model.event(mode, t + h, &next) > 0.0;
        if !crossed {
            t += h;
            y = next;
            continue;
        }
        // Bisect the step length for the crossing.
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            let ym = model.rk4(mode, t, &y, mid);
            if t + mid > guard_until && model.event(mode, t + mid, &ym) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
            if hi - lo < 1e-16 {
                break;
            }
        }
        y = model.rk4(mode, t, &y, hi);
        t += hi;
        if t >= end * (1.0 - 1e-12) {
            break;
        }
        mode = match mode {
            Mode::Slide(dir) => {
                let fs = model.static_friction(y[2]);
                if fs.abs() <= model.mu * model.normal(t) {
                    Mode::Grip
                } else {
                    Mode::Slide(-dir)
                }
            }
            Mode::Grip => Mode::Slide(if y[2] < 0.0 { -1.0 } else { 1.0 }),
        };
        phases += 1;
        guard_until = t + 1e-9;
    }
    Numerical {
        vx2: y[0],
        omega2: y[1],
        x2: y[2],
        v2: y[3],
        phases,
    }
}
