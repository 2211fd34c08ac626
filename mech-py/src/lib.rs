//! The native half of the Python package `mech` (`docs/python.md`): the run-time
//! [`mech_core::Mechanism`] behind a small class whose solvers take 2-D float arrays of
//! inputs and return 2-D arrays of the columns of `mech_core::runtime::columns`, the loop in Rust
//! with the GIL released and rayon inside. The Python layer (`python/mech/__init__.py`)
//! turns scalars, lists and callables into those arrays and the arrays into dicts.

use mech_core::dynamics::flywheel::Cycle;
use mech_core::dynamics::motor::Motor;
use mech_core::dynamics::regime::{Drive, Run, Steady};
use mech_core::model::{JointKind, Load};
use mech_core::runtime::columns::{Columns, Part};
use mech_core::runtime::mechanism::Loads;
use mech_core::solvers::batch::{each, Block};
use mech_core::solvers::traits::OneDof;
use mech_core::{MechError as CoreError, Mechanism};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::GILOnceCell;
use pyo3::types::{PyDict, PyTuple, PyType};
use rayon::prelude::*;
use std::sync::OnceLock;

mod spatial;

create_exception!(
    _mech,
    MechError,
    PyException,
    "An error of mech: the message says what is wrong, the numbers and the fix."
);
create_exception!(
    _mech,
    InvalidMechanism,
    MechError,
    "The description fails a check; `line` and `column` (1-based) locate the culprit."
);
create_exception!(
    _mech,
    NoAssembly,
    MechError,
    "The mechanism cannot be assembled at this input value."
);
create_exception!(
    _mech,
    Singular,
    MechError,
    "A dead point: the system is not solvable to the requested accuracy."
);

/// `mech.InvalidInput`: a bad number (NaN, infinite, out of range), the wrong shape, or a
/// size beyond the package's limits. Both a `mech.MechError` and a `ValueError`, so that
/// `except ValueError` catches it as it catches numpy's own; built with `type()` since a
/// pyo3 exception has one base.
fn invalid_input_type(py: Python<'_>) -> &Bound<'_, PyType> {
    static TYPE: GILOnceCell<Py<PyType>> = GILOnceCell::new();
    TYPE.get_or_init(py, || {
        let bases = PyTuple::new(
            py,
            [py.get_type::<MechError>(), py.get_type::<PyValueError>()],
        )
        .expect("a tuple");
        let dict = PyDict::new(py);
        dict.set_item("__module__", "mech._mech").expect("a dict");
        dict.set_item(
            "__doc__",
            "A bad number (NaN, infinite, out of range), the wrong shape, or a size beyond \
             the limits: a mech.MechError and a ValueError.",
        )
        .expect("a dict");
        py.get_type::<PyType>()
            .call1(("InvalidInput", bases, dict))
            .and_then(|t| Ok(t.downcast_into::<PyType>()?))
            .expect("the type InvalidInput")
            .unbind()
    })
    .bind(py)
}

/// A `mech.InvalidInput` with `message`.
fn invalid(message: impl Into<String>) -> PyErr {
    let message = message.into();
    Python::with_gil(|py| PyErr::from_type(invalid_input_type(py).clone(), message))
}

/// The most values (f64) one call returns: 2²⁸, 2 GiB. A larger batch is refused before
/// anything is allocated (it would end the process when memory runs out): split it.
const MAX_VALUES: usize = 1 << 28;

/// The longest cycle of `flywheel`, rad (1000 turns).
const MAX_PERIOD: f64 = 2000.0 * std::f64::consts::PI;

/// The most points of a cam profile.
const MAX_POINTS: usize = 1_000_000;

/// Refuse a text too large, binary or nested too deep for the parser (`origin` names it):
/// the loader's rule, `mech_core::checks::load::check_text`, as an `InvalidInput`.
fn check_text(text: &str, origin: &str) -> PyResult<()> {
    mech_core::checks::load::check_text(text, Some(origin)).map_err(|e| match e {
        CoreError::Invalid(m) => invalid(m),
        other => invalid(other.to_string()),
    })
}

/// Refuse an output of `rows` × `width` values beyond [`MAX_VALUES`].
fn check_size(rows: usize, width: usize, what: &str) -> PyResult<()> {
    let n = rows.saturating_mul(width.max(1));
    if n > MAX_VALUES {
        return Err(invalid(format!(
            "{what}: {rows} rows × {width} columns = {n} values ({:.1} GB), more than the limit of {MAX_VALUES} (2 GB); split the batch into chunks (docs/scale-out.md) or ask for fewer parts",
            n as f64 * 8.0 / 1e9
        )));
    }
    Ok(())
}

/// The first error a Python callable raised during a native computation: re-raised as it
/// is once the computation stops, not turned into a NaN.
type Raised = std::cell::RefCell<Option<PyErr>>;

/// The Python exception of a mech error. A check's message starts `[FILE:]LINE:COLUMN:`:
/// the exception carries `line`, `column` and `message`.
fn py_err(py: Python<'_>, e: CoreError) -> PyErr {
    match e {
        CoreError::Invalid(text) => {
            let err = InvalidMechanism::new_err(text.clone());
            let head = text.lines().next().unwrap_or("");
            let mut parts = head.split_once(": ").map_or("", |(at, _)| at).rsplit(':');
            let (col, line) = (
                parts.next().and_then(|c| c.parse::<usize>().ok()),
                parts.next().and_then(|l| l.parse::<usize>().ok()),
            );
            let v = err.value(py);
            let _ = v.setattr("line", line);
            let _ = v.setattr("column", col);
            let _ = v.setattr("message", text);
            err
        }
        CoreError::NoAssembly => NoAssembly::new_err(e.to_string()),
        CoreError::Singular { .. } => Singular::new_err(e.to_string()),
        CoreError::InvalidInput(_) => invalid(e.to_string()),
        other => MechError::new_err(other.to_string()),
    }
}

/// The rayon pool of the package: `MECH_NUM_THREADS` threads (default: rayon's choice,
/// the number of cores), so that a Dask or Ray worker does not oversubscribe its cores.
/// A sweep's per-variant (data n × C, ok n) stacked into (V, n, C) and (V, n) arrays.
pub(crate) fn stack_variants<'py>(
    py: Python<'py>,
    results: Vec<(Vec<f64>, Vec<bool>)>,
    n: usize,
    width: usize,
) -> (Bound<'py, PyArray3<f64>>, Bound<'py, numpy::PyArray2<bool>>) {
    let nv = results.len();
    let mut data = Vec::with_capacity(nv * n * width);
    let mut ok = Vec::with_capacity(nv * n);
    for (d, o) in results {
        data.extend(d);
        ok.extend(o);
    }
    let data = numpy::ndarray::Array3::from_shape_vec((nv, n, width), data)
        .expect("V × n × C values")
        .into_pyarray(py);
    let ok = numpy::ndarray::Array2::from_shape_vec((nv, n), ok)
        .expect("V × n values")
        .into_pyarray(py);
    (data, ok)
}

