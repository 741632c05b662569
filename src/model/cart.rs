//! What the cart does in a phase: moves, with string-on-string friction F_c against its motion, or
//! sticks, held by that friction (Sec. IV's proposed enhancement; F_c = 0 is the paper's model).

use serde::Serialize;

use super::setup::Setup;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Cart {
    /// Moving in direction +1 or -1; with no string friction the direction plays no part.
    Moving(i8),
    /// Held still by string friction.
    Stuck,
}

impl Cart {
    /// The string friction on the moving cart, -dir F_c (zero when stuck: the holding force is not a
    /// driving term of the motion).
    pub fn friction(self, setup: &Setup) -> f64 {
        match self {
            Cart::Moving(dir) => -f64::from(dir) * setup.cart_friction,
            Cart::Stuck => 0.0,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Cart::Moving(_) => "moving",
            Cart::Stuck => "stuck",
        }
    }
}
