//! The lanes flagged by a test: [`Bits`], packed as the backend's comparisons give them,
//! and [`Mask`], one bit per lane, as the kernels hand them to their caller.

use super::{Backend, Base, L, LANES};

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

/// A lane mask in packed form, as the backend's comparisons give it: per lane all bits set
/// (the lane is flagged) or none. [`Bits::mask`] hands it over as a [`Mask`].
#[derive(Clone, Copy)]
pub struct Bits<B: Backend = Base>(pub(super) B::R);

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

/// Per lane, `a` where `m` is set, else `b` (see [`Bits::select`] for a packed mask).
#[inline(always)]
pub fn select<B: Backend>(m: Mask, a: L<B>, b: L<B>) -> L<B> {
    Bits::from_mask(m).select(a, b)
}
