//! The critical angle: below it the ball slides for the whole contact; above it, it grips.

use rayon::prelude::*;
use serde::Serialize;

use crate::model::params::ParamId;
use crate::model::{Params, SolveError, solve};

/// Where the sliding regime ends as theta1 rises from glancing incidence.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "regime", content = "deg", rename_all = "kebab-case")]
pub enum Critical {
    /// The ball slides throughout for every theta1 below this angle, degrees.
    At(f64),
    /// The ball slides throughout at every angle up to normal incidence.
    AlwaysSlides,
    /// The ball grips even at the most glancing angle.
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

/// The scan step of [`full_model`], degrees. The sliding regime ends where the slip first reaches zero
/// exactly at release, and the grip then moves continuously earlier as theta1 rises, so a scan this
/// fine does not step over it; bisection then gives the angle far finer than 0.01 deg.
const SCAN_STEP: f64 = 0.05;

/// Scan angles solved together before looking for the first grip.
const BLOCK: usize = 128;

/// The full model's critical angle for the cart of `p` (its angle is ignored): the largest theta1
/// below which `slides_throughout()` holds. Every 0.05 deg from 0.05 deg upward is solved, in blocks
/// on all cores, until one grips; that angle and the one before it are then bisected to 1e-9 deg.
pub fn full_model(p: &Params) -> Result<Critical, SolveError> {
    let slides = |deg: f64| -> Result<bool, SolveError> {
        let mut q = *p;
        q.set(ParamId::Angle, deg);
        Ok(solve(&q)?.slides_throughout())
    };
    let n = (90.0 / SCAN_STEP).round() as usize;
    let angle = |i: usize| if i == n { 90.0 } else { i as f64 * SCAN_STEP };
    // Blocks of angles solved on all cores, upward from glancing incidence until one grips.
    let mut first_grip = None;
    for block in (1..=n).collect::<Vec<_>>().chunks(BLOCK) {
        let slid: Vec<bool> = block
            .par_iter()
            .map(|&i| slides(angle(i)))
            .collect::<Result<_, _>>()?;
        if let Some(j) = slid.iter().position(|s| !s) {
            first_grip = Some(block[j]);
            break;
        }
    }
    let Some(first_grip) = first_grip else {
        return Ok(Critical::AlwaysSlides);
    };
    if first_grip == 1 {
        return Ok(Critical::NeverSlidesThroughout);
    }
    let (mut lo, mut hi) = (angle(first_grip - 1), angle(first_grip));
    while hi - lo > 1e-9 {
        let mid = 0.5 * (lo + hi);
        if slides(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(Critical::At(0.5 * (lo + hi)))
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
