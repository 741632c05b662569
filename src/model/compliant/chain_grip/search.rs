//! Where the event search looks for the grip's break, and the bounds on |F''| it needs: in stages, a
//! strongly damped mode bounding |F''| only until it has died out.

use super::super::super::setup::Setup;
use super::super::stretch::SETTLED;
use nalgebra::DVector;

use std::cell::{Cell, RefCell};

use super::super::super::contact::ROUNDING;
use super::super::super::events::{Branch, first_rise_predicted_from_tangent};
use super::super::super::trig::{exp as fast_exp, sin_cos};
use super::super::Point;
use super::{C64, ChainGrip, MODES, NEGLIGIBLE, Turns};

/// An estimated bound this far above half the stage's refuses a cut without the exact bound (the
/// estimate is within 1e-12 of it, so the exact bound would refuse it too).
const SCREEN: f64 = 1e-9;

/// One stage of the grip's event search ([`ChainGrip::search_stages`]).
#[derive(Clone, Copy, Debug)]
pub struct Stage {
    pub from: f64,
    pub to: f64,
    /// A bound on |F''| over the stage.
    pub curvature: f64,
    /// The search's coarse step.
    pub step: f64,
    /// A bound on |F''''| over the stage (infinite where the modes do not give one).
    pub fourth: f64,
}

impl Stage {
    /// (from, to, bound on |F''|, step), for a search without the Taylor polynomials.
    pub fn plain(self) -> (f64, f64, f64, f64) {
        (self.from, self.to, self.curvature, self.step)
    }
}

/// A margin of the grip's event ([`ChainGrip::margins`]): its value and rate, and where the modes give
/// them, its second and third derivatives, for the Taylor polynomials of
/// [`super::super::super::events::first_rise_predicted_from_tangent`], the crossing predicted from
/// them at both ends of its interval, and its refinement by the cubic Taylor model (the (f, f', f'',
/// f''') branch's step; Newton's from the secant point without them).
#[derive(Clone, Copy, Debug)]
pub struct Margin {
    value: f64,
    rate: f64,
    higher: Option<(f64, f64)>,
}

impl Branch for Margin {
    #[inline]
    fn value(&self) -> f64 {
        self.value
    }
    #[inline]
    fn rate(&self) -> f64 {
        self.rate
    }
    #[inline]
    fn step(&self) -> f64 {
        match self.higher {
            Some((second, third)) => (self.value, self.rate, second, third).step(),
            None => -(self.value / self.rate),
        }
    }
    #[inline]
    fn higher(&self) -> Option<(f64, f64)> {
        self.higher
    }
}

impl ChainGrip {
    /// The grip's two margins at `t` ([`Setup::grip_margins`]: F_s - mu N and -F_s - mu N), with their
    /// second and third derivatives where the modes give F'' and F'''.
    #[inline]
    pub fn margins(&self, setup: &Setup, t: f64) -> [Margin; 2] {
        self.margins_keeping(setup, t, None)
    }

    /// [`ChainGrip::margins`], keeping the modes' e^{s_i τ} in `keep` where the grip sums its shares.
    #[inline(always)]
    pub(super) fn margins_keeping(
        &self,
        setup: &Setup,
        t: f64,
        keep: Option<&mut Turns>,
    ) -> [Margin; 2] {
        let ([force, rate], higher) = self.force_keeping(setup, t, keep);
        let normal = sin_cos(setup.w * t);
        match higher {
            Some((second, third)) => setup
                .grip_margins_with_derivatives(normal, [force, rate, second, third])
                .map(|(value, rate, second, third)| Margin {
                    value,
                    rate,
                    higher: Some((second, third)),
                }),
            None => setup
                .grip_margins_given(normal, force, rate)
                .map(|(value, rate)| Margin {
                    value,
                    rate,
                    higher: None,
                }),
        }
    }