fn pool() -> &'static rayon::ThreadPool {
    static POOL: OnceLock<rayon::ThreadPool> = OnceLock::new();
    POOL.get_or_init(|| {
        let n = std::env::var("MECH_NUM_THREADS")
            .ok()
            .and_then(|s| s.parse::<usize>().ok())
            .unwrap_or(0);
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .expect("a thread pool")
    })
}

/// The number of threads the solvers use.
#[pyfunction]
fn num_threads() -> usize {
    pool().current_num_threads()
}

fn parts_of(names: &[String]) -> PyResult<Vec<Part>> {
    names
        .iter()
        .map(|n| match n.as_str() {
            "inputs" => Ok(Part::Inputs),
            "positions" => Ok(Part::Positions),
            "points" => Ok(Part::Points),
            "rates" => Ok(Part::Rates),
            "reactions" => Ok(Part::Reactions),
            "driver" => Ok(Part::Driver),
            "virtual_power" => Ok(Part::VirtualPower),
            "zhukovski" => Ok(Part::Zhukovski),
            "shaking" => Ok(Part::Shaking),
            other => Err(invalid(format!(
                "unknown part `{other}`: the parts are inputs, positions, points, rates, reactions, driver, virtual_power, zhukovski, shaking"
            ))),
        })
        .collect()
}

/// The loads of one row: the flat values (force: 2, torque: 1, in declaration order).
/// Keep the first exception a Python callable raised, to re-raise it as it is.
fn keep_first(raised: &Raised, e: PyErr) {
    let mut r = raised.borrow_mut();
    if r.is_none() {
        *r = Some(e);
    }
}

/// The loads at q from a Python callable of q returning the flat loads; its exception is
/// kept in `raised` and becomes an `InvalidInput` naming q.
fn loads_callable<'a>(
    py: Python<'a>,
    m: &'a Mechanism,
    loads: &'a PyObject,
    raised: &'a Raised,
) -> impl Fn(f64) -> Result<Loads, CoreError> + 'a {
    move |q: f64| {
        let flat: Vec<f64> = loads
            .call1(py, (q,))
            .and_then(|v| v.extract(py))
            .map_err(|e| {
                let text = format!("the loads callable at q = {q}: {e}");
                keep_first(raised, e);
                CoreError::InvalidInput(text)
            })?;
        Ok(loads_of(m, &flat))
    }
}

/// The motor written `text` (`mech_core::dynamics::motor`), its `table(..)` given as the
/// (speeds, torques) the Python layer read, through `ratio`.
fn motor_of(
    text: &str,
    table: Option<(Vec<f64>, Vec<f64>)>,
    ratio: f64,
) -> Result<Motor, CoreError> {
    let read = |_: &str| match &table {
        Some((speed, torque)) => Motor::table(speed.clone(), torque.clone()),
        None => Err(CoreError::InvalidInput(
            "a table motor needs its speeds and torques".into(),
        )),
    };
    Motor::parse(text, &read)?.through(ratio)
}

/// The numbers of a flywheel sizing (`Mechanism.flywheel` in Python).
pub(crate) struct CycleArgs<'a> {
    pub start: f64,
    pub period: f64,
    pub breakpoints: &'a [f64],
    pub omega_mean: f64,
    pub irregularity: f64,
    pub rtol: f64,
}

/// The flywheel of a one-input machine (planar or spatial) over one cycle: the loads at
/// q from `loads`, the driver a callable of q (`None`: the constant torque that balances
/// the cycle); the names and values `Mechanism.flywheel` returns. The first exception a
/// callable raised is re-raised as it is.
pub(crate) fn flywheel_of<M: OneDof>(
    py: Python<'_>,
    m: &M,
    c: &CycleArgs,
    loads: impl Fn(f64) -> Result<M::Loads, CoreError>,
    driver: Option<&PyObject>,
    raised: &Raised,
) -> PyResult<Vec<(String, f64)>> {
    let (period, start) = (c.period, c.start);
    if period.is_finite() && period > MAX_PERIOD {
        return Err(invalid(format!(
            "period = {period:e} rad: {:.3e} turns, more than the limit of {:.0} turns; a cycle is the shortest span after which the loads repeat",
            period / std::f64::consts::TAU,
            MAX_PERIOD / std::f64::consts::TAU
        )));
    }
    if start.is_finite() && period > 0.0 && start.abs() * f64::EPSILON > 1e-9 * period {
        return Err(invalid(format!(
            "start = {start:e} rad: so large beside the period that the cycle's angles lose their precision; give a start within a few periods of 0"
        )));
    }
    let keep = |e: PyErr| keep_first(raised, e);
    let balance = driver.is_none();
    let call_driver = |q: f64| -> f64 {
        driver.map_or(0.0, |d| {
            d.call1(py, (q,))
                .and_then(|v| v.extract::<f64>(py))
                .unwrap_or_else(|e| {
                    keep(e);
                    f64::NAN
                })
        })
    };
    let run = || -> Result<Vec<(String, f64)>, CoreError> {
        let cycle = Cycle::new(m, start, period, c.breakpoints, loads, call_driver)?;
        let net = cycle.net_work();
        let (cycle, torque) = if balance {
            cycle.balanced()
        } else {
            (cycle, 0.0)
        };
        cycle.check_periodic()?;
        let fw = cycle.flywheel(c.omega_mean, c.irregularity)?;
        let sim = cycle.simulate(&fw.exact.state, c.rtol)?;
        let a = fw.approximate;
        Ok([
            ("net_work", net),
            ("balancing_torque", torque),
            ("s_max", a.s_max),
            ("q_s_max", a.q_s_max),
            ("s_min", a.s_min),
            ("q_s_min", a.q_s_min),
            ("fluctuation", a.s_max - a.s_min),
            ("inertia_approximate", a.inertia),
            ("inertia_exact", fw.exact.inertia),
            ("omega_max", sim.speeds.omega_max),
            ("omega_min", sim.speeds.omega_min),
            ("irregularity_simulated", sim.speeds.irregularity),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect())
    };
    let out = run();
    if let Some(e) = raised.borrow_mut().take() {
        return Err(e);
    }
    out.map_err(|e| py_err(py, e))
}

fn loads_of(m: &Mechanism, flat: &[f64]) -> Loads {
    let mut loads = m.loads();
    set_loads(m, &mut loads, flat);
    loads
}

/// Set `loads` from the flat values of one row (no allocation).
fn set_loads(m: &Mechanism, loads: &mut Loads, flat: &[f64]) {
    let mut at = 0;
    for l in m.model().loads.iter() {
        let w = if matches!(l, Load::Force { .. }) {
            2
        } else {
            1
        };
        if at + w <= flat.len() {
            loads.set_by_name(l.name(), &flat[at..at + w]);
        }
        at += w;
    }
}

/// The elements of a 2-D array in row-major order: borrowed when it is laid out so,
/// else copied.
fn row_major<'a>(a: &'a numpy::ndarray::ArrayView2<'a, f64>) -> std::borrow::Cow<'a, [f64]> {
    match a.as_slice() {
        Some(s) => std::borrow::Cow::Borrowed(s),
        None => std::borrow::Cow::Owned(a.iter().copied().collect()),
    }
}

/// The number of flat load values per row (force: 2, torque: 1, in declaration order).
fn load_width(m: &Mechanism) -> usize {
    m.model()
        .loads
        .iter()
        .map(|l| {
            if matches!(l, Load::Force { .. }) {
                2
            } else {
                1
            }
        })
        .sum()
}

/// The shapes of a batch: q (n, G), q̇ and q̈ the same, the flat loads (n, L). A mismatch
/// is an `InvalidInput`, never a slice out of bounds.
fn check_shapes(
    m: &Mechanism,
    q: &[usize],
    qd: &[usize],
    qdd: &[usize],
    loads: &[usize],
) -> PyResult<()> {
    let (g, l) = (m.dof(), load_width(m));
    if q[1] != g {
        return Err(invalid(format!(
            "inputs of shape {q:?} for {g} input(s): give (n, {g}), one row per configuration"
        )));
    }
    for (name, s) in [("qd", qd), ("qdd", qdd)] {
        if s != q {
            return Err(invalid(format!(
                "{name} of shape {s:?} but q of shape {q:?}: give one row per row of q"
            )));
        }
    }
    if loads != [q[0], l] {
        return Err(invalid(format!(
            "loads of shape {loads:?} for {} rows of {l} load value(s) each: give ({}, {l})",
            q[0], q[0]
        )));
    }
    Ok(())
}

/// The native mechanism (wrapped by `mech.Mechanism`).
#[pyclass(module = "mech._mech", name = "_Mechanism")]
#[derive(Clone)]
struct PyMechanism {
    inner: Mechanism,
}

/// Results of a table: (names, data (n, C), ok (n,), first error message or None).
type Table<'py> = (
    Vec<String>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<bool>>,
    Option<String>,
);

