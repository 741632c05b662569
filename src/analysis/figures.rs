//! The data of the paper's figures, ready to draw, at any parameters: Fig. 3 (F, X and omega against
//! t) at the given bounce, and Fig. 2 (omega2 against theta1) around it: the given incident spin and
//! the comparison spin, each for the given cart and the paper's other carts. At the defaults (the
//! paper's Fig. 3(c) case) these are the paper's figures: the three carts, omega1 = 0 and -100 rad/s.

use crate::model::params::{BOUNCE_PARAMS, ParamId, spec};
use crate::model::{Params, SolveOptions, solve_with};

use super::cases::{CARTS, SPINS};
use super::{AnalysisError, Span, sweep};

/// One line of a plot: a legend label and (x, y) points.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// One set of axes.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    pub title: String,
    /// Axis titles with units, e.g. `θ1 (deg)`.
    pub x_label: String,
    pub y_label: String,
    pub curves: Vec<Curve>,
}

/// A figure: panels laid out in `columns` columns, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    pub title: String,
    pub panels: Vec<Panel>,
    pub columns: usize,
    /// Width and height in pixels.
    pub size: (u32, u32),
}

/// The figures the `figure` command draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Which {
    Fig2,
    Fig3,
}

impl Which {
    pub const ALL: [Which; 2] = [Which::Fig2, Which::Fig3];

    pub fn name(self) -> &'static str {
        match self {
            Which::Fig2 => "fig2",
            Which::Fig3 => "fig3",
        }
    }

    /// Reads the figure's name.
    pub fn parse(text: &str) -> Result<Which, AnalysisError> {
        Which::ALL
            .into_iter()
            .find(|w| w.name() == text.trim())
            .ok_or_else(|| {
                AnalysisError::Input(format!(
                    "FIGURE must be one of fig2, fig3; got {}",
                    crate::model::units::echo(text.trim())
                ))
            })
    }

    /// The figure's data for the ball, speed, friction and impact of `base`.
    pub fn data(self, base: &Params) -> Result<Figure, AnalysisError> {
        self.data_with(base, &SolveOptions::default())
    }

    /// [`Which::data`] with every bounce solved on the caller's terms.
    pub fn data_with(self, base: &Params, options: &SolveOptions) -> Result<Figure, AnalysisError> {
        match self {
            Which::Fig2 => fig2(base, options),
            Which::Fig3 => fig3(base, options),
        }
    }
}

/// Angles of Fig. 2: 0.1 deg to 90 deg every 0.1 deg.
const FIG2_STEPS: usize = 900;

/// Samples of each Fig. 3 time series (both sides of every transition are added).
const FIG3_SAMPLES: usize = 1001;

/// The parameters a figure varies itself, named in its axes, panels and legends.
const DRAWN: [ParamId; 4] = [
    ParamId::Angle,
    ParamId::Spin,
    ParamId::CartMass,
    ParamId::Stiffness,
];

/// One curve's bounce: a legend label and the parameters.
struct Case {
    label: String,
    params: Params,
}

/// The paper's carts other than `base`'s, then `base`'s own cart (labelled as the paper's where it is
/// one), each with every other parameter of `base`.
fn cases(base: &Params) -> Vec<Case> {
    let given = CARTS
        .iter()
        .find(|c| c.mass == base.cart_mass && c.stiffness == base.stiffness);
    let label = given.map_or_else(
        || {
            format!(
                "M = {}, k = {}",
                spec(ParamId::CartMass).show(base.cart_mass),
                spec(ParamId::Stiffness).show(base.stiffness)
            )
        },
        |c| c.label.to_string(),
    );
    CARTS
        .iter()
        .filter(|c| Some(*c) != given)
        .map(|c| Case {
            label: c.label.to_string(),
            params: c.case(base, base.angle_deg, base.spin),
        })
        .chain([Case {
            label,
            params: *base,
        }])
        .collect()
}

