//! Spatial mechanisms (SPEC 3i) on the command line: a file whose first item is `space`
//! ([`mech_core::runtime::spatial_columns::is_spatial`]) is loaded as a
//! [`SpatialMechanism`]; `mech check` prints Kutzbach's count and the idle links, `mech
//! solve` and `mech sweep` write the columns of
//! [`mech_core::runtime::spatial_columns::SpatialColumns`], `mech draw` and `mech animate`
//! an isometric view, with the paths of chosen points ([`path`]) and the reaction arrows
//! ([`arrows`]).

use crate::columns::Level;
use crate::output::{Format, Writer};
use crate::scene::{Frame, Role, Shape};
use crate::{quantity, svg, Failure};
use mech_core::kernel::link_state::V2;
use mech_core::model::units::Dim;
use mech_core::runtime::spatial_columns::SpatialColumns;
use mech_core::spatial::{JointKind, LoadKind, SpatialLoads, SpatialMechanism};
use nalgebra::Vector3;
use std::fmt::Write as _;
use std::io::Write;

/// A spatial mechanism's messages rendered against its file: a message located `line L,
/// column C: ...` becomes `ORIGIN:L:C: ...` with the line and a caret under the column; a
/// whole-mechanism message (Kutzbach's count, the rank) `ORIGIN: ...`.
pub fn render(text: &str, origin: &str, messages: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    messages
        .lines()
        .map(|m| {
            let located = m.strip_prefix("line ").and_then(|rest| {
                let (l, rest) = rest.split_once(", column ")?;
                let (c, msg) = rest.split_once(": ")?;
                Some((l.parse::<usize>().ok()?, c.parse::<usize>().ok()?, msg))
            });
            match located {
                Some((l, c, msg)) => {
                    let mut s = format!("{origin}:{l}:{c}: {msg}");
                    if let Some(line) = lines.get(l.wrapping_sub(1)) {
                        let w = l.to_string().len();
                        let pad: String = line
                            .chars()
                            .take(c.saturating_sub(1))
                            .map(|ch| if ch == '\t' { '\t' } else { ' ' })
                            .collect();
                        let _ = write!(s, "\n{:w$} |\n{l} | {line}\n{:w$} | {pad}^ here", "", "");
                    }
                    s
                }
                None => format!("{origin}: {m}"),
            }
        })
        .collect::<Vec<_>>()
        .join("\n\n")
}

/// The spatial mechanism of `text` through every load-time check, its messages naming
/// `origin` ([`render`]).
pub fn parse(text: &str, origin: &str) -> Result<SpatialMechanism, Failure> {
    SpatialMechanism::from_dsl(text).map_err(|e| match e {
        mech_core::MechError::Invalid(m) => Failure::mechanism(render(text, origin, &m)),
        other => Failure::mechanism(format!("{origin}: {other}")),
    })
}

/// What `mech check` prints for a valid spatial mechanism: N and the pairs by class,
/// Kutzbach's G, the idle freedoms, the equations against the unknowns.
pub fn summary(m: &SpatialMechanism) -> String {
    let model = m.model();
    let c = m.kutzbach();
    let p = c.pairs_by_class;
    let mut s = String::new();
    let _ = writeln!(s, "mechanism `{}`: valid (spatial)", model.name);
    let _ = writeln!(
        s,
        "  N = {} links (ground included), pairs by class: P_I = {}, P_II = {}, P_III = {}, P_IV = {}, P_V = {}",
        c.n, p[0], p[1], p[2], p[3], p[4]
    );
    let _ = writeln!(
        s,
        "  Kutzbach: G = 6(N − 1) − 5 P_I − 4 P_II − 3 P_III − 2 P_IV − P_V = {} − {} − {} − {} − {} − {} = {}",
        c.equations(),
        5 * p[0],
        4 * p[1],
        3 * p[2],
        2 * p[3],
        p[4],
        c.mobility
    );
    if c.idle.is_empty() {
        let _ = writeln!(s, "  idle freedoms: none");
    } else {
        let _ = writeln!(s, "  idle freedoms: {}", c.idle.len());
        for &(b, j1, j2) in &c.idle {
            let _ = writeln!(
                s,
                "    link `{}` spins about the line through its spherical joints `{}` and `{}` (held by the solver)",
                model.bodies[b].name, model.joints[j1].name, model.joints[j2].name
            );
        }
    }
    let inputs: Vec<String> = model
        .inputs
        .iter()
        .map(|&j| {
            let joint = &model.joints[j];
            format!("`{}` ({})", joint.name, joint.kind.word())
        })
        .collect();
    let _ = writeln!(
        s,
        "  G − idle = {} = inputs declared: {} ({})",
        c.mobility - c.idle.len() as i64,
        c.inputs,
        inputs.join(", ")
    );
    let _ = writeln!(
        s,
        "  equations 6(N − 1) = {}, unknowns G − idle + reaction components = {} + {}",
        c.equations(),
        c.mobility - c.idle.len() as i64,
        c.reactions()
    );
    s
}

