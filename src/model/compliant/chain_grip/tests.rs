//! The grip's modes against the matrix exponential, Newton against the Schur form, the fallback.
use super::*;
use crate::model::params::Params;

fn grip_modes(params: &Params) -> (GripModes, Setup) {
    let setup = Setup::new(params);
    let chain = Arc::new(Chain::new(params, &setup));
    let spring = BallSpring::new(params, &setup);
    (GripModes::new(chain, &setup, spring.kb, spring.cb), setup)
}

/// A small deterministic generator (the tests need no more).
struct Lcg(u64);
impl Lcg {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn log(&mut self, lo: f64, hi: f64) -> f64 {
        lo * (hi / lo).powf(self.unit())
    }
}
/// The chain as the ball arrives with `spin`, at time `t`, its first `n` masses moving: each displaced
/// within 0.5 mm and at a speed within 0.5 m/s.
fn moving_start(setup: &Setup, spin: f64, t: f64, n: usize, rng: &mut Lcg) -> ChainState {
    let mut start = ChainState::from_contact(&setup.initial(spin));
    start.t = t;
    for i in 0..n {
        start.x[i] = 1e-3 * (rng.unit() - 0.5);
        start.v[i] = rng.unit() - 0.5;
    }
    start
}

fn random(rng: &mut Lcg) -> Params {
    Params {
        chain: (1.0 + 16.0 * rng.unit()).floor().min(16.0),
        cart_mass: rng.log(1e-3, 1.0),
        stiffness: rng.log(1e3, 1e5),
        mass: rng.log(0.04, 0.2),
        ball_stiffness: rng.log(1e4, 1e8),
        ball_damping: if rng.unit() < 0.2 {
            0.0
        } else {
            rng.log(0.01, 3.0)
        },
        ..Params::default()
    }
}

/// The state from the modes against the matrix exponential, relative in the energy norm.
fn modal_error(grip: &ChainGrip, tau: f64) -> f64 {
    let g = &grip.modes;
    let (modal, _) = grip.propagate(grip.start.t + tau, false);
    let exact = (&g.a * tau).exp() * g.to_energy(&grip.z0);
    (g.to_energy(&modal[..grip.z0.len()]) - exact).norm() / g.energy_norm(&grip.z0)
}

/// Against the matrix exponential in energy coordinates (where its rounding is that of the rates).
#[test]
fn the_modes_reproduce_the_matrix_exponential() {
    let mut rng = Lcg(11);
    let mut modal = 0;
    for case in 0..300 {
        let p = random(&mut rng);
        let (g, setup) = grip_modes(&p);
        let start = moving_start(&setup, 100.0, 0.0, g.n, &mut rng);
        let grip = ChainGrip::new(Arc::new(g), start, 1e-4 * rng.unit(), &setup, 0.0);
        if grip.coefficients.is_none() {
            continue;
        }
        modal += 1;
        for tau in [0.0, 1e-4, 1.7e-3, 5e-3] {
            let error = modal_error(&grip, tau);
            assert!(error < 1e-10, "case {case} {p:?}: tau {tau}: {error:e}");
        }
    }
    // Near-double roots are rare: the modes serve almost every grip.
    assert!(modal >= 290, "modes used in {modal} of 300 grips");
}

#[test]
fn newton_and_the_schur_form_find_the_same_roots() {
    let mut rng = Lcg(5);
    for _ in 0..100 {
        let p = random(&mut rng);
        let (g, _) = grip_modes(&p);
        let Some(modes) = g.find_modes() else {
            continue;
        };
        // The Schur form's roots are accurate to rounding of |A|, Newton's to rounding of each root:
        // polished, they agree.
        let schur: Vec<C64> =
            g.a.clone()
                .complex_eigenvalues()
                .iter()
                .map(|&s| g.polish(s, 5))
                .collect();
        assert_eq!(schur.len(), 2 * g.n + 2);
        for mode in &modes {
            let nearest = schur
                .iter()
                .map(|s| (s - mode.s).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest <= 1e-12 * mode.s.norm(),
                "{:?}: {nearest:e}",
                mode.s
            );
        }
    }
}

