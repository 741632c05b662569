//! `figure` at any parameters: Fig. 3 draws the given bounce beside the paper's other carts, Fig. 2
//! its omega2 against theta1 for its spin and the comparison spin; flags, presets and scenarios all
//! count, and an `--out` it cannot write is refused.

use crate::support::bin;

use std::process::{Output, Stdio};

use snapback::analysis::figures::Which;
use snapback::model::{Params, solve};

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("snapback-figure-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `snapback figure ARGS --out DIR/NAME` with `stdin`, and the SVG written.
fn figure(dir: &std::path::Path, name: &str, args: &[&str], stdin: &str) -> (Output, String) {
    let path = dir.join(name);
    let mut child = bin::command()
        .arg("figure")
        .args(args)
        .arg("--out")
        .arg(&path)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::io::Write::write_all(&mut child.stdin.take().unwrap(), stdin.as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    (out, std::fs::read_to_string(&path).unwrap_or_default())
}

#[test]
fn fig3_draws_the_given_bounce_beside_the_papers_other_carts() {
    let paper = Which::Fig3.data(&Params::default()).unwrap();
    let labels: Vec<&str> = paper.panels[0]
        .curves
        .iter()
        .map(|c| c.label.as_str())
        .collect();
    assert_eq!(
        labels,
        [
            "M = 10 kg, k = 4×10⁴ N/m",
            "M = 10 g, k = 4×10⁴ N/m",
            "M = 10 g, k = 1.5×10⁴ N/m"
        ]
    );
    let given = Params {
        cart_mass: 0.001,
        angle_deg: 45.0,
        ..Params::default()
    };
    let fig = Which::Fig3.data(&given).unwrap();
    assert!(
        fig.title
            .starts_with("Fig. 3: θ1 = 45 deg, ω1 = -100 rad/s"),
        "{}",
        fig.title
    );
    let curves = &fig.panels[2].curves;
    assert_eq!(curves.len(), 4);
    assert_eq!(curves[3].label, "M = 1.00 g, k = 15.00 kN/m");
    let omega_end = solve(&given).unwrap().outcome.omega2;
    assert!((curves[3].points.last().unwrap().1 - omega_end).abs() < 1e-9);
    // The paper's carts take the given angle too.
    let heavy = Params {
        cart_mass: 10.0,
        stiffness: 4e4,
        ..given
    };
    let heavy_end = solve(&heavy).unwrap().outcome.omega2;
    assert!((curves[0].points.last().unwrap().1 - heavy_end).abs() < 1e-9);
}

#[test]
fn fig2_sweeps_the_given_spin_and_the_comparison_spin() {
    let spins = |p: &Params| -> Vec<String> {
        Which::Fig2
            .data(p)
            .unwrap()
            .panels
            .iter()
            .map(|p| p.title.clone())
            .collect()
    };
    assert_eq!(
        spins(&Params::default()),
        ["(a) ω1 = 0 rad/s", "(b) ω1 = -100 rad/s"]
    );
    assert_eq!(
        spins(&Params {
            spin: 0.0,
            ..Params::default()
        }),
        ["(a) ω1 = 0 rad/s", "(b) ω1 = -100 rad/s"]
    );
    let topspin = Params {
        spin: 50.0,
        mu: 0.3,
        ..Params::default()
    };
    assert_eq!(spins(&topspin), ["(a) ω1 = 0 rad/s", "(b) ω1 = 50 rad/s"]);
    let fig = Which::Fig2.data(&topspin).unwrap();
    assert!(fig.title.contains("μ = 0.3"), "{}", fig.title);
    // The given cart's curve (the paper's soft spring here) at 60 deg is the given bounce.
    let (theta, omega2) = fig.panels[1].curves[2].points[599];
    assert_eq!(theta, 60.0);
    assert!((omega2 - solve(&topspin).unwrap().outcome.omega2).abs() < 1e-9);
}

#[test]
fn flags_presets_and_scenarios_change_the_figure() {
    let dir = temp_dir("inputs");
    let (_, default) = figure(&dir, "default.svg", &["fig3"], "");
    let (out, light) = figure(&dir, "light.svg", &["fig3", "--cart-mass", "1g"], "");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_ne!(default, light);
    assert!(light.contains("M = 1.00 g, k = 15.00 kN/m"));
    let (_, preset) = figure(&dir, "preset.svg", &["fig3", "--preset", "light-1g"], "");
    assert!(
        preset.contains("M = 1.00 g, k = 9.55 kN/m"),
        "the preset's cart"
    );
    let (out, piped) = figure(
        &dir,
        "piped.svg",
        &["fig2", "--scenario", "-"],
        "[params]\nspeed = \"12 m/s\"\nchain = 4\n",
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        piped.contains("v1 = 12 m/s, μ = 0.4, N = 4"),
        "the scenario's speed and chain"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_out_it_cannot_write_is_refused_naming_svg() {
    let dir = temp_dir("png");
    for name in ["fig3.png", "fig3", "fig3.svg.pdf"] {
        let (out, written) = figure(&dir, name, &["fig3"], "");
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(err.starts_with("error: --out must end in .svg"), "{err}");
        assert!(
            err.trim_end()
                .ends_with(&format!("got {}", dir.join(name).display())),
            "{err}"
        );
        assert_eq!(err.lines().count(), 1);
        assert!(written.is_empty() && !dir.join(name).exists());
    }
    let (out, _) = figure(&dir, "upper.SVG", &["fig3"], "");
    assert!(out.status.success());
    std::fs::remove_dir_all(&dir).unwrap();
}
