//! An independent solution of the ball on a chain of masses and springs by numerical integration:
//! classical fixed-step RK4 on the 2N + 2 equations of motion (v_x, omega, and each mass's X_i and V_i),
//! each transition located by bisection on the step length. It shares nothing with the exact solver (no
//! modes, no closed forms) but the equations: masses M/N, springs N k from the first mass through the
//! last to the wall, the ball's friction F on the first mass; sliding F = dir mu N, gripping the static
//! friction that keeps the contact point moving with the first mass, F_s = m_eff (K X)_1 / (M/N + m_eff).
//! On a free frame (`frame_mass` > 0, issue 23) the last spring goes to one more mass, the frame M_t, and
//! nothing to the wall; the normal impulse carries the apparent restitution e_A = (e_y M_n - m)/(M_n + m).
//! Its own plain rules decide what follows each transition: at zero slip, grip if |F_s| <= mu N, else the
//! friction reverses; a broken grip slides the way F_s pulled.
//!
//! String friction on the first mass (`cart_friction`, F_c): a Coulomb force against its motion, which
//! holds it still while the push on it, F - (K X)_1, is at most F_c (the ball rolling on it needs no
//! friction then). Gripping a moving first mass, F_s = m_eff ((K X)_1 + d F_c) / (M/N + m_eff).
//!
//! On a free frame the string friction acts between the first mass and the frame: moving relative to
//! the frame in direction d, -d F_c on the first mass and +d F_c on the frame; held, the two move as one
//! body at a_B = (F - (K X)_1 - (K X)_f) / (M/N + M_t) (a gripping ball then needs F_s = -m_eff a_B,
//! so its m_eff joins the body), while the force the frame must give the first mass,
//! push = F - (K X)_1 - (M/N) a_B, is at most F_c. On the wall a_B = 0 and this is the clamped rule.

use snapback::model::Params;

#[allow(dead_code)] // not every test file reads every field
#[derive(Clone, Copy, Debug)]
pub struct Numerical {
    pub vx2: f64,
    pub omega2: f64,
    /// The first mass's velocity at the end.
    pub v2: f64,
    /// Kinetic plus spring energy of the chain at the end (the frame's kinetic energy apart).
    pub chain_energy: f64,
    /// The first mass's displacement at the end, relative to the frame.
    pub x1: f64,
    /// The frame's velocity at the end (0 clamped).
    pub frame_v: f64,
    /// The momentum along the surface at the end of the ball (m v_x), the chain and the frame.
    pub momentum: f64,
    pub phases: usize,
    /// Phases of the ball alone: a change of the first mass's motion under a ball that slides on does
    /// not count.
    pub ball_phases: usize,
    /// Whether string friction held the first mass still at some time.
    pub stuck: bool,
    /// Whether the ball gripped at any time.
    pub gripped: bool,
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Ball {
    Slide(f64),
    Grip,
}

/// The first mass: moving in a direction, or held by string friction.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Cart {
    Moving(f64),
    Stuck,
}

struct Model {
    n: usize,
    /// The masses: the N links, then the frame when it is free.
    dof: usize,
    /// The frame's mass M_t (0: the wall).
    frame: f64,
    m: f64,
    r: f64,
    inertia: f64,
    /// Each mass, M/N.
    link: f64,
    /// Each spring, N k.
    kappa: f64,
    mu: f64,
    /// String friction on the first mass.
    fc: f64,
    n0: f64,
    w: f64,
}

/// v_x, omega, then X_1..X_N (and X_f), then V_1..V_N (and V_f).
type Y = Vec<f64>;

impl Model {
    fn normal(&self, t: f64) -> f64 {
        self.n0 * (self.w * t).sin()
    }

    fn m_eff(&self) -> f64 {
        1.0 / (1.0 / self.m + self.r * self.r / self.inertia)
    }