/// Newton's method finds the roots, with deflation where it found one twice, in nearly every case
/// (in 965 of these 1000 extreme ones; the Schur form serves the rest, at several times the cost).
#[test]
fn newton_finds_almost_every_set_of_roots() {
    let mut rng = Lcg(99);
    let mut found = 0;
    for _ in 0..1000 {
        let (g, _) = grip_modes(&random(&mut rng));
        let guesses = g.guesses().expect("the undamped modes");
        let newton: Vec<C64> = guesses
            .iter()
            .filter(|s| s.im >= 0.0)
            .map(|&s| g.polish(s, 30))
            .collect();
        if g.accept(&newton).is_some() || g.accept(&g.deflated(&guesses)).is_some() {
            found += 1;
        }
    }
    assert!(found >= 950, "Newton found {found} of 1000");
}

/// The grip's fallback, the exponential in energy coordinates, against its modes: the same contact
/// state and force, and its bound on |F''| holds.
#[test]
fn the_exponential_fallback_agrees_with_the_modes() {
    let mut rng = Lcg(29);
    for case in 0..40 {
        let p = Params {
            ball_stiffness: rng.log(1e4, 1e7),
            ..random(&mut rng)
        };
        let (g, setup) = grip_modes(&p);
        let start = moving_start(&setup, 50.0, 1e-3, g.n, &mut rng);
        let modal = ChainGrip::new(Arc::new(g), start, 1e-4 * rng.unit(), &setup, 0.0);
        let fallback = ChainGrip {
            coefficients: None,
            ..modal.clone()
        };
        let (bound, _, _) = fallback.force_bounds(&setup, start.t);
        let scale = modal.modes.energy_norm(&modal.z0);
        for k in 0..=8 {
            let t = start.t + 0.5e-3 * k as f64;
            let (a, b) = (modal.at(&setup, t), fallback.at(&setup, t));
            let speeds = (a.state.vx - b.state.vx).abs() + (a.state.v - b.state.v).abs();
            assert!(
                speeds <= 1e-9 * scale,
                "case {case} t {t}: speeds {speeds:e}"
            );
            let force = (a.friction - b.friction).abs();
            assert!(
                force <= 1e-9 * (bound / modal.modes.fastest.powi(2)),
                "case {case}: F"
            );
            // F'' from the modes' own e''' is not at hand; the rate's change over a short step is.
            let h = 1e-9;
            let second = (modal.at(&setup, t + h).friction_rate - a.friction_rate) / h;
            assert!(
                second.abs() <= bound * (1.0 + 1e-6),
                "case {case}: |F''| bound"
            );
        }
    }
}

/// A grip on a first mass pushed by string friction, z' = A z + b: its modes (with the push's Duhamel
/// terms) against the exponential of the augmented matrix, directly and through the fallback's
/// checkpoints, and the bounds on |F''| and |V_1''| holding for both.
#[test]
fn a_pushed_grip_solves_the_forced_system() {
    let mut rng = Lcg(41);
    let mut modal = 0;
    for case in 0..60 {
        let p = Params {
            ball_stiffness: rng.log(1e4, 1e7),
            ..random(&mut rng)
        };
        let (g, setup) = grip_modes(&p);
        let start = moving_start(&setup, 50.0, 1e-3, g.n, &mut rng);
        let push = if rng.unit() < 0.5 { -20.0 } else { 20.0 } * rng.unit();
        let grip = ChainGrip::new(Arc::new(g), start, 1e-4 * rng.unit(), &setup, push);
        let fallback = ChainGrip {
            coefficients: None,
            beta: None,
            checkpoints: Arc::new(Mutex::new(Vec::new())),
            ..grip.clone()
        };
        let g = &grip.modes;
        let (augmented, _, _) = g.forced_checkpoint();
        let start_energy = g.to_energy(&grip.z0).push(push);
        let scale = g.energy_norm(&grip.z0) + push.abs();
        modal += usize::from(grip.beta.is_some());
        for (name, evaluated) in [("modes", &grip), ("fallback", &fallback)] {
            let (force_bound, _, _) = evaluated.force_bounds(&setup, start.t);
            let (speed_bound, _) = evaluated.first_mass_bounds(&setup);
            for k in 0..=8 {
                let tau = 0.5e-3 * k as f64;
                let t = start.t + tau;
                let exact = (augmented * tau).exp() * &start_energy;
                let (z, _) = evaluated.propagate(t, false);
                let error = (g.to_energy(&z[..2 * g.n + 2]) - exact.rows(0, 2 * g.n + 2)).norm();
                assert!(
                    error <= 1e-9 * scale,
                    "case {case} {name} tau {tau}: {error:e}"
                );
                let h = 1e-9;
                let (a, b) = (evaluated.at(&setup, t), evaluated.at(&setup, t + h));
                let force = (b.friction_rate - a.friction_rate) / h;
                assert!(
                    force.abs() <= force_bound * (1.0 + 1e-6),
                    "case {case} {name}: |F''|"
                );
                let speed = (b.accel - a.accel) / h;
                assert!(
                    speed.abs() <= speed_bound * (1.0 + 1e-6),
                    "case {case} {name}: |V_1''|"
                );
            }
        }
    }
    assert!(modal >= 50, "the modes served {modal} of 60 pushed grips");
}

