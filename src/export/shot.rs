//! `snapback shot` as a table or JSON (the keys of issue 16: `contact`, `launch`, `net_clearance_m`,
//! `landing_m`, `flight_time_s`, `in`, `court_bounce`, `kick_height_m`, `trajectory`; issue 23's
//! `racquet`).

use std::fmt::Write;

use serde_json::{Value, json};

use crate::shot::Shot;
use crate::shot::court::NET_X;
use crate::shot::racquet::Recoil;

const RPM: f64 = 30.0 / std::f64::consts::PI;

/// What the racquet does to the shot: its effective masses at the impact point (kg; null when clamped),
/// the apparent restitution e_A and its recoil (m/s).
struct RacquetNumbers {
    masses: Option<(f64, f64)>,
    ey_apparent: f64,
    recoil: Recoil,
}

fn racquet(shot: &Shot) -> RacquetNumbers {
    let bounce = &shot.strings.bounce;
    RacquetNumbers {
        masses: shot.racquet.effective_masses(),
        ey_apparent: shot
            .racquet
            .ey_apparent(bounce.params.ey, bounce.params.mass),
        recoil: shot.racquet.recoil(bounce),
    }
}

/// The shot as a JSON value; `trajectory` only when the shot sampled one.
pub fn value(shot: &Shot) -> Value {
    let r = racquet(shot);
    let contact = &shot.strings.incidence;
    let launch = &shot.strings.leaving;
    let court = shot.court.as_ref().map(|c| {
        json!({
            "speed": c.leaving.speed(),
            "angle_deg": c.leaving.angle_deg(),
            "topspin_rpm": c.leaving.topspin() * RPM,
            "incidence_deg": c.incidence.theta1_deg,
        })
    });
    let mut doc = json!({
        "contact": {
            "angle_deg": contact.theta1_deg,
            "speed": contact.speed,
            "spin": contact.spin,
        },
        "launch": {
            "speed": launch.speed(),
            "angle_deg": launch.angle_deg(),
            "topspin_rpm": launch.topspin() * RPM,
            "vx": launch.velocity.x,
            "vy": launch.velocity.y,
        },
        "net_clearance_m": shot.net_clearance,
        "landing_m": shot.landing_x.map(|x| x - NET_X),
        "landing_x_m": shot.landing_x,
        "flight_time_s": shot.flight_time,
        "in": shot.is_in(),
        "court_bounce": court,
        "kick_height_m": shot.kick_height,
        "racquet": {
            "clamped": r.masses.is_none(),
            "effective_mass_normal": r.masses.map(|m| m.0),
            "effective_mass_tangential": r.masses.map(|m| m.1),
            "ey_apparent": r.ey_apparent,
            "recoil_speed": r.recoil.speed(),
            "recoil_normal": r.recoil.normal,
            "recoil_tangential": r.recoil.tangential,
        },
    });
    if !shot.trajectory.is_empty() {
        doc["trajectory"] = shot
            .trajectory
            .iter()
            .map(|[t, x, y, vx, vy]| json!({"t": t, "x": x, "y": y, "vx": vx, "vy": vy}))
            .collect();
    }
    doc
}

/// The shot as pretty JSON, newline-terminated.
pub fn json(shot: &Shot) -> String {
    let mut text = serde_json::to_string_pretty(&value(shot)).expect("a shot always serializes");
    text.push('\n');
    text
}

/// A length in m with 3 decimals, or what its absence means.
fn metres(value: Option<f64>, none: &str) -> String {
    value.map_or(none.to_string(), |v| format!("{v:.3} m"))
}

