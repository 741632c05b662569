//! The chain of masses and springs and its normal modes, sliding (the masses alone) and gripping (the
//! ball's effective mass m_eff added to the first mass).

use nalgebra::{DMatrix, SymmetricEigen};

/// The most masses one set of modes holds: the longest chain (16 links, `--chain`'s range) and a free
/// frame behind it.
pub const MAX: usize = 17;

/// The normal modes of one configuration of the chain: masses `mass` on the springs, mass-normalised
/// shapes Φ (Φᵀ D Φ = I with D = diag(mass), Φᵀ K Φ = diag(Ω²)), so that with x = Φ q each modal
/// coordinate obeys q_j'' + Ω_j² q_j = Φ_1j F for a force F on the first mass.
#[derive(Clone, Debug)]
pub struct Modes {
    pub n: usize,
    /// The masses, kg (the first carries the ball's m_eff while it grips).
    pub mass: [f64; MAX],
    /// Ω_j, rad/s.
    pub omega: [f64; MAX],
    /// `shape[i][j]` = Φ_ij, the displacement of mass i in mode j.
    pub shape: [[f64; MAX]; MAX],
    /// Φ_1j Ω_j², for the first mass's acceleration -Σ Φ_1j Ω_j² q_j (less its forcing).
    pub first_stiff: [f64; MAX],
    /// The largest |Φ_ij| over i, per mode.
    pub largest: [f64; MAX],
    /// The fastest Ω_j.
    pub fastest: f64,
    /// The rigid translation's mode (Ω = 0), on a free frame.
    pub rigid: Option<usize>,
    /// `inverse[j][i]` = Φ_ij m_i, the row of Φᵀ D that [`Modes::project`] takes mode j by, kept so
    /// that a projection reads one row in order and multiplies once an entry (the same products as
    /// Φ_ij m_i x_i, bit for bit).
    inverse: [[f64; MAX]; MAX],
}

impl Modes {
    /// `n` links of mass `link_mass` joined by springs `link_stiffness` (the last to the wall), with
    /// `extra` added to the first mass.
    ///
    /// The eigenproblem is solved in dimensionless form, A = S^(-1/2) T S^(-1/2) with T the spring
    /// pattern (tridiagonal 1, 2, ..., 2 on the diagonal, -1 beside it) and S = diag(1 + extra/link_mass,
    /// 1, ..., 1), so Ω_j² = (link_stiffness / link_mass) λ_j. Each λ_j is then recomputed as the
    /// Rayleigh quotient |B z|² / zᵀ S z of its vector z = S^(-1/2) u, with B the spring extensions
    /// (T = BᵀB): a sum of squares, accurate relative to λ_j even for a slow mode that QR resolves only to
    /// rounding of the largest eigenvalue.
    pub fn new(n: usize, link_mass: f64, link_stiffness: f64, extra: f64) -> Modes {
        Modes::build(n, link_mass, link_stiffness, extra, None)
    }

    /// `links` links as in [`Modes::new`], the last spring tied to a free frame of mass `frame` in place
    /// of the wall: `links` + 1 masses (the frame last) and no spring to the world. T then has 1 at both
    /// ends of its diagonal, S ends in `frame`/link_mass, and one mode is the rigid translation of the
    /// whole, written exactly: Ω = 0 and Φ_i = 1/sqrt(Σ masses) for every mass.
    pub fn framed(
        links: usize,
        link_mass: f64,
        link_stiffness: f64,
        extra: f64,
        frame: f64,
    ) -> Modes {
        Modes::build(links + 1, link_mass, link_stiffness, extra, Some(frame))
    }

