//! The analyses against the core: sweeps against single solves, the critical angle against Eq. (7),
//! optimisation against a dense scan, the claims coverage, and the figures' SVG.

use crate::support::rng;
use snapback::analysis::cases::{HEAVY, SOFT};
use snapback::analysis::claims;
use snapback::analysis::critical::{self, Critical};
use snapback::analysis::figures::Which;
use snapback::analysis::optimize::{Objective, optimize};
use snapback::analysis::reproduce::{self, Status};
use snapback::analysis::{Span, retune, sweep, timeline};
use snapback::export::svg;
use snapback::model::params::{ParamId, spec_named};
use snapback::model::{Params, solve};
use snapback::output::Replace;

#[test]
fn sweep_rows_are_single_solves_in_order() {
    let base = Params::default();
    for (name, from, to, log) in [
        ("angle", "5", "90", false),
        ("stiffness", "1kN/m", "100kN/m", true),
        ("spin", "100", "-300", false),
        ("cart-mass", "0.5g", "2kg", true),
    ] {
        let span = Span::parse(name, from, to, log).unwrap();
        let rows = sweep::sweep(&base, &span, 37).unwrap();
        assert_eq!(rows.len(), 37);
        assert_eq!(rows[0].value, span.from);
        assert_eq!(rows[36].value, span.to);
        for row in &rows {
            let mut p = base;
            p.set(span.spec.id, row.value);
            let b = solve(&p).unwrap();
            assert_eq!(row.omega2, b.outcome.omega2);
            assert_eq!(row.vx2, b.outcome.vx2);
            assert_eq!(row.vy2, b.outcome.vy2);
            assert_eq!(row.theta2_deg, b.outcome.theta2_deg);
            assert_eq!(row.ex, b.outcome.ex);
            assert_eq!(row.phases, b.phase_summary());
            assert_eq!(row.slides_throughout, b.slides_throughout());
        }
        let ordered = rows.windows(2).all(|w| {
            if span.from < span.to {
                w[0].value < w[1].value
            } else {
                w[0].value > w[1].value
            }
        });
        assert!(ordered, "{name}");
    }
}

#[test]
fn sweep_csv_round_trips() {
    let span = Span::parse("angle", "10", "90", false).unwrap();
    let steps = 70_000; // more than one block of the streamed CSV
    let rows = sweep::sweep(&Params::default(), &span, steps).unwrap();
    let mut out = Vec::new();
    sweep::write_csv(&mut out, &Params::default(), &span, steps).unwrap();
    let text = String::from_utf8(out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "angle_deg,omega2,vx2,vy2,theta2_deg,ex,phases,slides_throughout,cart_stuck,stretch,patch_slip"
    );
    assert_eq!(lines.len(), steps + 1);
    for (line, row) in lines[1..].iter().zip(&rows) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells[0].parse::<f64>().unwrap(), row.value);
        assert_eq!(cells[1].parse::<f64>().unwrap(), row.omega2);
        assert_eq!(cells[5].parse::<f64>().ok(), row.ex);
        assert_eq!(cells[6], row.phases);
        assert_eq!(cells[7], row.slides_throughout.to_string());
        assert_eq!(cells[8], row.cart_stuck.to_string());
        assert_eq!(cells[9].parse::<f64>().ok(), row.stretch);
        assert_eq!(cells[10].parse::<f64>().ok(), row.patch_slip);
    }
}

#[test]
fn full_model_critical_angle_tends_to_eq7_for_a_heavy_cart() {
    for (spin, mu) in [(0.0, 0.4), (-100.0, 0.4), (-200.0, 0.3), (50.0, 0.6)] {
        let mut p = HEAVY.case(&Params::default(), 45.0, spin);
        p.mu = mu;
        p.cart_mass = 1e6;
        let eq7 = critical::eq7(&p).degrees().unwrap();
        let full = critical::full_model(&p).unwrap().degrees().unwrap();
        assert!((full - eq7).abs() < 0.01, "spin {spin}: {full} vs {eq7}");
    }
}

#[test]
fn eq7_matches_the_papers_spinless_value_and_its_own_equation() {
    let p = HEAVY.case(&Params::default(), 45.0, 0.0);
    let theta = critical::eq7(&p).degrees().unwrap();
    assert!((theta - 23.9).abs() < 0.05, "{theta}");
    let back = HEAVY.case(&Params::default(), 45.0, -100.0);
    let t = critical::eq7(&back).degrees().unwrap().to_radians();
    let rhs = (1.0 - back.radius * back.spin / (back.speed * t.cos()))
        / (2.0 * back.mu * (1.0 + 1.0 / back.alpha));
    assert!((t.tan() - rhs).abs() < 1e-12);
}

