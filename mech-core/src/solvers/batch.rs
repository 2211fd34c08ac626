//! Many configurations per call (`docs/batch.md`): the runner behind every `*_many` method
//! of a generated struct and of the run-time `Mechanism`.
//!
//! Each configuration is independent. The caller's output slices are cut into rows, one per
//! configuration ([`Rows`]); a configuration that fails gets NaN in every slot of its row and
//! its index (with its error) in the returned [`BatchErrors`], the others are unaffected.
//! Below [`PARALLEL_FROM`] configurations the batch runs on the calling thread and allocates
//! nothing (unless some configuration fails); from there on, it is cut in halves recursively
//! and the halves run on rayon's pool (`RAYON_NUM_THREADS` sets its size).

use crate::kernel::lanes::{with_simd, Mask, LANES};
use crate::kernel::link_state::{LinkPose, PointPose, V2};
use crate::MechError;

/// From this many configurations on, a batch runs on rayon's pool; below, on the calling
/// thread. A chunk is never cut below [`CHUNK`] configurations.
pub const PARALLEL_FROM: usize = 4096;

/// The fewest configurations a thread is given.
pub const CHUNK: usize = 1024;

/// The configurations of a batch that failed, each with its error, in increasing index
/// order; or the reason the whole batch was refused (slices of the wrong length: then no
/// configuration was computed and every output slot is left as it was).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BatchErrors {
    indices: Vec<usize>,
    errors: Vec<MechError>,
    refused: Option<MechError>,
}

impl BatchErrors {
    /// A batch refused before any configuration was computed.
    pub fn refused(e: MechError) -> Self {
        BatchErrors {
            refused: Some(e),
            ..Self::default()
        }
    }
    /// True when every configuration was computed (no failure, no refusal).
    pub fn is_empty(&self) -> bool {
        self.indices.is_empty() && self.refused.is_none()
    }
    /// The number of failed configurations.
    pub fn len(&self) -> usize {
        self.indices.len()
    }
    /// The indices of the failed configurations, increasing.
    pub fn indices(&self) -> &[usize] {
        &self.indices
    }
    /// Each failed configuration's index and error, increasing.
    pub fn iter(&self) -> impl Iterator<Item = (usize, &MechError)> {
        self.indices.iter().copied().zip(self.errors.iter())
    }
    /// The error of configuration `i`, if it failed.
    pub fn get(&self, i: usize) -> Option<&MechError> {
        self.indices.binary_search(&i).ok().map(|k| &self.errors[k])
    }
    /// Why the whole batch was refused (mismatched slice lengths), if it was.
    pub fn refusal(&self) -> Option<&MechError> {
        self.refused.as_ref()
    }
    /// `Ok(())` when [`BatchErrors::is_empty`], else `Err(self)`: `?` in a caller that wants
    /// every configuration.
    pub fn into_result(self) -> Result<(), BatchErrors> {
        if self.is_empty() {
            Ok(())
        } else {
            Err(self)
        }
    }
    /// Record that configuration `i` failed with `e` (indices pushed in increasing order).
    pub fn push(&mut self, i: usize, e: MechError) {
        debug_assert!(self.indices.last().map_or(true, |&l| l < i));
        self.indices.push(i);
        self.errors.push(e);
    }
    /// Append the errors of a later chunk.
    fn append(&mut self, mut later: BatchErrors) {
        self.indices.append(&mut later.indices);
        self.errors.append(&mut later.errors);
    }
}

impl std::fmt::Display for BatchErrors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some(e) = &self.refused {
            return write!(f, "batch refused: {e}");
        }
        match self.iter().next() {
            None => write!(f, "every configuration solved"),
            Some((i, e)) => write!(
                f,
                "{} configuration{} failed (given NaN); the first, index {i}: {e}",
                self.len(),
                if self.len() == 1 { "" } else { "s" }
            ),
        }
    }
}

impl std::error::Error for BatchErrors {}

/// A slot that can be marked failed: NaN in every number it holds.
pub trait Nan {
    /// Write NaN in every number.
    fn set_nan(&mut self);
}

impl Nan for f64 {
    #[inline]
    fn set_nan(&mut self) {
        *self = f64::NAN;
    }
}

/// A 2-vector of NaN.
pub const NAN2: V2 = V2::new(f64::NAN, f64::NAN);

impl Nan for LinkPose {
    fn set_nan(&mut self) {
        *self = LinkPose {
            angle: f64::NAN,
            cg: NAN2,
        };
    }
}

impl Nan for PointPose {
    fn set_nan(&mut self) {
        self.pos = NAN2;
    }
}

/// Output slices cut into one row per configuration, the index of the first row kept so
/// that every row is named by its configuration's index in the whole batch.
pub trait Rows: Send + Sized {
    /// Cut after `k` rows: the first `k` rows, and the rest.
    fn split_at(self, k: usize) -> (Self, Self);
    /// Write NaN in every slot of configuration `i`'s row.
    fn fail(&mut self, i: usize);
}