    /// The first time in the rest of the contact at which a margin ([`ChainGrip::margins`]) rises
    /// through zero, and which (0: F_s reaches +mu N, 1: -mu N), searched stage by stage
    /// ([`ChainGrip::search_stages`]) with each stage's bounds on |f''| and |f''''| (mu N adds
    /// mu N0 w² and mu N0 w⁴) and the Taylor polynomials where the margins carry f'' and f''', each
    /// crossing refined from the one predicted from them at its interval's ends. The
    /// search evaluates the force alone, keeping each evaluation's e^{s_i τ}; the state where it ends
    /// (with the time and the branch) is summed from those it kept there, to the same bits as
    /// [`ChainGrip::at`]'s. A stage's start, its predecessor's end, is not evaluated again.
    ///
    /// A grip entered where a slide's patch stopped starts with a margin on its zero (F = ±mu N). The
    /// search would check that margin at the end of a short window only and then prove the rest of its
    /// first coarse interval, in three evaluations; searched instead as the interval's two halves, the
    /// Taylor polynomials from the start (its F'' and F''' are the shares' sums, without a sine) and
    /// from the middle prove the first half, and the second is proved as any other: two evaluations,
    /// and the same points from there on.
    pub fn first_break(&self, setup: &Setup) -> Option<(f64, usize, Point)> {
        let (w, peak) = (setup.w, setup.peak_friction());
        let margin_curvature = peak * w * w;
        let (mut stages, size) = self.search_stages(setup);
        let noise = ROUNDING * (peak + size);
        // The evaluation at the end of the current search, which the next one starts from.
        let end = Cell::new(f64::NAN);
        let kept = Cell::new(None::<(f64, [Margin; 2])>);
        let turns = RefCell::new(Turns::new());
        let f = |t: f64| {
            if let Some((at, margins)) = kept.get()
                && at == t
            {
                return margins;
            }
            let margins = self.margins_keeping(setup, t, Some(&mut turns.borrow_mut()));
            if t == end.get() {
                kept.set(Some((t, margins)));
            }
            margins
        };
        // The start, kept for the first search (a margin on its zero as the search tells one).
        end.set(self.start.t);
        if f(self.start.t).iter().any(|m| m.value >= -noise) {
            // The first coarse interval as the search takes it, in halves, then the rest: three
            // searches with the first stage's bounds and step.
            let stage = stages[0];
            let first = (stage.from + stage.step).min(stage.to);
            let middle = stage.from + 0.5 * (first - stage.from);
            stages[0].to = middle;
            let part = |from, to| Stage { from, to, ..stage };
            stages.splice(1..1, [part(middle, first), part(first, stage.to)]);
        }
        let (t, branch) = stages.into_iter().find_map(|stage| {
            end.set(stage.to);
            let curvature = [stage.curvature + margin_curvature; 2];
            let fourth = [stage.fourth + margin_curvature * w * w; 2];
            let bounds = [curvature, fourth];
            let (from, to, step) = (stage.from, stage.to, stage.step);
            first_rise_predicted_from_tangent(f, from, to, step, bounds, [noise; 2])
        })?;
        let point = self.at_turns(setup, t, &turns.borrow());
        Some((t, branch, point.unwrap_or_else(|| self.at(setup, t))))
    }

