//! One whole bounce: the phases in order, the outcome, the energy budget and the time series.

use serde::Serialize;

use super::events::first_rise;
use super::grip::Grip;
use super::params::{ParamError, Params};
use super::quadrature::integrate;
use super::setup::{Setup, State};
use super::slide::Slide;

/// Whether the ball slides on the cart or grips it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PhaseKind {
    Slide,
    Grip,
}

impl PhaseKind {
    pub fn name(self) -> &'static str {
        match self {
            PhaseKind::Slide => "slide",
            PhaseKind::Grip => "grip",
        }
    }
}

#[derive(Clone, Copy, Debug)]
enum Motion {
    Slide(Slide),
    Grip(Grip),
}

/// One phase of the bounce.
#[derive(Clone, Copy, Debug)]
pub struct Phase {
    pub kind: PhaseKind,
    /// The sign of the slip (and of the friction F) while sliding, +1 or -1; 0 while gripping.
    pub slip_sign: i8,
    /// Start time, s.
    pub start: f64,
    /// End time, s.
    pub end: f64,
    motion: Motion,
}

impl Phase {
    /// The exact state at `t` (meaningful for `t` in `[start, end]`).
    pub fn state_at(&self, setup: &Setup, t: f64) -> State {
        match &self.motion {
            Motion::Slide(slide) => slide.at(setup, t),
            Motion::Grip(grip) => grip.at(setup, t),
        }
    }

    /// The friction force on the ball, positive backward, in this phase at `state`.
    pub fn friction(&self, setup: &Setup, state: &State) -> f64 {
        match &self.motion {
            Motion::Slide(slide) => slide.friction(setup, state.t),
            Motion::Grip(_) => Grip::friction(setup, state.x),
        }
    }

    /// The state at the start of the phase.
    pub fn initial(&self) -> State {
        match &self.motion {
            Motion::Slide(slide) => slide.start,
            Motion::Grip(grip) => grip.start,
        }
    }

    pub fn duration(&self) -> f64 {
        self.end - self.start
    }
}

/// The ball as it leaves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Outcome {
    /// Rebound spin omega2, rad/s.
    pub omega2: f64,
    /// Rebound velocity along the surface, m/s.
    pub vx2: f64,
    /// Rebound velocity away from the surface, e_y v_y1, m/s.
    pub vy2: f64,
    /// Rebound speed, m/s.
    pub speed2: f64,
    /// Rebound angle from the surface, degrees (above 90 when the ball comes back).
    pub theta2_deg: f64,
    /// Tangential coefficient of restitution e_x = -(v_x2 - r omega2)/(v_x1 - r omega1); `None` when the
    /// ball arrives without slip.
    pub ex: Option<f64>,
    pub ey: f64,
    /// r omega2 / v_x2 (1 for rolling); `None` when v_x2 = 0.
    pub roll_ratio: Option<f64>,
}

/// Where the incoming energy went, J.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Energy {
    /// Ball kinetic energy (translation and rotation) before the bounce.
    pub initial: f64,
    /// Ball kinetic energy after.
    pub final_ball: f64,
    /// Cart kinetic plus spring energy after.
    pub final_cart: f64,
    /// ∫ F · slip dt, integrated over the sliding phases of the exact solution.
    pub friction_loss: f64,
    /// Lost in the normal direction, m v_y1^2 (1 - e_y^2)/2.
    pub normal_loss: f64,
    /// (initial - final_ball - final_cart - friction_loss - normal_loss) / initial.
    pub residual: f64,
}

/// One point of the time series.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Normal force N, N.
    pub normal: f64,
    /// Friction force on the ball F, N (positive backward, as in the paper's Fig. 3).
    pub friction: f64,
    /// Cart displacement X, m.
    pub x: f64,
    /// Cart velocity V, m/s.
    pub v: f64,
    /// Ball velocity along the surface v_x, m/s.
    pub vx: f64,
    /// Ball spin omega, rad/s.
    pub omega: f64,
    /// Slip speed v_x - r omega - V, m/s.
    pub slip: f64,
    /// Index of the phase in [`Bounce::phases`].
    pub phase: usize,
    pub kind: PhaseKind,
}

/// A solved bounce.
#[derive(Clone, Debug)]
pub struct Bounce {
    pub params: Params,
    pub setup: Setup,
    pub phases: Vec<Phase>,
    /// The state at t = T, when the ball leaves.
    pub final_state: State,
    pub outcome: Outcome,
}

/// Why a bounce could not be solved.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolveError {
    #[error(transparent)]
    Params(#[from] ParamError),
    #[error(
        "the cart oscillates too fast to resolve: sqrt(k/M) T = {radians:.3e} rad exceeds {MAX_RADIANS:e} \
         (lower the stiffness, raise the cart mass or shorten the impact)"
    )]
    TooFast { radians: f64 },
    #[error("the bounce switched between sliding and gripping more than {MAX_TRANSITIONS} times")]
    TooManyPhases,
}

