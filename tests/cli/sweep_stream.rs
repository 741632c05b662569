//! `sweep`'s streamed output: JSON and JSON Lines with the CSV's keys, in constant memory, and swept
//! values computed from the ends and the index (no float noise, no overflow).

use crate::support::bin;

use std::io::Read;
use std::process::Stdio;

use snapback::analysis::Span;
use snapback::analysis::sweep::{self, Layout};
use snapback::model::{Params, SolveOptions};

fn written(span: &Span, steps: usize, layout: Layout) -> String {
    let mut out = Vec::new();
    sweep::write(
        &mut out,
        &Params::default(),
        span,
        steps,
        layout,
        &SolveOptions::default(),
    )
    .unwrap();
    String::from_utf8(out).unwrap()
}

fn sweep_cli(args: &[&str]) -> String {
    let out = bin::command().arg("sweep").args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The first column of a CSV sweep: the swept values as printed.
fn swept_values(csv: &str) -> Vec<&str> {
    csv.lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect()
}

#[test]
fn streamed_json_is_the_pretty_array_of_the_rows() {
    let span = Span::parse("angle", "10", "90", false).unwrap();
    let steps = 70_000; // more than one block, many chunks
    let rows = sweep::sweep(&Params::default(), &span, steps).unwrap();
    let objects = rows.iter().map(|r| sweep::object("angle_deg", r)).collect();
    let mut expected = serde_json::to_string_pretty(&serde_json::Value::Array(objects)).unwrap();
    expected.push('\n');
    assert_eq!(written(&span, steps, Layout::Json), expected);
}

#[test]
fn json_lines_hold_one_object_per_row_with_the_csv_keys() {
    let span = Span::parse("cart-mass", "0.1g", "1kg", true).unwrap();
    let csv = written(&span, 9, Layout::Csv);
    let mut header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    header.sort_unstable();
    let lines = written(&span, 9, Layout::JsonLines);
    let rows = sweep::sweep(&Params::default(), &span, 9).unwrap();
    assert_eq!(lines.lines().count(), 9);
    for (line, row) in lines.lines().zip(&rows) {
        let object: serde_json::Value = serde_json::from_str(line).unwrap();
        let keys: Vec<&str> = object
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        assert_eq!(keys, header);
        assert_eq!(object, sweep::object("cart_mass_kg", row));
    }
    assert_eq!(
        sweep_cli(&[
            "--vary",
            "cart-mass",
            "--from",
            "0.1g",
            "--to",
            "1kg",
            "--steps",
            "9",
            "--log",
            "--format",
            "jsonl"
        ]),
        lines
    );
}

#[test]
fn swept_values_print_without_float_noise() {
    let csv = sweep_cli(&[
        "--vary", "angle", "--from", "0.1", "--to", "90", "--steps", "900",
    ]);
    let values = swept_values(&csv);
    assert_eq!(values.len(), 900);
    for (i, value) in values.iter().enumerate() {
        let tenths = i + 1;
        let expected = if tenths % 10 == 0 {
            (tenths / 10).to_string()
        } else {
            format!("{}.{}", tenths / 10, tenths % 10)
        };
        assert_eq!(*value, expected);
    }
    let log = sweep_cli(&[
        "--vary",
        "stiffness",
        "--from",
        "100",
        "--to",
        "1MN/m",
        "--steps",
        "5",
        "--log",
    ]);
    let values = swept_values(&log);
    assert_eq!(values, ["100", "1000", "10000", "100000", "1000000"]);
    // A value that is no short decimal keeps every digit.
    let thirds = sweep_cli(&["--vary", "mu", "--from", "0", "--to", "1", "--steps", "4"]);
    let values = swept_values(&thirds);
    assert_eq!(
        values,
        ["0", "0.3333333333333333", "0.6666666666666666", "1"]
    );
}

#[test]
fn the_widest_span_sweeps_without_overflow() {
    let csv = sweep_cli(&[
        "--vary", "spin", "--from", "-1e308", "--to", "1e308", "--steps", "3",
    ]);
    let values = swept_values(&csv);
    assert_eq!(values, ["-1e308", "0", "1e308"]);
    let span = Span::parse("spin", "-1.7e308", "1.7e308", false).unwrap();
    let values = span.values(1001);
    assert!(values.iter().all(|v| v.is_finite()));
    assert!(values.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(values[500], 0.0);
}

/// The peak resident memory of `snapback ARGS` in kB, read from /proc while its output is drained.
#[cfg(target_os = "linux")]
fn peak_memory_kb(args: &[&str]) -> (u64, usize) {
    let mut child = bin::command()
        .args(args)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let status = format!("/proc/{}/status", child.id());
    let mut stdout = child.stdout.take().unwrap();
    let (mut peak, mut bytes, mut buffer) = (0, 0, vec![0; 1 << 16]);
    loop {
        let n = stdout.read(&mut buffer).unwrap();
        if n == 0 {
            break;
        }
        bytes += n;
        let hwm = std::fs::read_to_string(&status).ok().and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("VmHWM:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        });
        peak = peak.max(hwm.unwrap_or(0));
    }
    assert!(child.wait().unwrap().success());
    (peak, bytes)
}

#[cfg(target_os = "linux")]
#[test]
#[ignore = "slow"]
fn a_million_row_json_sweep_streams_in_constant_memory() {
    let (peak, bytes) = peak_memory_kb(&[
        "sweep", "--vary", "angle", "--from", "0.1", "--to", "90", "--steps", "1000000",
        "--format", "json",
    ]);
    assert!(bytes > 200_000_000, "{bytes} bytes");
    assert!(
        peak > 0 && peak < 64 * 1024,
        "peak resident memory {peak} kB"
    );
}
