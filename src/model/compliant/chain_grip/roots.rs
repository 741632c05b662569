//! The roots of the grip's characteristic function g(s) = 1 + (k_b + c_b s) R(s): Newton's method from
//! the damped undamped modes, with Maehly's deflation where a root was found twice, then the Schur form
//! of the state matrix; each set accepted only if complete, distinct and satisfying g(s) = 0.

use super::super::super::chain::modes::MAX;
use super::{C64, GripModes, Mode, REAL, RESIDUAL, SAME};

impl GripModes {
    /// The roots: by Newton's method from the damped undamped modes (one start per pair); where two
    /// starts find the same root, by Newton's method with deflation from every start; else from the
    /// Schur form. Each set is accepted only if all 2(N + 1) roots are found, distinct, and satisfy
    /// g(s) = 0.
    pub(super) fn find_modes(&self) -> Option<Vec<Mode>> {
        if let Some(guesses) = self.guesses() {
            let newton: Vec<C64> = guesses
                .iter()
                .filter(|s| s.im >= 0.0)
                .map(|&s| self.polish(s, 30))
                .collect();
            if let Some(modes) = self
                .accept(&newton)
                .or_else(|| self.accept(&self.deflated(&guesses)))
            {
                return Some(modes);
            }
        }
        let schur: Vec<C64> = self
            .a
            .clone()
            .complex_eigenvalues()
            .iter()
            .map(|&s| self.polish(s, 5))
            .collect();
        self.accept(&schur)
    }

    /// g(s) and g'(s).
    pub(super) fn g(&self, s: C64) -> (C64, C64) {
        let s2 = s * s;
        let mut r = (s2 * self.m_eff).inv();
        let mut dr = -r * 2.0 / s;
        for j in 0..self.n {
            let p = (s2 + self.omega2[j]).inv();
            let a = self.phi1[j] * self.phi1[j];
            r += p * a;
            dr -= p * p * s * (2.0 * a);
        }
        let b = s * self.cb + self.kb;
        (b * r + 1.0, r * self.cb + b * dr)
    }

    /// |g(s)| relative to the size of the terms it is summed from.
    pub(super) fn residual(&self, s: C64) -> f64 {
        let s2 = s * s;
        let mut size = (s2 * self.m_eff).inv().norm();
        for j in 0..self.n {
            size += ((s2 + self.omega2[j]).inv() * (self.phi1[j] * self.phi1[j])).norm();
        }
        self.g(s).0.norm() / (1.0 + (s * self.cb + self.kb).norm() * size)
    }

    /// P'/P for P(s) = m_eff s² Π (s² + Ω_j²) g(s): the polynomial whose roots are g's, without its
    /// poles.
    pub(super) fn log_slope(&self, s: C64) -> C64 {
        let (g, dg) = self.g(s);
        let mut slope = dg / g + s.inv() * 2.0;
        for j in 0..self.n {
            slope += s * 2.0 / (s * s + self.omega2[j]);
        }
        slope
    }

    /// Newton's method on P from `s`, at most `steps` steps, stopping at rounding.
    pub(super) fn polish(&self, mut s: C64, steps: usize) -> C64 {
        for _ in 0..steps {
            let step = self.log_slope(s).inv();
            if !(step.re.is_finite() && step.im.is_finite()) {
                break;
            }
            s -= step;
            if step.norm_sqr() <= (4.0 * f64::EPSILON).powi(2) * s.norm_sqr() {
                break;
            }
        }
        s
    }

