//! Quantities with units: parse `"10 g"`, `"15kN/m"`, `"-100rad/s"`, `"955rpm"`; format for people.
//!
//! Every quantity has a *base unit* that the core works in: SI for all of them except angles, which the
//! parameters hold in degrees (the unit the paper and its readers use).

use std::fmt;

/// What a number measures. Decides which unit suffixes a value may carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    Mass,
    Length,
    Speed,
    Time,
    Stiffness,
    Angle,
    AngularVelocity,
    Force,
    /// A moment of inertia (a racquet's swing and twist weights).
    MomentOfInertia,
    Dimensionless,
}

/// One unit: its symbols (the first is the canonical one) and the factor that takes it to the base unit.
#[derive(Clone, Copy, Debug)]
pub struct Unit {
    pub symbols: &'static [&'static str],
    pub to_base: f64,
}

impl Unit {
    pub fn symbol(&self) -> &'static str {
        self.symbols[0]
    }
}

const fn unit(symbols: &'static [&'static str], to_base: f64) -> Unit {
    Unit { symbols, to_base }
}

const MASS: &[Unit] = &[unit(&["kg"], 1.0), unit(&["g"], 1e-3), unit(&["mg"], 1e-6)];
const LENGTH: &[Unit] = &[unit(&["m"], 1.0), unit(&["cm"], 1e-2), unit(&["mm"], 1e-3)];
const SPEED: &[Unit] = &[
    unit(&["m/s"], 1.0),
    unit(&["km/h"], 1.0 / 3.6),
    unit(&["mph"], 0.447_04),
];
const TIME: &[Unit] = &[
    unit(&["s"], 1.0),
    unit(&["ms"], 1e-3),
    unit(&["us", "µs"], 1e-6),
];
const STIFFNESS: &[Unit] = &[
    unit(&["N/m"], 1.0),
    unit(&["kN/m", "N/mm"], 1e3),
    unit(&["MN/m"], 1e6),
];
const ANGLE: &[Unit] = &[
    unit(&["deg", "°"], 1.0),
    unit(&["rad"], 180.0 / std::f64::consts::PI),
];
const ANGULAR_VELOCITY: &[Unit] = &[
    unit(&["rad/s"], 1.0),
    unit(&["rpm"], std::f64::consts::PI / 30.0),
    unit(&["rps", "rev/s"], 2.0 * std::f64::consts::PI),
];
const FORCE: &[Unit] = &[unit(&["N"], 1.0), unit(&["kN"], 1e3)];
const MOMENT_OF_INERTIA: &[Unit] = &[
    unit(&["kg m^2", "kg m²"], 1.0),
    unit(&["kg cm^2", "kg cm²"], 1e-4),
    unit(&["g cm^2", "g cm²"], 1e-7),
];

const ALL: [Dimension; 10] = [
    Dimension::Mass,
    Dimension::Length,
    Dimension::Speed,
    Dimension::Time,
    Dimension::Stiffness,
    Dimension::Angle,
    Dimension::AngularVelocity,
    Dimension::Force,
    Dimension::MomentOfInertia,
    Dimension::Dimensionless,
];

impl Dimension {
    /// The units a value of this dimension may carry, base unit first.
    pub fn units(self) -> &'static [Unit] {
        match self {
            Dimension::Mass => MASS,
            Dimension::Length => LENGTH,
            Dimension::Speed => SPEED,
            Dimension::Time => TIME,
            Dimension::Stiffness => STIFFNESS,
            Dimension::Angle => ANGLE,
            Dimension::AngularVelocity => ANGULAR_VELOCITY,
            Dimension::Force => FORCE,
            Dimension::MomentOfInertia => MOMENT_OF_INERTIA,
            Dimension::Dimensionless => &[],
        }
    }

    /// The unit the core works in; `""` for a pure number.
    pub fn base_symbol(self) -> &'static str {
        self.units().first().map_or("", Unit::symbol)
    }

    /// A noun for messages: "a mass", "an angle".
    pub fn noun(self) -> &'static str {
        match self {
            Dimension::Mass => "a mass",
            Dimension::Length => "a length",
            Dimension::Speed => "a speed",
            Dimension::Time => "a time",
            Dimension::Stiffness => "a stiffness",
            Dimension::Angle => "an angle",
            Dimension::AngularVelocity => "an angular velocity",
            Dimension::Force => "a force",
            Dimension::MomentOfInertia => "a moment of inertia",
            Dimension::Dimensionless => "a pure number",
        }
    }

    /// The unit with this symbol, if the dimension has it.
    pub fn find(self, symbol: &str) -> Option<&'static Unit> {
        self.units().iter().find(|u| u.symbols.contains(&symbol))
    }

    /// Every symbol a value may carry, the base unit's first (`kg`, `g`, `mg`).
    pub fn symbols(self) -> Vec<&'static str> {
        self.units()
            .iter()
            .flat_map(|u| u.symbols.iter().copied())
            .collect()
    }

    fn accepted(self) -> String {
        let symbols = self.symbols();
        if symbols.is_empty() {
            "no unit".to_string()
        } else {
            symbols.join(", ")
        }
    }
}