    /// The spring force on mass i (0-based), pulling back: (K X)_i.
    fn spring(&self, y: &Y, i: usize) -> f64 {
        let x = |j: usize| y[2 + j];
        let left = if i > 0 { x(i) - x(i - 1) } else { 0.0 };
        let right = if i + 1 < self.dof {
            x(i) - x(i + 1)
        } else if i < self.n {
            x(i)
        } else {
            0.0
        };
        self.kappa * (left + right)
    }

    /// Mass i: a link, or the frame.
    fn mass(&self, i: usize) -> f64 {
        if i < self.n { self.link } else { self.frame }
    }

    /// The static friction that keeps the contact point moving with a first mass moving in `dir`.
    fn static_friction(&self, y: &Y, dir: f64) -> f64 {
        self.m_eff() * (self.spring(y, 0) + dir * self.fc) / (self.link + self.m_eff())
    }

    fn friction(&self, ball: Ball, cart: Cart, t: f64, y: &Y) -> f64 {
        match (ball, cart) {
            (Ball::Slide(dir), _) => dir * self.mu * self.normal(t),
            (Ball::Grip, Cart::Moving(dir)) => self.static_friction(y, dir),
            (Ball::Grip, Cart::Stuck) => self.held_friction(y),
        }
    }

    /// The spring forces on the held body of first mass and frame, pulling back: (K X)_1 + (K X)_f
    /// (0 on the wall, where nothing holds the body but the wall).
    fn held_springs(&self, y: &Y) -> f64 {
        if self.dof > self.n {
            self.spring(y, 0) + self.spring(y, self.n)
        } else {
            0.0
        }
    }

    /// The held body's acceleration a_B under the ball's friction `f` (0 on the wall).
    fn held_accel(&self, f: f64, y: &Y) -> f64 {
        if self.dof > self.n {
            (f - self.held_springs(y)) / (self.link + self.frame)
        } else {
            0.0
        }
    }

    /// The static friction of a ball gripping the held body, -m_eff a_B (0 on the wall: it rolls).
    fn held_friction(&self, y: &Y) -> f64 {
        let m_eff = self.m_eff();
        m_eff * self.held_springs(y) / (self.link + self.frame + m_eff)
    }

    /// The force the string friction must give the held first mass (forward positive) to keep it
    /// with the frame (on the wall, still) under the ball's friction `f`: F - (K X)_1 - (M/N) a_B.
    fn held_push(&self, f: f64, y: &Y) -> f64 {
        f - self.spring(y, 0) - self.link * self.held_accel(f, y)
    }

    /// The first mass's velocity relative to the frame (to the wall).
    fn relative(&self, y: &Y) -> f64 {
        let v1 = y[2 + self.dof];
        if self.dof > self.n {
            v1 - y[2 + self.dof + self.n]
        } else {
            v1
        }
    }

    fn rate(&self, ball: Ball, cart: Cart, t: f64, y: &Y) -> Y {
        let f = self.friction(ball, cart, t, y);
        let n = self.dof;
        let mut out = vec![0.0; 2 + 2 * n];
        out[0] = -f / self.m;
        out[1] = f * self.r / self.inertia;
        for i in 0..n {
            out[2 + i] = y[2 + n + i];
            let push = match (i, cart) {
                (0, Cart::Moving(dir)) => f - dir * self.fc,
                (i, Cart::Moving(dir)) if i == self.n => dir * self.fc,
                (0, Cart::Stuck) => f,
                _ => 0.0,
            };
            out[2 + n + i] = (push - self.spring(y, i)) / self.mass(i);
        }
        if cart == Cart::Stuck {
            // The first mass moves with the frame (stays on the wall).
            let a = self.held_accel(f, y);
            out[2] = if n > self.n { y[2 + n + self.n] } else { 0.0 };
            out[2 + n] = a;
            if n > self.n {
                out[2 + n + self.n] = a;
            }
        }
        out
    }

