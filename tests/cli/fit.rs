//! `snapback fit`: recovery of known parameters from synthetic data, the coverage of its 95% intervals,
//! and its command line (formats, errors).

use crate::support::bin;

use crate::support::rng::Rng;

use assert_cmd::Command;
use levenberg_marquardt::LevenbergMarquardt;
use predicates::prelude::*;
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use snapback::analysis::fit::data::{Dataset, Measurement, Quantity, Row};
use snapback::analysis::fit::problem::{Model, Problem};
use snapback::analysis::fit::watch::{Tally, Watch};
use snapback::analysis::fit::{self, Fit, Options, Verdict, free};
use snapback::model::{ParamId, Params, solve};

/// The truth the synthetic data are made from: Fig. 3(c) with a 5 g cart on 12 kN/m and mu = 0.35.
fn truth() -> Params {
    Params {
        cart_mass: 0.005,
        stiffness: 12_000.0,
        mu: 0.35,
        ..Params::default()
    }
}

/// Standard deviation of the synthetic noise on omega2, rad/s.
const SIGMA: f64 = 3.0;

/// omega2 at angles 20..80 deg by 10 and spins 0 and -100 rad/s, from `truth()` plus normal noise of
/// SIGMA drawn from `seed`; each row carries SIGMA when `with_sigma`.
fn synthetic(seed: u64, with_sigma: bool) -> Dataset {
    let mut rng = StdRng::seed_from_u64(seed);
    let noise = Normal::new(0.0, SIGMA).unwrap();
    let mut rows = Vec::new();
    for spin in [0.0, -100.0] {
        for angle in (2..=8).map(|a| f64::from(a) * 10.0) {
            let conditions = vec![(ParamId::Angle, angle), (ParamId::Spin, spin)];
            let row = Row {
                line: rows.len() + 2,
                group: None,
                conditions,
                measured: Vec::new(),
            };
            let omega2 = solve(&row.params(&truth())).unwrap().outcome.omega2;
            rows.push(Row {
                measured: vec![Measurement {
                    quantity: Quantity::Omega2,
                    value: omega2 + noise.sample(&mut rng),
                    sigma: with_sigma.then_some(SIGMA),
                }],
                ..row
            });
        }
    }
    Dataset {
        origin: format!("synthetic-{seed}"),
        rows,
        conditions: vec![ParamId::Angle, ParamId::Spin],
        absolute_sigma: with_sigma,
        groups: Vec::new(),
    }
}

/// A lab's data set as the issue describes it: a light cart on a spring, omega2 at 8 angles from 15 to
/// 85 deg, two speeds (5 and 10 m/s) and two spins (0 and -100 rad/s): 32 rows. The noise drawn from
/// `seed` has standard deviation SIGMA; the rows carry `stated` as their sigma (SIGMA when honest), in
/// group `group_of(row index)` when there are `groups`.
struct Lab {
    truth: Params,
    seed: u64,
    stated: f64,
}

impl Lab {
    fn honest(truth: Params, seed: u64) -> Lab {
        Lab {
            truth,
            seed,
            stated: SIGMA,
        }
    }

    fn rows(&self, group: Option<usize>, truth: &Params, rng: &mut StdRng) -> Vec<Row> {
        let noise = Normal::new(0.0, SIGMA).unwrap();
        let mut rows = Vec::new();
        for speed in [5.0, 10.0] {
            for spin in [0.0, -100.0] {
                for i in 0..8 {
                    let mut row = Row {
                        line: 0,
                        group,
                        conditions: vec![
                            (ParamId::Angle, 15.0 + 10.0 * f64::from(i)),
                            (ParamId::Speed, speed),
                            (ParamId::Spin, spin),
                        ],
                        measured: Vec::new(),
                    };
                    let omega2 = solve(&row.params(truth)).unwrap().outcome.omega2;
                    row.measured.push(Measurement {
                        quantity: Quantity::Omega2,
                        value: omega2 + noise.sample(rng),
                        sigma: Some(self.stated),
                    });
                    rows.push(row);
                }
            }
        }
        rows
    }

