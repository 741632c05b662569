//! The forces on a spinning ball in flight: gravity, air drag against the velocity and Magnus lift
//! perpendicular to it, with Stepanek's fits for a tennis ball (A. Stepanek, "The aerodynamics of tennis
//! balls: the topspin lob", Am. J. Phys. 56, 138, 1988).

/// Acceleration of gravity, m/s^2.
pub const GRAVITY: f64 = 9.81;
/// Density of air, kg/m^3.
pub const AIR_DENSITY: f64 = 1.21;

/// The air the ball flies through; drag and lift can be switched off to test the flight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Air {
    pub density: f64,
    pub drag: bool,
    pub lift: bool,
}

impl Air {
    /// Still air at 1.21 kg/m^3, with drag and lift.
    pub const STILL: Air = Air {
        density: AIR_DENSITY,
        drag: true,
        lift: true,
    };
    /// No air: a parabola.
    pub const VACUUM: Air = Air {
        density: 0.0,
        drag: false,
        lift: false,
    };
}

/// Drag coefficient C_D = 0.55 + 1/(22.5 + 4.2 (v/v_s)^2.5)^0.4, with v_s = r |omega| (Stepanek 1988);
/// `ratio` is v/v_s (infinite without spin, where C_D = 0.55).
pub fn drag_coefficient(ratio: f64) -> f64 {
    if ratio.is_infinite() {
        return 0.55;
    }
    0.55 + (22.5 + 4.2 * ratio * ratio * ratio.sqrt()).powf(-0.4)
}

/// Lift coefficient C_L = 1/(2 + v/v_s) (Stepanek 1988); 0 without spin.
pub fn lift_coefficient(ratio: f64) -> f64 {
    1.0 / (2.0 + ratio)
}

/// A ball in flight: what the forces on it depend on besides its velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projectile {
    /// m, kg.
    pub mass: f64,
    /// r, m.
    pub radius: f64,
    /// Spin about z (counter-clockwise positive), rad/s; constant in flight (no spin decay).
    pub omega_z: f64,
    pub air: Air,
}

impl Projectile {
    /// The acceleration at velocity (vx, vy): gravity, drag 1/2 rho C_D A v^2 against the velocity and
    /// lift 1/2 rho C_L A v^2 along omega x v (topspin pushes down), A = pi r^2.
    pub fn acceleration(&self, vx: f64, vy: f64) -> (f64, f64) {
        let v = vx.hypot(vy);
        let spin_speed = self.radius * self.omega_z.abs();
        let ratio = v / spin_speed;
        // 1/2 rho A v / m; times C v gives the force per unit mass.
        let k = 0.5 * self.air.density * std::f64::consts::PI * self.radius * self.radius * v
            / self.mass;
        let mut ax = 0.0;
        let mut ay = -GRAVITY;
        if self.air.drag && v > 0.0 {
            let cd = k * drag_coefficient(ratio);
            ax -= cd * vx;
            ay -= cd * vy;
        }
        if self.air.lift && v > 0.0 && spin_speed > 0.0 {
            let cl = k * lift_coefficient(ratio) * self.omega_z.signum();
            ax -= cl * vy;
            ay += cl * vx;
        }
        (ax, ay)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stepanek_limits() {
        assert_eq!(drag_coefficient(f64::INFINITY), 0.55);
        assert!((drag_coefficient(0.0) - (0.55 + 22.5f64.powf(-0.4))).abs() < 1e-15);
        assert_eq!(lift_coefficient(f64::INFINITY), 0.0);
        assert_eq!(lift_coefficient(0.0), 0.5);
        // Faster spin, more drag and more lift.
        assert!(drag_coefficient(1.0) > drag_coefficient(3.0));
        assert!(lift_coefficient(1.0) > lift_coefficient(3.0));
    }

    #[test]
    fn topspin_pushes_down_and_drag_holds_back() {
        let ball = Projectile {
            mass: 0.057,
            radius: 0.033,
            omega_z: -200.0,
            air: Air::STILL,
        };
        let (ax, ay) = ball.acceleration(30.0, 0.0);
        assert!(ax < 0.0 && ay < -GRAVITY);
        let back = Projectile {
            omega_z: 200.0,
            ..ball
        };
        assert!(back.acceleration(30.0, 0.0).1 > -GRAVITY);
        let vacuum = Projectile {
            air: Air::VACUUM,
            ..ball
        };
        assert_eq!(vacuum.acceleration(30.0, 5.0), (0.0, -GRAVITY));
    }
}
