//! The inputs of a bounce, and the one table that says each parameter's name, unit, range, step and help.
//! The command line, the scenario files, the explorer's parameter panel and its help overlay all read it.

use std::fmt;

use serde::{Deserialize, Serialize};

use super::units::{self, Dimension};

/// The default chain length for inputs written before the chain existed: the single cart.
fn single_cart() -> f64 {
    1.0
}

/// One end of an allowed range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bound {
    Open(f64),
    Closed(f64),
    Unbounded,
}

/// The values a parameter may take, in its base unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    pub low: Bound,
    pub high: Bound,
}

impl Range {
    pub const fn contains(&self, value: f64) -> bool {
        let above = match self.low {
            Bound::Open(b) => value > b,
            Bound::Closed(b) => value >= b,
            Bound::Unbounded => true,
        };
        let below = match self.high {
            Bound::Open(b) => value < b,
            Bound::Closed(b) => value <= b,
            Bound::Unbounded => true,
        };
        value.is_finite() && above && below
    }

    /// The nearest allowed value (an open bound is approached by a relative 1e-9).
    pub fn clamp(&self, value: f64) -> f64 {
        let nudge = |b: f64, up: bool| {
            let d = b.abs().max(1e-12) * 1e-9;
            if up { b + d } else { b - d }
        };
        let mut v = value;
        match self.low {
            Bound::Open(b) if v <= b => v = nudge(b, true),
            Bound::Closed(b) if v < b => v = b,
            _ => {}
        }
        match self.high {
            Bound::Open(b) if v >= b => v = nudge(b, false),
            Bound::Closed(b) if v > b => v = b,
            _ => {}
        }
        v
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let low = match self.low {
            Bound::Open(b) => format!("({}", units::brief(b, 6)),
            Bound::Closed(b) => format!("[{}", units::brief(b, 6)),
            Bound::Unbounded => "(-inf".to_string(),
        };
        let high = match self.high {
            Bound::Open(b) => format!("{})", units::brief(b, 6)),
            Bound::Closed(b) => format!("{}]", units::brief(b, 6)),
            Bound::Unbounded => "inf)".to_string(),
        };
        write!(f, "{low}, {high}")
    }
}

/// How a key press changes a parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Step {
    /// Add this many base units.
    Add(f64),
    /// Multiply by this factor. From zero, a step up goes to [`Step::FIRST_FROM_ZERO`].
    Times(f64),
}

impl Step {
    /// Where a multiplicative step up from zero lands (only stiffness can be zero: 100 N/m).
    pub const FIRST_FROM_ZERO: f64 = 100.0;

    /// `value` moved one step up (`up`) or down, kept inside `range`.
    pub fn apply(self, value: f64, up: bool, range: &Range) -> f64 {
        let moved = match self {
            Step::Add(d) => {
                let v = if up { value + d } else { value - d };
                // Snap to the step grid so repeated steps give round numbers.
                let snapped = (v / d).round() * d;
                if (snapped - v).abs() < d * 1e-6 {
                    snapped
                } else {
                    v
                }
            }
            Step::Times(_) if value == 0.0 => {
                if up {
                    Self::FIRST_FROM_ZERO
                } else {
                    0.0
                }
            }
            Step::Times(f) => {
                if up {
                    value * f
                } else {
                    value / f
                }
            }
        };
        range.clamp(moved)
    }
}

/// Which part of the system a parameter describes; the explorer lists the groups apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// The ball, how it arrives and how it meets the surface.
    Ball,
    /// The surface that moves sideways: the cart, its spring and its string friction.
    Surface,
    /// A stroke on court (`snapback shot`): the incoming ball, the racquet's swing, the court.
    Shot,
    /// The racquet that strikes a shot: its mass, balance, swing and twist weights, where it meets the ball.
    Racquet,
}

impl Group {
    pub fn name(self) -> &'static str {
        match self {
            Group::Ball => "ball and impact",
            Group::Surface => "surface",
            Group::Shot => "shot",
            Group::Racquet => "racquet",
        }
    }

    /// True for the groups only a shot uses (the stroke and its racquet).
    pub const fn is_shot(self) -> bool {
        match self {
            Group::Ball | Group::Surface => false,
            Group::Shot | Group::Racquet => true,
        }
    }
}

/// Everything the program knows about one parameter.
#[derive(Clone, Copy, Debug)]
pub struct ParamSpec {
    pub id: ParamId,
    pub group: Group,
    /// Command-line flag without dashes, e.g. `cart-mass`.
    pub flag: &'static str,
    /// Key in scenario files, e.g. `cart_mass`.
    pub key: &'static str,
    /// Symbol used in the paper, e.g. `M`.
    pub symbol: &'static str,
    /// Short name for people.
    pub label: &'static str,
    pub dimension: Dimension,
    /// The unit of a bare number on the command line and in scenario files, where it is not the base unit
    /// (spin in rpm); `None` for the base unit.
    pub bare_unit: Option<&'static str>,
    /// The unit people think in, for display.
    pub display_unit: &'static str,
    /// Decimals shown in `display_unit`.
    pub decimals: usize,
    pub range: Range,
    pub fine: Step,
    pub coarse: Step,
    pub default: f64,
    /// True for a count: only whole numbers in the range are allowed.
    pub integer: bool,
    /// The magnitudes the solver can carry a bounce through (see [`Solvable`]); `None` where every
    /// value in the range can be solved.
    pub solvable: Option<Solvable>,
    pub help: &'static str,
}

/// The magnitudes a parameter can be solved with: zero where its range allows it, or between `smallest`
/// and `largest`. Within these, every product the solver forms stays below 1e200 in size and above
/// 1e-200 (beyond, the bounce's forces and rates leave what f64 resolves).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solvable {
    pub smallest: f64,
    pub largest: f64,
}

/// The dimensional scales of the ball, the impact and the cart.
const SCALE: Option<Solvable> = Some(Solvable {
    smallest: 1e-15,
    largest: 1e15,
});

