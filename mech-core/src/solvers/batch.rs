//! Many configurations per call (`docs/batch.md`): the runner behind every `*_many` method
//! of a generated struct and of the run-time `Mechanism`.
//!
//! Each configuration is independent. The caller's output slices are cut into rows, one per
//! configuration ([`Rows`]); a configuration that fails gets NaN in every slot of its row and
//! its index (with its error) in the returned [`BatchErrors`], the others are unaffected.
//! Below [`PARALLEL_FROM`] configurations the batch runs on the calling thread and allocates
//! nothing (unless some configuration fails); from there on, it is cut in halves recursively
//! and the halves run on rayon's pool (`RAYON_NUM_THREADS` sets its size).

use crate::kernel::lanes::{any, or, with_simd, Backend, Mask, L, LANES};
use crate::kernel::link_state::{LinkMotion, LinkPose, PointMotion, PointPose, V2};
use crate::model::{JointKind, Model};
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
    /// The rows of configurations `i..i + k`, one after the other (`k × width` slots: four
    /// rows a lane kernel writes at once).
    #[inline(always)]
    pub fn rows(&mut self, i: usize, k: usize) -> &mut [T] {
        let at = (i - self.first) * self.width;
        &mut self.data[at..at + k * self.width]
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

/// What a column function calls once per column of a [`Table`]: the column's name in two
/// parts (`"B"`, `".x"`; the name is their concatenation) and its SI unit.
pub type ColumnSink<'a> = dyn FnMut(&str, &str, &'static str) + 'a;

/// A structure-of-arrays result of many configurations: the answer of `kinematics_many`
/// and `kinetostatics_many` (`docs/batch.md#tables`). It holds `n` configurations of
/// `width` named quantities (its columns), one contiguous run per quantity: column `c`'s
/// value at configuration `i` is `values()[c·n + i]`, so [`Table::column`] is a slice of
/// `n` values. The columns are named and ordered as those of the `mech sweep` CSV
/// (`mech::columns::Columns`), without the inputs; SI units ([`Table::units`]).
///
/// Made once, with every value NaN, by the mechanism's `kinematics_table(n)` or
/// `kinetostatics_table(n)`, and reused call after call (a call writes every slot; a
/// batched call refuses a table of another mechanism, of the other kind, or of another
/// number of configurations: [`Table::resize`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    names: Vec<String>,
    units: Vec<&'static str>,
    n: usize,
    values: Vec<f64>,
}

impl Table {
    /// A table of `n` configurations with the columns `names` (their units `units`, one
    /// each), every value NaN. Panics when `names` and `units` differ in length.
    pub fn new(names: &[&str], units: &[&'static str], n: usize) -> Table {
        assert_eq!(names.len(), units.len(), "one unit per column");
        Table {
            names: names.iter().map(|s| s.to_string()).collect(),
            units: units.to_vec(),
            n,
            values: vec![f64::NAN; n * names.len()],
        }
    }
    /// A table of `n` configurations with the columns given by `columns` (a function that
    /// calls its argument once per column with the name in two parts and the unit, as
    /// [`kinematics_columns`]), every value NaN.
    pub fn with_columns(columns: impl FnOnce(&mut ColumnSink<'_>), n: usize) -> Table {
        let (mut names, mut units) = (Vec::new(), Vec::new());
        columns(&mut |a, b, u| {
            names.push(format!("{a}{b}"));
            units.push(u);
        });
        let width = names.len();
        Table {
            names,
            units,
            n,
            values: vec![f64::NAN; n * width],
        }
    }
    /// The number of configurations `n`.
    pub fn len(&self) -> usize {
        self.n
    }
    /// True when the table holds no configuration.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }
    /// The number of columns (quantities per configuration).
    pub fn width(&self) -> usize {
        self.names.len()
    }
    /// The column names, in order (`B.x`, `crank.omega`, `O2.fx`, `driver`, …).
    pub fn names(&self) -> &[String] {
        &self.names
    }
    /// The SI unit of each column (`m`, `rad/s`, `N`, `N·m`, …).
    pub fn units(&self) -> &[&'static str] {
        &self.units
    }
    /// The index of the column named `name`, if any.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|c| c == name)
    }
    /// The values of the column named `name`, one per configuration (`n` values), if any.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.index(name).map(|c| self.column_at(c))
    }
    /// The values of column `c` (its index in [`Table::names`]), one per configuration.
    pub fn column_at(&self, c: usize) -> &[f64] {
        &self.values[c * self.n..(c + 1) * self.n]
    }
    /// Column `name`'s value at configuration `i`, if the column exists and `i < n`.
    pub fn get(&self, name: &str, i: usize) -> Option<f64> {
        self.column(name).and_then(|c| c.get(i).copied())
    }
    /// Every value: the columns one after the other (`n` values each).
    pub fn values(&self) -> &[f64] {
        &self.values
    }
    /// Make room for `n` configurations (the columns kept, every value NaN); allocates
    /// only when the table grows beyond what it ever held.
    pub fn resize(&mut self, n: usize) {
        self.n = n;
        self.values.clear();
        self.values.resize(n * self.names.len(), f64::NAN);
    }
    /// The table cut into configurations for the batch runner, when it is one made for
    /// `n` configurations with the columns `columns` calls (name in two parts, unit);
    /// else the refusal, naming the lengths and the fix (`make`: the constructor to call).
    pub fn configurations(
        &mut self,
        make: &str,
        columns: impl FnOnce(&mut ColumnSink<'_>),
        n: usize,
    ) -> Result<Strided<'_>, MechError> {
        let mut k = 0;
        let mut same = true;
        columns(&mut |a, b, _| {
            same &= self.names.get(k).is_some_and(|c| {
                c.len() == a.len() + b.len() && c.starts_with(a) && c.ends_with(b)
            });
            k += 1;
        });
        if !same || k != self.names.len() {
            return Err(MechError::InvalidInput(format!(
                "`out` is not a table of this mechanism's {make} ({} columns where {k} are expected): make it with `{make}_table({n})`",
                self.names.len()
            )));
        }
        if self.n != n {
            return Err(MechError::InvalidInput(format!(
                "`out` holds {} configurations where `q` has {n}: call `out.resize({n})` or make it with `{make}_table({n})`",
                self.n
            )));
        }
        debug_assert_eq!(self.values.len(), self.n * self.names.len());
        Ok(Strided {
            ptr: self.values.as_mut_ptr(),
            stride: self.n,
            width: self.names.len(),
            first: 0,
            end: self.n,
            _values: std::marker::PhantomData,
        })
    }
}

