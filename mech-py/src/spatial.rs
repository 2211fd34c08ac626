//! Spatial mechanisms (SPEC 3i) for Python: [`mech_core::spatial::SpatialMechanism`]
//! behind `mech._mech._SpatialMechanism`, whose `table` gives the columns of
//! `mech_core::runtime::spatial_columns` (the `mech` tool's spatial CSV names) row by row.

use crate::{check_size, check_text, invalid, parts_of, py_err};
use mech_core::runtime::spatial_columns::{is_spatial as text_is_spatial, SpatialColumns};
use mech_core::spatial::{JointKind, LoadKind, SpatialMechanism};
use mech_core::MechError as CoreError;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use rayon::prelude::*;

/// True when `text` declares a spatial mechanism (its first item is `space`).
#[pyfunction]
pub fn is_spatial(text: &str) -> bool {
    text_is_spatial(text)
}

/// The messages of a spatial check as `[FILE:]LINE:COLUMN: message` (the planar loader's
/// form, so the exception carries `line` and `column`), a whole-mechanism one as
/// `[FILE: ]message`.
fn located(origin: Option<&str>, messages: &str) -> String {
    let file = origin.map_or(String::new(), |o| format!("{o}:"));
    messages
        .lines()
        .map(|m| {
            let at = m.strip_prefix("line ").and_then(|rest| {
                let (l, rest) = rest.split_once(", column ")?;
                let (c, msg) = rest.split_once(": ")?;
                Some((l.parse::<usize>().ok()?, c.parse::<usize>().ok()?, msg))
            });
            match (at, origin) {
                (Some((l, c, msg)), _) => format!("{file}{l}:{c}: {msg}"),
                (None, Some(o)) => format!("{o}: {m}"),
                (None, None) => m.to_string(),
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// (names, data (V, n, C), ok (V, n)).
type Sweep<'py> = (
    Vec<String>,
    Bound<'py, numpy::PyArray3<f64>>,
    Bound<'py, PyArray2<bool>>,
);

type View<'a> = numpy::ndarray::ArrayView2<'a, f64>;

/// The columns `cols` of `m` at every row of q, q̇, q̈ with the loads (each load's x, y, z;
/// no columns: none): the data (n × C, row by row), ok per row and the first error.
fn rows(
    m: &SpatialMechanism,
    cols: &SpatialColumns,
    q: &View,
    qd: &View,
    qdd: &View,
    loads: &View,
) -> (Vec<f64>, Vec<bool>, Option<String>) {
    let (n, width) = (q.nrows(), cols.names.len());
    let mut data = vec![f64::NAN; n * width];
    let mut ok = vec![false; n];
    let mut first = None;
    let names = m.loads().names;
    for i in 0..n {
        let row = |a: &View| a.row(i).to_vec();
        let mut l = m.loads();
        if loads.ncols() != 0 {
            let v = row(loads);
            for (k, name) in names.iter().enumerate() {
                l.set_by_name(name, &v[3 * k..3 * k + 3]);
            }
        }
        match cols.row(m, &row(q), &row(qd), &row(qdd), &l) {
            Ok(r) => {
                data[i * width..(i + 1) * width].copy_from_slice(&r);
                ok[i] = true;
            }
            Err(e) => {
                if first.is_none() {
                    first = Some(e.to_string());
                }
            }
        }
    }
    (data, ok, first)
}

/// `InvalidInput` unless q, q̇, q̈ are (n, G) each and the loads (n, 3 L) or empty.
fn shapes<'a>(
    m: &SpatialMechanism,
    q: &View<'a>,
    qd: &View<'a>,
    qdd: &View<'a>,
    loads: &View<'a>,
) -> PyResult<()> {
        let (n, g, nl) = (q.nrows(), m.dof(), 3 * m.model().loads.len());
        for (a, what) in [(&qd, "qd"), (&qdd, "qdd")] {
            if a.shape() != q.shape() {
                return Err(invalid(format!(
                    "{what} has shape {:?} and q {:?}: give the same shape (rows, {g})",
                    a.shape(),
                    q.shape()
                )));
            }
        }
        if q.ncols() != g {
            return Err(invalid(format!(
                "q has {} column(s) for {g} input(s): give one per input",
                q.ncols()
            )));
        }
        if loads.ncols() != 0 && (loads.nrows() != n || loads.ncols() != nl) {
            return Err(invalid(format!(
                "loads of shape {:?}: give ({n}, {nl}), the x, y, z of each load in order",
                loads.shape()
            )));
        }
    Ok(())
}

/// The native spatial mechanism (wrapped by `mech.SpatialMechanism`).
#[pyclass(module = "mech._mech", name = "_SpatialMechanism")]
#[derive(Clone)]
pub struct PySpatialMechanism {
    inner: SpatialMechanism,
}

/// (names, data (n, C), ok (n,), the first error message or None).
type Table<'py> = (
    Vec<String>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<bool>>,
    Option<String>,
);

#[pymethods]
impl PySpatialMechanism {
    /// A spatial mechanism from its `space` text (`origin`: a file name for the messages).
    #[staticmethod]
    #[pyo3(signature = (text, origin=None))]
    fn from_dsl(py: Python<'_>, text: &str, origin: Option<&str>) -> PyResult<Self> {
        check_text(text, origin.unwrap_or("the text"))?;
        SpatialMechanism::from_dsl(text)
            .map(|inner| PySpatialMechanism { inner })
            .map_err(|e| match e {
                mech_core::MechError::Invalid(m) => {
                    py_err(py, mech_core::MechError::Invalid(located(origin, &m)))
                }
                e => py_err(py, e),
            })
    }

    /// The number of inputs G.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }

    /// The mechanism's name.
    #[getter]
    fn name(&self) -> String {
        self.inner.model().name.clone()
    }

    /// The inputs: (joint name, its kind's word).
    #[getter]
    fn inputs(&self) -> Vec<(String, String)> {
        let model = self.inner.model();
        model
            .inputs
            .iter()
            .map(|&j| {
                (
                    model.joints[j].name.clone(),
                    model.joints[j].kind.word().to_string(),
                )
            })
            .collect()
    }

    /// The loads: (name, "force" | "torque"), three components each.
    #[getter]
    fn loads(&self) -> Vec<(String, String)> {
        self.inner
            .model()
            .loads
            .iter()
            .map(|l| {
                let kind = match l.kind {
                    LoadKind::Force { .. } => "force",
                    LoadKind::Torque { .. } => "torque",
                };
                (l.name.clone(), kind.to_string())
            })
            .collect()
    }

    /// The idle links (between two spherical joints).
    #[getter]
    fn idle_links(&self) -> Vec<String> {
        self.inner
            .idle_links()
            .into_iter()
            .map(str::to_string)
            .collect()
    }

    /// The column names of `parts`.
    fn columns(&self, parts: Vec<String>) -> PyResult<Vec<String>> {
        Ok(SpatialColumns::new(&self.inner, &parts_of(&parts)?).names)
    }

    /// Change one number of the drawing by name, re-checked
    /// (`SpatialMechanism::set_param`).
    fn set_param(&mut self, py: Python<'_>, path: &str, value: Vec<f64>) -> PyResult<()> {
        self.inner.set_param(path, &value).map_err(|e| py_err(py, e))
    }

    /// A parameter sweep: for each variant (a list of (path, values) given to `set_param`),
    /// the columns of `parts` at every row of q (n, G): (names, data (V, n, C), ok (V, n)); a
    /// variant that does not build (its drawing fails a check) is all NaN, a row that does
    /// not solve NaN, ok false.
    #[allow(clippy::too_many_arguments)]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        variants: Vec<Vec<(String, Vec<f64>)>>,
        parts: Vec<String>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        qdd: PyReadonlyArray2<'py, f64>,
        loads: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Sweep<'py>> {
        let cols = SpatialColumns::new(&self.inner, &parts_of(&parts)?);
        let (q, qd, qdd, loads) = (q.as_array(), qd.as_array(), qdd.as_array(), loads.as_array());
        shapes(&self.inner, &q, &qd, &qdd, &loads)?;
        let (n, width, nv) = (q.nrows(), cols.names.len(), variants.len());
        check_size(nv.saturating_mul(n), width, "the sweep")?;
        let base = &self.inner;
        let (q, qd, qdd, loads) = (q.view(), qd.view(), qdd.view(), loads.view());
        let results: Vec<(Vec<f64>, Vec<bool>)> = py.allow_threads(|| {
            crate::pool().install(|| {
                variants
                    .par_iter()
                    .map(|v| {
                        let mut m = base.clone();
                        let built = v.iter().try_for_each(|(path, value)| m.set_param(path, value));
                        if built.is_ok() {
                            let (d, o, _) = rows(&m, &cols, &q, &qd, &qdd, &loads);
                            (d, o)
                        } else {
                            (vec![f64::NAN; n * width], vec![false; n])
                        }
                    })
                    .collect()
            })
        });
        let (data, ok) = crate::stack_variants(py, results, n, width);
        Ok((cols.names, data, ok))
    }

    /// The columns of `parts` at every row of q, q̇, q̈ (n, G) with the loads (n, 3 L), each
    /// load's x, y, z in declaration order: (names, data (n, C), ok (n,), the first error).
    /// A failed row is NaN with ok false.
    fn table<'py>(
        &self,
        py: Python<'py>,
        parts: Vec<String>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        qdd: PyReadonlyArray2<'py, f64>,
        loads: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Table<'py>> {
        let m = &self.inner;
        let cols = SpatialColumns::new(m, &parts_of(&parts)?);
        let (q, qd, qdd, loads) = (
            q.as_array(),
            qd.as_array(),
            qdd.as_array(),
            loads.as_array(),
        );
        shapes(m, &q, &qd, &qdd, &loads)?;
        let n = q.nrows();
        check_size(n, cols.names.len(), "the table")?;
        let width = cols.names.len();
        let (data, ok, first) = rows(m, &cols, &q, &qd, &qdd, &loads);
        let data = numpy::ndarray::Array2::from_shape_vec((n, width), data)
            .expect("n × width values")
            .into_pyarray(py);
        Ok((cols.names, data, ok.into_pyarray(py), first))
    }
    /// The direct problem, q̈ from I* q̈ + ½ dI*/dq q̇² = driver + M*, at each row of q, q̇
    /// and the driver (n each) with the loads (n, 3 L): (q̈ (n,), ok (n,), the first error).
    /// A failed row is NaN with ok false.
    fn acceleration<'py>(
        &self,
        py: Python<'py>,
        q: Vec<f64>,
        qd: Vec<f64>,
        driver: Vec<f64>,
        loads: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<bool>>, Option<String>)> {
        let m = &self.inner;
        if m.dof() != 1 {
            return Err(invalid(format!(
                "the direct problem by Zhukovski needs one input; this mechanism has {}",
                m.dof()
            )));
        }
        let (loads, n, nl) = (loads.as_array(), q.len(), 3 * m.model().loads.len());
        if qd.len() != n || driver.len() != n {
            return Err(invalid(format!(
                "q, qd and driver of lengths {n}, {} and {}: give one value of each per configuration",
                qd.len(),
                driver.len()
            )));
        }
        if loads.ncols() != 0 && (loads.nrows() != n || loads.ncols() != nl) {
            return Err(invalid(format!(
                "loads of shape {:?}: give ({n}, {nl}), the x, y, z of each load in order",
                loads.shape()
            )));
        }
        let names = m.loads().names;
        let (mut out, mut ok, mut first) = (vec![f64::NAN; n], vec![false; n], None);
        for i in 0..n {
            let mut l = m.loads();
            if loads.ncols() != 0 {
                let v = loads.row(i).to_vec();
                for (k, name) in names.iter().enumerate() {
                    l.set_by_name(name, &v[3 * k..3 * k + 3]);
                }
            }
            match m.acceleration(q[i], qd[i], driver[i], &l) {
                Ok(a) => (out[i], ok[i]) = (a, true),
                Err(e) => {
                    first.get_or_insert_with(|| e.to_string());
                }
            }
        }
        Ok((out.into_pyarray(py), ok.into_pyarray(py), first))
    }
    /// The flywheel over one cycle (one revolute input): the loads at q from `loads` (a
    /// callable of q giving the x, y, z of each load in order), the driver a callable of q
    /// (`None`: the constant torque that balances the cycle); as `Mechanism.flywheel`.
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
        let m = &self.inner;
        let model = m.model();
        if m.dof() != 1 || !matches!(model.joints[model.inputs[0]].kind, JointKind::Revolute { .. }) {
            return Err(invalid("flywheel sizing needs one revolute input".to_string()));
        }
        let raised = crate::Raised::default();
        let names = m.loads().names;
        let call_loads = |q: f64| {
            let flat: Vec<f64> = loads
                .call1(py, (q,))
                .and_then(|v| v.extract(py))
                .map_err(|e| {
                    let text = format!("the loads callable at q = {q}: {e}");
                    crate::keep_first(&raised, e);
                    CoreError::InvalidInput(text)
                })?;
            let mut l = m.loads();
            for (k, name) in names.iter().enumerate() {
                if let Some(v) = flat.get(3 * k..3 * k + 3) {
                    l.set_by_name(name, v);
                }
            }
            Ok(l)
        };
        let cycle = crate::CycleArgs {
            start,
            period,
            breakpoints: &breakpoints,
            omega_mean,
            irregularity,
            rtol,
        };
        crate::flywheel_of(py, m, &cycle, call_loads, driver.as_ref(), &raised)
    }
}