impl ParamSpec {
    /// `--flag`.
    pub fn long_flag(&self) -> String {
        format!("--{}", self.flag)
    }

    /// The unit of a bare number: [`ParamSpec::bare_unit`], else the base unit (`""` for a pure number).
    pub fn bare_symbol(&self) -> &'static str {
        self.bare_unit
            .unwrap_or_else(|| self.dimension.base_symbol())
    }

    /// Every other unit suffix the value may carry (`g`, `mg` for a mass in kg).
    pub fn other_symbols(&self) -> Vec<&'static str> {
        let bare = self.bare_symbol();
        self.dimension
            .symbols()
            .into_iter()
            .filter(|s| *s != bare)
            .collect()
    }

    /// A base-unit value in the bare unit.
    fn in_bare(&self, base_value: f64) -> f64 {
        units::in_unit(base_value, self.dimension, self.bare_symbol())
    }

    /// The allowed range in the bare unit, e.g. `(0, 90] deg`.
    pub fn range_text(&self) -> String {
        if let (true, Bound::Closed(low), Bound::Closed(high)) =
            (self.integer, self.range.low, self.range.high)
        {
            return format!("{{{low}, {}, ..., {high}}}", low + 1.0);
        }
        let unit = self.bare_symbol();
        let bound = |b: Bound| match b {
            Bound::Open(v) => Bound::Open(self.in_bare(v)),
            Bound::Closed(v) => Bound::Closed(self.in_bare(v)),
            Bound::Unbounded => Bound::Unbounded,
        };
        let range = Range {
            low: bound(self.range.low),
            high: bound(self.range.high),
        };
        if unit.is_empty() {
            range.to_string()
        } else {
            format!("{range} {unit}")
        }
    }

    /// A value in the display unit, e.g. `10.0 g`.
    pub fn show(&self, base_value: f64) -> units::Shown {
        units::Shown {
            zero_label: self.zero_means(),
            ..units::show(base_value, self.dimension, self.display_unit, self.decimals)
        }
    }

    /// What a value of zero stands for, where it is not just a zero.
    pub fn zero_means(&self) -> Option<&'static str> {
        match self.id {
            ParamId::BallStiffness => Some("rigid"),
            ParamId::FrameMass => Some("clamped"),
            ParamId::FrameNormalMass => Some("frame mass"),
            ParamId::RacquetMass => Some("clamped"),
            _ => None,
        }
    }

    /// Parses user text (with an optional unit suffix, or the word a zero stands for, e.g. `clamped`)
    /// and checks the range.
    pub fn parse(&self, text: &str) -> Result<f64, ParamError> {
        if self.zero_means().is_some_and(|word| word == text.trim()) {
            return Ok(0.0);
        }
        let bare = self
            .dimension
            .find(self.bare_symbol())
            .map_or(1.0, |u| u.to_base);
        let value = units::parse_bare(text, self.dimension, bare).map_err(|source| {
            ParamError::Unparsable {
                flag: self.flag,
                given: units::echo(text.trim()),
                source: Box::new(source),
            }
        })?;
        self.check(value, &units::echo(text.trim()))?;
        Ok(value)
    }

    /// Where a bare number for this parameter usually lies ([`units::Usual`]); `None` where any value
    /// of its range is as likely as another, or no other unit could be meant.
    pub fn usual(&self) -> Option<units::Usual> {
        let (low, high) = match self.id {
            ParamId::Mass | ParamId::CartMass => (0.0, 1.0),
            ParamId::Radius => (0.0, 0.5),
            ParamId::Duration | ParamId::CourtDuration => (0.0, 0.05),
            ParamId::Stiffness | ParamId::BallStiffness => (10.0, f64::INFINITY),
            ParamId::Speed | ParamId::BallSpeed | ParamId::RacquetSpeed => (0.0, 75.0),
            ParamId::Spin => (0.0, 1000.0),
            _ => return None,
        };
        Some(units::Usual {
            low,
            high,
            typical: self.default,
        })
    }

    /// A note for a bare number far outside this parameter's usual range, as `name` shows it:
    /// `--cart-mass 10 is read as 10 kg; write 10g for grams` ([`units::bare_note`]).
    pub fn bare_note(&self, name: &str, text: &str) -> Option<String> {
        units::bare_note(
            name,
            text,
            self.dimension,
            self.bare_symbol(),
            self.usual()?,
        )
    }

    /// True when `value` is in the range (and whole, for a count).
    pub fn allows(&self, value: f64) -> bool {
        self.range.contains(value) && (!self.integer || value.fract() == 0.0)
    }

    /// Checks a base-unit value against the range; the message shows it in the bare unit.
    #[inline]
    pub fn check_value(&self, value: f64) -> Result<(), ParamError> {
        if self.allows(value) {
            Ok(())
        } else {
            self.refuse_value(value)
        }
    }

    /// The refusal of a value out of range, in the bare unit (kept out of line: every solve validates).
    #[cold]
    fn refuse_value(&self, value: f64) -> Result<(), ParamError> {
        let unit = self.bare_symbol();
        self.check(
            value,
            format!("{} {unit}", units::brief(self.in_bare(value), 6)).trim_end(),
        )
    }

    /// Checks a base-unit value against the range; `given` is what the user typed, for the message.
    pub fn check(&self, value: f64, given: &str) -> Result<(), ParamError> {
        if self.allows(value) {
            Ok(())
        } else {
            Err(ParamError::OutOfRange {
                flag: self.flag,
                range: self.range_text(),
                given: given.to_string(),
            })
        }
    }
}

/// A parameter value that cannot be used. The message names the flag, the allowed range and the value given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParamError {
    #[error("--{flag} must be in {range}; got {given}")]
    OutOfRange {
        flag: &'static str,
        range: String,
        given: String,
    },
    #[error("--{flag}: {source}; got {given}")]
    Unparsable {
        flag: &'static str,
        given: String,
        source: Box<units::UnitError>,
    },
}