/// The largest number of cart radians per contact the solver accepts (about 16 000 oscillations).
pub const MAX_RADIANS: f64 = 1e5;
/// The largest number of slide/grip transitions in one bounce.
pub const MAX_TRANSITIONS: usize = 10_000;
/// An arriving slip below this fraction of |v_x1| + r |omega1| counts as rolling.
const ROLLING: f64 = 1e-12;
/// Event functions are differences of terms this many times their size apart from rounding; a rise
/// smaller than that is noise (it matters near t = T, where N and with it F and F_s vanish).
const ROUNDING: f64 = 1e-12;

/// Solves one bounce exactly (Cross 2010, Sec. II): phase by phase in closed form, each transition
/// located by root finding on the exact expressions.
pub fn solve(params: &Params) -> Result<Bounce, SolveError> {
    params.validate()?;
    let setup = Setup::new(params);
    let radians = setup.omega_slide.max(setup.omega_grip) * setup.duration;
    if radians > MAX_RADIANS {
        return Err(SolveError::TooFast { radians });
    }
    let end = setup.duration;
    let start = setup.initial(params.spin);
    let slip0 = setup.slip(&start);
    let incoming = setup.vx1.abs() + setup.r * params.spin.abs();
    // A ball that arrives rolling grips at once (N(0) = 0 and F_s = 0, so the grip holds on the boundary).
    let (mut motion, mut from_boundary) = if slip0.abs() <= ROLLING * incoming {
        (Motion::Grip(Grip { start }), true)
    } else {
        (
            Motion::Slide(Slide::new(&setup, start, slip0.signum())),
            false,
        )
    };
    let mut phases = Vec::with_capacity(4);
    for _ in 0..MAX_TRANSITIONS {
        let phase_start = match &motion {
            Motion::Slide(s) => s.start,
            Motion::Grip(g) => g.start,
        };
        let t0 = phase_start.t;
        let event = match &motion {
            Motion::Slide(slide) => {
                // A slide that starts where the slip is zero starts with a slip of zero plus rounding;
                // measured from that start value, rounding can never fake a crossing at the start.
                let offset = if from_boundary {
                    setup.slip(&slide.start)
                } else {
                    0.0
                };
                let f = |t: f64| {
                    let (s, friction) = slide.evaluate(&setup, t);
                    let slip = setup.slip(&s) - offset;
                    [(
                        -slide.dir * slip,
                        -slide.dir * Slide::slip_rate(&setup, &s, friction),
                    )]
                };
                let s0 = &slide.start;
                let noise =
                    ROUNDING * (incoming + s0.vx.abs() + setup.r * s0.omega.abs() + s0.v.abs());
                let step = setup.event_step(setup.omega_slide);
                let curvature = slide.slip_curvature(&setup);
                first_rise(f, t0, end, step, curvature, noise, from_boundary)
            }
            Motion::Grip(grip) => {
                let f = |t: f64| Grip::margins(&setup, &grip.at(&setup, t));
                let noise =
                    ROUNDING * (setup.mu * setup.n0 + (setup.grip_gain * grip.start.x).abs());
                let step = setup.event_step(setup.omega_grip);
                let curvature = grip.margin_curvature(&setup);
                first_rise(f, t0, end, step, curvature, noise, from_boundary)
            }
        }
        // A transition within rounding of the end changes nothing.
        .filter(|&t| t < end * (1.0 - 1e-13));
        let t1 = event.unwrap_or(end);
        let (kind, slip_sign) = match &motion {
            Motion::Slide(s) => (PhaseKind::Slide, s.dir as i8),
            Motion::Grip(_) => (PhaseKind::Grip, 0),
        };
        let phase = Phase {
            kind,
            slip_sign,
            start: t0,
            end: t1,
            motion,
        };
        let state = phase.state_at(&setup, t1);
        if t1 > t0 {
            phases.push(phase);
        }
        if event.is_none() {
            return Ok(finish(params, setup, phases, state));
        }
        (motion, from_boundary) = match kind {
            // The slip reached zero: grip if static friction (Eq. 5) can hold it, else the friction reverses.
            PhaseKind::Slide => {
                let static_friction = Grip::friction(&setup, state.x);
                if static_friction.abs() <= setup.mu * setup.normal(t1) {
                    (Motion::Grip(Grip { start: state }), false)
                } else {
                    (
                        Motion::Slide(Slide::new(&setup, state, static_friction.signum())),
                        true,
                    )
                }
            }
            // |F_s| reached mu N: slide again, friction continuing in the direction of F_s.
            PhaseKind::Grip => {
                let dir = if state.x < 0.0 { -1.0 } else { 1.0 };
                (Motion::Slide(Slide::new(&setup, state, dir)), true)
            }
        };
    }
    Err(SolveError::TooManyPhases)
}

