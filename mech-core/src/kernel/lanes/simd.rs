//! The lane type: four `f64` values computed side by side, and the branch-free functions
//! the lane kernels need: [`sin_cos`], [`atan2`], [`wrap`].
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
//! [`super::with_simd`]'s AVX2 path. Both compute every lane with the same IEEE operations
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

// The polynomial and π constants are fdlibm's, digit for digit as published (each rounds
// to the double it names).
#![allow(clippy::excessive_precision)]
// Lanes are indexed side by side in several arrays at once.
#![allow(clippy::needless_range_loop)]

use crate::kernel::link_state::V2;
use std::marker::PhantomData;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// The number of configurations computed side by side.
pub const LANES: usize = 4;

/// Four `f64` values, one per configuration (a lane), in whatever unit the quantity has.
/// The arithmetic goes through the backend (module docs): the array is the storage the
/// callers read and write lane by lane, the operations load it into the backend's registers.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(transparent)]
pub struct L<B: Backend = Base>(pub [f64; LANES], PhantomData<B>);

/// The lanes that failed or may fail (set): the caller recomputes them with the scalar
/// kernels. The kernels compute their tests as [`Bits`] and hand them over as a `Mask`:
/// lane i is bit i of one word (a packed compare's `movmskpd`), so that combining two
/// masks is one `or` and "any lane" one test. `mask[k]` reads lane k.
///
/// Measured (callgrind, instructions per configuration, 1 024 per call, AVX2) against the
/// former `[bool; 4]`, whose bytes were spread from the compare's bits and gathered back
/// at each `or` and `any`: the four-bar `points_many` 72 → 64, `reduced_many` 114 → 106,
/// `acceleration_many` 138 → 132, the slider-crank `acceleration_many` 126 → 119.
#[derive(Clone, Copy, Default, PartialEq, Eq)]
pub struct Mask(u8);

impl Mask {
    /// The mask of lane i set where `lanes[i]`.
    #[inline(always)]
    pub fn from_lanes(lanes: [bool; LANES]) -> Mask {
        Mask(lanes.iter().rev().fold(0, |m, &b| (m << 1) | b as u8))
    }
    /// Each lane, set or not.
    #[inline(always)]
    pub fn lanes(self) -> [bool; LANES] {
        std::array::from_fn(|k| self.0 >> k & 1 != 0)
    }
    /// The lanes set, in order.
    #[inline(always)]
    pub fn set(self) -> impl Iterator<Item = usize> {
        (0..LANES).filter(move |&k| self.0 >> k & 1 != 0)
    }
}

impl std::ops::Index<usize> for Mask {
    type Output = bool;
    /// Whether lane `k` is set.
    #[inline(always)]
    fn index(&self, k: usize) -> &bool {
        assert!(k < LANES, "lane {k} of {LANES}");
        if self.0 >> k & 1 != 0 {
            &true
        } else {
            &false
        }
    }
}

impl std::fmt::Debug for Mask {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.lanes().fmt(f)
    }
}

/// No lane failed.
pub const NONE: Mask = Mask(0);

/// Every lane failed.
pub const ALL: Mask = Mask((1 << LANES) - 1);

/// Whether any lane of `m` is set.
#[inline(always)]
pub fn any(m: Mask) -> bool {
    m.0 != 0
}

/// The lanes set in `a` or in `b`.
#[inline(always)]
pub fn or(a: Mask, b: Mask) -> Mask {
    Mask(a.0 | b.0)
}

/// The backend on x86-64: each half of an [`L`] (two lanes) is an SSE2 register
/// (`__m128d`, in every x86-64 processor), every operation one packed instruction, every
/// comparison a packed compare whose lanes are all ones (true) or all zeros (false).
#[cfg(target_arch = "x86_64")]
mod hw {
    use core::arch::x86_64::*;

    /// An SSE2 intrinsic called where it is always available.
    macro_rules! sse2 {
        ($e:expr) => {
            // SAFETY: SSE2 is part of the x86-64 baseline, enabled in every x86-64
            // build and present in every x86-64 processor.
            unsafe { $e }
        };
    }

    /// Two lanes.
    pub type H = __m128d;

