//! The lane type: four `f64` values computed side by side ([`L`], [`V2L`]), and, by aspect:
//! - `backend`: the registers and instructions behind them ([`Backend`], [`Base`], [`Wide`]);
//! - `mask`: the lanes flagged by a test ([`Bits`] packed, [`Mask`] for the caller);
//! - `trig`: the branch-free functions the lane kernels need ([`sin_cos`], [`atan2`], [`wrap`]).
//!
//! **The backends.** An [`L`] is stored as `[f64; 4]` (the callers read and write lanes as
//! `.0[k]`) and computed by its [`Backend`], a type parameter of every lane type and
//! kernel, so that each kernel is compiled once per backend: [`Base`], the portable
//! baseline, two SSE2 registers (`__m128d`, part of the x86-64 baseline, so no run-time
//! test) with every operation one packed instruction per half, every comparison a packed
//! compare giving a [`Bits`] mask (lanes of all ones or all zeros), [`Bits::select`] an
//! and/andnot/or blend, "not finite" one packed compare of |x| against ∞, the quadrant of
//! [`sin_cos`] integer operations on the rounded multiple of π/2, and a [`Mask`] for the
//! caller one `movmskpd` per half (plain `[f64; 2]` halves with the same semantics on the
//! other architectures); and [`Wide`], the same operations on one 256-bit AVX register
//! (`__m256d`, the quadrant in AVX2 integer operations), run only inside
//! [`crate::kernel::lanes::with_simd`]'s AVX2 path. Both compute every lane with the same IEEE operations
//! in the same order, so they give the same results bit for bit.
//!
//! With [`Wide`] (callgrind, instructions per configuration, 1 024 configurations per
//! call): the four-bar `points_many` 89 (hand-written scalar code 190), `reduced_many` 128,
//! `acceleration_many` 160, the slider-crank `acceleration_many` 138; on [`Base`] 189, 270,
//! 328, 284. Before the two backends, on the 128-bit lanes VEX-encoded in the AVX2 path:
//! 173, 215, 268, 232. With the chunk's own copy of the drawing
//! ([`crate::solvers::batch::each_lanes`]) and the mask as one word ([`Mask`]): 64, 106,
//! 132, 119 on [`Wide`].
//!
//! Measured on the floor benchmark's batched four-bar and slider-crank (callgrind,
//! instructions per configuration, and the interleaved time ratio batched / hand-written
//! scalar code), against the former plain arrays left to LLVM's auto-vectoriser (whose
//! masks became scalar compares and branches, and whose arithmetic was vectorised partly,
//! often across x and y rather than across lanes, with shuffles between):
//!
//! | operation | arrays | SSE2 halves | ratio arrays → SSE2 |
//! |---|---|---|---|
//! | four-bar `points_many` | 245 | 173 (one finiteness test of the points' sum) | 1.11× → 0.70× |
//! | four-bar `reduced_many` | 300 | 215 | 0.56× → 0.395× |
//! | four-bar `acceleration_many` | (valgrind: illegal instruction) | 268 | 0.46× → 0.35× |
//! | slider-crank `acceleration_many` | 274 | 232 | 0.50× → 0.42× |
//!
//! Arithmetic as array loops (for LLVM to widen to 256-bit registers) with the packed masks
//! kept measured worse (points 207, reduced 216, four-bar acceleration 306, slider-crank
//! 271 instructions): the explicit halves it is.
//!
//! Every function here is `#[inline(always)]`, so that it is compiled with the target
//! features of the function it lands in.

// Lanes are indexed side by side in several arrays at once.
#![allow(clippy::needless_range_loop)]

use crate::kernel::link_state::V2;
use std::marker::PhantomData;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

mod backend;
mod mask;
mod trig;

pub use backend::{Backend, Base, Wide};
pub use mask::{any, or, select, Bits, Mask, ALL, NONE};
pub use trig::{atan2, sin_cos, wrap, SIN_COS_RANGE};

/// The number of configurations computed side by side.
pub const LANES: usize = 4;

