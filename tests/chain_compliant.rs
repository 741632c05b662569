//! The compliant ball on a chain of masses (`--chain N` with `--ball-stiffness`). An independent
//! numerical reference (common/chain_compliant_integrator.rs) is validated against what can be checked
//! today: for N = 1 the single cart's compliant reference and solver, for a free chain (k = 0) the single
//! cart of the first mass alone, for a stiff critically damped ball the rigid ball on the chain, its own
//! energy budget and its convergence in the step.

#[path = "common/chain_compliant_integrator.rs"]
mod chain_compliant_integrator;
#[path = "common/compliant_integrator.rs"]
mod compliant_integrator;

use chain_compliant_integrator::{Reference, integrate, step_for};
use snapback::model::{Bounce, Params, solve};

#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

/// The reference's step: a 250th of a radian of the fastest oscillation (see `step_for`).
const PER_RADIAN: f64 = 0.004;

/// Random bounces with a moderately stiff ball, as tests/compliant.rs draws them, on `chain` masses.
fn random_params(rng: &mut Rng, chain: usize) -> Params {
    Params {
        angle_deg: rng.uniform(5.0, 90.0),
        speed: rng.uniform(2.0, 30.0),
        spin: rng.uniform(-300.0, 300.0),
        mu: rng.uniform(0.1, 0.8),
        duration: rng.uniform(2e-3, 8e-3),
        ey: rng.uniform(0.3, 1.0),
        mass: rng.uniform(0.04, 0.2),
        radius: rng.uniform(0.02, 0.05),
        alpha: rng.uniform(0.4, 0.67),
        cart_mass: rng.log_uniform(3e-3, 1.0),
        stiffness: if rng.unit() < 0.1 {
            0.0
        } else {
            rng.log_uniform(1e3, 1e5)
        },
        cart_friction: 0.0,
        chain: chain as f64,
        ball_stiffness: rng.log_uniform(1e4, 1e6),
        ball_damping: if rng.unit() < 0.2 {
            0.0
        } else {
            rng.uniform(0.05, 1.5)
        },
    }
}

/// Random chains of 2 to 16 masses, lighter and with stiffer balls than `random_params` draws (more of
/// them grip several times).
fn random_chain(rng: &mut Rng) -> Params {
    let n = 2 + rng.below(15);
    Params {
        cart_mass: rng.log_uniform(1e-3, 1.0),
        ball_stiffness: rng.log_uniform(1e4, 1e7),
        ..random_params(rng, n)
    }
}

/// The cases on which the solver for the combination is compared with the reference.
fn solver_cases() -> Vec<Params> {
    let mut rng = Rng(0xc0a1_ba11_0000_0077);
    (0..60).map(|_| random_chain(&mut rng)).collect()
}

/// The reference at its usual step.
fn reference(p: &Params) -> Reference {
    integrate(p, step_for(p, PER_RADIAN))
}

/// The tangential speed scale |v_x1| + r |omega1| (at least a hundredth of the speed).
fn incoming(p: &Params) -> f64 {
    let vx1 = p.speed * (90.0 - p.angle_deg).to_radians().sin();
    (vx1.abs() + p.radius * p.spin.abs()).max(0.01 * p.speed)
}

/// k_b over the friction's peak mu N0: the stretch's scale as a force, 1/m.
fn stretch_scale(p: &Params) -> f64 {
    let vy1 = p.speed * (90.0 - p.angle_deg).to_radians().cos();
    let n0 = (1.0 + p.ey) * std::f64::consts::PI * p.mass * vy1 / (2.0 * p.duration);
    p.ball_stiffness / (p.mu * n0)
}

