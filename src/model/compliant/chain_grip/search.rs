//! Where the event search looks for the grip's break, and the bounds on |F''| it needs: in stages, a
//! strongly damped mode bounding |F''| only until it has died out.

use super::super::super::setup::Setup;
use super::super::stretch::SETTLED;
use super::{ChainGrip, NEGLIGIBLE};

impl ChainGrip {
    /// The stages of the event search over the rest of the contact, (from, to, bound on |F''|, step),
    /// and the size of the terms F is summed from. A strongly damped mode dominates the bound only
    /// until it has died out: the first 40 e-folds of the fastest decay are cut into stages of 4, each
    /// bounded from its start, with a step on the scale sqrt(|F''| / |F|) of its bound.
    pub fn search_stages(&self, setup: &Setup) -> (Vec<(f64, f64, f64, f64)>, f64) {
        let (t0, end) = (self.start.t, setup.duration);
        let decay = match &self.modes.modes {
            Some(list) if self.coefficients.is_some() => {
                list.iter().map(|m| -m.s.re).fold(0.0, f64::max)
            }
            _ => 0.0,
        };
        let stage = SETTLED / 10.0 / decay;
        let cuts = (1..=10)
            .map(|k| t0 + k as f64 * stage)
            .take_while(|&t| t < end);
        let stage_from = |from: f64, (curvature, terms, fastest): (f64, f64, f64)| {
            let rate = if terms > 0.0 {
                (curvature / terms).sqrt().min(fastest)
            } else {
                0.0
            };
            (from, end, curvature, setup.event_step(rate))
        };
        let first = self.force_bounds(setup, t0);
        let size = first.1;
        let mut stages = vec![stage_from(t0, first)];
        // A cut pays for itself only where the bound has fallen by half since the stage began.
        for cut in cuts {
            let next = stage_from(cut, self.force_bounds(setup, cut));
            let current = stages.last_mut().expect("one stage at least");
            if next.2 < 0.5 * current.2 {
                current.1 = cut;
                stages.push(next);
            }
        }
        (stages, size)
    }

    /// A bound on |F''| over the rest of the contact, and the size of the terms F is summed from (for
    /// the rounding floor).
    ///
    /// From `from` on: a mode decaying at -Re s has shrunk by e^(Re s (from - t0)) there, so a strongly
    /// damped mode stops counting once it has died out. Also the fastest rate still worth resolving.
    pub fn force_bounds(&self, setup: &Setup, from: f64) -> (f64, f64, f64) {
        let g = &self.modes;
        let (elapsed, remaining) = (from - self.start.t, setup.duration - self.start.t);
        match (&g.modes, &self.coefficients) {
            (Some(list), Some(c)) => {
                let (mut curvature, mut size) = (0.0, 0.0);
                let terms: Vec<(f64, f64)> = list
                    .iter()
                    .zip(c)
                    .map(|(mode, ci)| {
                        let growth = if mode.s.re <= 0.0 {
                            (mode.s.re * elapsed).exp()
                        } else {
                            (mode.s.re * remaining).exp()
                        };
                        let term = (ci * mode.force).norm() * growth;
                        curvature += term * mode.s.norm_sqr();
                        size += term;
                        (term * mode.s.norm_sqr(), mode.s.norm())
                    })
                    .collect();
                let fastest = terms
                    .iter()
                    .filter(|(part, _)| *part >= NEGLIGIBLE * curvature)
                    .map(|&(_, rate)| rate)
                    .fold(0.0, f64::max);
                (curvature, size, fastest)
            }
            _ => {
                // |h z| <= |T⁻ᵀ hᵀ| sqrt(2E), and F'' = h A² z = (T⁻ᵀ hᵀ)ᵀ Ã² z̃; the dashpot only lowers E.
                let dof = g.n + 1;
                let mut stretch = vec![0.0; 2 * dof];
                stretch[0] = 1.0;
                for j in 0..g.n {
                    stretch[j + 1] = -g.phi1[j];
                }
                let mut rate = vec![0.0; 2 * dof];
                rate[dof..].copy_from_slice(&stretch[..dof]);
                let force: Vec<f64> = (0..2 * dof)
                    .map(|i| g.kb * stretch[i] + g.cb * rate[i])
                    .collect();
                let second = g.a.transpose() * g.a.transpose() * g.dual(&force);
                let size = g.energy_norm(&self.z0);
                (
                    second.norm() * size,
                    (g.dual(&stretch).norm() * g.kb + g.dual(&rate).norm() * g.cb) * size,
                    g.fastest,
                )
            }
        }
    }
}
