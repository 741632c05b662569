//! A stroke on court, from the strings to the opponent's baseline: the racquet's bounce in the frame of the
//! moving strings ([`frame`], the core, on the frame of the racquet in the hand: [`racquet`]), the flight with drag and Magnus lift ([`flight`], [`aero`],
//! integrated by [`dopri`]), the bounce on the court ([`court`], the core again) and the second flight to
//! the opponent's baseline.
//!
//! Court frame (issue 16's conventions): x from the hitter's baseline towards the net, y up. The contacts
//! are instants of the flight: the ball leaves from where it arrived, with the velocity and spin the core
//! gives.

pub mod aero;
pub mod court;
pub mod dopri;
pub mod flight;
pub mod frame;
pub mod racquet;

use nalgebra::Vector2;

use crate::config;
use crate::model::{Bounce, Params, SolveError, SolveOptions, solve_with};
use aero::{Air, Projectile};
use court::{BASELINE_X, NET_HEIGHT, NET_X};
use flight::{Hit, Point, Stop, TooLong, fly};
use frame::{Incidence, Surface};
use racquet::{Hold, RacquetError};

/// The preset a shot starts from, before any preset, scenario or flag given.
pub const BASE_PRESET: &str = "topspin-forehand";

/// The parameters a shot starts from, wherever one is played (`snapback shot`, the explorer's shot
/// mode): the defaults with the [`BASE_PRESET`] applied (the ball's restitution on clamped strings and a
/// real racquet in the hand, where the paper's e_y = 1 on the defaults' wall would return every bit of the
/// ball's normal speed).
pub fn base() -> Params {
    config::preset(BASE_PRESET)
        .expect("the base preset is compiled in")
        .apply(Params::default())
}

/// Why a shot cannot be played.
#[derive(Debug, thiserror::Error)]
pub enum ShotError {
    #[error(
        "the racquet never meets the ball: the ball moves away from the strings at {0:.3} m/s relative \
         to them (check --racquet-speed, --swing-path, --face-angle against --ball-speed and --ball-descent)"
    )]
    NeverMeets(f64),
    #[error("--height must be above the ball's radius ({radius} m); got {height} m")]
    BelowRadius { height: f64, radius: f64 },
    #[error(transparent)]
    Racquet(#[from] RacquetError),
    #[error("on the strings: {0}")]
    Strings(SolveError),
    /// A combination the core does not solve on a free frame, which a shot's racquet in the hand is.
    #[error(
        "on the strings: {what} on a hand-held racquet is not solved yet (use --racquet-mass clamped)"
    )]
    HandHeld { what: &'static str },
    #[error("on the court: {0}")]
    Court(SolveError),
    #[error(transparent)]
    Flight(#[from] TooLong),
    /// Only where the path just touches the court at its lowest point, so that it does not come down.
    #[error("the ball only grazes the court: it does not come down onto it")]
    Grazes,
}

/// A ball's velocity (m/s) and spin about z (rad/s, counter-clockwise positive) in the court frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    pub velocity: Vector2<f64>,
    pub omega_z: f64,
}

impl Motion {
    pub fn speed(&self) -> f64 {
        self.velocity.norm()
    }

    /// Degrees above the horizontal, of the direction of travel (towards -x for a ball coming back).
    pub fn angle_deg(&self) -> f64 {
        self.velocity.y.atan2(self.velocity.x.abs()).to_degrees()
    }

    /// Topspin relative to the ball's own direction of travel, rad/s (negative: backspin).
    pub fn topspin(&self) -> f64 {
        if self.velocity.x >= 0.0 {
            -self.omega_z
        } else {
            self.omega_z
        }
    }
}

/// A bounce seen from the surface: how the ball arrives, in the paper's terms, the core's bounce, and the
/// ball leaving in the court frame.
#[derive(Clone, Debug)]
pub struct Contact {
    pub incidence: Incidence,
    pub bounce: Bounce,
    pub leaving: Motion,
}