/// The dimensions of input `k`'s coordinate and rate: (angle, angular speed) for a revolute
/// or helical input, (length, none) for a prismatic one.
pub fn input_dims(m: &SpatialMechanism, k: usize) -> (Dim, Dim) {
    let model = m.model();
    match model.joints[model.inputs[k]].kind {
        JointKind::Prismatic { .. } => (Dim::LENGTH, Dim::NONE),
        _ => (Dim::ANGLE, Dim::SPEED),
    }
}

/// One value per input of `m` from `texts` (`rate` 0: q, 1: q̇, 2: q̈); `default` for each
/// when `texts` is empty.
pub fn per_input(
    texts: &[String],
    m: &SpatialMechanism,
    rate: usize,
    what: &str,
    default: f64,
) -> Result<Vec<f64>, Failure> {
    let g = m.dof();
    if texts.is_empty() {
        return Ok(vec![default; g]);
    }
    if texts.len() != g {
        return Err(Failure::usage(format!(
            "{what}: {} value(s) given for {g} input(s); give one per input, in the order of `inputs`",
            texts.len()
        )));
    }
    texts
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let (d, v) = input_dims(m, k);
            let dim = match rate {
                0 => d,
                1 => v,
                _ => Dim::NONE,
            };
            quantity::parse(t, dim, what)
        })
        .collect()
}

/// The loads of `--load NAME=x,y,z` arguments: each a force (N) or a torque (N·m) as three
/// components in the global axes, units allowed (`push=4N,-3N,2.5N`).
pub fn loads(args: &[String], m: &SpatialMechanism) -> Result<SpatialLoadSet, Failure> {
    let model = m.model();
    let mut loads = m.loads();
    let mut tables = Vec::new();
    for a in args {
        let Some((name, value)) = a.split_once('=') else {
            return Err(Failure::usage(format!(
                "--load `{a}`: expected NAME=x,y,z (a spatial load has three components), e.g. `push=0,0,-100`"
            )));
        };
        let name = name.trim();
        let Some(load) = model.loads.iter().find(|l| l.name == name) else {
            let names: Vec<&str> = model.loads.iter().map(|l| l.name.as_str()).collect();
            return Err(Failure::usage(format!(
                "no load named `{name}`: the mechanism's loads are {}",
                if names.is_empty() {
                    "none".into()
                } else {
                    names.join(", ")
                }
            )));
        };
        let (dim, what, unit) = match load.kind {
            LoadKind::Force { body, point } => (
                Dim::FORCE,
                format!(
                    "a force on `{}` at `{}`",
                    model.bodies[body].name, model.points[point].0
                ),
                "`fx,fy,fz` (N)",
            ),
            LoadKind::Torque { body } => (
                Dim::TORQUE,
                format!("a torque on `{}`", model.bodies[body].name),
                "`mx,my,mz` (N·m)",
            ),
        };
        if let Some(path) = value.trim_start().strip_prefix('@') {
            let flag = format!("--load {name}");
            tables.push((name.to_string(), crate::loads::Table::read(path, 3, &flag)?));
            continue;
        }
        let parts: Vec<&str> = value.split(',').collect();
        if parts.len() != 3 {
            let example = parts
                .iter()
                .map(|p| p.trim())
                .chain(std::iter::repeat("0"))
                .take(3)
                .collect::<Vec<_>>()
                .join(",");
            return Err(Failure::usage(format!(
                "--load {name}: `{value}` has {} component(s), but `{name}` is {what} of a spatial mechanism: give three components {unit} in the global axes, e.g. `--load {name}={example}`",
                parts.len()
            )));
        }
        let v: Vec<f64> = parts
            .iter()
            .map(|p| quantity::parse(p, dim, &format!("--load {name}")))
            .collect::<Result<_, _>>()?;
        loads.set_by_name(name, &v);
    }
    Ok(SpatialLoadSet {
        constant: loads,
        tables,
    })
}

