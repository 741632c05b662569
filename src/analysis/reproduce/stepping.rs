//! The paper's own numerical method (Sec. III), as a program of its time would run it: Eqs. (1)-(6)
//! stepped by forward Euler at a fixed step h, Eq. (3) while the ball slides and Eq. (6), with the
//! static friction of Eq. (5), while it grips; each transition taken at the end of the step in which it
//! happens. A printed number this reproduces at a plausible step is a demonstrated cause of a small
//! difference from the exact solution. Rigid ball, single cart, no string friction: the paper's cases.

use crate::model::Params;

/// One step's end: time, cart displacement and velocity, s, m, m/s, and whether the ball grips.
#[derive(Clone, Copy, Debug)]
pub struct Step {
    pub t: f64,
    pub x: f64,
    pub v: f64,
    pub grip: bool,
}

/// Steps tried, s: from T/5000 to T/100 for the paper's T = 5 ms.
pub const STEPS: [f64; 6] = [1e-6, 2e-6, 5e-6, 1e-5, 2e-5, 5e-5];

/// The bounce of `p` stepped at `h`: the state at the end of every step.
pub fn run(p: &Params, h: f64) -> Vec<Step> {
    let theta = p.angle_deg.to_radians();
    let (m, r, big_m, k, mu) = (p.mass, p.radius, p.cart_mass, p.stiffness, p.mu);
    let inertia = p.alpha * m * r * r;
    // Eq. (5): F_s = m k X / (M (1 + m/M + m r^2/I)).
    let gain = m * k / (big_m * (1.0 + m / big_m + m * r * r / inertia));
    let n0 = (1.0 + p.ey) * std::f64::consts::PI * m * p.speed * theta.sin() / (2.0 * p.duration);
    let normal = |t: f64| n0 * (std::f64::consts::PI * t / p.duration).sin();
    let (mut vx, mut omega, mut x, mut v) = (p.speed * theta.cos(), p.spin, 0.0, 0.0);
    let mut grip = false;
    let steps = (p.duration / h).round() as usize;
    let mut out = Vec::with_capacity(steps);
    for i in 0..steps {
        let t = i as f64 * h;
        let limit = mu * normal(t);
        let slip = vx - r * omega - v;
        let mut f = gain * x;
        if grip && f.abs() > limit {
            grip = false;
        }
        if !grip {
            f = limit * slip.signum();
        }
        // Eqs. (1)-(3), or (6) while gripping, one Euler step.
        (vx, omega, x, v) = (
            vx - f / m * h,
            omega + f * r / inertia * h,
            x + v * h,
            v + (f - k * x) / big_m * h,
        );
        let t = (i + 1) as f64 * h;
        if !grip && (vx - r * omega - v) * slip <= 0.0 {
            grip = (gain * x).abs() <= mu * normal(t);
        }
        out.push(Step { t, x, v, grip });
    }
    out
}

/// The steps at which `quantity` of the stepped bounce of `case` prints as `printed` (`prints` says
/// whether a value does), described for a note; `None` when no step does.
pub fn cause(
    case: &Params,
    prints: impl Fn(f64) -> bool,
    unit: &str,
    quantity: impl Fn(&[Step]) -> f64,
) -> Option<String> {
    let found: Vec<String> = STEPS
        .iter()
        .map(|&h| (h, quantity(&run(case, h))))
        .filter(|&(_, value)| prints(value))
        .map(|(h, value)| format!("{:.0} µs: {value:.4} {unit}", h * 1e6))
        .collect();
    (!found.is_empty()).then(|| {
        format!(
            "the paper's own method (Euler steps, each transition at the end of its step) prints it \
             at a step of {}",
            found.join(", ")
        )
    })
}

/// The largest `f` over the steps, and when.
pub fn peak(steps: &[Step], f: impl Fn(&Step) -> f64) -> (f64, f64) {
    steps.iter().map(|s| (s.t, f(s))).fold(
        (0.0, f64::NEG_INFINITY),
        |a, b| if b.1 > a.1 { b } else { a },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::timeline;
    use crate::model::{Params, solve};

    #[test]
    fn fine_steps_converge_on_the_exact_bounce() {
        for (mass, stiffness) in [(10.0, 4e4), (0.01, 4e4), (0.01, 1.5e4)] {
            let p = Params {
                cart_mass: mass,
                stiffness,
                ..Params::default()
            };
            let exact = solve(&p).unwrap();
            let steps = run(&p, 2e-8);
            let grip = steps.iter().find(|s| s.grip).unwrap().t;
            let first = exact.phases[timeline::first_grip(&exact).unwrap()].start;
            assert!((grip - first).abs() < 1e-7, "{grip} {first}");
            let (_, x_max) = timeline::peak(&exact, |s| s.x);
            let stepped = peak(&steps, |s| s.x).1;
            assert!(
                (stepped - x_max).abs() < 1e-4 * x_max.abs(),
                "{stepped} {x_max}"
            );
            let end = steps.last().unwrap();
            assert!((end.t - p.duration).abs() < 1e-12);
            assert!(
                (end.v - exact.final_state.v).abs() < 1e-3,
                "{} {}",
                end.v,
                exact.final_state.v
            );
        }
    }
}