    /// `n` masses; with a `frame`, the last of them is the frame and no spring goes to the wall.
    fn build(
        n: usize,
        link_mass: f64,
        link_stiffness: f64,
        extra: f64,
        frame: Option<f64>,
    ) -> Modes {
        assert!((1..=MAX).contains(&n), "chain of {n} masses");
        let mut scale = [1.0; MAX];
        scale[0] = (1.0 + extra / link_mass).sqrt().recip();
        if let Some(frame) = frame {
            scale[n - 1] = (frame / link_mass).sqrt().recip();
        }
        // The last mass's springs: a link and the wall's, or the frame's one link.
        let last = if frame.is_some() { 1.0 } else { 2.0 };
        let mut a = DMatrix::<f64>::zeros(n, n);
        for i in 0..n {
            let diagonal = if i == 0 {
                1.0
            } else if i + 1 == n {
                last
            } else {
                2.0
            };
            a[(i, i)] = diagonal * scale[i] * scale[i];
            if i + 1 < n {
                let off = -scale[i] * scale[i + 1];
                a[(i, i + 1)] = off;
                a[(i + 1, i)] = off;
            }
        }
        let eigen = SymmetricEigen::new(a);
        let frequency = (link_stiffness / link_mass).sqrt();
        let mut mass = [0.0; MAX];
        for (i, m) in mass.iter_mut().enumerate().take(n) {
            *m = if i == 0 { link_mass + extra } else { link_mass };
        }
        if let Some(frame) = frame {
            mass[n - 1] = frame;
        }
        // The rigid translation (framed): the mode of the smallest eigenvalue, replaced by its exact form.
        let rigid = frame.map(|_| {
            let values = &eigen.eigenvalues;
            (0..n).fold(0, |best, j| if values[j] < values[best] { j } else { best })
        });
        // The springs' extensions: between neighbours, and the last mass's to the wall if clamped.
        let springs = if frame.is_some() { n - 1 } else { n };
        Modes::from_eigen(&eigen, mass, &scale, link_mass, frequency, rigid, |z| {
            (0..springs)
                .map(|i| {
                    let e = if i + 1 < n { z[i] - z[i + 1] } else { z[i] };
                    e * e
                })
                .sum()
        })
    }

    /// The chain on a free frame with its first mass held to the frame by string friction: the first
    /// mass and the frame are one body of mass `body` (M/N + M_t, with `extra` added: the ball's m_eff
    /// while it grips), and the `n` - 1 links behind it form a ring tied to that body at both ends, `n`
    /// springs `link_stiffness` from the body through the links back to the body. The masses are
    /// [body, link, ..., link]; T has 2 on its whole diagonal and -1 between neighbours and between the
    /// body and the last link (for `n` = 2 the two springs join the same pair: -2; for `n` = 1 there is
    /// no spring). One mode is the rigid translation, written exactly as in [`Modes::framed`]; the
    /// others' Ω_j² are Rayleigh quotients as in [`Modes::new`], over the ring's `n` springs.
    pub fn ring(n: usize, link_mass: f64, link_stiffness: f64, body: f64, extra: f64) -> Modes {
        assert!((1..=MAX).contains(&n), "ring of {n} masses");
        let mut scale = [1.0; MAX];
        scale[0] = ((body + extra) / link_mass).sqrt().recip();
        let mut a = DMatrix::<f64>::zeros(n, n);
        for i in 0..n {
            let j = (i + 1) % n;
            if i != j {
                a[(i, i)] += scale[i] * scale[i];
                a[(j, j)] += scale[j] * scale[j];
                a[(i, j)] -= scale[i] * scale[j];
                a[(j, i)] -= scale[i] * scale[j];
            }
        }
        let eigen = SymmetricEigen::new(a);
        let frequency = (link_stiffness / link_mass).sqrt();
        let mut mass = [0.0; MAX];
        for (i, m) in mass.iter_mut().enumerate().take(n) {
            *m = if i == 0 { body + extra } else { link_mass };
        }
        let values = &eigen.eigenvalues;
        let rigid = (0..n).fold(0, |best, j| if values[j] < values[best] { j } else { best });
        Modes::from_eigen(
            &eigen,
            mass,
            &scale,
            link_mass,
            frequency,
            Some(rigid),
            |z| (0..n).map(|i| (z[i] - z[(i + 1) % n]).powi(2)).sum(),
        )
    }