    /// Starting points: each undamped mode ω (1 + k_b R(iω) = 0, one root between neighbouring Ω_j²,
    /// Ω_0 = 0 for the ball), damped by the dashpot's share of it, σ = c_b e²/(2 (m_eff u² + Σ Q_j²)).
    pub(super) fn guesses(&self) -> Option<Vec<C64>> {
        let n = self.n;
        let mut poles: Vec<f64> = self.omega2[..n].to_vec();
        poles.push(0.0);
        poles.sort_by(f64::total_cmp);
        let weights: f64 = 1.0 / self.m_eff + self.phi1[..n].iter().map(|p| p * p).sum::<f64>();
        poles.push(poles[n] + self.kb * weights);
        let f = |lambda: f64| {
            let mut value = 1.0 - self.kb / (self.m_eff * lambda);
            let mut slope = self.kb / (self.m_eff * lambda * lambda);
            for j in 0..n {
                let d = self.omega2[j] - lambda;
                let a = self.phi1[j] * self.phi1[j];
                value += self.kb * a / d;
                slope += self.kb * a / (d * d);
            }
            (value, slope)
        };
        let mut out = Vec::with_capacity(2 * n + 2);
        for pair in poles.windows(2) {
            let (mut lo, mut hi) = (pair[0], pair[1]);
            if hi <= lo {
                continue;
            }
            let mut lambda = 0.5 * (lo + hi);
            for _ in 0..100 {
                let (value, slope) = f(lambda);
                if value < 0.0 {
                    lo = lambda;
                } else {
                    hi = lambda;
                }
                let step = value / slope;
                let newton = lambda - step;
                lambda = if newton > lo && newton < hi {
                    newton
                } else {
                    0.5 * (lo + hi)
                };
                // A start for Newton's method on g needs no more.
                if hi - lo <= 1e-6 * hi || step.abs() <= 1e-9 * lambda {
                    break;
                }
            }
            let omega = lambda.sqrt();
            let u = 1.0 / (self.m_eff * lambda);
            let mut mass = self.m_eff * u * u;
            let mut x1 = 0.0;
            for j in 0..n {
                let q = self.phi1[j] / (self.omega2[j] - lambda);
                mass += q * q;
                x1 += self.phi1[j] * q;
            }
            let e = u - x1;
            let sigma = self.cb * e * e / (2.0 * mass);
            if sigma < omega {
                let im = (omega * omega - sigma * sigma).sqrt();
                out.push(C64::new(-sigma, im));
                out.push(C64::new(-sigma, -im));
            } else {
                let d = (sigma * sigma - omega * omega).sqrt();
                out.push(C64::new(-sigma - d, 0.0));
                out.push(C64::new(-omega * omega / (sigma + d), 0.0));
            }
        }
        (out.len() == 2 * n + 2 && out.iter().all(|s| s.re.is_finite() && s.im.is_finite()))
            .then_some(out)
    }

    /// Every root, by Newton's method from each guess in turn on P divided by the roots already found
    /// (Maehly's deflation): each start finds a root not found before.
    pub(super) fn deflated(&self, guesses: &[C64]) -> Vec<C64> {
        let mut found: Vec<C64> = Vec::with_capacity(guesses.len());
        for &start in guesses {
            let mut s = start;
            for _ in 0..300 {
                let mut slope = self.log_slope(s);
                for &r in &found {
                    slope -= (s - r).inv();
                }
                let step = slope.inv();
                if !(step.re.is_finite() && step.im.is_finite()) {
                    break;
                }
                s -= step;
                if step.norm_sqr() <= (4.0 * f64::EPSILON).powi(2) * s.norm_sqr() {
                    break;
                }
            }
            found.push(s);
        }
        found
    }

    /// The modes from a set of roots: the upper half-plane and the real axis, each pair once, if they
    /// are all 2(N + 1) roots, distinct and accurate.
    pub(super) fn accept(&self, roots: &[C64]) -> Option<Vec<Mode>> {
        let mut kept: Vec<(C64, f64)> = Vec::with_capacity(roots.len());
        for &s in roots {
            if !(s.re.is_finite() && s.im.is_finite()) || s.norm() == 0.0 {
                return None;
            }
            if s.im.abs() <= REAL * s.norm() {
                kept.push((self.polish(C64::new(s.re, 0.0), 3), 1.0));
            } else if s.im > 0.0 {
                kept.push((s, 2.0));
            }
        }
        let total: f64 = kept.iter().map(|(_, w)| w).sum();
        if total != (2 * self.n + 2) as f64 {
            return None;
        }
        for (i, (a, _)) in kept.iter().enumerate() {
            if self.residual(*a) > RESIDUAL {
                return None;
            }
            if kept[..i]
                .iter()
                .any(|(b, _)| (a - b).norm() <= SAME * a.norm())
            {
                return None;
            }
        }
        Some(
            kept.iter()
                .map(|&(s, weight)| self.mode(s, weight))
                .collect(),
        )
    }

    pub(super) fn mode(&self, s: C64, weight: f64) -> Mode {
        let s2 = s * s;
        let u = -(s2 * self.m_eff).inv();
        let mut q = [C64::new(0.0, 0.0); MAX];
        let mut x1 = C64::new(0.0, 0.0);
        let mut kinetic = u * u * self.m_eff;
        let mut spring = 0.0;
        for ((qj, &phi), &omega2) in q.iter_mut().zip(&self.phi1).zip(&self.omega2).take(self.n) {
            *qj = (s2 + omega2).inv() * phi;
            x1 += *qj * phi;
            kinetic += *qj * *qj;
            spring += qj.norm_sqr() * omega2;
        }
        let e = u - x1;
        let force = e * (s * self.cb + self.kb);
        let norm = e * e * self.cb + kinetic * s * 2.0;
        // sqrt(2E) of the (complex) mode: k_b |e|² + Σ Ω² |Q|² + m_eff |s u|² + Σ |s Q|².
        let rates = (s * u).norm_sqr() * self.m_eff
            + q[..self.n]
                .iter()
                .map(|qj| (s * qj).norm_sqr())
                .sum::<f64>();
        let size = (self.kb * e.norm_sqr() + spring + rates).sqrt();
        Mode {
            s,
            rate: s.norm(),
            weight,
            u,
            q,
            e,
            force,
            norm,
            size,
        }
    }
}
