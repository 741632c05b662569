//! The range of one parameter that a sweep or an optimisation walks: `--vary PARAM --from A --to B`.

use crate::model::params::{PARAMS, ParamSpec, Params};
use crate::model::units;
use crate::model::{Bounce, SolveError, SolveOptions, Varied, solve_with};

use super::AnalysisError;

/// A parameter and the interval it runs over, in its base unit; `log` spaces the values geometrically.
#[derive(Clone, Copy, Debug)]
pub struct Span {
    pub spec: &'static ParamSpec,
    pub from: f64,
    pub to: f64,
    pub log: bool,
}

/// The largest number of steps a sweep or a scan accepts (each row is kept in memory).
pub const MAX_STEPS: usize = 10_000_000;

impl Span {
    /// Reads `--vary`, `--from` and `--to` as typed: `PARAM` is a flag name (`cart-mass`) or a key
    /// (`cart_mass`), and the ends take unit suffixes (`1g`) and must lie in the parameter's range.
    pub fn parse(vary: &str, from: &str, to: &str, log: bool) -> Result<Span, AnalysisError> {
        let spec = crate::model::params::spec_named(vary.trim()).ok_or_else(|| {
            let names: Vec<&str> = PARAMS.iter().map(|s| s.flag).collect();
            AnalysisError::Input(format!(
                "--vary must be one of {}; got {}",
                names.join(", "),
                vary.trim()
            ))
        })?;
        let end = |flag: &'static str, text: &str| {
            spec.parse(text)
                .map_err(|source| AnalysisError::Param { flag, source })
        };
        Span::new(spec, end("--from", from)?, end("--to", to)?, log)
    }

    /// A span between two values already in range; `log` needs both ends above zero.
    pub fn new(
        spec: &'static ParamSpec,
        from: f64,
        to: f64,
        log: bool,
    ) -> Result<Span, AnalysisError> {
        if log && (from <= 0.0 || to <= 0.0) {
            let unit = spec.dimension.base_symbol();
            return Err(AnalysisError::Input(format!(
                "--log needs --from and --to above 0; got --from {} {unit} --to {} {unit}",
                units::brief(from, 6),
                units::brief(to, 6)
            )));
        }
        Ok(Span {
            spec,
            from,
            to,
            log,
        })
    }

    /// The `i`-th of `n` values (n >= 2), ends included exactly, computed from the ends and the index
    /// alone (no accumulated step) so that no value overflows; a value within its rounding error of a
    /// short decimal is that decimal (0.3, not 0.30000000000000004). For a whole-number parameter a
    /// value within rounding of a whole number is that number (a geometric 1, 2, 4, 8, 16 is exact).
    pub fn at(&self, i: usize, n: usize) -> f64 {
        self.steps(n).at(i)
    }

    /// The `n` values of [`Span::at`], with what they share worked out once (a sweep asks for each).
    pub fn steps(&self, n: usize) -> Steps {
        let intervals = n.saturating_sub(1) as f64;
        let big = self.from.abs().max(self.to.abs());
        let scale = if big >= f64::MAX / intervals / 2.0 {
            OVERFLOW_SCALE
        } else {
            1.0
        };
        let (from_ln, to_ln) = if self.log {
            (self.from.ln(), self.to.ln())
        } else {
            (0.0, 0.0)
        };
        Steps {
            span: *self,
            low: self.from.min(self.to),
            high: self.from.max(self.to),
            integer: self.spec.integer,
            n,
            intervals,
            scale,
            scaled: (self.from * scale, self.to * scale),
            ln: (from_ln, to_ln),
            logs: from_ln.abs().max(to_ln.abs()),
        }
    }

    /// Checks that `n` values of a whole-number parameter all land on whole numbers (always true of
    /// any other parameter); the message names the first value that does not and the counts that work.
    pub fn check_steps(&self, flag: &str, n: usize) -> Result<(), AnalysisError> {
        let Some(bad) = self.off_whole(n) else {
            return Ok(());
        };
        let counts = self.whole_counts();
        if counts.is_empty() {
            return Err(AnalysisError::Input(format!(
                "--{} must be in {}; got --from {} --to {}",
                self.spec.flag,
                self.spec.range_text(),
                units::brief(self.from, 6),
                units::brief(self.to, 6),
            )));
        }
        let mut listed: Vec<String> = counts.iter().take(12).map(|c| c.to_string()).collect();
        if counts.len() > listed.len() {
            listed.push("...".to_string());
        }
        let last = listed.pop().expect("at least one count");
        let choices = if listed.is_empty() {
            last
        } else {
            format!("{} or {last}", listed.join(", "))
        };
        let every = (self.from - self.to).abs() as usize + 1;
        let advice = if self.log {
            format!("{choices} with --log, or {flag} {every} without it for every whole number")
        } else {
            format!("{choices} ({every} takes every whole number)")
        };
        Err(AnalysisError::Input(format!(
            "{flag} {n} puts --{} at {}, not a whole number; from {} to {} use {flag} {advice}",
            self.spec.flag,
            units::brief(bad, 6),
            units::brief(self.from, 6),
            units::brief(self.to, 6),
        )))
    }

    /// For a whole-number parameter, the first of `n` values that is not whole.
    fn off_whole(&self, n: usize) -> Option<f64> {
        if !self.spec.integer {
            return None;
        }
        let steps = self.steps(n);
        (0..n).map(|i| steps.at(i)).find(|v| v.fract() != 0.0)
    }

    /// The counts of values from 2 up to one per whole number that all land on whole numbers.
    fn whole_counts(&self) -> Vec<usize> {
        let every = ((self.from - self.to).abs() as usize + 1).min(MAX_STEPS);
        (2..=every.max(2))
            .filter(|&n| self.off_whole(n).is_none())
            .collect()
    }

    /// The span narrowed to the whole numbers inside it, in the same direction: its ends rounded
    /// inwards. An error, naming the flag, when it holds no whole number.
    pub fn whole(&self) -> Result<Span, AnalysisError> {
        let (lo, hi) = (self.from.min(self.to), self.from.max(self.to));
        let (first, last) = (lo.ceil(), hi.floor());
        if first > last {
            return Err(AnalysisError::Input(format!(
                "--from {} --to {} holds no whole number, and --{} must be in {}",
                units::brief(self.from, 6),
                units::brief(self.to, 6),
                self.spec.flag,
                self.spec.range_text(),
            )));
        }
        let (from, to) = if self.from <= self.to {
            (first, last)
        } else {
            (last, first)
        };
        Ok(Span { from, to, ..*self })
    }

    /// The whole numbers of the span, from `from` towards `to`.
    pub fn whole_numbers(&self) -> Result<Vec<f64>, AnalysisError> {
        let span = self.whole()?;
        let count = (span.to - span.from).abs() + 1.0;
        if count > MAX_STEPS as f64 {
            return Err(AnalysisError::Input(format!(
                "--{} from {} to {} holds {} whole numbers, more than the {MAX_STEPS} that can be solved",
                self.spec.flag,
                units::brief(span.from, 6),
                units::brief(span.to, 6),
                units::brief(count, 6),
            )));
        }
        let step = if span.to < span.from { -1.0 } else { 1.0 };
        Ok((0..count as usize)
            .map(|i| span.from + step * i as f64)
            .collect())
    }

    /// The value at the fraction `u` of the way from `from` (0) to `to` (1), geometric when `log`,
    /// inside the span.
    pub fn from_unit(&self, u: f64) -> f64 {
        if self.log {
            between_logs(self.from.ln(), self.to.ln(), u)
        } else {
            // Each end weighted, never their difference: nothing overflows.
            self.from * (1.0 - u) + self.to * u
        }
        .clamp(self.from.min(self.to), self.from.max(self.to))
    }

    /// `n` values from `from` to `to`, ends included.
    pub fn values(&self, n: usize) -> Vec<f64> {
        let steps = self.steps(n);
        (0..n).map(|i| steps.at(i)).collect()
    }

    /// The CSV column of the varied value: the parameter's key and base unit, e.g. `angle_deg`,
    /// `cart_mass_kg`, `stiffness_N_m`, `mu`.
    pub fn column(&self) -> String {
        column(self.spec)
    }

    /// The bounce with the varied parameter set to `value`, solved on the caller's terms.
    pub fn solve(
        &self,
        base: &Params,
        value: f64,
        options: &SolveOptions,
    ) -> Result<Bounce, AnalysisError> {
        solve_with(&self.with(base, value), options).map_err(|source| self.failed(value, source))
    }

    /// The bounces of `base` with this span's parameter varied ([`Varied`]), on the caller's terms: one
    /// per core solves a sweep's bounces with no allocation and one check of the other values.
    pub fn varied<'a>(&self, base: &Params, options: &SolveOptions<'a>) -> Varied<'a> {
        Varied::new(base, self.spec.id, options)
    }

    /// [`Span::solve`] by `varied` (from [`Span::varied`]), into its memory.
    pub fn solve_varied<'v>(
        &self,
        varied: &'v mut Varied,
        value: f64,
    ) -> Result<&'v Bounce, AnalysisError> {
        varied
            .solve(value)
            .map_err(|source| self.failed(value, source))
    }

    /// `base` with the varied parameter at `value`.
    fn with(&self, base: &Params, value: f64) -> Params {
        let mut params = *base;
        params.set(self.spec.id, value);
        params
    }

    /// The error of a bounce at `value` that could not be solved.
    #[cold]
    fn failed(&self, value: f64, source: SolveError) -> AnalysisError {
        AnalysisError::Solve {
            flag: self.spec.flag,
            value: format!(
                "{} {}",
                units::brief(value, 10),
                self.spec.dimension.base_symbol()
            )
            .trim_end()
            .to_string(),
            source,
        }
    }
}

