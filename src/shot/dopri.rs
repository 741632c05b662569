//! One step of the Dormand–Prince 5(4) Runge–Kutta pair (J. R. Dormand and P. J. Prince, J. Comput.
//! Appl. Math. 6, 19, 1980; the tableau of Hairer, Nørsett and Wanner, *Solving ODEs I*, Table 5.2):
//! the fifth-order solution is kept (local extrapolation), the difference from the embedded fourth-order
//! one estimates the local error, and the last stage is the derivative at the new point (FSAL).

/// The state of the flight: x, y (m), vx, vy (m/s).
pub type State = [f64; 4];

const A2: [f64; 1] = [1.0 / 5.0];
const A3: [f64; 2] = [3.0 / 40.0, 9.0 / 40.0];
const A4: [f64; 3] = [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0];
const A5: [f64; 4] = [
    19372.0 / 6561.0,
    -25360.0 / 2187.0,
    64448.0 / 6561.0,
    -212.0 / 729.0,
];
const A6: [f64; 5] = [
    9017.0 / 3168.0,
    -355.0 / 33.0,
    46732.0 / 5247.0,
    49.0 / 176.0,
    -5103.0 / 18656.0,
];
/// The fifth-order weights (also the last stage's row).
const B: [f64; 6] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];
/// Fifth- minus fourth-order weights, stages 1 to 7.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// The local error allowed per step, per component: `abs + rel |y|`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    pub abs: f64,
    pub rel: f64,
}

/// The result of one step.
#[derive(Clone, Copy, Debug)]
pub struct Step {
    pub y: State,
    /// The derivative at `y` (the next step's first stage).
    pub dy: State,
    /// The estimated local error over the tolerance, largest component (accept at or below 1).
    pub error: f64,
}

fn combine(y: &State, h: f64, k: &[State], a: &[f64]) -> State {
    let mut out = *y;
    for (kj, aj) in k.iter().zip(a) {
        for i in 0..4 {
            out[i] += h * aj * kj[i];
        }
    }
    out
}

/// One step of size `h` from `y`, whose derivative is `dy`, for y' = f(y) (the flight is autonomous).
pub fn step(f: impl Fn(&State) -> State, y: &State, dy: &State, h: f64, tol: Tolerance) -> Step {
    let mut k: [State; 7] = [*dy; 7];
    k[1] = f(&combine(y, h, &k[..1], &A2));
    k[2] = f(&combine(y, h, &k[..2], &A3));
    k[3] = f(&combine(y, h, &k[..3], &A4));
    k[4] = f(&combine(y, h, &k[..4], &A5));
    k[5] = f(&combine(y, h, &k[..5], &A6));
    let y_new = combine(y, h, &k[..6], &B);
    k[6] = f(&y_new);
    let mut error: f64 = 0.0;
    for i in 0..4 {
        let e: f64 = h * k.iter().zip(E).map(|(kj, ej)| ej * kj[i]).sum::<f64>();
        let scale = tol.abs + tol.rel * y[i].abs().max(y_new[i].abs());
        error = error.max(e.abs() / scale);
    }
    Step {
        y: y_new,
        dy: k[6],
        error,
    }
}

/// The next step size after a step of size `h` with scaled error `error` (safety 0.9, growth limited to
/// 0.2..5 per step).
pub fn next_size(h: f64, error: f64) -> f64 {
    let factor = if error == 0.0 {
        5.0
    } else {
        (0.9 * error.powf(-0.2)).clamp(0.2, 5.0)
    };
    h * factor
}

#[cfg(test)]
mod tests {
    use super::*;

    const TIGHT: Tolerance = Tolerance {
        abs: 1e-12,
        rel: 1e-12,
    };

    /// The stages' times.
    const C: [f64; 6] = [1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];

    #[test]
    fn the_tableau_is_consistent() {
        let rows: [&[f64]; 6] = [&A2, &A3, &A4, &A5, &A6, &B];
        for (row, c) in rows.iter().zip(C) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-14);
        }
        assert!(E.iter().sum::<f64>().abs() < 1e-15);
    }

    #[test]
    fn fifth_order_on_an_oscillator() {
        // x'' = -x as (x, y, vx, vy) = (x, 0, x', 0): the error of one step falls as h^6.
        let f = |y: &State| [y[2], 0.0, -y[0], 0.0];
        let y0 = [1.0, 0.0, 0.0, 0.0];
        let err = |h: f64| (step(f, &y0, &f(&y0), h, TIGHT).y[0] - h.cos()).abs();
        let ratio = err(0.2) / err(0.1);
        assert!((50.0..80.0).contains(&ratio), "{ratio}");
        assert!(next_size(0.1, 2.0) < 0.1 && next_size(0.1, 0.01) > 0.1);
    }
}
