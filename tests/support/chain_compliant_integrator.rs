//! An independent numerical solution of the compliant ball on a chain of masses: classical RK4 on the
//! 2N + 3 equations of motion, with every transition located by bisection of the step. It shares nothing
//! with the solver but the parameters.
//!
//! The chain: N equal masses M/N at X_1..X_N (velocities V_i), springs of stiffness kappa = N k between
//! neighbours and from the last mass to the wall; the ball touches the first mass. The ball: v_x and
//! omega, and the stretch e of its tangential contact spring k_b (dashpot c_b = 2 zeta sqrt(k_b m_eff),
//! m_eff = m alpha/(1 + alpha)). The force on the ball, positive backward, is F: m v_x' = -F,
//! I omega' = r F, and the first mass feels +F besides its springs.
//! - slide (dir = ±1): the patch slides on the first mass, F = dir mu N(t); the stretch follows
//!   c_b e' = F - k_b e (e' = F'/k_b without a dashpot); the patch slips on the first mass at
//!   (v_x - r omega - V_1) - e';
//! - grip: the patch moves with the first mass, e' = v_x - r omega - V_1, and F = k_b e + c_b e'.
//!
//! A slide ends when the patch's slip reaches zero (then grip); a grip ends when |F| reaches mu N (then
//! slide the way F points). The contact starts gripping when the ball arrives rolling, or, without a
//! dashpot, when the spring's initial rate k_b |slip0| does not beat the friction limit's mu N0 w;
//! otherwise it slides the way the arriving slip points.
//!
//! String friction F_c on the first mass (`cart_friction`): moving in direction d, it feels -d F_c
//! besides F and its springs, until V_1 reaches zero; then it is held (X_1' = V_1' = 0) while
//! |F - S_1| <= F_c, S_1 = kappa (X_1 - X_2) its spring (kappa X_1 alone), and otherwise moves the way
//! F - S_1 pushes it. It starts held when F_c > 0 (and the ball's first force cannot push it free).
//! While it is held the patch grips or slides on a still surface and the masses behind swing against it.
//!
//! On a free frame (`frame_mass` > 0, issue 23) the last spring goes to one more mass, the frame M_t,
//! and nothing to the wall; the normal impulse carries the apparent restitution
//! e_A = (e_y M_n - m)/(M_n + m) (M_n = M_t unless given). String friction then acts between the first
//! mass and the frame: moving relative to the frame in direction d, -d F_c on the first mass and
//! +d F_c on the frame, until V_1 - V_f reaches zero (the first mass then takes the frame's velocity);
//! held, the first mass and the frame move as one body, a_B = (F - S_1 - S_f)/(M/N + M_t) with S_f
//! the frame's spring, while the force the frame gives the first mass, F - S_1 - (M/N) a_B, stays
//! within ±F_c.
//!
//! Three more components ride along as quadratures of the energy budget: the friction loss
//! ∫ F (patch slip) dt over the slides, the dashpot loss ∫ c_b e'² dt and the string friction's loss
//! ∫ F_c |V_1 - V_f| dt (V_f = 0 on the wall).

use snapback::model::Params;
use std::f64::consts::PI;

/// The longest chain.
const MAX_LINKS: usize = 16;
/// v_x, omega, X_1..X_N (and X_f), V_1..V_N (and V_f), e, friction loss, dashpot loss, string friction
/// loss (the first 2N + 6, or 2N + 8 on a frame, are used).
const DIM: usize = 2 * (MAX_LINKS + 1) + 6;
type Y = [f64; DIM];

/// At most this many phases; a chattering bounce stops there (and says so in `capped`).
const MAX_PHASES: usize = 20_000;

/// Where the incoming tangential energy went, J.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// The ball's tangential kinetic energy on arrival, m v_x1²/2 + I omega1²/2.
    pub initial: f64,
    /// The ball's tangential kinetic energy at T.
    pub ball: f64,
    /// Kinetic plus spring energy of the whole chain at T (the frame's kinetic energy apart).
    pub chain: f64,
    /// k_b e(T)²/2.
    pub ball_spring: f64,
    /// ∫ F (patch slip) dt over the slides.
    pub friction_loss: f64,
    /// ∫ c_b e'² dt.
    pub dashpot_loss: f64,
    /// ∫ F_c |V_1 - V_f| dt.
    pub string_loss: f64,
}