fn finish(params: &Params, setup: Setup, phases: Vec<Phase>, last: State) -> Bounce {
    let vy2 = params.ey * setup.vy1;
    let r = setup.r;
    let incoming_slip = setup.vx1 - r * params.spin;
    let scale = setup.vx1.abs() + r * params.spin.abs();
    let ex = (incoming_slip.abs() > ROLLING * scale)
        .then(|| -(last.vx - r * last.omega) / incoming_slip);
    let outcome = Outcome {
        omega2: last.omega,
        vx2: last.vx,
        vy2,
        speed2: last.vx.hypot(vy2),
        theta2_deg: vy2.atan2(last.vx).to_degrees(),
        ex,
        ey: params.ey,
        roll_ratio: (last.vx != 0.0).then(|| r * last.omega / last.vx),
    };
    Bounce {
        params: *params,
        setup,
        phases,
        final_state: last,
        outcome,
    }
}

/// The energy budget of a solved bounce (see [`Bounce::energy`]).
fn energy_budget(params: &Params, setup: &Setup, phases: &[Phase], last: &State) -> Energy {
    let first = setup.initial(params.spin);
    let vy2 = params.ey * setup.vy1;
    let initial = setup.ball_tangential_energy(&first) + 0.5 * setup.m * setup.vy1 * setup.vy1;
    let final_ball = setup.ball_tangential_energy(last) + 0.5 * setup.m * vy2 * vy2;
    let final_cart = setup.cart_energy(last);
    let normal_loss = 0.5 * setup.m * (setup.vy1 * setup.vy1 - vy2 * vy2);
    let panel = 2.0 / setup.omega_slide.max(setup.w);
    let friction_loss = phases
        .iter()
        .filter(|p| p.kind == PhaseKind::Slide)
        .map(|p| {
            let power = |t: f64| {
                let s = p.state_at(setup, t);
                p.friction(setup, &s) * setup.slip(&s)
            };
            integrate(power, p.start, p.end, panel)
        })
        .sum();
    Energy {
        initial,
        final_ball,
        final_cart,
        friction_loss,
        normal_loss,
        residual: (initial - final_ball - final_cart - friction_loss - normal_loss) / initial,
    }
}

impl Bounce {
    /// Where the incoming energy went. The friction loss is integrated from the exact solution (Gauss-
    /// Legendre, to about 1e-14), independently of the end states, so the residual checks the solution.
    /// Computed on request: a sweep of outcomes does not pay for it.
    pub fn energy(&self) -> Energy {
        energy_budget(&self.params, &self.setup, &self.phases, &self.final_state)
    }

    /// The phase in force at `t`; at a transition, the one that begins there.
    pub fn phase_index_at(&self, t: f64) -> usize {
        self.phases.iter().rposition(|p| p.start <= t).unwrap_or(0)
    }

    /// The sample at `t` in phase `index`.
    pub fn sample_in(&self, index: usize, t: f64) -> Sample {
        let phase = &self.phases[index];
        let s = phase.state_at(&self.setup, t);
        Sample {
            t,
            normal: self.setup.normal(t),
            friction: phase.friction(&self.setup, &s),
            x: s.x,
            v: s.v,
            vx: s.vx,
            omega: s.omega,
            slip: self.setup.slip(&s),
            phase: index,
            kind: phase.kind,
        }
    }

    /// The sample at `t` (clamped to the contact); at a transition, the side of the phase that begins there.
    pub fn sample_at(&self, t: f64) -> Sample {
        let t = t.clamp(0.0, self.setup.duration);
        self.sample_in(self.phase_index_at(t), t)
    }

    /// `n` (at least 2) evenly spaced samples over [0, T], plus both sides of every transition, in time
    /// order, so that a force that jumps at a transition draws as a vertical step.
    pub fn series(&self, n: usize) -> Vec<Sample> {
        let n = n.max(2);
        let duration = self.setup.duration;
        let grid = |i: usize| {
            if i + 1 == n {
                duration
            } else {
                duration * i as f64 / (n - 1) as f64
            }
        };
        let last = self.phases.len() - 1;
        let mut out = Vec::with_capacity(n + 2 * last);
        let mut i = 0;
        for (index, phase) in self.phases.iter().enumerate() {
            if index > 0 {
                out.push(self.sample_in(index, phase.start));
            }
            while i < n && (grid(i) < phase.end || index == last) {
                let t = grid(i);
                if t > phase.start || index == 0 {
                    out.push(self.sample_in(index, t));
                }
                i += 1;
            }
            if index < last {
                out.push(self.sample_in(index, phase.end));
            }
        }
        out
    }

    /// The phase kinds joined, e.g. `slide-grip-slide`.
    pub fn phase_summary(&self) -> String {
        self.phases
            .iter()
            .map(|p| p.kind.name())
            .collect::<Vec<_>>()
            .join("-")
    }

    /// True when the ball slides for the whole contact.
    pub fn slides_throughout(&self) -> bool {
        self.phases.iter().all(|p| p.kind == PhaseKind::Slide)
    }
}