#[test]
fn critical_angle_separates_sliding_from_gripping() {
    let p = SOFT.case(&Params::default(), 45.0, -100.0);
    let Critical::At(deg) = critical::full_model(&p).unwrap() else {
        panic!("the soft spring has a critical angle");
    };
    let at = |a: f64| {
        let mut q = p;
        q.angle_deg = a;
        solve(&q).unwrap().slides_throughout()
    };
    assert!(at(deg - 0.005));
    assert!(!at(deg + 0.005));
    let frictionless = Params { mu: 0.0, ..p };
    assert_eq!(
        critical::full_model(&frictionless).unwrap(),
        Critical::AlwaysSlides
    );
}

/// The best value of a dense scan, for comparison with `optimize`.
fn dense_best(base: &Params, span: &Span, objective: Objective, minimize: bool) -> (f64, f64) {
    let rows = sweep::sweep(base, span, 20_000).unwrap();
    let sign = if minimize { -1.0 } else { 1.0 };
    rows.iter()
        .map(|r| {
            let mut p = *base;
            p.set(span.spec.id, r.value);
            let o = solve(&p).unwrap().outcome;
            (r.value, objective.of(&o).unwrap())
        })
        .max_by(|a, b| (sign * a.1).total_cmp(&(sign * b.1)))
        .unwrap()
}

#[test]
fn optimize_beats_a_dense_scan() {
    let one_gram = Params {
        cart_mass: 1e-3,
        ..Params::default()
    };
    let cases = [
        (
            one_gram,
            "stiffness",
            "100",
            "1e6",
            Objective::Omega2,
            false,
        ),
        (
            Params::default(),
            "angle",
            "1",
            "90",
            Objective::Omega2,
            false,
        ),
        (
            Params::default(),
            "stiffness",
            "1000",
            "1e5",
            Objective::Ex,
            false,
        ),
        (
            Params::default(),
            "angle",
            "20",
            "80",
            Objective::Theta2,
            true,
        ),
        (
            Params::default(),
            "spin",
            "-300",
            "300",
            Objective::Vx2,
            false,
        ),
    ];
    for (base, name, from, to, objective, minimize) in cases {
        let span = Span::parse(name, from, to, false).unwrap();
        let best = optimize(&base, &span, objective, minimize, 400).unwrap();
        let scan_span = snapback::analysis::optimize::scan_span(&span);
        let (x, y) = dense_best(&base, &scan_span, objective, minimize);
        let better = if minimize {
            best.objective_value <= y + 1e-9 * y.abs()
        } else {
            best.objective_value >= y - 1e-9 * y.abs()
        };
        assert!(better, "{name}: {} vs dense {y}", best.objective_value);
        let width = (span.to - span.from).abs();
        let near = if scan_span.log {
            (best.value / x).ln().abs() < 1e-3
        } else {
            (best.value - x).abs() < 1e-3 * width
        };
        assert!(near, "{name}: {} vs dense {x}", best.value);
        assert_eq!(
            objective.of(&best.bounce.outcome),
            Some(best.objective_value)
        );
    }
}

/// The chain lengths from `from` to `to` (either way) with the objective there, solved one by one.
fn each_chain(base: &Params, from: u32, to: u32, objective: Objective) -> Vec<(f64, f64)> {
    let ns: Vec<u32> = if from <= to {
        (from..=to).collect()
    } else {
        (to..=from).rev().collect()
    };
    ns.into_iter()
        .map(|n| {
            let params = Params {
                chain: f64::from(n),
                ..*base
            };
            let outcome = solve(&params).unwrap().outcome;
            (f64::from(n), objective.of(&outcome).unwrap())
        })
        .collect()
}