    fn data(&self) -> Dataset {
        let mut rng = StdRng::seed_from_u64(self.seed);
        let rows = self.rows(None, &self.truth, &mut rng);
        dataset(rows, Vec::new())
    }
}

/// The rows numbered as lines of a file from 2, in a data set with the lab's conditions.
fn dataset(mut rows: Vec<Row>, groups: Vec<String>) -> Dataset {
    for (i, row) in rows.iter_mut().enumerate() {
        row.line = i + 2;
    }
    Dataset {
        origin: "lab".into(),
        rows,
        conditions: vec![ParamId::Angle, ParamId::Speed, ParamId::Spin],
        absolute_sigma: true,
        groups,
    }
}

/// The light cart of the account: 2 g on 20 kN/m, mu 0.5, about 5 half-periods of the cart in
/// the 5 ms contact.
fn light_cart() -> Params {
    Params {
        cart_mass: 0.002,
        stiffness: 20_000.0,
        mu: 0.5,
        ..Params::default()
    }
}

fn fit_three(data: &Dataset) -> Fit {
    let free = free::parse_list("cart-mass,stiffness,mu", &data.conditions).unwrap();
    // The fit starts from the defaults (10 g, 15 kN/m, 0.4), not from the truth.
    fit::fit(&Params::default(), &free, data, &Options::default()).unwrap()
}

/// Whether each fitted parameter's Wald and profile 95% intervals hold `truth` (an open side reaches
/// the end of the range; a parameter the data cannot determine has no Wald interval, which claims
/// nothing and so counts as holding it).
fn covered(fit: &Fit, truth: &Params) -> Vec<(bool, bool)> {
    fit.free
        .iter()
        .map(|f| {
            let t = truth.get(f.id);
            let wald = f.ci95.is_none_or(|(lo, hi)| (lo..=hi).contains(&t));
            let (lo, hi) = f.profile95.expect("profiles are computed by default");
            let profile = lo.is_none_or(|lo| lo <= t) && hi.is_none_or(|hi| t <= hi);
            (wald, profile)
        })
        .collect()
}

#[test]
fn a_fit_recovers_known_parameters_within_their_intervals() {
    for with_sigma in [true, false] {
        let fit = fit_three(&synthetic(1, with_sigma));
        assert!(fit.converged, "{fit:?}");
        assert_eq!(fit.dof, 11);
        assert!(
            covered(&fit, &truth()).iter().all(|&(w, p)| w && p),
            "{:?}",
            fit.free
        );
        for f in &fit.free {
            let se = f.stderr.unwrap();
            // The data determine each to better than a quarter: a real recovery, not a wide interval.
            assert!(se < 0.25 * f.value, "{f:?}");
            // The profile interval is closed and holds the value.
            let (lo, hi) = f.profile95.unwrap();
            assert!(lo.unwrap() < f.value && f.value < hi.unwrap(), "{f:?}");
        }
        // Noise of SIGMA: the residuals scatter by about SIGMA.
        let spread = if with_sigma { fit.rms * SIGMA } else { fit.rms };
        assert!((0.5 * SIGMA..2.0 * SIGMA).contains(&spread), "{}", fit.rms);
        let verdict = if with_sigma {
            Verdict::Consistent
        } else {
            Verdict::Unjudged
        };
        assert_eq!(fit.verdict, verdict);
        assert_eq!(fit.p_value.is_some(), with_sigma);
    }
}

/// chi2 at the end of a plain local Levenberg-Marquardt run from the defaults: what a fit without a
/// global search finds.
fn local_chi2(data: &Dataset) -> f64 {
    let free = free::parse_list("cart-mass,stiffness,mu", &data.conditions).unwrap();
    let watch = Watch::none();
    let tally = Tally::new(&watch);
    let model = Model {
        base: Params::default(),
        free: &free,
        data,
        phase_limit: None,
        swing_limit: None,
        tally: &tally,
    };
    let start = free::coordinates(&Params::default(), &free);
    let (problem, _) = LevenbergMarquardt::new().minimize(Problem::new(&model, &start));
    model.chi2(&problem.u)
}

