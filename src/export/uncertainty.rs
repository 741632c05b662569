//! The spread of outcomes from uncertain inputs (Monte Carlo), as a table section and as JSON.

use std::fmt::Write;

use serde_json::{Map, Value, json};

use crate::analysis::uncertainty::{Bands, Spread};
use crate::model::params::spec;
use crate::model::units;

/// JSON: `samples`, `seed`, `inputs` {key: sigma in SI}, `outcomes` {name: {mean, sd}} (null where no
/// draw defines the outcome).
pub fn json(spreads: &[Spread], bands: &Bands) -> Value {
    let inputs: Map<String, Value> = spreads
        .iter()
        .map(|s| (spec(s.id).key.to_string(), Value::from(s.sigma)))
        .collect();
    let outcomes: Map<String, Value> = bands
        .bands
        .iter()
        .map(|b| {
            let value = if b.count == 0 {
                Value::Null
            } else {
                json!({"mean": b.mean, "sd": b.sd})
            };
            (b.quantity.name().to_string(), value)
        })
        .collect();
    json!({"samples": bands.samples, "seed": bands.seed, "inputs": inputs, "outcomes": outcomes})
}

/// `doc` (a pretty JSON object ending in `}\n`) with `key` added last, the other keys left in order.
pub fn append_key(doc: &str, key: &str, value: &Value) -> String {
    let body = doc.trim_end().strip_suffix('}').expect("a JSON object");
    let inner = serde_json::to_string_pretty(value)
        .expect("a value serializes")
        .replace('\n', "\n  ");
    format!("{},\n  \"{key}\": {inner}\n}}\n", body.trim_end())
}

/// The table section: the uncertain inputs, then each outcome's mean and standard deviation.
pub fn table(spreads: &[Spread], bands: &Bands) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nUncertainty (Monte Carlo, {} draws, seed {})",
        bands.samples, bands.seed
    );
    for s in spreads {
        let p = spec(s.id);
        let sigma = units::in_unit(s.sigma, p.dimension, p.display_unit);
        let _ = writeln!(
            out,
            "  {:<24}± {} {}",
            format!("{} {}", p.label, p.symbol),
            units::brief(sigma, 4),
            p.display_unit
        );
    }
    for b in &bands.bands {
        let name = match b.quantity.unit() {
            "" => b.quantity.name().to_string(),
            unit => format!("{} ({unit})", b.quantity.name()),
        };
        let shown = if b.count == 0 {
            "undefined in every draw".to_string()
        } else {
            format!("{} ± {}", units::brief(b.mean, 5), units::brief(b.sd, 3))
        };
        let _ = writeln!(out, "  {name:<24}{}", shown.trim_end());
    }
    out
}
