//! The free frame's event functions written once per phase, where the cart moves relative to the frame
//! on a spring without string friction: a detuned slide's slip and a grip's margins as fixed combinations
//! of sin and cos of the stretch's angle Ωτ and of the normal force's, each with its first three
//! derivatives (each derivative turns each oscillation a quarter and scales it by its frequency), so
//! that an evaluation of the event search is a dozen products after one `sin_cos2` and the state is
//! computed only where the search ends. The frame's rigid-body mode enters through the momentum P, which
//! only the ball's impulse changes: its terms are those of the impulse, with tau and 1 for its sine and
//! cosine. (The clamped single cart's sums, `cart/slide.rs` and `cart/grip.rs`, are the limit M_t -> ∞.)

use super::super::setup::Setup;
use super::super::sums::{ForceSums, SlipTerms};
use super::FrameMotion;

/// sin and cos of Ωτ (τ the time since the phase began), and of the normal force's angle: w τ sliding,
/// w t gripping.
pub type Angles = ((f64, f64), (f64, f64));

/// The slip event of a detuned slide on the free frame. With B = M + M_t, the cart's velocity is
/// V = (P + M_t y')/B (see [`FrameMotion`]), the momentum P = P0 + J with the ball's impulse
/// J = F0 (cos w t0 - cos w t)/w, and the stretch's rate y' = A w cos w t + b cos Ωτ - a Ω sin Ωτ with
/// a = y0 - A sin w t0, b = y0' - A w cos w t0 (the particular and free responses). The ball's contact
/// point slips at u' = u0' - J/m_eff, so the slip u' - V is, with R = 1/m_eff + 1/B,
/// u0' - P0/B - F0 R cos(w t0)/w + (F0 R/w - (M_t/B) A w) cos w t - (M_t/B) (b cos Ωτ - a Ω sin Ωτ),
/// and the event -dir (slip - offset) is its constant less (P/w) cos w t + B' cos Ωτ - Q sin Ωτ, with
/// P = dir (F0 R - (M_t/B) A w²), B' = dir (M_t/B) b, Q = dir (M_t/B) a Ω.
#[derive(Clone, Copy, Debug)]
pub struct SlipSums {
    dir: f64,
    /// The slip at the phase's start, from its state.
    slip0: f64,
    /// The contact point's speed u0' and the momentum's share P0/B at the start.
    contact: f64,
    momentum: f64,
    /// dir F0 R cos(w t0)/w.
    impulse0: f64,
    terms: SlipTerms,
}

impl SlipSums {
    /// The sums of `motion`, a slide whose cart moves on a spring without string friction and whose
    /// response is detuned (else `None`).
    pub fn new(motion: &FrameMotion, setup: &Setup) -> Option<Self> {
        let amplitude = motion.amplitude?;
        let (w, omega, dir) = (setup.w, motion.omega, motion.dir);
        if motion.held || motion.string != 0.0 || omega == 0.0 || dir == 0.0 {
            return None;
        }
        let s0 = &motion.start.s;
        let body = motion.cart + motion.frame;
        let share = motion.frame / body;
        let force_amplitude = dir * setup.peak_friction();
        let inverse = 1.0 / setup.m_eff + 1.0 / body;
        let (y0, dy0) = (s0.x, s0.v - motion.start.vf);
        let ball = dir * (force_amplitude * inverse - share * amplitude * w * w);
        let free_cos = dir * share * (dy0 - amplitude * w * motion.cos_wt0);
        let free_sin = dir * share * (y0 - amplitude * motion.sin_wt0) * omega;
        Some(SlipSums {
            dir,
            slip0: setup.slip(s0),
            contact: s0.vx - setup.r * s0.omega,
            momentum: motion.p0 / body,
            impulse0: dir * force_amplitude * inverse * motion.cos_wt0 / w,
            terms: SlipTerms::new(
                (motion.sin_wt0, motion.cos_wt0),
                (w, omega),
                [ball, free_cos, free_sin],
            ),
        })
    }

    /// Bounds on the event's second and fourth derivatives over the phase ([`SlipTerms::bounds`]).
    pub fn bounds(&self, setup: &Setup, omega: f64) -> [f64; 2] {
        self.terms.bounds(setup.w, omega)
    }

