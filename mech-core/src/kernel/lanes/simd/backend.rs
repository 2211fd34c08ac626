//! The registers and instructions behind a lane: the [`Backend`] trait, [`Base`] (two
//! SSE2 registers on x86-64, plain arrays elsewhere) and [`Wide`] (one AVX register).

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
/// backend; [`crate::kernel::lanes::with_simd`] runs the [`Wide`] instance where the processor has AVX2
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
    /// k mod 4 ∈ {2, 3}; the sign bit where k mod 4 ∈ {1, 2} (the quadrant of [`sin_cos`](super::sin_cos)).
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
/// compiled into the functions of [`crate::kernel::lanes::with_simd`]'s AVX2 path and must run only
/// there, on a processor with AVX2 and FMA ([`crate::kernel::lanes::simd_allowed`]): executing them on a
/// processor without AVX is undefined behaviour (an illegal instruction), so a caller
/// instantiates a kernel with `Wide` only in the `wide` closure of [`crate::kernel::lanes::with_simd`].
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
