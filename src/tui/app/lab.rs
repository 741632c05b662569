//! The lab's keys and answers (see [`crate::tui::lab`]): marking parameters free, fitting them to the
//! data on a worker, and the uncertainty typed with a value.

use std::thread;
use std::time::{Duration, Instant};

use crate::analysis::AnalysisError;
use crate::analysis::fit::Fit;
use crate::analysis::fit::data::Dataset;
use crate::analysis::fit::free::Free;
use crate::analysis::uncertainty::Spread;
use crate::model::params::{BOUNCE_PARAMS as PARAMS, ParamId, ParamSpec, spec};
use crate::model::units;

use super::App;
use crate::tui::lab::{FitEvent, FitJob, Fitting, Lab, fitted_text, symbols};
use crate::tui::vocabulary::{Action, Message, Tone, View};
use crate::tui::worker::Worker;

impl App {
    /// Starts the lab on `data`: the residuals are asked for at once.
    pub fn load_data(&mut self, data: Dataset) {
        self.lab = Lab::with_data(data);
        self.want_lab();
    }

    /// Asks the lab's workers for what the screen needs: the residuals always (with data), the band in
    /// the sweep view.
    pub(super) fn want_lab(&mut self) {
        let params = self.params;
        self.lab.want_residuals(&params);
        if self.view == View::Sweep {
            self.lab.want_band(&params);
        }
    }

    /// Takes what the lab's workers have sent; true if anything on screen changed.
    pub(super) fn poll_lab(&mut self) -> bool {
        let params = self.params;
        let mut changed = self.lab.collect(&params);
        if let Some(crash) = self.lab.fit_worker.as_ref().and_then(Worker::crash)
            && self.lab.fitting.take().is_some()
        {
            self.say(format!("fit stopped: {crash}"), Tone::Error);
            return true;
        }
        let events: Vec<FitEvent> = match &self.lab.fit_worker {
            Some(worker) => worker
                .try_iter()
                .filter(|(generation, _)| *generation == worker.latest())
                .map(|(_, event)| event)
                .collect(),
            None => Vec::new(),
        };
        for event in events {
            changed = true;
            match event {
                FitEvent::Progress(p) => {
                    if let Some(fitting) = &mut self.lab.fitting {
                        fitting.progress = Some(p);
                    }
                }
                FitEvent::Done(result) => self.fitted(*result),
            }
        }
        // The fit's clock in the status line moves on while it runs.
        changed || self.lab.fitting.is_some()
    }

    /// Waits a little for the lab's workers (for tests and benchmarks, which settle before each step;
    /// [`App::poll`] then takes what came).
    pub(super) fn wait_lab(&self, timeout: Duration) {
        thread::sleep(timeout.min(Duration::from_millis(5)));
    }

    /// The lab's keys: mark free, fit or stop the fit, and q or Esc while a fit runs.
    pub(super) fn update_lab(&mut self, action: Action) {
        match action {
            Action::ToggleFree => self.toggle_free(),
            Action::Fit if self.lab.fitting.is_some() => self.stop_fit(),
            Action::Fit => self.start_fit(),
            Action::Quit => self.stop_fit(),
            _ => {}
        }
    }

    fn say(&mut self, text: String, tone: Tone) {
        self.message = Some(Message { text, tone });
    }

    fn toggle_free(&mut self) {
        let spec = self.selected_spec();
        let name = format!("{} {}", spec.label, spec.symbol);
        if spec.integer {
            return self.say(
                format!("{name} is a whole number and cannot be fitted"),
                Tone::Error,
            );
        }
        if spec.group.is_shot() {
            return self.say(
                format!("{name} is the shot's: measured rebounds do not depend on it, so it cannot be fitted"),
                Tone::Error,
            );
        }
        if let Some(data) = &self.lab.data
            && data.conditions.contains(&spec.id)
        {
            let text = format!(
                "{name} is a column of {}: each row sets it, so it cannot be fitted",
                data.origin
            );
            return self.say(text, Tone::Error);
        }
        let free = &mut self.lab.free;
        let now_free = !free.contains(&spec.id);
        if now_free {
            free.push(spec.id);
            free.sort_by_key(|id| PARAMS.iter().position(|s| s.id == *id));
        } else {
            free.retain(|id| *id != spec.id);
        }
        let list = if free.is_empty() {
            "none".to_string()
        } else {
            symbols(free)
        };
        let next = match (&self.lab.data, now_free) {
            (Some(data), true) => format!("; F fits them to {}", data.origin),
            (None, true) => "; start with --data FILE.csv to fit them".to_string(),
            (_, false) => String::new(),
        };
        let state = if now_free { "free" } else { "fixed" };
        self.say(
            format!("{} {state} (free: {list}){next}", spec.symbol),
            Tone::Info,
        );
    }