impl PyMechanism {
    /// The mechanism, when it has one revolute input (`what` needs it).
    fn one_revolute_input(&self, what: &str) -> PyResult<&Mechanism> {
        let m = &self.inner;
        if m.dof() != 1 || m.model().joints[m.model().inputs[0]].kind != JointKind::Revolute {
            return Err(invalid(format!("{what} needs one revolute input")));
        }
        Ok(m)
    }
}

#[pymethods]
impl PyMechanism {
    /// A mechanism from DSL text (`origin`: a file name for the messages).
    #[staticmethod]
    #[pyo3(signature = (text, origin=None))]
    fn from_dsl(py: Python<'_>, text: &str, origin: Option<&str>) -> PyResult<Self> {
        check_text(text, origin.unwrap_or("the text"))?;
        let m = match origin {
            Some(o) => Mechanism::from_dsl_named(text, o),
            None => Mechanism::from_dsl(text),
        };
        m.map(|inner| PyMechanism { inner })
            .map_err(|e| py_err(py, e))
    }

    /// Change one number of the drawing (`points.A`, `links.rod.mass`, `gravity`, ...).
    fn set_param(&mut self, py: Python<'_>, path: &str, value: Vec<f64>) -> PyResult<()> {
        self.inner
            .set_param(path, &value)
            .map_err(|e| py_err(py, e))
    }

    /// The number of inputs G.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }

    /// The inputs: (joint name, "revolute" | "prismatic").
    #[getter]
    fn inputs(&self) -> Vec<(String, String)> {
        let model = self.inner.model();
        model
            .inputs
            .iter()
            .map(|&j| {
                (
                    model.joints[j].name.clone(),
                    model.joints[j].kind.keyword().to_string(),
                )
            })
            .collect()
    }

    /// The loads: (name, number of components: 2 for a force, 1 for a torque).
    #[getter]
    fn loads(&self) -> Vec<(String, usize)> {
        self.inner
            .model()
            .loads
            .iter()
            .map(|l| {
                (
                    l.name().to_string(),
                    if matches!(l, Load::Force { .. }) {
                        2
                    } else {
                        1
                    },
                )
            })
            .collect()
    }

    /// The mechanism's name.
    #[getter]
    fn name(&self) -> String {
        self.inner.model().name.clone()
    }

    /// The column names of `parts`.
    fn columns(&self, parts: Vec<String>) -> PyResult<Vec<String>> {
        Ok(Columns::new(&self.inner, &parts_of(&parts)?).names)
    }

