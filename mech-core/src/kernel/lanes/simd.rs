//! The lane type: four `f64` values computed side by side, written as plain fixed-size
//! arrays whose element-wise loops LLVM turns into packed instructions (two SSE2 registers
//! per lane value on the x86-64 baseline, one AVX register inside [`super::with_simd`]),
//! and the branch-free functions the lane kernels need: [`sin_cos`], [`atan2`], [`wrap`].
//!
//! Every function here is `#[inline(always)]`, so that it is compiled with the target
//! features of the function it lands in.

// The polynomial and π constants are fdlibm's, digit for digit as published (each rounds
// to the double it names).
#![allow(clippy::excessive_precision)]
// Lanes are indexed side by side in several arrays at once.
#![allow(clippy::needless_range_loop)]

use crate::kernel::link_state::V2;
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// The number of configurations computed side by side.
pub const LANES: usize = 4;

/// Four `f64` values, one per configuration (a lane), in whatever unit the quantity has.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(transparent)]
pub struct L(pub [f64; LANES]);

/// The lanes that failed or may fail (`true`): the caller recomputes them with the scalar
/// kernels.
pub type Mask = [bool; LANES];

/// No lane failed.
pub const NONE: Mask = [false; LANES];

/// Every lane failed.
pub const ALL: Mask = [true; LANES];

/// Whether any lane of `m` is set.
#[inline(always)]
pub fn any(m: Mask) -> bool {
    m[0] | m[1] | m[2] | m[3]
}

/// The lanes set in `a` or in `b`.
#[inline(always)]
pub fn or(a: Mask, b: Mask) -> Mask {
    [a[0] | b[0], a[1] | b[1], a[2] | b[2], a[3] | b[3]]
}

impl L {
    /// The same value `x` in every lane.
    #[inline(always)]
    pub const fn splat(x: f64) -> L {
        L([x; LANES])
    }
    /// The lanes `f(0)`, …, `f(3)`.
    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> f64) -> L {
        L(std::array::from_fn(f))
    }
    /// `f` applied to each lane.
    #[inline(always)]
    pub fn map(self, mut f: impl FnMut(f64) -> f64) -> L {
        L([f(self.0[0]), f(self.0[1]), f(self.0[2]), f(self.0[3])])
    }
    /// `f` applied lane by lane to `self` and `o`.
    #[inline(always)]
    pub fn zip(self, o: L, mut f: impl FnMut(f64, f64) -> f64) -> L {
        L([
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
            f(self.0[3], o.0[3]),
        ])
    }
    /// The comparison `f` lane by lane.
    #[inline(always)]
    pub fn test(self, o: L, mut f: impl FnMut(f64, f64) -> bool) -> Mask {
        [
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
            f(self.0[3], o.0[3]),
        ]
    }
    /// √x per lane (`f64::sqrt`, correctly rounded).
    #[inline(always)]
    pub fn sqrt(self) -> L {
        self.map(f64::sqrt)
    }
    /// |x| per lane.
    #[inline(always)]
    pub fn abs(self) -> L {
        self.map(f64::abs)
    }
    /// The larger of the two per lane (`self` when either is a NaN: `x < y ? y : x`).
    #[inline(always)]
    pub fn max(self, o: L) -> L {
        self.zip(o, |a, b| if a < b { b } else { a })
    }
    /// The smaller of the two per lane (`self` when either is a NaN: `y < x ? y : x`).
    #[inline(always)]
    pub fn min(self, o: L) -> L {
        self.zip(o, |a, b| if b < a { b } else { a })
    }
    /// The lanes where x < y.
    #[inline(always)]
    pub fn lt(self, o: L) -> Mask {
        self.test(o, |a, b| a < b)
    }
    /// The lanes where x is not finite (an infinity or a NaN).
    #[inline(always)]
    pub fn not_finite(self) -> Mask {
        self.test(L::splat(f64::INFINITY), |a, inf| !(a.abs() < inf))
    }
}

/// Per lane, `a` where `m` is set, else `b`.
#[inline(always)]
pub fn select(m: Mask, a: L, b: L) -> L {
    L([
        if m[0] { a.0[0] } else { b.0[0] },
        if m[1] { a.0[1] } else { b.0[1] },
        if m[2] { a.0[2] } else { b.0[2] },
        if m[3] { a.0[3] } else { b.0[3] },
    ])
}

