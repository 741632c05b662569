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
//! [`Lab`] holds the state and the workers; `app::lab` applies the lab's keys and takes the workers'
//! answers.

use std::sync::Arc;
use std::time::Instant;

use crate::analysis::AnalysisError;
use crate::analysis::fit::data::{Dataset, Row};
use crate::analysis::fit::free::Free;
use crate::analysis::fit::watch::{Progress, Stage, Watch};
use crate::analysis::fit::{self, Fit, Options};
use crate::analysis::uncertainty::Spread;
use crate::model::Params;
use crate::model::params::{ParamId, ParamSpec, Step, spec};

use super::band::Band;
use super::residuals::Residuals;
use super::solver::Recent;
use super::sweep::Sweeps;
use super::worker::{Crash, Worker};

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
pub(crate) enum FitEvent {
    Progress(Progress),
    /// Boxed: a fit is large beside a progress report.
    Done(Box<Result<Fit, AnalysisError>>),
}

/// A fit to run: the starting parameters and the free ones.
pub(crate) struct FitJob {
    pub(crate) base: Params,
    pub(crate) free: Vec<Free>,
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
    /// The residuals and the band whose jobs panicked: not asked for again.
    residuals_crashed: Option<Params>,
    band_crashed: Option<BandKey>,
    /// A crash of a worker's newest job, until the explorer has taken it for the status line.
    unreported: Option<Crash>,
    pub(crate) fit_worker: Option<Worker<FitJob, FitEvent>>,
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
    pub(crate) fn with_data(data: Dataset) -> Lab {
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
                work: None,
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
    pub(crate) fn want_residuals(&mut self, params: &Params) {
        let Some(worker) = &self.residual_worker else {
            return;
        };
        if let Some(known) = self.residual_cache.get(params) {
            self.residuals = Some(known);
            if self.residuals_wanted.take().is_some() {
                worker.cancel();
            }
        } else if self.residuals_wanted != Some(*params) && self.residuals_crashed != Some(*params)
        {
            self.residuals_wanted = Some(*params);
            worker.submit(*params);
        }
    }

    /// The band for `params` and the uncertainties typed, asked for unless computed or on its way.
    pub(crate) fn want_band(&mut self, params: &Params) {
        if self.spreads.is_empty() {
            if self.band_wanted.take().is_some()
                && let Some(worker) = &self.band_worker
            {
                worker.cancel();
            }
            return;
        }
        let key = (Sweeps::key(params), self.spreads.clone());
        if self.band_for(params).is_some()
            || self.band_wanted.as_ref() == Some(&key)
            || self.band_crashed.as_ref() == Some(&key)
        {
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

    /// Takes the residuals and the band that have come, or the crash of their job; true if any did.
    pub(crate) fn collect(&mut self, params: &Params) -> bool {
        let mut changed = false;
        if let Some(crash) = self.residual_worker.as_ref().and_then(Worker::crash)
            && let Some(wanted) = self.residuals_wanted.take()
        {
            self.residuals_crashed = Some(wanted);
            self.unreported = Some(crash);
            changed = true;
        }
        if let Some(crash) = self.band_worker.as_ref().and_then(Worker::crash)
            && let Some(wanted) = self.band_wanted.take()
        {
            self.band_crashed = Some(wanted);
            self.unreported = Some(crash);
            changed = true;
        }
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

    /// A crash not yet shown in the status line.
    pub fn take_crash(&mut self) -> Option<Crash> {
        self.unreported.take()
    }

    /// Stops the fit under way, if any; how many bounces it had solved.
    pub(crate) fn stop_fit(&mut self) -> Option<usize> {
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
pub(crate) fn symbols(ids: &[ParamId]) -> String {
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
pub(crate) fn fitted_text(f: &fit::Fitted) -> String {
    let s = spec(f.id);
    let value = fit::shown(f.id, f.value, f.stderr);
    let error = f.stderr.map_or(String::new(), |se| {
        format!(" ± {}", fit::shown(f.id, se, Some(se)))
    });
    format!("{} {value}{error} {}", s.symbol, s.display_unit)
        .trim_end()
        .to_string()
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
