//! The storage of one spatial solve: sized at compile time on the stack ([`Fixed`], what the
//! generated struct uses: no allocation) or at load on the heap ([`Dense`], what the
//! run-time mechanism uses, least squares included for redundant constraints).
//!
//! A solve needs the bodies' states, the constraint rows with their two bodies each, a
//! vector of 6(N − 1) unknowns and the factored Jacobian J (`Layout::rows_into` writes the
//! rows, [`assemble`] lays them into J). Every solver of `spatial` is written once over a
//! [`Frame`]; the two frames differ only in where these live and in the factorisation
//! (`crate::kernel::linalg::Lu` on the stack, nalgebra's LU or SVD on the heap).

use super::constraints::{BodyState, Row};
use super::kinematics::{solve, BodyMotion};
use crate::kernel::linalg::Lu;
use crate::MechError;
use nalgebra::{DMatrix, DVector, SMatrix, SVector, Vector3};

/// The rows of one solve, each with its two bodies (a, b), in the order written.
pub trait RowBuffer {
    /// Append a row acting on the bodies `owner` = (a, b).
    fn push(&mut self, row: Row, owner: (usize, usize));
    /// Forget every row.
    fn clear(&mut self);
    /// The rows written.
    fn rows(&self) -> &[Row];
    /// Each row's two bodies.
    fn owners(&self) -> &[(usize, usize)];
}

/// Where one spatial solve keeps its data (module docs). Implemented by [`Fixed`] and
/// [`Dense`]; a solver takes the frame by value (both are a few words).
pub trait Frame: Copy {
    /// Every body's state, the ground first.
    type States: AsRef<[BodyState]> + AsMut<[BodyState]>;
    /// Every body's motion, the ground first.
    type Motions: AsRef<[BodyMotion]> + AsMut<[BodyMotion]>;
    /// The constraint rows.
    type Rows: RowBuffer;
    /// A vector of the rows' length (the right-hand sides, the multipliers) or of the
    /// unknowns' (6(N − 1)); both are one length for a square system.
    type Vector: AsRef<[f64]> + AsMut<[f64]> + Clone;
    /// J factored.
    type Factored;
    /// `InvalidInput` unless the frame holds a mechanism of `bodies` bodies (the ground
    /// included) and `rows` constraint rows.
    fn fits(self, bodies: usize, rows: usize) -> Result<(), MechError>;
    /// The bodies at the drawing, at rest: body i's reference point at `o0[i]`.
    fn states(self, o0: &[Vector3<f64>]) -> Self::States;
    /// Every body at rest at the drawing's origin (to be overwritten).
    fn motions(self) -> Self::Motions;
    /// An empty row buffer.
    fn rows(self) -> Self::Rows;
    /// A zero vector of the rows' length.
    fn rhs(self) -> Self::Vector;
    /// A zero vector of the unknowns' length, 6(N − 1).
    fn unknowns(self) -> Self::Vector;
    /// Factor J of `rows` (6(N − 1) columns); `Singular` with a condition estimate when it is
    /// singular to working accuracy.
    fn factor(self, rows: &Self::Rows) -> Result<Self::Factored, MechError>;
    /// x with J x = b (b of the rows' length, x of the unknowns').
    fn solve(self, j: &Self::Factored, b: &Self::Vector) -> Result<Self::Vector, MechError>;
    /// λ with Jᵀ λ = w (w of the unknowns' length, λ of the rows'); a square J only.
    fn solve_transpose(
        self,
        j: &Self::Factored,
        w: &Self::Vector,
    ) -> Result<Self::Vector, MechError>;
}

/// J laid out from its rows: row r's blocks on body a's and body b's (v, ω) go to columns
/// 6(a − 1)..6a and 6(b − 1)..6b (the ground's, body 0, are dropped); `put(r, c, value)`
/// adds one coefficient.
pub fn assemble(rows: &[Row], owners: &[(usize, usize)], mut put: impl FnMut(usize, usize, f64)) {
    for (r, (row, &(a, b))) in rows.iter().zip(owners).enumerate() {
        for (body, blocks) in [(a, &row.a), (b, &row.b)] {
            if body > 0 {
                for (k, block) in blocks.iter().enumerate() {
                    for c in 0..3 {
                        put(r, 6 * (body - 1) + 3 * k + c, block[c]);
                    }
                }
            }
        }
    }
}

/// The stack frame of a mechanism with `N` bodies (the ground included) and `R` = 6(N − 1)
/// rows and unknowns: every buffer an array, J factored by `kernel::linalg::Lu` (partial
/// pivoting). For the generated struct, whose N and R are constants; a mechanism with
/// redundant constraints (more rows than unknowns) takes [`Dense`].
#[derive(Clone, Copy, Debug, Default)]
pub struct Fixed<const N: usize, const R: usize>;

/// [`Fixed`]'s rows: at most R; one more is counted, not kept (`Layout::rows_into` then
/// refuses the solve).
#[derive(Clone, Copy, Debug)]
pub struct FixedRows<const R: usize> {
    rows: [Row; R],
    owners: [(usize, usize); R],
    len: usize,
}

impl<const R: usize> RowBuffer for FixedRows<R> {
    #[inline]
    fn push(&mut self, row: Row, owner: (usize, usize)) {
        if self.len < R {
            self.rows[self.len] = row;
            self.owners[self.len] = owner;
        }
        self.len += 1;
    }
    fn clear(&mut self) {
        self.len = 0;
    }
    fn rows(&self) -> &[Row] {
        &self.rows[..self.len.min(R)]
    }
    fn owners(&self) -> &[(usize, usize)] {
        &self.owners[..self.len.min(R)]
    }
}