    /// The stages of the event search over the rest of the contact, and the size of the terms F is
    /// summed from. A strongly damped mode dominates the bound only until it has died out: the first 40
    /// e-folds of the fastest decay are cut into stages of 4, each bounded from its start, with a step
    /// on the scale sqrt(|F''| / |F|) of its bound. Each stage also bounds |F''''| by the same modes,
    /// each |s_i|² times its share of |F''| (F'''' = Re Σ c_i s_i⁴ F_i e^{s_i τ}; pushed,
    /// Re Σ (c_i s_i + β_i) s_i³ F_i e^{s_i τ}).
    pub fn search_stages(&self, setup: &Setup) -> (Vec<Stage>, f64) {
        let (t0, end) = (self.start.t, setup.duration);
        let decay = match &self.modes.modes {
            Some(list) if self.coefficients.is_some() => {
                list.iter().map(|m| -m.s.re).fold(0.0, f64::max)
            }
            _ => 0.0,
        };
        let stage = SETTLED / 10.0 / decay;
        let cuts = (1..=10)
            .map(|k| t0 + k as f64 * stage)
            .take_while(|&t| t < end);
        let stage_from = |from: f64, (curvature, terms, fastest, fourth): (f64, f64, f64, f64)| {
            let rate = if terms > 0.0 {
                (curvature / terms).sqrt().min(fastest)
            } else {
                0.0
            };
            Stage {
                from,
                to: end,
                curvature,
                step: setup.event_step(rate),
                fourth,
            }
        };
        let mut room = [ModeSize::NONE; MODES];
        let len = self.mode_sizes(setup, &mut room);
        let sizes = &room[..len];
        let growths_at = |elapsed: f64| {
            let mut growths = [0.0; MODES];
            for (g, m) in growths.iter_mut().zip(sizes) {
                *g = growth(m.re, elapsed, end - t0);
            }
            growths
        };
        let initial = growths_at(0.0);
        let first = self.force_bounds_with(setup, sizes, &initial);
        let size = first.1;
        let mut stages = Vec::with_capacity(11);
        stages.push(stage_from(t0, first));
        // Each cut's bound on |F''| estimated first with a decaying mode's shrinking over a stage,
        // e^{Re s stage}, taken once (within 1e-12 of the bound); only a cut the estimate does not
        // clearly refuse is bounded exactly, with an exponential a mode.
        let mut estimate = initial;
        let mut shrink = [1.0; MODES];
        for (s, m) in shrink.iter_mut().zip(sizes) {
            if m.re <= 0.0 {
                *s = fast_exp(m.re * stage);
            }
        }
        // A cut pays for itself only where the bound has fallen by half since the stage began.
        for cut in cuts {
            for (g, s) in estimate[..len].iter_mut().zip(&shrink) {
                *g *= s;
            }
            let current = stages.last().expect("one stage at least").curvature;
            if curvature(sizes, &estimate) >= 0.5 * current * (1.0 + SCREEN) {
                continue;
            }
            let growths = growths_at(cut - t0);
            let next = stage_from(cut, self.force_bounds_with(setup, sizes, &growths));
            let current = stages.last_mut().expect("one stage at least");
            if next.curvature < 0.5 * current.curvature {
                current.to = cut;
                stages.push(next);
            }
        }
        (stages, size)
    }

    /// A bound on |F''| over the rest of the contact, and the size of the terms F is summed from (for
    /// the rounding floor).
    ///
    /// From `from` on: a mode decaying at -Re s has shrunk by e^(Re s (from - t0)) there, so a strongly
    /// damped mode stops counting once it has died out. Also the fastest rate still worth resolving.
    pub fn force_bounds(&self, setup: &Setup, from: f64) -> (f64, f64, f64) {
        let mut room = [ModeSize::NONE; MODES];
        let len = self.mode_sizes(setup, &mut room);
        let sizes = &room[..len];
        let (elapsed, remaining) = (from - self.start.t, setup.duration - self.start.t);
        let mut growths = [0.0; MODES];
        for (g, m) in growths.iter_mut().zip(sizes) {
            *g = growth(m.re, elapsed, remaining);
        }
        let (curvature, size, fastest, _) = self.force_bounds_with(setup, sizes, &growths);
        (curvature, size, fastest)
    }

    /// Per mode, what [`ChainGrip::force_bounds`] scales by the mode's growth: its share of the bound
    /// on |F''| and of the size of F's terms, and |s_i| (empty where the modes do not reproduce the
    /// start). They stay the same over the grip, so the event search's stages take them once. Written
    /// into `room` (no allocation); returns how many.
    fn mode_sizes(&self, setup: &Setup, room: &mut [ModeSize; MODES]) -> usize {
        let remaining = setup.duration - self.start.t;
        let (Some(list), Some(c)) = (&self.modes.modes, &self.coefficients) else {
            return 0;
        };
        list.iter()
            .zip(c)
            .enumerate()
            .map(|(i, (mode, ci))| {
                // Pushed, F'' = Re Σ (c_i s_i + β_i) s_i e^{s_i τ} and the push's share of F is
                // β_i (e^{s_i τ} - 1)/s_i, at most |β_i| τ e^{max(Re s_i, 0) τ}.
                let (part, term, squared) = match &self.beta {
                    Some(beta) => {
                        let rate = (ci * mode.s + beta[i]) * mode.force;
                        let shift = (beta[i] * mode.force).norm() * remaining;
                        let part = rate.norm() * mode.rate;
                        (part, (ci * mode.force).norm() + shift, false)
                    }
                    None => ((ci * mode.force).norm(), 0.0, true),
                };
                ModeSize {
                    re: mode.s.re,
                    part,
                    term,
                    squared: squared.then(|| mode.s.norm_sqr()),
                    rate: mode.rate,
                }
            })
            .zip(room.iter_mut())
            .fold(0, |len, (size, slot)| {
                *slot = size;
                len + 1
            })
    }