/// A whole shot.
#[derive(Clone, Debug)]
pub struct Shot {
    /// The racquet that strikes the ball.
    pub racquet: Hold,
    /// The bounce on the strings.
    pub strings: Contact,
    /// Where the ball lands: x of the centre (and of the contact) as it comes down to its radius, m,
    /// when the ball clears the net and comes down beyond it.
    pub landing_x: Option<f64>,
    /// The ball's lowest point minus the net's height as the centre crosses the net, m; `None` when the
    /// ball comes down before the net.
    pub net_clearance: Option<f64>,
    /// From the stroke to the landing (or to the net, or to coming down before it), s.
    pub flight_time: f64,
    /// The bounce on the court, when the ball lands beyond the net.
    pub court: Option<Contact>,
    /// The centre's height as it crosses the opponent's baseline after the bounce, m.
    pub kick_height: Option<f64>,
    /// (t s, x m, y m, vx m/s, vy m/s) at every step from the stroke on, when asked for; the time of
    /// the second flight starts where the first ends (the court contact is an instant).
    pub trajectory: Vec<Point>,
}

impl Shot {
    /// Clears the net and lands between the net and the opponent's baseline (a ball on the line is in).
    pub fn is_in(&self) -> bool {
        self.net_clearance.is_some_and(|c| c > 0.0)
            && self.landing_x.is_some_and(|x| x > NET_X && x <= BASELINE_X)
    }
}

/// The incoming ball: speed `ball_speed` towards -x, descending at `ball_descent_deg`, topspin relative
/// to its travel (counter-clockwise for a ball going -x).
pub fn incoming(p: &Params) -> Motion {
    let (sin, cos) = p.ball_descent_deg.to_radians().sin_cos();
    Motion {
        velocity: -p.ball_speed * Vector2::new(cos, sin),
        omega_z: p.ball_topspin,
    }
}

/// The strings: moving at `racquet_speed` along the swing path, normal towards +x tilted down by the
/// face angle (a closed face).
pub fn strings(p: &Params) -> Surface {
    let (sin_s, cos_s) = p.swing_path_deg.to_radians().sin_cos();
    let (sin_f, cos_f) = p.face_angle_deg.to_radians().sin_cos();
    Surface {
        velocity: p.racquet_speed * Vector2::new(cos_s, sin_s),
        normal: Vector2::new(cos_f, -sin_f),
    }
}

/// How the ball meets the strings, in the paper's terms (the frame change alone, no solve).
pub fn incidence(p: &Params) -> Result<Incidence, ShotError> {
    let strings = strings(p);
    let ball = incoming(p);
    strings
        .incidence(ball.velocity, ball.omega_z)
        .ok_or_else(|| {
            ShotError::NeverMeets((ball.velocity - strings.velocity).dot(&strings.normal))
        })
}

/// The bounce on the strings: the frame change, the core (all of `p`'s ball and cart flags, with the
/// incidence it sees, on the frame of `p`'s racquet), and back to the court frame.
pub fn hit(p: &Params) -> Result<Contact, ShotError> {
    hit_by(p, &Hold::of(p)?, &SolveOptions::default())
}

/// The bounce the strings see, as the core's parameters: `p` with the incidence of the frame change and
/// the frame of `p`'s racquet (its effective masses; the wall when clamped). The one place a shot's
/// racquet becomes the frame the strings are tied to; the explorer's shot mode shows this bounce.
pub fn strings_params(p: &Params) -> Result<Params, ShotError> {
    on_strings(p, &Hold::of(p)?)
}

fn on_strings(p: &Params, racquet: &Hold) -> Result<Params, ShotError> {
    let incidence = incidence(p)?;
    let (frame_mass, frame_normal_mass) = racquet.frame_masses();
    Ok(Params {
        angle_deg: incidence.theta1_deg,
        speed: incidence.speed,
        spin: incidence.spin,
        frame_mass,
        frame_normal_mass,
        ..*p
    })
}

/// [`hit`] by `racquet`, solved on `options`' terms.
fn hit_by(p: &Params, racquet: &Hold, options: &SolveOptions) -> Result<Contact, ShotError> {
    let strings = strings(p);
    let incidence = incidence(p)?;
    let bounce = solve_with(&on_strings(p, racquet)?, options).map_err(|e| match e {
        SolveError::FreeFrame { what } => ShotError::HandHeld { what },
        e => ShotError::Strings(e),
    })?;
    let o = &bounce.outcome;
    let (velocity, omega_z) = strings.rebound(&incidence, o.vx2, o.vy2, o.omega2);
    Ok(Contact {
        incidence,
        bounce,
        leaving: Motion { velocity, omega_z },
    })
}

/// Plays the shot of `p` in still air; with `trajectory`, samples its path.
pub fn play(p: &Params, trajectory: bool) -> Result<Shot, ShotError> {
    play_with(p, trajectory, &SolveOptions::default())
}