impl Budget {
    /// (initial - everything accounted for) / initial.
    #[allow(dead_code)] // not every test file checks the budget
    pub fn residual(&self) -> f64 {
        (self.initial
            - self.ball
            - self.chain
            - self.ball_spring
            - self.friction_loss
            - self.dashpot_loss
            - self.string_loss)
            / self.initial
    }
}

#[derive(Clone, Debug)]
#[allow(dead_code)] // not every test file reads every field
pub struct Reference {
    pub vx2: f64,
    pub omega2: f64,
    /// Every mass's displacement at T, the first (the one the ball touches) first, the frame last.
    pub x: Vec<f64>,
    /// Every mass's velocity at T.
    pub v: Vec<f64>,
    /// The frame's velocity at T (0 clamped).
    pub frame_v: f64,
    /// m v_x and every mass's momentum along the surface at T.
    pub momentum: f64,
    /// The stretch of the ball's spring at T.
    pub e: f64,
    /// The number of phases.
    pub phases: usize,
    /// Each phase's slip sign in order: +1 or -1 sliding, 0 gripping.
    pub kinds: Vec<i8>,
    /// Each transition's time (one fewer than the phases).
    pub transitions: Vec<f64>,
    /// True when the bounce stopped at [`MAX_PHASES`] (chatter) before T.
    pub capped: bool,
    /// Whether string friction held the first mass at some time, and how often it stopped after moving.
    pub held: bool,
    pub stops: usize,
    pub energy: Budget,
}

struct Model {
    /// The masses: the N links, and the frame when it is free.
    n: usize,
    links: usize,
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
    n0: f64,
    w: f64,
    kb: f64,
    cb: f64,
    fc: f64,
}

/// What the first mass does: moving in direction +1 or -1 (0 without string friction), or held
/// (`None`).
type Cart = Option<f64>;

impl Model {
    fn new(p: &Params) -> Model {
        let links = p.chain as usize;
        assert!((1..=MAX_LINKS).contains(&links) && links as f64 == p.chain);
        let framed = p.frame_mass > 0.0;
        let n = links + usize::from(framed);
        let vy1 = p.speed * (90.0 - p.angle_deg).to_radians().cos();
        let m_eff = p.mass * p.alpha / (1.0 + p.alpha);
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
        Model {
            n,
            links,
            frame: p.frame_mass,
            m: p.mass,
            r: p.radius,
            inertia: p.alpha * p.mass * p.radius * p.radius,
            link: p.cart_mass / links as f64,
            kappa: p.stiffness * links as f64,
            mu: p.mu,
            n0: (1.0 + ey) * PI * p.mass * vy1 / (2.0 * p.duration),
            w: PI / p.duration,
            kb: p.ball_stiffness,
            cb: 2.0 * p.ball_damping * (p.ball_stiffness * m_eff).sqrt(),
            fc: p.cart_friction,
        }
    }

    fn dim(&self) -> usize {
        2 * self.n + 6
    }
    fn xi(&self, i: usize) -> usize {
        2 + i
    }
    fn vi(&self, i: usize) -> usize {
        2 + self.n + i
    }
    fn ei(&self) -> usize {
        2 + 2 * self.n
    }

    fn normal(&self, t: f64) -> f64 {
        self.n0 * (self.w * t).sin().max(0.0)
    }

    /// v_x - r omega - V_1: how fast the ball's contact point moves over the first mass.
    fn contact_slip(&self, y: &Y) -> f64 {
        y[0] - self.r * y[1] - y[self.vi(0)]
    }

