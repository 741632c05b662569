//! The grip's fallback where its modes cannot be used (near-double roots): the state matrix's exponential
//! in energy coordinates, exact but slow. exp(Ã h) is made once per bounce for a step h with |Ã h| <= 1,
//! applied step by step from each grip's start (the results kept), then a Taylor series for the rest.

use nalgebra::{DMatrix, DVector};

use super::{ChainGrip, GripModes};

impl GripModes {
    /// The exponential's step h and exp(Ã h).
    pub(super) fn checkpoint(&self) -> &(f64, DMatrix<f64>) {
        self.checkpoint.get_or_init(|| {
            let h = 1.0
                / self
                    .a
                    .column_iter()
                    .map(|c| c.lp_norm(1))
                    .fold(0.0, f64::max);
            (h, (&self.a * h).exp())
        })
    }

    /// For a grip pushed by string friction: the augmented matrix Ã⁺ = [[Ã, b̃], [0, 0]] with b̃ = T b the
    /// unit push on the first mass (b̃ = (0, 0, 0, Φ_1j), on a free frame Φ_1j - Φ_fj: Q is mass-normalised), so that
    /// exp(Ã⁺ τ) (z̃0, P) = (exp(Ã τ) z̃0 + ∫_0^τ exp(Ã s) b̃ P ds, P); a step h with |Ã⁺ h|₁ <= 1 and
    /// exp(Ã⁺ h).
    pub(super) fn forced_checkpoint(&self) -> &(DMatrix<f64>, f64, DMatrix<f64>) {
        self.forced_checkpoint.get_or_init(|| {
            let size = 2 * (self.n + 1);
            let mut augmented = DMatrix::<f64>::zeros(size + 1, size + 1);
            augmented.view_mut((0, 0), (size, size)).copy_from(&self.a);
            for j in 0..self.n {
                augmented[(self.n + 2 + j, size)] = self.push_row[j];
            }
            let h = 1.0
                / augmented
                    .column_iter()
                    .map(|c| c.lp_norm(1))
                    .fold(0.0, f64::max);
            let step = (&augmented * h).exp();
            (augmented, h, step)
        })
    }

    /// z̃ = T z for z = (u, Q, u', Q').
    pub(super) fn to_energy(&self, z: &[f64]) -> DVector<f64> {
        let dof = self.n + 1;
        let l = self.lower.as_ref().expect("a chain with springs");
        let y = DVector::from_column_slice(&z[..dof]);
        let position = l.transpose() * y;
        DVector::from_fn(2 * dof, |i, _| {
            if i < dof {
                position[i]
            } else if i == dof {
                z[i] * self.m_eff.sqrt()
            } else {
                z[i]
            }
        })
    }

    /// z = T⁻¹ z̃.
    pub(super) fn energy_to_state(&self, energy: &DVector<f64>) -> Vec<f64> {
        let dof = self.n + 1;
        let l = self.lower.as_ref().expect("a chain with springs");
        let y = l
            .transpose()
            .solve_upper_triangular(&energy.rows(0, dof).into_owned())
            .unwrap_or_else(|| DVector::from_element(dof, f64::NAN));
        let mut z: Vec<f64> = y.iter().copied().collect();
        z.extend(energy.rows(dof, dof).iter());
        z[dof] /= self.m_eff.sqrt();
        z
    }

    /// (T⁻ᵀ hᵀ): a row h of z-coordinates as a row of energy coordinates, so that
    /// |h z| <= |T⁻ᵀ hᵀ| sqrt(2E).
    pub(super) fn dual(&self, h: &[f64]) -> DVector<f64> {
        let dof = self.n + 1;
        let l = self.lower.as_ref().expect("a chain with springs");
        let position = l
            .solve_lower_triangular(&DVector::from_column_slice(&h[..dof]))
            .unwrap_or_else(|| DVector::from_element(dof, f64::INFINITY));
        DVector::from_fn(2 * dof, |i, _| {
            if i < dof {
                position[i]
            } else if i == dof {
                h[i] / self.m_eff.sqrt()
            } else {
                h[i]
            }
        })
    }

    /// sqrt(2E) of a real state z = (u, Q, u', Q').
    pub(super) fn energy_norm(&self, z: &[f64]) -> f64 {
        let n = self.n;
        let e = z[0] - (0..n).map(|j| self.phi1[j] * z[j + 1]).sum::<f64>();
        let mut sum = self.kb * e * e + self.m_eff * z[n + 1] * z[n + 1];
        for j in 0..n {
            sum += self.omega2[j] * z[j + 1] * z[j + 1] + z[n + 2 + j] * z[n + 2 + j];
        }
        sum.sqrt()
    }
}

impl ChainGrip {
    /// z̃ = exp(Ã τ) z̃0 (pushed: (z̃, P) = exp(Ã⁺ τ) (z̃0, P)): exp(Ã h) applied k times from the start
    /// (each result kept for the next call), then the Taylor series of exp(Ã δ) applied to that,
    /// δ = τ - k h < h, |Ã δ| <= 1.
    pub(super) fn exponential(&self, tau: f64) -> DVector<f64> {
        let (a, h, step) = if self.push == 0.0 {
            let (h, step) = self.modes.checkpoint();
            (&self.modes.a, *h, step)
        } else {
            let (augmented, h, step) = self.modes.forced_checkpoint();
            (augmented, *h, step)
        };
        let k = (tau.max(0.0) / h).floor() as usize;
        let base = {
            let mut points = self.checkpoints.lock().unwrap_or_else(|e| e.into_inner());
            if points.is_empty() {
                let start = self.modes.to_energy(&self.z0);
                points.push(if self.push == 0.0 {
                    start
                } else {
                    start.push(self.push)
                });
            }
            while points.len() <= k {
                let next = step * points.last().expect("the start");
                points.push(next);
            }
            points[k].clone()
        };
        let delta = tau - k as f64 * h;
        let mut sum = base.clone();
        let mut term = base;
        for m in 1..40 {
            term = (a * &term) * (delta / m as f64);
            sum += &term;
            if term.norm() <= f64::EPSILON * sum.norm() {
                break;
            }
        }
        sum
    }
}
