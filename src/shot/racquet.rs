//! The racquet in the hand: a rigid body whose strings the ball meets at one point of the long axis, free
//! to recoil and turn (the hand's force over the few ms of contact is neglected). Seen from the impact
//! point it is a frame of effective mass M_n normal to the strings and M_t along them (issue 23):
//!
//! - I_cm = SW - M_r (balance - 10 cm)^2 (the swing weight SW is quoted about an axis 10 cm from the
//!   butt; parallel-axis theorem),
//! - b = impact - balance, the impact point's distance from the centre of mass,
//! - 1/M_n = 1/M_r + b^2/I_cm: a normal impulse J at b moves the centre by J/M_r and turns the racquet
//!   in its swing plane by J b/I_cm,
//! - 1/M_t = 1/M_r + b^2/(I_cm + TW): a force along the face, across the long axis, turns it in the
//!   face's plane, whose moment of inertia is I_cm + TW (perpendicular-axis theorem).
//!
//! On a frame of normal mass M_n a ball of mass m leaves with the apparent restitution
//! e_A = (e_y M_n - m)/(M_n + m), e_y being its restitution on a clamped frame.

use crate::model::setup::apparent_restitution;
use crate::model::{Bounce, Params};

/// The axis the swing weight is quoted about, from the butt, m.
pub const SWING_AXIS: f64 = 0.10;

/// kg m^2 in kg cm^2, for messages.
const KG_CM2: f64 = 1e4;

/// A racquet's mass distribution and where the ball meets it (SI: kg, m, kg m^2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Racquet {
    /// M_r.
    pub mass: f64,
    /// The centre of mass from the butt.
    pub balance: f64,
    /// SW, about an axis [`SWING_AXIS`] from the butt.
    pub swing_weight: f64,
    /// TW, about the long axis.
    pub twist_weight: f64,
    /// The impact point from the butt.
    pub impact: f64,
}

/// How the strings are held: an immovable racquet (the paper's wall) or a racquet in the hand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Hold {
    Clamped,
    Hand(Racquet),
}

/// A racquet that cannot be: its mass, balance and swing weight leave no moment of inertia about its
/// centre of mass.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "--swing-weight {sw} kg cm^2 is too small for --racquet-mass {mass} g at --balance {balance} cm: \
     the moment of inertia about the centre of mass, I_cm = SW - M_r (balance - 10 cm)^2 = {sw} - {parallel} \
     = {i_cm} kg cm^2, must be above 0"
)]
pub struct RacquetError {
    sw: String,
    mass: String,
    balance: String,
    parallel: String,
    i_cm: String,
}

/// The racquet's recoil at the impact point from the ball's impulse: its velocity change, m/s, normal
/// to the strings (away from the ball) and along them (the way the ball's impulse pushes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Recoil {
    pub normal: f64,
    pub tangential: f64,
}

impl Recoil {
    /// The speed change's magnitude, m/s.
    pub fn speed(&self) -> f64 {
        self.normal.hypot(self.tangential)
    }
}

impl Racquet {
    /// I_cm = SW - M_r (balance - 10 cm)^2, kg m^2.
    pub fn moment_about_centre(&self) -> f64 {
        self.swing_weight - self.parallel()
    }

    /// M_r (balance - 10 cm)^2, the parallel-axis term.
    fn parallel(&self) -> f64 {
        self.mass * (self.balance - SWING_AXIS).powi(2)
    }

    /// M_n: 1/M_n = 1/M_r + b^2/I_cm, kg.
    pub fn effective_mass_normal(&self) -> f64 {
        self.effective_mass(self.moment_about_centre())
    }

    /// M_t: 1/M_t = 1/M_r + b^2/(I_cm + TW), kg.
    pub fn effective_mass_tangential(&self) -> f64 {
        self.effective_mass(self.moment_about_centre() + self.twist_weight)
    }

    /// The mass an impulse at the impact point sees on a body of moment of inertia `moment` about the
    /// centre of mass for the turn it causes.
    fn effective_mass(&self, moment: f64) -> f64 {
        let b = self.impact - self.balance;
        1.0 / (1.0 / self.mass + b * b / moment)
    }
}

