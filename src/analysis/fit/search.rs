//! The global search's starting points and the sorting of where its runs end into distinct minima.
//!
//! Starting points are a Halton sequence (bases 2, 3, 5, ...) in the optimiser's coordinates over each
//! free parameter's start box ([`Free::start_box`]), shifted modulo 1 by a seeded random vector
//! (Cranley-Patterson rotation) so that a seed gives another, equally even set. Physics guides half of
//! them: where a cart's mass M and stiffness k are both free, the spin out depends chiefly on how many
//! half-periods pi sqrt(M/k) of the cart fit into the contact time T (Cross, Sec. III: the cart springs
//! back while the ball grips), and the minima of chi2 lie in narrow valleys of that ratio. Every other
//! point therefore draws n = T / (pi sqrt(M/k)) log-uniformly in [`RATIO`] and sets k = M (pi n / T)^2.

use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

use super::free::{Free, Scale};
use crate::model::Params;
use crate::model::params::ParamId;

/// The half-periods of the cart per contact time that guided points span: a cart too heavy to spring
/// back within the contact to one that swings back and forth two dozen times.
pub const RATIO: (f64, f64) = (0.2, 25.0);

/// The first primes: the Halton bases of the first coordinates (a fit of more coordinates than this
/// reuses them with a shift).
const PRIMES: [u64; 16] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53];

/// The radical inverse of `index` in base `base`: the `index`-th point of the van der Corput sequence.
pub fn radical_inverse(mut index: u64, base: u64) -> f64 {
    let mut inverse = 0.0;
    let mut scale = 1.0 / base as f64;
    while index > 0 {
        inverse += (index % base) as f64 * scale;
        index /= base;
        scale /= base as f64;
    }
    inverse
}

/// `count` points of the seeded, shifted Halton sequence in the unit cube of `dim` dimensions.
pub fn halton(count: usize, dim: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = StdRng::seed_from_u64(seed);
    let shift: Vec<f64> = (0..dim).map(|_| rng.random::<f64>()).collect();
    (1..=count as u64)
        .map(|i| {
            (0..dim)
                .map(|d| {
                    let x = radical_inverse(i, PRIMES[d % PRIMES.len()]) + shift[d];
                    x - x.floor()
                })
                .collect()
        })
        .collect()
}

/// The start box of each free coordinate, around its value in `base`.
pub fn boxes(base: &Params, free: &[Free]) -> Vec<(f64, f64)> {
    free.iter().map(|f| f.start_box(base.get(f.id()))).collect()
}

/// `count` starting points in the optimiser's coordinates, half of them guided by the cart's
/// half-period where its mass and stiffness are both free (see the module's notes).
pub fn starting_points(base: &Params, free: &[Free], count: usize, seed: u64) -> Vec<Vec<f64>> {
    let boxes = boxes(base, free);
    let pairs = cart_pairs(free);
    halton(count, free.len(), seed)
        .into_iter()
        .enumerate()
        .map(|(i, unit)| {
            let mut u: Vec<f64> = unit
                .iter()
                .zip(&boxes)
                .map(|(x, (a, b))| a + (b - a) * x)
                .collect();
            if i % 2 == 1 {
                for &(m, k) in &pairs {
                    let duration = free
                        .iter()
                        .zip(&u)
                        .find(|(f, _)| f.id() == ParamId::Duration && f.group == free[m].group)
                        .map_or(base.duration, |(f, &x)| f.value(x));
                    let ratio = (RATIO.0.ln() + (RATIO.1 / RATIO.0).ln() * unit[k]).exp();
                    let stiffness =
                        free[m].value(u[m]) * (std::f64::consts::PI * ratio / duration).powi(2);
                    u[k] = free[k].coordinate(stiffness);
                }
            }
            u
        })
        .collect()
}

