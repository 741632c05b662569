//! The carts and incident conditions of the paper's Figs. 2 and 3 (Sec. III; listed in
//! `assets/claims.md`): a heavy cart, a light cart and a light cart on a soft spring.

use crate::model::params::ParamId;
use crate::model::{Bounce, Params, SolveOptions, solve_with};

use super::AnalysisError;

/// A cart: its mass and the stiffness of its spring.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cart {
    /// Short name, e.g. `heavy cart`.
    pub name: &'static str,
    /// The values for a legend, e.g. `M = 10 kg, k = 4×10⁴ N/m`.
    pub label: &'static str,
    /// M, kg.
    pub mass: f64,
    /// k, N/m.
    pub stiffness: f64,
}

/// M = 10 kg, k = 4e4 N/m: close to the rigid surface of Eq. (7).
pub const HEAVY: Cart = Cart {
    name: "heavy cart",
    label: "M = 10 kg, k = 4×10⁴ N/m",
    mass: 10.0,
    stiffness: 4e4,
};

/// M = 10 g, k = 4e4 N/m.
pub const LIGHT: Cart = Cart {
    name: "light cart",
    label: "M = 10 g, k = 4×10⁴ N/m",
    mass: 0.010,
    stiffness: 4e4,
};

/// M = 10 g, k = 1.5e4 N/m: the paper's Fig. 3(c), whose period suits the 5 ms impact.
pub const SOFT: Cart = Cart {
    name: "soft spring",
    label: "M = 10 g, k = 1.5×10⁴ N/m",
    mass: 0.010,
    stiffness: 1.5e4,
};

/// The three carts of Fig. 2 and Fig. 3, in the paper's order (a), (b), (c).
pub const CARTS: [Cart; 3] = [HEAVY, LIGHT, SOFT];

/// The incident spins of Fig. 2(a) and 2(b), rad/s.
pub const SPINS: [f64; 2] = [0.0, -100.0];

/// The angle of incidence of Fig. 3, degrees.
pub const FIG3_ANGLE: f64 = 60.0;

impl Cart {
    /// `base` on this cart, at `angle` degrees with incident spin `spin` rad/s.
    pub fn case(&self, base: &Params, angle: f64, spin: f64) -> Params {
        let mut p = *base;
        p.set(ParamId::CartMass, self.mass);
        p.set(ParamId::Stiffness, self.stiffness);
        p.set(ParamId::Angle, angle);
        p.set(ParamId::Spin, spin);
        p
    }

    /// The bounce of [`Cart::case`], solved on the caller's terms.
    pub fn solve(
        &self,
        base: &Params,
        angle: f64,
        spin: f64,
        options: &SolveOptions,
    ) -> Result<Bounce, AnalysisError> {
        solve_with(&self.case(base, angle, spin), options).map_err(|source| AnalysisError::Case {
            case: format!("{} at {angle} deg, omega1 = {spin} rad/s", self.name),
            source,
        })
    }
}
