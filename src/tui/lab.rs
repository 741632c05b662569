//! The lab: measurements beside the model and fits to them, and the uncertainty band of the sweep view.
//!
//! With `--data FILE.csv` the explorer solves every row at the current parameters on a worker
//! ([`Residuals`]) for the outcome panel, and draws the measured points on the charts they match
//! ([`at_conditions`]). `f` marks the selected parameter free, `F` fits the free ones to the data on
//! another worker (`analysis::fit`, the same fit as `snapback fit`) while the keys keep working, with
//! its progress in the status line; `F` again, Esc or q stop it. A finished fit sets the fitted values as
//! one change that `u` undoes. A value typed with an uncertainty (`60±1`) makes the sweep view draw the
//! Monte Carlo band of omega2 ([`Band`]), computed on a third worker.
//!
//! [`Lab`] holds the state and the workers; the `impl App` below applies the lab's keys and takes the
//! workers' answers.

use std::sync::Arc;
use std::thread;
use std::time::{Duration, Instant};

use crate::analysis::AnalysisError;
use crate::analysis::fit::data::{Dataset, Row};
use crate::analysis::fit::free::Free;
use crate::analysis::fit::watch::{Progress, Stage, Watch};
use crate::analysis::fit::{self, Fit, Options};
use crate::analysis::uncertainty::Spread;
use crate::model::params::{BOUNCE_PARAMS as PARAMS, Group, ParamId, ParamSpec, Step, spec};
use crate::model::{Params, units};

use super::app::{Action, App, Message, Tone, View};
use super::band::Band;
use super::residuals::Residuals;
use super::solver::Recent;
use super::sweep::Sweeps;
use super::worker::Worker;

/// A fit on its way.
#[derive(Clone, Debug)]
pub struct Fitting {
    /// The parameters it started from; the ones not free are held there.
    pub from: Params,
    pub free: Vec<ParamId>,
    pub started: Instant,
    /// Where it has got to, once it has said.
    pub progress: Option<Progress>,
}

/// What the fit's worker sends.
#[derive(Debug)]
enum FitEvent {
    Progress(Progress),
    /// Boxed: a fit is large beside a progress report.
    Done(Box<Result<Fit, AnalysisError>>),
}

/// A fit to run: the starting parameters and the free ones.
struct FitJob {
    base: Params,
    free: Vec<Free>,
}

/// The inputs of a band: the parameters (angle aside) and the uncertainties.
type BandKey = (Params, Vec<Spread>);

/// Measurements, free parameters, uncertainties, and what the workers made of them.
#[derive(Default)]
pub struct Lab {
    /// The measurements given with `--data`.
    pub data: Option<Arc<Dataset>>,
    /// The parameters marked free, in the order of the parameter panel.
    pub free: Vec<ParamId>,
    /// Standard uncertainties typed in the value prompt (`60±1`), base units.
    pub spreads: Vec<Spread>,
    /// The newest residuals computed: for the current parameters, or older ones while those are solved.
    pub residuals: Option<Arc<Residuals>>,
    /// The newest band computed.
    pub band: Option<Arc<Band>>,
    pub fitting: Option<Fitting>,
    residual_worker: Option<Worker<Params, Arc<Residuals>>>,
    residual_cache: Recent<Arc<Residuals>>,
    residuals_wanted: Option<Params>,
    band_worker: Option<Worker<BandKey, Arc<Band>>>,
    band_wanted: Option<BandKey>,
    fit_worker: Option<Worker<FitJob, FitEvent>>,
}

impl std::fmt::Debug for Lab {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Lab")
            .field("data", &self.data.as_ref().map(|d| &d.origin))
            .field("free", &self.free)
            .field("spreads", &self.spreads)
            .field("fitting", &self.fitting)
            .finish_non_exhaustive()
    }
}

