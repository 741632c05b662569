//! The explorer's shot: whether it explores one (shot mode), and the shots played for the shot view, on a
//! worker of their own ([`super::worker`]): the newest request first, queued older ones skipped, and the
//! answers kept by parameters, so that undo and a step back cost nothing.
//!
//! In shot mode the incidence of the bounce (theta1, v1, omega1) is what the strings see: the frame change
//! of [`crate::shot`] sets it from the incoming ball and the racquet ([`strings_params`]), so the contact
//! view shows the bounce on the strings, and the panel shows those three as derived, not to be edited.

use std::sync::Arc;
use std::time::Duration;

use super::solver::Recent;
use super::values::shown;
use super::worker::{Crash, Worker};
use crate::model::Params;
use crate::model::params::{Group, PARAMS, ParamId, ParamSpec, spec};
use crate::shot::racquet::Hold;
use crate::shot::{self, Shot, ShotError};

/// What the status line says when shot mode comes on (the shot view, or m).
pub const MODE_ON: &str = "shot mode (m leaves it): θ1, v1, ω1 and the frame (M_t, M_n) now follow from the racquet and the \
                           incoming ball, and the contact view shows the bounce on the strings";

/// What the status line says when shot mode comes on from a bounce and the shot's start changed
/// `filled` (as [`starting`] says), now at their values in `params`.
pub fn mode_on(filled: &[ParamId], params: &Params) -> String {
    let changed: Vec<String> = filled
        .iter()
        .map(|&id| spec(id))
        .filter(|s| s.group != Group::Shot)
        .map(|s| format!("{} {}", s.symbol, shown(s, params.get(s.id))))
        .collect();
    if changed.is_empty() {
        return MODE_ON.to_string();
    }
    format!(
        "{MODE_ON}; the shot starts as `snapback shot` plays it: {}",
        changed.join(", ")
    )
}

/// What the status line says when m turns shot mode off, `restored` the parameters back from before.
pub fn mode_off(restored: &[ParamId]) -> String {
    format!(
        "shot mode off: the bounce's own {} are back (Tab to the shot view or m turns it on again)",
        symbols(restored)
    )
}

