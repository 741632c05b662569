//! The stretch of the compliant ball's spring while it slides, in closed form.

use super::super::trig::sin_cos;
use super::BallSpring;
use crate::model::setup::Setup;

/// After this many decay times 1/lambda the stretch's transient has fallen by e^-40 (4e-18): the slide's
/// event search and quadrature use steps and panels on the transient's scale before, and on the cart's
/// after (a lightly damped ball has lambda = sqrt(k_b/m_eff)/(2 zeta) huge, and a whole phase on its
/// scale would never end).
pub(super) const SETTLED: f64 = 40.0;

/// The stretch of the ball's spring during a slide: e = C e^{-lambda tau} + P(t), with the particular
/// response P(t) = a (lambda sin wt - w cos wt), a = dir mu N0 / (c_b (lambda² + w²)); without damping
/// e = F/k_b.
#[derive(Clone, Copy, Debug)]
pub struct Stretch {
    t0: f64,
    /// C, m (0 without damping).
    transient: f64,
    /// a, m (dir mu N0 / k_b without damping).
    amplitude: f64,
    /// sqrt(lambda² + w²), for the bounds (w without damping).
    rate: f64,
    /// sin and cos of w t0, for [`Stretch::rates`] (with damping).
    angle0: (f64, f64),
    /// The ball's spring and dashpot. lambda = k_b/c_b is divided out where it is used rather than
    /// stored, so that a slide is no larger than the framed cart's phase ([`super::CompliantSlide`]).
    pub(super) spring: BallSpring,
}

impl Stretch {
    pub(super) fn new(c: &BallSpring, setup: &Setup, dir: f64, t0: f64, e0: f64) -> Self {
        let force = dir * setup.peak_friction();
        if c.cb > 0.0 {
            let lambda = c.kb / c.cb;
            let w = setup.w;
            let amplitude = force / (c.cb * (lambda * lambda + w * w));
            let (s, co) = sin_cos(w * t0);
            let p0 = amplitude * (lambda * s - w * co);
            Stretch {
                t0,
                transient: e0 - p0,
                amplitude,
                rate: lambda.hypot(w),
                angle0: (s, co),
                spring: *c,
            }
        } else {
            Stretch {
                t0,
                transient: 0.0,
                amplitude: force / c.kb,
                rate: setup.w,
                angle0: (0.0, 1.0),
                spring: *c,
            }
        }
    }

    /// True with a dashpot (c_b > 0): the stretch then relaxes at the rate lambda.
    #[inline]
    pub(super) fn damped(&self) -> bool {
        self.spring.cb > 0.0
    }

    /// lambda = k_b/c_b, the rate the stretch relaxes at (infinite without a dashpot: the stretch is
    /// then F/k_b at once).
    #[inline]
    pub(super) fn lambda(&self) -> f64 {
        if self.damped() {
            self.spring.kb / self.spring.cb
        } else {
            f64::INFINITY
        }
    }

    /// (e, e', e'') at `t`.
    #[inline]
    pub(super) fn at(&self, w: f64, t: f64) -> (f64, f64, f64) {
        let (s, co) = sin_cos(w * t);
        if self.damped() {
            let l = self.spring.kb / self.spring.cb;
            let decay = self.transient * (-l * (t - self.t0)).exp();
            let p = self.amplitude * (l * s - w * co);
            let dp = self.amplitude * w * (l * co + w * s);
            (decay + p, -l * decay + dp, l * l * decay - w * w * p)
        } else {
            let s = s.max(0.0);
            let e = self.amplitude * s;
            (e, self.amplitude * w * co, -w * w * e)
        }
    }

    /// e' and e'' written once for the phase as fixed combinations of sin and cos of w τ (τ = t - t0)
    /// and the transient's decay (`None` without damping), for an event search that has those angles at
    /// hand ([`StretchRates`]).
    pub(super) fn rates(&self, w: f64) -> Option<StretchRates> {
        if !self.damped() {
            return None;
        }
        let l = self.lambda();
        // The particular response P = a (lambda sin wt - w cos wt), with sin wt and cos wt by angle
        // addition from w t0: P' = a w (lambda cos wt + w sin wt), P'' = -w² P.
        let (s0, c0) = self.angle0;
        let aw = self.amplitude * w;
        let (lead, lag) = (l * c0 + w * s0, w * c0 - l * s0);
        Some(StretchRates {
            t0: self.t0,
            lambda: l,
            transient: self.transient,
            first: [aw * lead, aw * lag],
            second: [aw * w * lag, -aw * w * lead],
        })
    }