impl Hold {
    /// The racquet of a shot's parameters; `racquet_mass` 0 is clamped.
    pub fn of(p: &Params) -> Result<Hold, RacquetError> {
        if p.racquet_mass == 0.0 {
            return Ok(Hold::Clamped);
        }
        let racquet = Racquet {
            mass: p.racquet_mass,
            balance: p.balance,
            swing_weight: p.swing_weight,
            twist_weight: p.twist_weight,
            impact: p.impact,
        };
        let i_cm = racquet.moment_about_centre();
        // NaN fails this test too.
        if i_cm.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            let shown = |v: f64| crate::model::units::brief(v, 4);
            return Err(RacquetError {
                sw: shown(racquet.swing_weight * KG_CM2),
                mass: shown(racquet.mass * 1e3),
                balance: shown(racquet.balance * 1e2),
                parallel: shown(racquet.parallel() * KG_CM2),
                i_cm: shown(i_cm * KG_CM2),
            });
        }
        Ok(Hold::Hand(racquet))
    }

    /// (M_n, M_t), kg; `None` when clamped (both infinite).
    pub fn effective_masses(&self) -> Option<(f64, f64)> {
        match self {
            Hold::Clamped => None,
            Hold::Hand(r) => Some((r.effective_mass_normal(), r.effective_mass_tangential())),
        }
    }

    /// The frame the core ties the strings to, as its parameters `(frame_mass, frame_normal_mass)`: M_t and
    /// M_n, or 0 and 0 (the wall) when clamped.
    pub fn frame_masses(&self) -> (f64, f64) {
        self.effective_masses()
            .map_or((0.0, 0.0), |(normal, tangential)| (tangential, normal))
    }

    /// e_A = (e_y M_n - m)/(M_n + m) for a ball of mass `m` with restitution `ey` on clamped strings;
    /// `ey` itself when clamped.
    pub fn ey_apparent(&self, ey: f64, m: f64) -> f64 {
        self.effective_masses()
            .map_or(ey, |(normal, _)| apparent_restitution(ey, m, normal))
    }

    /// The racquet's velocity change at the impact point from the ball's impulse in `bounce` (solved in
    /// the frame of the strings before the contact): J_n / M_n normal to the strings, with
    /// J_n = m (v_y1 + v_y2), and J_t / M_t along them, with J_t = m (v_x1 - v_x2).
    pub fn recoil(&self, bounce: &Bounce) -> Recoil {
        match self.effective_masses() {
            None => Recoil {
                normal: 0.0,
                tangential: 0.0,
            },
            Some((normal, tangential)) => {
                let m = bounce.setup.m;
                let o = &bounce.outcome;
                Recoil {
                    normal: m * (bounce.setup.vy1 + o.vy2) / normal,
                    tangential: m * (bounce.setup.vx1 - o.vx2) / tangential,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The typical racquet: 320 g, balance 33 cm, SW 320 and TW 14 kg cm^2, struck at 52 cm.
    fn typical() -> Racquet {
        Racquet {
            mass: 0.320,
            balance: 0.33,
            swing_weight: 320e-4,
            twist_weight: 14e-4,
            impact: 0.52,
        }
    }

    #[test]
    fn the_typical_racquet_is_181_g_normal_to_the_strings_and_gives_e_a_041() {
        let r = typical();
        let i_cm = 0.0320 - 0.320 * 0.23 * 0.23;
        assert!((r.moment_about_centre() - i_cm).abs() < 1e-15);
        let normal = 1.0 / (1.0 / 0.320 + 0.19 * 0.19 / i_cm);
        let tangential = 1.0 / (1.0 / 0.320 + 0.19 * 0.19 / (i_cm + 14e-4));
        assert!((r.effective_mass_normal() - normal).abs() < 1e-15);
        assert!((r.effective_mass_tangential() - tangential).abs() < 1e-15);
        assert!((r.effective_mass_normal() - 0.181).abs() < 0.5e-3);
        assert!(r.effective_mass_tangential() > r.effective_mass_normal());
        let e_a = Hold::Hand(r).ey_apparent(0.85, 0.057);
        assert!((e_a - (0.85 * normal - 0.057) / (normal + 0.057)).abs() < 1e-15);
        assert!((e_a - 0.41).abs() < 0.005, "{e_a}");
    }

    #[test]
    fn at_the_centre_of_mass_the_racquet_is_its_whole_mass() {
        let r = Racquet {
            impact: 0.33,
            ..typical()
        };
        assert_eq!(r.effective_mass_normal(), 0.320);
        assert_eq!(r.effective_mass_tangential(), 0.320);
        // Further out the racquet turns more and is lighter to the ball.
        let tip = Racquet {
            impact: 0.60,
            ..typical()
        };
        assert!(tip.effective_mass_normal() < typical().effective_mass_normal());
    }

    #[test]
    fn clamped_is_the_wall() {
        let p = Params {
            racquet_mass: 0.0,
            ..Params::default()
        };
        let hold = Hold::of(&p).unwrap();
        assert_eq!(hold, Hold::Clamped);
        assert_eq!(hold.effective_masses(), None);
        assert_eq!(hold.ey_apparent(0.85, 0.057), 0.85);
        // A very heavy racquet approaches it.
        let heavy = Hold::Hand(Racquet {
            mass: 1e6,
            swing_weight: 1e6,
            ..typical()
        });
        assert!((heavy.ey_apparent(0.85, 0.057) - 0.85).abs() < 1e-6);
    }

    #[test]
    fn the_default_shot_is_struck_by_the_typical_racquet() {
        assert_eq!(Hold::of(&Params::default()), Ok(Hold::Hand(typical())));
    }

    #[test]
    fn a_racquet_without_moment_of_inertia_names_the_flags_and_values() {
        let p = Params {
            swing_weight: 100e-4,
            ..Params::default()
        };
        let err = Hold::of(&p).unwrap_err().to_string();
        assert_eq!(
            err,
            "--swing-weight 100 kg cm^2 is too small for --racquet-mass 320 g at --balance 33 cm: the \
             moment of inertia about the centre of mass, I_cm = SW - M_r (balance - 10 cm)^2 = 100 - \
             169.3 = -69.28 kg cm^2, must be above 0"
        );
    }
}
