//! Scenarios in the explorer: the preset picker (`p`), saving (`s`) and opening (`o`) scenario files,
//! undo and redo (`u`, Ctrl-R), the baseline (`b`, `B`) and exporting (`x`). Every way the parameters
//! change goes through the history, so each can be undone.

use std::path::{Path, PathBuf};

use crate::export;
use crate::model::Params;
use crate::model::params::spec_named;
use crate::output::{self, Replace};
use crate::scenario::{PRESETS, Scenario};

use super::App;
use crate::tui::baseline::Baseline;
use crate::tui::history;
use crate::tui::scenarios::{
    DEFAULT_SCENARIO_FILE, EXPORT_SAMPLES, complete, export_paths, load, resolve,
};
use crate::tui::vocabulary::{Action, FileKind, FilePrompt, Message, Mode, Tone};

impl App {
    /// Applies the actions of this module (see [`App::update`]).
    pub(super) fn update_scenarios(&mut self, action: Action) {
        match action {
            Action::OpenPicker => {
                // The user's presets are read afresh each time, so a file just added shows; a bad one
                // is named on the status line and the rest are listed.
                self.presets = PRESETS.iter().map(|p| (p.scenario(), false)).collect();
                match crate::config::user_presets() {
                    Ok(users) => self
                        .presets
                        .extend(users.into_iter().map(|u| (u.scenario, true))),
                    Err(e) => self.error(format!("your presets: {e}")),
                }
                // In shot mode a preset's incidence gives way to the frame change's, as on screen.
                let current = self.presets.iter().position(|(s, _)| {
                    let params = s.apply(Params::default());
                    self.strings_params(params).unwrap_or(params) == self.params
                });
                self.mode = Mode::Picker(current.unwrap_or(0));
            }
            Action::PickerUp | Action::PickerDown => {
                if let Mode::Picker(i) = &mut self.mode {
                    let n = self.presets.len().max(1);
                    *i = if action == Action::PickerUp {
                        (*i + n - 1) % n
                    } else {
                        (*i + 1) % n
                    };
                }
            }
            Action::PickerApply => {
                if let Mode::Picker(i) = std::mem::replace(&mut self.mode, Mode::Normal) {
                    self.apply_preset(i);
                }
            }
            Action::PickerClose | Action::PromptCancel => {
                if let Mode::Overwrite(path) = &self.mode {
                    let text = format!("not saved: {} is kept as it was", path.display());
                    self.info(text);
                }
                self.mode = Mode::Normal;
            }
            Action::StartSave => {
                let default = self
                    .last_file
                    .clone()
                    .unwrap_or_else(|| DEFAULT_SCENARIO_FILE.to_string());
                self.mode = Mode::File(FilePrompt {
                    kind: FileKind::Save,
                    text: String::new(),
                    default,
                });
            }
            Action::StartOpen => {
                self.mode = Mode::File(FilePrompt {
                    kind: FileKind::Open,
                    text: String::new(),
                    default: self.last_file.clone().unwrap_or_default(),
                });
            }
            Action::PromptInsert(c) => {
                if let Mode::File(prompt) = &mut self.mode {
                    prompt.text.push(c);
                }
            }
            Action::PromptBackspace => {
                if let Mode::File(prompt) = &mut self.mode {
                    prompt.text.pop();
                }
            }
            Action::PromptComplete => {
                let dir = self.dir.clone();
                if let Mode::File(prompt) = &mut self.mode {
                    // Tab on nothing typed takes the default, to edit.
                    prompt.text = if prompt.text.is_empty() {
                        prompt.default.clone()
                    } else {
                        complete(&dir, &prompt.text)
                    };
                }
            }
            Action::PromptSubmit => {
                if let Mode::File(prompt) = std::mem::replace(&mut self.mode, Mode::Normal) {
                    let typed = match prompt.text.trim() {
                        "" => prompt.default.trim(),
                        typed => typed,
                    };
                    match prompt.kind {
                        FileKind::Save => self.submit_save(typed),
                        FileKind::Open => self.submit_open(typed),
                    }
                }
            }
            Action::ConfirmOverwrite => {
                if let Mode::Overwrite(path) = std::mem::replace(&mut self.mode, Mode::Normal) {
                    self.save_to(&path);
                }
            }
            Action::Undo => self.walk_history(true),
            Action::Redo => self.walk_history(false),
            Action::PinBaseline => {
                let Some(solved) = self.solved.clone() else {
                    self.info("nothing to pin yet: the bounce is being solved".into());
                    return;
                };
                let replaced = self.baseline.is_some();
                let text = format!(
                    "baseline {}: ω2 {:.1} rad/s, drawn dimmer; b pins again, B clears",
                    if replaced { "replaced" } else { "pinned" },
                    solved.bounce.outcome.omega2
                );
                self.baseline = Some(Baseline { solved });
                self.info(text);
            }
            Action::ClearBaseline => {
                let text = if self.baseline.take().is_some() {
                    "baseline cleared"
                } else {
                    "no baseline to clear (b pins one)"
                };
                self.info(text.to_string());
            }
            Action::Export => self.export(),
            _ => {}
        }
    }

    fn info(&mut self, text: String) {
        self.message = Some(Message {
            text,
            tone: Tone::Info,
        });
    }

    fn error(&mut self, text: String) {
        self.message = Some(Message {
            text,
            tone: Tone::Error,
        });
    }

    /// `name` as a path: relative to [`App::dir`], `~/` in the home directory, absolute as it is.
    pub fn resolve(&self, name: &str) -> PathBuf {
        resolve(&self.dir, name)
    }

