//! What a compliant ball asks of the free frame's phase while its patch slides on a moving cart: the
//! ball, the cart and the frame then move exactly as under a sliding rigid ball (the ball's force is
//! F = dir mu N(t) either way), so the compliant ball on the single cart tied to a free frame slides by
//! [`FrameMotion`] itself, not by the chain's modes for one mass and its frame. (Held to the frame by
//! string friction, the compliant ball meets cart and frame as one body, `compliant/held_frame.rs`.)

use super::super::contact::Cart;
use super::super::setup::{Setup, State};
use super::super::trig::sin_cos;
use super::sums::SlipSums;
use super::{FrameMotion, FrameState, FramedCart};

/// One instant of a slide on the free frame, as the compliant ball reads it.
#[derive(Clone, Copy, Debug)]
pub struct Sliding {
    /// The ball and the cart (`x` the spring's stretch y, `v` the cart's velocity).
    pub state: State,
    /// The friction on the ball, positive backward, and its rate.
    pub friction: f64,
    pub friction_rate: f64,
    /// The cart's acceleration.
    pub accel: f64,
    /// The frame's velocity and acceleration along the surface.
    pub frame: (f64, f64),
}

/// A detuned slide's slip on the free frame written once for the phase (`sums.rs`), as the compliant
/// ball's event search reads it: that search adds its stretch's rates, which need sin and cos of w τ,
/// the angle the slip's sums share with them, so that an evaluation is one `sin_cos2` and a dozen
/// products, and the state is computed only where the search ends.
#[derive(Clone, Copy, Debug)]
pub struct SlideSums<'a> {
    motion: &'a FrameMotion,
    sums: SlipSums,
}

impl SlideSums<'_> {
    /// The event's value at the phase's start and its constant term, for the event -dir (slip - offset)
    /// measured from `offset`.
    pub fn constants(&self, offset: f64) -> (f64, f64) {
        self.sums.constants(offset)
    }

    /// The event -dir (slip - offset) and its rate at `t`, given [`SlideSums::constants`], with sin and
    /// cos of w τ there.
    #[inline(always)]
    pub fn at(&self, setup: &Setup, t: f64, constants: (f64, f64)) -> ((f64, f64), (f64, f64)) {
        let angles = self.motion.angles(setup, t);
        let (value, rate, _, _) = self.sums.event(angles, constants);
        ((value, rate), angles.1)
    }
}