#[test]
fn each_mode_carries_the_unit_force() {
    let p = Params {
        chain: 8.0,
        ball_stiffness: 1e6,
        ball_damping: 0.5,
        ..Params::default()
    };
    let (g, _) = grip_modes(&p);
    for mode in g
        .modes
        .as_ref()
        .expect("the default chain has distinct modes")
    {
        assert!((mode.force - 1.0).norm() < 1e-9, "{:?}", mode.force);
    }
}

/// The ball on the ring of a first mass held to a free frame: the modes the ring's mirror symmetry
/// keeps the held body still in (one for each pair of links mirrored about it, (N - 1)/2 on a ring of
/// N masses) swing apart, and the rest are solved in their modes, not by the exponential. Each still
/// mode obeys Q'' + Ω² Q = p_j P (checked by differences of the whole chain's state), and the grip
/// starts from its start state. (Long rings on heavy frames have lightly damped roots so near the
/// poles of R(s) that the residual check refuses them: the exponential serves those.)
#[test]
fn a_ring_grip_solves_its_mirror_modes_apart() {
    let mut rng = Lcg(17);
    let mut served = 0;
    for links in 2..=16 {
        let p = Params {
            chain: links as f64,
            frame_mass: rng.log(0.02, 2.0),
            stiffness: rng.log(1e3, 1e5),
            ball_stiffness: rng.log(1e4, 1e6),
            ball_damping: rng.log(0.1, 1.0),
            ..Params::default()
        };
        let setup = Setup::new(&p);
        let spring = BallSpring::new(&p, &setup);
        let ring = Chain::new(&p, &setup)
            .held_ring()
            .expect("a chain on a frame");
        let g = GripModes::new(Arc::new(ring), &setup, spring.kb, spring.cb);
        assert_eq!(g.still.len(), (links - 1) / 2, "{links} links");
        if g.modes.is_none() {
            continue;
        }
        served += 1;
        let masses = links;
        let mut start = moving_start(&setup, 50.0, 1e-3, masses, &mut rng);
        start.frame = masses - 1;
        let push = 20.0 * (rng.unit() - 0.5);
        let grip = ChainGrip::new(Arc::new(g), start, 1e-4 * rng.unit(), &setup, push);
        assert!(
            grip.coefficients.is_some(),
            "{links} links: the start in the modes"
        );
        let first = grip.full(&setup, start.t);
        for i in 0..masses {
            assert!(
                (first.x[i] - start.x[i]).abs() <= 1e-15,
                "{links} links: x[{i}]"
            );
            assert!(
                (first.v[i] - start.v[i]).abs() <= 1e-12,
                "{links} links: v[{i}]"
            );
        }
        let g = &grip.modes;
        let slide = &g.chain.slide;
        for (k, mode) in g.still.iter().enumerate() {
            assert!(
                slide.shape[0][mode.index].abs() <= 1e-12,
                "{links} links: still"
            );
            let modal = |t: f64| slide.project(&grip.full(&setup, t).x)[mode.index];
            let (t, h) = (start.t + 1.3e-3, 1e-6);
            let second = (modal(t + h) - 2.0 * modal(t) + modal(t - h)) / (h * h);
            let (q, _, ddq) = grip.still(k, t - start.t);
            let scale = mode.omega * mode.omega * q.abs() + (mode.push * push).abs();
            assert!(
                (second - ddq).abs() <= 1e-4 * scale,
                "{links} links, still mode {k}: {second:e} against {ddq:e}"
            );
        }
    }
    assert!(served >= 9, "the modes served {served} of 15 rings");
}