/// The light cart on a spring: a local search from the defaults stops in a second minimum with
/// chi2/dof far above 1; the global search reaches the minimum found from the truth (chi2/dof near 1),
/// its intervals hold the truth, and it names the other minima it found.
#[test]
fn the_global_search_finds_the_minimum_a_local_search_misses() {
    let data = Lab::honest(light_cart(), 7).data();
    let fit = fit_three(&data);
    let dof = fit.dof as f64;
    let local = local_chi2(&data);
    eprintln!(
        "light cart: local chi2/dof {:.2}, global {:.2}",
        local / dof,
        fit.chi2 / dof
    );
    assert!(local / dof > 3.0, "{local}");
    assert!(fit.chi2 / dof < 1.5, "{fit:?}");
    assert_eq!(fit.verdict, Verdict::Consistent);
    assert!(
        covered(&fit, &light_cart()).iter().all(|&(_, p)| p),
        "{:?}",
        fit.free
    );
    // The minima are distinct, best first, the fit's the first.
    assert_eq!(fit.minima[0].chi2, fit.chi2);
    assert!(fit.minima.windows(2).all(|w| w[0].chi2 <= w[1].chi2));
    // Reproducible: the same seed gives the same fit.
    assert_eq!(fit, fit_three(&data));
}

#[test]
fn understated_sigmas_and_outliers_get_a_poor_verdict_and_honest_data_a_consistent_one() {
    let honest = fit_three(&Lab::honest(truth(), 3).data());
    assert_eq!(honest.verdict, Verdict::Consistent, "{:?}", honest.p_value);
    assert!(honest.p_value.unwrap() >= 1e-3);
    assert!(honest.outliers().is_empty(), "{:?}", honest.outliers());
    let understated = Lab {
        stated: SIGMA / 3.0,
        ..Lab::honest(truth(), 3)
    };
    let fit = fit_three(&understated.data());
    assert_eq!(fit.verdict, Verdict::Poor);
    assert!(fit.p_value.unwrap() < 1e-3);
    // Three gross outliers (12 sigma) are named by their line (beside rows they pull off the model).
    let mut data = Lab::honest(truth(), 3).data();
    for i in [4, 13, 27] {
        data.rows[i].measured[0].value += 12.0 * SIGMA;
    }
    let fit = fit_three(&data);
    assert_eq!(fit.verdict, Verdict::Poor);
    assert!(fit.p_value.unwrap() < 1e-3);
    let lines: Vec<usize> = fit.outliers().iter().map(|o| o.0).collect();
    assert!([6, 15, 29].iter().all(|l| lines.contains(l)), "{lines:?}");
}

/// Truths drawn across the box (masses 1 to 50 g and stiffnesses 2 to 100 kN/m log-uniformly, mu 0.2
/// to 0.7 uniformly), one lab data set each; how often each parameter's Wald and profile intervals hold
/// the truth, over `sets` sets.
fn coverage(sets: u64) -> ([usize; 3], [usize; 3]) {
    let mut draw = Rng(0x05ee_df17);
    let (mut wald, mut profile) = ([0usize; 3], [0usize; 3]);
    for seed in 0..sets {
        let truth = Params {
            cart_mass: draw.log_uniform(0.001, 0.050),
            stiffness: draw.log_uniform(2_000.0, 100_000.0),
            mu: draw.uniform(0.2, 0.7),
            ..Params::default()
        };
        let fit = fit_three(&Lab::honest(truth, 100 + seed).data());
        for (i, (w, p)) in covered(&fit, &truth).into_iter().enumerate() {
            wald[i] += usize::from(w);
            profile[i] += usize::from(p);
        }
    }
    (wald, profile)
}

