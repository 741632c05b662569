//! A grip's start state in the modes: the weighted coefficients by the modes' orthogonality under
//! [[C, D], [D, 0]], with one step of iterative refinement, accepted only where they rebuild the state
//! and its force to rounding without cancellation.

use super::super::super::chain::modes::MAX;
use super::{C64, CANCELLATION, FORCE_RECONSTRUCTION, GripModes, Mode, RECONSTRUCTION};

/// Room for a grip's state: the ball's stretch and the masses' displacements, then their rates.
const STATE: usize = 2 * MAX + 2;

/// The weighted coefficients of a state in the modes, by their orthogonality, written into `c` (one a
/// mode), and the state they rebuild (its first `z.len()` entries; no allocation).
fn project(g: &GripModes, list: &[Mode], z: &[f64], c: &mut [C64]) -> [f64; STATE] {
    let n = g.n;
    let e = z[0] - (0..n).map(|j| g.phi1[j] * z[j + 1]).sum::<f64>();
    let mut rebuilt = [0.0; STATE];
    // The masses' displacements and rates, and their rebuilt copies, as slices of n (no index checks
    // in the loops over the masses).
    let (masses, rates) = (&z[1..=n], &z[n + 2..2 * n + 2]);
    for (mode, slot) in list.iter().zip(c) {
        *slot = {
            let q = &mode.q[..n];
            // w_iᵀ [[C, D], [D, 0]] z = c_b e_i e + φᵀ D y' + s φᵀ D y.
            let mut dy = mode.u * (g.m_eff * z[n + 1]);
            let mut y = mode.u * (g.m_eff * z[0]);
            for ((&q, &x), &v) in q.iter().zip(masses).zip(rates) {
                dy += q * v;
                y += q * x;
            }
            let c = (mode.e * (g.cb * e) + dy + mode.s * y) / mode.norm * mode.weight;
            let rate = c * mode.s;
            rebuilt[0] += (c * mode.u).re;
            rebuilt[n + 1] += (rate * mode.u).re;
            let (head, tail) = rebuilt.split_at_mut(n + 2);
            for ((&q, x), v) in q.iter().zip(&mut head[1..=n]).zip(&mut tail[..n]) {
                *x += (c * q).re;
                *v += (rate * q).re;
            }
            c
        };
    }
    rebuilt
}

/// The weighted coefficients of z0 in the modes, if they reproduce it (and its force: a stiff dashpot
/// weighs e' far above its share of the energy) to rounding without cancellation. One step of
/// iterative refinement takes up what the roots' rounding leaves of the orthogonality.
pub(super) fn coefficients(g: &GripModes, list: &[Mode], z0: &[f64]) -> Option<Vec<C64>> {
    let n = g.n;
    let size = g.energy_norm(z0);
    let len = z0.len();
    let mut c = vec![C64::new(0.0, 0.0); list.len()];
    let rebuilt = project(g, list, z0, &mut c);
    let mut residual = [0.0; STATE];
    for i in 0..len {
        residual[i] = z0[i] - rebuilt[i];
    }
    let mut correction = [C64::new(0.0, 0.0); 2 * MAX + 2];
    let rebuilt_residual = project(g, list, &residual[..len], &mut correction);
    for (ci, di) in c.iter_mut().zip(&correction) {
        *ci += di;
    }
    let mut error = [0.0; STATE];
    for i in 0..len {
        error[i] = rebuilt[i] + rebuilt_residual[i] - z0[i];
    }
    let error = &error[..len];
    // The checks' sizes by sqrt(|z|²) (the library's hypot is several times dearer; they only bound).
    let terms: f64 = list
        .iter()
        .zip(&c)
        .map(|(m, c)| c.norm_sqr().sqrt() * m.size)
        .sum();
    let e0 = z0[0] - (0..n).map(|j| g.phi1[j] * z0[j + 1]).sum::<f64>();
    let de0 = z0[n + 1] - (0..n).map(|j| g.phi1[j] * z0[n + 2 + j]).sum::<f64>();
    let force_terms = g.kb * e0.abs() + g.cb * de0.abs();
    let force_sum: f64 = list
        .iter()
        .zip(&c)
        .map(|(m, c)| (c * m.force).norm_sqr().sqrt())
        .sum();
    let force_error = (list
        .iter()
        .zip(&c)
        .map(|(m, c)| (c * m.force).re)
        .sum::<f64>()
        - (g.kb * e0 + g.cb * de0))
        .abs();
    let fine = c.iter().all(|c| c.re.is_finite() && c.im.is_finite())
        && g.energy_norm(error) <= RECONSTRUCTION * size
        && force_error <= FORCE_RECONSTRUCTION * (force_terms + force_sum)
        && terms <= CANCELLATION * size;
    (fine || size == 0.0).then_some(c)
}
