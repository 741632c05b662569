//! Which value of one parameter makes a computed quantity equal a printed number: the evidence
//! `reproduce` gives when the paper's value differs from the model's.

use rayon::prelude::*;

use crate::model::Params;
use crate::model::params::{ParamId, spec};

/// Scan points before bisection.
const SCAN: usize = 41;

/// The value of `id` in `[lo, hi]` nearest (relatively) to its value in `base` at which `f` equals
/// `target`: a scan (geometric when both ends are positive and a decade or more apart), then bisection
/// of every sign change to a relative 1e-10. `None` when `f - target` changes sign nowhere in the scan.
pub fn retune(
    base: &Params,
    id: ParamId,
    lo: f64,
    hi: f64,
    target: f64,
    f: impl Fn(&Params) -> Option<f64> + Sync,
) -> Option<f64> {
    let geometric = lo > 0.0 && hi / lo >= 10.0;
    let at = |u: f64| {
        if geometric {
            (lo.ln() + (hi.ln() - lo.ln()) * u).exp()
        } else {
            lo + (hi - lo) * u
        }
    };
    let gap = |value: f64| {
        let mut p = *base;
        p.set(id, value);
        f(&p).map(|v| v - target)
    };
    let scan: Vec<(f64, Option<f64>)> = (0..SCAN)
        .into_par_iter()
        .map(|i| {
            let u = i as f64 / (SCAN - 1) as f64;
            (u, gap(at(u)))
        })
        .collect();
    let current = base.get(id);
    let distance = |v: f64| ((v - current) / current.abs().max(f64::MIN_POSITIVE)).abs();
    scan.windows(2)
        .filter_map(|pair| match (pair[0], pair[1]) {
            ((ua, Some(0.0)), _) => Some(at(ua)),
            ((ua, Some(ga)), (ub, Some(gb))) if ga.signum() != gb.signum() => {
                let (mut ua, mut ub, mut ga) = (ua, ub, ga);
                for _ in 0..200 {
                    if (at(ub) - at(ua)).abs() <= 1e-10 * at(ua).abs().max(at(ub).abs()) {
                        break;
                    }
                    let um = 0.5 * (ua + ub);
                    match gap(at(um)) {
                        Some(gm) if gm.signum() == ga.signum() => {
                            ua = um;
                            ga = gm;
                        }
                        Some(_) => ub = um,
                        None => return None,
                    }
                }
                Some(at(0.5 * (ua + ub)))
            }
            _ => None,
        })
        .min_by(|a, b| distance(*a).total_cmp(&distance(*b)))
        .filter(|v| spec(id).range.contains(*v))
}

/// The values of the `candidates` (parameter, search interval) at which `f` equals `target`, for a
/// note: e.g. `k = 43210 N/m (43.21 kN/m) or M = 9.10 g`. `None` when no candidate reaches it.
pub fn explain(
    base: &Params,
    target: f64,
    candidates: &[(ParamId, f64, f64)],
    f: impl Fn(&Params) -> Option<f64> + Sync,
) -> Option<String> {
    let found: Vec<String> = candidates
        .iter()
        .filter_map(|&(id, lo, hi)| {
            let s = spec(id);
            retune(base, id, lo, hi, target, &f).map(|v| {
                format!(
                    "{} = {} (not {})",
                    s.symbol,
                    crate::model::units::show(v, s.dimension, s.display_unit, s.decimals + 1),
                    s.show(base.get(id))
                )
            })
        })
        .collect();
    (!found.is_empty()).then(|| found.join(" or "))
}
