//! Nelder–Mead's simplex search in the unit cube [0, 1]^d, with restarts: the local search
//! of [`super::optimize`] and of [`super::balance::optimal_balance`].
//!
//! Each iteration orders the d + 1 points, reflects the worst through the centroid c of
//! the others (x_r = c + (c − x_w), clamped to the cube), expands (c + 2 (c − x_w)) when
//! x_r is the best yet, accepts x_r when it beats the second worst, else contracts (c ±
//! ½ (c − x_w), outside when x_r beat the worst) and, when that fails too, shrinks every
//! point halfway towards the best. When the simplex collapses (its largest coordinate
//! spread from the best below 10⁻⁹) with budget left, it restarts from the next of
//! `restarts` (then from the best point so far), with a simplex of a tenth of the cube
//! along each axis. Deterministic; f may be infinite (an infeasible point ranks last).

/// Minimises `f` over [0, 1]^d from `simplex` (d + 1 points with their values, d ≥ 1),
/// `used` evaluations already made of a budget of `budget` (every call of `f` counts one).
/// `progress(evaluations, best)` is called after each iteration with the evaluations made
/// (`used` included) and the simplex's best value. Returns the best point seen, its value
/// and the evaluations made (`used` included).
pub(crate) fn nelder_mead(
    mut simplex: Vec<(Vec<f64>, f64)>,
    mut restarts: impl Iterator<Item = (Vec<f64>, f64)>,
    used: usize,
    budget: usize,
    mut f: impl FnMut(&[f64]) -> f64,
    mut progress: impl FnMut(usize, f64),
) -> (Vec<f64>, f64, usize) {
    let d = simplex.len() - 1;
    let mut evaluations = used;
    let mut value = |x: &[f64], n: &mut usize| {
        *n += 1;
        f(x)
    };
    let clamp = |x: Vec<f64>| -> Vec<f64> { x.into_iter().map(|t| t.clamp(0.0, 1.0)).collect() };
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut best_seen = simplex[0].clone();
    while evaluations + 2 <= budget {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        if simplex[0].1 < best_seen.1 {
            best_seen = simplex[0].clone();
        }
        let size = simplex
            .iter()
            .skip(1)
            .map(|s| {
                s.0.iter()
                    .zip(&simplex[0].0)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        if size < 1e-9 {
            if evaluations + d + 3 > budget {
                break;
            }
            let centre = restarts.next().unwrap_or_else(|| best_seen.clone());
            simplex = vec![centre.clone()];
            for i in 0..d {
                let mut x = centre.0.clone();
                x[i] = if x[i] > 0.5 { x[i] - 0.1 } else { x[i] + 0.1 };
                let fx = value(&x, &mut evaluations);
                simplex.push((x, fx));
            }
            continue;
        }
        let worst = simplex[d].clone();
        let centre: Vec<f64> = (0..d)
            .map(|i| simplex[..d].iter().map(|s| s.0[i]).sum::<f64>() / d as f64)
            .collect();
        let towards = |t: f64| -> Vec<f64> {
            centre
                .iter()
                .zip(&worst.0)
                .map(|(c, w)| c + t * (c - w))
                .collect()
        };
        let xr = clamp(towards(1.0));
        let fr = value(&xr, &mut evaluations);
        let (best, second) = (simplex[0].1, simplex[d - 1].1);
        if fr < best {
            let xe = clamp(towards(2.0));
            let fe = value(&xe, &mut evaluations);
            simplex[d] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < second {
            simplex[d] = (xr, fr);
        } else {
            let xc = clamp(towards(if fr < worst.1 { 0.5 } else { -0.5 }));
            let fc = value(&xc, &mut evaluations);
            if fc < fr.min(worst.1) {
                simplex[d] = (xc, fc);
            } else {
                // Shrink towards the best.
                let b = simplex[0].0.clone();
                for s in simplex.iter_mut().skip(1) {
                    let x: Vec<f64> = s.0.iter().zip(&b).map(|(x, b)| b + 0.5 * (x - b)).collect();
                    let fx = value(&x, &mut evaluations);
                    *s = (x, fx);
                }
            }
        }
        let now = simplex.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
        progress(evaluations, now);
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    if simplex[0].1 < best_seen.1 {
        best_seen = simplex[0].clone();
    }
    (best_seen.0, best_seen.1, evaluations)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quadratic bowl with its minimum inside the cube is found to 1e-6; one on the
    /// cube's face (beyond it) is held at the face; the budget is kept.
    #[test]
    fn finds_a_bowls_bottom_within_the_cube() {
        for (target, at) in [([0.3, 0.7], [0.3, 0.7]), ([1.4, 0.2], [1.0, 0.2])] {
            let f = |x: &[f64]| (x[0] - target[0]).powi(2) + 3.0 * (x[1] - target[1]).powi(2);
            let start = vec![
                (vec![0.5, 0.5], f(&[0.5, 0.5])),
                (vec![0.6, 0.5], f(&[0.6, 0.5])),
                (vec![0.5, 0.6], f(&[0.5, 0.6])),
            ];
            let (x, v, n) = nelder_mead(start, std::iter::empty(), 3, 400, f, |_, _| {});
            assert!(
                (x[0] - at[0]).abs() < 1e-6 && (x[1] - at[1]).abs() < 1e-6,
                "{x:?}"
            );
            assert!((v - f(&at)).abs() < 1e-10);
            assert!(n <= 400, "{n}");
        }
    }
}