/// How far a solved bounce is from the reference, each relative to its scale: velocities to
/// |v_x1| + r |omega1|, the first mass's displacement to that times T, energies to the incoming energy.
fn disagreements(p: &Params, b: &Bounce, r: &Reference) -> [(&'static str, f64); 8] {
    let speed = incoming(p);
    let e = b.energy();
    let energy = |solver: f64, reference: f64| (solver - reference).abs() / e.initial;
    [
        ("vx2", (b.outcome.vx2 - r.vx2).abs() / speed),
        (
            "omega2",
            p.radius * (b.outcome.omega2 - r.omega2).abs() / speed,
        ),
        (
            "X1",
            (b.final_state.x - r.x[0]).abs() / (speed * p.duration),
        ),
        ("V1", (b.final_state.v - r.v[0]).abs() / speed),
        ("ball spring", energy(e.ball_spring, r.energy.ball_spring)),
        ("chain energy", energy(e.final_cart, r.energy.chain)),
        (
            "friction loss",
            energy(e.friction_loss, r.energy.friction_loss),
        ),
        (
            "dashpot loss",
            energy(e.dashpot_loss, r.energy.dashpot_loss),
        ),
    ]
}

/// Phases that begin this close to T (relative) are left out of the comparison of phase structures:
/// there N, and with it the friction limit, vanishes, a grip that breaks so late breaks at a time set by
/// rounding, and the phase changes nothing.
const LATE: f64 = 1e-6;

/// The solver's phases as slip signs (0 gripping), leaving out the late ones.
fn solver_structure(b: &Bounce) -> Vec<i8> {
    b.phases
        .iter()
        .filter(|ph| ph.start < b.params.duration * (1.0 - LATE))
        .map(|ph| ph.slip_sign)
        .collect()
}

/// The reference's phases as slip signs, leaving out the late ones.
fn reference_structure(r: &Reference, duration: f64) -> Vec<i8> {
    std::iter::once(0.0)
        .chain(r.transitions.iter().copied())
        .zip(&r.kinds)
        .filter(|(start, _)| *start < duration * (1.0 - LATE))
        .map(|(_, &kind)| kind)
        .collect()
}

/// Asserts that `solve` agrees with the reference to 1e-7 on `cases` (the phase structure exactly), and
/// returns the worst disagreement and how many cases had three phases or more.
fn solver_agrees(cases: &[Params]) -> (f64, usize) {
    let mut worst: f64 = 0.0;
    let mut multi = 0;
    for (i, p) in cases.iter().enumerate() {
        let b = solve(p).unwrap_or_else(|e| panic!("case {i}: {e}\n{p:?}"));
        let r = reference(p);
        let what = format!(
            "case {i} (N = {}): {p:?}\nsolver {} phases {:?}, ends {:?}\nreference {:?}",
            p.chain,
            b.phases.len(),
            b.phases.iter().map(|ph| ph.slip_sign).collect::<Vec<_>>(),
            b.phases.iter().map(|ph| ph.end).collect::<Vec<_>>(),
            r
        );
        for (name, d) in disagreements(p, &b, &r) {
            assert!(d < 1e-7, "{name} off by {d:.2e}: {what}");
            worst = worst.max(d);
        }
        assert_eq!(
            solver_structure(&b),
            reference_structure(&r, p.duration),
            "phases: {what}"
        );
        if r.phases > 2 {
            multi += 1;
        }
    }
    (worst, multi)
}

#[test]
fn one_mass_agrees_with_the_single_cart_reference_and_the_solver() {
    let mut rng = Rng(0x0c4a_1ace_5eed_0002);
    let cases: Vec<Params> = (0..50).map(|_| random_params(&mut rng, 1)).collect();
    // Against the single cart's own reference.
    let mut worst: f64 = 0.0;
    for (i, p) in cases.iter().enumerate() {
        let r = reference(p);
        let c = compliant_integrator::integrate(p, 40_000);
        let speed = incoming(p);
        let force = stretch_scale(p);
        let d = [
            (r.vx2 - c.vx2).abs() / speed,
            p.radius * (r.omega2 - c.omega2).abs() / speed,
            (r.x[0] - c.x).abs() / (speed * p.duration),
            (r.v[0] - c.v).abs() / speed,
            // The stretch, as a force relative to the friction's peak.
            (r.e - c.e).abs() * force,
        ];
        for (name, d) in ["vx2", "omega2", "X", "V", "e"].iter().zip(d) {
            assert!(
                d < 1e-7,
                "case {i}: {name} off by {d:.2e}: {p:?}\n{r:?}\n{c:?}"
            );
            worst = worst.max(d);
        }
        assert_eq!(r.phases, c.phases, "case {i}: {p:?}\n{r:?}\n{c:?}");
    }
    // Against the solver, which works today for the single cart.
    let (against_solver, multi) = solver_agrees(&cases);
    eprintln!(
        "N = 1: worst disagreement {worst:.2e} with the single cart's reference, {against_solver:.2e} \
         with the solver; {multi} of {} cases with 3 phases or more",
        cases.len()
    );
    assert!(multi >= 20, "only {multi} cases with 3 phases or more");
}

#[test]
fn a_free_chain_is_its_first_mass_alone() {
    // k = 0: no springs; the ball pushes the first mass, M/N, and the others stay at rest.
    let mut rng = Rng(0xf4ee_c4a1_0000_0003);
    let mut worst: f64 = 0.0;
    let mut multi = 0;
    for i in 0..30 {
        let n = 2 + rng.below(15);
        let p = Params {
            stiffness: 0.0,
            ..random_params(&mut rng, n)
        };
        let r = reference(&p);
        let alone = Params {
            chain: 1.0,
            cart_mass: p.cart_mass / n as f64,
            ..p
        };
        let b = solve(&alone).unwrap_or_else(|e| panic!("case {i}: {e}"));
        for (name, d) in disagreements(&alone, &b, &r) {
            assert!(
                d < 1e-7,
                "case {i} (N = {n}): {name} off by {d:.2e}: {p:?}\n{r:?}"
            );
            worst = worst.max(d);
        }
        assert_eq!(
            solver_structure(&b),
            reference_structure(&r, p.duration),
            "case {i}: {p:?}"
        );
        assert!(r.x[1..].iter().chain(&r.v[1..]).all(|&z| z == 0.0));
        if r.phases > 2 {
            multi += 1;
        }
    }
    eprintln!("free chains: worst disagreement {worst:.2e}; {multi} of 30 with 3 phases or more");
    assert!(multi >= 10);
}

#[test]
fn a_stiff_critically_damped_ball_approaches_the_rigid_ball_on_the_chain() {
    // The rigid ball on the chain is solved in closed form today; the compliant ball must tend to it as
    // k_b grows at critical damping, phase for phase. A ball coupled to the wrong mass or through the
    // wrong slip would stop at an O(1) error.
    for (n, cart_mass, angle_deg) in [(2, 0.01, 60.0), (16, 0.05, 45.0), (8, 2e-3, 60.0)] {
        let base = Params {
            chain: n as f64,
            cart_mass,
            angle_deg,
            ..Params::default()
        };
        let rigid = solve(&base).unwrap();
        let rigid_phases: Vec<i8> = rigid.ball_phases().iter().map(|ph| ph.slip_sign).collect();
        assert!(rigid_phases.contains(&0), "N = {n}: {rigid_phases:?}");
        let speed = incoming(&base);
        let mut errors = vec![];
        for kb in [1e6, 1e7, 1e8, 1e9] {
            let p = Params {
                ball_stiffness: kb,
                ball_damping: 1.0,
                ..base
            };
            let r = reference(&p);
            let (o, s) = (&rigid.outcome, &rigid.final_state);
            let error = ((r.vx2 - o.vx2).abs()
                + p.radius * (r.omega2 - o.omega2).abs()
                + (r.v[0] - s.v).abs())
                / speed
                + (r.x[0] - s.x).abs() / (speed * p.duration);
            errors.push(error);
            if kb >= 1e8 {
                assert_eq!(r.kinds, rigid_phases, "N = {n}, k_b = {kb:e}");
            }
        }
        let shown: Vec<String> = errors.iter().map(|e| format!("{e:.1e}")).collect();
        eprintln!("N = {n}: error against the rigid ball at k_b = 1e6..1e9: {shown:?}");
        for pair in errors.windows(2) {
            assert!(pair[1] < pair[0], "N = {n}: {errors:?}");
        }
        assert!(errors[2] < 1e-3 && errors[3] < 1e-4, "N = {n}: {errors:?}");
    }
}

#[test]
fn the_reference_balances_energy_on_a_chain() {
    let mut rng = Rng(0xe4e4_c0a1_0000_0004);
    let mut worst: f64 = 0.0;
    let mut undamped = 0;
    for i in 0..80 {
        let p = if i % 2 == 0 {
            random_chain(&mut rng)
        } else {
            let n = 2 + rng.below(15);
            random_params(&mut rng, n)
        };
        let r = reference(&p);
        let e = r.energy;
        let residual = e.residual();
        assert!(
            residual.abs() < 1e-9,
            "case {i}: residual {residual:.2e}: {p:?}\n{r:?}"
        );
        worst = worst.max(residual.abs());
        assert!(e.chain >= 0.0 && e.ball_spring >= 0.0 && e.dashpot_loss >= 0.0);
        assert!(e.friction_loss >= -1e-12 * e.initial, "case {i}: {e:?}");
        if p.ball_damping == 0.0 {
            assert_eq!(e.dashpot_loss, 0.0);
            undamped += 1;
        } else {
            assert!(e.dashpot_loss > 0.0, "case {i}: {e:?}");
        }
    }
    eprintln!("worst energy residual of the reference {worst:.2e}");
    assert!(undamped >= 8);
}

#[test]
fn the_reference_converges_on_the_solver_cases() {
    let cases = solver_cases();
    let mut worst: f64 = 0.0;
    let mut multi = 0;
    let mut many = 0;
    for (i, p) in cases.iter().enumerate() {
        let r = reference(p);
        let fine = integrate(p, step_for(p, PER_RADIAN / 2.0));
        let speed = incoming(p);
        let force = stretch_scale(p);
        let d = [
            (r.vx2 - fine.vx2).abs() / speed,
            p.radius * (r.omega2 - fine.omega2).abs() / speed,
            (r.x[0] - fine.x[0]).abs() / (speed * p.duration),
            (r.v[0] - fine.v[0]).abs() / speed,
            (r.e - fine.e).abs() * force,
        ];
        for (name, d) in ["vx2", "omega2", "X1", "V1", "e"].iter().zip(d) {
            assert!(d < 1e-9, "case {i}: {name} moved by {d:.2e}: {p:?}");
            worst = worst.max(d);
        }
        assert_eq!(
            reference_structure(&r, p.duration),
            reference_structure(&fine, p.duration),
            "case {i}: {p:?}"
        );
        assert!(!r.capped);
        multi += usize::from(r.phases > 2);
        many += usize::from(r.phases > 4);
    }
    eprintln!(
        "halving the step moves the reference by {worst:.2e} at most; {multi} of {} cases with 3 \
         phases or more, {many} with 5 or more",
        cases.len()
    );
    assert!(multi >= 40 && many >= 5, "{multi} {many}");
}