/// Four `f64` values, one per configuration (a lane), in whatever unit the quantity has.
/// The arithmetic goes through the backend (module docs): the array is the storage the
/// callers read and write lane by lane, the operations load it into the backend's registers.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(transparent)]
pub struct L<B: Backend = Base>(pub [f64; LANES], PhantomData<B>);

/// The sign bit alone.
const SIGN: f64 = -0.0;

impl<B: Backend> L<B> {
    /// The lanes `a`.
    #[inline(always)]
    pub const fn new(a: [f64; LANES]) -> L<B> {
        L(a, PhantomData)
    }
    /// The lanes in the backend's registers.
    #[inline(always)]
    fn r(self) -> B::R {
        B::load(self.0)
    }
    /// From the backend's registers.
    #[inline(always)]
    fn of(r: B::R) -> L<B> {
        L(B::store(r), PhantomData)
    }
    /// `f` on the registers.
    #[inline(always)]
    fn lift(self, f: impl Fn(B::R) -> B::R) -> L<B> {
        L::of(f(self.r()))
    }
    /// `f` on the registers of `self` and `o`.
    #[inline(always)]
    fn lift2(self, o: L<B>, f: impl Fn(B::R, B::R) -> B::R) -> L<B> {
        L::of(f(self.r(), o.r()))
    }
    /// The packed comparison `f`.
    #[inline(always)]
    fn cmp(self, o: L<B>, f: impl Fn(B::R, B::R) -> B::R) -> Bits<B> {
        Bits(f(self.r(), o.r()))
    }
    /// Lane by lane, the pairs (x, y) of `x` = `self` and `y` (a point's coordinates per
    /// configuration, in the order a row of `points_many` holds them).
    #[inline(always)]
    pub fn pairs(self, y: L<B>) -> [[f64; 2]; LANES] {
        B::pairs(self.r(), y.r())
    }
    /// The same value `x` in every lane.
    #[inline(always)]
    pub const fn splat(x: f64) -> L<B> {
        L([x; LANES], PhantomData)
    }
    /// The lanes `f(0)`, …, `f(3)`.
    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> f64) -> L<B> {
        L::new(std::array::from_fn(f))
    }
    /// `f` applied to each lane (scalar code).
    #[inline(always)]
    pub fn map(self, mut f: impl FnMut(f64) -> f64) -> L<B> {
        L::new([f(self.0[0]), f(self.0[1]), f(self.0[2]), f(self.0[3])])
    }
    /// `f` applied lane by lane to `self` and `o` (scalar code).
    #[inline(always)]
    pub fn zip(self, o: L<B>, mut f: impl FnMut(f64, f64) -> f64) -> L<B> {
        L::new([
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
            f(self.0[3], o.0[3]),
        ])
    }
    /// The comparison `f` lane by lane (scalar code; the kernels use the packed
    /// comparisons [`L::less`], … instead).
    #[inline(always)]
    pub fn test(self, o: L<B>, mut f: impl FnMut(f64, f64) -> bool) -> Mask {
        Mask::from_lanes([
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
            f(self.0[3], o.0[3]),
        ])
    }
    /// √x per lane (correctly rounded, as `f64::sqrt`).
    #[inline(always)]
    pub fn sqrt(self) -> L<B> {
        self.lift(B::sqrt)
    }
    /// |x| per lane (the sign bit cleared).
    #[inline(always)]
    pub fn abs(self) -> L<B> {
        let s = B::splat(SIGN);
        self.lift(|a| B::andnot(s, a))
    }
    /// x with its sign flipped in the lanes set in `m`: `select(m, -x, x)`, one xor.
    #[inline(always)]
    pub fn flip_sign(self, m: Bits<B>) -> L<B> {
        let s = B::splat(SIGN);
        L::of(B::xor(self.r(), B::and(m.0, s)))
    }
    /// x with its sign flipped where `y`'s sign bit is set (negative, −0, negative NaNs).
    #[inline(always)]
    pub fn flip_sign_by(self, y: L<B>) -> L<B> {
        let s = B::splat(SIGN);
        self.lift2(y, |a, b| B::xor(a, B::and(b, s)))
    }
    /// The larger of the two per lane (`self` when either is a NaN: `x < y ? y : x`).
    #[inline(always)]
    pub fn max(self, o: L<B>) -> L<B> {
        o.lift2(self, B::max)
    }
    /// The smaller of the two per lane (`self` when either is a NaN: `y < x ? y : x`).
    #[inline(always)]
    pub fn min(self, o: L<B>) -> L<B> {
        o.lift2(self, B::min)
    }
    /// The lanes where x < y.
    #[inline(always)]
    pub fn lt(self, o: L<B>) -> Mask {
        self.less(o).mask()
    }
    /// The lanes where x is not finite (an infinity or a NaN).
    #[inline(always)]
    pub fn not_finite(self) -> Mask {
        self.non_finite().mask()
    }
    /// The lanes where x < y, packed.
    #[inline(always)]
    pub fn less(self, o: L<B>) -> Bits<B> {
        self.cmp(o, B::lt)
    }
    /// The lanes where x ≤ y, packed.
    #[inline(always)]
    pub fn less_eq(self, o: L<B>) -> Bits<B> {
        self.cmp(o, B::le)
    }
    /// The lanes where !(x < y) (x ≥ y or either a NaN), packed.
    #[inline(always)]
    pub fn not_less(self, o: L<B>) -> Bits<B> {
        self.cmp(o, B::nlt)
    }
    /// The lanes where !(x ≤ y) (x > y or either a NaN), packed.
    #[inline(always)]
    pub fn not_less_eq(self, o: L<B>) -> Bits<B> {
        self.cmp(o, B::nle)
    }
    /// The lanes where !(x > y) (x ≤ y or either a NaN), packed.
    #[inline(always)]
    pub fn not_greater(self, o: L<B>) -> Bits<B> {
        self.cmp(o, B::ngt)
    }
    /// The lanes where x is not finite, packed: !(|x| < ∞), one and, one compare.
    #[inline(always)]
    pub fn non_finite(self) -> Bits<B> {
        self.abs().not_less(L::splat(f64::INFINITY))
    }
}