    /// The event's value at the phase's start, exactly dir (offset - slip0), so that rounding cannot
    /// fake a crossing there when the offset is the start's slip, and its constant term,
    /// dir (offset - u0' + P0/B) + dir F0 R cos(w t0)/w, for the event measured from `offset`.
    pub fn constants(&self, offset: f64) -> (f64, f64) {
        let dir = self.dir;
        (
            dir * (offset - self.slip0),
            dir * (offset - self.contact + self.momentum) + self.impulse0,
        )
    }

    /// The event -dir (slip - offset) and its first three derivatives, given the slide's `Angles`
    /// and [`SlipSums::constants`].
    #[inline(always)]
    pub fn event(
        &self,
        ((s, c), (sin_w_tau, cos_w_tau)): Angles,
        constants: (f64, f64),
    ) -> (f64, f64, f64, f64) {
        self.terms.event((sin_w_tau, cos_w_tau), (s, c), constants)
    }
}

/// The static friction of a grip on the free frame whose cart moves on a spring without string
/// friction, F_s = g y with g = k m_eff/(M + m_eff) (Eq. (5) with the stretch y for X) and
/// y = y0 cos Ωτ + (y0'/Ω) sin Ωτ, Ω = Ω_g, as fixed combinations of sin and cos of Ωτ (else `None`).
pub fn force_sums(motion: &FrameMotion, setup: &Setup) -> Option<ForceSums> {
    let omega = motion.omega;
    if motion.held || motion.string != 0.0 || omega == 0.0 || motion.dir != 0.0 {
        return None;
    }
    let s0 = &motion.start.s;
    let gain = setup.m_eff * setup.k / motion.cart;
    Some(ForceSums::new(
        setup,
        gain,
        omega,
        (s0.x, s0.v - motion.start.vf),
    ))
}

#[cfg(test)]
mod tests {
    use super::super::super::contact::{Ball, Cart, Contact};
    use super::super::super::params::Params;
    use super::super::{FrameState, FramedCart};
    use super::*;

    /// Fig. 3(c) on frames of 188 g and 20 g, and with a light cart on a stiff spring.
    fn cases() -> Vec<(Setup, FramedCart)> {
        let base = Params::default();
        let light = Params {
            cart_mass: 0.002,
            stiffness: 40e3,
            ..base
        };
        [(base, 0.188), (base, 0.02), (light, 0.188)]
            .into_iter()
            .map(|(params, frame)| {
                let params = Params {
                    frame_mass: frame,
                    ..params
                };
                let setup = Setup::new(&params);
                let model = FramedCart::new(&params, &setup, frame).unwrap();
                (setup, model)
            })
            .collect()
    }

    /// `sums` (value and three derivatives) against `exact` (value and rate from the full state) at
    /// times across the rest of the contact: the value and rate to rounding, the second and third
    /// derivatives against central differences of the rate and the second.
    fn agree(
        setup: &Setup,
        t0: f64,
        sums: impl Fn(f64) -> (f64, f64, f64, f64),
        exact: impl Fn(f64) -> (f64, f64),
        scale: (f64, f64),
    ) {
        let h = 1e-4 * (setup.duration - t0);
        for i in 1..=20 {
            let t = t0 + (setup.duration - t0 - 2.0 * h) * f64::from(i) / 20.0;
            let (value, rate, second, third) = sums(t);
            let (exact_value, exact_rate) = exact(t);
            assert!(
                (value - exact_value).abs() <= 1e-12 * scale.0,
                "{value} {exact_value} at {t}"
            );
            assert!(
                (rate - exact_rate).abs() <= 1e-9 * scale.1,
                "{rate} {exact_rate} at {t}"
            );
            let (before, after) = (sums(t - h), sums(t + h));
            let second_by_difference = (after.1 - before.1) / (2.0 * h);
            let third_by_difference = (after.2 - before.2) / (2.0 * h);
            let size = second.abs() + third.abs() * h + scale.1 / setup.duration;
            assert!(
                (second - second_by_difference).abs() <= 1e-5 * size,
                "{second} at {t}"
            );
            let size = third.abs() + scale.1 / setup.duration.powi(2);
            assert!(
                (third - third_by_difference).abs() <= 1e-5 * size,
                "{third} at {t}"
            );
        }
    }