impl FrameMotion {
    /// The slip's sums of a slide whose cart moves on a spring without string friction and whose
    /// response is detuned (else `None`).
    pub fn slide_sums(&self, setup: &Setup) -> Option<SlideSums<'_>> {
        SlipSums::new(self, setup).map(|sums| SlideSums { motion: self, sums })
    }

    /// A slide (`dir` ±1) of the ball on `frame`'s cart from `start`, the cart moving relative to the
    /// frame in direction `cart` (which only string friction heeds).
    pub fn slide(setup: &Setup, frame: &FramedCart, start: FrameState, dir: f64, cart: i8) -> Self {
        FrameMotion::new(setup, frame, start, dir, Cart::Moving(cart))
    }

    /// Everything at `t`. The frame is pushed by the spring and the string friction, M_t X_f'' = k z
    /// with z = y + d F_c/k (see the module).
    #[inline]
    pub fn sliding_at(&self, setup: &Setup, t: f64) -> Sliding {
        let (p, _) = self.moving_at(setup, t);
        let frame_accel = setup.k * (p.state.s.x + self.string) / self.frame;
        Sliding {
            state: p.state.s,
            friction: p.friction,
            friction_rate: p.friction_rate,
            accel: p.accel,
            frame: (p.state.vf, frame_accel),
        }
    }

    /// A bound on the second derivative of the ball's slip over the rest of the contact (as the rigid
    /// ball's search bounds it), and the size of the terms the slip is summed from beyond the ball's and
    /// the cart's speeds (the frame's speed and the stretch's).
    pub fn slip_bounds(&self, setup: &Setup) -> (f64, f64) {
        let stretch_speed = self.stretch_speed(setup);
        (
            self.slip_curvature(setup, stretch_speed),
            self.start.vf.abs() + stretch_speed,
        )
    }

    /// A bound on the second derivative of its velocity relative to the frame, the
    /// stretch's y'' = F'/M - Ω² y' with |y'| at most the stretch's speed bound, and the size of the terms
    /// that velocity is summed from.
    pub fn stop_bounds(&self, setup: &Setup) -> (f64, f64) {
        let stretch_speed = self.stretch_speed(setup);
        let force_rate = setup.peak_friction() * setup.w;
        (
            force_rate / self.cart + self.omega * self.omega * stretch_speed,
            self.start.s.v.abs() + self.start.vf.abs() + stretch_speed,
        )
    }

    /// The frame's displacement at `t`, given the stretch y there and the frame's displacement `x0` at
    /// the phase's start. The centre of mass of the cart and the frame, X_c = X_f + (M/B) y with
    /// B = M + M_t, moves as the momentum P = P0 + J says: X_c = X_c0 + (P0 τ + ∫J)/B, with
    /// ∫J = F0 (τ cos w t0 - (sin w t - sin w t0)/w)/w (the frame's rigid-body mode, polynomial in τ
    /// besides the impulse's sine).
    pub fn frame_displacement(&self, setup: &Setup, t: f64, y: f64, x0: f64) -> f64 {
        let s0 = &self.start.s;
        let tau = t - s0.t;
        let body = self.cart + self.frame;
        let w = setup.w;
        let pushed = if tau == 0.0 {
            0.0
        } else {
            let (sin_w_tau, cos_w_tau) = sin_cos(w * tau);
            // sin w t - sin w t0.
            let rise = self.sin_wt0 * (cos_w_tau - 1.0) + self.cos_wt0 * sin_w_tau;
            self.dir * setup.peak_friction() * (tau * self.cos_wt0 - rise / w) / w
        };
        x0 + (self.cart * (s0.x - y) + self.p0 * tau + pushed) / body
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::contact::{Ball, Contact};
    use super::super::super::params::Params;
    use super::*;

    /// The slip's sums as the compliant ball's search reads them give the event the full state gives,
    /// -dir (slip - offset) and its rate, to rounding, with sin and cos of w τ as computed alone: from
    /// first contact and from a quarter of the contact, on frames of 188 g and 20 g.
    #[test]
    fn the_slide_s_sums_give_the_full_state_s_slip() {
        for frame in [0.188, 0.02] {
            let params = Params {
                frame_mass: frame,
                ..Params::default()
            };
            let setup = Setup::new(&params);
            let model = FramedCart::new(&params, &setup, frame).unwrap();
            let (start, mode) = model.start(&setup);
            let Ball::Slide(dir) = mode.0 else {
                panic!("Fig. 3(c) starts sliding")
            };
            let first = model.motion(&setup, &start, mode);
            let later = first.moving_at(&setup, 0.25 * setup.duration).0.state;
            let again = model.motion(&setup, &later, mode);
            let speeds = setup.vx1.abs() + setup.r * start.s.omega.abs();
            for (motion, from) in [(first, start), (again, later)] {
                let t0 = from.s.t;
                let sums = motion.slide_sums(&setup).expect("a detuned slide");
                for offset in [0.0, 0.25 * setup.slip(&from.s)] {
                    let constants = sums.constants(offset);
                    for i in 0..=40 {
                        let t = t0 + (setup.duration - t0) * f64::from(i) / 40.0;
                        let ((value, rate), angle) = sums.at(&setup, t, constants);
                        let p = motion.sliding_at(&setup, t);
                        let exact = -dir * (setup.slip(&p.state) - offset);
                        let exact_rate = dir * (p.friction / setup.m_eff + p.accel);
                        assert!(
                            (value - exact).abs() <= 1e-13 * speeds,
                            "{value} {exact} at {t}"
                        );
                        assert!(
                            (rate - exact_rate).abs() <= 1e-12 * speeds / setup.duration,
                            "{rate} {exact_rate} at {t}"
                        );
                        let (s, c) = sin_cos(setup.w * (t - t0));
                        assert!((angle.0 - s).abs() <= 1e-15 && (angle.1 - c).abs() <= 1e-15);
                    }
                }
            }
        }
    }
}