/// Over 200 seeded truths across the box the profile intervals (the kind the guide recommends) of each
/// of the three parameters hold the truth 90 to 98% of the time; the Wald intervals' coverage is printed.
#[test]
#[ignore = "slow"]
fn profile_intervals_cover_random_truths_90_to_98_percent_of_the_time() {
    const SETS: u64 = 200;
    let (wald, profile) = coverage(SETS);
    eprintln!(
        "coverage of {SETS} truths (cart_mass, stiffness, mu): profile {profile:?}, Wald {wald:?}"
    );
    for hit in profile {
        let rate = hit as f64 / SETS as f64;
        assert!((0.90..=0.98).contains(&rate), "profile {profile:?}");
    }
}

/// The quick version: over 6 truths, at most 2 of the 18 profile intervals miss.
#[test]
fn profile_intervals_cover_a_few_random_truths() {
    const SETS: u64 = 6;
    let (wald, profile) = coverage(SETS);
    eprintln!(
        "coverage of {SETS} truths (cart_mass, stiffness, mu): profile {profile:?}, Wald {wald:?}"
    );
    assert!(profile.iter().sum::<usize>() >= 16, "profile {profile:?}");
}

/// Three string beds that differ only in mu, the cart shared: a fit of one mu per group and a shared
/// stiffness recovers each within its intervals (the 95% intervals, of which one in twenty may miss, hold
/// at least 3 of the 4; each value lies within 3 standard errors).
#[test]
fn a_grouped_fit_recovers_each_groups_value() {
    let mus = [0.3, 0.45, 0.6];
    let lab = Lab::honest(truth(), 11);
    let mut rng = StdRng::seed_from_u64(lab.seed);
    let rows = mus
        .iter()
        .enumerate()
        .flat_map(|(g, &mu)| lab.rows(Some(g), &Params { mu, ..truth() }, &mut rng))
        .collect();
    let labels = ["nylon", "gut", "polyester"].map(String::from).to_vec();
    let data = dataset(rows, labels.clone());
    let free = free::parse_lists("stiffness", "mu", &data.conditions, 3).unwrap();
    // From the default stiffness and mu, the cart's mass as in the truth.
    let base = Params {
        cart_mass: truth().cart_mass,
        ..Params::default()
    };
    let fit = fit::fit(&base, &free, &data, &Options::default()).unwrap();
    assert_eq!(fit.groups, labels);
    assert_eq!(fit.free.len(), 4);
    assert_eq!(fit.verdict, Verdict::Consistent, "{:?}", fit.p_value);
    // Each within 3 standard errors; a 95% interval may miss now and then, so 3 of the 4 must hold it.
    let mut held = 0;
    for f in &fit.free {
        let t = match f.group {
            Some(g) => mus[g],
            None => truth().stiffness,
        };
        let se = f.stderr.unwrap();
        let value = f.value;
        assert!((value - t).abs() < 3.0 * se, "{f:?}");
        let (lo, hi) = f.ci95.unwrap();
        let (plo, phi) = f.profile95.unwrap();
        held += usize::from(lo <= t && t <= hi && plo.unwrap() <= t && t <= phi.unwrap());
    }
    assert!(held >= 3, "{:?}", fit.free);
}

fn snapback() -> Command {
    bin::snapback()
}

const DATA: &str = "# synthetic\nangle,spin,omega2,sigma_omega2\n20,0,135.6,3\n30,0,195.7,3\n40,0,223.5,3\n\
    50,0,214.4,3\n60,0,174.8,3\n70,0,122.5,3\n80,0,60.5,3\n20,-100rad/s,27.5,3\n30,-100,91.3,3\n\
    40,-100,151.9,3\n50,-100,172.6,3\n60,-100,178.7,3\n70,-100,135.2,3\n80,-955rpm,78.1,3\n";