const POSITIVE: Range = Range {
    low: Bound::Open(0.0),
    high: Bound::Unbounded,
};
const NON_NEGATIVE: Range = Range {
    low: Bound::Closed(0.0),
    high: Bound::Unbounded,
};
/// A distance from a racquet's butt: up to 73.66 cm, the longest racquet the rules allow (ITF Rules of
/// Tennis, Appendix II: 29 in).
const RACQUET_LENGTH: Range = Range {
    low: Bound::Open(0.0),
    high: Bound::Closed(0.7366),
};

/// Declares every parameter once: its field in [`Params`] (SI), its [`ParamId`], and its row of [`PARAMS`]
/// (name, unit, range, steps, default, help), in the order the explorer lists them; `get` and `set` follow.
macro_rules! parameters {
    ($($(#[$attr:meta])* $field:ident: $id:ident { $($spec:tt)* },)*) => {
        /// Inputs of one bounce, and of a shot on court. SI units, except the angles (fields ending in
        /// `_deg`), in degrees. The bounce's defaults are the paper's Fig. 3(c) case.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
        #[serde(default)]
        pub struct Params {
            $($(#[$attr])* pub $field: f64,)*
        }

        /// Names a parameter.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum ParamId {
            $($id,)*
        }

        /// Every parameter, in the order the explorer lists them.
        pub const PARAMS: &[ParamSpec] = &[$(ParamSpec { id: ParamId::$id, $($spec)* },)*];

        impl Params {
            /// Every value, in [`ParamId`]'s order (the order of [`PARAMS`]).
            #[inline]
            pub fn values(&self) -> [f64; PARAM_COUNT] {
                [$(self.$field,)*]
            }

            pub fn get(&self, id: ParamId) -> f64 {
                match id {
                    $(ParamId::$id => self.$field,)*
                }
            }

            /// Sets a value without checking it; see [`Params::with`] for the checked version.
            pub fn set(&mut self, id: ParamId, value: f64) {
                match id {
                    $(ParamId::$id => self.$field = value,)*
                }
            }
        }

        impl Default for Params {
            fn default() -> Self {
                Params {
                    $($field: spec(ParamId::$id).default,)*
                }
            }
        }
    };
}

parameters! {
    /// Incidence angle theta1 from the surface, degrees (90 is normal incidence).
    angle_deg: Angle {
        group: Group::Ball,
        flag: "angle",
        key: "angle",
        symbol: "θ1",
        label: "incidence angle",
        dimension: Dimension::Angle,
        bare_unit: None,
        display_unit: "deg",
        decimals: 1,
        range: Range {
            low: Bound::Open(0.0),
            high: Bound::Closed(90.0),
        },
        fine: Step::Add(1.0),
        coarse: Step::Add(10.0),
        default: 60.0,
        integer: false,
        solvable: None,
        help: "incidence angle theta1, measured from the surface (90 = normal incidence)",
    },
    /// Incident speed v1, m/s.
    speed: Speed {
        group: Group::Ball,
        flag: "speed",
        key: "speed",
        symbol: "v1",
        label: "incident speed",
        dimension: Dimension::Speed,
        bare_unit: None,
        display_unit: "m/s",
        decimals: 1,
        range: POSITIVE,
        fine: Step::Add(0.5),
        coarse: Step::Add(5.0),
        default: 10.0,
        integer: false,
        solvable: SCALE,
        help: "incident speed v1 of the ball's centre",
    },
    /// Incident spin omega1, rad/s; positive is the sense sliding friction drives (topspin), negative is backspin.
    spin: Spin {
        group: Group::Ball,
        flag: "spin",
        key: "spin",
        symbol: "ω1",
        label: "incident spin",
        dimension: Dimension::AngularVelocity,
        bare_unit: None,
        display_unit: "rad/s",
        decimals: 0,
        range: Range {
            low: Bound::Unbounded,
            high: Bound::Unbounded,
        },
        fine: Step::Add(10.0),
        coarse: Step::Add(100.0),
        default: -100.0,
        integer: false,
        solvable: None,
        help: "incident spin omega1; positive = topspin (the sense sliding friction drives), negative = backspin",
    },
    /// Coefficient of sliding friction mu between ball and cart.
    mu: Mu {
        group: Group::Ball,
        flag: "mu",
        key: "mu",
        symbol: "μ",
        label: "sliding friction",
        dimension: Dimension::Dimensionless,
        bare_unit: None,
        display_unit: "",
        decimals: 2,
        range: NON_NEGATIVE,
        fine: Step::Add(0.01),
        coarse: Step::Add(0.1),
        default: 0.4,
        integer: false,
        solvable: Some(Solvable {
            smallest: 0.0,
            largest: 1e6,
        }),
        help: "coefficient of sliding friction mu between ball and surface",
    },
    /// Impact duration T, s.
    duration: Duration {
        group: Group::Ball,
        flag: "duration",
        key: "duration",
        symbol: "T",
        label: "impact duration",
        dimension: Dimension::Time,
        bare_unit: None,
        display_unit: "ms",
        decimals: 2,
        range: POSITIVE,
        fine: Step::Add(0.1e-3),
        coarse: Step::Add(1e-3),
        default: 5e-3,
        integer: false,
        solvable: SCALE,
        help: "impact duration T; the normal force is N0 sin(pi t / T)",
    },
    /// Normal coefficient of restitution e_y.
    ey: Ey {
        group: Group::Ball,
        flag: "ey",
        key: "ey",
        symbol: "e_y",
        label: "normal restitution",
        dimension: Dimension::Dimensionless,
        bare_unit: None,
        display_unit: "",
        decimals: 2,
        range: Range {
            low: Bound::Closed(0.0),
            high: Bound::Closed(1.0),
        },
        fine: Step::Add(0.01),
        coarse: Step::Add(0.1),
        default: 1.0,
        integer: false,
        solvable: None,
        help: "normal coefficient of restitution e_y = v_y2 / v_y1",
    },
    /// Ball mass m, kg.
    mass: Mass {
        group: Group::Ball,
        flag: "mass",
        key: "mass",
        symbol: "m",
        label: "ball mass",
        dimension: Dimension::Mass,
        bare_unit: None,
        display_unit: "g",
        decimals: 1,
        range: POSITIVE,
        fine: Step::Times(1.02),
        coarse: Step::Times(1.25),
        default: 0.057,
        integer: false,
        solvable: SCALE,
        help: "ball mass m",
    },
    /// Ball radius r, m.
    radius: Radius {
        group: Group::Ball,
        flag: "radius",
        key: "radius",
        symbol: "r",
        label: "ball radius",
        dimension: Dimension::Length,
        bare_unit: None,
        display_unit: "mm",
        decimals: 1,
        range: POSITIVE,
        fine: Step::Add(0.5e-3),
        coarse: Step::Add(5e-3),
        default: 0.033,
        integer: false,
        solvable: SCALE,
        help: "ball radius r",
    },
    /// I = alpha m r^2.
    alpha: Alpha {
        group: Group::Ball,
        flag: "alpha",
        key: "alpha",
        symbol: "α",
        label: "inertia factor",
        dimension: Dimension::Dimensionless,
        bare_unit: None,
        display_unit: "",
        decimals: 3,
        range: POSITIVE,
        fine: Step::Add(0.005),
        coarse: Step::Add(0.05),
        default: 0.55,
        integer: false,
        solvable: Some(Solvable {
            smallest: 1e-6,
            largest: 1e6,
        }),
        help: "moment of inertia factor: I = alpha m r^2 (0.4 solid sphere, 2/3 thin shell, 0.55 tennis ball)",
    },
    /// Tangential stiffness k_b of the ball's contact region, N/m; 0 = a rigid ball (the paper's model).
    #[serde(default)]
    ball_stiffness: BallStiffness {
        group: Group::Ball,
        flag: "ball-stiffness",
        key: "ball_stiffness",
        symbol: "k_b",
        label: "ball stiffness",
        dimension: Dimension::Stiffness,
        bare_unit: None,
        display_unit: "kN/m",
        decimals: 1,
        range: NON_NEGATIVE,
        fine: Step::Times(1.1),
        coarse: Step::Times(2.0),
        default: 0.0,
        integer: false,
        solvable: Some(Solvable {
            smallest: 0.0,
            largest: 1e30,
        }),
        help: "tangential stiffness k_b of the ball's contact region (a massless spring and dashpot between \
               the ball and its contact patch); 0 = a rigid ball, the paper's model. On the cart (with string \
               friction too) or a chain (without). A stiff undamped ball does not approach the rigid ball: its force keeps \
               swinging and the grip chatters (up to 10 000 phases, then the bounce is refused)",
    },
    /// Damping ratio zeta of the ball's contact spring, relative to its mode sqrt(k_b/m_eff):
    /// c_b = 2 zeta sqrt(k_b m_eff).
    #[serde(default)]
    ball_damping: BallDamping {
        group: Group::Ball,
        flag: "ball-damping",
        key: "ball_damping",
        symbol: "ζ_b",
        label: "ball damping",
        dimension: Dimension::Dimensionless,
        bare_unit: None,
        display_unit: "",
        decimals: 3,
        range: Range {
            low: Bound::Closed(0.0),
            high: Bound::Closed(10.0),
        },
        fine: Step::Add(0.05),
        coarse: Step::Add(0.5),
        default: 0.0,
        integer: false,
        solvable: None,
        help: "damping ratio of the ball's contact spring, relative to sqrt(k_b/m_eff) (1 = critical); \
               ignored for a rigid ball. A stiff, critically damped ball approaches the rigid ball; an \
               undamped one chatters between grip and slide",
    },
    /// Cart mass M, kg.
    cart_mass: CartMass {
        group: Group::Surface,
        flag: "cart-mass",
        key: "cart_mass",
        symbol: "M",
        label: "cart mass",
        dimension: Dimension::Mass,
        bare_unit: None,
        display_unit: "g",
        decimals: 2,
        range: POSITIVE,
        fine: Step::Times(1.1),
        coarse: Step::Times(2.0),
        default: 0.010,
        integer: false,
        solvable: SCALE,
        help: "mass M of the surface that moves sideways (the cart; the moving part of the strings)",
    },
    /// Spring stiffness k, N/m.
    stiffness: Stiffness {
        group: Group::Surface,
        flag: "stiffness",
        key: "stiffness",
        symbol: "k",
        label: "spring stiffness",
        dimension: Dimension::Stiffness,
        bare_unit: None,
        display_unit: "kN/m",
        decimals: 2,
        range: NON_NEGATIVE,
        fine: Step::Times(1.05),
        coarse: Step::Times(1.5),
        default: 15000.0,
        integer: false,
        solvable: Some(Solvable {
            smallest: 0.0,
            largest: 1e30,
        }),
        help: "stiffness k of the spring that pulls the cart back (0 = a free cart)",
    },
    /// Coulomb friction on the cart, N (string-on-string friction; 0 is the paper's model).
    #[serde(default)]
    cart_friction: CartFriction {
        group: Group::Surface,
        flag: "cart-friction",
        key: "cart_friction",
        symbol: "F_c",
        label: "string friction",
        dimension: Dimension::Force,
        bare_unit: None,
        display_unit: "N",
        decimals: 1,
        range: NON_NEGATIVE,
        fine: Step::Add(1.0),
        coarse: Step::Add(10.0),
        default: 0.0,
        integer: false,
        solvable: Some(Solvable {
            smallest: 0.0,
            largest: 1e30,
        }),
        help: "Coulomb friction on the cart (string-on-string friction): the cart sticks while the spring \
               and the ball push it with less than this; 0 = the paper's model",
    },
    /// Number N of equal masses the cart is split into, a whole number 1..=16 (1 is the paper's single
    /// cart): a chain of masses M/N and springs N k, touched by the ball at its first mass.
    #[serde(default = "single_cart")]
    chain: Chain {
        group: Group::Surface,
        flag: "chain",
        key: "chain",
        symbol: "N",
        label: "chain masses",
        dimension: Dimension::Dimensionless,
        bare_unit: None,
        display_unit: "",
        decimals: 0,
        range: Range {
            low: Bound::Closed(1.0),
            high: Bound::Closed(16.0),
        },
        fine: Step::Add(1.0),
        coarse: Step::Add(5.0),
        default: 1.0,
        integer: true,
        solvable: None,
        help: "number N of equal masses the cart is split into: a chain of masses M/N joined by springs N k, \
               the last tied to the wall (static stiffness k at the ball); 1 = the paper's single cart",
    },
    /// Mass M_t of the frame the strings are tied to, along the surface, kg; 0 = clamped (an immovable
    /// wall, the paper's model). Also its effective mass normal to the surface unless
    /// `frame_normal_mass` is given.
    #[serde(default)]
    frame_mass: FrameMass {
        group: Group::Surface,
        flag: "frame-mass",
        key: "frame_mass",
        symbol: "M_t",
        label: "frame mass",
        dimension: Dimension::Mass,
        bare_unit: None,
        display_unit: "g",
        decimals: 1,
        range: NON_NEGATIVE,
        fine: Step::Times(1.1),
        coarse: Step::Times(2.0),
        default: 0.0,
        integer: false,
        solvable: SCALE,
        help: "mass M_t of the frame the spring (a chain's last spring) is tied to, free along the surface; \
               also its effective mass normal to the surface unless --frame-normal-mass is given; \
               clamped (0, the default) = an immovable wall, the paper's model",
    },
    /// Effective mass M_n of the frame normal to the surface, kg; 0 = the frame mass M_t.
    #[serde(default)]
    frame_normal_mass: FrameNormalMass {
        group: Group::Surface,
        flag: "frame-normal-mass",
        key: "frame_normal_mass",
        symbol: "M_n",
        label: "frame normal mass",
        dimension: Dimension::Mass,
        bare_unit: None,
        display_unit: "g",
        decimals: 1,
        range: NON_NEGATIVE,
        fine: Step::Times(1.1),
        coarse: Step::Times(2.0),
        default: 0.0,
        integer: false,
        solvable: SCALE,
        help: "effective mass M_n of the frame normal to the surface: the ball leaves with the apparent \
               restitution e_A = (e_y M_n - m)/(M_n + m); 0 (the default) = the frame mass M_t",
    },
    /// Height of the ball's centre where the racquet meets it, m (court frame: y up).
    height: Height {
        group: Group::Shot,
        flag: "height",
        key: "height",
        symbol: "h",
        label: "contact height",
        dimension: Dimension::Length,
        bare_unit: None,
        display_unit: "m",
        decimals: 2,
        range: Range {
            low: Bound::Open(0.0),
            high: Bound::Closed(5.0),
        },
        fine: Step::Add(0.05),
        coarse: Step::Add(0.5),
        default: 1.0,
        integer: false,
        solvable: None,
        help: "height of the ball's centre above the court where the racquet meets it, over the hitter's baseline",
    },
    /// Speed of the incoming ball, m/s, travelling towards -x.
    ball_speed: BallSpeed {
        group: Group::Shot,
        flag: "ball-speed",
        key: "ball_speed",
        symbol: "v_b",
        label: "incoming speed",
        dimension: Dimension::Speed,
        bare_unit: None,
        display_unit: "m/s",
        decimals: 1,
        range: Range {
            low: Bound::Closed(0.0),
            high: Bound::Closed(100.0),
        },
        fine: Step::Add(1.0),
        coarse: Step::Add(5.0),
        default: 20.0,
        integer: false,
        solvable: None,
        help: "speed of the incoming ball, travelling towards the hitter (0 = a ball at rest, as at the top of a serve toss)",
    },
    /// Angle of the incoming ball's path below the horizontal, degrees (negative: rising).
    ball_descent_deg: BallDescent {
        group: Group::Shot,
        flag: "ball-descent",
        key: "ball_descent",
        symbol: "δ_b",
        label: "incoming descent",
        dimension: Dimension::Angle,
        bare_unit: None,
        display_unit: "deg",
        decimals: 1,
        range: Range {
            low: Bound::Closed(-90.0),
            high: Bound::Closed(90.0),
        },
        fine: Step::Add(1.0),
        coarse: Step::Add(5.0),
        default: 10.0,
        integer: false,
        solvable: None,
        help: "angle of the incoming ball's path below the horizontal (negative = rising)",
    },
    /// Spin of the incoming ball, rad/s; topspin positive relative to its own direction of travel.
    ball_topspin: BallTopspin {
        group: Group::Shot,
        flag: "ball-topspin",
        key: "ball_topspin",
        symbol: "ω_b",
        label: "incoming topspin",
        dimension: Dimension::AngularVelocity,
        bare_unit: Some("rpm"),
        display_unit: "rpm",
        decimals: 0,
        range: Range {
            low: Bound::Closed(-10000.0 * std::f64::consts::PI / 30.0),
            high: Bound::Closed(10000.0 * std::f64::consts::PI / 30.0),
        },
        fine: Step::Add(100.0 * std::f64::consts::PI / 30.0),
        coarse: Step::Add(1000.0 * std::f64::consts::PI / 30.0),
        default: 1000.0 * std::f64::consts::PI / 30.0,
        integer: false,
        solvable: None,
        help: "spin of the incoming ball, topspin positive relative to its own direction of travel, negative = backspin",
    },
    /// Speed of the racquet (the strings where they meet the ball), m/s.
    racquet_speed: RacquetSpeed {
        group: Group::Shot,
        flag: "racquet-speed",
        key: "racquet_speed",
        symbol: "V_r",
        label: "racquet speed",
        dimension: Dimension::Speed,
        bare_unit: None,
        display_unit: "m/s",
        decimals: 1,
        range: Range {
            low: Bound::Closed(0.0),
            high: Bound::Closed(100.0),
        },
        fine: Step::Add(1.0),
        coarse: Step::Add(5.0),
        default: 20.0,
        integer: false,
        solvable: None,
        help: "speed of the racquet where it meets the ball, along the swing path",
    },
    /// Direction of the racquet's motion above the horizontal, towards +x, degrees (low to high positive).
    swing_path_deg: SwingPath {
        group: Group::Shot,
        flag: "swing-path",
        key: "swing_path",
        symbol: "ψ",
        label: "swing path",
        dimension: Dimension::Angle,
        bare_unit: None,
        display_unit: "deg",
        decimals: 1,
        range: Range {
            low: Bound::Open(-90.0),
            high: Bound::Open(90.0),
        },
        fine: Step::Add(1.0),
        coarse: Step::Add(5.0),
        default: 25.0,
        integer: false,
        solvable: None,
        help: "direction of the racquet's motion above the horizontal, towards the net (low to high = positive)",
    },
    /// Tilt of the string plane's normal below the horizontal, degrees (positive = closed face).
    face_angle_deg: FaceAngle {
        group: Group::Shot,
        flag: "face-angle",
        key: "face_angle",
        symbol: "φ",
        label: "face angle",
        dimension: Dimension::Angle,
        bare_unit: None,
        display_unit: "deg",
        decimals: 1,
        range: Range {
            low: Bound::Open(-90.0),
            high: Bound::Open(90.0),
        },
        fine: Step::Add(1.0),
        coarse: Step::Add(5.0),
        default: 0.0,
        integer: false,
        solvable: None,
        help: "tilt of the string plane's normal from the horizontal; positive = a closed face (normal tilted down)",
    },
    /// Coefficient of sliding friction between ball and court.
    court_mu: CourtMu {
        group: Group::Shot,
        flag: "court-mu",
        key: "court_mu",
        symbol: "μ_c",
        label: "court friction",
        dimension: Dimension::Dimensionless,
        bare_unit: None,
        display_unit: "",
        decimals: 2,
        range: NON_NEGATIVE,
        fine: Step::Add(0.01),
        coarse: Step::Add(0.1),
        default: 0.6,
        integer: false,
        solvable: None,
        help: "coefficient of sliding friction mu between ball and court",
    },
    /// Normal coefficient of restitution on the court.
    court_ey: CourtEy {
        group: Group::Shot,
        flag: "court-ey",
        key: "court_ey",
        symbol: "e_c",
        label: "court restitution",
        dimension: Dimension::Dimensionless,
        bare_unit: None,
        display_unit: "",
        decimals: 2,
        range: Range {
            low: Bound::Closed(0.0),
            high: Bound::Closed(1.0),
        },
        fine: Step::Add(0.01),
        coarse: Step::Add(0.1),
        default: 0.75,
        integer: false,
        solvable: None,
        help: "normal coefficient of restitution e_y of the bounce on the court",
    },
    /// Duration of the bounce on the court, s.
    court_duration: CourtDuration {
        group: Group::Shot,
        flag: "court-duration",
        key: "court_duration",
        symbol: "T_c",
        label: "court contact",
        dimension: Dimension::Time,
        bare_unit: None,
        display_unit: "ms",
        decimals: 2,
        range: POSITIVE,
        fine: Step::Add(0.1e-3),
        coarse: Step::Add(1e-3),
        default: 4e-3,
        integer: false,
        solvable: None,
        help: "duration of the bounce on the court (the normal force is a half sine, as on the strings)",
    },
    /// Mass M_r of the racquet that strikes a shot, kg; 0 = clamped (an immovable racquet).
    racquet_mass: RacquetMass {
        group: Group::Racquet,
        flag: "racquet-mass",
        key: "racquet_mass",
        symbol: "M_r",
        label: "racquet mass",
        dimension: Dimension::Mass,
        bare_unit: None,
        display_unit: "g",
        decimals: 0,
        range: NON_NEGATIVE,
        fine: Step::Add(0.005),
        coarse: Step::Add(0.02),
        default: 0.320,
        integer: false,
        solvable: None,
        help: "mass M_r of the racquet, held in the hand (free to recoil); clamped (0) = an immovable \
               racquet, the strings on a wall",
    },
    /// Balance: the racquet's centre of mass from the butt, m.
    balance: Balance {
        group: Group::Racquet,
        flag: "balance",
        key: "balance",
        symbol: "b_r",
        label: "balance",
        dimension: Dimension::Length,
        bare_unit: None,
        display_unit: "cm",
        decimals: 1,
        range: RACQUET_LENGTH,
        fine: Step::Add(0.005),
        coarse: Step::Add(0.02),
        default: 0.33,
        integer: false,
        solvable: None,
        help: "balance point: the racquet's centre of mass measured from the butt",
    },
    /// Swing weight SW: the racquet's moment of inertia about an axis 10 cm from the butt, kg m^2.
    swing_weight: SwingWeight {
        group: Group::Racquet,
        flag: "swing-weight",
        key: "swing_weight",
        symbol: "SW",
        label: "swing weight",
        dimension: Dimension::MomentOfInertia,
        bare_unit: Some("kg cm^2"),
        display_unit: "kg cm^2",
        decimals: 0,
        range: POSITIVE,
        fine: Step::Add(5e-4),
        coarse: Step::Add(20e-4),
        default: 320e-4,
        integer: false,
        solvable: None,
        help: "swing weight SW: the moment of inertia about an axis 10 cm from the butt, as racquet \
               specifications quote it",
    },
    /// Twist weight TW: the racquet's moment of inertia about its long axis, kg m^2.
    twist_weight: TwistWeight {
        group: Group::Racquet,
        flag: "twist-weight",
        key: "twist_weight",
        symbol: "TW",
        label: "twist weight",
        dimension: Dimension::MomentOfInertia,
        bare_unit: Some("kg cm^2"),
        display_unit: "kg cm^2",
        decimals: 1,
        range: NON_NEGATIVE,
        fine: Step::Add(0.5e-4),
        coarse: Step::Add(2e-4),
        default: 14e-4,
        integer: false,
        solvable: None,
        help: "twist weight TW: the moment of inertia about the racquet's long axis",
    },
    /// Where the ball meets the strings, measured from the butt along the long axis, m.
    impact: Impact {
        group: Group::Racquet,
        flag: "impact",
        key: "impact",
        symbol: "d_i",
        label: "impact point",
        dimension: Dimension::Length,
        bare_unit: None,
        display_unit: "cm",
        decimals: 1,
        range: RACQUET_LENGTH,
        fine: Step::Add(0.005),
        coarse: Step::Add(0.02),
        default: 0.52,
        integer: false,
        solvable: None,
        help: "where the ball meets the strings, measured from the butt along the long axis",
    },
}

/// The parameters of one bounce: every group but the shot's, which come last in [`PARAMS`].
pub const BOUNCE_PARAMS: &[ParamSpec] = PARAMS.split_at(bounce_count()).0;

const fn bounce_count() -> usize {
    let mut n = 0;
    while n < PARAMS.len() && !PARAMS[n].group.is_shot() {
        n += 1;
    }
    n
}

/// The number of parameters: the rows of [`PARAMS`].
pub const PARAM_COUNT: usize = PARAMS.len();

/// Each parameter's range as the closed interval of the values it allows (an open end moved to the
/// next f64 inside, an unbounded one to the largest finite f64, so NaN and the infinities fall
/// outside): the whole check of a value is two comparisons. Lower ends, then upper ends.
const RANGES: [[f64; PARAM_COUNT]; 2] = {
    let mut ranges = [[0.0; PARAM_COUNT]; 2];
    let mut i = 0;
    while i < PARAM_COUNT {
        let range = PARAMS[i].range;
        ranges[0][i] = match range.low {
            Bound::Open(b) => b.next_up(),
            Bound::Closed(b) => b,
            Bound::Unbounded => -f64::MAX,
        };
        ranges[1][i] = match range.high {
            Bound::Open(b) => b.next_down(),
            Bound::Closed(b) => b,
            Bound::Unbounded => f64::MAX,
        };
        i += 1;
    }
    ranges
};

/// The counts among the parameters (whole numbers only), by index.
const COUNTS: [usize; count_rows()] = {
    let mut counts = [0; count_rows()];
    let (mut i, mut n) = (0, 0);
    while i < PARAM_COUNT {
        if PARAMS[i].integer {
            counts[n] = i;
            n += 1;
        }
        i += 1;
    }
    counts
};

const fn count_rows() -> usize {
    let (mut i, mut n) = (0, 0);
    while i < PARAM_COUNT {
        n += PARAMS[i].integer as usize;
        i += 1;
    }
    n
}

/// True when every value lies in its range and every count is whole: the check of every solve, as
/// comparisons on the table [`RANGES`] (a count is compared with its truncation, which is exact below
/// 2^63; a count beyond fails here and is judged by its row).
#[inline]
fn all_allowed(values: &[f64; PARAM_COUNT]) -> bool {
    let [low, high] = &RANGES;
    let mut ok = true;
    for i in 0..PARAM_COUNT {
        ok &= (values[i] >= low[i]) & (values[i] <= high[i]);
    }
    for i in COUNTS {
        ok &= values[i] == values[i] as i64 as f64;
    }
    ok
}

/// The spec of one parameter: its row of [`PARAMS`], which lists them in [`ParamId`]'s order.
#[inline]
pub fn spec(id: ParamId) -> &'static ParamSpec {
    &PARAMS[id as usize]
}

/// The spec whose flag (`cart-mass`) or key (`cart_mass`) is `name`.
pub fn spec_named(name: &str) -> Option<&'static ParamSpec> {
    PARAMS.iter().find(|s| s.flag == name || s.key == name)
}

impl Params {
    /// A copy with one value changed, if the value is in range.
    pub fn with(mut self, id: ParamId, value: f64) -> Result<Self, ParamError> {
        spec(id).check_value(value)?;
        self.set(id, value);
        Ok(self)
    }

    /// Checks every value against its range.
    #[inline]
    pub fn validate(&self) -> Result<(), ParamError> {
        if all_allowed(&self.values()) {
            Ok(())
        } else {
            self.refusal()
        }
    }

    /// The first value out of its range, refused row by row (kept out of line: every solve validates,
    /// and [`all_allowed`] passes almost all of them).
    #[cold]
    #[inline(never)]
    fn refusal(&self) -> Result<(), ParamError> {
        PARAMS
            .iter()
            .try_for_each(|spec| spec.check_value(self.get(spec.id)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_fig3c() {
        let p = Params::default();
        assert_eq!(p.mass, 0.057);
        assert_eq!(p.radius, 0.033);
        assert_eq!(p.alpha, 0.55);
        assert_eq!(p.speed, 10.0);
        assert_eq!(p.angle_deg, 60.0);
        assert_eq!(p.spin, -100.0);
        assert_eq!(p.mu, 0.4);
        assert_eq!(p.duration, 0.005);
        assert_eq!(p.ey, 1.0);
        assert_eq!(p.cart_mass, 0.010);
        assert_eq!(p.stiffness, 15000.0);
        assert_eq!(p.chain, 1.0);
        assert!(p.validate().is_ok());
    }

    /// The table passes only what each row passes, and validation answers as the rows do, at and beside
    /// every bound and off the numbers.
    #[test]
    fn the_fast_check_is_the_rows_check() {
        let base = Params::default();
        for spec in PARAMS {
            let mut values = vec![0.0, -0.0, 0.5, 1.0, 2.5, 16.0, 17.0, -1.0, 1e300, -1e300];
            values.extend([
                f64::NAN,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::MAX,
                f64::MIN,
            ]);
            for bound in [spec.range.low, spec.range.high] {
                if let Bound::Open(b) | Bound::Closed(b) = bound {
                    values.extend([b, b.next_up(), b.next_down(), b + 0.5, b - 0.5]);
                }
            }
            for value in values {
                let mut p = base;
                p.set(spec.id, value);
                let rows = PARAMS.iter().try_for_each(|s| s.check_value(p.get(s.id)));
                assert!(
                    !all_allowed(&p.values()) || rows.is_ok(),
                    "{} {value}",
                    spec.flag
                );
                assert_eq!(p.validate(), rows, "{} {value}", spec.flag);
            }
        }
    }

    #[test]
    fn every_id_has_one_row() {
        for (i, spec) in PARAMS.iter().enumerate() {
            assert_eq!(spec.id as usize, i, "PARAMS is in ParamId's order");
            assert_eq!(PARAMS.iter().filter(|s| s.id == spec.id).count(), 1);
            assert_eq!(spec_named(spec.flag).map(|s| s.id), Some(spec.id));
            assert_eq!(spec_named(spec.key).map(|s| s.id), Some(spec.id));
        }
    }

    #[test]
    fn the_shot_group_comes_last() {
        let (bounce, shot) = PARAMS.split_at(BOUNCE_PARAMS.len());
        assert!(bounce.iter().all(|s| !s.group.is_shot()));
        assert!(!shot.is_empty() && shot.iter().all(|s| s.group.is_shot()));
    }

    #[test]
    fn a_bare_spin_of_the_incoming_ball_is_in_rpm() {
        let topspin = spec(ParamId::BallTopspin);
        let rpm = std::f64::consts::PI / 30.0;
        assert_eq!(topspin.parse("1000"), Ok(1000.0 * rpm));
        assert_eq!(topspin.parse("10 rad/s"), Ok(10.0));
        assert_eq!(topspin.bare_symbol(), "rpm");
        assert_eq!(topspin.other_symbols(), ["rad/s", "rps", "rev/s"]);
        let err = topspin.parse("20000").unwrap_err();
        assert_eq!(
            err.to_string(),
            "--ball-topspin must be in [-10000, 10000] rpm; got 20000"
        );
        let err = Params::default()
            .with(ParamId::BallTopspin, 2000.0)
            .unwrap_err();
        assert!(err.to_string().ends_with("got 19098.6 rpm"), "{err}");
        // Everyone else's bare number stays in the base unit.
        assert_eq!(spec(ParamId::Spin).parse("100"), Ok(100.0));
        assert_eq!(spec(ParamId::Spin).other_symbols(), ["rpm", "rps", "rev/s"]);
    }

    #[test]
    fn range_errors_name_flag_range_and_value() {
        let err = spec(ParamId::Angle).parse("95deg").unwrap_err();
        assert_eq!(err.to_string(), "--angle must be in (0, 90] deg; got 95deg");
        let err = spec(ParamId::CartMass).parse("-5g").unwrap_err();
        assert_eq!(
            err.to_string(),
            "--cart-mass must be in (0, inf) kg; got -5g"
        );
        let err = spec(ParamId::Ey).parse("1.5").unwrap_err();
        assert_eq!(err.to_string(), "--ey must be in [0, 1]; got 1.5");
        let err = spec(ParamId::Stiffness).parse("15 kg").unwrap_err();
        assert!(
            err.to_string()
                .starts_with("--stiffness: unit 'kg' is a mass"),
            "{err}"
        );
    }

    #[test]
    fn the_chain_takes_whole_numbers_only() {
        let chain = spec(ParamId::Chain);
        assert_eq!(chain.parse("8"), Ok(8.0));
        let err = chain.parse("2.5").unwrap_err();
        assert_eq!(
            err.to_string(),
            "--chain must be in {1, 2, ..., 16}; got 2.5"
        );
        let err = chain.parse("17").unwrap_err();
        assert_eq!(
            err.to_string(),
            "--chain must be in {1, 2, ..., 16}; got 17"
        );
        let err = Params::default().with(ParamId::Chain, 3.5).unwrap_err();
        assert_eq!(
            err.to_string(),
            "--chain must be in {1, 2, ..., 16}; got 3.5"
        );
        assert_eq!(chain.fine.apply(16.0, true, &chain.range), 16.0);
        assert_eq!(chain.coarse.apply(1.0, true, &chain.range), 6.0);
        // Inputs written before the chain existed are single carts.
        let old = r#"{"angle_deg":60.0,"speed":10.0,"spin":0.0,"mu":0.4,"duration":0.005,"ey":1.0,
            "mass":0.057,"radius":0.033,"alpha":0.55,"cart_mass":0.01,"stiffness":15000.0}"#;
        let p: Params = serde_json::from_str(old).unwrap();
        assert_eq!(p.chain, 1.0);
    }

    #[test]
    fn steps_stay_in_range_and_on_grid() {
        let angle = spec(ParamId::Angle);
        assert_eq!(angle.fine.apply(60.0, true, &angle.range), 61.0);
        assert_eq!(angle.coarse.apply(85.0, true, &angle.range), 90.0);
        let low = angle.fine.apply(0.5, false, &angle.range);
        assert!(low > 0.0 && low < 1e-6);
        let k = spec(ParamId::Stiffness);
        assert_eq!(k.coarse.apply(0.0, false, &k.range), 0.0);
        assert!((k.coarse.apply(15000.0, true, &k.range) - 22500.0).abs() < 1e-9);
    }
}