    /// [`ChainGrip::force_bounds`] given [`ChainGrip::mode_sizes`] and each mode's growth, with a bound
    /// on |F''''| (each mode's share of the bound on |F''| times |s_i|²; infinite without the modes).
    fn force_bounds_with(
        &self,
        setup: &Setup,
        sizes: &[ModeSize],
        growths: &[f64; MODES],
    ) -> (f64, f64, f64, f64) {
        let g = &self.modes;
        match (&g.modes, &self.coefficients) {
            (Some(_), Some(_)) => {
                let (mut curvature, mut size, mut fourth) = (0.0, 0.0, 0.0);
                let mut parts = [0.0; MODES];
                for ((m, slot), &growth) in sizes.iter().zip(&mut parts).zip(growths) {
                    let (part, term) = match m.squared {
                        None => (m.part * growth, m.term * growth),
                        Some(squared) => {
                            let term = m.part * growth;
                            (term * squared, term)
                        }
                    };
                    curvature += part;
                    size += term;
                    fourth += part * (m.rate * m.rate);
                    *slot = part;
                }
                let fastest = sizes
                    .iter()
                    .zip(parts)
                    .filter(|(_, part)| *part >= NEGLIGIBLE * curvature)
                    .map(|(m, _)| m.rate)
                    .fold(0.0, f64::max);
                (curvature, size, fastest, fourth)
            }
            _ => {
                // |h z| <= |T⁻ᵀ hᵀ| sqrt(2E), and F'' = h A² z = (T⁻ᵀ hᵀ)ᵀ Ã² z̃; the dashpot only lowers E.
                let dof = g.n + 1;
                let mut stretch = vec![0.0; 2 * dof];
                stretch[0] = 1.0;
                for j in 0..g.n {
                    stretch[j + 1] = -g.phi1[j];
                }
                let mut rate = vec![0.0; 2 * dof];
                rate[dof..].copy_from_slice(&stretch[..dof]);
                let force: Vec<f64> = (0..2 * dof)
                    .map(|i| g.kb * stretch[i] + g.cb * rate[i])
                    .collect();
                if self.push != 0.0 {
                    let (curvature, _) = self.energy_bounds(setup, &force);
                    let (_, stretch) = self.energy_bounds(setup, &stretch);
                    let (_, rate) = self.energy_bounds(setup, &rate);
                    let terms = stretch * g.kb + rate * g.cb;
                    return (curvature, terms, g.fastest, f64::INFINITY);
                }
                let second = g.a.transpose() * g.a.transpose() * g.dual(&force);
                let size = g.energy_norm(&self.z0);
                (
                    second.norm() * size,
                    (g.dual(&stretch).norm() * g.kb + g.dual(&rate).norm() * g.cb) * size,
                    g.fastest,
                    f64::INFINITY,
                )
            }
        }
    }