impl<const N: usize, const R: usize> Frame for Fixed<N, R> {
    type States = [BodyState; N];
    type Motions = [BodyMotion; N];
    type Rows = FixedRows<R>;
    type Vector = [f64; R];
    type Factored = Lu<R>;

    fn fits(self, bodies: usize, rows: usize) -> Result<(), MechError> {
        if bodies == N && rows == R && R == 6 * N.saturating_sub(1) {
            Ok(())
        } else {
            Err(MechError::InvalidInput(format!(
                "a fixed frame of {N} bodies and {R} rows holds a square system of 6(N − 1) = {R} unknowns; this mechanism has {bodies} bodies and {rows} rows (one with redundant constraints takes the heap frame)"
            )))
        }
    }

    fn states(self, o0: &[Vector3<f64>]) -> [BodyState; N] {
        std::array::from_fn(|i| BodyState::drawing(o0.get(i).copied().unwrap_or_default()))
    }
    fn motions(self) -> [BodyMotion; N] {
        [BodyMotion::rest(); N]
    }
    fn rows(self) -> FixedRows<R> {
        FixedRows {
            rows: [Row::default(); R],
            owners: [(0, 0); R],
            len: 0,
        }
    }
    fn rhs(self) -> [f64; R] {
        [0.0; R]
    }
    fn unknowns(self) -> [f64; R] {
        [0.0; R]
    }
    fn factor(self, rows: &FixedRows<R>) -> Result<Lu<R>, MechError> {
        if rows.len != R {
            return Err(MechError::InvalidInput(format!(
                "the constraint system has {} rows for {R} unknowns: the count of equations does not match the unknowns",
                rows.len
            )));
        }
        let mut j = SMatrix::<f64, R, R>::zeros();
        assemble(rows.rows(), rows.owners(), |r, c, v| j[(r, c)] += v);
        let lu = Lu::new(j);
        let condition = lu.condition();
        if !(condition < 1e13) {
            return Err(MechError::Singular { condition });
        }
        Ok(lu)
    }
    fn solve(self, j: &Lu<R>, b: &[f64; R]) -> Result<[f64; R], MechError> {
        finite(j.solve(&SVector::from(*b)).into())
    }
    fn solve_transpose(self, j: &Lu<R>, w: &[f64; R]) -> Result<[f64; R], MechError> {
        finite(j.solve_transpose(&SVector::from(*w)).into())
    }
}

/// `x` when every value is finite, else `Singular` (an overflow inside the solve).
fn finite<V: AsRef<[f64]>>(x: V) -> Result<V, MechError> {
    if x.as_ref().iter().all(|v| v.is_finite()) {
        Ok(x)
    } else {
        Err(MechError::Singular {
            condition: f64::INFINITY,
        })
    }
}

/// The heap frame, sized at load: `bodies` N, `rows` the rows (joints', drivers', idle
/// spins'; more than 6(N − 1) with redundant constraints, solved by least squares). What
/// the run-time mechanism uses; it allocates.
#[derive(Clone, Copy, Debug)]
pub struct Dense {
    /// N, the ground included.
    pub bodies: usize,
    /// The rows of J.
    pub rows: usize,
}

impl RowBuffer for (Vec<Row>, Vec<(usize, usize)>) {
    fn push(&mut self, row: Row, owner: (usize, usize)) {
        self.0.push(row);
        self.1.push(owner);
    }
    fn clear(&mut self) {
        self.0.clear();
        self.1.clear();
    }
    fn rows(&self) -> &[Row] {
        &self.0
    }
    fn owners(&self) -> &[(usize, usize)] {
        &self.1
    }
}

impl Frame for Dense {
    type States = Vec<BodyState>;
    type Motions = Vec<BodyMotion>;
    type Rows = (Vec<Row>, Vec<(usize, usize)>);
    type Vector = Vec<f64>;
    type Factored = DMatrix<f64>;

    fn fits(self, bodies: usize, rows: usize) -> Result<(), MechError> {
        if bodies == self.bodies && rows == self.rows {
            Ok(())
        } else {
            Err(MechError::InvalidInput(format!(
                "a heap frame of {} bodies and {} rows; this mechanism has {bodies} bodies and {rows} rows",
                self.bodies, self.rows
            )))
        }
    }

    fn states(self, o0: &[Vector3<f64>]) -> Vec<BodyState> {
        o0.iter().map(|&o| BodyState::drawing(o)).collect()
    }
    fn motions(self) -> Vec<BodyMotion> {
        vec![BodyMotion::rest(); self.bodies]
    }
    fn rows(self) -> Self::Rows {
        (Vec::with_capacity(self.rows), Vec::with_capacity(self.rows))
    }
    fn rhs(self) -> Vec<f64> {
        vec![0.0; self.rows]
    }
    fn unknowns(self) -> Vec<f64> {
        vec![0.0; 6 * self.bodies.saturating_sub(1)]
    }
    fn factor(self, rows: &Self::Rows) -> Result<DMatrix<f64>, MechError> {
        let mut j = DMatrix::zeros(rows.0.len(), 6 * self.bodies.saturating_sub(1));
        assemble(&rows.0, &rows.1, |r, c, v| j[(r, c)] += v);
        Ok(j)
    }
    fn solve(self, j: &DMatrix<f64>, b: &Vec<f64>) -> Result<Vec<f64>, MechError> {
        Ok(solve(j.clone(), DVector::from_column_slice(b))?.data.into())
    }
    fn solve_transpose(self, j: &DMatrix<f64>, w: &Vec<f64>) -> Result<Vec<f64>, MechError> {
        Ok(solve(j.transpose(), DVector::from_column_slice(w))?
            .data
            .into())
    }
}
