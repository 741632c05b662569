//! Causes of a close value that the model can demonstrate, computed on the spot: a parameter that the
//! paper prints rounded, kept within that rounding, which makes the computed value print the paper's
//! number.

use crate::analysis::retune;
use crate::model::Params;
use crate::model::params::ParamId;

/// The parameters the paper prints to two significant figures, at their printed values, with half a
/// unit of the last printed digit: m = 57 g, r = 33 mm, alpha = 0.55 (the tennis ball's measured
/// properties) and the soft spring's k = 1.5×10⁴ N/m. The one-figure values (mu = 0.4, v1 = 10 m/s,
/// T = 5 ms, M = 10 g, k = 4×10⁴ N/m) are round inputs chosen for the model, and a rounding of 10 %
/// and more would explain anything.
const ROUNDED: [(ParamId, f64, f64); 4] = [
    (ParamId::Mass, 0.057, 0.0005),
    (ParamId::Radius, 0.033, 0.0005),
    (ParamId::Alpha, 0.55, 0.005),
    (ParamId::Stiffness, 1.5e4, 500.0),
];

/// Which rounded parameter of `case` (one still at its printed value), kept within its rounding,
/// makes `f` equal the printed `target`; `None` when none does.
pub fn rounded(
    case: &Params,
    target: f64,
    f: impl Fn(&Params) -> Option<f64> + Sync,
) -> Option<String> {
    let candidates: Vec<(ParamId, f64, f64)> = ROUNDED
        .iter()
        .filter(|&&(id, printed, _)| case.get(id) == printed)
        .map(|&(id, printed, half)| (id, printed - half, printed + half))
        .collect();
    retune::explain(case, target, &candidates, f).map(|found| {
        format!(
            "a parameter the paper rounds gives {target}: {found}, within the rounding of its \
             printed value"
        )
    })
}