/// The largest violation over a wall grip's search stages of its F'' and F''' (against central
/// differences of F' and F'') and of each stage's bound on |F''''| (scaled by `scale`; against the
/// central difference of F''' at h = 1e-5 of the fastest mode's period over pi, whose truncation is
/// about (h |s|)²/6 = 2e-11 of the bound, covered by a relative room of 1e-6, and whose rounding is a
/// few ulps of |F'''| over h, covered by 1e3 ulps of the largest). Each stage is sampled from its start
/// to its end, 2h inside it.
fn fourth_violation(grip: &ChainGrip, setup: &Setup, scale: f64) -> (f64, f64) {
    let (stages, _) = grip.search_stages(setup);
    let fastest = grip
        .modes
        .modes
        .as_ref()
        .expect("the modes")
        .iter()
        .map(|m| m.s.norm())
        .fold(0.0, f64::max);
    let h = 1e-5 / fastest;
    let higher = |t: f64| grip.force_with_higher(setup, t).1.expect("F'' and F'''");
    let (mut derivatives, mut fourth) = (0.0f64, 0.0f64);
    for stage in stages {
        let n = 256;
        let samples: Vec<f64> = (0..=n)
            .map(|i| stage.from + 2.0 * h + (stage.to - stage.from - 4.0 * h) * i as f64 / n as f64)
            .collect();
        let largest = samples
            .iter()
            .map(|&t| higher(t).1.abs())
            .fold(0.0, f64::max);
        let slack = 1e3 * f64::EPSILON * largest / h;
        for &t in &samples {
            let (second, third) = higher(t);
            let (before, after) = (grip.at(setup, t - h), grip.at(setup, t + h));
            // The search's F and F' are the state's, bit for bit.
            let point = grip.at(setup, t);
            let ([force, rate], _) = grip.force_with_higher(setup, t);
            assert_eq!(
                [force.to_bits(), rate.to_bits()],
                [point.friction.to_bits(), point.friction_rate.to_bits()]
            );
            // So is the state summed from the exponentials the search kept there (on the wall).
            let mut turns = Turns::new();
            grip.margins_keeping(setup, t, Some(&mut turns));
            let Some(kept) = grip.at_turns(setup, t, &turns) else {
                assert!(grip.frame_shares.is_some(), "kept at t");
                continue;
            };
            let bits = |p: &Point| {
                let s = p.state;
                [
                    s.t,
                    s.vx,
                    s.omega,
                    s.x,
                    s.v,
                    p.friction,
                    p.friction_rate,
                    p.e,
                    p.de,
                    p.dde,
                    p.slip_rate,
                    p.accel,
                    p.frame.0,
                    p.frame.1,
                ]
                .map(f64::to_bits)
            };
            assert_eq!(bits(&kept), bits(&point));
            let rate_difference = (after.friction_rate - before.friction_rate) / (2.0 * h);
            let (second_before, third_before) = higher(t - h);
            let (second_after, third_after) = higher(t + h);
            let second_difference = (second_after - second_before) / (2.0 * h);
            // F'' and F''' within 1e-6 of the stage's bounds on them.
            derivatives = derivatives
                .max((second - rate_difference).abs() / stage.curvature)
                .max((third - second_difference).abs() / (stage.curvature * fastest));
            let difference = (third_after - third_before) / (2.0 * h);
            let bound = scale * stage.fourth * (1.0 + 1e-6) + slack;
            fourth = fourth.max(difference.abs() / bound);
        }
    }
    (derivatives, fourth)
}