    /// (F, e') in mode `dir` (0 = grip).
    fn force(&self, dir: f64, t: f64, y: &Y) -> (f64, f64) {
        let e = y[self.ei()];
        if dir == 0.0 {
            let de = self.contact_slip(y);
            (self.kb * e + self.cb * de, de)
        } else {
            let f = dir * self.mu * self.normal(t);
            let de = if self.cb > 0.0 {
                (f - self.kb * e) / self.cb
            } else {
                dir * self.mu * self.n0 * self.w * (self.w * t).cos() / self.kb
            };
            (f, de)
        }
    }

    /// The chain's springs on mass i, pulling it back towards rest.
    fn spring(&self, y: &Y, i: usize) -> f64 {
        let x = |j: usize| y[self.xi(j)];
        let behind = if i > 0 { x(i) - x(i - 1) } else { 0.0 };
        let ahead = if i + 1 < self.n {
            x(i) - x(i + 1)
        } else if i < self.links {
            x(i)
        } else {
            0.0
        };
        self.kappa * (behind + ahead)
    }

    /// Mass i: a link, or the frame.
    fn mass(&self, i: usize) -> f64 {
        if i < self.links {
            self.link
        } else {
            self.frame
        }
    }

    /// True on a free frame (the last mass).
    fn framed(&self) -> bool {
        self.n > self.links
    }

    /// The first mass's velocity relative to the frame (to the wall).
    fn relative(&self, y: &Y) -> f64 {
        if self.framed() {
            y[self.vi(0)] - y[self.vi(self.n - 1)]
        } else {
            y[self.vi(0)]
        }
    }

    /// The acceleration of the held body of first mass and frame under the ball's force `f` (0 on the
    /// wall, where the first mass stays still).
    fn held_accel(&self, f: f64, y: &Y) -> f64 {
        if self.framed() {
            let springs = self.spring(y, 0) + self.spring(y, self.n - 1);
            (f - springs) / (self.link + self.frame)
        } else {
            0.0
        }
    }

    /// The force the string friction must give the held first mass to keep it with the frame (still
    /// on the wall): F - S_1 - (M/N) a_B.
    fn held_push(&self, f: f64, y: &Y) -> f64 {
        f - self.spring(y, 0) - self.link * self.held_accel(f, y)
    }

    fn rate(&self, (dir, cart): (f64, Cart), t: f64, y: &Y) -> Y {
        let (f, de) = self.force(dir, t, y);
        let mut out = [0.0; DIM];
        out[0] = -f / self.m;
        out[1] = self.r * f / self.inertia;
        let frame = self.n - 1;
        for i in 0..self.n {
            out[self.xi(i)] = y[self.vi(i)];
            let push = match (i, cart) {
                (0, Some(d)) => f - d * self.fc,
                (i, Some(d)) if i == frame && self.framed() => d * self.fc,
                _ => 0.0,
            };
            out[self.vi(i)] = (push - self.spring(y, i)) / self.mass(i);
        }
        if cart.is_none() && self.framed() {
            // The first mass moves with the frame, one body.
            let a = self.held_accel(f, y);
            (out[self.vi(0)], out[self.vi(frame)]) = (a, a);
        } else if cart.is_none() {
            out[self.xi(0)] = 0.0;
            out[self.vi(0)] = 0.0;
        }
        let ei = self.ei();
        out[ei] = de;
        out[ei + 1] = if dir == 0.0 {
            0.0
        } else {
            f * (self.contact_slip(y) - de)
        };
        out[ei + 2] = self.cb * de * de;
        out[ei + 3] = self.fc * self.relative(y).abs();
        out
    }

