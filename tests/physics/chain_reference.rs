//! A reference for the rigid ball on a chain without string friction (on the wall and on a free frame):
//! each bounce of the golden corpus solved again with every transition time polished to the last bit.
//! The solver's own search stops its refinement within a few units in the last place of the crossing; the
//! reference takes the crossing the search found, brackets the very event function the search watched
//! (the slide's slip from its start value, the grip's margin that broke) between two adjacent floats by
//! bisection, and ends the phase at whichever of the two the function is nearer zero. Everything else
//! (the phases' closed forms, the transitions' rules, the outcome and the energy budget) is the solver's.
//!
//! The test checks that the solver's outcome is the reference's to 1e-10 of each field's scale on every
//! such line (they stand within 7.4e-12). With `SNAPBACK_CHAIN_REFERENCE=path` it also writes the reference's lines
//! there, in the corpus's form, so that a change that moves the corpus can be judged against it:
//! `python3 tests/golden/compare.py` measures old and new against these lines.

use std::io::Write as _;
use std::path::PathBuf;

use serde_json::{Value, json};

use super::golden::{params_of, phase_times};
use snapback::model::chain::{ChainMotion, ChainOfMasses, ChainState};
use snapback::model::contact::{Ball, Cause, Contact, Found, Mode};
use snapback::model::driver::run;
use snapback::model::trig::sin_cos;
use snapback::model::{Bounce, Params, Setup, SolveOptions, State, solve};

/// The most the solver's numbers may stand from the reference's, relative to their field's scale (the
/// largest magnitude under the same top-level key, as `compare.py` measures, and at least [`FLOOR`]).
/// The corpus's chain lines stand within 7.4e-12 (an `ex` of 0.011 that leaves nearly rolling), most
/// within 3e-13; a transition found a step away, or a phase too many, stands off by far more.
const AGREEMENT: f64 = 1e-10;

/// The least scale a field is measured against: a frame velocity that is zero to rounding (1e-16 m/s)
/// is measured against a millimetre a second, not against itself.
const FLOOR: f64 = 1e-3;

/// The chain model with every event time the search finds polished to adjacent floats.
struct Polished<'a>(&'a ChainOfMasses);

impl Contact for Polished<'_> {
    type State = ChainState;
    type Motion = ChainMotion;
    type Probe = ();

    fn start(&self, setup: &Setup) -> (ChainState, Mode) {
        self.0.start(setup)
    }

    fn time(state: &ChainState) -> f64 {
        ChainOfMasses::time(state)
    }

    fn contact(state: &ChainState) -> State {
        ChainOfMasses::contact(state)
    }

    fn motion(&self, setup: &Setup, state: &ChainState, mode: Mode) -> ChainMotion {
        self.0.motion(setup, state, mode)
    }

    fn first_event(
        &self,
        setup: &Setup,
        motion: &ChainMotion,
        state: &ChainState,
        mode: Mode,
        cause: Cause,
    ) -> Found<()> {
        let found = self.0.first_event(setup, motion, state, mode, cause);
        let event = found.event.map(|(t, next)| {
            let event = |t: f64| watched(setup, motion, (state.t, mode.0, cause), next, t);
            (polish(event, t, state.t), next)
        });
        Found { event, last: None }
    }

    fn state_at(&self, setup: &Setup, motion: &ChainMotion, t: f64, _: Option<()>) -> ChainState {
        self.0.state_at(setup, motion, t, None)
    }

    fn next(&self, setup: &Setup, state: &mut ChainState, mode: Mode, cause: Cause) -> Mode {
        self.0.next(setup, state, mode, cause)
    }
}

/// The event function the search watched at `t`, as it computes it: a slide's slip in its direction
/// (from its start value when the slide starts on its zero), or the margin of the grip that broke.
fn watched(
    setup: &Setup,
    motion: &ChainMotion,
    (t0, ball, began): (f64, Ball, Cause),
    ended: Cause,
    t: f64,
) -> f64 {
    let contact = motion.contact(setup, t);
    match (ball, ended) {
        (Ball::Slide(dir), _) => {
            let offset = if matches!(began, Cause::SlipZero | Cause::GripBreak(_)) {
                setup.slip(&motion.contact(setup, t0).state)
            } else {
                0.0
            };
            -dir * (setup.slip(&contact.state) - offset)
        }
        (Ball::Grip, Cause::GripBreak(sign)) => {
            let margins = setup.grip_margins_given(
                sin_cos(setup.w * t),
                contact.friction,
                contact.friction_rate,
            );
            margins[usize::from(sign < 0.0)].0
        }
        (Ball::Grip, other) => panic!("a grip ended by {other:?}"),
    }
}