    /// Makes `params` current as one change that can be undone; `what` says what it was. If the solver
    /// refuses them, the parameters go back and the reason replaces `what`.
    fn change_to(&mut self, params: Params, what: String) {
        let params = match self.strings_params(params) {
            Ok(params) => params,
            Err(reason) => return self.error(format!("{reason} (parameters unchanged)")),
        };
        if params == self.params {
            self.info(format!("{what} (the parameters were already these)"));
            return;
        }
        self.history.record(self.params);
        self.info(what);
        self.set_params(params, "parameters");
    }

    fn apply_preset(&mut self, index: usize) {
        let Some((scenario, _)) = self.presets.get(index).cloned() else {
            return;
        };
        let what = format!("preset {}: {}", scenario.name, scenario.description);
        if scenario.is_shot() {
            self.explore_shot();
        }
        self.change_to(scenario.apply(Params::default()), what);
    }

    fn submit_save(&mut self, typed: &str) {
        if typed.is_empty() {
            self.error("save: no file name given (nothing saved)".into());
            return;
        }
        let name = if typed.ends_with(".toml") {
            typed.to_string()
        } else {
            format!("{typed}.toml")
        };
        let path = self.resolve(&name);
        self.last_file = Some(name);
        if path.is_dir() {
            self.error(format!("{} is a directory (nothing saved)", path.display()));
        } else if path.exists() {
            self.mode = Mode::Overwrite(path);
        } else {
            self.save_to(&path);
        }
    }

    fn save_to(&mut self, path: &Path) {
        let name = path
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        let description = match &self.solved {
            Some(s) if s.params == self.params => format!(
                "Saved from the snapback explorer (ω2 {:.1} rad/s)",
                s.bounce.outcome.omega2
            ),
            _ => "Saved from the snapback explorer".to_string(),
        };
        let mut scenario = Scenario::from_params(&name, &description, &self.params);
        // Outside shot mode the shot's parameters are the defaults: a file without them opens as a bounce.
        // In shot mode the incidence is the shot's to set: a file without it opens as a shot.
        let shot = self.shots.on;
        scenario.values.retain(|key, _| {
            spec_named(key).is_none_or(|s| {
                if shot {
                    !crate::tui::shot::derived(s.id)
                } else {
                    !s.group.is_shot()
                }
            })
        });
        match scenario.save(path) {
            Ok(()) => {
                self.file_params = Some(self.params);
                self.info(format!("saved {}", path.display()));
            }
            Err(e) => self.error(format!("not saved: {e}")),
        }
    }

    fn submit_open(&mut self, typed: &str) {
        if typed.is_empty() {
            self.error("open: no file name given".into());
            return;
        }
        // Standard input is the terminal the explorer reads its keys from.
        if crate::input::is_stdin(Path::new(typed)) {
            self.error("open: the explorer reads its keys from standard input; give a file".into());
            return;
        }
        // `what-if` opens what-if.toml when there is no file called what-if.
        let mut name = typed.to_string();
        if !self.resolve(&name).exists() && self.resolve(&format!("{name}.toml")).is_file() {
            name.push_str(".toml");
        }
        match load(&self.resolve(&name), &name) {
            Ok(scenario) => {
                self.last_file = Some(name.clone());
                let what = if scenario.description.is_empty() {
                    format!("opened {name}")
                } else {
                    format!("opened {name}: {}", scenario.description)
                };
                if scenario.is_shot() {
                    self.explore_shot();
                }
                // In shot mode the file's incidence gives way to the frame change's, as on screen.
                let params = scenario.apply(Params::default());
                self.file_params = Some(self.strings_params(params).unwrap_or(params));
                self.change_to(params, what);
            }
            Err(e) => self.error(format!("{e} (parameters unchanged)")),
        }
    }

    fn walk_history(&mut self, back: bool) {
        let (word, target) = if back {
            ("undo", self.history.undo(self.params))
        } else {
            ("redo", self.history.redo(self.params))
        };
        let Some(target) = target else {
            self.info(format!("{word}: nothing to {word}"));
            return;
        };
        // A change from before shot mode comes back with the incidence the strings see.
        let target = self.strings_params(target).unwrap_or(target);
        let from = self.params;
        let left = if back {
            self.history.undo_len()
        } else {
            self.history.redo_len()
        };
        let text = format!(
            "{word}: {} ({left} more to {word})",
            history::describe(&from, &target)
        );
        self.info(text);
        self.set_params(target, "parameters");
    }

    /// Writes `snapback-N.csv` (the time series) and `snapback-N.json` (the outcome) into [`App::dir`],
    /// N the first number that names neither file yet.
    fn export(&mut self) {
        let Some(solved) = self.solved.clone().filter(|s| s.params == self.params) else {
            self.error(
                "not exported: the bounce is still being solved; try again in a moment".into(),
            );
            return;
        };
        let Some(n) = (1..10_000).find(|n| {
            let (csv, json) = export_paths(&self.dir, *n);
            !csv.exists() && !json.exists()
        }) else {
            self.error(format!(
                "not exported: {} already holds 10000 exports",
                self.dir.display()
            ));
            return;
        };
        let (csv, json) = export_paths(&self.dir, n);
        let series = export::csv::series(&solved.bounce.series(EXPORT_SAMPLES));
        let outcome = export::json::bounce(&solved.bounce);
        let written = output::write(&csv, series.as_bytes(), Replace::Writable)
            .and_then(|()| output::write(&json, outcome.as_bytes(), Replace::Writable));
        match written {
            Ok(()) => self.info(format!(
                "exported the series to {} and the outcome to {}",
                csv.display(),
                json.display()
            )),
            Err(e) => self.error(format!("not exported: {e}")),
        }
    }
}
