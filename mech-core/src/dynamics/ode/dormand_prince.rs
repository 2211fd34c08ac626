//! Dormand–Prince 5(4): [`DormandPrince`], the pair [`Dp5`] with its coefficients, and
//! Shampine's quartic dense output [`Dp5Poly`].

use super::adaptive::{Adaptive, Tableau, Tolerance};
use super::dense::{Interpolant, StepDense};
use super::method::{eval, lincomb, Stats};
use crate::MechError;

/// Dormand–Prince 5(4) (Hairer's DOPRI5): fifth-order solution, fourth-order embedded
/// error estimate, 7 stages with the last one reused (FSAL: 6 new evaluations a step),
/// Shampine's quartic dense output.
pub type DormandPrince = Adaptive<Dp5>;

/// The Dormand–Prince 5(4) pair (see [`DormandPrince`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dp5;

mod dp5 {
    pub const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
    pub const A2: [f64; 1] = [1.0 / 5.0];
    pub const A3: [f64; 2] = [3.0 / 40.0, 9.0 / 40.0];
    pub const A4: [f64; 3] = [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0];
    pub const A5: [f64; 4] = [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ];
    pub const A6: [f64; 5] = [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ];
    /// The fifth-order weights (also the 7th stage's row: FSAL).
    pub const B: [f64; 6] = [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ];
    /// b − b̂ (fifth minus fourth order), over the 7 stages.
    pub const E: [f64; 7] = [
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ];
    /// Shampine's dense output: y(t0 + θh) = y0 + h Σ_j k_j Σ_m P[j][m] θ^(m+1).
    pub const P: [[f64; 4]; 7] = [
        [
            1.0,
            -8048581381.0 / 2820520608.0,
            8663915743.0 / 2820520608.0,
            -12715105075.0 / 11282082432.0,
        ],
        [0.0, 0.0, 0.0, 0.0],
        [
            0.0,
            131558114200.0 / 32700410799.0,
            -68118460800.0 / 10900136933.0,
            87487479700.0 / 32700410799.0,
        ],
        [
            0.0,
            -1754552775.0 / 470086768.0,
            14199869525.0 / 1410260304.0,
            -10690763975.0 / 1880347072.0,
        ],
        [
            0.0,
            127303824393.0 / 49829197408.0,
            -318862633887.0 / 49829197408.0,
            701980252875.0 / 199316789632.0,
        ],
        [
            0.0,
            -282668133.0 / 205662961.0,
            2019193451.0 / 616988883.0,
            -1453857185.0 / 822651844.0,
        ],
        [
            0.0,
            40617522.0 / 29380423.0,
            -110615467.0 / 29380423.0,
            69997945.0 / 29380423.0,
        ],
    ];
}

/// Shampine's quartic dense output of [`DormandPrince`]: y0 + h Σ_m Q_m θ^(m+1), Q = Kᵀ P.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dp5Poly<const N: usize> {
    q: [[f64; N]; 4],
}

impl<const N: usize> Interpolant<N> for Dp5Poly<N> {
    fn at(d: &StepDense<N, Self>, s: f64) -> [f64; N] {
        let q = &d.poly.q;
        let mut out = d.y0;
        for i in 0..N {
            let p = ((q[3][i] * s + q[2][i]) * s + q[1][i]) * s + q[0][i];
            out[i] += d.h * s * p;
        }
        out
    }
}

impl<const N: usize> Tableau<N> for Dp5 {
    const ERROR_ORDER: u32 = 4;
    type Poly = Dp5Poly<N>;
    fn attempt<F>(
        f: &mut F,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        h: f64,
        _: &Tolerance,
        stats: &mut Stats,
    ) -> Result<([f64; N], [f64; N], [f64; N], Dp5Poly<N>), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        use dp5::*;
        let mut k = [[0.0; N]; 7];
        k[0] = *dy;
        k[1] = eval(f, t + C[1] * h, &lincomb(y, h, &A2, &[k[0]]), stats)?;
        k[2] = eval(f, t + C[2] * h, &lincomb(y, h, &A3, &[k[0], k[1]]), stats)?;
        k[3] = eval(
            f,
            t + C[3] * h,
            &lincomb(y, h, &A4, &[k[0], k[1], k[2]]),
            stats,
        )?;
        k[4] = eval(
            f,
            t + C[4] * h,
            &lincomb(y, h, &A5, &[k[0], k[1], k[2], k[3]]),
            stats,
        )?;
        k[5] = eval(
            f,
            t + C[5] * h,
            &lincomb(y, h, &A6, &[k[0], k[1], k[2], k[3], k[4]]),
            stats,
        )?;
        let y1 = lincomb(y, h, &B, &[k[0], k[1], k[2], k[3], k[4], k[5]]);
        k[6] = eval(f, t + h, &y1, stats)?;
        let e = lincomb(&[0.0; N], h, &E, &k);
        let mut q = [[0.0; N]; 4];
        for (m, qm) in q.iter_mut().enumerate() {
            let col: [f64; 7] = core::array::from_fn(|j| P[j][m]);
            *qm = lincomb(&[0.0; N], 1.0, &col, &k);
        }
        Ok((y1, e, k[6], Dp5Poly { q }))
    }
}
