//! The data of the paper's figures, ready to draw: Fig. 2 (omega2 against theta1 for the three carts,
//! (a) omega1 = 0 and (b) omega1 = -100 rad/s) and Fig. 3 (F, X and omega against t at 60 deg for the
//! three carts with omega1 = -100 rad/s).

use crate::model::Params;
use crate::model::params::{ParamId, spec};

use super::cases::{CARTS, FIG3_ANGLE, SPINS};
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
        match self {
            Which::Fig2 => fig2(base),
            Which::Fig3 => fig3(base),
        }
    }
}

/// Angles of Fig. 2: 0.1 deg to 90 deg every 0.1 deg.
const FIG2_STEPS: usize = 900;

/// Samples of each Fig. 3 time series (both sides of every transition are added).
const FIG3_SAMPLES: usize = 1001;

/// Fig. 2: omega2 against theta1 for the three carts; panel (a) omega1 = 0, (b) omega1 = -100 rad/s.
pub fn fig2(base: &Params) -> Result<Figure, AnalysisError> {
    let angles = Span::new(spec(ParamId::Angle), 0.1, 90.0, false)?;
    let panels = SPINS
        .iter()
        .zip(["(a)", "(b)"])
        .map(|(&spin, tag)| {
            let curves = CARTS
                .iter()
                .map(|cart| {
                    // The angle is the swept parameter; any valid start will do.
                    let p = cart.case(base, FIG3_ANGLE, spin);
                    let rows = sweep::sweep(&p, &angles, FIG2_STEPS)?;
                    Ok(Curve {
                        label: cart.label.to_string(),
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
            "Fig. 2: rebound spin ω2 against angle of incidence θ1 (v1 = {} m/s, μ = {})",
            base.speed, base.mu
        ),
        panels,
        columns: 2,
        size: (1200, 560),
    })
}

/// Fig. 3: the friction force F, the cart displacement X and the ball's spin omega against time, at
/// 60 deg with omega1 = -100 rad/s, for the three carts.
pub fn fig3(base: &Params) -> Result<Figure, AnalysisError> {
    let spin = SPINS[1];
    let series = CARTS
        .iter()
        .map(|cart| {
            let b = cart.solve(base, FIG3_ANGLE, spin)?;
            Ok((cart.label, b.series(FIG3_SAMPLES)))
        })
        .collect::<Result<Vec<_>, AnalysisError>>()?;
    let panel = |title: &str, y_label: &str, y: fn(&crate::model::Sample) -> f64| Panel {
        title: title.to_string(),
        x_label: "t (ms)".into(),
        y_label: y_label.to_string(),
        curves: series
            .iter()
            .map(|(label, samples)| Curve {
                label: label.to_string(),
                points: samples.iter().map(|s| (s.t * 1e3, y(s))).collect(),
            })
            .collect(),
    };
    Ok(Figure {
        title: format!(
            "Fig. 3: θ1 = {FIG3_ANGLE} deg, ω1 = {spin} rad/s (F > 0: friction on the ball acts backward)"
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