/// A [`Table`]'s slots of the configurations `first..end`, for the batch runner ([`Rows`]):
/// column `c` of configuration `i` at `c·n + i` of the table's values. Two parts made by
/// [`Rows::split_at`] write disjoint slots (their configurations differ).
#[derive(Debug)]
pub struct Strided<'a> {
    ptr: *mut f64,
    stride: usize,
    width: usize,
    first: usize,
    end: usize,
    _values: std::marker::PhantomData<&'a mut [f64]>,
}

// SAFETY: a `Strided` is a unique borrow of the slots of its configurations (the parts of
// a split own disjoint configurations), as `&mut [f64]` is Send.
unsafe impl Send for Strided<'_> {}

impl Strided<'_> {
    /// The number of columns.
    #[inline(always)]
    pub fn width(&self) -> usize {
        self.width
    }
    /// Write `v` in column `c` of configuration `i` (its index in the whole batch).
    #[inline(always)]
    pub fn set(&mut self, i: usize, c: usize, v: f64) {
        assert!(
            i >= self.first && i < self.end && c < self.width,
            "slot out of range"
        );
        // SAFETY: i < end ≤ stride and c < width, so c·stride + i < width·stride, the
        // length of the table's values; configuration i belongs to this part alone.
        unsafe { *self.ptr.add(c * self.stride + i) = v }
    }
    /// Write configuration `i`'s row, `row[c]` in column c (`row` has one value per column).
    #[inline(always)]
    pub fn put(&mut self, i: usize, row: &[f64]) {
        assert_eq!(row.len(), self.width, "one value per column");
        for (c, &v) in row.iter().enumerate() {
            self.set(i, c, v);
        }
    }
    /// Write the four values `v` in column `c` of configurations `i..i + 4` (one run of
    /// the column: what a lane kernel computes).
    #[inline(always)]
    pub fn set4(&mut self, i: usize, c: usize, v: [f64; 4]) {
        assert!(
            i >= self.first && i + 4 <= self.end && c < self.width,
            "slot out of range"
        );
        // SAFETY: as in `set`, for the four configurations i..i + 4 of this part.
        unsafe { std::ptr::copy_nonoverlapping(v.as_ptr(), self.ptr.add(c * self.stride + i), 4) }
    }
}

impl Rows for Strided<'_> {
    fn split_at(self, k: usize) -> (Self, Self) {
        assert!(self.first + k <= self.end);
        let mid = self.first + k;
        (
            Strided {
                end: mid,
                _values: std::marker::PhantomData,
                ..self
            },
            Strided {
                first: mid,
                _values: std::marker::PhantomData,
                ..self
            },
        )
    }
    fn fail(&mut self, i: usize) {
        for c in 0..self.width {
            self.set(i, c, f64::NAN);
        }
    }
}