/// `θ1, v1 and ω1`.
fn symbols(ids: &[ParamId]) -> String {
    let names: Vec<&str> = ids.iter().map(|&id| spec(id).symbol).collect();
    match names.split_last() {
        Some((last, [])) => last.to_string(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The parameters a shot starts from when shot mode comes on from a bounce: every parameter still at
/// its default takes the value a shot starts from ([`crate::shot::base`], as `snapback shot` plays),
/// the ones the user changed stay, as flags given to `snapback shot` would; with the ids it changed.
pub fn starting(params: &Params) -> (Params, Vec<ParamId>) {
    let base = shot::base();
    let default = Params::default();
    let mut start = *params;
    let mut filled = Vec::new();
    for s in PARAMS {
        let id = s.id;
        if !derived(id) && params.get(id) == default.get(id) && base.get(id) != default.get(id) {
            start.set(id, base.get(id));
            filled.push(id);
        }
    }
    (start, filled)
}

/// The parameters the frame change sets in a shot: the incidence, and the frame the racquet in the hand
/// is to the strings.
pub const DERIVED: [ParamId; 5] = [
    ParamId::Angle,
    ParamId::Speed,
    ParamId::Spin,
    ParamId::FrameMass,
    ParamId::FrameNormalMass,
];

/// True for a parameter the frame change sets in a shot.
pub fn derived(id: ParamId) -> bool {
    DERIVED.contains(&id)
}

/// `params` with the incidence the strings see and the frame of the racquet
/// ([`crate::shot::strings_params`]); an error when the racquet never meets the ball.
pub fn strings_params(params: &Params) -> Result<Params, ShotError> {
    shot::strings_params(params)
}

/// What the shot decides of the bounce on the strings, read from the shot's own groups (the incoming
/// ball, the racquet's swing and the racquet), whatever bounce is on screen (a refused one leaves the
/// one before): the incidence where the racquet meets the ball, the frame the racquet in the hand is
/// to the strings, and e_A, the ball's apparent restitution on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Decided {
    /// `params` with the strings' incidence; `None` when the racquet never meets the ball.
    pub strings: Option<Params>,
    /// (M_t, M_n), kg, 0 for clamped; and e_A. `None` when the racquet's numbers are inconsistent.
    pub frame: Option<((f64, f64), f64)>,
}

impl Decided {
    pub fn of(params: &Params) -> Decided {
        let frame = Hold::of(params)
            .ok()
            .map(|h| (h.frame_masses(), h.ey_apparent(params.ey, params.mass)));
        Decided {
            strings: shot::strings_params(params).ok(),
            frame,
        }
    }

    /// The value the shot gives the derived parameter `id` (see [`derived`]).
    pub fn value(&self, id: ParamId) -> Option<f64> {
        match id {
            ParamId::FrameMass => self.frame.map(|((t, _), _)| t),
            ParamId::FrameNormalMass => self.frame.map(|((_, n), _)| n),
            _ => self.strings.map(|p| p.get(id)),
        }
    }

    /// e_A = (e_y M_n - m)/(M_n + m) on the racquet's frame (e_y itself when clamped).
    pub fn ey_apparent(&self) -> Option<f64> {
        self.frame.map(|(_, e)| e)
    }
}

/// Why `spec`, set by the frame change, cannot be changed in a shot; it names the shot's own
/// parameters as the panel does (as `snapback shot` refuses --angle, --speed and --spin).
pub fn refusal(param: &ParamSpec) -> String {
    let name = |id: ParamId| {
        let s = spec(id);
        format!("{} {}", s.label, s.symbol)
    };
    if matches!(param.id, ParamId::FrameMass | ParamId::FrameNormalMass) {
        return format!(
            "{} {} is the racquet's effective mass at the impact point in a shot: change the racquet \
             ({}, {}, {}, {}, {})",
            param.label,
            param.symbol,
            name(ParamId::RacquetMass),
            name(ParamId::Balance),
            name(ParamId::SwingWeight),
            name(ParamId::TwistWeight),
            name(ParamId::Impact),
        );
    }
    format!(
        "{} {} is what the strings see, set by the frame change in a shot: change the incoming ball \
         ({}, {}, {}) or the racquet ({}, {}, {})",
        param.label,
        param.symbol,
        name(ParamId::BallSpeed),
        name(ParamId::BallDescent),
        name(ParamId::BallTopspin),
        name(ParamId::RacquetSpeed),
        name(ParamId::SwingPath),
        name(ParamId::FaceAngle),
    )
}

/// One shot played, or why it cannot be.
#[derive(Clone, Debug)]
pub struct Played {
    pub params: Params,
    pub shot: Result<Shot, String>,
}

/// A shot does not depend on the incidence fields, which it derives: they are left out of the key.
fn key(params: &Params) -> Params {
    Params {
        angle_deg: 0.0,
        speed: 0.0,
        spin: 0.0,
        ..*params
    }
}

/// The worker: a job is the shots wanted (the current one first, then the baseline's), each answered
/// as it is played.
type ShotWorker = Worker<Vec<Params>, Arc<Played>>;

fn spawn() -> ShotWorker {
    Worker::spawn("shot", |wanted: Vec<Params>, job| {
        for params in wanted {
            if job.cancelled() {
                return;
            }
            let shot = shot::play(&params, true).map_err(|e| e.to_string());
            if !job.send(Arc::new(Played { params, shot })) {
                return;
            }
        }
    })
}

/// Shot mode and the shots played.
#[derive(Debug, Default)]
pub struct Shots {
    /// True while the explorer explores a shot: from a shot preset, scenario or flag, or once the shot
    /// view has been shown.
    pub on: bool,
    /// The parameters as they were when shot mode came on: leaving it brings their incidence back.
    pub before: Option<Params>,
    /// The parameters the shot's start changed when shot mode came on from a bounce ([`starting`]), with
    /// the values it gave them: leaving brings back those not changed since.
    pub filled: Vec<(ParamId, f64)>,
    /// The newest shot played for the current parameters, or for earlier ones while those are played.
    pub shown: Option<Arc<Played>>,
    /// The keys of the shots asked for and not answered yet.
    wanted: Vec<Params>,
    cache: Recent<Arc<Played>>,
    /// Started on the first request.
    worker: Option<ShotWorker>,
    /// A crash of the worker's newest job, until the explorer has taken it for the status line.
    unreported: Option<Crash>,
}

impl Shots {
    /// Asks for the shots of `current` and, if pinned, of the `baseline`; takes at once what is known.
    pub fn request(&mut self, current: &Params, baseline: Option<&Params>) {
        if let Some(known) = self.cache.get(&key(current)) {
            self.shown = Some(known);
        }
        let missing: Vec<Params> = std::iter::once(current)
            .chain(baseline)
            .map(key)
            .filter(|k| self.cache.get(k).is_none())
            .collect();
        if missing.is_empty() {
            if !self.wanted.is_empty() {
                self.wanted.clear();
                if let Some(worker) = &self.worker {
                    worker.cancel();
                }
            }
        } else if missing != self.wanted {
            self.wanted = missing.clone();
            self.worker.get_or_insert_with(spawn).submit(missing);
        }
    }

    /// The shot of `params`, if it has been played.
    pub fn known(&self, params: &Params) -> Option<Arc<Played>> {
        self.cache.get(&key(params))
    }

    /// True while a shot asked for has not come yet.
    pub fn pending(&self) -> bool {
        !self.wanted.is_empty()
    }

    /// Takes the shots that have arrived for `current`'s request; true if any did. If the job panicked,
    /// the shots it had not played are answered with the crash (and not asked for again).
    pub fn poll(&mut self, current: &Params) -> bool {
        // The crash first: the results its job sent before it are then all in.
        let (crash, arrived): (_, Vec<_>) = match &self.worker {
            Some(worker) => (worker.crash(), worker.try_iter().collect()),
            None => return false,
        };
        let taken = self.take(arrived, current);
        let Some(crash) = crash else {
            return taken;
        };
        for k in std::mem::take(&mut self.wanted) {
            let played = Arc::new(Played {
                params: k,
                shot: Err(crash.to_string()),
            });
            self.cache.put(k, Arc::clone(&played));
            if k == key(current) {
                self.shown = Some(played);
            }
        }
        self.unreported = Some(crash);
        true
    }

    /// A crash not yet shown in the status line.
    pub fn take_crash(&mut self) -> Option<Crash> {
        self.unreported.take()
    }

    /// Waits up to `timeout` for a shot, then as [`Shots::poll`] (for tests, which settle each step).
    pub fn wait(&mut self, timeout: Duration, current: &Params) -> bool {
        let Some(first) = self.worker.as_ref().and_then(|w| w.wait(timeout)) else {
            return false;
        };
        let taken = self.take(vec![first], current);
        self.poll(current) || taken
    }

    fn take(&mut self, arrived: Vec<(u64, Arc<Played>)>, current: &Params) -> bool {
        let latest = self.worker.as_ref().map_or(0, |w| w.latest());
        let mut changed = false;
        for (generation, played) in arrived {
            let k = key(&played.params);
            if generation != latest || !self.wanted.contains(&k) {
                continue;
            }
            self.wanted.retain(|w| *w != k);
            self.cache.put(k, Arc::clone(&played));
            if k == key(current) {
                self.shown = Some(played);
            }
            changed = true;
        }
        changed
    }

    /// When the shot on screen ends, s from the stroke: at the last point of its path.
    pub fn flight_end(&self) -> Option<f64> {
        let shot = self.shown.as_ref()?.shot.as_ref().ok()?;
        Some(shot.trajectory.last()?[0])
    }

    /// True while the shot on screen is not that of `current`.
    pub fn stale(&self, current: &Params) -> bool {
        self.shown
            .as_ref()
            .is_none_or(|p| key(&p.params) != key(current))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config;

    #[test]
    fn the_strings_see_what_snapback_shot_says() {
        let p = config::preset("topspin-forehand")
            .unwrap()
            .apply(Params::default());
        let derived = strings_params(&p).unwrap();
        let hit = shot::hit(&p).unwrap();
        assert_eq!(derived.angle_deg, hit.incidence.theta1_deg);
        assert_eq!(derived.speed, hit.incidence.speed);
        assert_eq!(derived.spin, hit.incidence.spin);
        assert_eq!(
            Params {
                angle_deg: p.angle_deg,
                speed: p.speed,
                spin: p.spin,
                frame_mass: p.frame_mass,
                frame_normal_mass: p.frame_normal_mass,
                ..derived
            },
            p
        );
        // The strings are tied to the racquet's frame.
        assert_eq!(derived, hit.bounce.params);
    }

    #[test]
    fn a_racquet_that_never_meets_the_ball_is_an_error() {
        let p = Params {
            racquet_speed: 0.0,
            ball_speed: 0.0,
            ..Params::default()
        };
        assert!(matches!(strings_params(&p), Err(ShotError::NeverMeets(_))));
    }

    #[test]
    fn the_refusal_names_the_shot_parameters() {
        let text = refusal(spec(ParamId::Speed));
        for word in [
            "incident speed",
            "incoming speed",
            "racquet speed",
            "face angle",
        ] {
            assert!(text.contains(word), "{word} in {text}");
        }
    }

    #[test]
    fn a_shot_from_the_default_bounce_starts_as_snapback_shot_plays() {
        let (start, filled) = starting(&Params::default());
        let base = shot::base();
        for s in PARAMS.iter().filter(|s| !derived(s.id)) {
            assert_eq!(start.get(s.id), base.get(s.id), "{}", s.label);
        }
        assert!(filled.contains(&ParamId::Ey), "{filled:?}");
        // What the user changed stays, as a flag would.
        let mu = Params {
            mu: 0.3,
            ..Params::default()
        };
        let (start, filled) = starting(&mu);
        assert_eq!(start.mu, 0.3);
        assert!(!filled.contains(&ParamId::Mu));
        assert_eq!(start.ey, base.ey);
        let message = mode_on(&filled, &start);
        assert!(message.contains("snapback shot"), "{message}");
        assert!(message.contains("m leaves it"), "{message}");
        assert_eq!(
            mode_off(&DERIVED),
            "shot mode off: the bounce's own θ1, v1, ω1, M_t and M_n are back (Tab to the shot view or m turns it on again)"
        );
    }
}
