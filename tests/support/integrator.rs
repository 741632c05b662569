//! An independent solution of the ball-on-cart model by numerical integration: classical fixed-step RK4
//! on the equations of motion (vx, omega, X, V), with each transition located by bisection on the step
//! length. It shares nothing with the exact solver but the equations of the paper, and decides what
//! follows each transition by its own plain rules. String friction on the cart (a Coulomb force F_c
//! against its motion, holding it still while the push on it is at most F_c) is included.

use snapback::model::Params;

#[allow(dead_code)] // not every test file reads every field
#[derive(Clone, Copy, Debug)]
pub struct Numerical {
    pub vx2: f64,
    pub omega2: f64,
    pub x2: f64,
    pub v2: f64,
    /// How many phases the ball and cart went through.
    pub phases: usize,
    /// How many phases the ball went through (a slide, a grip, a slide the other way), whatever the cart
    /// did meanwhile.
    pub ball_phases: usize,
    /// Whether the ball gripped at any time.
    pub gripped: bool,
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Ball {
    Slide(f64),
    Grip,
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Cart {
    Moving(f64),
    Stuck,
}

struct Model {
    m: f64,
    r: f64,
    inertia: f64,
    big_m: f64,
    k: f64,
    mu: f64,
    fc: f64,
    n0: f64,
    w: f64,
}

type Y = [f64; 4]; // vx, omega, X, V

impl Model {
    fn normal(&self, t: f64) -> f64 {
        self.n0 * (self.w * t).sin()
    }

    /// The ball's effective mass at the contact point.
    fn m_eff(&self) -> f64 {
        1.0 / (1.0 / self.m + self.r * self.r / self.inertia)
    }

    /// Static friction that keeps the contact point moving with a cart that moves in `dir`: Eq. (5)
    /// with the string friction added to the spring force.
    fn static_friction(&self, x: f64, dir: f64) -> f64 {
        self.m_eff() * (self.k * x + dir * self.fc) / (self.big_m + self.m_eff())
    }

    fn friction(&self, ball: Ball, cart: Cart, t: f64, y: &Y) -> f64 {
        match (ball, cart) {
            (Ball::Slide(dir), _) => dir * self.mu * self.normal(t),
            (Ball::Grip, Cart::Moving(dir)) => self.static_friction(y[2], dir),
            (Ball::Grip, Cart::Stuck) => 0.0,
        }
    }

    fn rate(&self, ball: Ball, cart: Cart, t: f64, y: &Y) -> Y {
        let f = self.friction(ball, cart, t, y);
        let (dx, dv) = match cart {
            Cart::Moving(dir) => (y[3], (f - self.k * y[2] - dir * self.fc) / self.big_m),
            Cart::Stuck => (0.0, 0.0),
        };
        [-f / self.m, f * self.r / self.inertia, dx, dv]
    }

    fn rk4(&self, ball: Ball, cart: Cart, t: f64, y: &Y, h: f64) -> Y {
        let add = |a: &Y, b: &Y, s: f64| {
            [
                a[0] + s * b[0],
                a[1] + s * b[1],
                a[2] + s * b[2],
                a[3] + s * b[3],
            ]
        };
        let k1 = self.rate(ball, cart, t, y);
        let k2 = self.rate(ball, cart, t + h / 2.0, &add(y, &k1, h / 2.0));
        let k3 = self.rate(ball, cart, t + h / 2.0, &add(y, &k2, h / 2.0));
        let k4 = self.rate(ball, cart, t + h, &add(y, &k3, h));
        let mut out = *y;
        for i in 0..4 {
            out[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        out
    }

    fn slip(&self, y: &Y) -> f64 {
        y[0] - self.r * y[1] - y[3]
    }

    /// Whether the ball's event (the slip reached zero, or the grip broke) and the cart's (it stopped,
    /// or came unstuck) have happened.
    fn events(&self, ball: Ball, cart: Cart, t: f64, y: &Y) -> (bool, bool) {
        let f = self.friction(ball, cart, t, y);
        let ball_event = match ball {
            Ball::Slide(dir) => -dir * self.slip(y) > 0.0,
            Ball::Grip => f.abs() > self.mu * self.normal(t),
        };
        let cart_event = match cart {
            Cart::Moving(dir) => self.fc > 0.0 && -dir * y[3] > 0.0,
            Cart::Stuck => (f - self.k * y[2]).abs() > self.fc,
        };
        (ball_event, cart_event)
    }

    fn ended(&self, ball: Ball, cart: Cart, t: f64, y: &Y) -> bool {
        let (ball_event, cart_event) = self.events(ball, cart, t, y);
        ball_event || cart_event
    }

    /// The ball's mode once the cart moves in `dir` and the slip is zero: grip if it can hold.
    fn ball_on_moving_cart(&self, t: f64, x: f64, dir: f64, sliding: Ball) -> Ball {
        let fs = self.static_friction(x, dir);
        if fs.abs() <= self.mu * self.normal(t) {
            Ball::Grip
        } else {
            match sliding {
                Ball::Slide(s) => Ball::Slide(-s),
                Ball::Grip => Ball::Slide(fs.signum()),
            }
        }
    }

    fn next(&self, ball: Ball, cart: Cart, ball_fired: bool, t: f64, y: &mut Y) -> (Ball, Cart) {
        let x = y[2];
        match (ball, cart, ball_fired) {
            // The slip reached zero.
            (Ball::Slide(_), Cart::Moving(dir), true) => {
                (self.ball_on_moving_cart(t, x, dir, ball), cart)
            }
            (Ball::Slide(_), Cart::Stuck, true) => {
                if (self.k * x).abs() <= self.fc {
                    (Ball::Grip, Cart::Stuck)
                } else {
                    let dir = (-self.k * x).signum();
                    (self.ball_on_moving_cart(t, x, dir, ball), Cart::Moving(dir))
                }
            }
            // The moving cart came to rest under a sliding ball.
            (Ball::Slide(s), Cart::Moving(_), false) => {
                y[3] = 0.0;
                let push = s * self.mu * self.normal(t) - self.k * x;
                if push.abs() <= self.fc {
                    (ball, Cart::Stuck)
                } else {
                    (ball, Cart::Moving(push.signum()))
                }
            }
            // The stuck cart was pushed free.
            (Ball::Slide(s), Cart::Stuck, false) => {
                let push = s * self.mu * self.normal(t) - self.k * x;
                (ball, Cart::Moving(push.signum()))
            }
            // The grip broke.
            (Ball::Grip, Cart::Moving(dir), true) => {
                (Ball::Slide(self.static_friction(x, dir).signum()), cart)
            }
            // The cart came to rest under a gripping ball.
            (Ball::Grip, Cart::Moving(_), false) => {
                y[3] = 0.0;
                if (self.k * x).abs() <= self.fc {
                    (Ball::Grip, Cart::Stuck)
                } else {
                    let dir = (-self.k * x).signum();
                    (self.ball_on_moving_cart(t, x, dir, ball), Cart::Moving(dir))
                }
            }
            (Ball::Grip, Cart::Stuck, _) => (ball, cart),
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
        fc: p.cart_friction,
        n0: (1.0 + p.ey) * std::f64::consts::PI * p.mass * vy1 / (2.0 * p.duration),
        w: std::f64::consts::PI / p.duration,
    };
    let end = p.duration;
    let mut y: Y = [vx1, p.spin, 0.0, 0.0];
    let slip0 = model.slip(&y);
    let mut ball = if slip0 == 0.0 {
        Ball::Grip
    } else {
        Ball::Slide(slip0.signum())
    };
    let mut cart = if p.cart_friction > 0.0 {
        Cart::Stuck
    } else {
        Cart::Moving(1.0)
    };
    let mut t = 0.0;
    let mut phases = 1;
    let mut ball_phases = 1;
    let mut gripped = ball == Ball::Grip;
    // An event function right after a transition sits on zero; ignore it for a few nanoseconds.
    let mut guard_until = 0.0;
    while t < end {
        let h = max_step.min(end - t);
        let next = model.rk4(ball, cart, t, &y, h);
        let crossed = t + h > guard_until && model.ended(ball, cart, t + h, &next);
        if !crossed {
            t += h;
            y = next;
            continue;
        }
        // Bisect the step length for the crossing.
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            let ym = model.rk4(ball, cart, t, &y, mid);
            if t + mid > guard_until && model.ended(ball, cart, t + mid, &ym) {
                hi = mid;
            } else {
                lo = mid;
            }
            if hi - lo < 1e-16 {
                break;
            }
        }
        y = model.rk4(ball, cart, t, &y, hi);
        t += hi;
        if t >= end * (1.0 - 1e-12) {
            break;
        }
        let ball_fired = model.events(ball, cart, t, &y).0;
        let before = ball;
        (ball, cart) = model.next(ball, cart, ball_fired, t, &mut y);
        phases += 1;
        ball_phases += usize::from(ball != before);
        gripped |= ball == Ball::Grip;
        guard_until = t + 1e-9;
    }
    Numerical {
        vx2: y[0],
        omega2: y[1],
        x2: y[2],
        v2: y[3],
        phases,
        ball_phases,
        gripped,
    }
}