/// [`play`] with its two bounces (strings and court) solved on `options`' terms: a command's Ctrl-C
/// stops the shot within one phase of either.
pub fn play_with(p: &Params, trajectory: bool, options: &SolveOptions) -> Result<Shot, ShotError> {
    play_in_with(p, Air::STILL, trajectory, options)
}

/// Plays the shot of `p` in `air`.
pub fn play_in(p: &Params, air: Air, trajectory: bool) -> Result<Shot, ShotError> {
    play_in_with(p, air, trajectory, &SolveOptions::default())
}

/// [`play_in`] on `options`' terms.
fn play_in_with(
    p: &Params,
    air: Air,
    trajectory: bool,
    options: &SolveOptions,
) -> Result<Shot, ShotError> {
    if p.height <= p.radius {
        return Err(ShotError::BelowRadius {
            height: p.height,
            radius: p.radius,
        });
    }
    let racquet = Hold::of(p)?;
    let strings = hit_by(p, &racquet, options)?;
    let r = p.radius;
    let projectile = |m: &Motion| Projectile {
        mass: p.mass,
        radius: r,
        omega_z: m.omega_z,
        air,
    };
    let mut path = Vec::new();
    let launch = strings.leaving;
    let start = [0.0, p.height, launch.velocity.x, launch.velocity.y];
    let ball = projectile(&launch);
    let first = fly(
        &ball,
        start,
        &[Stop::CrossX(NET_X), Stop::Down(r)],
        trajectory.then_some(&mut path),
    )?;
    let mut shot = Shot {
        racquet,
        strings,
        landing_x: None,
        net_clearance: None,
        flight_time: first.t,
        court: None,
        kick_height: None,
        trajectory: Vec::new(),
    };
    let mut end = first;
    if first.stop == 0 {
        let clearance = first.state[1] - r - NET_HEIGHT;
        shot.net_clearance = Some(clearance);
        if clearance > 0.0 {
            let from = path.len();
            let second = fly(
                &ball,
                first.state,
                &[Stop::Down(r)],
                trajectory.then_some(&mut path),
            )?;
            shift(&mut path[from..], first.t);
            end = Hit {
                t: first.t + second.t,
                ..second
            };
            shot.flight_time = end.t;
            shot.landing_x = Some(end.state[0]);
        }
    }
    let mut last = end;
    if let Some(x) = shot.landing_x {
        let arriving = Motion {
            velocity: Vector2::new(end.state[2], end.state[3]),
            omega_z: launch.omega_z,
        };
        let court = bounce_on_court(p, &arriving, options)?;
        let leaving = court.leaving;
        shot.court = Some(court);
        if x < BASELINE_X && leaving.velocity.y > 0.0 {
            let start = [x, r, leaving.velocity.x, leaving.velocity.y];
            let stops = [Stop::CrossX(BASELINE_X), Stop::Down(r)];
            let from = path.len();
            let kick = fly(
                &projectile(&leaving),
                start,
                &stops,
                trajectory.then_some(&mut path),
            )?;
            shift(&mut path[from..], end.t);
            if kick.stop == 0 {
                shot.kick_height = Some(kick.state[1]);
            }
            last = Hit {
                t: end.t + kick.t,
                ..kick
            };
        }
    }
    if trajectory {
        let [x, y, vx, vy] = last.state;
        path.push([last.t, x, y, vx, vy]);
        shot.trajectory = path;
    }
    Ok(shot)
}

/// Moves the times of `points` on by `t`: a later flight's clock starts where the earlier ones end.
fn shift(points: &mut [Point], t: f64) {
    points.iter_mut().for_each(|p| p[0] += t);
}

/// The bounce on the court of a ball arriving with `arriving` (the court at rest, normal up).
fn bounce_on_court(
    p: &Params,
    arriving: &Motion,
    options: &SolveOptions,
) -> Result<Contact, ShotError> {
    let floor = Surface::at_rest(Vector2::new(0.0, 1.0));
    let incidence = floor
        .incidence(arriving.velocity, arriving.omega_z)
        .ok_or(ShotError::Grazes)?;
    let bounce = court::bounce_with(p, &incidence, options).map_err(ShotError::Court)?;
    let o = &bounce.outcome;
    let (velocity, omega_z) = floor.rebound(&incidence, o.vx2, o.vy2, o.omega2);
    Ok(Contact {
        incidence,
        bounce,
        leaving: Motion { velocity, omega_z },
    })
}