    /// The two halves of four lanes.
    #[inline(always)]
    pub fn split(a: [f64; 4]) -> [H; 2] {
        // SAFETY: [f64; 4] and [__m128d; 2] are both 32 bytes of f64 values in lane order
        // (any bit pattern is valid for both).
        unsafe { core::mem::transmute::<[f64; 4], [H; 2]>(a) }
    }
    /// Four lanes from their two halves.
    #[inline(always)]
    pub fn join(h: [H; 2]) -> [f64; 4] {
        // SAFETY: as in `split`.
        unsafe { core::mem::transmute::<[H; 2], [f64; 4]>(h) }
    }
    #[inline(always)]
    pub fn splat(x: f64) -> H {
        sse2!(_mm_set1_pd(x))
    }
    #[inline(always)]
    pub fn add(a: H, b: H) -> H {
        sse2!(_mm_add_pd(a, b))
    }
    #[inline(always)]
    pub fn sub(a: H, b: H) -> H {
        sse2!(_mm_sub_pd(a, b))
    }
    #[inline(always)]
    pub fn mul(a: H, b: H) -> H {
        sse2!(_mm_mul_pd(a, b))
    }
    #[inline(always)]
    pub fn div(a: H, b: H) -> H {
        sse2!(_mm_div_pd(a, b))
    }
    #[inline(always)]
    pub fn sqrt(a: H) -> H {
        sse2!(_mm_sqrt_pd(a))
    }
    /// a > b ? a : b (b when either is a NaN).
    #[inline(always)]
    pub fn max(a: H, b: H) -> H {
        sse2!(_mm_max_pd(a, b))
    }
    /// a < b ? a : b (b when either is a NaN).
    #[inline(always)]
    pub fn min(a: H, b: H) -> H {
        sse2!(_mm_min_pd(a, b))
    }
    #[inline(always)]
    pub fn and(a: H, b: H) -> H {
        sse2!(_mm_and_pd(a, b))
    }
    /// !a & b.
    #[inline(always)]
    pub fn andnot(a: H, b: H) -> H {
        sse2!(_mm_andnot_pd(a, b))
    }
    #[inline(always)]
    pub fn or(a: H, b: H) -> H {
        sse2!(_mm_or_pd(a, b))
    }
    #[inline(always)]
    pub fn xor(a: H, b: H) -> H {
        sse2!(_mm_xor_pd(a, b))
    }
    #[inline(always)]
    pub fn lt(a: H, b: H) -> H {
        sse2!(_mm_cmplt_pd(a, b))
    }
    #[inline(always)]
    pub fn le(a: H, b: H) -> H {
        sse2!(_mm_cmple_pd(a, b))
    }
    /// !(a < b), true when either is a NaN.
    #[inline(always)]
    pub fn nlt(a: H, b: H) -> H {
        sse2!(_mm_cmpnlt_pd(a, b))
    }
    /// !(a ≤ b).
    #[inline(always)]
    pub fn nle(a: H, b: H) -> H {
        sse2!(_mm_cmpnle_pd(a, b))
    }
    /// !(a > b).
    #[inline(always)]
    pub fn ngt(a: H, b: H) -> H {
        sse2!(_mm_cmpngt_pd(a, b))
    }
    /// The lanes' sign bits as bits 0 and 1.
    #[inline(always)]
    pub fn movemask(m: H) -> u32 {
        sse2!(_mm_movemask_pd(m)) as u32
    }
    /// A mask from two booleans.
    #[inline(always)]
    pub fn from_bools(a: bool, b: bool) -> H {
        sse2!(_mm_castsi128_pd(_mm_set_epi64x(-(b as i64), -(a as i64))))
    }
    /// For `t` = k + 1.5·2⁵² (k whole): all ones where k is odd; the sign bit where
    /// k mod 4 ∈ {2, 3} (sin's sign flip); the sign bit where k mod 4 ∈ {1, 2} (cos's).
    #[inline(always)]
    pub fn quadrant(t: H) -> (H, H, H) {
        sse2!({
            let k = _mm_castpd_si128(t);
            let odd_sign = _mm_slli_epi64(k, 63);
            // The high 32 bits of each odd lane are 0x8000_0000, the low 0: spread the sign.
            let odd = _mm_shuffle_epi32(_mm_srai_epi32(odd_sign, 31), 0b11_11_01_01);
            let two = _mm_set1_epi64x(2);
            let sin_sign = _mm_slli_epi64(_mm_and_si128(k, two), 62);
            let cos_k = _mm_add_epi64(k, _mm_set1_epi64x(1));
            let cos_sign = _mm_slli_epi64(_mm_and_si128(cos_k, two), 62);
            (
                _mm_castsi128_pd(odd),
                _mm_castsi128_pd(sin_sign),
                _mm_castsi128_pd(cos_sign),
            )
        })
    }
}

