//! How the explorer writes a parameter's value: in the unit people think in, the same in the parameter
//! panel, the history's account of a change and the status line.

use crate::model::ParamSpec;
use crate::model::units::Shown;

/// `value` as the panel shows it: in the parameter's display unit, but a mass of 1 kg or more in kg.
pub fn shown(spec: &ParamSpec, value: f64) -> Shown {
    let shown = spec.show(value);
    if shown.symbol == "g" && value >= 1.0 {
        Shown {
            value,
            symbol: "kg",
            decimals: 3,
            ..shown
        }
    } else {
        shown
    }
}