/// The loads of a spatial run: the constants of `--load NAME=x,y,z` and the tables of
/// `--load NAME=@file.csv` (columns q, then the three components in SI, N or N·m, linear
/// between rows and repeating with the table's span, as the planar tables).
#[derive(Debug)]
pub struct SpatialLoadSet {
    constant: SpatialLoads,
    tables: Vec<(String, crate::loads::Table)>,
}

impl SpatialLoadSet {
    /// The loads at the first input's value `q`.
    pub fn at(&self, q: f64) -> SpatialLoads {
        let mut loads = self.constant.clone();
        for (name, table) in &self.tables {
            loads.set_by_name(name, &table.at(q));
        }
        loads
    }
}

/// `mech solve` of a spatial mechanism: one configuration in `format` (`table`: one
/// quantity a line with its unit).
#[allow(clippy::too_many_arguments)]
pub fn solve(
    m: &SpatialMechanism,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    loads: &SpatialLoads,
    level: Level,
    format: Format,
    out: impl Write,
) -> Result<(), Failure> {
    let cols = SpatialColumns::new(m, level.parts());
    let row = cols.row(m, q, qd, qdd, loads)?;
    if format == Format::Table {
        let mut out = out;
        let w = cols.names.iter().map(String::len).max().unwrap_or(1);
        for ((n, u), v) in cols.names.iter().zip(&cols.units).zip(&row) {
            writeln!(out, "{n:<w$}  {v:>20.12e}  {u}")?;
        }
        out.flush()?;
        return Ok(());
    }
    let mut w = Writer::new(out, format, &cols.names, &cols.units)?;
    w.row(&row)?;
    w.finish()?;
    Ok(())
}

/// `mech sweep` of a spatial mechanism: the first input from `from` to `to` in `steps`
/// steps, the others at `rest[1..]`, one row per input, in order (serially: each position
/// is continued from the drawing).
#[allow(clippy::too_many_arguments)]
pub fn sweep(
    m: &SpatialMechanism,
    (from, to, steps): (f64, f64, usize),
    rest: &[f64],
    qd: &[f64],
    qdd: &[f64],
    loads: &SpatialLoadSet,
    level: Level,
    format: Format,
    out: impl Write,
) -> Result<(), Failure> {
    let cols = SpatialColumns::new(m, level.parts());
    let mut w = Writer::new(out, format, &cols.names, &cols.units)?;
    let mut q = rest.to_vec();
    for k in 0..=steps {
        q[0] = crate::solve::inputs(from, to, steps, k);
        let row = cols
            .row(m, &q, qd, qdd, &loads.at(q[0]))
            .map_err(|e| Failure::mechanism(format!("at q = {}: {e}", q[0])))?;
        w.row(&row)?;
    }
    w.finish()?;
    Ok(())
}

/// The isometric projection of a point (m): the view from (1, 1, 1) towards the origin,
/// z up: X = (y − x)/√2, Y = (2z − x − y)/√6 (the x axis to the lower left, y to the lower
/// right).
pub fn isometric(p: Vector3<f64>) -> V2 {
    V2::new(
        (p.y - p.x) / std::f64::consts::SQRT_2,
        (2.0 * p.z - p.x - p.y) / 6f64.sqrt(),
    )
}

