//! What the page asks for, as JSON: the model (the inputs, the picture, the error), one
//! frame of the drawing at the sliders' values (the points as `mech solve` gives them),
//! and the charts over the first input (the columns of `mech sweep`, plus the shaking
//! force and a cam's pressure angle).

use super::state::{Good, Snapshot};
use crate::columns::{Columns, Part};
use crate::loads::LoadSet;
use crate::{scene, svg, Failure};
use serde_json::{json, Map, Value};

/// Steps of the charts over the first input's range (rows = steps + 1).
pub const CHART_STEPS: usize = 360;

/// The model as the page sees it: the version, FILE, its error (message and line), and
/// of the last good mechanism its name, inputs, points, joints, view and picture.
pub fn model(s: &Snapshot, file: &str) -> Value {
    let error = s
        .error
        .as_ref()
        .map(|d| json!({ "message": d.message, "line": d.line }));
    let mut out = json!({ "version": s.version, "file": file, "error": error });
    if let Some(g) = &s.good {
        let model = g.mechanism.model();
        let v = &g.view;
        let extra = json!({
            "name": model.name,
            "inputs": g.inputs.iter().map(|i| json!({
                "name": i.name, "unit": i.unit, "from": i.range.0, "to": i.range.1,
                "reference": i.reference,
            })).collect::<Vec<_>>(),
            "points": model.points.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(),
            "joints": model.joints.iter().map(|j| j.name.as_str()).collect::<Vec<_>>(),
            "redundant": g.mechanism.redundant(),
            "view": { "x_min": v.x_min, "y_max": v.y_max, "k": v.k, "pad": v.pad,
                      "width": v.width, "height": v.height },
            "picture": g.picture,
        });
        if let (Value::Object(o), Value::Object(e)) = (&mut out, extra) {
            o.extend(e);
        }
    }
    out
}

/// One frame at inputs `q`: every shape's placing attributes (in the picture's order),
/// and every point in the drawing (m: the `<point>.x`, `<point>.y` of `mech solve`) and in
/// the picture (px).
pub fn frame(g: &Good, q: &[f64]) -> Result<Value, Failure> {
    let m = &g.mechanism;
    if q.len() != m.dof() {
        return Err(Failure::usage(format!(
            "q: {} value(s) for {} input(s)",
            q.len(),
            m.dof()
        )));
    }
    let f = scene::frame(m, q)?;
    let attrs: Vec<Vec<(&str, String)>> = f
        .shapes
        .iter()
        .map(|s| svg::attributes(&g.view, s))
        .collect();
    let cols = Columns::new(m, Part::POSE);
    let none = LoadSet::default().at(m, q[0]);
    let row = cols.row(m, q, &vec![0.0; q.len()], &vec![0.0; q.len()], &none)?;
    let (mut points, mut px) = (Map::new(), Map::new());
    for p in &m.model().points {
        let at = |c: &str| {
            let name = format!("{}.{c}", p.name);
            cols.names.iter().position(|n| *n == name).map(|i| row[i])
        };
        if let (Some(x), Some(y)) = (at("x"), at("y")) {
            points.insert(p.name.clone(), json!([x, y]));
            let (a, b) = g.view.px(mech_core::kernel::link_state::V2::new(x, y));
            px.insert(p.name.clone(), json!([a, b]));
        }
    }
    Ok(json!({ "q": q, "attrs": attrs, "points": points, "px": px }))
}

/// The charts over the first input's range in [`CHART_STEPS`] steps, the other inputs at
/// `rest`, every input at speed `qd` (no acceleration, no load given, as `mech sweep
/// --speed` without `--load`): `x`, and the columns `driver`, `virtual_power`,
/// `inertia`, `moment`, `<joint>.fx`, `<joint>.fy` (as `mech sweep` names and computes
/// them), `shaking.fx`, `shaking.fy` (as `mech shaking`); with a cam, its pressure
/// angle over the cam's turn.
pub fn charts(g: &Good, rest: &[f64], qd: &[f64]) -> Result<Value, Failure> {
    let m = &g.mechanism;
    let dof = m.dof();
    if rest.len() != dof || qd.len() != dof {
        return Err(Failure::usage(format!(
            "give {dof} input value(s) and {dof} speed(s)"
        )));
    }
    let (a, b) = g.inputs[0].range;
    let mut q = Vec::with_capacity((CHART_STEPS + 1) * dof);
    let mut x = Vec::with_capacity(CHART_STEPS + 1);
    for k in 0..=CHART_STEPS {
        let v = crate::solve::inputs(a, b, CHART_STEPS, k);
        x.push(v);
        q.push(v);
        q.extend_from_slice(&rest[1..]);
    }
    let parts: Vec<Part> = Part::ALL.iter().copied().chain([Part::Shaking]).collect();
    let cols = Columns::new(m, &parts);
    let width = cols.names.len();
    let n = CHART_STEPS + 1;
    let mut buf = vec![0.0; n * width];
    let (qds, qdds) = (qd.repeat(n), vec![0.0; n * dof]);
    let loads = LoadSet::default().at(m, a);
    let at = |_: usize| std::borrow::Cow::Borrowed(&loads);
    let errors = cols.rows_many(m, &q, &qds, &qdds, &at, &mut buf);
    if let Some(e) = errors.refusal() {
        return Err(Failure::mechanism(e.to_string()));
    }
    let model = m.model();
    let wanted = |n: &str| {
        matches!(
            n,
            "driver" | "virtual_power" | "inertia" | "moment" | "shaking.fx" | "shaking.fy"
        ) || n.starts_with("driver.")
            || n.starts_with("virtual_power.")
            || model
                .joints
                .iter()
                .any(|j| n == format!("{}.fx", j.name) || n == format!("{}.fy", j.name))
    };
    let (mut columns, mut units) = (Map::new(), Map::new());
    for (i, name) in cols.names.iter().enumerate() {
        if wanted(name) {
            // A configuration that did not assemble is null (NaN is no JSON number).
            let v: Vec<Value> = (0..n)
                .map(|r| {
                    let y = buf[r * width + i];
                    if y.is_finite() {
                        json!(y)
                    } else {
                        Value::Null
                    }
                })
                .collect();
            columns.insert(name.clone(), Value::Array(v));
            units.insert(name.clone(), json!(cols.units[i]));
        }
    }
    let cam = match m.cam(None) {
        Ok((name, geom)) => {
            let table = geom.profile.table(CHART_STEPS);
            let col = |c: &str| {
                mech_core::elements::cam::Profile::COLUMNS
                    .iter()
                    .position(|n| *n == c)
            };
            match (col("theta"), col("pressure_angle")) {
                (Some(t), Some(p)) => json!({
                    "name": name,
                    "theta": table.iter().map(|r| r[t]).collect::<Vec<_>>(),
                    "pressure_angle": table.iter().map(|r| r[p]).collect::<Vec<_>>(),
                }),
                _ => Value::Null,
            }
        }
        Err(_) => Value::Null,
    };
    Ok(json!({
        "x": x,
        "unit": g.inputs[0].unit,
        "speed": qd,
        "columns": columns,
        "units": units,
        "failed": errors.indices().len(),
        "cam": cam,
    }))
}
