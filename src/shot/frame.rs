//! The change to and from the paper's frame for a surface moving at constant velocity: the strings of a
//! racquet in mid-swing, or the court (at rest).
//!
//! Court frame: x towards the net, y up, spin `omega_z` counter-clockwise positive (z out of the page).
//! The paper's frame (Cross 2010, Fig. 1): its x axis lies along the surface, the way the ball's velocity
//! relative to the surface runs along it, its y axis along the normal; theta1 is measured from the surface
//! and the spin omega is positive in the sense that sliding friction drives (topspin).

use nalgebra::Vector2;

/// A flat surface moving at a constant velocity.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// m/s, court frame.
    pub velocity: Vector2<f64>,
    /// Unit normal out of the surface, towards the ball.
    pub normal: Vector2<f64>,
}

/// How the ball meets a surface, in the paper's terms, with the axes that take it back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incidence {
    /// theta1, degrees from the surface, in (0, 90].
    pub theta1_deg: f64,
    /// v1, the speed relative to the surface, m/s.
    pub speed: f64,
    /// omega1 in the paper's sense, rad/s.
    pub spin: f64,
    /// The paper's x axis in the court frame.
    tangent: Vector2<f64>,
    /// omega (paper) = sense * omega_z: +1 or -1, the z component of normal x tangent.
    sense: f64,
}

impl Surface {
    /// The surface at rest with the normal at `normal`.
    pub fn at_rest(normal: Vector2<f64>) -> Self {
        Surface {
            velocity: Vector2::zeros(),
            normal,
        }
    }

    /// The paper's incidence of a ball at `velocity` (court frame) spinning at `omega_z`; `None` when the
    /// ball does not move towards the surface.
    pub fn incidence(&self, velocity: Vector2<f64>, omega_z: f64) -> Option<Incidence> {
        let relative = velocity - self.velocity;
        let towards = -relative.dot(&self.normal);
        // NaN fails this test too.
        if towards.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        let along = Vector2::new(self.normal.y, -self.normal.x);
        let (tangent, vx) = match relative.dot(&along) {
            a if a >= 0.0 => (along, a),
            a => (-along, -a),
        };
        let sense = self.normal.x * tangent.y - self.normal.y * tangent.x;
        Some(Incidence {
            theta1_deg: towards.atan2(vx).to_degrees().min(90.0),
            speed: relative.norm(),
            spin: sense * omega_z,
            tangent,
            sense,
        })
    }

    /// The ball's velocity and `omega_z` in the court frame after a rebound of `vx2` along the surface
    /// (paper's x), `vy2` away from it and spin `omega2` in the paper's sense.
    pub fn rebound(
        &self,
        incidence: &Incidence,
        vx2: f64,
        vy2: f64,
        omega2: f64,
    ) -> (Vector2<f64>, f64) {
        let relative = incidence.tangent * vx2 + self.normal * vy2;
        (relative + self.velocity, incidence.sense * omega2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ball_rolling_forward_on_the_floor_has_topspin_in_both_frames() {
        let floor = Surface::at_rest(Vector2::new(0.0, 1.0));
        // Travelling +x, clockwise (omega_z < 0) is topspin.
        let i = floor.incidence(Vector2::new(3.0, -4.0), -10.0).unwrap();
        assert_eq!(i.speed, 5.0);
        assert!((i.theta1_deg - 4f64.atan2(3.0).to_degrees()).abs() < 1e-12);
        assert_eq!(i.spin, 10.0);
        let (v, w) = floor.rebound(&i, 2.0, 1.0, 20.0);
        assert_eq!((v.x, v.y, w), (2.0, 1.0, -20.0));
        // Travelling -x the tangent turns round, and so does the sense of topspin.
        let i = floor.incidence(Vector2::new(-3.0, -4.0), 10.0).unwrap();
        assert_eq!(i.spin, 10.0);
        assert_eq!(floor.rebound(&i, 2.0, 1.0, 20.0).0.x, -2.0);
    }

    #[test]
    fn a_ball_leaving_the_surface_never_meets_it() {
        let strings = Surface {
            velocity: Vector2::new(30.0, 0.0),
            normal: Vector2::new(1.0, 0.0),
        };
        assert!(strings.incidence(Vector2::new(31.0, 0.0), 0.0).is_none());
        assert!(strings.incidence(Vector2::new(-5.0, 2.0), 0.0).is_some());
        assert!(
            strings
                .incidence(Vector2::new(f64::NAN, 0.0), 0.0)
                .is_none()
        );
    }
}