    /// The columns of `parts` at every row of q, q̇, q̈ (n, G) with the flat loads (n, L):
    /// (names, data (n, C), ok (n,), the first error). A failed row is NaN with ok false.
    fn table<'py>(
        &self,
        py: Python<'py>,
        parts: Vec<String>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        qdd: PyReadonlyArray2<'py, f64>,
        loads: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Table<'py>> {
        let cols = Columns::new(&self.inner, &parts_of(&parts)?);
        let (q, qd, qdd, loads) = (
            q.as_array(),
            qd.as_array(),
            qdd.as_array(),
            loads.as_array(),
        );
        check_shapes(
            &self.inner,
            q.shape(),
            qd.shape(),
            qdd.shape(),
            loads.shape(),
        )?;
        let n = q.nrows();
        check_size(n, cols.names.len(), "the table")?;
        // Rows as plain slices of the (n, G) and (n, L) arrays in row-major order (copied
        // once if numpy gave another layout).
        let nl = loads.ncols();
        let (q, qd, qdd, loads) = (
            row_major(&q),
            row_major(&qd),
            row_major(&qdd),
            row_major(&loads),
        );
        let (q, qd, qdd, loads) = (&q[..], &qd[..], &qdd[..], &loads[..]);
        let width = cols.names.len();
        let m = &self.inner;
        // Through the batch runner (`Columns::rows_many`): one scratch per chunk, chunks on
        // the package's pool; a failed row is NaN, its index and error in `errors`.
        let mut data = vec![0.0; n * width];
        let base = m.loads();
        let at = |k: usize| {
            if nl == 0 {
                std::borrow::Cow::Borrowed(&base)
            } else {
                std::borrow::Cow::Owned(loads_of(m, &loads[k * nl..(k + 1) * nl]))
            }
        };
        let errors =
            py.allow_threads(|| pool().install(|| cols.rows_many(m, q, qd, qdd, &at, &mut data)));
        if let Some(e) = errors.refusal() {
            return Err(invalid(e.to_string()));
        }
        let mut ok = vec![true; n];
        for &i in errors.indices() {
            ok[i] = false;
        }
        let first = errors.iter().next().map(|(_, e)| e.to_string());
        let data = numpy::ndarray::Array2::from_shape_vec((n, width), data)
            .expect("shape")
            .into_pyarray(py);
        Ok((cols.names, data, ok.into_pyarray(py), first))
    }

    /// The direct problem q̈ at rows of (q, q̇, driver) with the flat loads (one input):
    /// (q̈ (n,), ok (n,), the first error).
    fn acceleration<'py>(
        &self,
        py: Python<'py>,
        q: Vec<f64>,
        qd: Vec<f64>,
        driver: Vec<f64>,
        loads: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<bool>>,
        Option<String>,
    )> {
        if self.inner.dof() != 1 {
            return Err(invalid(format!(
                "the direct problem by Zhukovski needs one input; this mechanism has {}",
                self.inner.dof()
            )));
        }
        let loads = loads.as_array();
        let n = q.len();
        if qd.len() != n || driver.len() != n {
            return Err(invalid(format!(
                "q, qd and driver of lengths {n}, {} and {}: give one value of each per configuration",
                qd.len(),
                driver.len()
            )));
        }
        let l = load_width(&self.inner);
        if loads.shape() != [n, l] {
            return Err(invalid(format!(
                "loads of shape {:?} for {n} rows of {l} load value(s) each: give ({n}, {l})",
                loads.shape()
            )));
        }
        let m = &self.inner;
        let mut v = vec![0.0; n];
        // Loads the same on every row (or none): `acceleration_many`; else a row's loads each.
        let flat = loads.as_standard_layout();
        let flat = flat.as_slice().unwrap_or(&[]);
        let same = l == 0 || flat.chunks(l).all(|r| r == &flat[..l]);
        let errors = py.allow_threads(|| {
            pool().install(|| {
                if same {
                    let common = loads_of(m, if n == 0 { &[] } else { &flat[..l] });
                    m.acceleration_many(&q, &qd, &driver, &common, &mut v)
                } else {
                    let rows = match Block::new("out", &mut v, 1, n) {
                        Ok(r) => r,
                        Err(e) => return mech_core::solvers::batch::refuse(e),
                    };
                    each(n, rows, |k, r: &mut Block<f64>| {
                        let lk = loads_of(m, &flat[k * l..(k + 1) * l]);
                        *r.at(k) = OneDof::acceleration(m, q[k], qd[k], driver[k], &lk)?;
                        Ok(())
                    })
                }
            })
        });
        if let Some(e) = errors.refusal() {
            return Err(invalid(e.to_string()));
        }
        let mut ok = vec![true; n];
        for &i in errors.indices() {
            ok[i] = false;
        }
        let first = errors.iter().next().map(|(_, e)| e.to_string());
        Ok((v.into_pyarray(py), ok.into_pyarray(py), first))
    }

    /// A parameter sweep: for each variant (a list of (path, values) given to
    /// `set_param`), the columns of `parts` at every row of q (n, G): data (V, n, C) and
    /// ok (V, n); a variant that does not build (its drawing fails a check) is all NaN.
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        variants: Vec<Vec<(String, Vec<f64>)>>,
        parts: Vec<String>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        qdd: PyReadonlyArray2<'py, f64>,
        loads: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(
        Vec<String>,
        Bound<'py, PyArray3<f64>>,
        Bound<'py, numpy::PyArray2<bool>>,
    )> {
        let parts = parts_of(&parts)?;
        let cols = Columns::new(&self.inner, &parts);
        let (q, qd, qdd, loads) = (
            q.as_array(),
            qd.as_array(),
            qdd.as_array(),
            loads.as_array(),
        );
        check_shapes(
            &self.inner,
            q.shape(),
            qd.shape(),
            qdd.shape(),
            loads.shape(),
        )?;
        let (n, width, nv) = (q.nrows(), cols.names.len(), variants.len());
        check_size(nv.saturating_mul(n), width, "the sweep")?;
        let nl = loads.ncols();
        let (q, qd, qdd, loads) = (
            row_major(&q),
            row_major(&qd),
            row_major(&qdd),
            row_major(&loads),
        );
        let (q, qd, qdd, loads) = (&q[..], &qd[..], &qdd[..], &loads[..]);
        let base = &self.inner;
        let results: Vec<(Vec<f64>, Vec<bool>)> = py.allow_threads(|| {
            pool().install(|| {
                variants
                    .par_iter()
                    .map(|v| {
                        let mut m = base.clone();
                        let built = v
                            .iter()
                            .try_for_each(|(path, value)| m.set_param(path, value));
                        let mut data = vec![f64::NAN; n * width];
                        let mut ok = vec![false; n];
                        if built.is_ok() {
                            let at = |k: usize| {
                                std::borrow::Cow::Owned(loads_of(&m, &loads[k * nl..(k + 1) * nl]))
                            };
                            let errors = cols.rows_many(&m, q, qd, qdd, &at, &mut data);
                            if errors.refusal().is_none() {
                                ok.iter_mut().for_each(|o| *o = true);
                                for &i in errors.indices() {
                                    ok[i] = false;
                                }
                            }
                        }
                        (data, ok)
                    })
                    .collect()
            })
        });
        let (data, ok) = stack_variants(py, results, n, width);
        Ok((cols.names, data, ok))
    }

    /// Flywheel sizing over a cycle (one revolute input), loads and driver given by
    /// Python callables of q returning the flat loads and the driver torque.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (start, period, breakpoints, omega_mean, irregularity, loads, driver, rtol))]
    fn flywheel(
        &self,
        py: Python<'_>,
        start: f64,
        period: f64,
        breakpoints: Vec<f64>,
        omega_mean: f64,
        irregularity: f64,
        loads: PyObject,
        driver: Option<PyObject>,
        rtol: f64,
    ) -> PyResult<Vec<(String, f64)>> {
        let m = self.one_revolute_input("flywheel sizing")?;
        // The first exception of a callable, re-raised as it is.
        let raised = Raised::default();
        let call_loads = loads_callable(py, m, &loads, &raised);
        let cycle = CycleArgs {
            start,
            period,
            breakpoints: &breakpoints,
            omega_mean,
            irregularity,
            rtol,
        };
        flywheel_of(py, m, &cycle, call_loads, driver.as_ref(), &raised)
    }

    /// The motion under a motor from (q0, qd0) over [0, t_end] at `samples` + 1 even times
    /// (`mech_core::dynamics::regime::Drive::run`; from rest, the start is checked first):
    /// (t, q, qd, torque on the input).
    #[allow(clippy::too_many_arguments, clippy::type_complexity)]
    #[pyo3(signature = (motor, table, ratio, q0, qd0, t_end, samples, loads, flywheel))]
    fn simulate_motor(
        &self,
        py: Python<'_>,
        motor: String,
        table: Option<(Vec<f64>, Vec<f64>)>,
        ratio: f64,
        q0: f64,
        qd0: f64,
        t_end: f64,
        samples: usize,
        loads: PyObject,
        flywheel: f64,
    ) -> PyResult<(Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>)> {
        let m = self.one_revolute_input("a motor")?;
        let raised = Raised::default();
        let run = || -> Result<Run, CoreError> {
            let drive = Drive::new(
                m,
                motor_of(&motor, table, ratio)?,
                loads_callable(py, m, &loads, &raised),
            )
            .flywheel(flywheel)?;
            if qd0 == 0.0 {
                drive.start_up(q0, t_end, samples)
            } else {
                drive.run(q0, qd0, t_end, samples)
            }
        };
        let out = run();
        if let Some(e) = raised.borrow_mut().take() {
            return Err(e);
        }
        let r = out.map_err(|e| py_err(py, e))?;
        Ok((r.t, r.q, r.qd, r.torque))
    }

    /// The periodic steady regime under a motor (`Drive::steady`): (q, qd, t, torque, the
    /// summary as (name, value) pairs).
    #[allow(clippy::too_many_arguments, clippy::type_complexity)]
    #[pyo3(signature = (motor, table, ratio, start, period, points, loads, flywheel))]
    fn regime(
        &self,
        py: Python<'_>,
        motor: String,
        table: Option<(Vec<f64>, Vec<f64>)>,
        ratio: f64,
        start: f64,
        period: f64,
        points: usize,
        loads: PyObject,
        flywheel: f64,
    ) -> PyResult<(Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<(String, f64)>)> {
        let m = self.one_revolute_input("a motor")?;
        if !(period > 0.0 && period <= MAX_PERIOD) || !(2..=1_000_000).contains(&points) {
            return Err(invalid(format!(
                "period = {period} rad and points = {points}: give a positive period of at most {:.0} turns and 2 to 1000000 points",
                MAX_PERIOD / std::f64::consts::TAU
            )));
        }
        let raised = Raised::default();
        let run = || -> Result<Steady, CoreError> {
            Drive::new(
                m,
                motor_of(&motor, table, ratio)?,
                loads_callable(py, m, &loads, &raised),
            )
            .flywheel(flywheel)?
            .steady(start, period, points)
        };
        let out = run();
        if let Some(e) = raised.borrow_mut().take() {
            return Err(e);
        }
        let s = out.map_err(|e| py_err(py, e))?;
        let c = &s.check;
        let summary = [
            ("mean_speed", s.mean_speed),
            ("epsilon", s.epsilon),
            ("period_time", s.period_time),
            ("motor_peak_torque", c.peak_torque),
            ("motor_rms_torque", c.rms_torque),
            ("motor_mean_power", c.mean_power),
            ("motor_rated_torque", c.rated_torque.unwrap_or(f64::NAN)),
            ("within_rating", if c.within_rating { 1.0 } else { 0.0 }),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        Ok((s.q, s.qd, s.t, s.torque, summary))
    }

    /// The strength of every member over one period at the constant speed `qd`
    /// (`Mechanism::strength`): one row per member (its governing criterion), or one per
    /// criterion with `all`: (members, criteria, rows of stress_max, stress_mean,
    /// stress_alt, safety, q).
    #[allow(clippy::type_complexity)]
    #[pyo3(signature = (qd, period, steps, loads, all))]
    fn strength(
        &self,
        py: Python<'_>,
        qd: f64,
        period: f64,
        steps: usize,
        loads: PyObject,
        all: bool,
    ) -> PyResult<(Vec<String>, Vec<String>, Vec<[f64; 5]>)> {
        let m = self.one_revolute_input("a strength analysis")?;
        let raised = Raised::default();
        let out = m.strength(qd, period, steps, loads_callable(py, m, &loads, &raised));
        if let Some(e) = raised.borrow_mut().take() {
            return Err(e);
        }
        let s = out.map_err(|e| py_err(py, e))?;
        let (mut members, mut criteria, mut rows) = (Vec::new(), Vec::new(), Vec::new());
        for member in &s.members {
            let checks: Vec<&mech_core::strength::Check> = if all {
                member.checks.iter().collect()
            } else {
                member.governing().into_iter().collect()
            };
            for c in checks {
                members.push(member.name.clone());
                criteria.push(c.criterion.name().to_string());
                rows.push([c.stress_max, c.stress_mean, c.stress_alt, c.safety, c.q]);
            }
        }
        Ok((members, criteria, rows))
    }

    /// Size the dimensions written `free(LO..HI)` in `text` (`mech_core::design::sizing`):
    /// (the passes as rows of total_mass, peak_torque, flywheel (NaN without an
    /// irregularity), worst; the free dimensions as (link, name, value); the sized text;
    /// converged; the unmet members).
    #[allow(clippy::type_complexity, clippy::too_many_arguments)]
    #[pyo3(signature = (text, safety, qd, period, steps, irregularity, loads))]
    fn size(
        &self,
        py: Python<'_>,
        text: &str,
        safety: f64,
        qd: f64,
        period: f64,
        steps: usize,
        irregularity: Option<f64>,
        loads: PyObject,
    ) -> PyResult<(
        Vec<[f64; 4]>,
        Vec<(String, String, f64)>,
        String,
        bool,
        Vec<String>,
    )> {
        use mech_core::design::sizing;
        let m = self.one_revolute_input("sizing")?;
        let free = sizing::free_dimensions(text, None).map_err(|e| py_err(py, e))?;
        let req = sizing::Requirement {
            safety,
            speed: qd,
            period,
            steps,
            irregularity,
        };
        let raised = Raised::default();
        let out = sizing::size(m, &free, req, loads_callable(py, m, &loads, &raised));
        if let Some(e) = raised.borrow_mut().take() {
            return Err(e);
        }
        let sized = out.map_err(|e| py_err(py, e))?;
        let rows = sized
            .iterations
            .iter()
            .map(|it| {
                [
                    it.total_mass,
                    it.peak_torque,
                    it.flywheel.unwrap_or(f64::NAN),
                    it.worst,
                ]
            })
            .collect();
        let dims = free
            .iter()
            .zip(&sized.dims)
            .map(|(f, v)| (f.link.clone(), f.name.clone(), *v))
            .collect();
        let written = sizing::write_sized(text, &free, &sized.dims);
        Ok((rows, dims, written, sized.converged, sized.unmet))
    }

    /// The stop from (q0, qd0 > 0) with the motor off and a constant brake torque against
    /// the motion (`Drive::stop` every `dt` seconds, or `Drive::stop_steps` at `points` + 1
    /// even times when `dt` is None): (t, q, qd, torque on the input, the time to rest, the
    /// angle turned).
    #[allow(clippy::too_many_arguments, clippy::type_complexity)]
    #[pyo3(signature = (q0, qd0, brake, dt, points, t_max, loads, flywheel))]
    fn stop(
        &self,
        py: Python<'_>,
        q0: f64,
        qd0: f64,
        brake: f64,
        dt: Option<f64>,
        points: usize,
        t_max: f64,
        loads: PyObject,
        flywheel: f64,
    ) -> PyResult<(Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, f64, f64)> {
        let m = self.one_revolute_input("a stop")?;
        let raised = Raised::default();
        let run = || -> Result<mech_core::dynamics::regime::Stop, CoreError> {
            // The motor is off during a stop: the drive never asks it for a torque.
            let drive = Drive::new(m, Motor::constant(0.0)?, loads_callable(py, m, &loads, &raised))
                .flywheel(flywheel)?;
            match dt {
                Some(dt) => drive.stop(q0, qd0, brake, dt, t_max),
                None => drive.stop_steps(q0, qd0, brake, points, t_max),
            }
        };
        let out = run();
        if let Some(e) = raised.borrow_mut().take() {
            return Err(e);
        }
        let s = out.map_err(|e| py_err(py, e))?;
        Ok((s.run.t, s.run.q, s.run.qd, s.run.torque, s.time, s.travel))
    }

    /// A cam's profile at `points` cam angles over a turn (`mech::cam::Profile::row`):
    /// (the cam's name, the column names, the rows (points, 10), and the design figures:
    /// the largest pressure angle and where, the smallest convex radius and where, rad and
    /// m, and undercut). `name` None: the mechanism's only cam.
    #[allow(clippy::type_complexity)]
    #[pyo3(signature = (name, points))]
    fn cam_profile<'py>(
        &self,
        py: Python<'py>,
        name: Option<String>,
        points: usize,
    ) -> PyResult<(
        String,
        Vec<String>,
        Bound<'py, PyArray2<f64>>,
        (f64, f64, f64, f64, bool),
    )> {
        let (cam, g) = self.inner.cam(name.as_deref()).map_err(|e| py_err(py, e))?;
        if !(3..=MAX_POINTS).contains(&points) {
            return Err(invalid(format!(
                "points = {points}: a profile needs from 3 to {MAX_POINTS} points"
            )));
        }
        let p = &g.profile;
        let rows: Vec<Vec<f64>> = p.table(points).iter().map(|r| r.to_vec()).collect();
        let c = p.check(points);
        Ok((
            cam.to_string(),
            mech_core::elements::cam::Profile::COLUMNS
                .iter()
                .map(|c| c.to_string())
                .collect(),
            PyArray2::from_vec2(py, &rows)?,
            (
                c.max_pressure_angle.0,
                c.max_pressure_angle.1,
                c.min_convex_radius.0,
                c.min_convex_radius.1,
                c.undercut,
            ),
        ))
    }

    /// Reduce for pickling: the DSL text cannot be recovered from the model, so the
    /// Python wrapper pickles its text and parameters; this native object refuses.
    fn __reduce__(&self) -> PyResult<()> {
        Err(PyTypeError::new_err(
            "cannot pickle the native core mech._mech._Mechanism: pickle the mech.Mechanism that holds it (it travels as its text and parameters)",
        ))
    }
}

