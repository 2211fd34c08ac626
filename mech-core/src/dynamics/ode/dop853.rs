//! Hairer's DOP853: [`Dop853`], its step and error estimate ([`Dop8`]) and its
//! seventh-order dense output ([`Dop8Poly`]); the coefficients are in
//! `dop853_coefficients`.

use super::adaptive::{Adaptive, Tableau, Tolerance};
use super::dense::{Interpolant, StepDense};
use super::method::{eval, lincomb, Stats};
use crate::MechError;

/// Hairer's DOP853: an eighth-order explicit Runge–Kutta method with a combined 5th/3rd
/// order error estimate (12 stages, the 13th, f at the new point, reused), and a
/// seventh-order dense output that costs 3 more evaluations a step, spent on every step
/// for an observer and only on the event's step for an event.
pub type Dop853 = Adaptive<Dop8>;

/// The DOP853 method's coefficients and error estimate (see [`Dop853`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dop8;

/// The dense output of [`Dop853`].
pub type Dop853Dense<const N: usize> = StepDense<N, Dop8Poly<N>>;

/// The interpolant of [`Dop853`]: the seventh-degree polynomial of Hairer's `contd8`,
/// y = y0 + θ(F0 + (1−θ)(F1 + θ(F2 + (1−θ)(F3 + θ(F4 + (1−θ)(F5 + θ F6)))))). Until the
/// extra stages are computed ([`Method::densify`](super::Method::densify)) it is the cubic
/// Hermite interpolant (F3..F6 = 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dop8Poly<const N: usize> {
    coef: [[f64; N]; 7],
    /// The 16 stages (the last 3 only once the interpolant is complete).
    k: [[f64; N]; 16],
    degree7: bool,
}

impl<const N: usize> Interpolant<N> for Dop8Poly<N> {
    fn at(d: &StepDense<N, Self>, s: f64) -> [f64; N] {
        let s1 = 1.0 - s;
        let top = if d.poly.degree7 { 7 } else { 3 };
        let mut out = [0.0; N];
        for i in 0..N {
            let mut acc = 0.0;
            for (m, c) in d.poly.coef[..top].iter().enumerate().rev() {
                acc += c[i];
                acc *= if m % 2 == 0 { s } else { s1 };
            }
            out[i] = d.y0[i] + acc;
        }
        out
    }
}

impl<const N: usize> Tableau<N> for Dop8 {
    const ERROR_ORDER: u32 = 7;
    type Poly = Dop8Poly<N>;
    fn attempt<F>(
        f: &mut F,
        t: f64,
        y: &[f64; N],
        dy: &[f64; N],
        h: f64,
        tol: &Tolerance,
        stats: &mut Stats,
    ) -> Result<([f64; N], [f64; N], [f64; N], Dop8Poly<N>), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        use super::dop853_coefficients::*;
        let mut k = [[0.0; N]; 16];
        k[0] = *dy;
        for s in 1..12 {
            let ys = lincomb(y, h, &A[s], &k);
            k[s] = eval(f, t + C[s] * h, &ys, stats)?;
        }
        let y1 = lincomb(y, h, &A[12], &k);
        k[12] = eval(f, t + h, &y1, stats)?;
        // Hairer's combined estimate |h| ‖e5‖² / sqrt(‖e5‖² + 0.01 ‖e3‖²), returned as the
        // vector e = ratio · e5 whose scaled RMS norm equals it.
        let (mut n5, mut n3) = (0.0, 0.0);
        let mut e5 = [0.0; N];
        for i in 0..N {
            let (mut a5, mut a3) = (0.0, 0.0);
            for j in 0..13 {
                a5 += E5[j] * k[j][i];
                a3 += E3[j] * k[j][i];
            }
            let sc = tol.scale(y[i], y1[i]);
            e5[i] = a5;
            n5 += (a5 / sc).powi(2);
            n3 += (a3 / sc).powi(2);
        }
        let ratio = if n5 == 0.0 && n3 == 0.0 {
            0.0
        } else {
            h.abs() * n5.sqrt() / (n5 + 0.01 * n3).sqrt()
        };
        let e = e5.map(|v| ratio * v);
        let mut coef = [[0.0; N]; 7];
        for i in 0..N {
            let dyi = y1[i] - y[i];
            coef[0][i] = dyi;
            coef[1][i] = h * k[0][i] - dyi;
            coef[2][i] = 2.0 * dyi - h * (k[12][i] + k[0][i]);
        }
        Ok((
            y1,
            e,
            k[12],
            Dop8Poly {
                coef,
                k,
                degree7: false,
            },
        ))
    }

    fn densify<F>(
        f: &mut F,
        d: &mut StepDense<N, Dop8Poly<N>>,
        stats: &mut Stats,
    ) -> Result<(), MechError>
    where
        F: FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError>,
    {
        use super::dop853_coefficients::*;
        if d.poly.degree7 {
            return Ok(());
        }
        let (t, h) = (d.t0, d.h);
        for s in 13..16 {
            let ys = lincomb(&d.y0, h, &A[s], &d.poly.k);
            d.poly.k[s] = eval(f, t + C[s] * h, &ys, stats)?;
        }
        for m in 0..4 {
            d.poly.coef[3 + m] = lincomb(&[0.0; N], h, &D[m], &d.poly.k);
        }
        d.poly.degree7 = true;
        Ok(())
    }
}
