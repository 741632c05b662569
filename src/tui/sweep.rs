//! The paper's Fig. 2 for the current parameters: rebound spin omega2 against incidence angle theta1,
//! solved at [`Sweep::ANGLES`] angles evenly spaced over (0, 90] degrees, and the same for a comparison
//! incident spin (the paper's two cases, omega1 = 0 and -100 rad/s), with the angles where the two cross.
//! Solved on the worker, the angles in parallel, and abandoned as soon as a newer request comes.

use rayon::prelude::*;

use crate::model::{ParamId, Params, SolveError, solve_cancellable};

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

    /// The sweep for `params`; `None` once `cancelled` says so.
    pub fn compute(params: &Params, cancelled: &(impl Fn() -> bool + Sync)) -> Option<Sweep> {
        let solved: Vec<Option<SweepPoint>> = (1..=Self::ANGLES)
            .into_par_iter()
            .map(|i| {
                let angle_deg = 90.0 * i as f64 / Self::ANGLES as f64;
                let mut p = *params;
                p.set(ParamId::Angle, angle_deg);
                match solve_cancellable(&p, cancelled) {
                    Ok(b) => Ok(Some(SweepPoint {
                        angle_deg,
                        omega2: b.outcome.omega2,
                        slides_throughout: b.slides_throughout(),
                    })),
                    Err(SolveError::Cancelled) => Err(()),
                    Err(_) => Ok(None),
                }
            })
            .collect::<Result<_, ()>>()
            .ok()?;
        Some(Sweep {
            points: solved.into_iter().flatten().collect(),
        })
    }

    /// The incident spin the comparison curve is drawn for: none, or the paper's backspin of -100 rad/s
    /// when the current spin is already none.
    pub fn comparison_spin(spin: f64) -> f64 {
        if spin == 0.0 { -100.0 } else { 0.0 }
    }

    /// The sweep for the comparison spin, other parameters as in `params`.
    pub fn comparison(params: &Params, cancelled: &(impl Fn() -> bool + Sync)) -> Option<Sweep> {
        let mut p = *params;
        p.set(ParamId::Spin, Self::comparison_spin(params.spin));
        Self::compute(&p, cancelled)
    }

    /// The angles, degrees, where this curve crosses `other` (linearly interpolated between the solved
    /// angles): where the sign of the difference of omega2 changes.
    pub fn crossings(&self, other: &Sweep) -> Vec<f64> {
        let diff: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter_map(|p| {
                let q = other.points.iter().find(|q| q.angle_deg == p.angle_deg)?;
                Some((p.angle_deg, p.omega2 - q.omega2))
            })
            .collect();
        diff.windows(2)
            .filter_map(|w| {
                let ((a0, d0), (a1, d1)) = (w[0], w[1]);
                if d0 == 0.0 {
                    Some(a0)
                } else if d0 * d1 < 0.0 {
                    Some(a0 + (a1 - a0) * d0 / (d0 - d1))
                } else {
                    None
                }
            })
            .collect()
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

/// Both curves of the sweep view for one set of parameters (the angle aside: it changes neither).
#[derive(Clone, Debug, PartialEq)]
pub struct Sweeps {
    pub key: Params,
    pub current: Sweep,
    pub comparison: Sweep,
}

impl Sweeps {
    /// What the sweeps depend on: every parameter but the angle.
    pub fn key(params: &Params) -> Params {
        Params {
            angle_deg: 0.0,
            ..*params
        }
    }

    /// Both sweeps for `params`; `None` once `cancelled` says so.
    pub fn compute(params: &Params, cancelled: &(impl Fn() -> bool + Sync)) -> Option<Sweeps> {
        Some(Sweeps {
            key: Self::key(params),
            current: Sweep::compute(params, cancelled)?,
            comparison: Sweep::comparison(params, cancelled)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_sweep_slides_at_glancing_angles_only() {
        let sweep = Sweep::compute(&Params::default(), &|| false).unwrap();
        assert_eq!(sweep.points.len(), Sweep::ANGLES);
        let ranges = sweep.sliding_ranges();
        assert_eq!(ranges.len(), 1, "{ranges:?}");
        let (low, high) = ranges[0];
        assert_eq!(low, 0.5);
        // The paper: with omega1 = -100 rad/s the ball slides throughout below about 31 degrees.
        assert!(high > 25.0 && high < 40.0, "{high}");
    }

    #[test]
    fn backspin_overtakes_no_spin_at_steep_angles_on_a_light_cart() {
        // The paper's Fig. 2: for the 10 g cart, omega1 = -100 rad/s gives less spin than omega1 = 0 below
        // about 60 degrees and can give more above.
        let params = Params::default();
        let Sweeps {
            current,
            comparison: other,
            ..
        } = Sweeps::compute(&params, &|| false).unwrap();
        assert_eq!(Sweep::comparison_spin(params.spin), 0.0);
        let crossings = current.crossings(&other);
        assert_eq!(crossings.len(), 1, "{crossings:?}");
        assert!(crossings[0] > 55.0 && crossings[0] < 80.0, "{crossings:?}");
        let at = |s: &Sweep, a: f64| s.points.iter().find(|p| p.angle_deg == a).unwrap().omega2;
        assert!(at(&current, 30.0) < at(&other, 30.0));
        assert!(at(&current, 85.0) > at(&other, 85.0));
        // Symmetric: the crossing is the same seen from the other curve.
        assert_eq!(other.crossings(&current).len(), 1);
        assert_eq!(Sweep::comparison_spin(0.0), -100.0);
    }
}