/// The portable backend: each half of an [`L`] is a plain `[f64; 2]`, masks are lanes of
/// all ones or all zeros as on x86-64.
#[cfg(not(target_arch = "x86_64"))]
mod hw {
    /// Two lanes.
    pub type H = [f64; 2];

    #[inline(always)]
    fn map2(a: H, b: H, f: impl Fn(f64, f64) -> f64) -> H {
        [f(a[0], b[0]), f(a[1], b[1])]
    }
    #[inline(always)]
    fn bits2(a: H, b: H, f: impl Fn(u64, u64) -> u64) -> H {
        map2(a, b, |x, y| f64::from_bits(f(x.to_bits(), y.to_bits())))
    }
    #[inline(always)]
    fn test2(a: H, b: H, f: impl Fn(f64, f64) -> bool) -> H {
        map2(a, b, |x, y| f64::from_bits(if f(x, y) { !0 } else { 0 }))
    }
    #[inline(always)]
    pub fn split(a: [f64; 4]) -> [H; 2] {
        [[a[0], a[1]], [a[2], a[3]]]
    }
    #[inline(always)]
    pub fn join(h: [H; 2]) -> [f64; 4] {
        [h[0][0], h[0][1], h[1][0], h[1][1]]
    }
    #[inline(always)]
    pub fn splat(x: f64) -> H {
        [x, x]
    }
    #[inline(always)]
    pub fn add(a: H, b: H) -> H {
        map2(a, b, |x, y| x + y)
    }
    #[inline(always)]
    pub fn sub(a: H, b: H) -> H {
        map2(a, b, |x, y| x - y)
    }
    #[inline(always)]
    pub fn mul(a: H, b: H) -> H {
        map2(a, b, |x, y| x * y)
    }
    #[inline(always)]
    pub fn div(a: H, b: H) -> H {
        map2(a, b, |x, y| x / y)
    }
    #[inline(always)]
    pub fn sqrt(a: H) -> H {
        [a[0].sqrt(), a[1].sqrt()]
    }
    #[inline(always)]
    pub fn max(a: H, b: H) -> H {
        map2(a, b, |x, y| if x > y { x } else { y })
    }
    #[inline(always)]
    pub fn min(a: H, b: H) -> H {
        map2(a, b, |x, y| if x < y { x } else { y })
    }
    #[inline(always)]
    pub fn and(a: H, b: H) -> H {
        bits2(a, b, |x, y| x & y)
    }
    #[inline(always)]
    pub fn andnot(a: H, b: H) -> H {
        bits2(a, b, |x, y| !x & y)
    }
    #[inline(always)]
    pub fn or(a: H, b: H) -> H {
        bits2(a, b, |x, y| x | y)
    }
    #[inline(always)]
    pub fn xor(a: H, b: H) -> H {
        bits2(a, b, |x, y| x ^ y)
    }
    #[inline(always)]
    pub fn lt(a: H, b: H) -> H {
        test2(a, b, |x, y| x < y)
    }
    #[inline(always)]
    pub fn le(a: H, b: H) -> H {
        test2(a, b, |x, y| x <= y)
    }
    #[inline(always)]
    pub fn nlt(a: H, b: H) -> H {
        test2(a, b, |x, y| !(x < y))
    }
    #[inline(always)]
    pub fn nle(a: H, b: H) -> H {
        test2(a, b, |x, y| !(x <= y))
    }
    #[inline(always)]
    pub fn ngt(a: H, b: H) -> H {
        test2(a, b, |x, y| !(x > y))
    }
    #[inline(always)]
    pub fn movemask(m: H) -> u32 {
        (m[0].to_bits() >> 63) as u32 | ((m[1].to_bits() >> 63) as u32) << 1
    }
    #[inline(always)]
    pub fn from_bools(a: bool, b: bool) -> H {
        let m = |x: bool| f64::from_bits(if x { !0 } else { 0 });
        [m(a), m(b)]
    }
    #[inline(always)]
    pub fn quadrant(t: H) -> (H, H, H) {
        let f = |g: fn(u64) -> u64| {
            [
                f64::from_bits(g(t[0].to_bits())),
                f64::from_bits(g(t[1].to_bits())),
            ]
        };
        (
            f(|k| if k & 1 != 0 { !0 } else { 0 }),
            f(|k| (k & 2) << 62),
            f(|k| (k.wrapping_add(1) & 2) << 62),
        )
    }
}