    fn rk4(&self, (ball, cart): (Ball, Cart), t: f64, y: &Y, h: f64) -> Y {
        let add = |a: &Y, b: &Y, s: f64| -> Y { a.iter().zip(b).map(|(a, b)| a + s * b).collect() };
        let k1 = self.rate(ball, cart, t, y);
        let k2 = self.rate(ball, cart, t + h / 2.0, &add(y, &k1, h / 2.0));
        let k3 = self.rate(ball, cart, t + h / 2.0, &add(y, &k2, h / 2.0));
        let k4 = self.rate(ball, cart, t + h, &add(y, &k3, h));
        (0..y.len())
            .map(|i| h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
            .collect()
    }

    fn slip(&self, y: &Y) -> f64 {
        y[0] - self.r * y[1] - y[2 + self.dof]
    }

    /// Whether the ball's event (the slip reached zero, or the grip broke) and the first mass's (it
    /// stopped, or was pushed free) have happened.
    fn events(&self, (ball, cart): (Ball, Cart), t: f64, y: &Y) -> (bool, bool) {
        let f = self.friction(ball, cart, t, y);
        let ball_event = match ball {
            Ball::Slide(dir) => -dir * self.slip(y) > 0.0,
            Ball::Grip => f.abs() > self.mu * self.normal(t),
        };
        let cart_event = match cart {
            Cart::Moving(dir) => self.fc > 0.0 && -dir * self.relative(y) > 0.0,
            Cart::Stuck => self.held_push(f, y).abs() > self.fc,
        };
        (ball_event, cart_event)
    }

    fn ended(&self, mode: (Ball, Cart), t: f64, y: &Y) -> bool {
        let (ball_event, cart_event) = self.events(mode, t, y);
        ball_event || cart_event
    }

    /// The ball at zero slip on a first mass moving in `dir`: grip if it can hold, else the friction
    /// reverses (or, from a grip, slides the way F_s pulls).
    fn ball_on_moving(&self, t: f64, y: &Y, dir: f64, ball: Ball) -> Ball {
        let fs = self.static_friction(y, dir);
        if fs.abs() <= self.mu * self.normal(t) {
            Ball::Grip
        } else {
            match ball {
                Ball::Slide(s) => Ball::Slide(-s),
                Ball::Grip => Ball::Slide(fs.signum()),
            }
        }
    }

    /// The first mass at rest (relative to the frame) under a gripping ball: held if the push the
    /// held grip needs is within F_c (the ball sliding on if that grip needs more than mu N), else it
    /// moves the way it is pushed.
    fn at_rest_under_grip(&self, t: f64, y: &Y, ball: Ball) -> (Ball, Cart) {
        let held = self.held_friction(y);
        let push = self.held_push(held, y);
        if push.abs() > self.fc {
            let dir = push.signum();
            (self.ball_on_moving(t, y, dir, ball), Cart::Moving(dir))
        } else if held.abs() <= self.mu * self.normal(t) {
            (Ball::Grip, Cart::Stuck)
        } else {
            self.held_slide(t, y, held.signum())
        }
    }

    /// A ball sliding with `s` on a first mass at rest (relative to the frame): held if the push is
    /// within F_c, else moving the way it is pushed.
    fn held_slide(&self, t: f64, y: &Y, s: f64) -> (Ball, Cart) {
        let push = self.held_push(s * self.mu * self.normal(t), y);
        if push.abs() <= self.fc {
            (Ball::Slide(s), Cart::Stuck)
        } else {
            (Ball::Slide(s), Cart::Moving(push.signum()))
        }
    }

    fn next(
        &self,
        (ball, cart): (Ball, Cart),
        ball_fired: bool,
        t: f64,
        y: &mut Y,
    ) -> (Ball, Cart) {
        let n = self.dof;
        // The frame's velocity (0 on the wall), which a first mass that stops takes.
        let rest = if n > self.n { y[2 + n + self.n] } else { 0.0 };
        match (ball, cart, ball_fired) {
            (Ball::Slide(_), Cart::Moving(dir), true) => {
                (self.ball_on_moving(t, y, dir, ball), cart)
            }
            (Ball::Slide(_), Cart::Stuck, true) => self.at_rest_under_grip(t, y, ball),
            // The first mass came to rest under a sliding ball.
            (Ball::Slide(s), Cart::Moving(_), false) => {
                y[2 + n] = rest;
                self.held_slide(t, y, s)
            }
            (Ball::Slide(s), Cart::Stuck, false) => {
                let push = self.held_push(s * self.mu * self.normal(t), y);
                (ball, Cart::Moving(push.signum()))
            }
            (Ball::Grip, Cart::Moving(dir), true) => {
                (Ball::Slide(self.static_friction(y, dir).signum()), cart)
            }
            (Ball::Grip, Cart::Moving(_), false) => {
                y[2 + n] = rest;
                self.at_rest_under_grip(t, y, ball)
            }
            // The grip on the held body broke (never on the wall, where the ball rolls freely).
            (Ball::Grip, Cart::Stuck, true) => {
                self.held_slide(t, y, self.held_friction(y).signum())
            }
            // Pushed free, under a gripping ball.
            (Ball::Grip, Cart::Stuck, false) => {
                let dir = self.held_push(self.held_friction(y), y).signum();
                (self.ball_on_moving(t, y, dir, ball), Cart::Moving(dir))
            }
        }
    }

    /// The links' kinetic energy and every spring's (the frame's kinetic energy apart).
    fn energy(&self, y: &Y) -> f64 {
        let (n, dof) = (self.n, self.dof);
        let kinetic: f64 = (0..n).map(|i| y[2 + dof + i].powi(2)).sum::<f64>() * self.link;
        let stretch: f64 = (0..n)
            .map(|i| {
                let e = if i + 1 < dof {
                    y[2 + i] - y[3 + i]
                } else {
                    y[2 + i]
                };
                e * e
            })
            .sum::<f64>()
            * self.kappa;
        0.5 * (kinetic + stretch)
    }

    /// m v_x and every mass's momentum along the surface.
    fn momentum(&self, y: &Y) -> f64 {
        let dof = self.dof;
        self.m * y[0] + (0..dof).map(|i| self.mass(i) * y[2 + dof + i]).sum::<f64>()
    }
}

/// A step small against the contact time and the fastest mode, which is below 2 sqrt(N k / (M/N))
/// (Gershgorin: the eigenvalues of K/m are at most 4 N k / (M/N), and 2 N k / M_t on the frame's row).
pub fn step_for(p: &Params) -> f64 {
    let n = p.chain;
    let mut fastest =
        (std::f64::consts::PI / p.duration).max(2.0 * n * (p.stiffness / p.cart_mass).sqrt());
    if p.frame_mass > 0.0 {
        fastest = fastest.max((2.0 * n * p.stiffness / p.frame_mass).sqrt());
    }
    (p.duration / 20_000.0).min(0.004 / fastest)
}

/// A running sum kept with the rounding error of each addition (Kahan's compensated summation). The
/// clock and the state add up to millions of steps; added plainly, the clock drifts by up to half an ulp
/// a step, always the same way for a fixed step, and the positions likewise: over 1e6 steps enough to
/// move a 30 mg mass's velocity by 1e-7 m/s.
#[derive(Clone)]
struct Compensated {
    sum: Vec<f64>,
    carry: Vec<f64>,
}

impl Compensated {
    fn new(sum: Vec<f64>) -> Self {
        let carry = vec![0.0; sum.len()];
        Self { sum, carry }
    }

