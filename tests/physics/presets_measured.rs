//! Presets calibrated on a measurement reproduce each number their `source` cites within 10%; the
//! presets that cite none say so, and the superball preset shows the limit its description states.

use snapback::model::solve;
use snapback::scenario;

/// A preset, the measured number its source cites (as the source writes it) and the model's value.
fn check(name: &str, cited: &str, measured: f64, model: impl Fn(&snapback::model::Bounce) -> f64) {
    let preset = scenario::preset(name).unwrap();
    assert!(
        preset.source.contains(cited),
        "{name}'s source does not cite {cited}: {}",
        preset.source
    );
    let bounce = solve(&preset.apply(Default::default())).unwrap();
    let value = model(&bounce);
    let off = value / measured - 1.0;
    eprintln!(
        "{name}: {cited} measured, model {value:.4} ({:+.1}%)",
        off * 100.0
    );
    assert!(
        off.abs() <= 0.10,
        "{name}: model {value} against {measured}"
    );
}

fn rpm(b: &snapback::model::Bounce) -> f64 {
    b.outcome.omega2 * 30.0 / std::f64::consts::PI
}

#[test]
fn string_presets_reproduce_the_measured_spins() {
    // Lindsey and Cross, 'String Movement and Spin': clamped racquet, 56 mph, 40 deg from the normal,
    // -3820 rpm; average spin out of eight polyester and four nylon tests.
    check("polyester-strings", "1687 rpm", 1687.0, rpm);
    check("nylon-strings", "1403 rpm", 1403.0, rpm);
    let spin = |name: &str| {
        let p = scenario::preset(name).unwrap().apply(Default::default());
        rpm(&solve(&p).unwrap())
    };
    // The measured ratio, polyester 20% above nylon.
    let ratio = spin("polyester-strings") / spin("nylon-strings");
    assert!((ratio / 1.202 - 1.0).abs() <= 0.10, "{ratio}");
}

#[test]
fn uncalibrated_presets_say_so() {
    for name in ["billiard-cushion", "golf-compliant-face"] {
        let preset = scenario::preset(name).unwrap();
        assert!(
            preset
                .description
                .contains("not calibrated on a measurement"),
            "{name}"
        );
        assert!(
            preset.source.contains("No published measurement is cited"),
            "{name}"
        );
    }
    // The superball ends rolling (e_x = 0), as its description says, unlike the measured ball.
    let p = scenario::preset("superball-rigid-floor")
        .unwrap()
        .apply(Default::default());
    let ex = solve(&p).unwrap().outcome.ex.unwrap();
    assert!(ex.abs() < 0.01, "{ex}");
}
