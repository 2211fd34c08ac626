//! The branch-free functions of the lane kernels: [`sin_cos`] and [`atan2`] after fdlibm,
//! with the scalar functions for the lanes outside their fast ranges, and [`wrap`].

// The polynomial and π constants are fdlibm's, digit for digit as published (each rounds
// to the double it names).
#![allow(clippy::excessive_precision)]

use super::{Backend, Bits, L, LANES};

/// 1.5·2⁵²: adding and removing it rounds a number below 2⁵¹ in magnitude to the nearest
/// whole number (ties to even), with no rounding instruction; the sum's low mantissa bits
/// are that whole number modulo 2⁵¹.
const ROUND: f64 = 6_755_399_441_055_744.0;

/// 2/π.
const INV_PIO2: f64 = std::f64::consts::FRAC_2_PI;
/// The first 33 bits of π/2 (fdlibm's `pio2_1`): k·PIO2_1 is exact for k < 2²⁰.
const PIO2_1: f64 = 1.570_796_326_734_125_614_17e0;
/// The next 33 bits of π/2 (fdlibm's `pio2_2`).
const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11;
/// π/2 − PIO2_1 − PIO2_2 (fdlibm's `pio2_2t`).
const PIO2_2T: f64 = 2.022_266_248_795_950_631_54e-21;

/// The range |x| ≤ `SIN_COS_RANGE` (rad) of [`sin_cos`]'s vector path: the number of
/// quarter turns k < 2²⁰ keeps k·PIO2_1 and k·PIO2_2 exact.
pub const SIN_COS_RANGE: f64 = 1.0e6;

/// sin and cos of x + y on |x + y| ≤ π/4 (+ tiny), y a small correction of x: musl's
/// `__sin(x, y, 1)` (fdlibm's `__kernel_sin`), error below 1 ulp.
#[inline(always)]
fn kernel_sin<B: Backend>(x: L<B>, y: L<B>) -> L<B> {
    const S1: f64 = -1.666_666_666_666_663_243_48e-1;
    const S2: f64 = 8.333_333_333_322_489_461_24e-3;
    const S3: f64 = -1.984_126_982_985_794_931_34e-4;
    const S4: f64 = 2.755_731_370_707_006_767_89e-6;
    const S5: f64 = -2.505_076_025_340_686_341_95e-8;
    const S6: f64 = 1.589_690_995_211_550_102_21e-10;
    let z = x * x;
    let w = z * z;
    let r = (z * (z * S4 + S3) + S2) + z * w * (z * S6 + S5);
    let v = z * x;
    x - ((z * (y * 0.5 - v * r) - y) - v * S1)
}

/// cos of x + y on |x + y| ≤ π/4 (+ tiny): musl's `__cos(x, y)` (fdlibm's
/// `__kernel_cos`), error below 1 ulp.
#[inline(always)]
fn kernel_cos<B: Backend>(x: L<B>, y: L<B>) -> L<B> {
    const C1: f64 = 4.166_666_666_666_660_190_37e-2;
    const C2: f64 = -1.388_888_888_887_410_957_49e-3;
    const C3: f64 = 2.480_158_728_947_672_941_78e-5;
    const C4: f64 = -2.755_731_435_139_066_330_35e-7;
    const C5: f64 = 2.087_572_321_298_174_827_90e-9;
    const C6: f64 = -1.135_964_755_778_819_482_65e-11;
    let z = x * x;
    let w = z * z;
    let r = z * (z * (z * C3 + C2) + C1) + w * w * (z * (z * C6 + C5) + C4);
    let hz = z * 0.5;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + (z * r - x * y))
}

/// (sin x, cos x) per lane, x in rad, branch-free: x reduced by the nearest whole number k
/// of quarter turns with π/2 in three parts (fdlibm's medium-range reduction, exact to
/// about 2⁻¹¹⁹ k), then fdlibm's minimax polynomials on |r| ≤ π/4 and the quadrant k mod 4.
///
/// Accuracy against `f64::sin_cos`, measured by
/// `sin_cos_and_atan2_are_within_their_stated_ulps` over 1.2·10⁶ arguments
/// (|x| ≤ 10⁴π, |x| ≤ 1, |x| ≤ 10⁶): at most 1 ulp for both. Lanes beyond
/// |x| ≤ [`SIN_COS_RANGE`] (and NaNs, infinities) are computed by `f64::sin_cos`.
#[inline(always)]
pub fn sin_cos<B: Backend>(x: L<B>) -> (L<B>, L<B>) {
    let t = x * INV_PIO2 + ROUND;
    let k = t - ROUND;
    // r = x − k π/2 as y0 + y1: k·PIO2_1 and k·PIO2_2 are exact, so is x − k·PIO2_1.
    let r0 = x - k * PIO2_1;
    let w = k * PIO2_2;
    let r = r0 - w;
    let w = k * PIO2_2T - ((r0 - r) - w);
    let y0 = r - w;
    let y1 = (r - y0) - w;
    let (s, c) = (kernel_sin(y0, y1), kernel_cos(y0, y1));
    // The quadrant: k mod 4 in the low bits of t; sin and cos swapped where k is odd, sin
    // negated where k mod 4 ∈ {2, 3}, cos where k mod 4 ∈ {1, 2} (sign bits xored in).
    let (odd, ss, cs) = B::quadrant(t.r());
    let odd = Bits::<B>(odd);
    let (s1, c1) = (odd.select(c, s), odd.select(s, c));
    let mut sn = L::of(B::xor(s1.r(), ss));
    let mut cs = L::of(B::xor(c1.r(), cs));
    let out = x.abs().not_less_eq(L::splat(SIN_COS_RANGE));
    if out.any() {
        let out = out.mask();
        for i in 0..LANES {
            if out[i] {
                (sn.0[i], cs.0[i]) = x.0[i].sin_cos();
            }
        }
    }
    (sn, cs)
}

