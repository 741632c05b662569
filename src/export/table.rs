//! The readable summary of `snapback simulate`.

use std::fmt::Write;

use crate::analysis::timeline;
use crate::model::params::BOUNCE_PARAMS as PARAMS;
use crate::model::units::{Dimension, show};
use crate::model::{Bounce, Cart, FrameKind, PhaseKind};

/// Parameters, outcome, phases in ms and the energy budget, as aligned text.
pub fn summary(b: &Bounce) -> String {
    let mut out = String::new();
    let o = &b.outcome;
    let e = &b.energy();
    let _ = writeln!(out, "Parameters");
    for spec in PARAMS {
        let name = format!("{} {}", spec.label, spec.symbol);
        let _ = writeln!(out, "  {name:<24}{}", spec.show(b.params.get(spec.id)));
    }
    let _ = writeln!(out, "\nOutcome");
    let rpm = o.omega2 * 30.0 / std::f64::consts::PI;
    let _ = writeln!(
        out,
        "  {:<24}{:.1} rad/s ({rpm:.0} rpm)",
        "rebound spin ω2", o.omega2
    );
    let _ = writeln!(out, "  {:<24}{:.3} m/s", "v_x2", o.vx2);
    let _ = writeln!(out, "  {:<24}{:.3} m/s", "v_y2", o.vy2);
    let _ = writeln!(out, "  {:<24}{:.3} m/s", "rebound speed v2", o.speed2());
    let _ = writeln!(out, "  {:<24}{:.2} deg", "rebound angle θ2", o.theta2_deg);
    let ex =
        o.ex.map_or("undefined (no incoming slip)".to_string(), |ex| {
            format!("{ex:.4}")
        });
    let _ = writeln!(out, "  {:<24}{ex}", "e_x");
    let _ = writeln!(out, "  {:<24}{:.2}", "e_y", o.ey);
    if b.setup.frame_normal_mass.is_some() {
        let _ = writeln!(out, "  {:<24}{:.4}", "apparent e_A", b.setup.ey_apparent);
    }
    if let Some(ratio) = o.roll_ratio {
        let _ = writeln!(out, "  {:<24}{ratio:.4}", "r ω2 / v_x2");
    }
    // The model names what the ball touches (a chain's first mass) and where the energy left behind is.
    let model = b.params.model();
    let words = model.words();
    let cart = words.touched;
    let _ = writeln!(out, "\nPhases ({})", b.phase_summary());
    // A compliant ball grips through its contact patch, and its force then follows its spring.
    let compliant = model.compliant();
    let decimals = phase_decimals(b.phases.iter().flat_map(|p| [p.start * 1e3, p.end * 1e3]));
    let width = decimals + 3;
    for p in &b.phases {
        let stuck;
        let slip = match (p.kind, p.slip_sign, p.cart) {
            (PhaseKind::Grip, _, Cart::Stuck) if compliant => {
                stuck = format!("patch grips the stuck {cart}, F = k_b e + c_b e'");
                &stuck
            }
            (PhaseKind::Grip, _, Cart::Stuck) => {
                stuck = format!("rolling on the stuck {cart}");
                &stuck
            }
            (PhaseKind::Grip, _, _) if compliant => {
                stuck = format!("patch moves with the {cart}, F = k_b e + c_b e'");
                &stuck
            }
            (PhaseKind::Grip, _, _) => {
                stuck = format!("contact point moves with the {cart}");
                &stuck
            }
            (_, s, Cart::Stuck) => {
                let way = if s > 0 {
                    "forward, F = +μN"
                } else {
                    "backward, F = -μN"
                };
                stuck = format!("slipping {way}; {cart} stuck");
                &stuck
            }
            (_, s, _) if s > 0 => "slipping forward, F = +μN",
            _ => "slipping backward, F = -μN",
        };
        let _ = writeln!(
            out,
            "  {:<6}{:>width$.decimals$} - {:>w$.decimals$} ms  {slip}",
            p.kind.name(),
            p.start * 1e3,
            p.end * 1e3,
            w = width - 1
        );
    }
    let _ = writeln!(
        out,
        "  {cart} at release: X = {}, V = {:.3} m/s",
        show(b.final_state.x, Dimension::Length, "mm", 3),
        b.final_state.v
    );
    if model.frame == FrameKind::Free {
        let _ = writeln!(
            out,
            "  frame at release: V = {:.3} m/s (X above is the strings' stretch from it)",
            b.frame_velocity()
        );
    }
    let travel = timeline::travel(b);
    let _ = writeln!(
        out,
        "  {cart} peak: |X| = {} at {:.3} ms, |V| = {:.3} m/s at {:.3} ms",
        show(travel.peak_x, Dimension::Length, "mm", 3),
        travel.peak_x_at * 1e3,
        travel.peak_v,
        travel.peak_v_at * 1e3
    );
    let _ = writeln!(out, "\nEnergy");
    let share = |j: f64| 100.0 * j / e.initial;
    let mut rows = vec![
        ("incoming ball", e.initial),
        ("outgoing ball", e.final_ball),
        (words.surface_springs, e.final_cart),
        ("lost to friction", e.friction_loss),
        ("lost normally (e_y)", e.normal_loss),
        ("lost at the cart (F_c)", e.cart_friction_loss),
    ];
    // A compliant ball leaves energy in its spring and loses some in its dashpot.
    if compliant {
        rows.push(("ball's spring (k_b)", e.ball_spring));
        rows.push(("lost in dashpot (c_b)", e.dashpot_loss));
    }
    // A frame that is not clamped leaves moving, normal to the surface and along it.
    if b.setup.frame_normal_mass.is_some() {
        rows.push(("frame (kinetic)", e.frame));
    }
    for (name, joules) in rows {
        let _ = writeln!(
            out,
            "  {name:<24}{:>10.2} mJ {:>6.2} %",
            joules * 1e3,
            share(joules)
        );
    }
    let _ = writeln!(out, "  {:<24}{:>10.1e} (relative)", "residual", e.residual);
    out
}

/// The decimals (4 to 9) at which every two different phase boundaries, in ms, read differently: a grip
/// that breaks 20 ns before the end of contact shows as 4.99998 - 5.00000, not 5.0000 - 5.0000.
fn phase_decimals(boundaries: impl Iterator<Item = f64> + Clone) -> usize {
    let distinct = |d: usize| {
        let mut shown = boundaries.clone().map(|t| (t, format!("{t:.d$}")));
        let mut previous: Option<(f64, String)> = None;
        shown.all(|(t, text)| {
            let clash = previous
                .as_ref()
                .is_some_and(|(u, seen)| *u != t && *seen == text);
            previous = Some((t, text));
            !clash
        })
    };
    (4..=9).find(|&d| distinct(d)).unwrap_or(9)
}