    fn rk4(&self, mode: (f64, Cart), t: f64, y: &Y, h: f64) -> Y {
        let d = self.dim();
        let add = |a: &Y, b: &Y, s: f64| -> Y {
            let mut out = [0.0; DIM];
            for i in 0..d {
                out[i] = a[i] + s * b[i];
            }
            out
        };
        let k1 = self.rate(mode, t, y);
        let k2 = self.rate(mode, t + h / 2.0, &add(y, &k1, h / 2.0));
        let k3 = self.rate(mode, t + h / 2.0, &add(y, &k2, h / 2.0));
        let k4 = self.rate(mode, t + h, &add(y, &k3, h));
        let mut out = [0.0; DIM];
        for i in 0..d {
            out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        out
    }

    /// The event function of mode `dir`, positive once the phase has ended, and the mode that follows.
    fn event(&self, dir: f64, t: f64, y: &Y) -> (f64, f64) {
        let (f, de) = self.force(dir, t, y);
        if dir == 0.0 {
            (f.abs() - self.mu * self.normal(t), f.signum())
        } else {
            let patch_slip = self.contact_slip(y) - de;
            (-dir * patch_slip, 0.0)
        }
    }

    /// The first mass's event function: positive once a moving one has reversed or a held one is pushed
    /// harder than F_c (never without string friction).
    fn cart_event(&self, (dir, cart): (f64, Cart), t: f64, y: &Y) -> f64 {
        if self.fc == 0.0 {
            return -1.0;
        }
        match cart {
            Some(d) => -d * self.relative(y),
            None => self.held_push(self.force(dir, t, y).0, y).abs() - self.fc,
        }
    }

    /// A held first mass, or one moving the way the net force pushes it.
    fn cart_at_rest(&self, dir: f64, t: f64, y: &Y) -> Cart {
        let push = self.held_push(self.force(dir, t, y).0, y);
        (push.abs() > self.fc).then(|| push.signum())
    }

    fn budget(&self, vx1: f64, omega1: f64, y: &Y) -> Budget {
        let (n, links) = (self.n, self.links);
        let ball = |vx: f64, omega: f64| 0.5 * (self.m * vx * vx + self.inertia * omega * omega);
        let kinetic: f64 = (0..links).map(|i| y[self.vi(i)].powi(2)).sum::<f64>() * self.link;
        let stretch: f64 = (0..links)
            .map(|i| {
                let d = if i + 1 < n {
                    y[self.xi(i)] - y[self.xi(i + 1)]
                } else {
                    y[self.xi(i)]
                };
                d * d
            })
            .sum::<f64>()
            * self.kappa;
        let ei = self.ei();
        Budget {
            initial: ball(vx1, omega1),
            ball: ball(y[0], y[1]),
            chain: 0.5 * (kinetic + stretch),
            ball_spring: 0.5 * self.kb * y[ei] * y[ei],
            friction_loss: y[ei + 1],
            dashpot_loss: y[ei + 2],
            string_loss: y[ei + 3],
        }
    }
}

/// Upper bounds on the fastest oscillation (Gershgorin on the stiffnesses over the masses: the chain's
/// springs, and the ball's spring between its m_eff and the first mass) and the fastest decay (the
/// dashpot between m_eff and the first mass while gripping, the stretch's k_b/c_b while sliding), 1/s.
fn rates(p: &Params) -> (f64, f64) {
    let model = Model::new(p);
    let m_eff = 1.0 / (1.0 / model.m + model.r * model.r / model.inertia);
    let both = 1.0 / m_eff + 1.0 / model.link;
    let mut springs = 4.0 * model.kappa / model.link;
    if model.frame > 0.0 {
        springs = springs.max(2.0 * model.kappa / model.frame);
    }
    let oscillation = (springs + 2.0 * model.kb * both).sqrt();
    let decay = if model.cb > 0.0 {
        (model.cb * both).max(model.kb / model.cb)
    } else {
        0.0
    };
    (oscillation.max(model.w), decay.max(model.w))
}

/// An upper bound on the fastest rate in the bounce, 1/s.
#[allow(dead_code)] // not every test file needs it
pub fn fastest(p: &Params) -> f64 {
    let (oscillation, decay) = rates(p);
    oscillation.max(decay)
}

/// A step small against the contact time and the fastest motion: `per_radian` of a radian of the fastest
/// oscillation, ten times that of the fastest decay (RK4 follows a decay accurately at h rate < 0.1),
/// and at most T/20 000.
pub fn step_for(p: &Params, per_radian: f64) -> f64 {
    let (oscillation, decay) = rates(p);
    (p.duration / 20_000.0)
        .min(per_radian / oscillation)
        .min(10.0 * per_radian / decay)
}

/// Integrates one bounce with RK4 steps of at most `max_step` seconds.
pub fn integrate(p: &Params, max_step: f64) -> Reference {
    let model = Model::new(p);
    let n = model.n;
    let vx1 = p.speed * (90.0 - p.angle_deg).to_radians().sin();
    let mut y: Y = [0.0; DIM];
    y[0] = vx1;
    y[1] = p.spin;
    let slip0 = model.contact_slip(&y);
    let scale = vx1.abs() + p.radius * p.spin.abs();
    // Rolling grips; without a dashpot the spring takes up a small slip before the friction limit grows.
    let rolling = slip0.abs() <= 1e-12 * scale;
    let gentle = model.cb == 0.0 && model.kb * slip0.abs() <= model.mu * model.n0 * model.w;
    let mut dir = if rolling || gentle {
        0.0
    } else {
        slip0.signum()
    };
    // An event function sits on zero when its phase starts: it counts as risen only above rounding.
    let tolerance = |dir: f64| {
        if dir == 0.0 {
            1e-11 * model.mu * model.n0
        } else {
            1e-11 * (scale + 1.0)
        }
    };
    let force_scale = model.mu * model.n0;
    let cart_tolerance = |cart: Cart| match cart {
        Some(_) => 1e-11 * (scale + 1.0),
        None => 1e-11 * (force_scale + model.fc),
    };
    // Held at first unless the ball's first force (the dashpot's on a gripping arrival) pushes harder
    // than F_c.
    let mut cart: Cart = Some(0.0);
    if model.fc > 0.0 {
        cart = model.cart_at_rest(dir, 0.0, &y);
    }
    let mut held = cart.is_none();
    let mut stops = 0;
    let ended = |mode: (f64, Cart), t: f64, y: &Y| {
        model.event(mode.0, t, y).0 > tolerance(mode.0)
            || model.cart_event(mode, t, y) > cart_tolerance(mode.1)
    };
    let end = p.duration;
    let mut t = 0.0;
    let mut kinds = vec![dir as i8];
    let mut transitions = vec![];
    let mut capped = false;
    while t < end {
        let h = max_step.min(end - t);
        let next = model.rk4((dir, cart), t, &y, h);
        if !ended((dir, cart), t + h, &next) {
            y = next;
            t += h;
            continue;
        }
        // The shortest part of the step after which the event function has risen.
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let ym = model.rk4((dir, cart), t, &y, mid);
            if ended((dir, cart), t + mid, &ym) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        y = model.rk4((dir, cart), t, &y, hi);
        t += hi;
        // A transition within rounding of the end changes nothing.
        if t >= end * (1.0 - 1e-12) {
            break;
        }
        let (ball_event, next_dir) = model.event(dir, t, &y);
        if model.cart_event((dir, cart), t, &y) > cart_tolerance(cart) {
            if cart.is_some() {
                // It stops on the wall, or takes the frame's velocity.
                y[model.vi(0)] = if model.framed() {
                    y[model.vi(n - 1)]
                } else {
                    0.0
                };
                stops += 1;
            }
            cart = model.cart_at_rest(dir, t, &y);
            held |= cart.is_none();
        }
        if ball_event > tolerance(dir) {
            dir = next_dir;
        }
        kinds.push(dir as i8);
        transitions.push(t);
        if kinds.len() >= MAX_PHASES {
            capped = true;
            break;
        }
    }
    Reference {
        vx2: y[0],
        omega2: y[1],
        x: (0..n).map(|i| y[model.xi(i)]).collect(),
        v: (0..n).map(|i| y[model.vi(i)]).collect(),
        frame_v: if model.frame > 0.0 {
            y[model.vi(n - 1)]
        } else {
            0.0
        },
        momentum: model.m * y[0] + (0..n).map(|i| model.mass(i) * y[model.vi(i)]).sum::<f64>(),
        e: y[model.ei()],
        phases: kinds.len(),
        kinds,
        transitions,
        capped,
        held,
        stops,
        energy: model.budget(vx1, p.spin, &y),
    }
}