/// The most targets a synthesis takes (the CLI's limit).
const MAX_TARGETS: usize = 10_000;

fn check_targets(n: usize, what: &str) -> PyResult<()> {
    if n > MAX_TARGETS {
        return Err(invalid(format!(
            "{n} {what}: more than the limit of {MAX_TARGETS}; synthesis needs three to a few dozen, thin them"
        )));
    }
    Ok(())
}

/// Function generation by Freudenstein's equation
/// (`mech_core::design::synthesis::freudenstein::function`): the four-bar through `pairs`
/// (input θ₂, output θ₄, rad from the frame line) with frame length `frame` (m), as (its
/// mechanism file's text, the error Σ (θ₄(θ₂ᵢ) − θ₄ᵢ)² in rad²).
#[pyfunction]
#[pyo3(signature = (pairs, frame))]
fn synthesize_function(py: Python<'_>, pairs: Vec<[f64; 2]>, frame: f64) -> PyResult<(String, f64)> {
    use mech_core::design::synthesis::freudenstein;
    check_targets(pairs.len(), "pairs")?;
    let s = freudenstein::function(&pairs, frame).map_err(|e| py_err(py, e))?;
    let doc = format!(
        "Function generator through {} (input, output) pairs: Freudenstein's equation{} (mech.synthesize_function).",
        pairs.len(),
        if s.exact { "" } else { ", least squares" }
    );
    Ok((s.four_bar.to_mech("FunctionGenerator", &doc), s.error))
}

