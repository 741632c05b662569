//! The paper's Fig. 2 for the current parameters: rebound spin omega2 against incidence angle theta1,
//! solved at [`Sweep::ANGLES`] angles evenly spaced over (0, 90] degrees.

use crate::model::{ParamId, Params, solve};

/// One solved angle of the sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepPoint {
    pub angle_deg: f64,
    /// Rebound spin, rad/s.
    pub omega2: f64,
    /// True when the ball slides for the whole contact at this angle.
    pub slides_throughout: bool,
}

/// omega2(theta1) with every other parameter held at its current value.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// In increasing angle; an angle the core cannot solve is left out.
    pub points: Vec<SweepPoint>,
}

impl Sweep {
    /// How many angles are solved: every half degree from 0.5 to 90.
    pub const ANGLES: usize = 180;

    pub fn compute(params: &Params) -> Sweep {
        let points = (1..=Self::ANGLES)
            .filter_map(|i| {
                let angle_deg = 90.0 * i as f64 / Self::ANGLES as f64;
                let mut p = *params;
                p.set(ParamId::Angle, angle_deg);
                solve(&p).ok().map(|b| SweepPoint {
                    angle_deg,
                    omega2: b.outcome.omega2,
                    slides_throughout: b.slides_throughout(),
                })
            })
            .collect();
        Sweep { points }
    }

    /// The runs of angles (first, last, in degrees) over which the ball slides throughout.
    pub fn sliding_ranges(&self) -> Vec<(f64, f64)> {
        let mut ranges: Vec<(f64, f64)> = Vec::new();
        let mut open = false;
        for p in &self.points {
            match (p.slides_throughout, open, ranges.last_mut()) {
                (true, true, Some(last)) => last.1 = p.angle_deg,
                (true, _, _) => ranges.push((p.angle_deg, p.angle_deg)),
                (false, _, _) => {}
            }
            open = p.slides_throughout;
        }
        ranges
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_sweep_slides_at_glancing_angles_only() {
        let sweep = Sweep::compute(&Params::default());
        assert_eq!(sweep.points.len(), Sweep::ANGLES);
        let ranges = sweep.sliding_ranges();
        assert_eq!(ranges.len(), 1, "{ranges:?}");
        let (low, high) = ranges[0];
        assert_eq!(low, 0.5);
        // The paper: with omega1 = -100 rad/s the ball slides throughout below about 31 degrees.
        assert!(high > 25.0 && high < 40.0, "{high}");
    }
}