    /// The modes of `mass` from the eigenvectors of the scaled spring pattern (`scale` the diagonal of
    /// S^(-1/2), in units of `link_mass`): the mode `rigid`, if any, written exactly as the rigid
    /// translation; every other Ω_j² the Rayleigh quotient `stretch(z)`/|u|² of its vector z = S^(-1/2) u,
    /// `stretch` summing the squared extensions of the springs, times the link's k/m.
    fn from_eigen(
        eigen: &SymmetricEigen<f64, nalgebra::Dyn>,
        mass: [f64; MAX],
        scale: &[f64; MAX],
        link_mass: f64,
        frequency: f64,
        rigid: Option<usize>,
        stretch: impl Fn(&[f64]) -> f64,
    ) -> Modes {
        let n = eigen.eigenvalues.len();
        let total: f64 = mass[..n].iter().sum();
        let mut modes = Modes {
            n,
            mass,
            omega: [0.0; MAX],
            shape: [[0.0; MAX]; MAX],
            first_stiff: [0.0; MAX],
            largest: [0.0; MAX],
            fastest: 0.0,
            rigid,
            inverse: [[0.0; MAX]; MAX],
        };
        let root_mass = link_mass.sqrt();
        for j in 0..n {
            if rigid == Some(j) {
                let phi = total.sqrt().recip();
                for row in modes.shape.iter_mut().take(n) {
                    row[j] = phi;
                }
                modes.largest[j] = phi;
                continue;
            }
            let u = eigen.eigenvectors.column(j);
            let z: Vec<f64> = (0..n).map(|i| scale[i] * u[i]).collect();
            let norm: f64 = (0..n).map(|i| u[i] * u[i]).sum();
            let lambda = (stretch(&z) / norm).max(0.0);
            let omega = frequency * lambda.sqrt();
            modes.omega[j] = omega;
            let mut largest: f64 = 0.0;
            for (i, zi) in z.iter().enumerate() {
                // Φ = D^(-1/2) u with D = link_mass S.
                let phi = zi / (root_mass * norm.sqrt());
                modes.shape[i][j] = phi;
                largest = largest.max(phi.abs());
            }
            modes.largest[j] = largest;
            modes.first_stiff[j] = modes.shape[0][j] * omega * omega;
            modes.fastest = modes.fastest.max(omega);
        }
        modes.invert();
        modes
    }

    /// The masses behind a first mass held still by string friction: `n` links of mass `link_mass`
    /// between two fixed ends (the held mass and the wall) joined by `n + 1` springs `link_stiffness`.
    /// Their modes are known in closed form: Φ_ij = sqrt(2/((n+1) m)) sin(i j π/(n+1)) and
    /// Ω_j = 2 sqrt(κ/m) sin(j π/(2(n+1))) for i, j = 1..n.
    pub fn clamped(n: usize, link_mass: f64, link_stiffness: f64) -> Modes {
        assert!(n < MAX, "a chain of {n} masses behind the first");
        let mut modes = Modes {
            n,
            mass: [0.0; MAX],
            omega: [0.0; MAX],
            shape: [[0.0; MAX]; MAX],
            first_stiff: [0.0; MAX],
            largest: [0.0; MAX],
            fastest: 0.0,
            rigid: None,
            inverse: [[0.0; MAX]; MAX],
        };
        let ends = (n + 1) as f64;
        let norm = (2.0 / (ends * link_mass)).sqrt();
        let frequency = 2.0 * (link_stiffness / link_mass).sqrt();
        for j in 0..n {
            modes.mass[j] = link_mass;
            let omega = frequency * ((j + 1) as f64 * std::f64::consts::FRAC_PI_2 / ends).sin();
            modes.omega[j] = omega;
            for i in 0..n {
                let angle = ((i + 1) * (j + 1)) as f64 * std::f64::consts::PI / ends;
                modes.shape[i][j] = norm * angle.sin();
                modes.largest[j] = modes.largest[j].max(modes.shape[i][j].abs());
            }
            modes.first_stiff[j] = modes.shape[0][j] * omega * omega;
            modes.fastest = modes.fastest.max(omega);
        }
        modes.invert();
        modes
    }

    /// Fills [`Modes::inverse`] from the finished shapes and masses.
    fn invert(&mut self) {
        for (j, row) in self.inverse.iter_mut().enumerate().take(self.n) {
            for (i, entry) in row.iter_mut().enumerate().take(self.n) {
                *entry = self.shape[i][j] * self.mass[i];
            }
        }
    }

    /// The modal coordinates q = Φᵀ D x of displacements (or velocities) `x`.
    pub fn project(&self, x: &[f64; MAX]) -> [f64; MAX] {
        let mut q = [0.0; MAX];
        for (j, qj) in q.iter_mut().enumerate().take(self.n) {
            *qj = self.project_one(j, x);
        }
        q
    }