/// The operations of a lane backend on `R`, the register(s) holding the four lanes: the
/// arithmetic the kernels use, packed comparisons giving lanes of all ones (true) or all
/// zeros, and the bit operations of the masks. Two implementations: [`Base`] (two 128-bit
/// SSE2 registers on x86-64, plain arrays elsewhere) and [`Wide`] (one 256-bit AVX
/// register). Every kernel is generic over its backend, so each is compiled once per
/// backend; [`super::with_simd`] runs the [`Wide`] instance where the processor has AVX2
/// and FMA, the [`Base`] one otherwise.
///
/// Both backends compute every lane with the same IEEE operations in the same order (no
/// FMA contraction), so they give the same results bit for bit.
pub trait Backend: Copy + Default + std::fmt::Debug + PartialEq + Send + Sync + 'static {
    /// The four lanes in registers.
    type R: Copy;
    /// The lanes `a` in registers.
    fn load(a: [f64; 4]) -> Self::R;
    /// The lanes of `r`.
    fn store(r: Self::R) -> [f64; 4];
    /// `x` in every lane.
    fn splat(x: f64) -> Self::R;
    /// a + b.
    fn add(a: Self::R, b: Self::R) -> Self::R;
    /// a − b.
    fn sub(a: Self::R, b: Self::R) -> Self::R;
    /// a · b.
    fn mul(a: Self::R, b: Self::R) -> Self::R;
    /// a / b.
    fn div(a: Self::R, b: Self::R) -> Self::R;
    /// √a, correctly rounded.
    fn sqrt(a: Self::R) -> Self::R;
    /// a > b ? a : b (b when either is a NaN).
    fn max(a: Self::R, b: Self::R) -> Self::R;
    /// a < b ? a : b (b when either is a NaN).
    fn min(a: Self::R, b: Self::R) -> Self::R;
    /// a & b (bits).
    fn and(a: Self::R, b: Self::R) -> Self::R;
    /// !a & b (bits).
    fn andnot(a: Self::R, b: Self::R) -> Self::R;
    /// a | b (bits).
    fn or(a: Self::R, b: Self::R) -> Self::R;
    /// a ^ b (bits).
    fn xor(a: Self::R, b: Self::R) -> Self::R;
    /// a < b.
    fn lt(a: Self::R, b: Self::R) -> Self::R;
    /// a ≤ b.
    fn le(a: Self::R, b: Self::R) -> Self::R;
    /// !(a < b).
    fn nlt(a: Self::R, b: Self::R) -> Self::R;
    /// !(a ≤ b).
    fn nle(a: Self::R, b: Self::R) -> Self::R;
    /// !(a > b).
    fn ngt(a: Self::R, b: Self::R) -> Self::R;
    /// Lane i's sign bit as bit i.
    fn movemask(m: Self::R) -> u32;
    /// A mask from four booleans.
    fn from_bools(m: [bool; 4]) -> Self::R;
    /// For `t` = k + 1.5·2⁵² (k whole): all ones where k is odd; the sign bit where
    /// k mod 4 ∈ {2, 3}; the sign bit where k mod 4 ∈ {1, 2} (the quadrant of [`sin_cos`]).
    fn quadrant(t: Self::R) -> (Self::R, Self::R, Self::R);
    /// Lane by lane, the pairs (x, y): the rows of a structure of arrays (x, y) turned
    /// into an array of structures.
    #[inline(always)]
    fn pairs(x: Self::R, y: Self::R) -> [[f64; 2]; 4] {
        let (x, y) = (Self::store(x), Self::store(y));
        [[x[0], y[0]], [x[1], y[1]], [x[2], y[2]], [x[3], y[3]]]
    }
}

/// The portable backend: two SSE2 registers (`__m128d`) on x86-64, part of its baseline;
/// two `[f64; 2]` arrays elsewhere. Every operation one packed instruction per half.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Base;

