//! Check 4 of `docs/conventions.md#checks`: the rank of the constraint Jacobian at the
//! drawing (redundancy and determinacy).

use super::{names, plural, RANK_TOL, SIGNIFICANT};
use crate::front::resolve::{Culprit, Issue};
use crate::kernel::constraints::ConKind;
use crate::model::Model;
use crate::plan::geometry::{all_cons, drawing_states, joint_geoms};
use nalgebra::{DMatrix, DVector};

/// The dimensionless constraint Jacobian of the whole mechanism at the drawing.
#[derive(Clone, Debug, PartialEq)]
pub struct Jacobian {
    /// J: one row per scalar constraint of [`crate::plan::geometry::all_cons`] (joints and their
    /// drivers, in joint order), columns (x, y, φ·L) of links 1..N (the ground is fixed).
    /// Angle rows are multiplied by L, so every entry is dimensionless.
    pub matrix: DMatrix<f64>,
    /// The joint of each row.
    pub joint: Vec<usize>,
    /// Whether each row is a driver row (an input's equation).
    pub driver: Vec<bool>,
    /// L = [`Model::scale`], m.
    pub scale: f64,
}

impl Jacobian {
    /// The sub-matrix of the rows selected by `keep(row)`.
    fn select(&self, keep: impl Fn(usize) -> bool) -> (DMatrix<f64>, Vec<usize>) {
        let rows: Vec<usize> = (0..self.matrix.nrows()).filter(|&r| keep(r)).collect();
        let mut m = DMatrix::zeros(rows.len(), self.matrix.ncols());
        for (i, &r) in rows.iter().enumerate() {
            m.row_mut(i).copy_from(&self.matrix.row(r));
        }
        (m, rows)
    }
}

/// Assemble the constraint Jacobian ∂Φ/∂(x, y, φ) of every joint and driver at the
/// drawing from [`crate::kernel::constraints::scaled_rows`], scaled to be
/// dimensionless: columns (x, y, φ·L) of links 1..N, angle rows × L, L = [`Model::scale`] (m).
pub fn jacobian(model: &Model) -> Jacobian {
    let geoms = joint_geoms(model);
    let states = drawing_states(model);
    let cons = all_cons(model);
    let n = model.n_links();
    let cols = 3 * n.saturating_sub(1);
    let scale = model.scale();
    let total: usize = cons.iter().map(|c| c.kind.rows()).sum();
    let mut matrix = DMatrix::zeros(total, cols);
    let mut joint = Vec::with_capacity(total);
    let mut driver = Vec::with_capacity(total);
    let mut r = 0;
    for c in &cons {
        crate::kernel::constraints::scaled_rows(
            *c,
            &geoms[c.joint],
            &states,
            scale,
            |k, link, e| {
                if link != 0 && link < n {
                    for (i, x) in e.iter().enumerate() {
                        matrix[(r + k, 3 * (link - 1) + i)] += x;
                    }
                }
            },
        );
        for _ in 0..c.kind.rows() {
            joint.push(c.joint);
            driver.push(matches!(
                c.kind,
                ConKind::DriveRevolute(_) | ConKind::DrivePrismatic(_)
            ));
        }
        r += c.kind.rows();
    }
    Jacobian {
        matrix,
        joint,
        driver,
        scale,
    }
}

/// Rank and null spaces of a matrix by SVD.
struct RankInfo {
    rank: usize,
    /// Basis of {y : yᵀ J = 0} (length = rows).
    left_null: Vec<DVector<f64>>,
    /// Basis of {x : J x = 0} (length = columns).
    right_null: Vec<DVector<f64>>,
}

/// SVD of J padded with zeros to a square matrix, so that both U and V are complete.
/// `None` when J is not finite or the SVD does not converge.
fn rank_info(j: &DMatrix<f64>) -> Option<RankInfo> {
    let (m, n) = j.shape();
    if !j.iter().all(|v| v.is_finite()) {
        return None;
    }
    let s = m.max(n);
    if s == 0 {
        return Some(RankInfo {
            rank: 0,
            left_null: Vec::new(),
            right_null: Vec::new(),
        });
    }
    let mut a = DMatrix::zeros(s, s);
    a.view_mut((0, 0), (m, n)).copy_from(j);
    let svd = a.try_svd(true, true, f64::EPSILON, 100_000)?;
    let sv = &svd.singular_values;
    let tol = RANK_TOL * sv.max();
    let small: Vec<usize> = (0..s).filter(|&i| sv[i] <= tol || sv[i].is_nan()).collect();
    let rank = s - small.len();
    let u = svd.u.as_ref()?;
    let vt = svd.v_t.as_ref()?;
    // Padded rows / columns contribute null vectors supported outside J's range; the
    // restrictions to J's rows / columns of the whole small-σ basis span the true spaces.
    let restrict = |v: DVector<f64>| if v.amax() > 1e-8 { Some(v) } else { None };
    let left_null = small
        .iter()
        .filter_map(|&i| restrict(u.column(i).rows(0, m).into_owned()))
        .collect();
    let right_null = small
        .iter()
        .filter_map(|&i| restrict(vt.row(i).columns(0, n).transpose()))
        .collect();
    Some(RankInfo {
        rank,
        left_null,
        right_null,
    })
}