/// The shapes of `m` at `q` in the isometric projection ([`isometric`]): the global axes
/// (three guide lines labelled `x`, `y`, `z` at the drawing's lowest corner), each moving
/// link (a bar between its two points, a plate through its points taken in turn about
/// their centre), a pin at each joint,
/// the points' names.
pub fn frame(m: &SpatialMechanism, q: &[f64]) -> Result<Frame, Failure> {
    let model = m.model();
    let pose = m.pose(q)?;
    let at: Vec<Vector3<f64>> = model
        .points
        .iter()
        .map(|(p, _)| {
            pose.point(p)
                .ok_or_else(|| Failure::mechanism(format!("the point `{p}` belongs to no link")))
        })
        .collect::<Result<_, _>>()?;
    // The axes at the drawing's lowest corner (not the pose's: they stay put in an animation).
    let drawn = model.points.iter().map(|(_, p)| *p);
    let (mut lo, mut hi) = (model.points[0].1, model.points[0].1);
    for p in drawn {
        lo = lo.inf(&p);
        hi = hi.sup(&p);
    }
    let size = (hi - lo).max().max(1e-6);
    let mut shapes = Vec::new();
    for (axis, name) in [
        (Vector3::x(), "x"),
        (Vector3::y(), "y"),
        (Vector3::z(), "z"),
    ] {
        let tip = lo + axis * 0.2 * size;
        shapes.push(Shape {
            role: Role::Guide,
            name: format!("axis {name}"),
            points: vec![isometric(lo), isometric(tip)],
        });
        shapes.push(Shape {
            role: Role::Label,
            name: name.to_string(),
            points: vec![isometric(tip)],
        });
    }
    for b in &model.bodies[1..] {
        let mut points: Vec<V2> = b.points.iter().map(|&p| isometric(at[p])).collect();
        if points.len() > 2 {
            // A plate: its points in turn about their centre (a simple polygon).
            let c = points.iter().fold(V2::zeros(), |s, p| s + p) / points.len() as f64;
            points.sort_by(|p, q| {
                let angle = |v: &V2| (v.y - c.y).atan2(v.x - c.x);
                angle(p).total_cmp(&angle(q))
            });
        }
        let role = match points.len() {
            0 | 1 => continue,
            2 => Role::Bar,
            _ => Role::Plate,
        };
        shapes.push(Shape {
            role,
            name: b.name.clone(),
            points,
        });
    }
    for j in &model.joints {
        shapes.push(Shape {
            role: Role::Pin,
            name: j.name.clone(),
            points: vec![isometric(at[j.point])],
        });
    }
    for (k, (p, _)) in model.points.iter().enumerate() {
        shapes.push(Shape {
            role: Role::Label,
            name: p.clone(),
            points: vec![isometric(at[k]) + V2::new(0.02, 0.02) * size],
        });
    }
    Ok(Frame {
        q: q.to_vec(),
        shapes,
    })
}

/// The size of `m`'s drawing (m): the largest distance between two of its points as
/// drawn.
pub fn size(m: &SpatialMechanism) -> f64 {
    let points = &m.model().points;
    points
        .iter()
        .flat_map(|(_, a)| points.iter().map(move |(_, b)| (a - b).norm()))
        .fold(0.0, f64::max)
}

/// The default range of the first input, for `mech draw --path` and `mech animate`: a turn
/// (0 to 2π) for a revolute or helical input, ± a tenth of the drawing's size ([`size`])
/// for a prismatic one.
pub fn default_range(m: &SpatialMechanism) -> (f64, f64) {
    if input_dims(m, 0).0 == Dim::ANGLE {
        (0.0, std::f64::consts::TAU)
    } else {
        let s = 0.1 * size(m);
        (-s, s)
    }
}

/// The path of the point `name` over `qs` in the isometric projection ([`isometric`]): its
/// position at each input that assembles.
pub fn path(m: &SpatialMechanism, name: &str, qs: &[Vec<f64>]) -> Result<Shape, Failure> {
    let model = m.model();
    if model.point_index(name).is_none() {
        let names = model.points.iter().map(|(p, _)| p.as_str());
        return Err(crate::scene::no_such_point(name, names));
    }
    let points = qs
        .iter()
        .filter_map(|q| m.pose(q).ok()?.point(name))
        .map(isometric)
        .collect();
    Ok(Shape {
        role: Role::Path,
        name: name.to_string(),
        points,
    })
}