macro_rules! binary {
    ($tr:ident, $f:ident, $hw:ident, $tra:ident, $fa:ident) => {
        impl<B: Backend> $tr for L<B> {
            type Output = L<B>;
            #[inline(always)]
            fn $f(self, o: L<B>) -> L<B> {
                self.lift2(o, B::$hw)
            }
        }
        impl<B: Backend> $tr<f64> for L<B> {
            type Output = L<B>;
            #[inline(always)]
            fn $f(self, o: f64) -> L<B> {
                let o = B::splat(o);
                self.lift(|a| B::$hw(a, o))
            }
        }
        impl<B: Backend> $tr<L<B>> for f64 {
            type Output = L<B>;
            #[inline(always)]
            fn $f(self, o: L<B>) -> L<B> {
                let s = B::splat(self);
                o.lift(|b| B::$hw(s, b))
            }
        }
        impl<B: Backend> $tra for L<B> {
            #[inline(always)]
            fn $fa(&mut self, o: L<B>) {
                *self = $tr::$f(*self, o);
            }
        }
    };
}
binary!(Add, add, add, AddAssign, add_assign);
binary!(Sub, sub, sub, SubAssign, sub_assign);
binary!(Mul, mul, mul, MulAssign, mul_assign);
binary!(Div, div, div, DivAssign, div_assign);

impl<B: Backend> Neg for L<B> {
    type Output = L<B>;
    #[inline(always)]
    fn neg(self) -> L<B> {
        let s = B::splat(SIGN);
        self.lift(|a| B::xor(a, s))
    }
}

/// A plane vector per lane (m, m/s, m/s², N): the lane twin of [`V2`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct V2L<B: Backend = Base> {
    /// x components.
    pub x: L<B>,
    /// y components.
    pub y: L<B>,
}