/// Why a text is not a quantity of the wanted dimension.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum UnitError {
    #[error("no value given")]
    Empty,
    #[error("'{0}' is not a number")]
    NotANumber(String),
    #[error("'{0}' is not a finite number")]
    NotFinite(String),
    #[error("unknown unit '{unit}' (accepted: {accepted})")]
    UnknownUnit { unit: String, accepted: String },
    #[error("unit '{unit}' is {found}, but this value is {wanted} (accepted: {accepted})")]
    WrongDimension {
        unit: String,
        found: &'static str,
        wanted: &'static str,
        accepted: String,
    },
}

/// Splits `"-1.5e4 kN/m"` into `("-1.5e4", "kN/m")`.
fn split_number(text: &str) -> (&str, &str) {
    let bytes = text.as_bytes();
    let mut end = 0;
    if matches!(bytes.first(), Some(b'+' | b'-')) {
        end = 1;
    }
    while end < bytes.len() && (bytes[end].is_ascii_digit() || bytes[end] == b'.') {
        end += 1;
    }
    // An exponent only counts when digits follow it, so "1e4" is a number but "1em" would not be.
    if end < bytes.len() && matches!(bytes[end], b'e' | b'E') {
        let mut exp = end + 1;
        if exp < bytes.len() && matches!(bytes[exp], b'+' | b'-') {
            exp += 1;
        }
        if exp < bytes.len() && bytes[exp].is_ascii_digit() {
            while exp < bytes.len() && bytes[exp].is_ascii_digit() {
                exp += 1;
            }
            end = exp;
        }
    }
    (&text[..end], text[end..].trim())
}

/// The longest text a message echoes whole.
const ECHO: usize = 40;

/// User text as a message echoes it: whole up to `ECHO` characters, else its start and its length, so
/// that a value 100 000 digits long does not flood the terminal.
pub fn echo(text: &str) -> String {
    let length = text.chars().count();
    if length <= ECHO {
        text.to_string()
    } else {
        let start: String = text.chars().take(ECHO).collect();
        format!("{start}... ({length} characters)")
    }
}

/// Parses a value with an optional unit suffix into the dimension's base unit.
/// A bare number is taken to be in the base unit.
pub fn parse(text: &str, dimension: Dimension) -> Result<f64, UnitError> {
    parse_bare(text, dimension, 1.0)
}

/// Like [`parse`], but a bare number is in the unit whose factor to the base unit is `bare_to_base`.
pub fn parse_bare(text: &str, dimension: Dimension, bare_to_base: f64) -> Result<f64, UnitError> {
    let text = text.trim();
    if text.is_empty() {
        return Err(UnitError::Empty);
    }
    let (number, suffix) = split_number(text);
    let value: f64 = match number.parse() {
        Ok(v) => v,
        // "inf", "NaN" and friends are numbers to Rust but never a valid parameter.
        Err(_) if text.parse::<f64>().is_ok() => {
            return Err(UnitError::NotFinite(echo(text)));
        }
        Err(_) => return Err(UnitError::NotANumber(echo(text))),
    };
    if !value.is_finite() {
        return Err(UnitError::NotFinite(echo(text)));
    }
    if suffix.is_empty() {
        return Ok(value * bare_to_base);
    }
    if let Some(unit) = dimension.find(suffix) {
        return Ok(value * unit.to_base);
    }
    let accepted = dimension.accepted();
    match ALL.iter().find(|d| d.find(suffix).is_some()) {
        Some(other) => Err(UnitError::WrongDimension {
            unit: echo(suffix),
            found: other.noun(),
            wanted: dimension.noun(),
            accepted,
        }),
        None => Err(UnitError::UnknownUnit {
            unit: echo(suffix),
            accepted,
        }),
    }
}

