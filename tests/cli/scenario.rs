//! Presets and scenario files: every preset loads and solves, save then load gives identical parameters,
//! each kind of bad file names the file, the line and the key, and the command line applies them.

use crate::support::bin;

use assert_cmd::Command;
use snapback::config::preset;
use snapback::model::{Params, solve};
use snapback::scenario::{PRESETS, Scenario, ScenarioError};

fn snapback() -> Command {
    bin::snapback()
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("snapback-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn every_preset_loads_and_solves() {
    let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
    for required in [
        "fig3a-heavy-cart",
        "fig3b-light-cart",
        "fig3c-soft-spring",
        "light-1g",
        "light-0.1g",
    ] {
        assert!(names.contains(&required), "missing preset {required}");
    }
    for p in PRESETS {
        let params = p.scenario().apply(Params::default());
        let bounce = solve(&params).unwrap_or_else(|e| panic!("{}: {e}", p.name));
        assert!(bounce.outcome.omega2.is_finite());
    }
}

#[test]
fn the_papers_presets_reproduce_the_papers_spins() {
    let spin = |name: &str| {
        solve(&preset(name).unwrap().apply(Params::default()))
            .unwrap()
            .outcome
            .omega2
    };
    assert_eq!(
        preset("fig3c-soft-spring")
            .unwrap()
            .apply(Params::default()),
        Params::default()
    );
    assert!((spin("light-1g") - 216.0).abs() < 1.0);
    assert!((spin("light-0.1g") - 223.0).abs() < 1.0);
}

#[test]
fn save_then_load_gives_identical_parameters() {
    let dir = temp_dir("roundtrip");
    let awkward = Params {
        angle_deg: 47.123456789012345,
        spin: -955.0 * std::f64::consts::PI / 30.0,
        cart_mass: 1.0 / 3.0 * 1e-3,
        stiffness: 12345.678901234567,
        duration: 4.1e-3,
        ..Params::default()
    };
    for params in [Params::default(), awkward] {
        let path = dir.join("what-if.toml");
        Scenario::from_params("what-if", "a test \"quoted\" description", &params)
            .save(&path)
            .unwrap();
        let loaded = Scenario::load(&path).unwrap();
        assert_eq!(loaded.apply(Params::default()), params);
        assert_eq!(loaded.description, "a test \"quoted\" description");
        assert_eq!(loaded.name, "what-if");
    }
    // Nothing but the file itself is left in the directory.
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}

/// Parses `text` as the file `bad.toml` and returns (line, key, message).
fn invalid(text: &str) -> (usize, Option<String>, String) {
    match Scenario::parse(text, "bad.toml") {
        Err(ScenarioError::Invalid {
            origin,
            line,
            key,
            message,
        }) => {
            assert_eq!(origin, "bad.toml");
            (line, key, message)
        }
        other => panic!("expected an invalid-scenario error, got {other:?}"),
    }
}

#[test]
fn bad_files_name_the_line_and_the_key() {
    let (line, _, message) = invalid("description = \"x\"\n[params\nmu = 0.4\n");
    assert_eq!(line, 2, "{message}");

    let (line, key, message) =
        invalid("description = \"x\"\n\n[params]\nmu = 0.4\nfriction = 0.3\n");
    assert_eq!((line, key.as_deref()), (5, Some("friction")));
    assert!(
        message.contains("unknown parameter 'friction'"),
        "{message}"
    );

    let (line, key, message) = invalid("[params]\nangle = \"60 deg\"\ncart_mass = true\n");
    assert_eq!((line, key.as_deref()), (3, Some("cart_mass")));
    assert!(
        message.contains("must be a number or a string with a unit, not boolean"),
        "{message}"
    );

    let (line, key, message) = invalid("[params]\nstiffness = \"15 kg\"\n");
    assert_eq!((line, key.as_deref()), (2, Some("stiffness")));
    assert!(message.contains("unit 'kg' is a mass"), "{message}");

    let (line, key, message) = invalid("[params]\n\n\nangle = \"95 deg\"\n");
    assert_eq!((line, key.as_deref()), (4, Some("angle")));
    assert!(
        message.contains("angle must be in (0, 90] deg; got 95 deg"),
        "{message}"
    );

    let (line, _, message) = invalid("description = \"x\"\ncolour = \"red\"\n");
    assert_eq!(line, 2);
    assert!(message.contains("colour"), "{message}");
}

#[test]
fn error_text_reads_file_line_message() {
    let err = Scenario::parse("[params]\nmu = -1\n", "what-if.toml").unwrap_err();
    assert_eq!(
        err.to_string(),
        "what-if.toml:2: mu must be in [0, inf); got -1"
    );
    let err = preset("no-such-thing").unwrap_err().to_string();
    assert!(
        err.starts_with("unknown preset 'no-such-thing' (known: fig3c-soft-spring,"),
        "{err}"
    );
}

#[test]
fn command_line_applies_preset_then_scenario_then_flags() {
    let dir = temp_dir("cli");
    let path = dir.join("light.toml");
    std::fs::write(
        &path,
        "description = \"light\"\n[params]\ncart_mass = \"1 g\"\nstiffness = \"9.554 kN/m\"\n",
    )
    .unwrap();
    let json = |args: &[&str]| -> serde_json::Value {
        let out = snapback()
            .arg("simulate")
            .args(args)
            .args(["--format", "json"])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let from_file = json(&["--scenario", path.to_str().unwrap()]);
    assert_eq!(from_file["params"]["cart_mass"].as_f64(), Some(0.001));
    let overridden = json(&["--scenario", path.to_str().unwrap(), "--cart-mass", "2g"]);
    assert_eq!(overridden["params"]["cart_mass"].as_f64(), Some(0.002));
    assert_eq!(overridden["params"]["stiffness"].as_f64(), Some(9554.0));
    let preset = json(&["--preset", "fig3a-heavy-cart"]);
    assert_eq!(preset["params"]["cart_mass"].as_f64(), Some(10.0));
}

#[test]
fn command_line_rejects_bad_scenarios_with_status_2() {
    let dir = temp_dir("bad-cli");
    let path = dir.join("broken.toml");
    std::fs::write(&path, "[params]\ncart_mass = \"-1 g\"\n").unwrap();
    let out = snapback()
        .args(["simulate", "--scenario", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("broken.toml:2: cart_mass must be in (0, inf) kg; got -1 g"),
        "{err}"
    );

    let out = snapback()
        .args(["simulate", "--scenario", "/no/such/file.toml"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8(out.stderr)
            .unwrap()
            .contains("/no/such/file.toml")
    );

    let out = snapback()
        .args(["simulate", "--preset", "fig9"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8(out.stderr)
            .unwrap()
            .contains("unknown preset 'fig9'")
    );
}

#[test]
fn presets_command_lists_every_preset() {
    let out = snapback().arg("presets").output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for p in PRESETS {
        assert!(text.contains(p.name), "{}", p.name);
        assert!(text.contains(&p.scenario().description));
    }
    let out = snapback()
        .args(["presets", "--format", "json"])
        .output()
        .unwrap();
    let list: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(list.as_array().unwrap().len(), PRESETS.len());
    assert!(list[0]["params"]["cart_mass"].is_number());
}