/// Scales the ends of a linear span whose weighted sum could overflow: 2^-32, exact.
const OVERFLOW_SCALE: f64 = 1.0 / 4_294_967_296.0;

/// The `n` values of a span ([`Span::steps`]): the ends' scale, scaled ends and logarithms, taken once.
#[derive(Clone, Copy, Debug)]
pub struct Steps {
    span: Span,
    /// The smaller end and the larger.
    low: f64,
    high: f64,
    /// True for a whole-number parameter.
    integer: bool,
    n: usize,
    /// n - 1.
    intervals: f64,
    /// 1, or `OVERFLOW_SCALE` where the weighted sum of the ends could overflow.
    scale: f64,
    /// The ends times `scale`.
    scaled: (f64, f64),
    /// The ends' logarithms (a geometric span's; 0 otherwise).
    ln: (f64, f64),
    /// The larger of the logarithms' sizes.
    logs: f64,
}

impl Steps {
    /// The `i`-th value ([`Span::at`]).
    pub fn at(&self, i: usize) -> f64 {
        let span = &self.span;
        if i == 0 {
            return span.from;
        }
        if i + 1 >= self.n {
            return span.to;
        }
        let (value, error) = if span.log {
            self.geometric(i)
        } else {
            self.linear(i)
        };
        let value = short_decimal(value, error).clamp(self.low, self.high);
        if self.integer {
            nearly_whole(value).unwrap_or(value)
        } else {
            value
        }
    }