impl Lab {
    /// A lab on `data`, its workers started.
    fn with_data(data: Dataset) -> Lab {
        let data = Arc::new(data);
        let rows = Arc::clone(&data);
        let residual_worker = Worker::spawn("residuals", move |params: Params, job| {
            if let Some(r) = Residuals::compute(&params, &rows, &|| job.cancelled()) {
                job.send(Arc::new(r));
            }
        });
        let measured = Arc::clone(&data);
        let fit_worker = Worker::spawn("fit", move |fit: FitJob, job| {
            let watch = Watch {
                cancelled: &|| job.cancelled(),
                progress: &|p| {
                    job.send(FitEvent::Progress(p));
                },
            };
            let result =
                fit::fit_watched(&fit.base, &fit.free, &measured, &Options::default(), &watch);
            if !matches!(result, Err(AnalysisError::Cancelled)) {
                job.send(FitEvent::Done(Box::new(result)));
            }
        });
        Lab {
            data: Some(data),
            residual_worker: Some(residual_worker),
            fit_worker: Some(fit_worker),
            ..Lab::default()
        }
    }

    /// True while residuals, a band or a fit asked for have not come.
    pub fn pending(&self) -> bool {
        self.residuals_wanted.is_some() || self.band_wanted.is_some() || self.fitting.is_some()
    }

    /// The uncertainty of parameter `id`, if one was typed.
    pub fn spread(&self, id: ParamId) -> Option<f64> {
        self.spreads.iter().find(|s| s.id == id).map(|s| s.sigma)
    }

    /// True when `id` is marked free.
    pub fn is_free(&self, id: ParamId) -> bool {
        self.free.contains(&id)
    }

    /// The band for `params` and the uncertainties typed, if computed.
    pub fn band_for(&self, params: &Params) -> Option<&Band> {
        let band = self.band.as_deref()?;
        (band.key == Sweeps::key(params) && band.spreads == self.spreads).then_some(band)
    }

    /// The residuals of the data at `params`: known, or asked for.
    fn want_residuals(&mut self, params: &Params) {
        let Some(worker) = &self.residual_worker else {
            return;
        };
        if let Some(known) = self.residual_cache.get(params) {
            self.residuals = Some(known);
            if self.residuals_wanted.take().is_some() {
                worker.cancel();
            }
        } else if self.residuals_wanted != Some(*params) {
            self.residuals_wanted = Some(*params);
            worker.submit(*params);
        }
    }

    /// The band for `params` and the uncertainties typed, asked for unless computed or on its way.
    fn want_band(&mut self, params: &Params) {
        if self.spreads.is_empty() {
            if self.band_wanted.take().is_some()
                && let Some(worker) = &self.band_worker
            {
                worker.cancel();
            }
            return;
        }
        let key = (Sweeps::key(params), self.spreads.clone());
        if self.band_for(params).is_some() || self.band_wanted.as_ref() == Some(&key) {
            return;
        }
        let worker = self.band_worker.get_or_insert_with(|| {
            Worker::spawn("band", |(key, spreads): BandKey, job| {
                if let Some(band) = Band::compute(&key, &spreads, &|| job.cancelled()) {
                    job.send(Arc::new(band));
                }
            })
        });
        worker.submit(key.clone());
        self.band_wanted = Some(key);
    }

    /// Takes the residuals and the band that have come; true if any did.
    fn collect(&mut self, params: &Params) -> bool {
        let mut changed = false;
        if let Some(worker) = &self.residual_worker {
            for (generation, r) in worker.try_iter() {
                if generation == worker.latest() && self.residuals_wanted == Some(r.params) {
                    self.residuals_wanted = None;
                    self.residual_cache.put(r.params, Arc::clone(&r));
                    if r.params == *params {
                        self.residuals = Some(r);
                    }
                    changed = true;
                }
            }
        }
        if let Some(worker) = &self.band_worker {
            for (generation, band) in worker.try_iter() {
                let key = (band.key, band.spreads.clone());
                if generation == worker.latest() && self.band_wanted.as_ref() == Some(&key) {
                    self.band_wanted = None;
                    self.band = Some(band);
                    changed = true;
                }
            }
        }
        changed
    }