/// Each half through `hw`.
macro_rules! halves {
    ($($f:ident),*) => {$(
        #[inline(always)]
        fn $f(a: Self::R, b: Self::R) -> Self::R {
            [hw::$f(a[0], b[0]), hw::$f(a[1], b[1])]
        }
    )*};
}

impl Backend for Base {
    type R = [hw::H; 2];
    #[inline(always)]
    fn load(a: [f64; 4]) -> Self::R {
        hw::split(a)
    }
    #[inline(always)]
    fn store(r: Self::R) -> [f64; 4] {
        hw::join(r)
    }
    #[inline(always)]
    fn splat(x: f64) -> Self::R {
        let h = hw::splat(x);
        [h, h]
    }
    halves!(add, sub, mul, div, max, min, and, andnot, or, xor, lt, le, nlt, nle, ngt);
    #[inline(always)]
    fn sqrt(a: Self::R) -> Self::R {
        [hw::sqrt(a[0]), hw::sqrt(a[1])]
    }
    #[inline(always)]
    fn movemask(m: Self::R) -> u32 {
        hw::movemask(m[0]) | hw::movemask(m[1]) << 2
    }
    #[inline(always)]
    fn from_bools(m: [bool; 4]) -> Self::R {
        [hw::from_bools(m[0], m[1]), hw::from_bools(m[2], m[3])]
    }
    #[inline(always)]
    fn quadrant(t: Self::R) -> (Self::R, Self::R, Self::R) {
        let ((o0, s0, c0), (o1, s1, c1)) = (hw::quadrant(t[0]), hw::quadrant(t[1]));
        ([o0, o1], [s0, s1], [c0, c1])
    }
}

/// The 256-bit backend on x86-64: the four lanes in one AVX register (`__m256d`), every
/// operation one instruction, the quadrant's integer operations AVX2. Its operations are
/// compiled into the functions of [`super::with_simd`]'s AVX2 path and must run only
/// there, on a processor with AVX2 and FMA ([`super::simd_allowed`]): executing them on a
/// processor without AVX is undefined behaviour (an illegal instruction), so a caller
/// instantiates a kernel with `Wide` only in the `wide` closure of [`super::with_simd`].
/// On the other architectures it is [`Base`].
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wide;