    /// The `i`-th evenly spaced value as one weighted sum over one division,
    /// (from (n-1-i) + to i) / (n-1), so whole ends give correctly rounded values; the ends are scaled
    /// by a power of two (exactly) where the sum could overflow. With a bound on its rounding error.
    fn linear(&self, i: usize) -> (f64, f64) {
        let (weight_from, weight_to) = (whole(self.n - 1 - i), whole(i));
        let ((from, to), intervals, scale) = (self.scaled, self.intervals, self.scale);
        // Undoing the scale, a power of two, is exact either way: by a product, not a second division.
        let value = (from * weight_from + to * weight_to) / intervals * scale.recip();
        // Each end's own rounding and that of the two products, the sum and the quotient, on the
        // size of the terms (larger than the value where the ends' signs differ).
        let terms = (from.abs() * weight_from + to.abs() * weight_to) / intervals * scale.recip();
        (value, 2.0 * f64::EPSILON * terms)
    }

    /// The `i`-th geometrically spaced value, with a bound on its rounding error (exp carries the
    /// logarithm's absolute error as a relative one).
    fn geometric(&self, i: usize) -> (f64, f64) {
        let value = between_logs(self.ln.0, self.ln.1, whole(i) / self.intervals)
            .clamp(self.low, self.high);
        (value, 2.0 * f64::EPSILON * (1.0 + self.logs) * value.abs())
    }
}