/// `text` without its minus sign where it shows zero (a spin of -1e-15 rad/s reads 0.0, not -0.0).
fn unsigned_zero(text: String) -> String {
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

/// The shot as aligned text.
pub fn table(shot: &Shot) -> String {
    let mut out = String::new();
    let c = &shot.strings.incidence;
    let l = &shot.strings.leaving;
    let _ = writeln!(out, "On the strings (the paper's frame)");
    let _ = writeln!(out, "  {:<24}{:.2} deg", "incidence θ1", c.theta1_deg);
    let _ = writeln!(out, "  {:<24}{:.2} m/s", "speed v1", c.speed);
    let _ = writeln!(
        out,
        "  {:<24}{} rad/s ({} rpm)",
        "spin ω1",
        unsigned_zero(format!("{:.1}", c.spin)),
        unsigned_zero(format!("{:.0}", c.spin * RPM))
    );
    let _ = writeln!(
        out,
        "  {:<24}{:.1} rad/s ({})",
        "rebound spin ω2",
        shot.strings.bounce.outcome.omega2,
        shot.strings.bounce.phase_summary()
    );
    let r = racquet(shot);
    let _ = writeln!(out, "\nRacquet");
    match r.masses {
        None => {
            let _ = writeln!(out, "  {:<24}clamped (immovable)", "held");
        }
        Some((normal, tangential)) => {
            let _ = writeln!(out, "  {:<24}in the hand, free to recoil", "held");
            let _ = writeln!(
                out,
                "  {:<24}{:.1} g normal, {:.1} g along the strings",
                "effective mass",
                normal * 1e3,
                tangential * 1e3
            );
        }
    }
    let _ = writeln!(
        out,
        "  {:<24}{:.3} (e_y {:.3} on clamped strings)",
        "apparent restitution", r.ey_apparent, shot.strings.bounce.params.ey
    );
    let _ = writeln!(
        out,
        "  {:<24}{:.2} m/s ({:.2} normal, {:.2} along)",
        "recoil at impact",
        r.recoil.speed(),
        r.recoil.normal,
        r.recoil.tangential
    );
    let _ = writeln!(out, "\nLaunch");
    let _ = writeln!(
        out,
        "  {:<24}{:.2} m/s ({:.1} km/h)",
        "speed",
        l.speed(),
        l.speed() * 3.6
    );
    let _ = writeln!(
        out,
        "  {:<24}{:.2} deg",
        "angle above horizontal",
        l.angle_deg()
    );
    let _ = writeln!(out, "  {:<24}{:.0} rpm", "topspin", l.topspin() * RPM);
    let _ = writeln!(out, "\nFlight");
    let _ = writeln!(
        out,
        "  {:<24}{}",
        "net clearance",
        metres(shot.net_clearance, "comes down before the net")
    );
    let _ = writeln!(
        out,
        "  {:<24}{}",
        "landing beyond the net",
        metres(shot.landing_x.map(|x| x - NET_X), "none")
    );
    let _ = writeln!(out, "  {:<24}{:.3} s", "flight time", shot.flight_time);
    let _ = writeln!(
        out,
        "  {:<24}{}",
        "in",
        if shot.is_in() { "yes" } else { "no" }
    );
    if let Some(court) = &shot.court {
        let b = &court.leaving;
        let _ = writeln!(out, "\nCourt bounce");
        let _ = writeln!(
            out,
            "  {:<24}{:.2} deg",
            "incidence", court.incidence.theta1_deg
        );
        let _ = writeln!(
            out,
            "  {:<24}{:.2} m/s at {:.2} deg, {:.0} rpm topspin",
            "leaves at",
            b.speed(),
            b.angle_deg(),
            b.topspin() * RPM
        );
    }
    let _ = writeln!(
        out,
        "  {:<24}{}",
        "kick height",
        metres(
            shot.kick_height,
            "none (does not cross the baseline after bouncing)"
        )
    );
    out
}

/// `sweep --shot` as CSV: the varied value's `column`, then the shot's numbers (an empty field for a
/// null, as the effective masses of a clamped racquet; `in` as true or false).
pub fn csv(column: &str, rows: &[(f64, Shot)]) -> String {
    let mut out = format!(
        "{column},contact_angle_deg,contact_speed,contact_spin,launch_speed,launch_angle_deg,\
         launch_topspin_rpm,net_clearance_m,landing_m,flight_time_s,in,kick_height_m,ey_apparent,\
         effective_mass_normal,effective_mass_tangential,recoil_speed\n"
    );
    // `+ 0.0` writes -0 as 0.
    let field = |v: Option<f64>| v.map_or(String::new(), |v| (v + 0.0).to_string());
    for (value, s) in rows {
        let c = &s.strings.incidence;
        let l = &s.strings.leaving;
        let r = racquet(s);
        let _ = writeln!(
            out,
            "{value},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            c.theta1_deg,
            c.speed,
            c.spin + 0.0,
            l.speed(),
            l.angle_deg() + 0.0,
            l.topspin() * RPM + 0.0,
            field(s.net_clearance),
            field(s.landing_x.map(|x| x - NET_X)),
            s.flight_time,
            s.is_in(),
            field(s.kick_height),
            r.ey_apparent,
            field(r.masses.map(|m| m.0)),
            field(r.masses.map(|m| m.1)),
            r.recoil.speed(),
        );
    }
    out
}