    /// Where the transient has died out (t0 without damping).
    pub(super) fn settled(&self) -> f64 {
        if self.damped() {
            self.t0 + SETTLED / self.lambda()
        } else {
            self.t0
        }
    }

    /// A bound on |e'''| from `from` (at or after t0) on.
    pub(super) fn third(&self, w: f64, from: f64) -> f64 {
        if self.damped() {
            let l = self.lambda();
            let decay = (-l * (from - self.t0)).exp();
            l * l * l * self.transient.abs() * decay + self.amplitude.abs() * w.powi(3) * self.rate
        } else {
            self.amplitude.abs() * w.powi(3)
        }
    }

    /// A bound on |e'| from t0 on.
    pub(super) fn speed(&self, w: f64) -> f64 {
        if self.damped() {
            self.lambda() * self.transient.abs() + self.amplitude.abs() * w * self.rate
        } else {
            self.amplitude.abs() * w
        }
    }
}

/// The damped stretch's rates e' = -lambda T + P' and e'' = lambda² T - w² P, T = C e^{-lambda τ} the
/// transient, with the particular response's as fixed combinations of sin and cos of w τ
/// ([`Stretch::rates`]): an evaluation is one exponential and a few products.
#[derive(Clone, Copy, Debug)]
pub(super) struct StretchRates {
    t0: f64,
    lambda: f64,
    /// C, m.
    transient: f64,
    /// P' = first[0] cos w τ + first[1] sin w τ.
    first: [f64; 2],
    /// -w² P = second[0] cos w τ + second[1] sin w τ.
    second: [f64; 2],
}

impl StretchRates {
    /// (e', e'') at `t`, given sin and cos of w τ there.
    #[inline(always)]
    pub(super) fn at(&self, t: f64, (s, c): (f64, f64)) -> (f64, f64) {
        let l = self.lambda;
        let decay = self.transient * (-l * (t - self.t0)).exp();
        (
            -l * decay + self.first[0] * c + self.first[1] * s,
            l * l * decay + self.second[0] * c + self.second[1] * s,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::params::Params;
    use super::*;

    /// The rates written as sums of sin and cos of w τ are the stretch's own e' and e'', to rounding,
    /// from a slide starting at first contact or later, either way, light to heavy damping.
    #[test]
    fn the_rates_by_sums_are_the_stretchs() {
        for (zeta, dir, start, e0) in [
            (0.05, 1.0, 0.0, 0.0),
            (0.3, -1.0, 0.2, 1e-4),
            (1.0, 1.0, 0.55, -3e-4),
            (4.0, -1.0, 0.9, 2e-5),
        ] {
            let params = Params {
                ball_stiffness: 1e5,
                ball_damping: zeta,
                ..Params::default()
            };
            let setup = Setup::new(&params);
            let spring = BallSpring::new(&params, &setup);
            let w = setup.w;
            let t0 = start * setup.duration;
            let stretch = Stretch::new(&spring, &setup, dir, t0, e0);
            let rates = stretch.rates(w).expect("damped");
            let scale = stretch.speed(w) * (1.0 + stretch.lambda() / w);
            for k in 0..=20 {
                let t = t0 + (setup.duration - t0) * f64::from(k) / 20.0;
                let (_, de, dde) = stretch.at(w, t);
                let (by_sums, second) = rates.at(t, sin_cos(w * (t - t0)));
                let what = format!("zeta {zeta} dir {dir} t0 {t0} t {t}");
                assert!((by_sums - de).abs() <= 1e-13 * scale, "e' {what}");
                assert!(
                    (second - dde).abs() <= 1e-13 * scale * (stretch.lambda() + w),
                    "e'' {what}"
                );
            }
        }
        let undamped = Params {
            ball_stiffness: 1e5,
            ball_damping: 0.0,
            ..Params::default()
        };
        let setup = Setup::new(&undamped);
        let stretch = Stretch::new(&BallSpring::new(&undamped, &setup), &setup, 1.0, 0.0, 0.0);
        assert!(stretch.rates(setup.w).is_none());
    }
}
