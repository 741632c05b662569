//! JSON for one bounce. The keys `params`, `omega2`, `vx2`, `vy2`, `theta2_deg`, `ex`, `phases` and
//! `energy` are a contract other programs rely on.

use serde::Serialize;

use crate::analysis::timeline::{Travel, travel};
use crate::model::{Bounce, Energy, Params};

#[derive(Serialize)]
struct PhaseJson {
    kind: &'static str,
    /// s
    start: f64,
    /// s
    end: f64,
    /// +1 or -1 while sliding (the sign of the slip and of F), 0 while gripping.
    slip: i8,
    /// "moving", or "stuck" while string friction holds the cart.
    cart: &'static str,
}

#[derive(Serialize)]
struct CartJson {
    /// m, at release
    x: f64,
    /// m/s, at release
    v: f64,
    /// The largest |X| (m) and |V| (m/s) over the contact, and when (s).
    #[serde(flatten)]
    travel: Travel,
}

#[derive(Serialize)]
struct FrameJson {
    /// The frame's velocity along the surface at release, m/s (0 on a clamped frame).
    v: f64,
}

#[derive(Serialize)]
struct BounceJson<'a> {
    params: &'a Params,
    omega2: f64,
    omega2_rpm: f64,
    vx2: f64,
    vy2: f64,
    speed2: f64,
    theta2_deg: f64,
    ex: Option<f64>,
    ey: f64,
    /// The apparent restitution e_A on the frame (e_y on a clamped frame).
    ey_apparent: f64,
    roll_ratio: Option<f64>,
    slides_throughout: bool,
    phase_summary: String,
    phases: Vec<PhaseJson>,
    cart: CartJson,
    frame: FrameJson,
    energy: Energy,
}

fn document(b: &Bounce) -> BounceJson<'_> {
    let o = &b.outcome;
    BounceJson {
        params: &b.params,
        omega2: o.omega2,
        omega2_rpm: o.omega2 * 30.0 / std::f64::consts::PI,
        vx2: o.vx2,
        vy2: o.vy2,
        speed2: o.speed2(),
        theta2_deg: o.theta2_deg,
        ex: o.ex,
        ey: o.ey,
        ey_apparent: b.setup.ey_apparent,
        roll_ratio: o.roll_ratio,
        slides_throughout: b.slides_throughout(),
        phase_summary: b.phase_summary(),
        phases: b
            .phases
            .iter()
            .map(|p| PhaseJson {
                kind: p.kind.name(),
                start: p.start,
                end: p.end,
                slip: p.slip_sign,
                cart: p.cart.name(),
            })
            .collect(),
        cart: CartJson {
            x: b.final_state.x,
            v: b.final_state.v,
            travel: travel(b),
        },
        frame: FrameJson {
            v: b.frame_velocity(),
        },
        energy: b.energy(),
    }
}

/// The JSON value of a bounce.
pub fn value(b: &Bounce) -> serde_json::Value {
    serde_json::to_value(document(b)).expect("a bounce always serializes")
}

/// A bounce as pretty JSON, newline-terminated.
pub fn bounce(b: &Bounce) -> String {
    let mut text = serde_json::to_string_pretty(&document(b)).expect("a bounce always serializes");
    text.push('\n');
    text
}