/// Motion generation by Burmester theory
/// (`mech_core::design::synthesis::burmester::motion`): the four-bar through `poses`
/// (x, y in m, angle in rad), `circle_points` the circle points of A and B in the moving
/// frame (m) for three poses, as (its mechanism file's text, the error in m², the offset γ
/// in rad of A → B from the poses' angles, the crank's angle q at each pose in rad).
#[pyfunction]
#[pyo3(signature = (poses, circle_points))]
fn synthesize_motion(
    py: Python<'_>,
    poses: Vec<[f64; 3]>,
    circle_points: Option<[[f64; 2]; 2]>,
) -> PyResult<(String, f64, f64, Vec<f64>)> {
    use mech_core::design::synthesis::burmester;
    check_targets(poses.len(), "poses")?;
    let s = burmester::motion(&poses, circle_points).map_err(|e| py_err(py, e))?;
    let doc = format!(
        "Motion generator through {} poses: Burmester theory{} (mech.synthesize_motion).",
        poses.len(),
        if s.exact { "" } else { ", least squares" }
    );
    Ok((
        s.four_bar.to_mech("MotionGenerator", &doc),
        s.error,
        s.offset,
        s.crank_angles,
    ))
}

/// Path synthesis of a four-bar (`mech_core::design::synthesis::path::synthesize`) or,
/// with `six_bar`, of a Stephenson III six-bar (`..::six_bar::synthesize`, closed paths):
/// `targets` an (n, 2) array of points (m), `angles` their crank angles (rad, from the
/// frame line) for prescribed timing. Returns the linkage's mechanism text (the SPEC names
/// O2, O4, A, B, P, input O2; a six-bar adds C, D, O6), its error E (m², SPEC §3f) and a
/// dict of how it was found. The search runs in the package's thread pool with the GIL
/// released.
#[pyfunction]
#[pyo3(signature = (targets, angles, closed, seed, evaluations, transmission, ratio, six_bar=false))]
#[allow(clippy::too_many_arguments)]
fn synthesize_path<'py>(
    py: Python<'py>,
    targets: PyReadonlyArray2<'py, f64>,
    angles: Option<Vec<f64>>,
    closed: bool,
    seed: u64,
    evaluations: usize,
    transmission: f64,
    ratio: f64,
    six_bar: bool,
) -> PyResult<(String, f64, Bound<'py, PyDict>)> {
    use mech_core::design::synthesis::path::{synthesize, PathError, PathOptions, PathProblem};
    let a = targets.as_array();
    if a.ncols() != 2 {
        return Err(invalid(format!(
            "points of shape {:?}: give n points as an (n, 2) array of x, y (m)",
            a.shape()
        )));
    }
    let problem = PathProblem {
        targets: a.rows().into_iter().map(|r| [r[0], r[1]]).collect(),
        angles,
        closed,
    };
    let options = PathOptions {
        seed,
        evaluations,
        transmission: transmission.to_radians(),
        ratio,
    };
    let refused = |e: PathError| match e {
        PathError::Infeasible { .. } => MechError::new_err(e.to_string()),
        other => invalid(other.to_string()),
    };
    let n = problem.targets.len();
    let info = PyDict::new(py);
    let (text, error, evaluations, seconds) = if six_bar {
        let s = py
            .allow_threads(|| {
                pool().install(|| {
                    mech_core::design::synthesis::six_bar::synthesize(&problem, &options, |_| {})
                })
            })
            .map_err(refused)?;
        info.set_item("transmission", s.transmission)?;
        info.set_item("ratio", s.ratio)?;
        let doc = format!(
            "Stephenson III six-bar from mech.synthesize_path (seed {seed}): E = {:e} m² over {n} targets.",
            s.error
        );
        let text = s.six_bar.to_mech("PathGenerator", &doc);
        (text, s.error, s.evaluations, s.search_seconds)
    } else {
        let s = py
            .allow_threads(|| pool().install(|| synthesize(&problem, &options, |_| {})))
            .map_err(refused)?;
        info.set_item("transmission", s.transmission)?;
        info.set_item("ratio", s.ratio)?;
        info.set_item("crank_range", s.crank_range)?;
        let doc = format!(
            "Four-bar from mech.synthesize_path (seed {seed}): E = {:e} m² over {n} targets.",
            s.error
        );
        let text = s.four_bar.to_mech("PathGenerator", &doc);
        (text, s.error, s.evaluations, s.search_seconds)
    };
    info.set_item("evaluations", evaluations)?;
    info.set_item("evaluations_per_second", evaluations as f64 / seconds)?;
    Ok((text, error, info))
}

