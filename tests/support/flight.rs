//! An independent flight for the shot tests: classic fixed-step RK4 on (x, y, vx, vy) with the issue's
//! forces written out again (gravity 9.81, air 1.21 kg/m^3, Stepanek's C_D and C_L), events bisected on the
//! step size from the start of the step that crosses them, and the rigid-surface bounce of the paper's
//! model in closed form. Nothing here calls the solver.

/// Time step, s: RK4's error at 1e-4 s is far below a micrometre over a shot.
const DT: f64 = 1e-4;

pub struct Ball {
    pub mass: f64,
    pub radius: f64,
    pub alpha: f64,
}

fn derivative(ball: &Ball, omega: f64, s: [f64; 4]) -> [f64; 4] {
    let (vx, vy) = (s[2], s[3]);
    let v = (vx * vx + vy * vy).sqrt();
    let area = std::f64::consts::PI * ball.radius * ball.radius;
    let (mut ax, mut ay) = (0.0, -9.81);
    if v > 0.0 {
        let spin_speed = ball.radius * omega.abs();
        let (cd, cl) = if spin_speed == 0.0 {
            (0.55, 0.0)
        } else {
            let q = v / spin_speed;
            (
                0.55 + 1.0 / (22.5 + 4.2 * q.powf(2.5)).powf(0.4),
                1.0 / (2.0 + q),
            )
        };
        let q = 0.5 * 1.21 * area * v / ball.mass;
        // Drag against v; lift along omega_z z x v = omega_z (-vy, vx).
        ax += -q * cd * vx - q * cl * omega.signum() * vy;
        ay += -q * cd * vy + q * cl * omega.signum() * vx;
    }
    [vx, vy, ax, ay]
}

fn rk4(ball: &Ball, omega: f64, s: [f64; 4], h: f64) -> [f64; 4] {
    let add = |a: [f64; 4], k: [f64; 4], f: f64| std::array::from_fn(|i| a[i] + f * k[i]);
    let k1 = derivative(ball, omega, s);
    let k2 = derivative(ball, omega, add(s, k1, h / 2.0));
    let k3 = derivative(ball, omega, add(s, k2, h / 2.0));
    let k4 = derivative(ball, omega, add(s, k3, h));
    std::array::from_fn(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// Flies until `event(state)` turns from positive to zero or below; returns the state there.
pub fn fly_until(
    ball: &Ball,
    omega: f64,
    mut s: [f64; 4],
    event: impl Fn(&[f64; 4]) -> f64,
) -> [f64; 4] {
    for _ in 0..2_000_000 {
        let next = rk4(ball, omega, s, DT);
        if event(&s) > 0.0 && event(&next) <= 0.0 {
            let (mut lo, mut hi) = (0.0, DT);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if event(&rk4(ball, omega, s, mid)) > 0.0 {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            return rk4(ball, omega, s, hi);
        }
        s = next;
    }
    panic!("the reference flight never ended");
}

/// The rigid-surface bounce of Cross's model: slip s = v_x - r omega falls under sliding friction
/// mu N at the rate (1 + 1/alpha) mu N / m; if it reaches zero the ball rolls out (angular momentum about
/// the contact point kept), otherwise it slides throughout. `vx` along the surface, `vy` towards it,
/// `omega` in the paper's sense; returns (vx2, vy2 away, omega2).
pub fn rigid_bounce(
    ball: &Ball,
    mu: f64,
    ey: f64,
    vx: f64,
    vy: f64,
    omega: f64,
) -> (f64, f64, f64) {
    let impulse = (1.0 + ey) * vy;
    let slip = vx - ball.radius * omega;
    if slip.abs() > mu * (1.0 + 1.0 / ball.alpha) * impulse {
        let push = slip.signum() * mu * impulse;
        (
            vx - push,
            ey * vy,
            omega + push / (ball.alpha * ball.radius),
        )
    } else {
        let vx2 = (vx + ball.alpha * ball.radius * omega) / (1.0 + ball.alpha);
        (vx2, ey * vy, vx2 / ball.radius)
    }
}

/// What the reference finds for a shot launched from (0, height) with velocity (vx, vy) and spin
/// omega_z: net clearance, landing x, kick height.
pub struct Outcome {
    pub clearance: Option<f64>,
    pub landing: Option<f64>,
    pub kick: Option<f64>,
}

#[allow(clippy::too_many_arguments)]
pub fn shot(
    ball: &Ball,
    height: f64,
    vx: f64,
    vy: f64,
    omega_z: f64,
    court_mu: f64,
    court_ey: f64,
) -> Outcome {
    let (net, net_height, baseline, r) = (11.885, 0.914, 23.77, ball.radius);
    let mut out = Outcome {
        clearance: None,
        landing: None,
        kick: None,
    };
    let start = [0.0, height, vx, vy];
    let first = fly_until(ball, omega_z, start, |s| (net - s[0]).min(s[1] - r));
    if first[1] - r <= 1e-9 && first[0] < net {
        return out;
    }
    let clearance = first[1] - r - net_height;
    out.clearance = Some(clearance);
    if clearance <= 0.0 {
        return out;
    }
    let land = fly_until(ball, omega_z, first, |s| s[1] - r);
    out.landing = Some(land[0]);
    if land[0] >= baseline {
        return out;
    }
    // The court: normal up; along +x the paper's spin is -omega_z.
    let forward = land[2] >= 0.0;
    let (along, paper_spin) = if forward {
        (land[2], -omega_z)
    } else {
        (-land[2], omega_z)
    };
    let (vx2, vy2, omega2) = rigid_bounce(ball, court_mu, court_ey, along, -land[3], paper_spin);
    let (vx2, omega_z2) = if forward {
        (vx2, -omega2)
    } else {
        (-vx2, omega2)
    };
    if vy2 <= 0.0 {
        return out;
    }
    let kick = fly_until(ball, omega_z2, [land[0], r, vx2, vy2], |s| {
        (baseline - s[0]).min(s[1] - r)
    });
    if kick[0] >= baseline - 1e-9 && kick[1] > r {
        out.kick = Some(kick[1]);
    }
    out
}
