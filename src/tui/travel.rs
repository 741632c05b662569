//! How far the ball has travelled along the surface and how far it has turned, for the schematic.
//!
//! The core gives the ball's velocity v_x and spin omega exactly at any time but not their integrals, so
//! [`Travel`] integrates the exact solution numerically: Simpson's rule on each interval of a fine grid
//! of the bounce (the grid includes every phase transition, so no interval straddles one and the
//! integrands are smooth on each), accumulated once per solve; a time between grid points adds one more
//! Simpson panel from the grid point before it. With [`Travel::INTERVALS`] intervals the error is far below
//! anything a terminal can show.

use crate::model::{Bounce, Sample};

/// The ball's displacement along the surface, integral of v_x dt, and rotation angle, integral of
/// omega dt, at the nodes of a fine grid over the contact.
#[derive(Clone, Debug, PartialEq)]
pub struct Travel {
    /// The grid: the core's series, with both sides of every transition.
    nodes: Vec<Sample>,
    /// Integral of v_x from 0 to each node, m.
    x: Vec<f64>,
    /// Integral of omega from 0 to each node, rad (positive in the sense of positive omega).
    angle: Vec<f64>,
}

/// Simpson's rule for the integral of `value` over `[a.t, b.t]` within phase `a.phase`.
fn simpson(bounce: &Bounce, a: &Sample, b: &Sample, value: fn(&Sample) -> f64) -> f64 {
    let h = b.t - a.t;
    if h <= 0.0 {
        return 0.0;
    }
    let mid = bounce.sample_in(a.phase, a.t + 0.5 * h);
    h / 6.0 * (value(a) + 4.0 * value(&mid) + value(b))
}

fn vx(s: &Sample) -> f64 {
    s.vx
}

fn omega(s: &Sample) -> f64 {
    s.omega
}

impl Travel {
    /// Evenly spaced intervals of the grid (the transitions add a few more).
    pub const INTERVALS: usize = 1000;

    /// Integrates the bounce's v_x and omega over its grid.
    pub fn compute(bounce: &Bounce) -> Travel {
        let nodes = bounce.series(Self::INTERVALS + 1);
        let mut x = Vec::with_capacity(nodes.len());
        let mut angle = Vec::with_capacity(nodes.len());
        let (mut sum_x, mut sum_angle) = (0.0, 0.0);
        for (i, node) in nodes.iter().enumerate() {
            if i > 0 {
                let a = &nodes[i - 1];
                // Both ends of a panel of nonzero width lie in one phase: the grid includes every transition.
                sum_x += simpson(bounce, a, node, vx);
                sum_angle += simpson(bounce, a, node, omega);
            }
            x.push(sum_x);
            angle.push(sum_angle);
        }
        Travel { nodes, x, angle }
    }

    /// The integrals of v_x (m) and omega (rad) from 0 to `t`, clamped to the contact.
    pub fn at(&self, bounce: &Bounce, t: f64) -> (f64, f64) {
        let t = t.clamp(0.0, bounce.setup.duration);
        // The last node at or before t: at a transition, the side of the phase that begins there.
        let i = self.nodes.partition_point(|s| s.t <= t).saturating_sub(1);
        let a = &self.nodes[i];
        if t <= a.t {
            return (self.x[i], self.angle[i]);
        }
        let b = bounce.sample_in(a.phase, t);
        (
            self.x[i] + simpson(bounce, a, &b, vx),
            self.angle[i] + simpson(bounce, a, &b, omega),
        )
    }

    /// The smallest and largest displacement along the surface over the contact, m (0 is the start).
    pub fn x_extent(&self) -> (f64, f64) {
        self.x
            .iter()
            .fold((0.0f64, 0.0f64), |(lo, hi), &x| (lo.min(x), hi.max(x)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Params, solve};

    /// The trapezoid rule on a very fine even grid of the exact solution: a check independent of the grid.
    fn trapezoid(bounce: &Bounce, t: f64, value: fn(&Sample) -> f64) -> f64 {
        let n = 200_000;
        let h = t / n as f64;
        (0..n)
            .map(|i| {
                let a = bounce.sample_at(h * i as f64);
                let b = bounce.sample_at(h * (i + 1) as f64);
                0.5 * h * (value(&a) + value(&b))
            })
            .sum()
    }

    #[test]
    fn integrals_match_a_fine_trapezoid_rule() {
        let bounce = solve(&Params::default()).unwrap();
        let travel = Travel::compute(&bounce);
        let duration = bounce.setup.duration;
        for t in [
            0.0,
            0.3e-3,
            bounce.phases[1].start,
            2.2e-3,
            4.9e-3,
            duration,
        ] {
            let (x, angle) = travel.at(&bounce, t);
            assert!((x - trapezoid(&bounce, t, vx)).abs() < 1e-9, "x at {t}");
            assert!(
                (angle - trapezoid(&bounce, t, omega)).abs() < 1e-7,
                "angle at {t}"
            );
        }
        assert_eq!(travel.at(&bounce, 0.0), (0.0, 0.0));
    }

    #[test]
    fn a_ball_without_phases_changes_moves_at_constant_speed() {
        // No friction: v_x and omega stay as they came in.
        let params = Params {
            mu: 0.0,
            ..Params::default()
        };
        let bounce = solve(&params).unwrap();
        let travel = Travel::compute(&bounce);
        let t = 3.7e-3;
        let (x, angle) = travel.at(&bounce, t);
        assert!((x - bounce.setup.vx1 * t).abs() < 1e-12);
        assert!((angle - params.spin * t).abs() < 1e-12);
    }
}