    fn start_fit(&mut self) {
        let Some(data) = &self.lab.data else {
            return self.say(
                "no measurements to fit: start the explorer with --data FILE.csv".into(),
                Tone::Error,
            );
        };
        if self.lab.free.is_empty() {
            return self.say(
                "no free parameters: f marks the selected parameter free, then F fits".into(),
                Tone::Error,
            );
        }
        let (n, k) = (data.measurements(), self.lab.free.len());
        if n <= k {
            let text = format!(
                "{}: {n} measurements cannot determine {k} free parameters; free fewer (f)",
                data.origin
            );
            return self.say(text, Tone::Error);
        }
        let Some(worker) = &self.lab.fit_worker else {
            return;
        };
        let free = self
            .lab
            .free
            .iter()
            .map(|&id| Free::new(spec(id)))
            .collect();
        worker.submit(FitJob {
            base: self.params,
            free,
        });
        self.lab.fitting = Some(Fitting {
            from: self.params,
            free: self.lab.free.clone(),
            started: Instant::now(),
            progress: None,
        });
    }

    fn stop_fit(&mut self) {
        if let Some(solves) = self.lab.stop_fit() {
            self.say(
                format!("fit stopped after {solves} bounces; parameters unchanged"),
                Tone::Info,
            );
        }
    }

    /// A fit has finished: its values become the parameters, one change that `u` undoes; unless the data
    /// cannot determine one of them, or a parameter it held fixed has changed meanwhile.
    fn fitted(&mut self, result: Result<Fit, AnalysisError>) {
        let Some(fitting) = self.lab.fitting.take() else {
            return;
        };
        let seconds = fitting.started.elapsed().as_secs_f64();
        let fit = match result {
            Ok(fit) => fit,
            Err(AnalysisError::Cancelled) => return,
            Err(e) => return self.say(format!("fit failed: {e}"), Tone::Error),
        };
        let undetermined = fit.undetermined();
        if !undetermined.is_empty() {
            let text = format!(
                "the data cannot determine {}: fit not applied; fix it (f) or add rows in which it changes the outcome",
                symbols(&undetermined)
            );
            return self.say(text, Tone::Error);
        }
        let conditions = self
            .lab
            .data
            .as_ref()
            .map_or(Vec::new(), |d| d.conditions.clone());
        let moved: Vec<ParamId> = PARAMS
            .iter()
            .map(|s| s.id)
            .filter(|id| !fitting.free.contains(id) && !conditions.contains(id))
            .filter(|&id| fitting.from.get(id) != self.params.get(id))
            .collect();
        if !moved.is_empty() {
            let text = format!(
                "fit not applied: {} changed while it ran, and the fit held the old value; F fits again",
                symbols(&moved)
            );
            return self.say(text, Tone::Error);
        }
        let mut params = self.params;
        for f in &fit.free {
            params.set(f.id, f.value);
        }
        let values: Vec<String> = fit.free.iter().map(fitted_text).collect();
        let converged = if fit.converged { "" } else { ", NOT converged" };
        let verdict = match fit.p_value {
            Some(p) => format!("{} (p {})", fit.verdict.name(), units::brief(p, 2)),
            None => format!("{} (no sigmas)", fit.verdict.name()),
        };
        let text = format!(
            "fit in {seconds:.2} s: {}; chi2 {} for {} dof{converged}, verdict {verdict}",
            values.join(", "),
            units::brief(fit.chi2, 4),
            fit.dof
        );
        if params == self.params {
            return self.say(
                format!("{text} (the parameters were already these)"),
                Tone::Info,
            );
        }
        self.history.record(self.params);
        self.say(format!("{text}; u undoes"), Tone::Info);
        self.set_params(params, "parameters");
    }

    /// A value was typed with an uncertainty `sigma` (0 removes it): the sweep view draws the band.
    pub(super) fn spread_typed(&mut self, spec: &'static ParamSpec, sigma: f64) {
        self.lab.spreads.retain(|s| s.id != spec.id);
        let text = if sigma > 0.0 {
            self.lab.spreads.push(Spread { id: spec.id, sigma });
            let shown = spec.show(sigma);
            format!(
                "{} ± {}: the sweep view (Tab) draws ω2's band, ± 1 sd over {} draws; ±0 removes it",
                spec.symbol,
                shown,
                crate::tui::band::SAMPLES
            )
        } else {
            format!("{} has no uncertainty now", spec.symbol)
        };
        self.say(text, Tone::Info);
        self.want_lab();
    }
}
