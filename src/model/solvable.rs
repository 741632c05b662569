//! What the solver can finish. Every value in a parameter's range is valid input, but f64 carries a
//! bounce through only while its scales stay clear of overflow, underflow and rounding: each parameter
//! is checked against the magnitudes its row of the parameter table says can be solved
//! ([`ParamSpec::solvable`]), and a lightly damped ball against the relaxation its dashpot can resolve.

use super::error::Unsolvable;
use super::params::{PARAM_COUNT, PARAMS, ParamId, ParamSpec, Params, Solvable, spec};
use super::units;

/// Why the scales are bounded.
pub(super) const SCALES: &str = "beyond, the bounce's forces and rates leave what f64 resolves";

/// The most decay times 1/lambda of a damped ball's stretch (lambda = k_b/c_b) that one contact may
/// hold: the slide's event search steps on that scale while the transient lasts, and a step must stay
/// far above the rounding of t.
pub const MAX_RELAXATIONS: f64 = 1e15;

/// Each parameter's solvable magnitudes from its row of [`PARAMS`]: the smallest, the largest, and
/// 0 where its range allows zero (NaN where not, so that no size equals it); a row without limits
/// allows from 0 to infinity.
const LIMITS: [[f64; PARAM_COUNT]; 3] = {
    let mut limits = [
        [0.0; PARAM_COUNT],
        [f64::INFINITY; PARAM_COUNT],
        [f64::NAN; PARAM_COUNT],
    ];
    let mut i = 0;
    while i < PARAM_COUNT {
        if let Some(limit) = PARAMS[i].solvable {
            limits[0][i] = limit.smallest;
            limits[1][i] = limit.largest;
            if PARAMS[i].range.contains(0.0) {
                limits[2][i] = 0.0;
            }
        }
        i += 1;
    }
    limits
};

/// Checks every parameter against the magnitudes that can be solved, and a damped ball's relaxation.
/// Every solve asks: the magnitudes are compared on the table `LIMITS`; a refusal (or a NaN, which
/// the table cannot pass) goes row by row.
#[inline]
pub fn check(params: &Params) -> Result<(), Unsolvable> {
    magnitudes(params)?;
    relaxation(params)
}

/// [`check`] without the relaxation: every parameter's magnitude alone.
#[inline]
pub(super) fn magnitudes(params: &Params) -> Result<(), Unsolvable> {
    let values = params.values();
    let [smallest, largest, zero] = &LIMITS;
    let mut ok = true;
    for i in 0..PARAM_COUNT {
        let size = values[i].abs();
        ok &= (size == zero[i]) | ((size >= smallest[i]) & (size <= largest[i]));
    }
    if ok { Ok(()) } else { by_rows(params) }
}

/// [`magnitudes`] row by row: the first parameter outside the magnitudes that can be solved is refused
/// with its range.
#[cold]
#[inline(never)]
fn by_rows(params: &Params) -> Result<(), Unsolvable> {
    PARAMS
        .iter()
        .try_for_each(|row| magnitude(row, params.get(row.id)))
}

/// Checks `value` of the parameter `row` against the magnitudes that can be solved: [`check`]'s
/// refusal of it, when every other parameter passes.
#[inline]
pub(super) fn magnitude(row: &ParamSpec, value: f64) -> Result<(), Unsolvable> {
    let Some(limit) = row.solvable else {
        return Ok(());
    };
    let size = value.abs();
    let zero_ok = row.range.contains(0.0);
    if (size == 0.0 && zero_ok) || (size >= limit.smallest && size <= limit.largest) {
        Ok(())
    } else {
        Err(refusal(row, &limit, value))
    }
}

/// The message for `value` of the parameter `row` outside `limit`.
pub(super) fn refusal(row: &ParamSpec, limit: &Solvable, value: f64) -> Unsolvable {
    let unit = row.dimension.base_symbol();
    let largest = number(limit.largest);
    let range = if row.range.contains(-1.0) {
        format!("[-{largest}, {largest}]")
    } else if limit.smallest == 0.0 {
        format!("[0, {largest}]")
    } else {
        format!("[{}, {largest}]", number(limit.smallest))
    };
    Unsolvable {
        flag: row.flag,
        range: format!("{range} {unit}").trim_end().to_string(),
        given: format!("{} {unit}", number(value)).trim_end().to_string(),
        why: SCALES,
    }
}

/// A damped ball's stretch relaxes at lambda = k_b/c_b = sqrt(k_b/m_eff)/(2 zeta); lambda T must stay
/// within [`MAX_RELAXATIONS`], which bounds zeta from below (zero, an undamped ball, is solved apart).
#[inline]
pub(super) fn relaxation(params: &Params) -> Result<(), Unsolvable> {
    let zeta = params.ball_damping;
    if params.ball_stiffness == 0.0 || zeta == 0.0 {
        return Ok(());
    }
    let m_eff = params.mass * params.alpha / (1.0 + params.alpha);
    let smallest =
        (params.ball_stiffness / m_eff).sqrt() * params.duration / (2.0 * MAX_RELAXATIONS);
    if zeta >= smallest {
        return Ok(());
    }
    let spec = spec(ParamId::BallDamping);
    Err(Unsolvable {
        flag: spec.flag,
        range: format!("{{0}} or [{}, 10]", units::brief(smallest, 3)),
        given: number(zeta),
        why: "a lighter damping relaxes the ball's stretch faster than the impact's time can resolve",
    })
}

/// The shortest text that reads back as `value`, in exponent form outside ordinary magnitudes.
fn number(value: f64) -> String {
    if value == 0.0 || (1e-4..1e9).contains(&value.abs()) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_and_the_paper_are_solvable() {
        assert_eq!(check(&Params::default()), Ok(()));
    }

    /// The table answers as the rows do, at and beside every limit and off the numbers.
    #[test]
    fn the_table_is_the_rows() {
        for row in PARAMS {
            let mut values = vec![0.0, 1.0, -1.0, f64::NAN, f64::INFINITY, f64::MAX];
            if let Some(limit) = row.solvable {
                for b in [limit.smallest, limit.largest] {
                    values.extend([b, -b, b.next_up(), b.next_down(), -b.next_up()]);
                }
            }
            for value in values {
                let mut p = Params::default();
                p.set(row.id, value);
                let rows = by_rows(&p).and_then(|()| relaxation(&p));
                assert_eq!(check(&p), rows, "{} {value}", row.flag);
            }
        }
    }

    #[test]
    fn a_value_beyond_the_scales_is_refused_with_its_range() {
        let p = Params {
            speed: 1e160,
            ..Params::default()
        };
        assert_eq!(
            check(&p).unwrap_err().to_string(),
            format!("--speed must be in [1e-15, 1e15] m/s to be solved ({SCALES}); got 1e160 m/s")
        );
        // The solve carries any spin (its energy overflows, which a report refuses).
        let p = Params {
            spin: -1e308,
            ..Params::default()
        };
        assert_eq!(check(&p), Ok(()));
    }

    #[test]
    fn a_lightly_damped_ball_is_refused_but_an_undamped_one_is_not() {
        let ball = Params {
            ball_stiffness: 1e5,
            ..Params::default()
        };
        assert_eq!(check(&ball), Ok(()));
        let light = Params {
            ball_damping: 1e-20,
            ..ball
        };
        let message = check(&light).unwrap_err().to_string();
        assert!(
            message.starts_with("--ball-damping must be in {0} or [5.56e-15, 10]"),
            "{message}"
        );
        let enough = Params {
            ball_damping: 1e-14,
            ..ball
        };
        assert_eq!(check(&enough), Ok(()));
    }
}