/// Optimise the mechanism `text` (`mech_core::design::optimize`): the variables as (name,
/// lo, hi, unit word or None), the objective by name (`path` with `targets` and `point`),
/// the constraints written as on the command line; `loads` a callable of q returning the
/// flat loads. Returns (values, objective, initial, history as (evaluations, best), the
/// optimised text, evaluations).
#[pyfunction]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
#[pyo3(signature = (text, vary, minimize, targets, point, irregularity, subject_to, qd, period, steps, evaluations, seed, loads))]
fn optimize(
    py: Python<'_>,
    text: &str,
    vary: Vec<(String, f64, f64, Option<String>)>,
    minimize: String,
    targets: Option<Vec<[f64; 2]>>,
    point: Option<String>,
    irregularity: Option<f64>,
    subject_to: Vec<String>,
    qd: f64,
    period: f64,
    steps: usize,
    evaluations: usize,
    seed: u64,
    loads: PyObject,
) -> PyResult<(Vec<f64>, f64, f64, Vec<(usize, f64)>, String, usize)> {
    use mech_core::design::optimize::{Constraint, Objective, Settings, Variable};
    check_text(text, "the text")?;
    let mut vars = Vec::new();
    for (name, lo, hi, unit) in vary {
        let unit = match unit {
            None => None,
            Some(w) => Some(mech_core::model::units::lookup(&w).ok_or_else(|| {
                invalid(format!("vary {name}: unknown unit `{w}`; the words are {}", mech_core::model::units::all_words()))
            })?),
        };
        let f = unit.map_or(1.0, |u| u.factor);
        vars.push(Variable { name, lo: lo * f, hi: hi * f, unit });
    }
    let objective = if minimize == "path" {
        match (targets, point) {
            (Some(targets), Some(point)) => Objective::Path { targets, point },
            _ => return Err(invalid("minimize=\"path\" needs targets (an array of x, y) and point (the point's name)")),
        }
    } else {
        Objective::parse(&minimize, irregularity, |_| Err(CoreError::InvalidInput("give a path's targets as an array".into())))
            .map_err(|e| py_err(py, e))?
    };
    let constraints = subject_to
        .iter()
        .map(|c| Constraint::parse(c))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| py_err(py, e))?;
    let settings = Settings { speed: qd, period, steps, evaluations, seed };
    let raised = Raised::default();
    let out = mech_core::design::optimize::optimize(text, &vars, &objective, &constraints, settings, |m, q| {
        let flat: Vec<f64> = loads.call1(py, (q,)).and_then(|v| v.extract(py)).map_err(|e| {
            let text = format!("the loads callable at q = {q}: {e}");
            keep_first(&raised, e);
            CoreError::InvalidInput(text)
        })?;
        Ok(loads_of(m, &flat))
    });
    if let Some(e) = raised.borrow_mut().take() {
        return Err(e);
    }
    let o = out.map_err(|e| py_err(py, e))?;
    Ok((o.values, o.objective, o.initial, o.history, o.text, o.evaluations))
}