    /// Mode j's coordinate q_j of `x`, as [`Modes::project`] takes it (the same sum, bit for bit).
    #[inline(always)]
    pub fn project_one(&self, j: usize, x: &[f64; MAX]) -> f64 {
        self.inverse[j][..self.n]
            .iter()
            .zip(x)
            .map(|(a, x)| a * x)
            .sum()
    }

    /// [`Modes::project`] of displacements `x` and velocities `v` together, written into the first
    /// `n` entries of `q` and `dq` (the rest left as they are), reading each row of Φᵀ D once: the
    /// same sums, bit for bit.
    pub fn project_both(
        &self,
        (x, v): (&[f64; MAX], &[f64; MAX]),
        (q, dq): (&mut [f64; MAX], &mut [f64; MAX]),
    ) {
        let n = self.n;
        for ((row, qj), dqj) in self
            .inverse
            .iter()
            .zip(q.iter_mut())
            .zip(dq.iter_mut())
            .take(n)
        {
            // From -0.0, as `Iterator::sum` starts.
            let (mut sq, mut sdq) = (-0.0, -0.0);
            for ((a, xi), vi) in row[..n].iter().zip(x).zip(v) {
                sq += a * xi;
                sdq += a * vi;
            }
            (*qj, *dqj) = (sq, sdq);
        }
    }

    /// The displacements (or velocities) x = Φ q of modal coordinates `q`.
    pub fn expand(&self, q: &[f64; MAX]) -> [f64; MAX] {
        let mut x = [0.0; MAX];
        for (i, xi) in x.iter_mut().enumerate().take(self.n) {
            *xi = (0..self.n).map(|j| self.shape[i][j] * q[j]).sum();
        }
        x
    }

    /// [`Modes::expand`] of the coordinates `q` and of their rates `dq` together, into `x` and `v`
    /// (their first `n` entries), reading each row of Φ once: the same sums, bit for bit.
    pub fn expand_both(
        &self,
        (q, dq): (&[f64; MAX], &[f64; MAX]),
        (x, v): (&mut [f64; MAX], &mut [f64; MAX]),
    ) {
        self.expand_rows((q, dq), (x, v), 0..self.n);
    }