/// A value in a chosen unit, for people: `Display` prints it with the given decimals and the unit symbol.
#[derive(Clone, Copy, Debug)]
pub struct Shown {
    pub value: f64,
    pub symbol: &'static str,
    pub decimals: usize,
    /// What a zero means, shown instead of the number (a ball stiffness of 0 is a rigid ball).
    pub zero_label: Option<&'static str>,
}

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let (0.0, Some(label)) = (self.value, self.zero_label) {
            return f.write_str(label);
        }
        let value = if self.value == 0.0 { 0.0 } else { self.value }; // no "-0"
        if self.symbol.is_empty() {
            write!(f, "{value:.*}", self.decimals)
        } else {
            write!(f, "{value:.*} {}", self.decimals, self.symbol)
        }
    }
}

/// Converts a base-unit value into `symbol` of `dimension`.
///
/// # Panics
/// When `symbol` is not a unit of `dimension`: a programming error, never user input.
pub fn in_unit(base_value: f64, dimension: Dimension, symbol: &'static str) -> f64 {
    if symbol.is_empty() {
        return base_value;
    }
    let unit = dimension
        .find(symbol)
        .unwrap_or_else(|| panic!("{symbol} is not a unit of {}", dimension.noun()));
    base_value / unit.to_base
}

/// A base-unit value shown in `symbol` with `decimals` places.
pub fn show(base_value: f64, dimension: Dimension, symbol: &'static str, decimals: usize) -> Shown {
    Shown {
        value: in_unit(base_value, dimension, symbol),
        symbol,
        decimals,
        zero_label: None,
    }
}