macro_rules! binary {
    ($tr:ident, $f:ident, $op:tt, $tra:ident, $fa:ident) => {
        impl $tr for L {
            type Output = L;
            #[inline(always)]
            fn $f(self, o: L) -> L {
                L([self.0[0] $op o.0[0], self.0[1] $op o.0[1], self.0[2] $op o.0[2], self.0[3] $op o.0[3]])
            }
        }
        impl $tr<f64> for L {
            type Output = L;
            #[inline(always)]
            fn $f(self, o: f64) -> L {
                L([self.0[0] $op o, self.0[1] $op o, self.0[2] $op o, self.0[3] $op o])
            }
        }
        impl $tr<L> for f64 {
            type Output = L;
            #[inline(always)]
            fn $f(self, o: L) -> L {
                L([self $op o.0[0], self $op o.0[1], self $op o.0[2], self $op o.0[3]])
            }
        }
        impl $tra for L {
            #[inline(always)]
            fn $fa(&mut self, o: L) {
                *self = *self $op o;
            }
        }
    };
}
binary!(Add, add, +, AddAssign, add_assign);
binary!(Sub, sub, -, SubAssign, sub_assign);
binary!(Mul, mul, *, MulAssign, mul_assign);

impl Div for L {
    type Output = L;
    #[inline(always)]
    fn div(self, o: L) -> L {
        self.zip(o, |a, b| a / b)
    }
}

impl Div<L> for f64 {
    type Output = L;
    #[inline(always)]
    fn div(self, o: L) -> L {
        L::splat(self) / o
    }
}

impl Neg for L {
    type Output = L;
    #[inline(always)]
    fn neg(self) -> L {
        self.map(|a| -a)
    }
}

/// A plane vector per lane (m, m/s, m/s², N): the lane twin of [`V2`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct V2L {
    /// x components.
    pub x: L,
    /// y components.
    pub y: L,
}

impl V2L {
    /// The vector `v` in every lane.
    #[inline(always)]
    pub fn splat(v: V2) -> V2L {
        V2L {
            x: L::splat(v.x),
            y: L::splat(v.y),
        }
    }
    /// From its components.
    #[inline(always)]
    pub fn new(x: L, y: L) -> V2L {
        V2L { x, y }
    }
    /// The vector of lane `i`.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> V2 {
        V2::new(self.x.0[i], self.y.0[i])
    }
    /// As `[x, y]`.
    #[inline(always)]
    pub fn xy(self) -> [L; 2] {
        [self.x, self.y]
    }
    /// a·b.
    #[inline(always)]
    pub fn dot(self, o: V2L) -> L {
        self.x * o.x + self.y * o.y
    }
    /// a·b with `b` the same in every lane.
    #[inline(always)]
    pub fn dot_v(self, o: V2) -> L {
        self.x * o.x + self.y * o.y
    }
    /// |a|².
    #[inline(always)]
    pub fn norm_squared(self) -> L {
        self.x * self.x + self.y * self.y
    }
    /// a × b = a_x b_y − a_y b_x.
    #[inline(always)]
    pub fn cross(self, o: V2L) -> L {
        self.x * o.y - self.y * o.x
    }
    /// perp(a) = (−a_y, a_x).
    #[inline(always)]
    pub fn perp(self) -> V2L {
        V2L {
            x: -self.y,
            y: self.x,
        }
    }
    /// `d` (the same in every lane) turned by the unit complex `self` = (cos φ, sin φ),
    /// as [`crate::kernel::link_state::rotate`].
    #[inline(always)]
    pub fn rotate(self, d: V2) -> V2L {
        V2L {
            x: self.x * d.x - self.y * d.y,
            y: self.y * d.x + self.x * d.y,
        }
    }
    /// `d` turned by the unit complex `self`, both per lane.
    #[inline(always)]
    pub fn rotate_l(self, d: V2L) -> V2L {
        V2L {
            x: self.x * d.x - self.y * d.y,
            y: self.y * d.x + self.x * d.y,
        }
    }
    /// The lanes where a component is not finite.
    #[inline(always)]
    pub fn not_finite(self) -> Mask {
        (self.x + self.y).not_finite()
    }
}

impl Add for V2L {
    type Output = V2L;
    #[inline(always)]
    fn add(self, o: V2L) -> V2L {
        V2L::new(self.x + o.x, self.y + o.y)
    }
}

impl Add<V2> for V2L {
    type Output = V2L;
    #[inline(always)]
    fn add(self, o: V2) -> V2L {
        V2L::new(self.x + o.x, self.y + o.y)
    }
}

impl Sub for V2L {
    type Output = V2L;
    #[inline(always)]
    fn sub(self, o: V2L) -> V2L {
        V2L::new(self.x - o.x, self.y - o.y)
    }
}

impl Sub<V2> for V2L {
    type Output = V2L;
    #[inline(always)]
    fn sub(self, o: V2) -> V2L {
        V2L::new(self.x - o.x, self.y - o.y)
    }
}

impl Mul<L> for V2L {
    type Output = V2L;
    #[inline(always)]
    fn mul(self, k: L) -> V2L {
        V2L::new(self.x * k, self.y * k)
    }
}