/// `i as f64`, through `i64` where it fits (one conversion instruction; the unsigned one takes a
/// dozen): the same value, the nearest f64 to `i`.
#[inline]
fn whole(i: usize) -> f64 {
    i64::try_from(i).map_or(i as f64, |i| i as f64)
}

/// The value whose logarithm lies the fraction `u` of the way from `from_ln` to `to_ln`.
#[inline]
fn between_logs(from_ln: f64, to_ln: f64, u: f64) -> f64 {
    (from_ln * (1.0 - u) + to_ln * u).exp()
}

/// The decimal of at most 12 significant digits nearest `value`, when it lies within `error` of it;
/// otherwise `value`. Removes the noise of rounding (10.000000000000002 is 10) without moving a value
/// by more than its own rounding error.
fn short_decimal(value: f64, error: f64) -> f64 {
    let decimal = twelve_digits(value, error)
        .or_else(|| format!("{value:.11e}").parse::<f64>().ok())
        .unwrap_or(value);
    if (decimal - value).abs() <= error {
        decimal
    } else {
        value
    }
}

/// Exact powers of ten, 10^0 to 10^22.
const POWERS: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The 12-digit decimal nearest `value` as an f64, n 10^-p with n whole, |n| < 10^12, by arithmetic
/// (no text), where that gives what `{:.11e}` read back gives whenever it can lie within `error`:
/// `None` (the text's turn) outside 10^-11..10^33, or when `error` is not below an eighth of a unit of
/// the twelfth digit. Both divisions and products round once from exact operands (n and 10^|p| are
/// exact), so a candidate is the correctly rounded decimal; the scaled value's own rounding (about
/// 1e-4 of a unit) can pick the other neighbour only where both lie half a unit away, beyond `error`.
fn twelve_digits(value: f64, error: f64) -> Option<f64> {
    let size = value.abs();
    if !(1e-11..1e33).contains(&size) {
        return None;
    }
    // 12 - (decimal digits before the point), from the binary exponent, then corrected.
    let binary = i32::try_from((size.to_bits() >> 52) as i64 - 1023).ok()?;
    // floor(binary log10 2) as (binary 78913) >> 18, exact for |binary| < 1650 (and corrected below).
    let mut p = 11 - ((binary * 78_913) >> 18);
    for _ in 0..3 {
        let power = POWERS[usize::try_from(p.unsigned_abs())
            .ok()
            .filter(|&i| i < POWERS.len())?];
        let (scaled, unit) = if p >= 0 {
            (size * power, 1.0 / power)
        } else {
            (size / power, power)
        };
        if scaled >= 999_999_999_999.5 {
            p -= 1;
        } else if scaled < 99_999_999_999.5 {
            p += 1;
        } else {
            // NaN refuses too.
            if error.partial_cmp(&(0.125 * unit)) != Some(std::cmp::Ordering::Less) {
                return None;
            }
            // scaled.round() without a call: scaled is positive and below 2^40, so its fraction is
            // exact (and its whole part that of `as i64`, one instruction where `as u64` takes a dozen).
            let whole = scaled as i64 as f64;
            let n = if scaled - whole >= 0.5 {
                whole + 1.0
            } else {
                whole
            };
            let decimal = if p >= 0 { n / power } else { n * power };
            return Some(decimal.copysign(value));
        }
    }
    None
}

/// The whole number `value` is within rounding of (a relative 1e-9), if any.
fn nearly_whole(value: f64) -> Option<f64> {
    let whole = value.round();
    ((value - whole).abs() <= 1e-9 * whole.abs().max(1.0)).then_some(whole)
}

/// The column name of a parameter: its key and base unit, `/` written `_`.
pub fn column(spec: &ParamSpec) -> String {
    let unit = spec.dimension.base_symbol();
    if unit.is_empty() {
        spec.key.to_string()
    } else {
        format!("{}_{}", spec.key, unit.replace('/', "_"))
    }
}