#[test]
fn json_has_the_promised_keys() {
    let out = snapback()
        .args(["fit", "--data", "-", "--free", "cart-mass,stiffness,mu"])
        .args(["--format", "json"])
        .write_stdin(DATA)
        .assert()
        .success();
    let doc: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    for key in ["cart_mass", "stiffness", "mu"] {
        let p = &doc["free"][key];
        let (lo, hi) = (
            p["ci95"][0].as_f64().unwrap(),
            p["ci95"][1].as_f64().unwrap(),
        );
        let value = p["value"].as_f64().unwrap();
        assert!(
            lo < value && value < hi && p["stderr"].as_f64().unwrap() > 0.0,
            "{p}"
        );
    }
    assert_eq!(doc["dof"], 11);
    assert_eq!(doc["converged"], true);
    assert!(doc["chi2"].as_f64().unwrap() > 0.0 && doc["rms"].as_f64().unwrap() > 0.0);
    assert_eq!(doc["correlation"].as_array().unwrap().len(), 3);
    assert_eq!(doc["correlation"][1][1], 1.0);
    let rows = doc["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 14);
    let first = &rows[0];
    let (m, y, r) = (
        first["measured"]["omega2"].as_f64().unwrap(),
        first["model"]["omega2"].as_f64().unwrap(),
        first["residual"]["omega2"].as_f64().unwrap(),
    );
    assert_eq!(m, 135.6);
    assert!((y - m - r).abs() < 1e-12);
}

#[test]
fn bad_data_name_file_line_and_column_and_exit_2() {
    let dir = std::env::temp_dir().join(format!("snapback-fit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.csv");
    for (text, message) in [
        (
            "angle,omega9\n40,1\n",
            "bad.csv:1:2: unknown column 'omega9'",
        ),
        (
            "angle,omega2\n40,1\n50\n",
            "bad.csv:3:2: missing value for omega2",
        ),
        ("angle,omega2\n40,1\n4o,2\n", "bad.csv:3:1: angle: "),
        (
            "angle,omega2\n40,1.2.3\n",
            "bad.csv:2:2: '1.2.3' is not a number",
        ),
    ] {
        std::fs::write(&path, text).unwrap();
        let out = snapback()
            .args(["fit", "--free", "mu", "--data"])
            .arg(&path)
            .assert()
            .code(2);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(
            stderr.starts_with("error: ") && stderr.contains(message),
            "{stderr}"
        );
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn too_few_rows_are_refused() {
    snapback()
        .args(["fit", "--data", "-", "--free", "cart-mass,stiffness,mu"])
        .write_stdin("angle,omega2\n40,100\n50,120\n")
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "2 measurements cannot determine 3 free parameters",
        ));
}

#[test]
fn a_parameter_the_data_cannot_determine_is_named_not_nan() {
    // A rigid ball ignores its damping: nothing in the data depends on it.
    let out = snapback()
        .args(["fit", "--data", "-", "--free", "mu,ball-damping"])
        .write_stdin(DATA)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(
        text.contains("the data cannot determine ball-damping"),
        "{text}"
    );
    assert!(!text.to_lowercase().contains("nan"), "{text}");
    let out = snapback()
        .args([
            "fit",
            "--data",
            "-",
            "--free",
            "mu,ball-damping",
            "--format",
            "json",
        ])
        .write_stdin(DATA)
        .assert()
        .success();
    let doc: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert_eq!(doc["undetermined"], serde_json::json!(["ball_damping"]));
    assert!(doc["free"]["ball_damping"]["stderr"].is_null());
    assert!(doc["free"]["mu"]["stderr"].as_f64().unwrap() > 0.0);
    assert_eq!(doc["converged"], false);
}

#[test]
fn json_has_the_verdict_the_minima_the_profile_and_what_was_assumed() {
    let out = snapback()
        .args(["fit", "--data", "-", "--free", "cart-mass,stiffness,mu"])
        .args(["--format", "json", "--speed", "10"])
        .write_stdin(DATA)
        .assert()
        .success();
    let doc: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert_eq!(doc["verdict"], "consistent");
    let p = doc["p_value"].as_f64().unwrap();
    assert!((1e-3..=1.0).contains(&p), "{p}");
    let minima = doc["minima"].as_array().unwrap();
    assert_eq!(minima[0]["chi2"], doc["chi2"]);
    assert_eq!(minima[0]["values"]["mu"], doc["free"]["mu"]["value"]);
    for key in ["cart_mass", "stiffness", "mu"] {
        let p = &doc["free"][key];
        let value = p["value"].as_f64().unwrap();
        let (lo, hi) = (
            p["profile95"][0].as_f64().unwrap(),
            p["profile95"][1].as_f64().unwrap(),
        );
        assert!(lo < value && value < hi, "{p}");
        assert_eq!(p["poorly_determined"], false);
    }
    // The speed came from its flag: no column sets it.
    assert_eq!(doc["assumed"], serde_json::json!({"speed": 10.0}));
    assert_eq!(doc["assumed_from"]["speed"], "from --speed");
    assert_eq!(doc["outliers"], serde_json::json!([]));
    assert_eq!(doc["groups"], serde_json::json!({}));
    // Wald only: no profile computed, none reported.
    let out = snapback()
        .args(["fit", "--data", "-", "--free", "mu", "--intervals", "wald"])
        .args(["--format", "json"])
        .write_stdin(DATA)
        .assert()
        .success();
    let doc: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert!(doc["free"]["mu"].get("profile95").is_none());
    assert!(doc["free"]["mu"]["ci95"].is_array());
}

#[test]
fn a_file_with_a_byte_order_mark_and_no_spin_column_says_which_spin_it_used() {
    let text =
        "\u{feff}angle,omega2,sigma_omega2\n20,135.6,3\n30,195.7,3\n40,223.5,3\n50,214.4,3\n";
    let out = snapback()
        .args(["fit", "--data", "-", "--free", "mu"])
        .write_stdin(text)
        .assert()
        .success();
    let table = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(
        table.contains("4 rows, 4 measurements, 1 free parameter\n"),
        "{table}"
    );
    assert!(
        table.contains("spin not in the data: -100 rad/s for every row, from the default"),
        "{table}"
    );
    assert!(
        table.contains("speed not in the data: 10 m/s for every row, from the default"),
        "{table}"
    );
    assert!(table.contains("verdict: "), "{table}");
}

#[test]
fn label_columns_are_ignored_on_request_and_otherwise_named_as_unknown() {
    let text = "string,angle,omega2\nA,20,135.6\nB,30,195.7\nC,40,223.5\n";
    snapback()
        .args(["fit", "--data", "-", "--free", "mu"])
        .write_stdin(text)
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "<stdin>:1:1: unknown column 'string'",
        ));
    snapback()
        .args(["fit", "--data", "-", "--free", "mu", "--ignore", "string"])
        .write_stdin(text)
        .assert()
        .success();
    snapback()
        .args([
            "fit",
            "--data",
            "-",
            "--free-per-group",
            "mu",
            "--ignore",
            "string",
        ])
        .write_stdin(text)
        .assert()
        .code(2)
        .stderr(predicates::str::contains("--group"));
}

