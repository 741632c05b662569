//! The free parameters of a fit and the space the optimiser moves in. A parameter bounded only below
//! by zero (a mass, a stiffness, mu, a duration) is fitted as its logarithm, so it stays positive and
//! its scale does not matter; any other is fitted as it is and clamped into its range. A parameter free
//! per group has one coordinate for each group of the data; the rows of a group see that one.

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
    /// The group whose rows this value holds for (an index into the data's groups); `None`: every row.
    pub group: Option<usize>,
}

impl Free {
    pub fn new(spec: &'static ParamSpec) -> Free {
        let positive = matches!(spec.range.low, Bound::Open(0.0) | Bound::Closed(0.0))
            && spec.range.high == Bound::Unbounded;
        Free {
            spec,
            scale: if positive { Scale::Log } else { Scale::Linear },
            group: None,
        }
    }

    /// The same parameter, for the rows of group `group` only.
    pub fn in_group(self, group: usize) -> Free {
        Free {
            group: Some(group),
            ..self
        }
    }

    /// True when this value holds for a row of group `group`.
    pub fn holds_for(&self, group: Option<usize>) -> bool {
        self.group.is_none() || self.group == group
    }

    /// The bounds of the coordinate: where the parameter reaches an end of its range (infinite for a
    /// log parameter, whose ends 0 and infinity lie at minus and plus infinity).
    pub fn coordinate_range(&self) -> (f64, f64) {
        let end = |b: Bound, unbounded: f64| match (self.scale, b) {
            (Scale::Linear, Bound::Open(x) | Bound::Closed(x)) => x,
            _ => unbounded,
        };
        (
            end(self.spec.range.low, f64::NEG_INFINITY),
            end(self.spec.range.high, f64::INFINITY),
        )
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
    parse_named("--free", list, data_columns, &[])
}

/// The parameters of `shared` (`--free`) for every row and those of `per_group` (`--free-per-group`)
/// once for each of `groups` labels, checked as [`parse_list`] does and not named in both lists.
pub fn parse_lists(
    shared: &str,
    per_group: &str,
    data_columns: &[ParamId],
    groups: usize,
) -> Result<Vec<Free>, String> {
    let mut free = if shared.trim().is_empty() {
        Vec::new()
    } else {
        parse_list(shared, data_columns)?
    };
    if per_group.trim().is_empty() {
        return Ok(free);
    }
    if groups == 0 {
        return Err("--free-per-group: name the column of group labels with --group".into());
    }
    let each = parse_named("--free-per-group", per_group, data_columns, &free)?;
    for f in each {
        free.extend((0..groups).map(|g| f.in_group(g)));
    }
    Ok(free)
}

fn parse_named(
    option: &str,
    list: &str,
    data_columns: &[ParamId],
    others: &[Free],
) -> Result<Vec<Free>, String> {
    let mut free: Vec<Free> = Vec::new();
    for name in list.split(',').map(str::trim) {
        let spec = spec_named(name).ok_or_else(|| {
            format!("{option}: unknown parameter '{name}' (use parameter flags: cart-mass, stiffness, mu, ...)")
        })?;
        if spec.integer {
            return Err(format!(
                "{option}: {} is a whole number and cannot be fitted; set it with --{}",
                spec.flag, spec.flag
            ));
        }
        if free.iter().any(|f| f.id() == spec.id) {
            return Err(format!("{option}: {} is named twice", spec.flag));
        }
        if others.iter().any(|f| f.id() == spec.id) {
            return Err(format!(
                "{option}: {} is also in --free; a parameter is shared or per group, not both",
                spec.flag
            ));
        }
        if data_columns.contains(&spec.id) {
            return Err(format!(
                "{option}: {} is a column of the data, a condition of each row, not a parameter to fit",
                spec.flag
            ));
        }
        free.push(Free::new(spec));
    }
    Ok(free)
}

/// `base` with the free parameters at coordinates `u`, as the rows of `group` see them (the shared
/// parameters, and those of the group).
pub fn place_for(base: &Params, free: &[Free], u: &[f64], group: Option<usize>) -> Params {
    let mut p = *base;
    for (f, &x) in free.iter().zip(u) {
        if f.holds_for(group) {
            p.set(f.id(), f.value(x));
        }
    }
    p
}

/// `base` with the shared free parameters at coordinates `u`.
pub fn place(base: &Params, free: &[Free], u: &[f64]) -> Params {
    place_for(base, free, u, None)
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
    fn a_parameter_per_group_has_a_coordinate_for_each_group() {
        let free = parse_lists("mu", "cart-friction", &[], 3).unwrap();
        let groups: Vec<_> = free.iter().map(|f| f.group).collect();
        assert_eq!(groups, vec![None, Some(0), Some(1), Some(2)]);
        let base = Params::default();
        let u = [0.3f64.ln(), 0.1f64.ln(), 0.2f64.ln(), 0.4f64.ln()];
        let p = place_for(&base, &free, &u, Some(1));
        assert!((p.mu - 0.3).abs() < 1e-12 && (p.cart_friction - 0.2).abs() < 1e-12);
        assert_eq!(place(&base, &free, &u).cart_friction, base.cart_friction);
        assert!(
            parse_lists("mu", "mu", &[], 2)
                .unwrap_err()
                .contains("also in --free")
        );
        assert!(
            parse_lists("", "mu", &[], 0)
                .unwrap_err()
                .contains("--group")
        );
        assert_eq!(Free::new(spec(ParamId::Ey)).coordinate_range(), (0.0, 1.0));
        assert_eq!(
            Free::new(spec(ParamId::CartMass)).coordinate_range(),
            (f64::NEG_INFINITY, f64::INFINITY)
        );
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