/// One output slice of `width` slots per configuration.
#[derive(Debug)]
pub struct Block<'a, T> {
    data: &'a mut [T],
    width: usize,
    first: usize,
}

impl<'a, T> Block<'a, T> {
    /// `data` as `n` rows of `width` slots; `MechError::InvalidInput` naming `name` when its
    /// length is not `n × width`.
    pub fn new(name: &str, data: &'a mut [T], width: usize, n: usize) -> Result<Self, MechError> {
        match n.checked_mul(width) {
            Some(len) if len == data.len() => Ok(Block {
                data,
                width,
                first: 0,
            }),
            _ => Err(MechError::InvalidInput(format!(
                "`{name}` has {} slots for {n} configurations of {width} each: give it {} (= {n} × {width})",
                data.len(),
                n.saturating_mul(width)
            ))),
        }
    }
    /// The row of configuration `i` (its index in the whole batch).
    #[inline(always)]
    pub fn row(&mut self, i: usize) -> &mut [T] {
        let k = (i - self.first) * self.width;
        &mut self.data[k..k + self.width]
    }
    /// The first slot of configuration `i`'s row (a one-slot row).
    #[inline(always)]
    pub fn at(&mut self, i: usize) -> &mut T {
        &mut self.data[(i - self.first) * self.width]
    }
}

impl<T: Nan + Send> Rows for Block<'_, T> {
    fn split_at(self, k: usize) -> (Self, Self) {
        let (a, b) = self.data.split_at_mut(k * self.width);
        let (w, f) = (self.width, self.first);
        (
            Block {
                data: a,
                width: w,
                first: f,
            },
            Block {
                data: b,
                width: w,
                first: f + k,
            },
        )
    }
    fn fail(&mut self, i: usize) {
        self.row(i).iter_mut().for_each(T::set_nan);
    }
}

impl<A: Rows, B: Rows> Rows for (A, B) {
    fn split_at(self, k: usize) -> (Self, Self) {
        let ((a1, a2), (b1, b2)) = (self.0.split_at(k), self.1.split_at(k));
        ((a1, b1), (a2, b2))
    }
    fn fail(&mut self, i: usize) {
        self.0.fail(i);
        self.1.fail(i);
    }
}

/// `MechError::InvalidInput` unless every `(name, length)` of `inputs` is `n`.
pub fn same_len(inputs: &[(&str, usize)], n: usize) -> Result<(), MechError> {
    match inputs.iter().find(|(_, len)| *len != n) {
        None => Ok(()),
        Some((name, len)) => Err(MechError::InvalidInput(format!(
            "`{name}` has {len} configurations where `q` has {n}: give every input slice one value per configuration"
        ))),
    }
}

/// Run configurations `0..n` into `rows`: `one(i, &mut rows)` computes configuration `i` into
/// its row; an `Err` fills the row with NaN and records the index. On the calling thread
/// below [`PARALLEL_FROM`] configurations, on rayon's pool from there on.
pub fn each<R: Rows>(
    n: usize,
    rows: R,
    one: impl Fn(usize, &mut R) -> Result<(), MechError> + Sync,
) -> BatchErrors {
    each_with(n, rows, || (), |i, r, _| one(i, r))
}

/// [`each`] on the calling thread for a `one` that need not be `Sync` (a trait's default
/// method over a machine of unknown thread safety): configurations `0..n` in order.
pub fn serial<R: Rows>(
    n: usize,
    mut rows: R,
    mut one: impl FnMut(usize, &mut R) -> Result<(), MechError>,
) -> BatchErrors {
    let mut errors = BatchErrors::default();
    for i in 0..n {
        if let Err(e) = one(i, &mut rows) {
            rows.fail(i);
            errors.push(i, e);
        }
    }
    errors
}

/// [`each`] with a scratch value made by `init` once per chunk (a buffer of link states)
/// and handed to every configuration of the chunk.
pub fn each_with<R: Rows, S>(
    n: usize,
    rows: R,
    init: impl Fn() -> S + Sync,
    one: impl Fn(usize, &mut R, &mut S) -> Result<(), MechError> + Sync,
) -> BatchErrors {
    chunks(n, rows, &|range, rows: &mut R, errors: &mut BatchErrors| {
        let mut scratch = init();
        for i in range {
            if let Err(e) = one(i, rows, &mut scratch) {
                rows.fail(i);
                errors.push(i, e);
            }
        }
    })
}