/// The columns of a kinematics table (`kinematics_many`), in order, each given to `col` as
/// its name in two parts and its SI unit: every point's `<point>.x`, `<point>.y` (m), every
/// moving link's `<link>.angle` (rad), every point's `<point>.vx`, `.vy` (m/s), `.ax`,
/// `.ay` (m/s²), every moving link's `<link>.omega` (rad/s), `<link>.alpha` (rad/s²):
/// the positions and rates of `mech::columns::Part::KINEMATICS`, points and links in
/// declaration order.
pub fn kinematics_columns(model: &Model, col: &mut ColumnSink<'_>) {
    for p in &model.points {
        col(&p.name, ".x", "m");
        col(&p.name, ".y", "m");
    }
    for l in &model.links[1..] {
        col(&l.name, ".angle", "rad");
    }
    for p in &model.points {
        for (s, u) in [
            (".vx", "m/s"),
            (".vy", "m/s"),
            (".ax", "m/s²"),
            (".ay", "m/s²"),
        ] {
            col(&p.name, s, u);
        }
    }
    for l in &model.links[1..] {
        col(&l.name, ".omega", "rad/s");
        col(&l.name, ".alpha", "rad/s²");
    }
}

/// The columns of a kinetostatics table (`kinetostatics_many`), in order, as
/// [`kinematics_columns`]: every joint's reaction `<joint>.fx`, `<joint>.fy` (N, by its
/// first link on its second) and, for a prismatic joint, `<joint>.moment` (N·m); then the
/// motor action of each input, `driver` (one input) or `driver.<joint>` (N·m for a
/// revolute input, N for a prismatic one): the `Reactions` and `Driver` columns of
/// `mech::columns`. None for a mechanism with redundant constraints (no reactions).
pub fn kinetostatics_columns(model: &Model, col: &mut ColumnSink<'_>) {
    if model.allow_redundant {
        return;
    }
    for j in &model.joints {
        col(&j.name, ".fx", "N");
        col(&j.name, ".fy", "N");
        if j.kind == JointKind::Prismatic {
            col(&j.name, ".moment", "N·m");
        }
    }
    let g = model.inputs.len();
    for &k in &model.inputs {
        let j = &model.joints[k];
        let unit = if j.kind == JointKind::Revolute {
            "N·m"
        } else {
            "N"
        };
        if g == 1 {
            col("driver", "", unit);
        } else {
            col("driver.", &j.name, unit);
        }
    }
}

/// The columns `names` with their `units` (one each) as a column function of
/// [`Table::configurations`]: what a generated struct's constants give.
pub fn named<'a>(
    names: &'a [&'a str],
    units: &'a [&'static str],
) -> impl FnOnce(&mut ColumnSink<'_>) + 'a {
    move |col| {
        for (n, &u) in names.iter().zip(units) {
            col(n, "", u);
        }
    }
}

/// Write one configuration's kinematics into its slots of a kinematics table, in the order
/// of [`kinematics_columns`]: `points` every point's motion (declaration order), `links`
/// every moving link's (ground excluded).
#[inline]
pub fn put_kinematics<'m>(
    r: &mut Strided<'_>,
    i: usize,
    points: impl IntoIterator<Item = &'m PointMotion> + Clone,
    links: impl IntoIterator<Item = &'m LinkMotion> + Clone,
) {
    let mut c = 0;
    let mut put = |r: &mut Strided<'_>, v: f64| {
        r.set(i, c, v);
        c += 1;
    };
    for p in points.clone() {
        put(r, p.pos.x);
        put(r, p.pos.y);
    }
    for l in links.clone() {
        put(r, l.angle);
    }
    for p in points {
        for v in [p.vel.x, p.vel.y, p.acc.x, p.acc.y] {
            put(r, v);
        }
    }
    for l in links {
        put(r, l.omega);
        put(r, l.alpha);
    }
}

/// Write four configurations' kinematics (`i..i + 4`, computed in lanes) into their slots
/// of a kinematics table, in the order of [`kinematics_columns`]: `points` every point's
/// position, velocity and acceleration (each `[x, y]`), `links` every moving link's angle,
/// ω and α. The lanes of `mask`, and those where a value is not finite (their sum is not),
/// are left for the one-configuration solver; the mask of them is returned. Where no lane
/// is masked, each column's four values are one run of the table.
#[inline(always)]
pub fn put_kinematics_lanes<B: Backend>(
    r: &mut Strided<'_>,
    i: usize,
    mask: Mask,
    points: &[[[L<B>; 2]; 3]],
    links: &[[L<B>; 3]],
) -> Mask {
    let mut sum = L::<B>::splat(0.0);
    for p in points {
        sum += ((p[0][0] + p[0][1]) + (p[1][0] + p[1][1])) + (p[2][0] + p[2][1]);
    }
    for l in links {
        sum += (l[0] + l[1]) + l[2];
    }
    let mask = or(mask, sum.not_finite());
    let all = !any(mask);
    let mut c = 0;
    let mut put = |r: &mut Strided<'_>, v: L<B>| {
        if all {
            r.set4(i, c, v.0);
        } else {
            for (k, masked) in mask.lanes().into_iter().enumerate() {
                if !masked {
                    r.set(i + k, c, v.0[k]);
                }
            }
        }
        c += 1;
    };
    for p in points {
        put(r, p[0][0]);
        put(r, p[0][1]);
    }
    for l in links {
        put(r, l[0]);
    }
    for p in points {
        for v in [p[1][0], p[1][1], p[2][0], p[2][1]] {
            put(r, v);
        }
    }
    for l in links {
        put(r, l[1]);
        put(r, l[2]);
    }
    mask
}