/// atan t on 0 ≤ t ≤ 1: fdlibm's `atan` (its first three intervals, branch-free: each lane
/// takes the transformed argument (a t + b)/(c t + d) and the constants of its interval),
/// error below 1 ulp.
#[inline(always)]
fn atan_unit<B: Backend>(t: L<B>) -> L<B> {
    const HI: [f64; 2] = [4.636_476_090_008_060_935_15e-1, std::f64::consts::FRAC_PI_4];
    const LO: [f64; 2] = [
        2.269_877_745_296_168_709_24e-17,
        3.061_616_997_868_383_017_93e-17,
    ];
    const AT: [f64; 11] = [
        3.333_333_333_333_293_180_27e-1,
        -1.999_999_999_987_648_324_76e-1,
        1.428_571_427_250_346_637_11e-1,
        -1.111_111_040_546_235_578_80e-1,
        9.090_887_133_436_506_561_96e-2,
        -7.691_876_205_044_829_994_95e-2,
        6.661_073_137_387_531_206_69e-2,
        -5.833_570_133_790_573_486_45e-2,
        4.976_877_994_615_932_360_17e-2,
        -3.653_157_274_421_691_552_70e-2,
        1.628_582_011_536_578_236_23e-2,
    ];
    // Interval −1: t < 7/16, x = t; 0: t < 11/16, x = (2t − 1)/(2 + t); 1: x = (t − 1)/(t + 1).
    let small = t.less(L::splat(7.0 / 16.0));
    let mid = t.less(L::splat(11.0 / 16.0));
    let one = L::splat(1.0);
    let two_or_one = mid.select(L::splat(2.0), one);
    let num = small.select(t, two_or_one * t - 1.0);
    let den = small.select(one, t + two_or_one);
    let x = num / den;
    let z = x * x;
    let w = z * z;
    let s1 = z * (w * (w * (w * (w * (w * AT[10] + AT[8]) + AT[6]) + AT[4]) + AT[2]) + AT[0]);
    let s2 = w * (w * (w * (w * (w * AT[9] + AT[7]) + AT[5]) + AT[3]) + AT[1]);
    let hi = mid.select(L::splat(HI[0]), L::splat(HI[1]));
    let lo = mid.select(L::splat(LO[0]), L::splat(LO[1]));
    let p = x * (s1 + s2);
    small.select(x - p, hi - ((p - lo) - x))
}

/// atan2(y, x) per lane (rad, in (−π, π]), branch-free: atan of t = min(|x|, |y|) /
/// max(|x|, |y|) ≤ 1 (fdlibm's polynomial), then π/2 − z when |y| > |x|, π − z when x < 0
/// (π/2 and π in two parts), and y's sign.
///
/// Accuracy against `f64::atan2`, measured by `sin_cos_and_atan2_are_within_their_stated_ulps`
/// over 10⁶ arguments (directions all around, magnitudes 10⁻³ to 10³): at most 2 ulp. Lanes
/// where both are zero or either is not finite are computed by `f64::atan2`.
#[inline(always)]
pub fn atan2<B: Backend>(y: L<B>, x: L<B>) -> L<B> {
    const PIO2_HI: f64 = std::f64::consts::FRAC_PI_2;
    const PIO2_LO: f64 = 6.123_233_995_736_766_035_87e-17;
    const PI_HI: f64 = std::f64::consts::PI;
    const PI_LO: f64 = 1.224_646_799_147_353_177_2e-16;
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ax.less(ay);
    let (mn, mx) = (steep.select(ax, ay), steep.select(ay, ax));
    let z = atan_unit(mn / mx);
    let west = x.less(L::splat(0.0));
    // hi − (±z − lo): z; π/2 − z (steep); π − z (west); π/2 + z (steep and west).
    let hi = steep.select(
        L::splat(PIO2_HI),
        west.select(L::splat(PI_HI), L::splat(0.0)),
    );
    let lo = steep.select(
        L::splat(PIO2_LO),
        west.select(L::splat(PI_LO), L::splat(0.0)),
    );
    // −z where steep == west: z's sign flipped by each, then once more.
    let z = hi - (-z.flip_sign(steep).flip_sign(west) - lo);
    // −z where y's sign bit is set.
    let mut out = z.flip_sign_by(y);
    let special = mx
        .not_greater(L::splat(0.0))
        .or(mx.not_less(L::splat(f64::INFINITY)))
        .or((mn + y).non_finite());
    if special.any() {
        let special = special.mask();
        for i in 0..LANES {
            if special[i] {
                out.0[i] = y.0[i].atan2(x.0[i]);
            }
        }
    }
    out
}

/// Angle difference wrapped to (−π, π] (rad) per lane: the same operations as
/// [`crate::kernel::link_state::wrap`], so the same results bit for bit (lanes beyond
/// |a| ≥ 10⁹ go through it).
#[inline(always)]
pub fn wrap<B: Backend>(a: L<B>) -> L<B> {
    use std::f64::consts::{PI, TAU};
    let r = a - ((a / L::splat(TAU) + ROUND) - ROUND) * TAU;
    let low = r.less_eq(L::splat(-PI));
    let mut out = low.select(r + TAU, r);
    let far = a.abs().not_less(L::splat(1e9));
    if far.any() {
        let far = far.mask();
        for i in 0..LANES {
            if far[i] {
                out.0[i] = crate::kernel::link_state::wrap(a.0[i]);
            }
        }
    }
    out
}