/// The time next to `found` (the search's crossing of `event`, after `t0`) where `event` crosses zero to
/// the last bit: a bracket of adjacent floats, low at most zero and high above it, by bisection; of its
/// two ends, the one where `event` is nearer zero.
fn polish(event: impl Fn(f64) -> f64, found: f64, t0: f64) -> f64 {
    let (mut low, mut high) = (found, found);
    let mut reach = found.next_up() - found;
    if event(found) > 0.0 {
        while event(low) > 0.0 {
            low = (found - reach).max(t0);
            reach *= 2.0;
            assert!(low > t0 || event(low) <= 0.0, "no bracket below {found}");
        }
    } else {
        while event(high) <= 0.0 {
            high = found + reach;
            reach *= 2.0;
            assert!(reach < 1e-6 * found.abs(), "no bracket above {found}");
        }
    }
    while low.next_up() < high {
        let middle = low + 0.5 * (high - low);
        let middle = middle.clamp(low.next_up(), high.next_down());
        if event(middle) > 0.0 {
            high = middle;
        } else {
            low = middle;
        }
    }
    if event(low).abs() < event(high).abs() {
        low
    } else {
        high
    }
}

/// What the golden corpus records of a solved bounce (`golden.rs`), but its refusals and phase names.
fn record(args: &[String], params: &Params, bounce: &Bounce) -> Value {
    let o = &bounce.outcome;
    let e = bounce.energy();
    let f = bounce.final_state;
    let mut line = json!({
        "args": args,
        "omega2": o.omega2,
        "vx2": o.vx2,
        "ex": o.ex,
        "final": [f.x, f.v, f.vx, f.omega],
        "phase_times": phase_times(bounce),
        "energy": {
            "final_ball": e.final_ball,
            "final_cart": e.final_cart,
            "friction_loss": e.friction_loss,
        },
    });
    if params.frame_mass > 0.0 || params.frame_normal_mass > 0.0 {
        line["frame_v"] = json!(bounce.frame_velocity());
        line["energy"]["frame"] = json!(e.frame);
    }
    line
}

/// The bounce of `params` with every transition polished (the solver's bounce with its phases, final
/// state and outcome replaced by the reference's).
fn reference(params: &Params) -> Bounce {
    let mut bounce = solve(params).expect("solved");
    let setup = Setup::new(params);
    let model = ChainOfMasses::new(params, &setup).expect("a chain");
    let mut phases = Vec::new();
    let last = run(
        &Polished(&model),
        &setup,
        &SolveOptions::default(),
        &mut phases,
    )
    .expect("solved");
    let r = setup.r;
    let incoming = setup.vx1 - r * params.spin;
    bounce.outcome.omega2 = last.omega;
    bounce.outcome.vx2 = last.vx;
    bounce.outcome.ex = bounce
        .outcome
        .ex
        .map(|_| -(last.vx - r * last.omega) / incoming);
    bounce.phases = phases;
    bounce.final_state = last;
    bounce
}

/// The largest move of a number between `a` and `b` relative to its scale (`compare.py`'s measure);
/// infinite when their shapes differ.
fn moved(a: &Value, b: &Value, scale: f64) -> f64 {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            if x == y { 0.0 } else { (x - y).abs() / scale }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .map(|(a, b)| moved(a, b, scale))
            .fold(0.0, f64::max),
        (Value::Object(x), Value::Object(y)) if x.len() == y.len() => x
            .iter()
            .map(|(k, v)| y.get(k).map_or(f64::INFINITY, |w| moved(v, w, scale)))
            .fold(0.0, f64::max),
        _ if a == b => 0.0,
        _ => f64::INFINITY,
    }
}

/// The largest magnitude of the numbers in `value`.
fn magnitude(value: &Value) -> f64 {
    match value {
        Value::Number(x) => x.as_f64().unwrap().abs(),
        Value::Array(x) => x.iter().map(magnitude).fold(0.0, f64::max),
        Value::Object(x) => x.values().map(magnitude).fold(0.0, f64::max),
        _ => 0.0,
    }
}

#[test]
fn the_chain_s_transitions_are_the_polished_reference_s() {
    let corpus = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden/bounces.jsonl");
    let text = std::fs::read_to_string(corpus).expect("the golden corpus");
    let mut out = std::env::var_os("SNAPBACK_CHAIN_REFERENCE")
        .map(|path| std::fs::File::create(path).expect("the reference's file"));
    let mut checked = 0;
    for line in text.lines() {
        let golden: Value = serde_json::from_str(line).expect("a JSON line");
        let args: Vec<String> = serde_json::from_value(golden["args"].clone()).expect("args");
        if golden.get("refused").is_some() {
            continue;
        }
        let params = params_of(&args).expect("valid flags");
        if params.chain < 2.0
            || params.stiffness == 0.0
            || params.ball_stiffness > 0.0
            || params.cart_friction > 0.0
        {
            continue;
        }
        let solved = record(&args, &params, &solve(&params).expect("solved"));
        let polished = record(&args, &params, &reference(&params));
        for (key, value) in solved.as_object().unwrap() {
            let scale = magnitude(value).max(FLOOR);
            let distance = moved(value, &polished[key], scale);
            assert!(
                distance <= AGREEMENT,
                "{args:?} {key}: {value} against the reference's {} ({distance:.1e} of its scale)",
                polished[key]
            );
        }
        if let Some(out) = &mut out {
            writeln!(out, "{polished}").expect("written");
        }
        checked += 1;
    }
    assert!(checked >= 100, "{checked} chain lines");
}
