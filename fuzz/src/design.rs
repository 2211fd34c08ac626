//! The design tools of a case: every cam's profile (the `mech cam` path), the equivalent
//! mass systems of the links, and one parameter of the drawing changed by `set_param`.

use crate::exercise::{loads, Case, Finding, PARAMS};
use mech_core::model::JointKind;
use mech_core::{MechError, Mechanism};

/// Every cam's profile (the `mech cam` path): its table, its design figures, its points
/// and its law far from the drawing. Where the profile exists (`missing` is `None`)
/// every number is finite.
pub fn cams(c: &mut Case, m: &Mechanism) {
    for (_, geom) in m.cams() {
        let p = &geom.profile;
        c.numbers("cam frame", &[geom.axis, geom.centre]);
        c.numbers(
            "cam profile numbers",
            &[p.base_radius, p.offset, p.roller()],
        );
        let Some(check) = c.call("cam check", || p.check(36)) else {
            continue;
        };
        c.numbers("cam check", &check);
        for theta in [1e6, -1e15, 1e300] {
            if let Some(s) = c.call("cam law", || p.law.eval(theta)) {
                c.numbers("cam law far from the drawing", &s);
            }
        }
        if let Some(j) = c.call("cam jumps", || p.law.jumps(1e-9)) {
            let numbers: Vec<[f64; 3]> = j.iter().map(|j| [j.at, j.before, j.after]).collect();
            c.numbers("cam jumps", &numbers);
        }
        if check.missing.is_some() {
            continue;
        }
        if let Some(t) = c.call("cam table", || p.table(36)) {
            c.numbers("cam table", &t);
        }
        if let Some(pts) = c.call("cam points", || p.points(12)) {
            c.numbers("cam points", &pts);
        }
    }
}

/// The equivalent mass systems of every moving link with a mass: its mass and inertia
/// shared between its cg and its first two points.
pub fn equivalent_masses(c: &mut Case, m: &Mechanism) {
    use mech_core::dynamics::equivalent_mass as eq;
    let model = m.model();
    for link in model.links.iter().skip(1) {
        let (Some(mass), [a, b, ..]) = (link.mass, link.points.as_slice()) else {
            continue;
        };
        let r = |p: usize| {
            let [x, y] = model.points[p].pos;
            (x - link.cg[0]).hypot(y - link.cg[1])
        };
        let i_g = link.inertia;
        if let Some(e) = c.attempt("bar_three_masses", || {
            eq::bar_three_masses(mass, i_g, r(*a), r(*b))
        }) {
            c.numbers("bar_three_masses", &[e.at_a, e.at_b, e.at_g]);
        }
        c.solve("bar_two_masses_static", || {
            eq::bar_two_masses_static(mass, r(*a), r(*b))
        });
        c.solve("bar_two_masses_complete", || {
            eq::bar_two_masses_complete(mass, i_g, r(*a))
        });
        let pts = [model.points[*a].pos, model.points[*b].pos, link.cg];
        c.solve("planar_four_masses", || {
            eq::planar_four_masses(mass, i_g, pts)
        });
    }
}

/// One parameter of the drawing changed by `set_param` (the run-time `from_params`) to
/// a hostile number chosen by `pick`; when it is accepted, the new mechanism's pose and
/// kinematics.
pub fn parameter(c: &mut Case, m: &Mechanism, pick: u64) {
    let model = m.model();
    let mut paths: Vec<(String, usize)> = vec![("gravity".into(), 2)];
    paths.extend(
        model
            .points
            .iter()
            .map(|p| (format!("points.{}", p.name), 2)),
    );
    for l in model.links.iter().skip(1) {
        paths.push((format!("links.{}.cg", l.name), 2));
        for what in ["mass", "inertia", "flywheel"] {
            paths.push((format!("links.{}.{what}", l.name), 1));
        }
    }
    for j in &model.joints {
        if j.kind != JointKind::Revolute {
            paths.push((format!("axes.{}", j.name), 2));
        }
    }
    for e in &model.elements {
        for what in ["stiffness", "free_length", "free_angle", "damping"] {
            paths.push((format!("elements.{}.{what}", e.name), 1));
        }
    }
    let (path, n) = &paths[(pick % paths.len() as u64) as usize];
    let x = PARAMS[((pick >> 16) % PARAMS.len() as u64) as usize];
    let value = [x, 0.25 * x + 0.1][..*n].to_vec();
    c.at = format!(" after set_param({path}, {value:?})");
    let mut changed = m.clone();
    let Some(r) = c.call("set_param", || changed.set_param(path, &value)) else {
        return;
    };
    match r {
        Ok(()) if !x.is_finite() => c.found.push(Finding::NonFinite(format!(
            "set_param{}: Ok for a non-finite value",
            c.at
        ))),
        Ok(()) => {
            let g = changed.dof();
            c.solve("pose", || changed.pose(&vec![0.3; g]));
            if let Some(mo) = c.solve("kinematics", || {
                changed.kinematics(&vec![0.3; g], &vec![2.0; g], &vec![0.0; g])
            }) {
                c.solve("driver_action", || {
                    changed.driver_action(&mo, &loads(&changed, 1e3))
                });
            }
        }
        Err(MechError::Internal(e)) => c
            .found
            .push(Finding::Panic(format!("set_param{}: {e}", c.at))),
        Err(_) => {}
    }
}