impl Mul<f64> for V2L {
    type Output = V2L;
    #[inline(always)]
    fn mul(self, k: f64) -> V2L {
        V2L::new(self.x * k, self.y * k)
    }
}

impl Neg for V2L {
    type Output = V2L;
    #[inline(always)]
    fn neg(self) -> V2L {
        V2L::new(-self.x, -self.y)
    }
}

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
fn kernel_sin(x: L, y: L) -> L {
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
fn kernel_cos(x: L, y: L) -> L {
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
pub fn sin_cos(x: L) -> (L, L) {
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
    // The quadrant: k mod 4 in the low bits of t.
    let odd: Mask = std::array::from_fn(|i| t.0[i].to_bits() & 1 != 0);
    let neg: Mask = std::array::from_fn(|i| t.0[i].to_bits() & 2 != 0);
    let (s1, c1) = (select(odd, c, s), select(odd, -s, c));
    let (mut sn, mut cs) = (select(neg, -s1, s1), select(neg, -c1, c1));
    let out = x.abs().test(L::splat(SIN_COS_RANGE), |a, r| !(a <= r));
    if any(out) {
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
fn atan_unit(t: L) -> L {
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
    let small = t.lt(L::splat(7.0 / 16.0));
    let mid = t.lt(L::splat(11.0 / 16.0));
    let one = L::splat(1.0);
    let two_or_one = select(mid, L::splat(2.0), one);
    let num = select(small, t, two_or_one * t - 1.0);
    let den = select(small, one, t + two_or_one);
    let x = num / den;
    let z = x * x;
    let w = z * z;
    let s1 = z * (w * (w * (w * (w * (w * AT[10] + AT[8]) + AT[6]) + AT[4]) + AT[2]) + AT[0]);
    let s2 = w * (w * (w * (w * (w * AT[9] + AT[7]) + AT[5]) + AT[3]) + AT[1]);
    let hi = select(mid, L::splat(HI[0]), L::splat(HI[1]));
    let lo = select(mid, L::splat(LO[0]), L::splat(LO[1]));
    let p = x * (s1 + s2);
    select(small, x - p, hi - ((p - lo) - x))
}

/// atan2(y, x) per lane (rad, in (−π, π]), branch-free: atan of t = min(|x|, |y|) /
/// max(|x|, |y|) ≤ 1 (fdlibm's polynomial), then π/2 − z when |y| > |x|, π − z when x < 0
/// (π/2 and π in two parts), and y's sign.
///
/// Accuracy against `f64::atan2`, measured by `sin_cos_and_atan2_are_within_their_stated_ulps`
/// over 10⁶ arguments (directions all around, magnitudes 10⁻³ to 10³): at most 2 ulp. Lanes
/// where both are zero or either is not finite are computed by `f64::atan2`.
#[inline(always)]
pub fn atan2(y: L, x: L) -> L {
    const PIO2_HI: f64 = std::f64::consts::FRAC_PI_2;
    const PIO2_LO: f64 = 6.123_233_995_736_766_035_87e-17;
    const PI_HI: f64 = std::f64::consts::PI;
    const PI_LO: f64 = 1.224_646_799_147_353_177_2e-16;
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ax.lt(ay);
    let (mn, mx) = (select(steep, ax, ay), select(steep, ay, ax));
    let z = atan_unit(mn / mx);
    let west = x.lt(L::splat(0.0));
    // hi − (±z − lo): z; π/2 − z (steep); π − z (west); π/2 + z (steep and west).
    let hi = select(
        steep,
        L::splat(PIO2_HI),
        select(west, L::splat(PI_HI), L::splat(0.0)),
    );
    let lo = select(
        steep,
        L::splat(PIO2_LO),
        select(west, L::splat(PI_LO), L::splat(0.0)),
    );
    let flip: Mask = std::array::from_fn(|i| steep[i] == west[i]);
    let z = hi - (select(flip, -z, z) - lo);
    let south: Mask = std::array::from_fn(|i| y.0[i].is_sign_negative());
    let mut out = select(south, -z, z);
    let special = mx.test(L::splat(f64::INFINITY), |m, inf| !(m > 0.0 && m < inf));
    let special = or(special, (mn + y).not_finite());
    if any(special) {
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
pub fn wrap(a: L) -> L {
    use std::f64::consts::{PI, TAU};
    let r = a - ((a / L::splat(TAU) + ROUND) - ROUND) * TAU;
    let low = r.test(L::splat(-PI), |r, p| r <= p);
    let mut out = select(low, r + TAU, r);
    let far = a.abs().test(L::splat(1e9), |a, lim| !(a < lim));
    if any(far) {
        for i in 0..LANES {
            if far[i] {
                out.0[i] = crate::kernel::link_state::wrap(a.0[i]);
            }
        }
    }
    out
}