/// The shipped table of Lindsey's measurements: one string-on-string friction per material, the rest of
/// the polyester preset shared; the labels are ignored.
#[test]
fn the_shipped_string_table_fits_one_friction_per_material() {
    let out = snapback()
        .args([
            "fit",
            "--data",
            "assets/data/twu-string-movement-and-spin.csv",
        ])
        .args(["--preset", "polyester-strings", "--group", "material"])
        .args([
            "--ignore",
            "company,string,gauge,tension_lb,angle_article_deg",
        ])
        .args(["--free-per-group", "cart-friction", "--format", "json"])
        .assert()
        .success();
    let doc: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    let groups = doc["groups"].as_object().unwrap();
    let names: Vec<&String> = groups.keys().collect();
    assert_eq!(names, ["gut", "nylon", "polyester"]);
    for (_, g) in groups {
        let f = &g["cart_friction"];
        assert!(f["value"].as_f64().unwrap() >= 0.0, "{f}");
        assert!(f["profile95"].is_array() && f["ci95"].is_array(), "{f}");
    }
    assert_eq!(doc["verdict"], "unjudged");
    assert_eq!(doc["dof"], 11);
}

/// The columns of the table section that starts at the line beginning with `heading`: each heading word
/// in `right` ends where every row's cell ends (counted in characters), however long the labels.
fn aligned(table: &str, heading: &str, right: &[&str]) {
    let lines: Vec<&str> = table.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.starts_with(heading))
        .unwrap_or_else(|| panic!("no {heading:?} in\n{table}"));
    let head: Vec<char> = lines[at].chars().collect();
    let rows: Vec<&str> = lines[at + 1..]
        .iter()
        .take_while(|l| !l.is_empty() && !l.starts_with("  *"))
        .copied()
        .collect();
    assert!(!rows.is_empty(), "{table}");
    for word in right {
        let start = lines[at].find(word).unwrap();
        let end = lines[at][..start].chars().count() + word.chars().count();
        for row in &rows {
            let cells: Vec<char> = row.chars().collect();
            assert!(
                cells[end - 1] != ' ' && cells.get(end).is_none_or(|c| *c == ' '),
                "{word:?} is not aligned in\n{}\n{row}",
                String::from_iter(&head)
            );
        }
    }
}

