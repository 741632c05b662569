//! The compliant ball on a free frame (issue 23, `--ball-stiffness` with `--frame-mass`), on the single
//! cart and on a chain: against the independent integration of support/chain_compliant_integrator.rs with
//! the frame as a free last mass, the heavy frame against the wall, momentum along the surface, the
//! energy budget, and property tests over random frames.

use proptest::prelude::*;

use crate::support::chain_compliant_integrator::{Reference, integrate, step_for};
use crate::support::compliant::{incoming, random_compliant, solved_or_refused};
use crate::support::energy::assert_nothing_created;
use crate::support::prop::{config, within_the_cone};
use crate::support::rng::Rng;
use snapback::model::{Bounce, Params, PhaseKind, solve};

/// A random compliant ball on `chain` masses with springs, tied to a frame of 20 g to 20 kg.
fn random_framed(rng: &mut Rng, chain: usize) -> Params {
    let mut p = random_compliant(rng, chain);
    p.stiffness = rng.log_uniform(1e3, 1e5);
    p.ball_damping = rng.uniform(0.05, 1.5);
    p.frame_mass = rng.log_uniform(0.02, 20.0);
    if rng.unit() < 0.5 {
        p.frame_normal_mass = rng.log_uniform(0.05, 20.0);
    }
    p
}

/// How far the solver is from the reference, each relative to its scale (the string friction's loss is
/// zero on both sides without it). Shared with the framed chain's string-friction test.
pub(super) fn disagreements(p: &Params, b: &Bounce, r: &Reference) -> [(&'static str, f64); 8] {
    let speed = incoming(p);
    let e = b.energy();
    let links = p.chain as usize;
    // The reference's first mass relative to its frame (the last entry).
    let x1 = r.x[0] - r.x[links];
    [
        ("vx2", (b.outcome.vx2 - r.vx2).abs() / speed),
        (
            "omega2",
            p.radius * (b.outcome.omega2 - r.omega2).abs() / speed,
        ),
        (
            "X1 - Xf",
            (b.final_state.x - x1).abs() / (speed * p.duration),
        ),
        ("V1", (b.final_state.v - r.v[0]).abs() / speed),
        ("Vf", (b.frame_velocity() - r.frame_v).abs() / speed),
        (
            "chain energy",
            (e.final_cart - r.energy.chain).abs() / e.initial,
        ),
        (
            "dashpot loss",
            (e.dashpot_loss - r.energy.dashpot_loss).abs() / e.initial,
        ),
        (
            "string loss",
            (e.cart_friction_loss - r.energy.string_loss).abs() / e.initial,
        ),
    ]
}

#[test]
fn the_compliant_ball_on_a_frame_agrees_with_an_independent_integration() {
    let mut rng = Rng(0xf4a3_c0a1_ba11_0001);
    let mut multi = 0;
    let mut worst: f64 = 0.0;
    for case in 0..40 {
        // The single cart on a frame first, then chains.
        let links = if case % 2 == 0 { 1 } else { 2 + rng.below(6) };
        let p = random_framed(&mut rng, links);
        let b = solve(&p).unwrap_or_else(|e| panic!("case {case}: {e}\n{p:?}"));
        let r = integrate(&p, step_for(&p, 0.0005));
        let what = format!("case {case}: {p:?} ({})\n{r:?}", b.phase_summary());
        assert_eq!(b.phases.len(), r.phases, "{what}");
        for (name, d) in disagreements(&p, &b, &r) {
            assert!(d < 1e-9, "{name} off by {d:.2e}: {what}");
            worst = worst.max(d);
        }
        multi += usize::from(r.phases > 2);
    }
    eprintln!("worst disagreement {worst:.2e}; {multi} of 40 cases with 3 phases or more");
    assert!(multi >= 10, "only {multi} cases with 3 phases or more");
}

#[test]
fn a_heavy_frame_under_a_compliant_ball_approaches_the_wall() {
    let mut rng = Rng(0xf4a3_c0a1_ba11_0002);
    for case in 0..40 {
        let links = if case % 2 == 0 { 1 } else { 2 + rng.below(6) };
        let mut p = random_framed(&mut rng, links);
        p.frame_normal_mass = 0.0;
        p.frame_mass = 0.0;
        let wall = solve(&p).expect("a clamped compliant ball solves");
        p.frame_mass = 1e6;
        let heavy = solve(&p).expect("a heavy frame solves");
        let what = format!("case {case}: {p:?} ({})", wall.phase_summary());
        let speed = incoming(&p);
        let tol = 1e-5;
        let (a, b) = (&wall.outcome, &heavy.outcome);
        assert!((a.vx2 - b.vx2).abs() <= tol * speed, "{what}");
        assert!(
            p.radius * (a.omega2 - b.omega2).abs() <= tol * speed,
            "{what}"
        );
        assert!(heavy.frame_velocity().abs() <= 1e-5 * p.speed, "{what}");
    }
}

#[test]
fn momentum_along_the_surface_of_ball_cart_and_frame_is_conserved() {
    // On the single cart the bounce reports every mass: m v_x + M V + M_t V_f is m v_x1 at the end.
    let mut rng = Rng(0xf4a3_c0a1_ba11_0003);
    for case in 0..100 {
        let p = random_framed(&mut rng, 1);
        let b = solve(&p).expect("a framed compliant ball solves");
        let vx1 = p.speed * (90.0 - p.angle_deg).to_radians().sin();
        let before = p.mass * vx1;
        let after = p.mass * b.outcome.vx2
            + p.cart_mass * b.final_state.v
            + p.frame_mass * b.frame_velocity();
        let scale = p.mass * incoming(&p);
        assert!(
            (after - before).abs() <= 1e-12 * scale,
            "case {case}: {before} -> {after} ({p:?})"
        );
    }
}

#[test]
fn the_frame_under_a_compliant_ball_creates_no_energy() {
    let mut rng = Rng(0xf4a3_c0a1_ba11_0004);
    for case in 0..200 {
        let links = 1 + rng.below(8);
        let p = random_framed(&mut rng, links);
        let b = solve(&p).expect("a framed compliant ball solves");
        let e = b.energy();
        assert_nothing_created(&e, &format!("case {case}: {p:?}"));
        assert!(e.dashpot_loss >= 0.0, "case {case}: {e:?}");
    }
}

proptest! {
    #![proptest_config(config(200))]

    #[test]
    fn random_frames_under_a_compliant_ball_solve_finite_within_the_friction_cone(
        seed in any::<u64>(),
    ) {
        let mut rng = Rng(seed | 1);
        let links = 1 + rng.below(15);
        let mut p = random_framed(&mut rng, links);
        p.frame_mass = rng.log_uniform(1e-3, 1e3);
        p.ball_stiffness = rng.log_uniform(1e4, 1e7);
        // A ball or chain too fast to resolve, or a chattering lightly damped ball, is refused.
        let Some(b) = solved_or_refused(&p)? else {
            return Ok(());
        };
        prop_assert!(b.outcome.vx2.is_finite() && b.outcome.omega2.is_finite());
        prop_assert!(b.frame_velocity().is_finite());
        let e = b.energy();
        prop_assert!(e.residual.abs() < 1e-9, "{:?}", e);
        let n_peak = b.setup.n0;
        for s in b.series(64) {
            within_the_cone(&p, &s, n_peak)?;
            if s.kind == PhaseKind::Grip {
                // The patch holds while the ball grips: its slip on the surface is nil.
                prop_assert!(s.patch_slip.abs() <= 1e-9 * p.speed, "patch slip {}", s.patch_slip);
            }
        }
    }
}