/// The reaction arrows of `m` at (q, q̇, q̈) under `loads`, in the isometric projection: at
/// each joint's current point p, the force F by the joint's first link on its second, from
/// p to p + F·s projected ([`isometric`]), s such that the largest force is `length` m in
/// space. No arrow when every reaction is zero.
pub fn arrows(
    m: &SpatialMechanism,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    loads: &SpatialLoads,
    length: f64,
) -> Result<Vec<Shape>, Failure> {
    let motion = m.kinematics(q, qd, qdd)?;
    let forces = m.kinetostatics(&motion, loads)?;
    let norms = forces.reactions.iter().map(|r| r.force.norm());
    let Some(scale) = crate::scene::arrow_scale(norms, length) else {
        return Ok(Vec::new());
    };
    m.model()
        .joints
        .iter()
        .zip(&forces.reactions)
        .map(|(j, r)| {
            let [p, _, _] = motion.point_motion_at(j.point).ok_or_else(|| {
                Failure::mechanism(format!("the joint `{}`'s point belongs to no link", j.name))
            })?;
            Ok(Shape {
                role: Role::Arrow,
                name: j.name.clone(),
                points: vec![isometric(p), isometric(p + r.force * scale)],
            })
        })
        .collect()
}

/// `mech draw` of a spatial mechanism: the isometric picture of [`frame`] at `--at`, with
/// the `--path` of each point over the first input's [`default_range`] (361 values, the
/// other inputs at `--at`) and, with `--forces`, the reaction arrows ([`arrows`]) at
/// `--speed`, `--accel` and `--load`, the largest a quarter of the drawing's size. The SVG
/// text.
pub fn draw(m: &SpatialMechanism, args: &crate::draw::DrawArgs) -> Result<String, Failure> {
    let q = per_input(&args.at, m, 0, "--at", 0.0)?;
    let frame = frame(m, &q)?;
    let mut extra = Vec::new();
    if !args.path.is_empty() {
        let (a, b) = default_range(m);
        let turn = crate::draw::range(&q, a, b, 360);
        for p in &args.path {
            extra.push(path(m, p, &turn)?);
        }
    }
    if args.forces {
        let qd = per_input(&args.speed, m, 1, "--speed", 0.0)?;
        let qdd = per_input(&args.accel, m, 2, "--accel", 0.0)?;
        let loads = loads(&args.load, m)?.at(q[0]);
        extra.extend(arrows(m, &q, &qd, &qdd, &loads, 0.25 * size(m))?);
    }
    Ok(svg::still(&frame, &extra, args.width, args.height).0)
}

/// `mech animate` of a spatial mechanism: the isometric picture of [`frame`] at `frames`
/// values of the first input from `from` to `to` (defaults: [`default_range`]), the other
/// inputs at `rest`, with the `--path` of each point over those values under it; a value
/// where it does not assemble shows the last one that did. The SVG text.
pub fn animate(m: &SpatialMechanism, args: &crate::draw::AnimateArgs) -> Result<String, Failure> {
    let (d, _) = input_dims(m, 0);
    let (a0, b0) = default_range(m);
    let bound = |t: &Option<String>, default: f64, what: &str| match t {
        Some(t) => quantity::parse(t, d, what),
        None => Ok(default),
    };
    let (a, b) = (
        bound(&args.from, a0, "--from")?,
        bound(&args.to, b0, "--to")?,
    );
    if !(b - a).is_finite() {
        return Err(Failure::usage(
            "--from and --to: the range overflows f64; give a narrower range",
        ));
    }
    if args.rest.len() + 1 != m.dof() {
        return Err(Failure::usage(format!(
            "--rest: {} value(s) for the {} input(s) after the first",
            args.rest.len(),
            m.dof() - 1
        )));
    }
    let mut q = vec![a];
    for (k, t) in args.rest.iter().enumerate() {
        q.push(quantity::parse(t, input_dims(m, k + 1).0, "--rest")?);
    }
    let qs = crate::draw::range(&q, a, b, args.frames - 1);
    let frames = crate::scene::held(qs.iter().map(|q| frame(m, q).ok()).collect())?;
    let extra: Vec<Shape> = args
        .path
        .iter()
        .map(|p| path(m, p, &qs))
        .collect::<Result<_, _>>()?;
    Ok(svg::animated(&frames, &extra, args.width, args.height, args.seconds).0)
}