    /// Stops the fit under way, if any; how many bounces it had solved.
    fn stop_fit(&mut self) -> Option<usize> {
        let fitting = self.fitting.take()?;
        if let Some(worker) = &self.fit_worker {
            worker.cancel();
        }
        Some(fitting.progress.map_or(0, |p| p.solves))
    }

    /// The status line's account of the fit under way.
    pub fn progress_text(&self) -> Option<String> {
        let fitting = self.fitting.as_ref()?;
        let names = symbols(&fitting.free);
        let step = match fitting.progress {
            None => "starting".to_string(),
            Some(Progress {
                stage: Stage::Scan,
                done,
                of,
                ..
            }) => format!("scanning starts {done}/{of}"),
            Some(Progress {
                stage: Stage::Refine,
                done,
                of,
                ..
            }) => format!("short runs {done}/{of}"),
            Some(Progress {
                stage: Stage::Converge,
                done,
                of,
                ..
            }) => format!("converging minima {done}/{of}"),
            Some(Progress {
                stage: Stage::Profile,
                done,
                of,
                ..
            }) => format!("profile intervals {done}/{of}"),
        };
        let solves = fitting.progress.map_or(0, |p| p.solves);
        Some(format!(
            "fitting {names}: {step}, {solves} bounces solved, {:.1} s · F or Esc stops",
            fitting.started.elapsed().as_secs_f64()
        ))
    }
}

/// The symbols of `ids`, `M, k, μ`.
fn symbols(ids: &[ParamId]) -> String {
    ids.iter()
        .map(|&id| spec(id).symbol)
        .collect::<Vec<_>>()
        .join(", ")
}

/// True when `a` and `b` are within half of `spec`'s fine step of each other: as close as the arrow
/// keys bring a value.
fn close(spec: &ParamSpec, a: f64, b: f64) -> bool {
    match spec.fine {
        Step::Add(d) => (a - b).abs() <= d / 2.0,
        Step::Times(f) => a == b || (a / b - 1.0).abs() <= (f - 1.0) / 2.0,
    }
}

/// True when every condition of `row` but those in `except` is close to its value in `params`
/// (within half a fine step): the row was measured where `params` are.
pub fn at_conditions(row: &Row, params: &Params, except: &[ParamId]) -> bool {
    row.conditions
        .iter()
        .filter(|(id, _)| !except.contains(id))
        .all(|&(id, value)| close(spec(id), value, params.get(id)))
}

/// A fitted value with its standard error in the panel's units: `M 4.92 ± 0.61 g`.
fn fitted_text(f: &fit::Fitted) -> String {
    let s = spec(f.id);
    let value = fit::shown(f.id, f.value, f.stderr);
    let error = f.stderr.map_or(String::new(), |se| {
        format!(" ± {}", fit::shown(f.id, se, Some(se)))
    });
    format!("{} {value}{error} {}", s.symbol, s.display_unit)
        .trim_end()
        .to_string()
}

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
        if spec.group == Group::Shot {
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
        let text = format!(
            "fit in {seconds:.2} s: {}; chi2 {} for {} dof{converged}",
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
                super::band::SAMPLES
            )
        } else {
            format!("{} has no uncertainty now", spec.symbol)
        };
        self.say(text, Tone::Info);
        self.want_lab();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::fit::data::parse;

    #[test]
    fn rows_match_within_half_a_fine_step() {
        let data = parse("angle,spin,cart-mass,omega2\n50,-104,10.4g,1\n", "d.csv").unwrap();
        let row = &data.rows[0];
        let p = Params::default();
        // Spin within 5 rad/s (half of 10), cart mass within 5 % (half of x1.1); the angle is left out.
        assert!(at_conditions(row, &p, &[ParamId::Angle]));
        assert!(!at_conditions(row, &p, &[]));
        let far = p.with(ParamId::Spin, -110.0).unwrap();
        assert!(!at_conditions(row, &far, &[ParamId::Angle]));
        assert!(at_conditions(row, &far, &[ParamId::Angle, ParamId::Spin]));
    }
}