#[test]
fn optimize_over_the_chain_is_the_best_of_every_whole_number() {
    let light = Params {
        cart_mass: 1e-3,
        stiffness: 5e3,
        ..Params::default()
    };
    for base in [Params::default(), light] {
        for (from, to) in [(1, 16), (16, 1), (3, 9)] {
            for objective in Objective::ALL {
                for minimize in [false, true] {
                    let span =
                        Span::parse("chain", &from.to_string(), &to.to_string(), false).unwrap();
                    let best = optimize(&base, &span, objective, minimize, 400).unwrap();
                    let each = each_chain(&base, from, to, objective);
                    // The first of equal values from --from on, as the optimizer takes it.
                    let expected = each
                        .iter()
                        .copied()
                        .reduce(|a, b| {
                            let better = if minimize { b.1 < a.1 } else { b.1 > a.1 };
                            if better { b } else { a }
                        })
                        .unwrap();
                    let case = format!("{from}..{to} {} min {minimize}", objective.name());
                    assert_eq!((best.value, best.objective_value), expected, "{case}");
                    assert_eq!(best.bounce.params.chain, best.value, "{case}");
                    assert_eq!(objective.of(&best.bounce.outcome), Some(expected.1));
                    assert!(best.exhaustive, "{case}");
                    assert!(!best.span.log);
                    assert_eq!((best.span.from, best.span.to), (from.into(), to.into()));
                }
            }
        }
    }
    // The default case: the most spin is at an interior N, not at an end.
    let span = Span::parse("chain", "1", "16", true).unwrap();
    let best = optimize(&Params::default(), &span, Objective::Omega2, false, 3).unwrap();
    assert!(best.value > 1.0 && best.value < 16.0, "{}", best.value);
    assert!(!best.span.log, "a whole-number search is not geometric");
    // A continuous parameter is still scanned and refined.
    let span = Span::parse("angle", "20", "80", false).unwrap();
    assert!(
        !optimize(&Params::default(), &span, Objective::Omega2, false, 400)
            .unwrap()
            .exhaustive
    );
}

#[test]
fn a_chain_range_is_narrowed_to_its_whole_numbers_and_refused_without_one() {
    let chain = spec_named("chain").unwrap();
    // Ends that are not whole (possible through the library) are rounded inwards.
    let span = Span::new(chain, 1.5, 3.7, false).unwrap();
    assert_eq!(span.whole_numbers().unwrap(), vec![2.0, 3.0]);
    let best = optimize(&Params::default(), &span, Objective::Omega2, false, 400).unwrap();
    let each = each_chain(&Params::default(), 2, 3, Objective::Omega2);
    let top = if each[0].1 >= each[1].1 {
        each[0]
    } else {
        each[1]
    };
    assert_eq!((best.value, best.objective_value), top);
    assert_eq!((best.span.from, best.span.to), (2.0, 3.0));
    let reversed = Span::new(chain, 3.7, 1.5, false).unwrap();
    assert_eq!(reversed.whole_numbers().unwrap(), vec![3.0, 2.0]);
    // No whole number between the ends.
    let empty = Span::new(chain, 1.2, 1.8, false).unwrap();
    let err = optimize(&Params::default(), &empty, Objective::Omega2, false, 400)
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "--from 1.2 --to 1.8 holds no whole number, and --chain must be in {1, 2, ..., 16}"
    );
}

#[test]
fn a_chain_sweep_lands_on_whole_numbers_or_is_refused() {
    let base = Params::default();
    let span = Span::parse("chain", "1", "16", false).unwrap();
    let rows = sweep::sweep(&base, &span, 16).unwrap();
    let each = each_chain(&base, 1, 16, Objective::Omega2);
    for (row, (n, omega2)) in rows.iter().zip(&each) {
        assert_eq!((row.value, row.omega2), (*n, *omega2));
    }
    let values = |span: &Span, steps| -> Vec<f64> {
        sweep::sweep(&base, span, steps)
            .unwrap()
            .iter()
            .map(|r| r.value)
            .collect()
    };
    assert_eq!(values(&span, 4), [1.0, 6.0, 11.0, 16.0]);
    // Geometric steps that land on whole numbers are exact.
    let log = Span::parse("chain", "1", "16", true).unwrap();
    assert_eq!(values(&log, 5), [1.0, 2.0, 4.0, 8.0, 16.0]);
    // Steps between whole numbers: refused before anything is solved or written.
    let err = sweep::sweep(&base, &span, 5).unwrap_err().to_string();
    assert_eq!(
        err,
        "--steps 5 puts --chain at 4.75, not a whole number; from 1 to 16 use --steps 2, 4, 6 or 16 \
         (16 takes every whole number)"
    );
    let err = sweep::sweep(&base, &log, 6).unwrap_err().to_string();
    assert!(
        err.contains("use --steps 2, 3 or 5 with --log, or --steps 16 without it"),
        "{err}"
    );
    let mut out = Vec::new();
    assert!(sweep::write_csv(&mut out, &base, &span, 3).is_err());
    assert!(out.is_empty(), "no header before the refusal");
    // Every other parameter sweeps at any count.
    let angle = Span::parse("angle", "10", "80", false).unwrap();
    // A third of the way, correctly rounded: (2 x 10 + 80) / 3.
    assert_eq!(values(&angle, 4)[1], 100.0 / 3.0);
}