/// Indices `g` of the groups (joints or links) whose entries in any of `vectors` are
/// significant; `group_of(i)` gives the group of entry `i`.
fn significant(
    vectors: &[DVector<f64>],
    groups: usize,
    group_of: impl Fn(usize) -> usize,
) -> Vec<usize> {
    let mut hit = vec![false; groups];
    for v in vectors {
        let mut mag = vec![0.0f64; groups];
        for (i, x) in v.iter().enumerate() {
            let g = group_of(i);
            mag[g] = mag[g].max(x.abs());
        }
        let top = mag.iter().cloned().fold(0.0, f64::max);
        for (g, &x) in mag.iter().enumerate() {
            if top > 0.0 && x > SIGNIFICANT * top {
                hit[g] = true;
            }
        }
    }
    (0..groups).filter(|&g| hit[g]).collect()
}

/// Check 4 of `docs/conventions.md#checks`: geometric redundancy and determinacy at the drawing
/// (`docs/theory.md` §1.4).
///
/// With J the dimensionless Jacobian of [`jacobian`] (3(N − 1) columns) and rank decided
/// by SVD with the relative tolerance [`RANK_TOL`]:
///
/// - (a) redundancy: the joint rows J_c (drivers excluded) must be independent,
///   rank J_c = rows of J_c; otherwise rows − rank constraints are redundant (the
///   reactions are indeterminate). The joints taking part are those with significant
///   components in a left null vector (a self-stress). An issue unless
///   `#[allow(redundant)]`.
/// - (b) determinacy: with the driver rows, rank J = 3(N − 1); otherwise the inputs do not
///   determine the position (a dead point in the drawing, or a missing input); the links
///   that can still move are those with significant components in a right null vector.
///   Skipped when (a) reported, as its consequence.
/// - with `#[allow(redundant)]`: the mobility at the drawing, 3(N − 1) − rank J_c, must
///   equal the number of inputs, then (b) applies.
///
/// Assumes a finite drawing (check 5); returns no issue when J is not finite.
pub fn geometric(model: &Model) -> Vec<Issue> {
    let mut out = Vec::new();
    let n = model.n_links();
    if n < 2 {
        return out;
    }
    let jac = jacobian(model);
    let cols = jac.matrix.ncols();
    let (jc, crow) = jac.select(|r| !jac.driver[r]);
    let Some(ci) = rank_info(&jc) else {
        return out;
    };
    let nj = model.joints.len();
    let joint_list = |js: &[usize]| names(js.iter().map(|&j| model.joints[j].name.clone()));
    let link_list = |ls: &[usize]| names(ls.iter().map(|&l| model.links[l].name.clone()));
    let redundant = jc.nrows() - ci.rank;
    let takes_part = significant(&ci.left_null, nj, |i| jac.joint[crow[i]]);
    let mut determinacy = true;
    if model.allow_redundant {
        let mobility = cols - ci.rank;
        let k = model.inputs.len();
        if mobility != k {
            determinacy = false;
            let mut culprits = vec![Culprit::Inputs];
            culprits.extend((0..nj).map(Culprit::Joint));
            out.push(Issue {
                culprits,
                message: format!(
                    "with #[allow(redundant)] the inputs must match the mobility at the drawing: the joints' {} have rank {} of 3(N−1) = {cols} coordinates, which leaves {}, but {} declared: declare {}",
                    plural(jc.nrows(), "equation", "equations"),
                    ci.rank,
                    plural(mobility, "DOF", "DOF"),
                    if k == 1 { "1 input was".to_string() } else { format!("{k} inputs were") },
                    plural(mobility, "input", "inputs"),
                ),
            });
        }
    } else if redundant > 0 {
        determinacy = false;
        let mut culprits: Vec<Culprit> = takes_part.iter().map(|&j| Culprit::Joint(j)).collect();
        if culprits.is_empty() {
            culprits.push(Culprit::Mechanism);
        }
        out.push(Issue {
            culprits,
            message: format!(
                "redundant constraints at the drawing: the joints' {} have rank {}, so {} and the reactions are indeterminate (e.g. parallel cranks, or coaxial pins); joints {} take part: remove a joint/link, or accept with #[allow(redundant)] (then only driver actions, no reactions)",
                plural(jc.nrows(), "constraint equation", "constraint equations"),
                ci.rank,
                plural(redundant, "constraint is redundant", "constraints are redundant"),
                joint_list(&takes_part),
            ),
        });
    }
    if determinacy {
        let Some(ai) = rank_info(&jac.matrix) else {
            return out;
        };
        if ai.rank < cols {
            let moving: Vec<usize> = significant(&ai.right_null, n - 1, |i| i / 3)
                .into_iter()
                .map(|l| l + 1)
                .collect();
            let mut culprits = vec![Culprit::Inputs];
            culprits.extend(moving.iter().map(|&l| Culprit::Link(l)));
            out.push(Issue {
                culprits,
                message: format!(
                    "the inputs do not determine the position at the drawing (a dead point, or a missing input): {} {} can still move with the inputs held (the {} of the joints and inputs have rank {} < 3(N−1) = {cols}): redraw the mechanism away from the dead point, or add an input",
                    if moving.len() == 1 { "link" } else { "links" },
                    link_list(&moving),
                    plural(jac.matrix.nrows(), "equation", "equations"),
                    ai.rank,
                ),
            });
        }
    }
    out
}