/// Reads a count flag such as `--steps`: an integer in `[min, MAX_STEPS]`.
pub fn parse_count(flag: &str, text: &str, min: usize) -> Result<usize, AnalysisError> {
    match text.trim().parse::<usize>() {
        Ok(n) if (min..=MAX_STEPS).contains(&n) => Ok(n),
        _ => Err(AnalysisError::Input(format!(
            "{flag} must be an integer in [{min}, {MAX_STEPS}]; got {}",
            text.trim()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_carry_the_base_unit() {
        let col = |name| column(crate::model::params::spec_named(name).unwrap());
        assert_eq!(col("angle"), "angle_deg");
        assert_eq!(col("cart-mass"), "cart_mass_kg");
        assert_eq!(col("stiffness"), "stiffness_N_m");
        assert_eq!(col("mu"), "mu");
        assert_eq!(col("spin"), "spin_rad_s");
    }

    #[test]
    fn ends_are_exact_and_log_is_geometric() {
        let span = Span::parse("stiffness", "1kN/m", "100kN/m", true).unwrap();
        let v = span.values(3);
        assert_eq!(v[0], 1000.0);
        assert_eq!(v[2], 100000.0);
        assert!((v[1] - 10000.0).abs() < 1e-8);
        let lin = Span::parse("angle", "10", "20", false).unwrap();
        assert_eq!(lin.values(11)[3], 13.0);
    }

    /// The arithmetic decimal agrees with the text's, read back, wherever either is kept.
    #[test]
    fn short_decimals_match_the_text() {
        let by_text = |value: f64, error: f64| match format!("{value:.11e}").parse::<f64>() {
            Ok(decimal) if (decimal - value).abs() <= error => decimal,
            _ => value,
        };
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let (mut kept, mut arithmetic) = (0, 0);
        for _ in 0..300_000 {
            let bits = next();
            // Short decimals nudged by a few units in the last place, and arbitrary values.
            let value = if bits % 3 == 0 {
                f64::from_bits(bits)
            } else {
                let digits = (bits >> 20) % 1_000_000_000_000;
                let exponent = (bits % 50) as i32 - 20;
                let short: f64 = format!("{digits}e{exponent}").parse().unwrap();
                let nudge = (bits >> 8) % 9;
                f64::from_bits(short.to_bits().wrapping_add(nudge).wrapping_sub(4))
            };
            let error = value.abs() * f64::EPSILON * ((next() % 64) as f64 + 0.5);
            let expected = by_text(value, error);
            let got = short_decimal(value, error);
            assert_eq!(
                got.to_bits(),
                expected.to_bits(),
                "{value:e} within {error:e}"
            );
            kept += usize::from(got != value);
            arithmetic += usize::from(twelve_digits(value, error).is_some());
        }
        assert!(kept > 10_000 && arithmetic > 150_000, "{kept} {arithmetic}");
    }

    /// `whole` is `as f64` on every count, those beyond `i64` too.
    #[test]
    fn whole_counts_convert_as_f64() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let edges = [
            0,
            1,
            (1 << 53) - 1,
            1 << 53,
            (1 << 53) + 1,
            i64::MAX as usize,
            i64::MAX as usize + 1,
            usize::MAX,
        ];
        let random = (0..100_000).map(|k| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> (k % 64)) as usize
        });
        for i in edges.into_iter().chain(random) {
            assert_eq!(whole(i).to_bits(), (i as f64).to_bits(), "{i}");
        }
    }

    /// The integer floor of binary log10 2 is the float's over every binary exponent of an f64.
    #[test]
    fn the_decimal_exponent_is_the_floats() {
        for binary in -1100..=1100 {
            let float = (f64::from(binary) * std::f64::consts::LOG10_2).floor() as i32;
            assert_eq!((binary * 78_913) >> 18, float, "{binary}");
        }
    }

    #[test]
    fn bad_input_names_flag_range_and_value() {
        let err = Span::parse("spinn", "0", "1", false)
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("--vary must be one of angle, speed"),
            "{err}"
        );
        assert!(err.ends_with("got spinn"), "{err}");
        let err = Span::parse("angle", "10", "95", false)
            .unwrap_err()
            .to_string();
        assert_eq!(err, "--to: --angle must be in (0, 90] deg; got 95");
        let err = Span::parse("stiffness", "0", "10", true)
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("--log needs --from and --to above 0"),
            "{err}"
        );
        let err = parse_count("--steps", "1", 2).unwrap_err().to_string();
        assert_eq!(err, "--steps must be an integer in [2, 10000000]; got 1");
    }
}
