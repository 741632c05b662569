//! The critical angle: below it the ball slides one way for the whole contact (Eq. (7)); above it the
//! friction reverses or the ball grips. And the second threshold, where a grip first appears.

use rayon::prelude::*;
use serde::Serialize;

use crate::model::params::ParamId;
use crate::model::{Params, PhaseKind, SolveError, SolveOptions, solve_with};

/// Where a sliding regime ends as theta1 rises from glancing incidence: sliding one way throughout
/// (the critical angle), or sliding without a grip (the first grip).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "regime", content = "deg", rename_all = "kebab-case")]
pub enum Critical {
    /// The regime holds for every theta1 below this angle, degrees.
    At(f64),
    /// The regime holds at every angle up to normal incidence.
    AlwaysSlides,
    /// The regime does not hold even at the most glancing angle.
    NeverSlidesThroughout,
    /// Eq. (7) does not apply: r omega1 >= v1, so the contact point arrives at rest or moving backward
    /// at every angle, and the equation assumes it moves forward.
    Inapplicable,
}

impl Critical {
    pub fn degrees(self) -> Option<f64> {
        match self {
            Critical::At(deg) => Some(deg),
            _ => None,
        }
    }
}

/// Eq. (7), the rigid-surface limit: the ball's contact point comes to rest exactly as it leaves,
/// v_x1 - r omega1 = (1 + e_y) mu (1 + 1/alpha) v_y1, i.e. for e_y = 1
/// tan(theta1) = (1 - r omega1 / v_x1) / (2 mu (1 + 1/alpha)).
///
/// v_x1 = v1 cos(theta1) depends on theta1, so with omega1 != 0 this is an equation in theta1, not a
/// formula. Divided by v1 it reads cos(theta1) - c sin(theta1) = r omega1 / v1 with
/// c = (1 + e_y) mu (1 + 1/alpha); the left side is sqrt(1 + c^2) cos(theta1 + atan c), strictly
/// decreasing on [0, 90] deg, so the root is unique and exact:
/// theta1 = acos(r omega1 / (v1 sqrt(1 + c^2))) - atan(c).
pub fn eq7(p: &Params) -> Critical {
    let c = (1.0 + p.ey) * p.mu * (1.0 + 1.0 / p.alpha);
    let s = p.radius * p.spin / p.speed;
    if s >= 1.0 {
        return Critical::Inapplicable;
    }
    if s <= -c {
        // Even at normal incidence the friction impulse cannot stop the slip.
        return Critical::AlwaysSlides;
    }
    let theta = (s / (1.0 + c * c).sqrt()).acos() - c.atan();
    Critical::At(theta.to_degrees())
}

/// The scan step of [`thresholds`], degrees. Sliding one way ends where the slip first reaches zero
/// exactly at release; as theta1 rises that moment moves continuously earlier, to where N is large
/// enough to hold a grip, so a scan this fine steps over neither threshold (none did over 1500 random
/// carts and chains scanned every 0.005 deg); bisection then gives each far finer than 0.01 deg.
const SCAN_STEP: f64 = 0.05;

/// Scan angles solved together before looking for the first grip.
const BLOCK: usize = 128;

/// The full model's two thresholds for the cart of `p` (its angle is ignored).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thresholds {
    /// The critical angle as Eq. (7) means it: the largest theta1 below which the ball slides one way
    /// for the whole contact ([`crate::model::Bounce::slides_throughout`]).
    pub slides_throughout: Critical,
    /// The largest theta1 below which the ball never grips. Between the two the slip reaches zero
    /// while the grip cannot hold (on a light cart, late in the contact as N falls), so the friction
    /// reverses without gripping (slide-slide). A compliant ball's patch always grips when its slip
    /// reaches zero, so for it the two coincide.
    pub first_grip: Critical,
}

/// What one solve tells the scan.
#[derive(Clone, Copy)]
struct Regime {
    one_way: bool,
    grips: bool,
}

