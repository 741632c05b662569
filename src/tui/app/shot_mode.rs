//! Shot mode on and off: from a start, a preset or a file that is a shot ([`App::explore_shot`]), from a
//! bounce by Tab into the shot view or `m` ([`App::enter_shot`], the shot then starts as `snapback shot`
//! plays it), off by `m` ([`App::leave_shot`]) or by `R` when the explorer started as a bounce.

use crate::model::params::BOUNCE_PARAMS as PARAMS;
use crate::model::{ParamId, Params};

use super::App;
use crate::tui::shot;
use crate::tui::vocabulary::{Message, Tone, View};

impl App {
    /// Explores a shot from now on, the parameters as they are: the shot group joins the panel, the
    /// incidence follows from the racquet and the incoming ball, and the contact view shows the bounce
    /// on the strings.
    pub fn explore_shot(&mut self) {
        self.shot_on(self.params, Vec::new());
    }

    /// Starts the explorer in shot mode (a shot preset, scenario or flag): `R` comes back to it.
    pub fn start_in_shot_mode(&mut self) {
        self.explore_shot();
        self.start_shot = true;
    }

    /// Turns shot mode on from a bounce: the shot starts as `snapback shot` plays it, every parameter
    /// still at its default taking the shot's starting value ([`shot::starting`]); the status line says
    /// so and which values changed.
    pub(super) fn enter_shot(&mut self) {
        let (start, filled) = shot::starting(&self.params);
        self.shot_on(start, filled.clone());
        self.message = Some(Message {
            text: shot::mode_on(&filled, &start),
            tone: Tone::Info,
        });
    }

    fn shot_on(&mut self, params: Params, filled: Vec<ParamId>) {
        if self.shots.on {
            return;
        }
        self.shots.on = true;
        self.shots.before = Some(self.params);
        self.shots.filled = filled.iter().map(|&id| (id, params.get(id))).collect();
        if shot::derived(self.selected_spec().id) {
            self.selected = PARAMS.len();
        }
        self.set_params(params, "parameters");
    }

    /// Leaves shot mode: the shot group leaves the panel, the bounce's own incidence (from before shot
    /// mode) comes back with what the shot's start changed and has not been changed since, and the
    /// shot view gives way to the contact view.
    pub fn leave_shot(&mut self) {
        let restored = self.shot_off();
        let mut params = self.params;
        for &id in &restored {
            if let Some(before) = self.shots.before {
                params.set(id, before.get(id));
            }
        }
        self.shots.before = None;
        self.set_params(params, "parameters");
        self.message = Some(Message {
            text: shot::mode_off(&restored),
            tone: Tone::Info,
        });
    }

    /// Turns shot mode off, the parameters as they are; which ones leaving it should bring back.
    fn shot_off(&mut self) -> Vec<ParamId> {
        self.shots.on = false;
        let mut restored = shot::DERIVED.to_vec();
        for (id, entered) in std::mem::take(&mut self.shots.filled) {
            if self.params.get(id) == entered && !restored.contains(&id) {
                restored.push(id);
            }
        }
        if self.selected >= PARAMS.len() {
            self.selected = 0;
        }
        if self.view == View::Shot {
            self.view = View::Contact;
        }
        restored
    }

    /// `R`: every parameter back to the start, shot mode too (off when the explorer started as a
    /// bounce, on when it started as a shot); the status line says what it did.
    pub(super) fn reset_all(&mut self) {
        let mode = if self.shots.on && !self.start_shot {
            self.shot_off();
            self.shots.before = None;
            ", and shot mode is off (Tab to the shot view or m turns it on)"
        } else if !self.shots.on && self.start_shot {
            self.explore_shot();
            ", and shot mode is on, as at the start (m leaves it)"
        } else {
            ""
        };
        let changed = self.params != self.start;
        self.try_apply(self.start);
        if self.message.is_some() {
            return;
        }
        if !changed && !mode.is_empty() {
            self.set_params(self.start, "parameters");
        }
        let text = if changed || !mode.is_empty() {
            format!("reset: every parameter is back to the start{mode}")
        } else {
            "reset: every parameter is at the start already".to_string()
        };
        self.message = Some(Message {
            text,
            tone: Tone::Info,
        });
    }
}