/// Write one configuration's kinetostatics into its slots of a kinetostatics table, in the
/// order of [`kinetostatics_columns`]: `joints` every joint's force (N) and, for a
/// prismatic joint alone, its moment (N·m), declaration order; `driver` the motor actions.
#[inline]
pub fn put_kinetostatics(
    r: &mut Strided<'_>,
    i: usize,
    joints: impl IntoIterator<Item = (V2, Option<f64>)>,
    driver: &[f64],
) {
    let mut c = 0;
    for (f, moment) in joints {
        r.set(i, c, f.x);
        r.set(i, c + 1, f.y);
        c += 2;
        if let Some(m) = moment {
            r.set(i, c, m);
            c += 1;
        }
    }
    for &d in driver {
        r.set(i, c, d);
        c += 1;
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
/// at once ([`crate::kernel::lanes`]) on the [`Base`](crate::kernel::lanes::Base) backend,
/// `wide` the same on the [`Wide`](crate::kernel::lanes::Wide) one (the kernel compiled
/// twice: one generic function called as `f::<Base>` and `f::<Wide>`); each writes the rows
/// of the lanes it does not mask and returns the mask; every masked lane, and the last
/// configurations of a chunk that do not fill four lanes, go through `one(i, &mut rows)`,
/// the one-configuration solver, whose answer (a value or an error) is then the batch's.
/// A chunk runs `wide` where the processor has AVX2 and FMA
/// ([`crate::kernel::lanes::with_simd`]), `four` otherwise.
///
/// `four` and `wide` read the mechanism from `drawing`'s copy, made once per chunk (a
/// generated struct is plain arrays of numbers: the copy is a `memcpy`, no allocation).
/// The copy is the chunk's own, so the compiler knows the rows written between two
/// blocks of four cannot change it: what the kernels compute from the drawing alone (a
/// dyad's squared lengths, the inverse of a link's squared pin distance) is worked out
/// once per chunk, not once per block. Callgrind, instructions per configuration (1 024
/// per call, AVX2): the four-bar `points_many` 81 → 72, `reduced_many` 128 → 114,
/// `acceleration_many` 160 → 138, the slider-crank `acceleration_many` 138 → 126.
pub fn each_lanes<R: Rows, C: Clone + Sync>(
    n: usize,
    rows: R,
    drawing: &C,
    four: impl Fn(&C, usize, &mut R) -> Mask + Sync,
    wide: impl Fn(&C, usize, &mut R) -> Mask + Sync,
    one: impl Fn(usize, &mut R) -> Result<(), MechError> + Sync,
) -> BatchErrors {
    chunks(n, rows, &|range, rows: &mut R, errors: &mut BatchErrors| {
        with_simd(
            (rows, errors),
            #[inline(always)]
            |(rows, errors)| lanes_chunk(range.clone(), rows, errors, drawing, &four, &one),
            #[inline(always)]
            |(rows, errors)| lanes_chunk(range.clone(), rows, errors, drawing, &wide, &one),
        )
    })
}

/// The configurations `range` four by four through `four` on a copy of `drawing`, the
/// masked lanes and the tail through `one`.
#[inline(always)]
fn lanes_chunk<R: Rows, C: Clone>(
    range: std::ops::Range<usize>,
    rows: &mut R,
    errors: &mut BatchErrors,
    drawing: &C,
    four: &impl Fn(&C, usize, &mut R) -> Mask,
    one: &impl Fn(usize, &mut R) -> Result<(), MechError>,
) {
    let drawing = drawing.clone();
    let mut scalar = |i: usize, rows: &mut R| {
        if let Err(e) = one(i, rows) {
            rows.fail(i);
            errors.push(i, e);
        }
    };
    let mut i = range.start;
    while i + LANES <= range.end {
        let mask = four(&drawing, i, rows);
        if any(mask) {
            for k in mask.set() {
                scalar(i + k, rows);
            }
        }
        i += LANES;
    }
    for j in i..range.end {
        scalar(j, rows);
    }
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