fn regime(p: &Params, deg: f64, options: &SolveOptions) -> Result<Regime, SolveError> {
    let mut q = *p;
    q.set(ParamId::Angle, deg);
    let b = solve_with(&q, options)?;
    Ok(Regime {
        one_way: b.slides_throughout(),
        grips: b.phases.iter().any(|ph| ph.kind == PhaseKind::Grip),
    })
}

/// Both thresholds: every 0.05 deg from 0.05 deg upward is solved, in blocks on all cores, until the
/// ball grips; for each threshold the first angle past it and the one before are then bisected to
/// 1e-9 deg.
pub fn thresholds(p: &Params) -> Result<Thresholds, SolveError> {
    thresholds_with(p, &SolveOptions::default())
}

/// [`thresholds`] with every bounce solved on the caller's terms.
pub fn thresholds_with(p: &Params, options: &SolveOptions) -> Result<Thresholds, SolveError> {
    let n = (90.0 / SCAN_STEP).round() as usize;
    let angle = |i: usize| if i == n { 90.0 } else { i as f64 * SCAN_STEP };
    let mut scanned: Vec<Regime> = Vec::with_capacity(n);
    for block in (1..=n).collect::<Vec<_>>().chunks(BLOCK) {
        let found: Vec<Regime> = block
            .par_iter()
            .map(|&i| regime(p, angle(i), options))
            .collect::<Result<_, _>>()?;
        scanned.extend(found);
        if scanned.iter().any(|r| r.grips) {
            break;
        }
    }
    let edge = |holds: fn(Regime) -> bool| -> Result<Critical, SolveError> {
        let Some(first) = scanned.iter().position(|&r| !holds(r)) else {
            return Ok(Critical::AlwaysSlides);
        };
        if first == 0 {
            return Ok(Critical::NeverSlidesThroughout);
        }
        // scanned[i] is angle(i + 1).
        let (mut lo, mut hi) = (angle(first), angle(first + 1));
        while hi - lo > 1e-9 {
            let mid = 0.5 * (lo + hi);
            if holds(regime(p, mid, options)?) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Ok(Critical::At(0.5 * (lo + hi)))
    };
    Ok(Thresholds {
        slides_throughout: edge(|r| r.one_way)?,
        first_grip: edge(|r| !r.grips)?,
    })
}

/// The full model's critical angle: [`Thresholds::slides_throughout`].
pub fn full_model(p: &Params) -> Result<Critical, SolveError> {
    full_model_with(p, &SolveOptions::default())
}

/// [`full_model`] with every bounce solved on the caller's terms.
pub fn full_model_with(p: &Params, options: &SolveOptions) -> Result<Critical, SolveError> {
    thresholds_with(p, options).map(|t| t.slides_throughout)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eq7_without_spin_is_explicit() {
        let p = Params {
            spin: 0.0,
            ..Params::default()
        };
        let expected = (1.0_f64 / (2.0 * 0.4 * (1.0 + 1.0 / 0.55)))
            .atan()
            .to_degrees();
        let got = eq7(&p).degrees().unwrap();
        assert!((got - expected).abs() < 1e-12, "{got} {expected}");
    }

    #[test]
    fn eq7_with_backspin_satisfies_the_equation() {
        let p = Params::default();
        let theta = eq7(&p).degrees().unwrap().to_radians();
        let vx1 = p.speed * theta.cos();
        let rhs = (1.0 - p.radius * p.spin / vx1) / (2.0 * p.mu * (1.0 + 1.0 / p.alpha));
        assert!((theta.tan() - rhs).abs() < 1e-12);
    }

    #[test]
    fn eq7_limits() {
        let topspin = Params {
            spin: 400.0,
            ..Params::default()
        };
        assert_eq!(eq7(&topspin), Critical::Inapplicable);
        let frictionless = Params {
            mu: 0.0,
            ..Params::default()
        };
        assert_eq!(eq7(&frictionless), Critical::AlwaysSlides);
    }
}