/// The 256-bit backend is the portable one outside x86-64.
#[cfg(not(target_arch = "x86_64"))]
pub type Wide = Base;

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{Backend, Wide};
    use core::arch::x86_64::*;

    /// An AVX or AVX2 intrinsic of [`Wide`].
    macro_rules! avx {
        ($e:expr) => {
            // SAFETY: `Wide` runs only in `with_simd`'s AVX2 path, on a processor with AVX2
            // and FMA (detected at run time before any `Wide` kernel is called).
            unsafe { $e }
        };
    }
    macro_rules! op {
        ($($f:ident => $i:ident),*) => {$(
            #[inline(always)]
            fn $f(a: __m256d, b: __m256d) -> __m256d {
                avx!($i(a, b))
            }
        )*};
    }
    macro_rules! cmp {
        ($($f:ident => $c:ident),*) => {$(
            #[inline(always)]
            fn $f(a: __m256d, b: __m256d) -> __m256d {
                avx!(_mm256_cmp_pd::<$c>(a, b))
            }
        )*};
    }

    impl Backend for Wide {
        type R = __m256d;
        #[inline(always)]
        fn load(a: [f64; 4]) -> __m256d {
            // SAFETY: [f64; 4] and __m256d are both 32 bytes of f64 values in lane order.
            unsafe { core::mem::transmute::<[f64; 4], __m256d>(a) }
        }
        #[inline(always)]
        fn store(r: __m256d) -> [f64; 4] {
            // SAFETY: as in `load`.
            unsafe { core::mem::transmute::<__m256d, [f64; 4]>(r) }
        }
        #[inline(always)]
        fn splat(x: f64) -> __m256d {
            avx!(_mm256_set1_pd(x))
        }
        op!(add => _mm256_add_pd, sub => _mm256_sub_pd, mul => _mm256_mul_pd,
            div => _mm256_div_pd, max => _mm256_max_pd, min => _mm256_min_pd,
            and => _mm256_and_pd, andnot => _mm256_andnot_pd, or => _mm256_or_pd,
            xor => _mm256_xor_pd);
        cmp!(lt => _CMP_LT_OS, le => _CMP_LE_OS, nlt => _CMP_NLT_US, nle => _CMP_NLE_US,
            ngt => _CMP_NGT_US);
        #[inline(always)]
        fn sqrt(a: __m256d) -> __m256d {
            avx!(_mm256_sqrt_pd(a))
        }
        #[inline(always)]
        fn movemask(m: __m256d) -> u32 {
            avx!(_mm256_movemask_pd(m)) as u32
        }
        #[inline(always)]
        fn from_bools(m: [bool; 4]) -> __m256d {
            let b = |x: bool| -(x as i64);
            avx!(_mm256_castsi256_pd(_mm256_set_epi64x(
                b(m[3]),
                b(m[2]),
                b(m[1]),
                b(m[0])
            )))
        }
        #[inline(always)]
        fn quadrant(t: __m256d) -> (__m256d, __m256d, __m256d) {
            avx!({
                let k = _mm256_castpd_si256(t);
                let one = _mm256_set1_epi64x(1);
                let two = _mm256_set1_epi64x(2);
                // 0 − (k & 1): all ones where k is odd.
                let odd = _mm256_sub_epi64(_mm256_setzero_si256(), _mm256_and_si256(k, one));
                let sin_sign = _mm256_slli_epi64::<62>(_mm256_and_si256(k, two));
                let cos_k = _mm256_add_epi64(k, one);
                let cos_sign = _mm256_slli_epi64::<62>(_mm256_and_si256(cos_k, two));
                (
                    _mm256_castsi256_pd(odd),
                    _mm256_castsi256_pd(sin_sign),
                    _mm256_castsi256_pd(cos_sign),
                )
            })
        }
        /// Two unpacks: (x₀ y₀ x₂ y₂) and (x₁ y₁ x₃ y₃), each pair a 128-bit half.
        #[inline(always)]
        fn pairs(x: __m256d, y: __m256d) -> [[f64; 2]; 4] {
            let (lo, hi) = avx!((_mm256_unpacklo_pd(x, y), _mm256_unpackhi_pd(x, y)));
            // SAFETY: two __m256d are 64 bytes of f64 values, as [[f64; 2]; 4].
            let [a, b, c, d] =
                unsafe { core::mem::transmute::<[__m256d; 2], [[f64; 2]; 4]>([lo, hi]) };
            [a, c, b, d]
        }
    }
}

/// The sign bit alone.
const SIGN: f64 = -0.0;

/// A lane mask in packed form, as the backend's comparisons give it: per lane all bits set
/// (the lane is flagged) or none. [`Bits::mask`] hands it over as a [`Mask`].
#[derive(Clone, Copy)]
pub struct Bits<B: Backend = Base>(B::R);

impl<B: Backend> Bits<B> {
    /// The lanes set in `self` or in `o`.
    #[inline(always)]
    pub fn or(self, o: Bits<B>) -> Bits<B> {
        Bits(B::or(self.0, o.0))
    }
    /// Lane i's flag as bit i.
    #[inline(always)]
    pub fn bits(self) -> u32 {
        B::movemask(self.0)
    }
    /// Whether any lane is set.
    #[inline(always)]
    pub fn any(self) -> bool {
        self.bits() != 0
    }
    /// As a [`Mask`] (lane i bit i, as the compare's sign bits).
    #[inline(always)]
    pub fn mask(self) -> Mask {
        Mask(self.bits() as u8)
    }
    /// From a [`Mask`].
    #[inline(always)]
    pub fn from_mask(m: Mask) -> Bits<B> {
        Bits(B::from_bools(m.lanes()))
    }
    /// Per lane, `a` where set, else `b`: (m ∧ a) ∨ (¬m ∧ b), no branch.
    #[inline(always)]
    pub fn select(self, a: L<B>, b: L<B>) -> L<B> {
        L::of(B::or(B::and(self.0, a.r()), B::andnot(self.0, b.r())))
    }
}

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

/// Per lane, `a` where `m` is set, else `b` (see [`Bits::select`] for a packed mask).
#[inline(always)]
pub fn select<B: Backend>(m: Mask, a: L<B>, b: L<B>) -> L<B> {
    Bits::from_mask(m).select(a, b)
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