    /// [`Modes::expand_both`] for the masses `rows` only (the others' entries are left as they are),
    /// each the same sum, bit for bit.
    #[inline]
    pub fn expand_rows(
        &self,
        (q, dq): (&[f64; MAX], &[f64; MAX]),
        (x, v): (&mut [f64; MAX], &mut [f64; MAX]),
        rows: std::ops::Range<usize>,
    ) {
        let n = self.n;
        let rows = rows.start..rows.end.min(n);
        let masses = self.shape[rows.clone()]
            .iter()
            .zip(&mut x[rows.clone()])
            .zip(&mut v[rows]);
        for ((row, xi), vi) in masses {
            // From -0.0, as `Iterator::sum` starts.
            let (mut sx, mut sv) = (-0.0, -0.0);
            for ((phi, qj), dqj) in row[..n].iter().zip(q).zip(dq) {
                sx += phi * qj;
                sv += phi * dqj;
            }
            (*xi, *vi) = (sx, sv);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// K of `n` springs `kappa` in a line from mass 1 to the wall.
    fn stiffness(n: usize, kappa: f64) -> DMatrix<f64> {
        let mut k = DMatrix::<f64>::zeros(n, n);
        for i in 0..n {
            k[(i, i)] = if i == 0 { kappa } else { 2.0 * kappa };
            if i + 1 < n {
                k[(i, i + 1)] = -kappa;
                k[(i + 1, i)] = -kappa;
            }
        }
        k
    }

    #[test]
    fn modes_diagonalise_mass_and_stiffness() {
        for n in [1, 2, 5, 16] {
            for extra in [0.0, 0.03, 30.0] {
                let (m, kappa) = (0.01 / n as f64, 15000.0 * n as f64);
                let modes = Modes::new(n, m, kappa, extra);
                let phi = DMatrix::from_fn(n, n, |i, j| modes.shape[i][j]);
                let d = DMatrix::from_fn(n, n, |i, j| if i == j { modes.mass[i] } else { 0.0 });
                let identity = phi.transpose() * &d * &phi;
                let spectral = phi.transpose() * stiffness(n, kappa) * &phi;
                for i in 0..n {
                    for j in 0..n {
                        let want = if i == j { 1.0 } else { 0.0 };
                        assert!((identity[(i, j)] - want).abs() < 1e-12, "n {n} I {i} {j}");
                        let want = if i == j { modes.omega[i].powi(2) } else { 0.0 };
                        let scale = modes.fastest.powi(2);
                        assert!((spectral[(i, j)] - want).abs() < 1e-12 * scale, "n {n} K");
                    }
                }
            }
        }
    }

    #[test]
    fn clamped_modes_diagonalise_the_chain_behind_a_held_mass() {
        for n in [1, 2, 7, 15] {
            let (m, kappa) = (0.01 / (n + 1) as f64, 15000.0 * (n + 1) as f64);
            let modes = Modes::clamped(n, m, kappa);
            let phi = DMatrix::from_fn(n, n, |i, j| modes.shape[i][j]);
            // Both ends fixed: every diagonal entry of K is 2 kappa.
            let k = stiffness(n + 1, kappa).remove_row(0).remove_column(0);
            let identity = phi.transpose() * &phi * m;
            let spectral = phi.transpose() * k * &phi;
            let scale = modes.fastest.powi(2);
            for i in 0..n {
                for j in 0..n {
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((identity[(i, j)] - want).abs() < 1e-12, "n {n} I {i} {j}");
                    let want = if i == j { modes.omega[i].powi(2) } else { 0.0 };
                    assert!((spectral[(i, j)] - want).abs() < 1e-12 * scale, "n {n} K");
                }
            }
        }
    }

    #[test]
    fn framed_modes_diagonalise_mass_and_stiffness_and_hold_the_rigid_translation() {
        for links in [1, 2, 5, 15] {
            for (extra, frame) in [(0.0, 0.32), (0.03, 0.005), (30.0, 1e6)] {
                let (m, kappa) = (0.01 / links as f64, 15000.0 * links as f64);
                let modes = Modes::framed(links, m, kappa, extra, frame);
                let n = links + 1;
                assert_eq!(modes.n, n);
                assert_eq!(modes.mass[links], frame);
                // The free chain: the frame's row has its one spring, and no spring goes to the wall.
                let mut k = stiffness(n, kappa);
                k[(links, links)] = kappa;
                let phi = DMatrix::from_fn(n, n, |i, j| modes.shape[i][j]);
                let d = DMatrix::from_fn(n, n, |i, j| if i == j { modes.mass[i] } else { 0.0 });
                let identity = phi.transpose() * &d * &phi;
                let spectral = phi.transpose() * k * &phi;
                let scale = modes.fastest.powi(2);
                for i in 0..n {
                    for j in 0..n {
                        let want = if i == j { 1.0 } else { 0.0 };
                        let what = format!("links {links} frame {frame} I {i} {j}");
                        assert!((identity[(i, j)] - want).abs() < 1e-10, "{what}");
                        let want = if i == j { modes.omega[i].powi(2) } else { 0.0 };
                        assert!((spectral[(i, j)] - want).abs() < 1e-12 * scale, "{what} K");
                    }
                }
                let rigid: Vec<usize> = (0..n).filter(|&j| modes.omega[j] == 0.0).collect();
                assert_eq!(rigid.len(), 1, "links {links} frame {frame}");
                assert_eq!(modes.rigid, Some(rigid[0]));
                assert_eq!(modes.first_stiff[rigid[0]], 0.0);
            }
        }
    }

    #[test]
    fn ring_modes_diagonalise_the_held_body_and_the_links_behind_it() {
        for n in [1, 2, 3, 6, 16] {
            for (body, extra) in [(0.3, 0.0), (0.005, 0.03), (1e6, 0.0)] {
                let (m, kappa) = (0.01 / n as f64, 15000.0 * n as f64);
                let modes = Modes::ring(n, m, kappa, body, extra);
                assert_eq!(modes.mass[0], body + extra);
                // The ring: spring i joins mass i and mass i + 1, the last back to the body.
                let mut k = DMatrix::<f64>::zeros(n, n);
                for i in 0..n {
                    let j = (i + 1) % n;
                    if i != j {
                        k[(i, i)] += kappa;
                        k[(j, j)] += kappa;
                        k[(i, j)] -= kappa;
                        k[(j, i)] -= kappa;
                    }
                }
                let phi = DMatrix::from_fn(n, n, |i, j| modes.shape[i][j]);
                let d = DMatrix::from_fn(n, n, |i, j| if i == j { modes.mass[i] } else { 0.0 });
                let identity = phi.transpose() * &d * &phi;
                let spectral = phi.transpose() * k * &phi;
                let scale = modes.fastest.powi(2).max(1.0);
                for i in 0..n {
                    for j in 0..n {
                        let want = if i == j { 1.0 } else { 0.0 };
                        let what = format!("n {n} body {body} I {i} {j}");
                        assert!((identity[(i, j)] - want).abs() < 1e-10, "{what}");
                        let want = if i == j { modes.omega[i].powi(2) } else { 0.0 };
                        assert!((spectral[(i, j)] - want).abs() < 1e-12 * scale, "{what} K");
                    }
                }
                let rigid: Vec<usize> = (0..n).filter(|&j| modes.omega[j] == 0.0).collect();
                assert_eq!(rigid.len(), 1, "n {n} body {body}");
                assert_eq!(modes.rigid, Some(rigid[0]));
            }
        }
    }

    #[test]
    fn projecting_and_expanding_both_or_some_rows_are_each_alone_bit_for_bit() {
        let all = [
            Modes::new(8, 0.01 / 8.0, 8.0 * 15000.0, 0.03),
            Modes::framed(4, 0.0025, 60000.0, 0.0, 0.188),
            Modes::ring(5, 0.002, 75000.0, 0.19, 0.03),
            Modes::clamped(3, 0.0025, 60000.0),
        ];
        for modes in all {
            let (mut x, mut v) = ([0.0; MAX], [0.0; MAX]);
            for i in 0..modes.n {
                (x[i], v[i]) = (1e-3 * (i as f64 + 0.3).sin(), -2.0 * (1.7 * i as f64).cos());
            }
            let (mut q, mut dq) = ([7.0; MAX], [7.0; MAX]);
            modes.project_both((&x, &v), (&mut q, &mut dq));
            let (mut y, mut u) = ([7.0; MAX], [7.0; MAX]);
            modes.expand_both((&q, &dq), (&mut y, &mut u));
            let n = modes.n;
            let bits = |a: &[f64]| a[..n].iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&q), bits(&modes.project(&x)), "n {n}");
            assert_eq!(bits(&dq), bits(&modes.project(&v)), "n {n}");
            assert_eq!(bits(&y), bits(&modes.expand(&q)), "n {n}");
            assert_eq!(bits(&u), bits(&modes.expand(&dq)), "n {n}");
            // A range of masses alone: the same bits there, the rest untouched.
            let (mut z, mut w) = ([7.0; MAX], [7.0; MAX]);
            modes.expand_rows((&q, &dq), (&mut z, &mut w), 1..n - 1);
            for i in 0..MAX {
                let inside = (1..n - 1).contains(&i);
                let (want_x, want_v) = if inside { (y[i], u[i]) } else { (7.0, 7.0) };
                assert_eq!(z[i].to_bits(), want_x.to_bits(), "n {n} x {i}");
                assert_eq!(w[i].to_bits(), want_v.to_bits(), "n {n} v {i}");
            }
        }
    }

    #[test]
    fn one_link_is_the_single_cart() {
        let modes = Modes::new(1, 0.01, 15000.0, 0.0);
        assert_eq!(modes.omega[0], (15000.0f64 / 0.01).sqrt());
        assert!((modes.shape[0][0].abs() - 10.0).abs() < 1e-14);
    }

    #[test]
    fn static_stiffness_at_the_first_mass_is_k() {
        // (K^-1)_11 = sum_j Φ_1j² / Ω_j² = 1/k.
        for n in [1, 3, 16] {
            let k = 15000.0;
            let modes = Modes::new(n, 0.01 / n as f64, n as f64 * k, 0.0);
            let compliance: f64 = (0..n)
                .map(|j| modes.shape[0][j].powi(2) / modes.omega[j].powi(2))
                .sum();
            assert!((compliance * k - 1.0).abs() < 1e-12, "n {n}: {compliance}");
        }
    }
}