#[test]
fn reproduce_covers_every_claim_with_its_printed_numbers() {
    let report = reproduce::reproduce(&Params::default()).unwrap();
    let claims = claims::all();
    assert!(report.missing.is_empty(), "{:?}", report.missing);
    for claim in &claims {
        assert!(report.rows.iter().any(|r| r.id == claim.id), "{}", claim.id);
    }
    for row in &report.rows {
        let claim = claims
            .iter()
            .find(|c| c.id == row.id)
            .unwrap_or_else(|| panic!("{} is not a claim id", row.id));
        let quoted = claim.statement.contains(row.printed)
            || (row.printed == "0" && claim.statement.contains("zero"));
        assert!(
            quoted,
            "{}: {} not in {:?}",
            row.id, row.printed, claim.statement
        );
        assert!(row.computed.is_finite(), "{} {}", row.id, row.quantity);
        let precision_ok = row.status != Status::Reproduced
            || row.difference.abs() <= 0.5 * 10f64.powi(-decimals(row.printed)) + 1e-12;
        assert!(precision_ok, "{} {}", row.id, row.quantity);
        // A close value needs a demonstrated cause; without one it is a miss, and says so.
        if row.status == Status::Close {
            assert!(row.explained, "{} {}", row.id, row.quantity);
        }
        if !row.accounted_for() {
            assert_eq!(row.status, Status::Differs);
            assert!(row.note.contains("no cause"), "{}", row.note);
        }
    }
    assert_eq!(report.complete(), report.unexplained().is_empty());
}