/// Counterweights for the mechanism `text` (`mech_core::design::balance`, SPEC 3g), the
/// balanced text returned: `method` "force" (`force_balance`: a four-bar exactly; a
/// slider-crank's crank for its rotating masses and the fraction `fraction` of the
/// reciprocating one) or "optimal" (`optimal_balance` at `speed` rad/s with `weights` on
/// the RMS of shaking force, shaking moment and driver torque); `radius` (m) the
/// counterweights' distance from their pivots, `None` for each link's own length.
#[pyfunction]
#[pyo3(signature = (text, speed, method, fraction, radius, weights))]
fn balance(
    py: Python<'_>,
    text: &str,
    speed: f64,
    method: &str,
    fraction: f64,
    radius: Option<f64>,
    weights: (f64, f64, f64),
) -> PyResult<String> {
    use mech_core::design::balance::{
        force_balance, optimal_balance, write_counterweights, BalanceWeights,
    };
    check_text(text, "the text")?;
    let m = mech_core::Mechanism::from_dsl(text).map_err(|e| py_err(py, e))?;
    if m.dof() != 1 {
        return Err(invalid("balancing takes a mechanism with one input"));
    }
    let weights = match method {
        "force" => force_balance(m.model(), fraction, radius),
        "optimal" => {
            let w = BalanceWeights {
                force: weights.0,
                moment: weights.1,
                driver: weights.2,
            };
            py.allow_threads(|| optimal_balance(text, speed, w, radius))
        }
        other => {
            return Err(invalid(format!(
                "method = {other:?}: give \"force\" or \"optimal\""
            )))
        }
    }
    .map_err(|e| invalid(e.to_string()))?;
    write_counterweights(text, &weights).map_err(|e| invalid(e.to_string()))
}

/// An engine of several cylinders (`mech_core::design::engine`): `layout` "inline", "v"
/// (bank angle `bank`, rad) or "boxer", `cylinders`, the throws from the four-stroke
/// `firing` order (cylinders from 1) or given as `phases` (rad), the crank radius, rod
/// length (m), reciprocating mass (kg) and pin spacing (m); with `balance_couple` the two
/// end-plane crankshaft counterweights that cancel a rotating primary couple. Returns
/// the engine's mechanism text and its rows of the classical balance table (before, and
/// after the counterweights when asked), each a dict of the exact and first-order
/// amplitudes.
#[pyfunction]
#[pyo3(signature = (layout, cylinders, bank, firing, phases, radius, rod, mass, spacing, balance_couple))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
fn engine<'py>(
    py: Python<'py>,
    layout: &str,
    cylinders: usize,
    bank: f64,
    firing: Option<Vec<usize>>,
    phases: Option<Vec<f64>>,
    radius: f64,
    rod: f64,
    mass: f64,
    spacing: f64,
    balance_couple: bool,
) -> PyResult<(String, Vec<Bound<'py, PyDict>>)> {
    use mech_core::design::engine::{
        balance_table, primary_couple_counterweights, Engine, Layout,
    };
    let bad = |e: CoreError| invalid(e.to_string());
    let layout = match layout {
        "inline" => Layout::Inline,
        "boxer" => Layout::Boxer,
        "v" => Layout::Vee { bank },
        other => {
            return Err(invalid(format!(
                "layout = {other:?}: give \"inline\", \"v\" or \"boxer\""
            )))
        }
    };
    let mut e = Engine::new(layout, cylinders).map_err(bad)?;
    (e.radius, e.rod, e.mass, e.spacing) = (radius, rod, mass, spacing);
    if let Some(order) = &firing {
        e = e.with_firing(order).map_err(bad)?;
    }
    if let Some(throws) = &phases {
        e = e.with_throws(throws).map_err(bad)?;
    }
    let steps = 360;
    let mut rows = vec![balance_table(&e, steps).map_err(bad)?];
    if balance_couple {
        let ends = (e.pins() as f64 - 1.0) / 2.0 * e.spacing;
        let w = primary_couple_counterweights(&e, &rows[0].exact[0], e.radius, (-ends, ends))
            .map_err(bad)?;
        e.counterweights = w.to_vec();
        let mut after = balance_table(&e, steps).map_err(bad)?;
        after.engine += " balanced";
        rows.push(after);
    }
    let text = e.to_mech("Engine").map_err(bad)?;
    let dicts = rows
        .iter()
        .map(|r| {
            let d = PyDict::new(py);
            d.set_item("engine", &r.engine)?;
            d.set_item("firing", &r.firing)?;
            d.set_item("throws", &r.throws)?;
            d.set_item("primary_force", (r.primary_force[0], r.primary_force[1]))?;
            d.set_item("secondary_force", (r.secondary_force[0], r.secondary_force[1]))?;
            d.set_item("primary_couple", (r.primary_couple[0], r.primary_couple[1]))?;
            d.set_item("secondary_couple", (r.secondary_couple[0], r.secondary_couple[1]))?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok((text, dicts))
}

/// The native module `mech._mech`.
#[pymodule]
fn _mech(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMechanism>()?;
    m.add_class::<spatial::PySpatialMechanism>()?;
    m.add_function(wrap_pyfunction!(spatial::is_spatial, m)?)?;
    m.add_function(wrap_pyfunction!(num_threads, m)?)?;
    m.add_function(wrap_pyfunction!(optimize, m)?)?;
    m.add_function(wrap_pyfunction!(balance, m)?)?;
    m.add_function(wrap_pyfunction!(engine, m)?)?;
    m.add_function(wrap_pyfunction!(synthesize_function, m)?)?;
    m.add_function(wrap_pyfunction!(synthesize_motion, m)?)?;
    m.add_function(wrap_pyfunction!(synthesize_path, m)?)?;
    let py = m.py();
    // The module they are found in, for pickle (a worker's exception travels back to
    // the client): `mech._mech`, not the `_mech` the macro names.
    for t in [
        py.get_type::<MechError>(),
        py.get_type::<InvalidMechanism>(),
        py.get_type::<NoAssembly>(),
        py.get_type::<Singular>(),
    ] {
        t.setattr("__module__", "mech._mech")?;
    }
    m.add("MechError", py.get_type::<MechError>())?;
    m.add("InvalidMechanism", py.get_type::<InvalidMechanism>())?;
    m.add("NoAssembly", py.get_type::<NoAssembly>())?;
    m.add("Singular", py.get_type::<Singular>())?;
    m.add("InvalidInput", invalid_input_type(py))?;
    Ok(())
}