/// A number formatted briefly for people: up to `significant` digits, no trailing zeros, no exponent for
/// ordinary magnitudes (`15000`, `0.057`, `-100`).
pub fn brief(value: f64, significant: usize) -> String {
    if value == 0.0 || !value.is_finite() {
        return if value.is_finite() {
            "0".into()
        } else {
            format!("{value}")
        };
    }
    let magnitude = value.abs().log10().floor() as i32;
    if !(-4..=9).contains(&magnitude) {
        return format!("{value:.*e}", significant.saturating_sub(1));
    }
    let decimals = (significant as i32 - 1 - magnitude).max(0) as usize;
    let text = format!("{value:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// Where a bare number for a quantity usually lies, in the base unit: one outside `[low, high]` (in
/// size; zero never counts, it is a free cart or a rigid ball) is more likely a slip of unit than meant.
/// `typical` picks the unit a slip most likely meant: the one that brings the number nearest it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Usual {
    pub low: f64,
    pub high: f64,
    pub typical: f64,
}

/// A note for a bare number far outside the usual range of its quantity, saying how it is read and what
/// to write for the unit it likely meant: `--cart-mass 10 is read as 10 kg; write 10g for grams`.
/// `name` names the value as the caller shows it (`--cart-mass` on the command line, `cart mass` in the
/// explorer), `text` is the value as typed and `bare` the symbol a bare number is read in. A value with
/// a unit, or one that does not parse, gets no note; an uncertainty (`10±1`) is left aside.
pub fn bare_note(
    name: &str,
    text: &str,
    dimension: Dimension,
    bare: &str,
    usual: Usual,
) -> Option<String> {
    let value_text = text.split('±').next()?.split("+-").next()?.trim();
    let (number, suffix) = split_number(value_text);
    if !suffix.is_empty() || number != value_text {
        return None;
    }
    let value: f64 = number.parse().ok()?;
    let bare_unit = dimension.find(bare)?;
    let usual_size = |v: f64| v == 0.0 || (usual.low..=usual.high).contains(&v.abs());
    if !value.is_finite() || usual_size(value * bare_unit.to_base) {
        return None;
    }
    let read = format!("{name} {number} is read as {number} {bare}");
    let distance = |unit: &Unit| {
        let v = (value * unit.to_base).abs();
        if usual.typical == 0.0 {
            0.0
        } else {
            (v / usual.typical.abs()).ln().abs()
        }
    };
    let meant = dimension
        .units()
        .iter()
        .filter(|u| u.symbol() != bare_unit.symbol() && usual_size(value * u.to_base))
        .min_by(|a, b| distance(a).total_cmp(&distance(b)));
    Some(match meant {
        Some(unit) => format!(
            "{read}; write {number}{} for {}",
            unit.symbol(),
            unit_words(unit.symbol())
        ),
        None if value.abs() * bare_unit.to_base > usual.high => {
            let high = usual.high / bare_unit.to_base;
            format!("{read}, more than the usual {} {bare}", brief(high, 3))
        }
        None => {
            let low = usual.low / bare_unit.to_base;
            format!("{read}, less than the usual {} {bare}", brief(low, 3))
        }
    })
}

/// A unit's name in words, for a note: `g` is grams.
fn unit_words(symbol: &str) -> &str {
    match symbol {
        "kg" => "kilograms",
        "g" => "grams",
        "mg" => "milligrams",
        "m" => "metres",
        "cm" => "centimetres",
        "mm" => "millimetres",
        "m/s" => "metres per second",
        "km/h" => "kilometres per hour",
        "mph" => "miles per hour",
        "s" => "seconds",
        "ms" => "milliseconds",
        "us" | "µs" => "microseconds",
        "N/m" => "newtons per metre",
        "kN/m" => "kilonewtons per metre",
        "N/mm" => "newtons per millimetre",
        "MN/m" => "meganewtons per metre",
        "deg" | "°" => "degrees",
        "rad" => "radians",
        "rad/s" => "radians per second",
        "rpm" => "revolutions per minute",
        "rps" | "rev/s" => "revolutions per second",
        "N" => "newtons",
        "kN" => "kilonewtons",
        other => other,
    }
}

/// The remedy for a value whose unit was typed after a space (`--cart-mass 10 g`, which a shell passes
/// as two words): `write 10g`, when `number` is a bare number and `word` one of the dimension's units.
pub fn spaced_unit(number: &str, word: &str, dimension: Dimension) -> Option<String> {
    let (digits, suffix) = split_number(number.trim());
    let parses = suffix.is_empty() && digits.parse::<f64>().is_ok_and(f64::is_finite);
    (parses && dimension.find(word).is_some())
        .then(|| format!("write {digits}{word}, without a space"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_suffixes_into_base_units() {
        assert_eq!(parse("10g", Dimension::Mass), Ok(0.01));
        assert_eq!(parse("0.01kg", Dimension::Mass), Ok(0.01));
        assert_eq!(parse("5ms", Dimension::Time), Ok(0.005));
        assert_eq!(parse("33mm", Dimension::Length), Ok(0.033));
        assert_eq!(parse("15kN/m", Dimension::Stiffness), Ok(15000.0));
        assert_eq!(parse("60deg", Dimension::Angle), Ok(60.0));
        assert_eq!(parse("-100rad/s", Dimension::AngularVelocity), Ok(-100.0));
        assert_eq!(parse(" 1.5e4 N/m ", Dimension::Stiffness), Ok(15000.0));
        let rpm = parse("955rpm", Dimension::AngularVelocity).unwrap();
        assert!((rpm - 100.007366).abs() < 1e-5, "{rpm}");
        let rad = parse("1rad", Dimension::Angle).unwrap();
        assert!((rad - 57.29577951308232).abs() < 1e-12);
        let sw = parse("320 kg cm^2", Dimension::MomentOfInertia).unwrap();
        assert!((sw - 0.032).abs() < 1e-15, "{sw}");
        assert_eq!(parse("0.032 kg m²", Dimension::MomentOfInertia), Ok(0.032));
        assert!(matches!(
            parse("320 kg", Dimension::MomentOfInertia),
            Err(UnitError::WrongDimension { .. })
        ));
    }

    #[test]
    fn bare_numbers_are_base_units() {
        assert_eq!(parse("0.4", Dimension::Dimensionless), Ok(0.4));
        assert_eq!(parse("-3", Dimension::Speed), Ok(-3.0));
        assert_eq!(parse("1e-5", Dimension::Mass), Ok(1e-5));
    }

    #[test]
    fn rejects_bad_text_with_reasons() {
        assert_eq!(parse("", Dimension::Mass), Err(UnitError::Empty));
        assert!(matches!(
            parse("abc", Dimension::Mass),
            Err(UnitError::NotANumber(_))
        ));
        assert!(matches!(
            parse("inf", Dimension::Mass),
            Err(UnitError::NotFinite(_))
        ));
        assert!(matches!(
            parse("NaN", Dimension::Mass),
            Err(UnitError::NotFinite(_))
        ));
        assert!(matches!(
            parse("1e999", Dimension::Mass),
            Err(UnitError::NotFinite(_))
        ));
        assert!(matches!(
            parse("10 furlongs", Dimension::Length),
            Err(UnitError::UnknownUnit { .. })
        ));
        let err = parse("10g", Dimension::Angle).unwrap_err();
        assert!(
            matches!(
                err,
                UnitError::WrongDimension {
                    found: "a mass",
                    ..
                }
            ),
            "{err}"
        );
        assert!(matches!(
            parse("2 g", Dimension::Dimensionless),
            Err(UnitError::WrongDimension { .. })
        ));
    }

    #[test]
    fn shows_in_people_units() {
        assert_eq!(show(0.01, Dimension::Mass, "g", 1).to_string(), "10.0 g");
        assert_eq!(
            show(15000.0, Dimension::Stiffness, "kN/m", 1).to_string(),
            "15.0 kN/m"
        );
        assert_eq!(
            show(-0.0, Dimension::Length, "mm", 2).to_string(),
            "0.00 mm"
        );
        assert_eq!(brief(15000.0, 4), "15000");
        assert_eq!(brief(0.057, 4), "0.057");
        assert_eq!(brief(-100.0, 4), "-100");
        assert_eq!(brief(1e-5, 3), "1.00e-5");
    }

    #[test]
    fn a_bare_number_far_outside_its_usual_range_gets_a_note() {
        let mass = Usual {
            low: 0.0,
            high: 1.0,
            typical: 0.01,
        };
        let note = |text: &str| bare_note("--cart-mass", text, Dimension::Mass, "kg", mass);
        assert_eq!(
            note("10").as_deref(),
            Some("--cart-mass 10 is read as 10 kg; write 10g for grams")
        );
        assert_eq!(note("10±1").as_deref(), note("10").as_deref());
        assert_eq!(note("0.5"), None);
        assert_eq!(note("10kg"), None);
        assert_eq!(note("10 g"), None);
        assert_eq!(note("ten"), None);
        let radius = Usual {
            low: 0.0,
            high: 0.5,
            typical: 0.033,
        };
        assert_eq!(
            bare_note("--radius", "33", Dimension::Length, "m", radius).as_deref(),
            Some("--radius 33 is read as 33 m; write 33mm for millimetres")
        );
        let stiffness = Usual {
            low: 10.0,
            high: f64::INFINITY,
            typical: 15e3,
        };
        let k = |text: &str| bare_note("--stiffness", text, Dimension::Stiffness, "N/m", stiffness);
        assert_eq!(
            k("5").as_deref(),
            Some("--stiffness 5 is read as 5 N/m; write 5kN/m for kilonewtons per metre")
        );
        assert_eq!(k("0"), None);
        let time = Usual {
            low: 0.0,
            high: 0.05,
            typical: 0.005,
        };
        assert_eq!(
            bare_note("duration", "1e6", Dimension::Time, "s", time).as_deref(),
            Some("duration 1e6 is read as 1e6 s, more than the usual 0.05 s")
        );
    }

    #[test]
    fn a_unit_after_a_space_is_named() {
        assert_eq!(
            spaced_unit("10", "g", Dimension::Mass).as_deref(),
            Some("write 10g, without a space")
        );
        assert_eq!(spaced_unit("10", "kN/m", Dimension::Mass), None);
        assert_eq!(spaced_unit("ten", "g", Dimension::Mass), None);
    }
}