#[test]
fn reproduce_checks_that_the_fig3c_cart_returns_to_its_origin() {
    let report = reproduce::reproduce(&Params::default()).unwrap();
    let row = report.rows.iter().find(|r| r.id == "fig3c-return").unwrap();
    let b = solve(&Params::default()).unwrap();
    assert_eq!(row.computed, b.final_state.x * 1e3);
    assert_eq!(row.paper, 0.0);
    assert_eq!(row.status, Status::Differs, "X(T) = {} mm", row.computed);
    assert!(row.accounted_for(), "{}", row.note);
    // The reason's spring brings the cart back at T.
    let k: f64 = row
        .note
        .split("needs k = ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|k| k.parse().ok())
        .unwrap_or_else(|| panic!("{}", row.note));
    let back = solve(&Params {
        stiffness: k,
        ..Params::default()
    })
    .unwrap();
    assert!(back.final_state.x.abs() < 1e-6, "{}", back.final_state.x);
}

fn decimals(printed: &str) -> i32 {
    printed.split_once('.').map_or(0, |(_, f)| f.len() as i32)
}

#[test]
fn reproduce_rows_match_the_model() {
    let report = reproduce::reproduce(&Params::default()).unwrap();
    let row = |id: &str, quantity: &str| {
        report
            .rows
            .iter()
            .find(|r| r.id == id && r.quantity.contains(quantity))
            .unwrap_or_else(|| panic!("{id} {quantity}"))
            .computed
    };
    let fig3c = solve(&Params::default()).unwrap();
    assert_eq!(row("fig3c-spin", "omega2"), fig3c.outcome.omega2);
    assert!((row("fig3a-grip-time", "sliding") - 2.2579).abs() < 1e-4);
    assert!((row("fig3c-max-x", "maximum") - 7.689).abs() < 1e-3);
    let coefficient = 2.0 * 0.4 * 10.0 / (0.55 * 0.033);
    assert!((row("eq8-coefficient", "coefficient") - coefficient).abs() < 1e-9);
}

#[test]
fn the_cart_turns_round_where_its_velocity_vanishes() {
    let b = solve(&Params::default()).unwrap();
    let (t, x) = timeline::peak(&b, |s| s.x);
    let s = b.sample_at(t);
    assert!(s.v.abs() < 1e-5, "{}", s.v);
    assert_eq!(s.x, x);
    assert!((t * 1e3 - 3.075).abs() < 1e-3);
}

#[test]
fn the_peak_travel_is_the_papers_fig3() {
    // Fig. 3(b): "a maximum positive displacement of 4.4 mm at t = 2.3 ms"; Fig. 3(c): "a maximum
    // displacement of 7.7 mm at 3.1 ms" and "a maximum forward speed of 5.0 m/s at 1.34 ms", but the
    // cart swings back faster than that before the ball leaves, so the largest |V| is at release.
    let light = Params {
        stiffness: 4e4,
        ..Params::default()
    };
    // The paper reads Fig. 3(b) off its curve: the model's 4.31 mm at 2.31 ms is 2% below.
    let b = solve(&light).unwrap();
    let t = timeline::travel(&b);
    assert!((t.peak_x * 1e3 - 4.4).abs() < 0.1, "{t:?}");
    assert!((t.peak_x_at * 1e3 - 2.3).abs() < 0.05, "{t:?}");
    // The same maximum as `reproduce`'s scan of X, which never goes negative here.
    let (at, x) = timeline::peak(&b, |s| s.x);
    assert!((x / t.peak_x - 1.0).abs() < 1e-13 && (at - t.peak_x_at).abs() < 1e-9);
    let b = solve(&Params::default()).unwrap();
    let t = timeline::travel(&b);
    assert!((t.peak_x * 1e3 - 7.7).abs() < 0.05, "{t:?}");
    assert!((t.peak_x_at * 1e3 - 3.1).abs() < 0.05, "{t:?}");
    assert_eq!(t.peak_v, b.final_state.v.abs());
    assert_eq!(t.peak_v_at, b.setup.duration);
    // The forward peak the paper quotes is the largest V before the cart turns (the model's 5.11 m/s
    // at 1.324 ms, as `reproduce` reports it).
    let (at, v) = timeline::peak_between(&b, 0.0, t.peak_x_at, |s| s.v);
    assert!(
        (v - 5.0).abs() < 0.15 && (at * 1e3 - 1.34).abs() < 0.03,
        "{v} at {at}"
    );
}

#[test]
fn the_peak_travel_is_exact_on_every_contact_model() {
    let base = Params::default();
    let cases = [
        base,
        Params {
            cart_mass: 1e-3,
            stiffness: 9.554e3,
            ..base
        },
        Params { chain: 8.0, ..base },
        Params {
            ball_stiffness: 1e5,
            ball_damping: 0.3,
            cart_friction: 20.0,
            ..base
        },
        Params {
            chain: 4.0,
            ball_stiffness: 1e6,
            cart_friction: 10.0,
            ..base
        },
        Params {
            angle_deg: 35.0,
            cart_friction: 8.0,
            ..base
        },
    ];
    for p in cases {
        let b = solve(&p).unwrap();
        let t = timeline::travel(&b);
        // Never below any sample of a dense series, and above the densest one by no more than its
        // spacing allows (0.25 us: V dt for the displacement, A dt for the velocity).
        let series = b.series(20_001);
        let dense =
            |f: fn(&snapback::model::Sample) -> f64| series.iter().map(f).fold(0.0, f64::max);
        let (x, v) = (dense(|s| s.x.abs()), dense(|s| s.v.abs()));
        assert!(
            t.peak_x >= x * (1.0 - 1e-14) && t.peak_x <= x * (1.0 + 1e-5),
            "{p:?}: {t:?} {x}"
        );
        assert!(
            t.peak_v >= v * (1.0 - 1e-14) && t.peak_v <= v * (1.0 + 1e-3),
            "{p:?}: {t:?} {v}"
        );
        // Inside the contact the largest |X| is where the cart turns round: V = 0 there.
        let at = b.sample_at(t.peak_x_at);
        assert_eq!(at.x.abs(), t.peak_x);
        if t.peak_x_at < b.setup.duration {
            assert!(
                at.v.abs() < 1e-6 * t.peak_v,
                "{p:?}: V = {} at the peak",
                at.v
            );
        }
    }
}

#[test]
fn the_peak_travel_holds_on_random_bounces() {
    // Random bounces over every contact model: the peak is never below a dense series' largest sample,
    // nor above it by more than the series' spacing allows.
    let mut rng = rng::Rng(0x5eed_7a1e);
    let mut checked = 0;
    while checked < 40 {
        let chain = [1.0, 1.0, 2.0, 5.0][rng.below(4)];
        let p = Params {
            angle_deg: rng.uniform(20.0, 85.0),
            spin: rng.uniform(-400.0, 100.0),
            cart_mass: rng.log_uniform(1e-3, 0.1),
            stiffness: rng.log_uniform(2e3, 2e5),
            cart_friction: [0.0, rng.uniform(0.0, 60.0)][rng.below(2)],
            ball_stiffness: [0.0, rng.log_uniform(3e4, 1e7)][rng.below(2)],
            ball_damping: rng.uniform(0.05, 1.0),
            chain,
            ..Params::default()
        };
        let Ok(b) = solve(&p) else { continue };
        checked += 1;
        let t = timeline::travel(&b);
        let series = b.series(20_001);
        let x = series.iter().map(|s| s.x.abs()).fold(0.0, f64::max);
        let v = series.iter().map(|s| s.v.abs()).fold(0.0, f64::max);
        assert!(
            t.peak_x >= x * (1.0 - 1e-14) && t.peak_x <= x * (1.0 + 1e-4),
            "{p:?}: {t:?} {x}"
        );
        assert!(
            t.peak_v >= v * (1.0 - 1e-14) && t.peak_v <= v * (1.0 + 1e-2),
            "{p:?}: {t:?} {v}"
        );
    }
}

#[test]
fn strings_held_by_their_friction_do_not_travel() {
    let p = Params {
        cart_friction: 1e4,
        ..Params::default()
    };
    let t = timeline::travel(&solve(&p).unwrap());
    assert_eq!((t.peak_x, t.peak_v), (0.0, 0.0));
}

#[test]
fn retune_finds_the_value_that_prints_a_number() {
    let p = Params::default();
    let k = retune::retune(&p, ParamId::Stiffness, 5e3, 5e4, 162.8, |q| {
        solve(q).ok().map(|b| b.outcome.omega2)
    })
    .unwrap();
    let q = Params { stiffness: k, ..p };
    assert!((solve(&q).unwrap().outcome.omega2 - 162.8).abs() < 1e-6);
}

#[test]
fn figures_follow_eq8_at_glancing_angles() {
    let fig = Which::Fig2.data(&Params::default()).unwrap();
    assert_eq!(fig.panels.len(), 2);
    for (panel, spin) in fig.panels.iter().zip([0.0, -100.0]) {
        assert_eq!(panel.curves.len(), 3);
        for curve in &panel.curves {
            let (theta, omega2) = curve.points[50];
            let eq8 = spin + 2.0 * 0.4 * 10.0 / (0.55 * 0.033) * theta.to_radians().sin();
            assert!((omega2 - eq8).abs() < 1e-9);
        }
    }
    let fig3 = Which::Fig3.data(&Params::default()).unwrap();
    assert_eq!(fig3.panels.len(), 3);
    assert!(fig3.panels.iter().all(|p| p.curves.len() == 3));
}

/// Every piece of text in an SVG document.
fn svg_texts(svg: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(svg).expect("the SVG is XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    doc.descendants()
        .filter(|n| n.is_text())
        .filter_map(|n| n.text())
        .map(str::to_string)
        .collect()
}

#[test]
fn svg_figures_are_xml_with_axis_titles_and_legends() {
    let base = Params::default();
    let expected: [(Which, &[&str]); 2] = [
        (
            Which::Fig2,
            &[
                "θ1 (deg)",
                "ω2 (rad/s)",
                "M = 10 kg, k = 4×10⁴ N/m",
                "(b) ω1 = -100 rad/s",
            ],
        ),
        (
            Which::Fig3,
            &[
                "t (ms)",
                "F (N)",
                "X (mm)",
                "ω (rad/s)",
                "M = 10 g, k = 1.5×10⁴ N/m",
            ],
        ),
    ];
    for (which, titles) in expected {
        let svg = svg::render(&which.data(&base).unwrap()).unwrap();
        let texts = svg_texts(&svg);
        for title in titles {
            assert!(
                texts.iter().any(|t| t.trim() == *title),
                "{}: {title} missing",
                which.name()
            );
        }
    }
}

#[test]
fn svg_is_written_atomically_or_not_at_all() {
    let dir = std::env::temp_dir().join(format!("snapback-svg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fig = Which::Fig3.data(&Params::default()).unwrap();
    let path = dir.join("fig3.svg");
    svg::write(&fig, &path, Replace::Writable).unwrap();
    svg_texts(&std::fs::read_to_string(&path).unwrap());
    let leftovers = std::fs::read_dir(&dir).unwrap().count();
    assert_eq!(leftovers, 1);
    let err = svg::write(&fig, &dir.join("missing").join("x.svg"), Replace::Writable).unwrap_err();
    assert!(err.to_string().contains("missing"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}
