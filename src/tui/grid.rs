//! The heatmap's grid: cart masses across and spring stiffnesses up, each spaced evenly in log, shared
//! by the map ([`super::heatmap`]), the search for its best point ([`super::peak`]) and its drawing.

/// Cells across: cart masses.
pub const MASSES: usize = 60;
/// Cells up: spring stiffnesses.
pub const STIFFNESSES: usize = 30;
/// Cart mass range, kg: 0.1 g to 100 g.
pub const MASS_RANGE: [f64; 2] = [1e-4, 0.1];
/// Stiffness range, N/m: 1 kN/m to 100 kN/m.
pub const STIFFNESS_RANGE: [f64; 2] = [1e3, 1e5];

/// The `i`-th of `n` values spaced evenly in log over `range`.
fn log_grid(range: [f64; 2], i: usize, n: usize) -> f64 {
    let [low, high] = range;
    low * (high / low).powf(i as f64 / (n - 1) as f64)
}

/// The cart mass of column `i`, kg.
pub fn mass(i: usize) -> f64 {
    log_grid(MASS_RANGE, i, MASSES)
}

/// The stiffness of row `j` (0 is the softest), N/m.
pub fn stiffness(j: usize) -> f64 {
    log_grid(STIFFNESS_RANGE, j, STIFFNESSES)
}

/// Where `value` lies on a log axis over `range` with `n` cells: the nearest cell, or `None` outside.
pub fn cell_of(value: f64, range: [f64; 2], n: usize) -> Option<usize> {
    let [low, high] = range;
    let f = (value / low).ln() / (high / low).ln();
    (-0.5 / (n - 1) as f64..=1.0 + 0.5 / (n - 1) as f64)
        .contains(&f)
        .then(|| ((f * (n - 1) as f64).round() as usize).min(n - 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_span_the_ranges_in_log() {
        assert_eq!(mass(0), 1e-4);
        assert!((mass(MASSES - 1) - 0.1).abs() < 1e-15);
        assert!((stiffness(STIFFNESSES - 1) - 1e5).abs() < 1e-9);
        // The default 10 g cart and 15 kN/m spring are inside.
        let i = cell_of(0.010, MASS_RANGE, MASSES).unwrap();
        assert!((mass(i) / 0.010).ln().abs() < 0.07);
        assert_eq!(cell_of(1.0, MASS_RANGE, MASSES), None);
        assert_eq!(cell_of(1e-4, MASS_RANGE, MASSES), Some(0));
    }
}