/// [`each`] through a lane kernel: `four(i, &mut rows)` computes configurations `i..i + 4`
/// at once ([`crate::kernel::lanes`]), writes the rows of the lanes it does not mask and
/// returns the mask; every masked lane, and the last configurations of a chunk that do not
/// fill four lanes, go through `one(i, &mut rows)`, the one-configuration solver, whose
/// answer (a value or an error) is then the batch's. The chunk runs in
/// [`crate::kernel::lanes::with_simd`].
pub fn each_lanes<R: Rows>(
    n: usize,
    rows: R,
    four: impl Fn(usize, &mut R) -> Mask + Sync,
    one: impl Fn(usize, &mut R) -> Result<(), MechError> + Sync,
) -> BatchErrors {
    chunks(n, rows, &|range, rows: &mut R, errors: &mut BatchErrors| {
        let scalar = |i: usize, rows: &mut R, errors: &mut BatchErrors| {
            if let Err(e) = one(i, rows) {
                rows.fail(i);
                errors.push(i, e);
            }
        };
        with_simd(
            #[inline(always)]
            || {
                let mut i = range.start;
                while i + LANES <= range.end {
                    let mask = four(i, rows);
                    for (k, &masked) in mask.iter().enumerate() {
                        if masked {
                            scalar(i + k, rows, errors);
                        }
                    }
                    i += LANES;
                }
                for j in i..range.end {
                    scalar(j, rows, errors);
                }
            },
        )
    })
}

/// The configurations `range` of one chunk, computed into its rows, failures recorded.
pub type ChunkFn<'f, R> = dyn Fn(std::ops::Range<usize>, &mut R, &mut BatchErrors) + Sync + 'f;

/// Run `chunk` over `0..n` cut in chunks: the whole range on the calling thread below
/// [`PARALLEL_FROM`], halves on rayon's pool (down to [`CHUNK`]) from there on. The chunk
/// function owns the loop, so that a lane kernel can take configurations four by four.
pub fn chunks<R: Rows>(n: usize, rows: R, chunk: &ChunkFn<'_, R>) -> BatchErrors {
    let mut errors = BatchErrors::default();
    if n < PARALLEL_FROM {
        let mut rows = rows;
        chunk(0..n, &mut rows, &mut errors);
        return errors;
    }
    split(0, n, rows, chunk)
}

fn split<R: Rows>(first: usize, n: usize, rows: R, chunk: &ChunkFn<'_, R>) -> BatchErrors {
    if n <= 2 * CHUNK {
        let mut errors = BatchErrors::default();
        let mut rows = rows;
        chunk(first..first + n, &mut rows, &mut errors);
        return errors;
    }
    let half = n / 2;
    let (a, b) = rows.split_at(half);
    let (mut ea, eb) = rayon::join(
        || split(first, half, a, chunk),
        || split(first + half, n - half, b, chunk),
    );
    ea.append(eb);
    ea
}

/// A batch's answer when its slices do not fit: the refusal, nothing computed.
pub fn refuse(e: MechError) -> BatchErrors {
    BatchErrors::refused(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A failing configuration gets NaN and its index; the others their value; on one
    /// thread and on the pool (the same answer, errors in order).
    #[test]
    fn failures_are_masked_and_listed_in_order_on_any_number_of_threads() {
        for n in [
            0,
            1,
            7,
            PARALLEL_FROM - 1,
            PARALLEL_FROM,
            3 * PARALLEL_FROM + 5,
        ] {
            let mut out = vec![0.0; 2 * n];
            let rows = Block::new("out", &mut out, 2, n).unwrap();
            let errs = each(n, rows, |i, r: &mut Block<f64>| {
                if i % 97 == 3 {
                    return Err(MechError::NoAssembly);
                }
                r.row(i).copy_from_slice(&[i as f64, -(i as f64)]);
                Ok(())
            });
            let failed: Vec<usize> = (0..n).filter(|i| i % 97 == 3).collect();
            assert_eq!(errs.indices(), &failed[..], "n = {n}");
            assert_eq!(errs.len(), failed.len());
            assert_eq!(errs.is_empty(), failed.is_empty());
            for i in 0..n {
                if i % 97 == 3 {
                    assert!(out[2 * i].is_nan() && out[2 * i + 1].is_nan());
                    assert_eq!(errs.get(i), Some(&MechError::NoAssembly));
                } else {
                    assert_eq!(out[2 * i..2 * i + 2], [i as f64, -(i as f64)]);
                    assert_eq!(errs.get(i), None);
                }
            }
        }
    }

    /// Slices of the wrong length are refused with the numbers and the fix, nothing written.
    #[test]
    fn wrong_lengths_are_refused_with_the_numbers() {
        let mut out = vec![1.0; 5];
        let e = Block::new("out", &mut out, 2, 3).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid input: `out` has 5 slots for 3 configurations of 2 each: give it 6 (= 3 × 2)"
        );
        let e = same_len(&[("qd", 4)], 3).unwrap_err();
        assert!(
            e.to_string()
                .contains("`qd` has 4 configurations where `q` has 3"),
            "{e}"
        );
        let r = refuse(e);
        assert!(!r.is_empty() && r.len() == 0 && r.refusal().is_some());
        assert!(r.clone().into_result().is_err());
        assert!(BatchErrors::default().into_result().is_ok());
        // An absurd count does not overflow.
        assert!(Block::new("out", &mut out, 2, usize::MAX).is_err());
    }
}