#[test]
fn a_long_group_label_keeps_the_table_aligned() {
    let table = std::fs::read_to_string("assets/data/twu-string-movement-and-spin.csv")
        .unwrap()
        .replace(",polyester,", ",polyester co-polymère monofilament,");
    let out = snapback()
        .args(["fit", "--data", "-", "--preset", "polyester-strings"])
        .args(["--group", "material", "--free-per-group", "cart-friction"])
        .args([
            "--ignore",
            "company,string,gauge,tension_lb,angle_article_deg",
        ])
        .write_stdin(table)
        .assert()
        .success();
    let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    assert!(
        text.contains("[polyester co-polymère monofilament]"),
        "{text}"
    );
    aligned(&text, "  parameter", &["value", "stderr"]);
    aligned(&text, "   line", &["line", "measured", "model", "residual"]);
}

#[test]
fn a_fit_refused_by_its_cost_limit_names_the_limit() {
    // A 0.1 g cart on 1000 kN/m swings 159 half-periods in the contact: beyond the search's 100.
    snapback()
        .args([
            "fit",
            "--data",
            "assets/data/synthetic-strings.csv",
            "--free",
            "mu",
        ])
        .args(["--cart-mass", "0.1g", "--stiffness", "1000kN/m"])
        .assert()
        .code(2)
        .stderr(
            predicates::str::contains("cannot be solved at any starting point (line 4:")
                .and(predicates::str::contains("159 half-periods"))
                .and(predicates::str::contains(
                    "more than the 100 a fit allows while it searches",
                )),
        );
}

#[test]
fn a_bounce_over_the_phase_limit_is_refused_naming_the_limit() {
    let data = synthetic(1, true);
    let free = free::parse_list("mu", &data.conditions).unwrap();
    let watch = Watch::none();
    let tally = Tally::new(&watch);
    let model = Model {
        base: Params::default(),
        free: &free,
        data: &data,
        phase_limit: Some(60),
        swing_limit: Some(100.0),
        tally: &tally,
    };
    // A stiff ball chatters on the paper's cart: thousands of phases, refused at the 61st.
    let chattering = Params {
        ball_stiffness: 1e12,
        ..Params::default()
    };
    let why = model.refusal(&chattering, "while it searches").unwrap();
    assert!(
        why.contains("more than 60 times, the most a fit allows while it searches"),
        "{why}"
    );
    assert_eq!(model.refusal(&Params::default(), "while it searches"), None);
}