/// The pairs (cart mass, stiffness) of free coordinates that hold for the same rows, both fitted as
/// logarithms.
fn cart_pairs(free: &[Free]) -> Vec<(usize, usize)> {
    let find = |id: ParamId, group: Option<usize>| {
        free.iter()
            .position(|f| f.id() == id && f.group == group && f.scale == Scale::Log)
    };
    free.iter()
        .enumerate()
        .filter(|(_, f)| f.id() == ParamId::CartMass && f.scale == Scale::Log)
        .filter_map(|(m, f)| find(ParamId::Stiffness, f.group).map(|k| (m, k)))
        .collect()
}

/// The largest distance between `a` and `b` in any coordinate, in widths of its start box.
pub fn distance(a: &[f64], b: &[f64], boxes: &[(f64, f64)]) -> f64 {
    a.iter()
        .zip(b)
        .zip(boxes)
        .map(|((x, y), (lo, hi))| (x - y).abs() / (hi - lo))
        .fold(0.0, f64::max)
}

/// A point of the search: where it is, its chi2, and whether a run of Levenberg-Marquardt ended there
/// meeting its tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub u: Vec<f64>,
    pub chi2: f64,
    pub converged: bool,
}

/// The points sorted best first and thinned: a point within `radius` (see [`distance`]) of a better
/// one kept already is dropped; at most `most` are kept, and none whose chi2 is not finite.
pub fn distinct(
    mut points: Vec<Point>,
    boxes: &[(f64, f64)],
    radius: f64,
    most: usize,
) -> Vec<Point> {
    points.retain(|p| p.chi2.is_finite());
    points.sort_by(|a, b| a.chi2.total_cmp(&b.chi2));
    let mut kept: Vec<Point> = Vec::new();
    for p in points {
        if kept.len() == most {
            break;
        }
        if kept.iter().all(|k| distance(&p.u, &k.u, boxes) > radius) {
            kept.push(p);
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::spec;

    #[test]
    fn halton_points_fill_the_cube_evenly_and_a_seed_repeats_them() {
        assert_eq!(radical_inverse(1, 2), 0.5);
        assert_eq!(radical_inverse(3, 2), 0.75);
        assert!((radical_inverse(5, 3) - 7.0 / 9.0).abs() < 1e-15);
        let points = halton(64, 2, 1);
        assert_eq!(points, halton(64, 2, 1));
        assert_ne!(points, halton(64, 2, 2));
        // Each quarter of each axis holds 16 of 64 points, give or take one.
        for d in 0..2 {
            for q in 0..4 {
                let n = points
                    .iter()
                    .filter(|p| (p[d] * 4.0).floor() as usize == q)
                    .count();
                assert!((15..=17).contains(&n), "{d} {q} {n}");
            }
        }
    }

    #[test]
    fn guided_points_span_the_half_periods_per_contact() {
        let free = [
            Free::new(spec(ParamId::CartMass)),
            Free::new(spec(ParamId::Stiffness)),
            Free::new(spec(ParamId::Mu)),
        ];
        let base = Params::default();
        let points = starting_points(&base, &free, 40, 3);
        let ratios: Vec<f64> = points
            .iter()
            .skip(1)
            .step_by(2)
            .map(|u| {
                let half = std::f64::consts::PI * (u[0].exp() / u[1].exp()).sqrt();
                base.duration / half
            })
            .collect();
        assert!(
            ratios
                .iter()
                .all(|r| (RATIO.0..=RATIO.1).contains(&(r * (1.0 + 1e-12))))
        );
        assert!(ratios.iter().any(|&r| r < 1.0) && ratios.iter().any(|&r| r > 10.0));
    }

    #[test]
    fn distinct_keeps_the_best_of_each_neighbourhood() {
        let boxes = [(0.0, 1.0)];
        let point = |u: f64, chi2: f64| Point {
            u: vec![u],
            chi2,
            converged: true,
        };
        let points = vec![
            point(0.5, 2.0),
            point(0.51, 1.0),
            point(0.9, 3.0),
            point(0.1, f64::INFINITY),
        ];
        let kept = distinct(points, &boxes, 0.05, 10);
        assert_eq!(kept, vec![point(0.51, 1.0), point(0.9, 3.0)]);
        assert_eq!(distinct(kept, &boxes, 0.05, 1).len(), 1);
    }
}