/// The parameters of `base` away from their defaults, other than `shown` and those the figure
/// draws, as `, v1 = 12.0 m/s, N = 8`; empty at the defaults.
fn conditions(base: &Params, shown: &[ParamId]) -> String {
    BOUNCE_PARAMS
        .iter()
        .filter(|s| !DRAWN.contains(&s.id) && !shown.contains(&s.id))
        .filter(|s| base.get(s.id) != s.default)
        .map(|s| format!(", {} = {}", s.symbol, s.show(base.get(s.id))))
        .collect()
}

/// Fig. 2 around `base`: omega2 against theta1, one panel for omega1 = 0 and one for the given spin
/// (-100 rad/s when that is 0), each with the given cart and the paper's other carts.
pub fn fig2(base: &Params, options: &SolveOptions) -> Result<Figure, AnalysisError> {
    let angles = Span::new(spec(ParamId::Angle), 0.1, 90.0, false)?;
    let spins = [
        SPINS[0],
        if base.spin == 0.0 {
            SPINS[1]
        } else {
            base.spin
        },
    ];
    let cases = cases(base);
    let panels = spins
        .iter()
        .zip(["(a)", "(b)"])
        .map(|(&spin, tag)| {
            let curves = cases
                .iter()
                .map(|case| {
                    // The angle is the swept parameter.
                    let p = Params {
                        spin,
                        ..case.params
                    };
                    let rows = sweep::sweep_with(&p, &angles, FIG2_STEPS, options)?;
                    Ok(Curve {
                        label: case.label.clone(),
                        points: rows.iter().map(|r| (r.value, r.omega2)).collect(),
                    })
                })
                .collect::<Result<_, AnalysisError>>()?;
            Ok(Panel {
                title: format!("{tag} ω1 = {spin} rad/s"),
                x_label: "θ1 (deg)".into(),
                y_label: "ω2 (rad/s)".into(),
                curves,
            })
        })
        .collect::<Result<_, AnalysisError>>()?;
    Ok(Figure {
        title: format!(
            "Fig. 2: rebound spin ω2 against angle of incidence θ1 (v1 = {} m/s, μ = {}{})",
            base.speed,
            base.mu,
            conditions(base, &[ParamId::Speed, ParamId::Mu])
        ),
        panels,
        columns: 2,
        size: (1200, 560),
    })
}

/// Fig. 3 at `base`: the friction force F, the cart displacement X and the ball's spin omega against
/// time, at the given angle and spin, for the given cart and the paper's other carts.
pub fn fig3(base: &Params, options: &SolveOptions) -> Result<Figure, AnalysisError> {
    let series = cases(base)
        .into_iter()
        .map(|case| {
            let b = solve_with(&case.params, options).map_err(|source| AnalysisError::Case {
                case: format!(
                    "{} at {} deg, omega1 = {} rad/s",
                    case.label, base.angle_deg, base.spin
                ),
                source,
            })?;
            Ok((case.label, b.series(FIG3_SAMPLES)))
        })
        .collect::<Result<Vec<_>, AnalysisError>>()?;
    let panel = |title: &str, y_label: &str, y: fn(&crate::model::Sample) -> f64| Panel {
        title: title.to_string(),
        x_label: "t (ms)".into(),
        y_label: y_label.to_string(),
        curves: series
            .iter()
            .map(|(label, samples)| Curve {
                label: label.clone(),
                points: samples.iter().map(|s| (s.t * 1e3, y(s))).collect(),
            })
            .collect(),
    };
    Ok(Figure {
        title: format!(
            "Fig. 3: θ1 = {} deg, ω1 = {} rad/s{} (F > 0: friction on the ball acts backward)",
            base.angle_deg,
            base.spin,
            conditions(base, &[])
        ),
        panels: vec![
            panel("friction force on the ball", "F (N)", |s| s.friction),
            panel("cart displacement", "X (mm)", |s| s.x * 1e3),
            panel("ball spin", "ω (rad/s)", |s| s.omega),
        ],
        columns: 1,
        size: (900, 1100),
    })
}
