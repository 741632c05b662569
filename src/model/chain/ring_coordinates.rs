//! The ring's coordinates (issue 23): with the first mass held to a free frame, the frame's place and
//! each link's place behind the first less its offset on the springs' rest line, X_i = X_f + d (N + 1 -
//! i)/N (d = X_1 - X_f, the first mass's place on the frame), in which the ring's modes are written
//! ([`super::ring`] holds the physics of that phase).

use super::modes::MAX;
use super::{Chain, ChainState};

/// The ring's coordinates and velocities at `start` (the first mass held to the frame): B's, the
/// frame's X_f and V_f, then each link's behind the first, less its offset d (N + 1 - i)/N on the rest
/// line.
pub fn coordinates(chain: &Chain, start: &ChainState) -> ([f64; MAX], [f64; MAX]) {
    let (n, frame) = (chain.n, start.frame);
    let d = start.x[0] - start.x[frame];
    let (mut y, mut v) = ([0.0; MAX], [0.0; MAX]);
    (y[0], v[0]) = (start.x[frame], start.v[frame]);
    for i in 1..n {
        y[i] = start.x[i] - rest(n, d, i);
        v[i] = start.v[i];
    }
    (y, v)
}

/// The whole chain from the ring's coordinates `y` and velocities `v`: the frame at y_1, the first mass
/// d ahead of it at its velocity, each link behind at y_i plus its offset on the rest line.
pub fn place(
    chain: &Chain,
    start: &ChainState,
    y: &[f64; MAX],
    v: &[f64; MAX],
) -> ([f64; MAX], [f64; MAX]) {
    let (n, frame) = (chain.n, start.frame);
    let d = start.x[0] - start.x[frame];
    let (mut x, mut u) = ([0.0; MAX], [0.0; MAX]);
    (x[frame], u[frame]) = (y[0], v[0]);
    (x[0], u[0]) = (y[0] + d, v[0]);
    for i in 1..n {
        x[i] = rest(n, d, i) + y[i];
        u[i] = v[i];
    }
    (x, u)
}

/// Link `i` (0-based) on the rest line, relative to the frame: d (N - i)/N.
fn rest(n: usize, d: f64, i: usize) -> f64 {
    d * (n - i) as f64 / n as f64
}