/// The wall grip's F'' and F''' (its margins' Taylor polynomials) are the derivatives of its F' (and its
/// F and F' those of its state, bit for bit, as is the state summed from the exponentials the search
/// kept), and
/// each search stage's bound on |F''''| holds over the stage, on random chains and balls; half the bound
/// fails somewhere, so the check can fail.
#[test]
fn the_grip_bounds_its_fourth_derivative() {
    let mut rng = Lcg(17);
    let (mut checked, mut halved) = (0, 0.0f64);
    for case in 0..60 {
        let p = Params {
            ball_stiffness: rng.log(1e4, 1e7),
            ..random(&mut rng)
        };
        let (g, setup) = grip_modes(&p);
        let start = moving_start(&setup, 50.0, 1e-3 * rng.unit(), g.n, &mut rng);
        let grip = ChainGrip::new(Arc::new(g), start, 1e-4 * rng.unit(), &setup, 0.0);
        if grip.shares.is_none() {
            continue;
        }
        checked += 1;
        let (derivatives, fourth) = fourth_violation(&grip, &setup, 1.0);
        assert!(
            derivatives <= 1e-6,
            "case {case} {p:?}: F'', F''' {derivatives:e}"
        );
        assert!(
            fourth <= 1.0,
            "case {case} {p:?}: |F''''| at {fourth} of its bound"
        );
        halved = halved.max(fourth_violation(&grip, &setup, 0.5).1);
    }
    assert!(checked >= 50, "{checked} grips by their shares");
    assert!(halved > 1.0, "half the bound holds everywhere ({halved})");
}

/// A free frame's grip without a push sums its shares, the frame's four among them: its point agrees
/// with the same grip summed mode by mode through the library's exponential (to rounding), its F''
/// and F''' are the derivatives of its F', and each search stage's bound on |F''''| holds.
#[test]
fn a_framed_grip_sums_its_shares() {
    let mut rng = Lcg(29);
    let mut checked = 0;
    for case in 0..40 {
        let p = Params {
            frame_mass: rng.log(0.02, 2.0),
            ..random(&mut rng)
        };
        let (g, setup) = grip_modes(&p);
        assert!(g.translation.is_some(), "case {case}: a chain on a frame");
        let masses = g.chain.slide.n;
        let start = moving_start(&setup, 50.0, 1e-3 * rng.unit(), masses, &mut rng);
        let grip = ChainGrip::new(Arc::new(g), start, 1e-4 * rng.unit(), &setup, 0.0);
        if grip.frame_shares.is_none() {
            continue;
        }
        checked += 1;
        let by_modes = ChainGrip {
            shares: None,
            frame_shares: None,
            ..grip.clone()
        };
        for k in 0..=20 {
            let t = start.t + 2e-4 * k as f64;
            let (a, b) = (grip.at(&setup, t), by_modes.at(&setup, t));
            let pairs = [
                (a.state.vx, b.state.vx),
                (a.state.omega * setup.r, b.state.omega * setup.r),
                (a.state.x, b.state.x),
                (a.state.v, b.state.v),
                (a.e, b.e),
                (a.de, b.de),
                (a.frame.0, b.frame.0),
            ];
            let scale = pairs.iter().map(|&(x, _)| x.abs()).fold(1e-3, f64::max);
            for (field, (x, y)) in pairs.into_iter().enumerate() {
                assert!(
                    (x - y).abs() <= 1e-12 * scale,
                    "case {case}, field {field} at {t}: {x:e} against {y:e}"
                );
            }
        }
        let (derivatives, fourth) = fourth_violation(&grip, &setup, 1.0);
        assert!(
            derivatives <= 1e-6,
            "case {case} {p:?}: F'', F''' {derivatives:e}"
        );
        assert!(
            fourth <= 1.0,
            "case {case} {p:?}: |F''''| at {fourth} of its bound"
        );
    }
    assert!(checked >= 30, "{checked} framed grips by their shares");
}
