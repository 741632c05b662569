//! The free parameters of a fit and the space the optimiser moves in. A parameter bounded only below
//! by zero (a mass, a stiffness, mu, a duration) is fitted as its logarithm, so it stays positive and
//! its scale does not matter; any other is fitted as it is and clamped into its range.

use crate::model::params::{Bound, ParamId, ParamSpec, Params, Step, spec_named};

/// How a parameter maps to the optimiser's coordinate u.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// u = ln p.
    Log,
    /// u = p, clamped into the range.
    Linear,
}

/// One free parameter.
#[derive(Clone, Copy, Debug)]
pub struct Free {
    pub spec: &'static ParamSpec,
    pub scale: Scale,
}

impl Free {
    pub fn new(spec: &'static ParamSpec) -> Free {
        let positive = matches!(spec.range.low, Bound::Open(0.0) | Bound::Closed(0.0))
            && spec.range.high == Bound::Unbounded;
        Free {
            spec,
            scale: if positive { Scale::Log } else { Scale::Linear },
        }
    }

    pub fn id(&self) -> ParamId {
        self.spec.id
    }

    /// The parameter value at coordinate `u`, inside its range.
    pub fn value(&self, u: f64) -> f64 {
        let p = match self.scale {
            Scale::Log => u.exp(),
            Scale::Linear => u,
        };
        self.spec.range.clamp(p)
    }

    /// The coordinate of value `p` (a zero of a log parameter is moved to a small positive value).
    pub fn coordinate(&self, p: f64) -> f64 {
        match self.scale {
            Scale::Log => p.max(f64::MIN_POSITIVE).ln(),
            Scale::Linear => p,
        }
    }

    /// The box the starting points are drawn from: a decade and a half either side of `p` for a log
    /// parameter (from the first step above zero when `p` is zero), the whole range when it is finite,
    /// and otherwise `p` give or take twice its size plus the coarse step.
    pub fn start_box(&self, p: f64) -> (f64, f64) {
        match self.scale {
            Scale::Log => {
                let centre = if p > 0.0 {
                    p
                } else if self.spec.default > 0.0 {
                    self.spec.default
                } else {
                    Step::FIRST_FROM_ZERO
                };
                let c = centre.ln();
                (
                    c - 1.5 * std::f64::consts::LN_10,
                    c + 1.5 * std::f64::consts::LN_10,
                )
            }
            Scale::Linear => match (self.spec.range.low, self.spec.range.high) {
                (Bound::Open(a) | Bound::Closed(a), Bound::Open(b) | Bound::Closed(b)) => (a, b),
                _ => {
                    let step = match self.spec.coarse {
                        Step::Add(d) => d,
                        Step::Times(_) => 1.0,
                    };
                    let half = 2.0 * p.abs() + step;
                    (p - half, p + half)
                }
            },
        }
    }
}

/// The free parameters named in `list` (flags or keys, comma separated), checked: known, not a count
/// (the chain), not twice, not also a data column.
pub fn parse_list(list: &str, data_columns: &[ParamId]) -> Result<Vec<Free>, String> {
    let mut free: Vec<Free> = Vec::new();
    for name in list.split(',').map(str::trim) {
        let spec = spec_named(name).ok_or_else(|| {
            format!("--free: unknown parameter '{name}' (use parameter flags: cart-mass, stiffness, mu, ...)")
        })?;
        if spec.integer {
            return Err(format!(
                "--free: {} is a whole number and cannot be fitted; set it with --{}",
                spec.flag, spec.flag
            ));
        }
        if free.iter().any(|f| f.id() == spec.id) {
            return Err(format!("--free: {} is named twice", spec.flag));
        }
        if data_columns.contains(&spec.id) {
            return Err(format!(
                "--free: {} is a column of the data, a condition of each row, not a parameter to fit",
                spec.flag
            ));
        }
        free.push(Free::new(spec));
    }
    Ok(free)
}

/// `base` with the free parameters at coordinates `u`.
pub fn place(base: &Params, free: &[Free], u: &[f64]) -> Params {
    let mut p = *base;
    for (f, &x) in free.iter().zip(u) {
        p.set(f.id(), f.value(x));
    }
    p
}

/// The coordinates of the free parameters' values in `params`.
pub fn coordinates(params: &Params, free: &[Free]) -> Vec<f64> {
    free.iter()
        .map(|f| f.coordinate(params.get(f.id())))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::spec;

    #[test]
    fn positive_parameters_are_fitted_in_log_space_and_others_clamped() {
        let mass = Free::new(spec(ParamId::CartMass));
        assert_eq!(mass.scale, Scale::Log);
        assert!((mass.value(mass.coordinate(0.002)) - 0.002).abs() < 1e-15);
        let angle = Free::new(spec(ParamId::Angle));
        assert_eq!(angle.scale, Scale::Linear);
        assert_eq!(angle.value(120.0), 90.0);
        assert_eq!(Free::new(spec(ParamId::Spin)).scale, Scale::Linear);
        assert_eq!(Free::new(spec(ParamId::Ey)).start_box(0.8), (0.0, 1.0));
    }

    #[test]
    fn the_list_is_checked() {
        assert_eq!(parse_list("cart-mass,stiffness", &[]).unwrap().len(), 2);
        assert!(
            parse_list("chain", &[])
                .unwrap_err()
                .contains("whole number")
        );
        assert!(
            parse_list("mu,mu", &[])
                .unwrap_err()
                .contains("named twice")
        );
        assert!(
            parse_list("angle", &[ParamId::Angle])
                .unwrap_err()
                .contains("column of the data")
        );
        assert!(
            parse_list("moo", &[])
                .unwrap_err()
                .contains("unknown parameter 'moo'")
        );
    }
}