impl<B: Backend> V2L<B> {
    /// The vector `v` in every lane.
    #[inline(always)]
    pub fn splat(v: V2) -> V2L<B> {
        V2L {
            x: L::splat(v.x),
            y: L::splat(v.y),
        }
    }
    /// From its components.
    #[inline(always)]
    pub fn new(x: L<B>, y: L<B>) -> V2L<B> {
        V2L { x, y }
    }
    /// The vector of lane `i`.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> V2 {
        V2::new(self.x.0[i], self.y.0[i])
    }
    /// As `[x, y]`.
    #[inline(always)]
    pub fn xy(self) -> [L<B>; 2] {
        [self.x, self.y]
    }
    /// a·b.
    #[inline(always)]
    pub fn dot(self, o: V2L<B>) -> L<B> {
        self.x * o.x + self.y * o.y
    }
    /// a·b with `b` the same in every lane.
    #[inline(always)]
    pub fn dot_v(self, o: V2) -> L<B> {
        self.x * o.x + self.y * o.y
    }
    /// |a|².
    #[inline(always)]
    pub fn norm_squared(self) -> L<B> {
        self.x * self.x + self.y * self.y
    }
    /// a × b = a_x b_y − a_y b_x.
    #[inline(always)]
    pub fn cross(self, o: V2L<B>) -> L<B> {
        self.x * o.y - self.y * o.x
    }
    /// perp(a) = (−a_y, a_x).
    #[inline(always)]
    pub fn perp(self) -> V2L<B> {
        V2L {
            x: -self.y,
            y: self.x,
        }
    }
    /// `d` (the same in every lane) turned by the unit complex `self` = (cos φ, sin φ),
    /// as [`crate::kernel::link_state::rotate`].
    #[inline(always)]
    pub fn rotate(self, d: V2) -> V2L<B> {
        V2L {
            x: self.x * d.x - self.y * d.y,
            y: self.y * d.x + self.x * d.y,
        }
    }
    /// `d` turned by the unit complex `self`, both per lane.
    #[inline(always)]
    pub fn rotate_l(self, d: V2L<B>) -> V2L<B> {
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
    /// The lanes where a component is not finite, packed.
    #[inline(always)]
    pub fn non_finite(self) -> Bits<B> {
        (self.x + self.y).non_finite()
    }
}

impl<B: Backend> Add for V2L<B> {
    type Output = V2L<B>;
    #[inline(always)]
    fn add(self, o: V2L<B>) -> V2L<B> {
        V2L::new(self.x + o.x, self.y + o.y)
    }
}

impl<B: Backend> Add<V2> for V2L<B> {
    type Output = V2L<B>;
    #[inline(always)]
    fn add(self, o: V2) -> V2L<B> {
        V2L::new(self.x + o.x, self.y + o.y)
    }
}

impl<B: Backend> Sub for V2L<B> {
    type Output = V2L<B>;
    #[inline(always)]
    fn sub(self, o: V2L<B>) -> V2L<B> {
        V2L::new(self.x - o.x, self.y - o.y)
    }
}

impl<B: Backend> Sub<V2> for V2L<B> {
    type Output = V2L<B>;
    #[inline(always)]
    fn sub(self, o: V2) -> V2L<B> {
        V2L::new(self.x - o.x, self.y - o.y)
    }
}

impl<B: Backend> Mul<L<B>> for V2L<B> {
    type Output = V2L<B>;
    #[inline(always)]
    fn mul(self, k: L<B>) -> V2L<B> {
        V2L::new(self.x * k, self.y * k)
    }
}

impl<B: Backend> Mul<f64> for V2L<B> {
    type Output = V2L<B>;
    #[inline(always)]
    fn mul(self, k: f64) -> V2L<B> {
        V2L::new(self.x * k, self.y * k)
    }
}

impl<B: Backend> Neg for V2L<B> {
    type Output = V2L<B>;
    #[inline(always)]
    fn neg(self) -> V2L<B> {
        V2L::new(-self.x, -self.y)
    }
}
