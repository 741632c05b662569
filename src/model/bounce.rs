//! A solved bounce: the phases in order, the outcome, and queries of the exact solution (samples, the
//! time series, the ball's phases, the energy budget). Results only: the solving is [`super::solve()`]'s.

use serde::Serialize;

use super::contact::{Cart, ROLLING};
use super::energy::{Energy, energy_budget};
use super::params::Params;
use super::phase::{BallPhase, Phase, PhaseKind};
use super::setup::{Setup, State};

/// The ball as it leaves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Outcome {
    /// Rebound spin omega2, rad/s.
    pub omega2: f64,
    /// Rebound velocity along the surface, m/s.
    pub vx2: f64,
    /// Rebound velocity away from the surface, e_y v_y1, m/s.
    pub vy2: f64,
    /// Rebound angle from the surface, degrees (above 90 when the ball comes back).
    pub theta2_deg: f64,
    /// Tangential coefficient of restitution e_x = -(v_x2 - r omega2)/(v_x1 - r omega1); `None` when the
    /// ball arrives without slip.
    pub ex: Option<f64>,
    pub ey: f64,
    /// r omega2 / v_x2 (1 for rolling); `None` when v_x2 = 0.
    pub roll_ratio: Option<f64>,
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
    /// Cart displacement X (on a chain, its first mass's), m.
    pub x: f64,
    /// Cart velocity V (on a chain, its first mass's), m/s.
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
    /// True while string friction holds the cart still.
    pub cart_stuck: bool,
    /// A compliant ball's stretch e, m (0 for a rigid ball).
    pub stretch: f64,
    /// The slip of the ball's contact patch on the cart, m/s (for a rigid ball, the slip itself).
    pub patch_slip: f64,
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

/// The bounce of `params` solved into `phases`, leaving in state `last`.
pub(super) fn finish(params: &Params, setup: Setup, phases: Vec<Phase>, last: State) -> Bounce {
    Bounce {
        params: *params,
        outcome: outcome(params, &setup, &last),
        setup,
        phases,
        final_state: last,
    }
}

impl Outcome {
    /// Rebound speed, m/s (computed when asked: a sweep's CSV does not print it).
    pub fn speed2(&self) -> f64 {
        self.vx2.hypot(self.vy2)
    }
}

/// The ball as it leaves in state `last`.
fn outcome(params: &Params, setup: &Setup, last: &State) -> Outcome {
    let vy2 = setup.vy2();
    let r = setup.r;
    let incoming_slip = setup.vx1 - r * params.spin;
    let scale = setup.vx1.abs() + r * params.spin.abs();
    let ex = (incoming_slip.abs() > ROLLING * scale)
        .then(|| -(last.vx - r * last.omega) / incoming_slip);
    Outcome {
        omega2: last.omega,
        vx2: last.vx,
        vy2,
        theta2_deg: vy2.atan2(last.vx).to_degrees(),
        ex,
        ey: params.ey,
        roll_ratio: (last.vx != 0.0).then(|| r * last.omega / last.vx),
    }
}

impl Bounce {
    /// [`finish`] in place: the outcome of the parameters, constants, phases and final state already
    /// solved into the bounce.
    pub(super) fn refinish(&mut self) {
        self.outcome = outcome(&self.params, &self.setup, &self.final_state);
    }

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
        let slip = self.setup.slip(&s);
        let patch = phase.patch_at(&self.setup, t);
        Sample {
            t,
            normal: self.setup.normal(t),
            friction: phase.friction(&self.setup, &s),
            x: s.x,
            v: s.v,
            vx: s.vx,
            omega: s.omega,
            slip,
            phase: index,
            kind: phase.kind,
            cart_stuck: phase.cart == Cart::Stuck,
            stretch: patch.map_or(0.0, |(e, _)| e),
            patch_slip: patch.map_or(slip, |(_, p)| p),
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

    /// The ball's phases: consecutive phases that differ only in what the cart does (it sticks, starts
    /// or turns) are one phase of the ball.
    pub fn ball_phases(&self) -> Vec<BallPhase> {
        let mut merged: Vec<BallPhase> = Vec::with_capacity(self.phases.len());
        for p in &self.phases {
            match merged.last_mut() {
                Some(last) if last.kind == p.kind && last.slip_sign == p.slip_sign => {
                    last.end = p.end
                }
                _ => merged.push(BallPhase {
                    kind: p.kind,
                    slip_sign: p.slip_sign,
                    start: p.start,
                    end: p.end,
                }),
            }
        }
        merged
    }

    /// The ball's phase kinds joined, e.g. `slide-grip-slide`.
    pub fn phase_summary(&self) -> String {
        let mut summary = String::with_capacity(6 * self.phases.len());
        for (i, kind) in self.ball_phase_kinds().enumerate() {
            if i > 0 {
                summary.push('-');
            }
            summary.push_str(kind.name());
        }
        summary
    }

    /// The kinds of the ball's phases in order (those [`Bounce::phase_summary`] names), with no
    /// allocation: consecutive phases that differ only in what the cart does are one.
    pub fn ball_phase_kinds(&self) -> impl Iterator<Item = PhaseKind> + '_ {
        let mut previous = None;
        self.phases.iter().filter_map(move |p| {
            let ball = Some((p.kind, p.slip_sign));
            (ball != previous).then(|| {
                previous = ball;
                p.kind
            })
        })
    }

    /// The velocity along the surface of the frame the strings are tied to, as the ball leaves (0 on a
    /// clamped frame).
    pub fn frame_velocity(&self) -> f64 {
        self.phases
            .last()
            .map_or(0.0, |p| p.motion().frame_velocity(&self.setup, p.end))
    }

    /// True when string friction holds the cart still at some time in the contact.
    pub fn cart_ever_stuck(&self) -> bool {
        self.phases.iter().any(|p| p.cart == Cart::Stuck)
    }

    /// A compliant ball's stretch e (m) and its patch's slip on the cart (m/s) as it leaves; `None` for
    /// a rigid ball.
    pub fn final_patch(&self) -> Option<(f64, f64)> {
        let last = self.phases.last()?;
        last.patch_at(&self.setup, last.end)
    }

    /// True when the ball slides one way for the whole contact: every phase a slide with the slip sign
    /// of the first, so the friction never grips and never changes sign. This is the regime of Eq. (7)
    /// and Eq. (8): a late reversal (slide-slide) does not count, and neither does a grip. Phases that
    /// differ only in what the cart does (string friction: it sticks or comes unstuck under the sliding
    /// ball) keep the slip's sign and do count. For a compliant ball the slide is its contact patch's.
    pub fn slides_throughout(&self) -> bool {
        let one_way = |sign: i8| {
            self.phases
                .iter()
                .all(|p| p.kind == PhaseKind::Slide && p.slip_sign == sign)
        };
        self.phases
            .first()
            .is_some_and(|first| one_way(first.slip_sign))
    }
}