    /// For the first mass's stopping: a bound on |V_1''| over the rest of the contact, and the size of
    /// the terms V_1 is summed from. In the modes V_1 = Re Σ (c_i s_i + β_i) e^{s_i τ} X_1i (X_1i the
    /// first mass in mode i), so |V_1''| <= Σ |(c_i s_i + β_i) X_1i| |s_i|² e^{max(Re s_i, 0) τ}. On a
    /// free frame the same for V_1 - V_f, the first mass relative to the frame (X_1i - X_fi; the
    /// translation moves both alike).
    pub fn first_mass_bounds(&self, setup: &Setup) -> (f64, f64) {
        let g = &self.modes;
        let remaining = setup.duration - self.start.t;
        let frame = self.start.frame;
        let start = (self.start.v[0] - if frame > 0 { self.start.v[frame] } else { 0.0 }).abs();
        // The still modes move V_f alone.
        let (still_curvature, still_size) = self.still_bounds(|m| m.frame);
        let (curvature, size) = match (&g.modes, &self.coefficients) {
            (Some(list), Some(c)) => {
                let (mut curvature, mut size) = (0.0, start);
                for (i, (mode, ci)) in list.iter().zip(c).enumerate() {
                    let beta = self.beta.as_ref().map_or(C64::new(0.0, 0.0), |b| b[i]);
                    let share = match g.frame_shares.get(i) {
                        Some(&xf) => mode.u - mode.e - xf,
                        None => mode.u - mode.e,
                    };
                    let term =
                        ((ci * mode.s + beta) * share).norm() * growth(mode.s.re, 0.0, remaining);
                    curvature += term * mode.s.norm_sqr();
                    size += term;
                }
                (curvature, size)
            }
            _ => {
                // The first mass's row (relative to the frame on a free one) is the push's.
                let mut first = vec![0.0; 2 * g.n + 2];
                first[g.n + 2..].copy_from_slice(&g.push_row[..g.n]);
                let (curvature, size) = self.energy_bounds(setup, &first);
                (curvature, size + start)
            }
        };
        (curvature + still_curvature, size + still_size)
    }

    /// For a row h in z-coordinates, bounds on |h z''| and |h z| over the rest of the contact through
    /// the energy norm: |h z| <= |T⁻ᵀ hᵀ| sqrt(2E), z'' = A² z + A b, and sqrt(2E) grows at most at
    /// |b̃| = |P| (Σ Φ_1j²)^(1/2) under the push (the dashpot only lowers it).
    fn energy_bounds(&self, setup: &Setup, h: &[f64]) -> (f64, f64) {
        let g = &self.modes;
        let push = self.push.abs();
        let unit: f64 = g.push_row[..g.n].iter().map(|p| p * p).sum::<f64>().sqrt();
        let reach = g.energy_norm(&self.z0) + push * unit * (setup.duration - self.start.t);
        let dual = g.dual(h);
        let second = g.a.transpose() * g.a.transpose() * &dual;
        let mut forcing = DVector::<f64>::zeros(2 * g.n + 2);
        for j in 0..g.n {
            forcing[g.n + 2 + j] = g.push_row[j];
        }
        let constant = (dual.transpose() * &g.a * forcing)[0].abs() * push;
        (second.norm() * reach + constant, dual.norm() * reach)
    }
}

/// One mode's constant shares of [`ChainGrip::force_bounds`], before its growth.
#[derive(Clone, Copy)]
struct ModeSize {
    /// Re s_i, which sets the growth.
    re: f64,
    /// Pushed: |(c_i s_i + β_i) F_i| |s_i|; otherwise |c_i F_i|.
    part: f64,
    /// Pushed: |c_i F_i| + |β_i F_i| (t_end - t0) (otherwise unused).
    term: f64,
    /// Unpushed: |s_i|², by which the grown |c_i F_i| bounds the mode's |F''|.
    squared: Option<f64>,
    /// |s_i|.
    rate: f64,
}

impl ModeSize {
    /// An unused slot of [`ChainGrip::mode_sizes`]'s room.
    const NONE: ModeSize = ModeSize {
        re: 0.0,
        part: 0.0,
        term: 0.0,
        squared: None,
        rate: 0.0,
    };
}

/// The bound on |F''| of [`ChainGrip::force_bounds_with`]'s modes alone, given their growths.
fn curvature(sizes: &[ModeSize], growths: &[f64; MODES]) -> f64 {
    sizes
        .iter()
        .zip(growths)
        .map(|(m, &growth)| match m.squared {
            None => m.part * growth,
            Some(squared) => m.part * growth * squared,
        })
        .sum()
}

/// How much a mode of rate s may have grown (or least shrunk) over the contact from `elapsed` after the
/// grip's start: e^{Re s elapsed} for a decaying mode, e^{Re s remaining} otherwise.
fn growth(re: f64, elapsed: f64, remaining: f64) -> f64 {
    if re <= 0.0 {
        // e^0 = 1 exactly, without the call.
        if elapsed == 0.0 {
            return 1.0;
        }
        (re * elapsed).exp()
    } else {
        (re * remaining).exp()
    }
}