    #[test]
    fn the_slip_sums_are_the_slide_s_slip() {
        for (setup, model) in cases() {
            let (start, (ball, cart)) = model.start(&setup);
            let Ball::Slide(dir) = ball else {
                panic!("Fig. 3(c) starts sliding")
            };
            let first = model.motion(&setup, &start, (ball, cart));
            // From first contact, and again from where that slide stands at a quarter of the contact
            // (where the stretch, its free swing and the normal force's phase are all under way).
            let later = first.moving_at(&setup, 0.25 * setup.duration).0.state;
            let again = model.motion(&setup, &later, (ball, cart));
            for (motion, from) in [(first, start), (again, later)] {
                let t0 = from.s.t;
                let offset = 0.25 * setup.slip(&from.s);
                let sums = SlipSums::new(&motion, &setup).expect("a detuned slide");
                let constants = sums.constants(offset);
                // At the start, exactly dir (offset - slip0).
                assert_eq!(
                    sums.event(motion.angles(&setup, t0), constants).0,
                    dir * (offset - setup.slip(&from.s))
                );
                let exact = |t: f64| {
                    let (p, _) = motion.moving_at(&setup, t);
                    let rate = -p.friction / setup.m_eff - p.accel;
                    (-dir * (setup.slip(&p.state.s) - offset), -dir * rate)
                };
                // The search's bound on the second derivative holds over the rest of the contact.
                let bound = motion.slip_curvature(&setup, motion.stretch_speed(&setup));
                for i in 0..=50 {
                    let t = t0 + (setup.duration - t0) * f64::from(i) / 50.0;
                    let second = sums.event(motion.angles(&setup, t), constants).2;
                    assert!(second.abs() <= bound * (1.0 + 1e-12), "{second} {bound}");
                }
                let speeds = setup.vx1.abs() + setup.r * start.s.omega.abs();
                let scale = (speeds, speeds / setup.duration);
                agree(
                    &setup,
                    t0,
                    |t| sums.event(motion.angles(&setup, t), constants),
                    exact,
                    scale,
                );
            }
        }
    }

    #[test]
    fn the_force_sums_are_the_grip_s_margins() {
        for (setup, model) in cases() {
            // A grip from where the slide stands at a third of the contact.
            let (start, mode) = model.start(&setup);
            let slide = model.motion(&setup, &start, mode);
            let t0 = setup.duration / 3.0;
            let state: FrameState = slide.moving_at(&setup, t0).0.state;
            let grip = model.motion(&setup, &state, (Ball::Grip, Cart::Moving(1)));
            let sums = force_sums(&grip, &setup).expect("a moving grip on a spring");
            for branch in 0..2 {
                let exact = |t: f64| {
                    let (p, normal) = grip.moving_at(&setup, t);
                    let margins = setup.grip_margins_given(normal, p.friction, p.friction_rate);
                    margins[branch]
                };
                let force = setup.peak_friction() + setup.k * state.s.x.abs();
                let scale = (force, force / setup.duration);
                agree(
                    &setup,
                    t0,
                    |t| sums.margins(&setup, grip.angles(&setup, t))[branch],
                    exact,
                    scale,
                );
            }
        }
    }

    #[test]
    fn the_frame_moves_at_its_velocity() {
        for (setup, model) in cases() {
            let (start, mode) = model.start(&setup);
            let slide = model.motion(&setup, &start, mode);
            let x0 = 1e-3;
            let at = |t: f64| {
                let y = slide.moving_at(&setup, t).0.state.s.x;
                slide.frame_displacement(&setup, t, y, x0)
            };
            assert_eq!(at(0.0), x0);
            let h = 1e-6 * setup.duration;
            for i in 1..10 {
                let t = setup.duration * f64::from(i) / 10.0;
                let vf = slide.moving_at(&setup, t).0.state.vf;
                let by_difference = (at(t + h) - at(t - h)) / (2.0 * h);
                assert!(
                    (by_difference - vf).abs() <= 1e-6 * (vf.abs() + 1e-3),
                    "{by_difference} {vf}"
                );
            }
        }
    }
}