    /// The sum with `step` added.
    fn plus(&self, step: &[f64]) -> Self {
        let mut next = self.clone();
        for (i, step) in step.iter().enumerate() {
            let z = step - self.carry[i];
            next.sum[i] = self.sum[i] + z;
            next.carry[i] = (next.sum[i] - self.sum[i]) - z;
        }
        next
    }
}

/// Integrates one bounce on the chain with steps of at most `max_step` seconds.
pub fn integrate(p: &Params, max_step: f64) -> Numerical {
    let theta = p.angle_deg.to_radians();
    let n = p.chain as usize;
    let framed = p.frame_mass > 0.0;
    let dof = n + usize::from(framed);
    // The apparent restitution on a frame of normal mass M_n (M_t unless given).
    let normal_mass = if p.frame_normal_mass > 0.0 {
        p.frame_normal_mass
    } else {
        p.frame_mass
    };
    let ey = if framed {
        (p.ey * normal_mass - p.mass) / (normal_mass + p.mass)
    } else {
        p.ey
    };
    let model = Model {
        n,
        dof,
        frame: p.frame_mass,
        m: p.mass,
        r: p.radius,
        inertia: p.alpha * p.mass * p.radius * p.radius,
        link: p.cart_mass / n as f64,
        kappa: p.stiffness * n as f64,
        mu: p.mu,
        fc: p.cart_friction,
        n0: (1.0 + ey) * std::f64::consts::PI * p.mass * p.speed * theta.sin() / (2.0 * p.duration),
        w: std::f64::consts::PI / p.duration,
    };
    let end = p.duration;
    let mut y: Y = vec![0.0; 2 + 2 * dof];
    y[0] = p.speed * theta.cos();
    y[1] = p.spin;
    let slip0 = model.slip(&y);
    let ball = if slip0 == 0.0 {
        Ball::Grip
    } else {
        Ball::Slide(slip0.signum())
    };
    let cart = if p.cart_friction > 0.0 {
        Cart::Stuck
    } else {
        Cart::Moving(1.0)
    };
    let mut mode = (ball, cart);
    // The clock and the state are sums of up to millions of steps, each kept with its rounding error.
    let mut clock = Compensated::new(vec![0.0]);
    let mut state = Compensated::new(y);
    let mut phases = 1;
    let mut ball_phases = 1;
    let mut stuck = cart == Cart::Stuck;
    let mut gripped = ball == Ball::Grip;
    // An event function right after a transition sits on zero; ignore it for a few nanoseconds.
    let mut guard_until = 0.0;
    while clock.sum[0] < end {
        let t = clock.sum[0];
        let h = max_step.min(end - t);
        // The events are tested on the values that are kept.
        let after = |step: f64| {
            let y = state.plus(&model.rk4(mode, t, &state.sum, step));
            (clock.plus(&[step]), y)
        };
        let (clock_next, next) = after(h);
        let t_next = clock_next.sum[0];
        let crossed = t_next > guard_until && model.ended(mode, t_next, &next.sum);
        if !crossed {
            (clock, state) = (clock_next, next);
            continue;
        }
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            let (clock_mid, ym) = after(mid);
            let t_mid = clock_mid.sum[0];
            if t_mid > guard_until && model.ended(mode, t_mid, &ym.sum) {
                hi = mid;
            } else {
                lo = mid;
            }
            if hi - lo < 1e-16 {
                break;
            }
        }
        (clock, state) = after(hi);
        let t = clock.sum[0];
        if t >= end * (1.0 - 1e-12) {
            break;
        }
        let ball_fired = model.events(mode, t, &state.sum).0;
        let before = mode.0;
        let kept = state.sum.clone();
        mode = model.next(mode, ball_fired, t, &mut state.sum);
        // A velocity the transition set starts afresh.
        for (i, carry) in state.carry.iter_mut().enumerate() {
            if state.sum[i] != kept[i] {
                *carry = 0.0;
            }
        }
        ball_phases += usize::from(mode.0 != before);
        stuck |= mode.1 == Cart::Stuck;
        gripped |= mode.0 == Ball::Grip;
        phases += 1;
        guard_until = t + 1e-9;
    }
    let y = state.sum;
    Numerical {
        vx2: y[0],
        omega2: y[1],
        v2: y[2 + dof],
        chain_energy: model.energy(&y),
        x1: if framed { y[2] - y[2 + n] } else { y[2] },
        frame_v: if framed { y[2 + dof + n] } else { 0.0 },
        momentum: model.momentum(&y),
        phases,
        ball_phases,
        stuck,
        gripped,
    }
}
