//! The uncertainty band of the sweep view: omega2's mean and standard deviation against the incidence
//! angle when some inputs carry a standard uncertainty (typed `60±1` in the value prompt). At each of
//! [`ANGLES`] angles, [`monte_carlo`] draws [`SAMPLES`] bounces with the same seed, so the band is smooth;
//! computed off the UI thread, an angle at a time, and abandoned between angles once newer inputs are
//! asked for.

use crate::analysis::fit::data::Quantity;
use crate::analysis::uncertainty::{Spread, monte_carlo};
use crate::model::{ParamId, Params};

/// Angles of the band: every 2 degrees from 2 to 90.
pub const ANGLES: usize = 45;
/// Monte Carlo draws at each angle.
pub const SAMPLES: usize = 200;
/// The seed of every angle's draws.
pub const SEED: u64 = 1;

/// omega2 over the draws at one angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandPoint {
    pub angle_deg: f64,
    /// Mean and standard deviation of omega2, rad/s.
    pub mean: f64,
    pub sd: f64,
}

/// The band for one set of parameters (the angle aside) and uncertainties.
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    /// The parameters, as [`crate::tui::sweep::Sweeps::key`] gives them.
    pub key: Params,
    pub spreads: Vec<Spread>,
    /// In increasing angle; an angle where a draw cannot be solved is left out.
    pub points: Vec<BandPoint>,
}

impl Band {
    /// The band of `key` with `spreads`; `None` once `cancelled` says so.
    pub fn compute(
        key: &Params,
        spreads: &[Spread],
        cancelled: &impl Fn() -> bool,
    ) -> Option<Band> {
        let mut points = Vec::with_capacity(ANGLES);
        for i in 1..=ANGLES {
            if cancelled() {
                return None;
            }
            let angle_deg = 90.0 * i as f64 / ANGLES as f64;
            let mut p = *key;
            p.set(ParamId::Angle, angle_deg);
            let Ok(bands) = monte_carlo(&p, spreads, SAMPLES, SEED) else {
                continue;
            };
            if let Some(b) = bands.bands.iter().find(|b| b.quantity == Quantity::Omega2) {
                points.push(BandPoint {
                    angle_deg,
                    mean: b.mean,
                    sd: b.sd,
                });
            }
        }
        Some(Band {
            key: *key,
            spreads: spreads.to_vec(),
            points,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spread_in_spin_widens_the_band_and_none_gives_a_line() {
        let key = Params::default();
        let flat = Band::compute(&key, &[], &|| false).unwrap();
        assert_eq!(flat.points.len(), ANGLES);
        assert!(flat.points.iter().all(|p| p.sd < 1e-9));
        let spin = [Spread {
            id: ParamId::Spin,
            sigma: 20.0,
        }];
        let band = Band::compute(&key, &spin, &|| false).unwrap();
        let at = |b: &Band, a: f64| *b.points.iter().find(|p| p.angle_deg == a).unwrap();
        assert!(at(&band, 60.0).sd > 1.0);
        assert!((at(&band, 60.0).mean - at(&flat, 60.0).mean).abs() < at(&band, 60.0).sd);
        assert!(Band::compute(&key, &spin, &|| true).is_none());
    }
}
