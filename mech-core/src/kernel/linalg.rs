//! Small dense linear algebra on the stack: LU with partial pivoting of an N×N system,
//! and the threshold on the condition estimate beyond which a system is `Singular`.

use nalgebra::{SMatrix, SVector};

/// Threshold on the condition estimate κ (the pivot ratio of a group's scaled system)
/// beyond which it is reported `Singular` (a dead point or toggle position). Near a
/// toggle, rates carry a relative error of order ε·κ², so 1e6 bounds it by about 1e-4.
pub const SINGULAR_CONDITION: f64 = 1e6;

/// LU factorisation with partial pivoting of a small fixed-size matrix, on the stack.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lu<const N: usize> {
    m: SMatrix<f64, N, N>,
    perm: [usize; N],
}

impl<const N: usize> Lu<N> {
    /// Factor P A = L U (L unit lower, U upper, stored together).
    #[inline(always)]
    pub fn new(mut m: SMatrix<f64, N, N>) -> Self {
        let mut perm = [0usize; N];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        for k in 0..N {
            let mut piv = k;
            for i in k + 1..N {
                if m[(i, k)].abs() > m[(piv, k)].abs() {
                    piv = i;
                }
            }
            if piv != k {
                m.swap_rows(k, piv);
                perm.swap(k, piv);
            }
            let d = m[(k, k)];
            if d == 0.0 {
                continue;
            }
            for i in k + 1..N {
                let f = m[(i, k)] / d;
                m[(i, k)] = f;
                for c in k + 1..N {
                    m[(i, c)] -= f * m[(k, c)];
                }
            }
        }
        Lu { m, perm }
    }
    /// Pivot ratio max|U_ii| / min|U_ii|: a cheap condition estimate (∞ when singular).
    #[inline(always)]
    pub fn condition(&self) -> f64 {
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for i in 0..N {
            let d = self.m[(i, i)].abs();
            lo = lo.min(d);
            hi = hi.max(d);
        }
        if lo > 0.0 {
            hi / lo
        } else {
            f64::INFINITY
        }
    }
    /// Solve A x = b.
    #[inline]
    pub fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let mut x = SVector::<f64, N>::zeros();
        for i in 0..N {
            let mut v = b[self.perm[i]];
            for k in 0..i {
                v -= self.m[(i, k)] * x[k];
            }
            x[i] = v;
        }
        for i in (0..N).rev() {
            let mut v = x[i];
            for k in i + 1..N {
                v -= self.m[(i, k)] * x[k];
            }
            x[i] = v / self.m[(i, i)];
        }
        x
    }
    /// Solve Aᵀ x = b.
    #[inline]
    pub fn solve_transpose(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        // Aᵀ = Uᵀ Lᵀ P: solve Uᵀ y = b, Lᵀ z = y, x = Pᵀ z.
        let mut y = SVector::<f64, N>::zeros();
        for i in 0..N {
            let mut v = b[i];
            for k in 0..i {
                v -= self.m[(k, i)] * y[k];
            }
            y[i] = v / self.m[(i, i)];
        }
        for i in (0..N).rev() {
            let mut v = y[i];
            for k in i + 1..N {
                v -= self.m[(k, i)] * y[k];
            }
            y[i] = v;
        }
        let mut x = SVector::<f64, N>::zeros();
        for i in 0..N {
            x[self.perm[i]] = y[i];
        }
        x
    }
}

/// The inverse of a 2×2 matrix A = [[a, b], [c, d]], refused near singularity by the
/// condition estimate of A·diag(c₀, c₁) (the columns scaled to be dimensionless):
/// κ_F = ‖A C‖_F ‖(A C)⁻¹‖_F = ‖A C‖²_F / |det A C| (exact for 2×2: ‖B⁻¹‖_F = ‖B‖_F / |det B|).
///
/// Kept as the adjugate and 1/det: a solve multiplies by 1/det last, so the division runs
/// beside the products adj·b instead of before them (the direct problem waits on it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inverse2 {
    /// adj A = det A · A⁻¹, row major.
    pub adj: [[f64; 2]; 2],
    /// 1/det A.
    pub inv_det: f64,
}

impl Inverse2 {
    /// Invert `m` (row major; columns given as the caller scaled them to be dimensionless);
    /// `Singular` when κ_F ≥ [`SINGULAR_CONDITION`] or it is not finite.
    #[inline(always)]
    pub fn new(m: [[f64; 2]; 2]) -> Result<Self, crate::MechError> {
        Self::scaled(m, [1.0, 1.0])
    }
    /// Invert `m` (row major), the condition estimate taken on `m` with its columns
    /// multiplied by `c` (which makes them dimensionless): `Singular` when
    /// ‖A C‖²_F ≥ [`SINGULAR_CONDITION`] |det A C| or either is not finite. The test
    /// multiplies, so that the one division is 1/det.
    #[inline(always)]
    pub fn scaled(m: [[f64; 2]; 2], c: [f64; 2]) -> Result<Self, crate::MechError> {
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        let norm2 = c[0] * c[0] * (m[0][0] * m[0][0] + m[1][0] * m[1][0])
            + c[1] * c[1] * (m[0][1] * m[0][1] + m[1][1] * m[1][1]);
        check_condition(norm2, (c[0] * c[1] * det).abs())?;
        Ok(Inverse2 {
            adj: [[m[1][1], -m[0][1]], [-m[1][0], m[0][0]]],
            inv_det: 1.0 / det,
        })
    }
    /// A⁻¹ b = (adj A · b) / det A.
    #[inline(always)]
    pub fn solve(&self, b: [f64; 2]) -> [f64; 2] {
        let m = &self.adj;
        [
            (m[0][0] * b[0] + m[0][1] * b[1]) * self.inv_det,
            (m[1][0] * b[0] + m[1][1] * b[1]) * self.inv_det,
        ]
    }
    /// A⁻ᵀ b = (adj Aᵀ · b) / det A.
    #[inline(always)]
    pub fn solve_transpose(&self, b: [f64; 2]) -> [f64; 2] {
        let m = &self.adj;
        [
            (m[0][0] * b[0] + m[1][0] * b[1]) * self.inv_det,
            (m[0][1] * b[0] + m[1][1] * b[1]) * self.inv_det,
        ]
    }
}

/// A 2×2 system's condition test, κ_F = ‖A C‖²_F / |det A C| ([`Inverse2`]) from
/// `norm2` = ‖A C‖²_F and `sdet` = |det A C|: `Singular` when κ_F ≥
/// [`SINGULAR_CONDITION`] or either is not finite. It multiplies, so that the caller's
/// one division is 1/det.
#[inline(always)]
pub fn check_condition(norm2: f64, sdet: f64) -> Result<(), crate::MechError> {
    if norm2 < SINGULAR_CONDITION * sdet {
        Ok(())
    } else {
        Err(singular2(norm2, sdet))
    }
}

/// The `Singular` error of a 2×2 system with ‖A C‖²_F = `norm2` and |det A C| = `sdet`.
#[cold]
#[inline(never)]
fn singular2(norm2: f64, sdet: f64) -> crate::MechError {
    let condition = norm2 / sdet;
    crate::MechError::Singular {
        condition: if condition.is_nan() {
            f64::INFINITY
        } else {
            condition
        },
    }
}
