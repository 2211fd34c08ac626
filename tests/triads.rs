//! Triad machines (issue 35; `tests/common/triads.rs`): the generated solvers, whose triad
//! goes through `mech_core::kernel::triad` (one eliminated unknown), against the oracle's
//! dense Newton continued from the drawing and the run-time `Mechanism`, over a full turn
//! of the crank; continuity on the drawn assembly; `NoAssembly` past a dead point; and no
//! allocation.

#[path = "common/triads.rs"]
mod triads;

use crate::counting;
use crate::measure::within;
use mech::prelude::*;
use mech_oracle::GenericMechanism;
use triads::*;

/// The text the macro compiled.
const TRIADS: &str = include_str!("common/triads.rs");

/// The drawing's crank angle of a machine whose crank runs from point `o` to point `a`.
fn q0(o: Vector2<f64>, a: Vector2<f64>) -> f64 {
    let d = a - o;
    d.y.atan2(d.x)
}

/// The generated pose, the run-time `Mechanism`'s and the oracle's (dense Newton continued
/// from the drawing: the drawn assembly) agree at 72 crank angles over a full turn, to
/// 1e-12 of the drawing's size; and so do the velocities.
macro_rules! agrees {
    ($test:ident, $ty:ident, $name:literal, $o:ident, $a:ident) => {
        #[test]
        fn $test() {
            let m = $ty::new();
            let oracle = GenericMechanism::from_rust_source(TRIADS, $name).unwrap();
            let runtime = mech::Mechanism::from_rust_source(TRIADS, $name).unwrap();
            let p = m.params();
            let start = q0(p.points.$o, p.points.$a);
            let size = $ty::POINT_NAMES
                .iter()
                .map(|n| m.pose(start).unwrap().point(n).unwrap().pos.norm())
                .fold(0.0, f64::max);
            for k in 0..72 {
                let q = start + std::f64::consts::TAU * k as f64 / 72.0;
                let gen = m.pose(q).unwrap();
                let want = oracle.pose(&[q]).unwrap();
                let rt = runtime.pose(&[q]).unwrap();
                let mo = m.kinematics(q, 2.0, -1.0).unwrap();
                let wk = oracle.kinematics(&[q], &[2.0], &[-1.0]).unwrap();
                for n in $ty::POINT_NAMES {
                    let g = gen.point(n).unwrap().pos;
                    let d = (g - want.point(n).unwrap().pos).norm() / size;
                    assert!(within(d, 1e-12), "{n} at step {k}: {d:e} from the oracle");
                    let d = (g - rt.point(n).unwrap().pos).norm() / size;
                    assert!(within(d, 1e-12), "{n} at step {k}: {d:e} from the run time");
                    let (v, w) = (mo.point(n).unwrap().vel, wk.point(n).unwrap().vel);
                    let d = (v - w).norm() / (2.0 * size);
                    assert!(within(d, 1e-11), "{n} at step {k}: velocity {d:e}");
                }
            }
        }
    };
}

agrees!(
    stephenson3_agrees_with_the_oracle,
    StephensonIII,
    "StephensonIII",
    P0,
    P1
);
agrees!(
    stephenson2_agrees_with_the_oracle,
    Stephenson2,
    "Stephenson2",
    O,
    E
);

/// A whole turn in 1° steps stays on the drawn assembly: every point moves by no more than
/// its speed and acceleration allow over the step, and comes back to where it started
/// (as `kinematics::continuity` for the dyad chains).
macro_rules! continuity {
    ($test:ident, $ty:ident, $o:ident, $a:ident) => {
        #[test]
        fn $test() {
            let m = $ty::new();
            let p = m.params();
            let start = q0(p.points.$o, p.points.$a);
            let dq = std::f64::consts::TAU / 360.0;
            let mut prev = m.pose(start).unwrap();
            let mut prev_speed = m.kinematics(start, 1.0, 0.0).unwrap();
            let first = prev;
            for k in 1..=360 {
                let q = start + dq * k as f64;
                let now = m.pose(q).unwrap();
                let speed = m.kinematics(q, 1.0, 0.0).unwrap();
                for n in $ty::POINT_NAMES {
                    let step = (now.point(n).unwrap().pos - prev.point(n).unwrap().pos).norm();
                    let (s0, s1) = (prev_speed.point(n).unwrap(), speed.point(n).unwrap());
                    let v = s0.vel.norm().max(s1.vel.norm());
                    let a = s0.acc.norm().max(s1.acc.norm());
                    let bound = 1.01 * (v * dq + a * dq * dq) + 1e-12;
                    assert!(step <= bound, "{n} jumps {step} > {bound} at step {k}");
                }
                prev = now;
                prev_speed = speed;
            }
            for n in $ty::POINT_NAMES {
                let back = (prev.point(n).unwrap().pos - first.point(n).unwrap().pos).norm();
                assert!(within(back, 1e-14), "{n} back to the start: {back:e}");
            }
        }
    };
}

continuity!(continuity_stephenson3, StephensonIII, P0, P1);
continuity!(continuity_stephenson2, Stephenson2, O, E);

/// A crank too long for the triad (its pin moved out to 2.2× its length): past the dead
/// points the pose is `NoAssembly`, never a panic or a NaN; where it assembles it is the
/// oracle's (continued from the drawing, up to where the oracle stops).
#[test]
fn past_a_dead_point_no_assembly() {
    let mut p = StephensonIIIParams::default();
    p.points.P1 = p.points.P0 + (p.points.P1 - p.points.P0) * 2.2;
    let m = StephensonIII::from_params(p.clone()).unwrap();
    let start = q0(p.points.P0, p.points.P1);
    let (mut ok, mut none) = (0, 0);
    for k in 0..=360 {
        let q = start + std::f64::consts::TAU * k as f64 / 360.0;
        match m.pose(q) {
            Ok(pose) => {
                ok += 1;
                for n in StephensonIII::POINT_NAMES {
                    let x = pose.point(n).unwrap().pos;
                    assert!(x.x.is_finite() && x.y.is_finite(), "{n} at step {k}");
                }
            }
            Err(e) => {
                assert_eq!(e, MechError::NoAssembly, "step {k}");
                none += 1;
            }
        }
        assert!(
            m.kinematics(q, 1.0, 0.0).is_ok() == m.pose(q).is_ok(),
            "step {k}"
        );
    }
    assert!(ok > 0 && none > 0, "{ok} assembled, {none} not");
}

/// Zero heap allocations in every solver of the triad machines (the elimination and its
/// fallback are on the stack).
#[test]
fn triad_solvers_do_not_allocate() {
    fn count<R>(f: impl FnOnce() -> R) -> (usize, R) {
        let before = counting::count();
        let r = f();
        (counting::count() - before, r)
    }
    macro_rules! no_alloc {
        ($ty:ident, $loads:ident) => {{
            let m = $ty::new();
            let mut loads = $loads::default();
            assert!(loads.set_by_name("load", &[3.0, -2.0]));
            assert!(loads.set_by_name("resist", &[0.5]));
            for q in [0.4, 2.5, 4.0] {
                let (n, p) = count(|| m.pose(q));
                p.unwrap();
                assert_eq!(n, 0, "pose allocated");
                let (n, mo) = count(|| m.kinematics(q, 3.0, -2.0));
                let mo = mo.unwrap();
                assert_eq!(n, 0, "kinematics allocated");
                let (n, f) = count(|| m.kinetostatics(&mo, &loads));
                f.unwrap();
                assert_eq!(n, 0, "kinetostatics allocated");
                let (n, d) = count(|| m.driver_action(&mo, &loads));
                d.unwrap();
                assert_eq!(n, 0, "driver_action allocated");
                let (n, r) = count(|| m.reduced(q));
                r.unwrap();
                assert_eq!(n, 0, "reduced allocated");
            }
        }};
    }
    no_alloc!(StephensonIII, StephensonIIILoads);
    no_alloc!(Stephenson2, Stephenson2Loads);
}

/// A sweep of the run-time `Mechanism` in 1° steps through the rows of `mech sweep`
/// (`Columns::rows_many`), where each triad starts from the previous row's configuration
/// (`runtime::warm`), and the batched forms (`pose_many`, `points_many`, `kinematics_many`,
/// `reduced_many`, `acceleration_many`), which do not: each of their configurations is one
/// call's, failures included, to 1e-12 of the size. On both machines as drawn the sweep's
/// rows are one call's too, and every point moves from the previous row by no more than
/// its speed and acceleration allow (the assembly continued). With a crank too long for
/// the triad (2.2×, dead points on the turn) one call from the drawing fails at some
/// configurations where the triad assembles and, past the dead points, lands on another
/// assembly of the same determinant sign at others; the sweep solves wherever one call
/// does, and every link of every row it solves keeps its drawing's lengths (1e-12).
#[test]
fn a_warm_sweep_follows_the_drawn_assembly() {
    use mech::columns::{Columns, Part};
    use std::borrow::Cow;
    let p3 = StephensonIII::new().params().points.clone();
    let p2 = Stephenson2::new().params().points.clone();
    for (name, o, a, pa, stretch) in [
        ("StephensonIII", p3.P0, p3.P1, "P1", 1.0),
        ("Stephenson2", p2.O, p2.E, "E", 1.0),
        ("StephensonIII", p3.P0, p3.P1, "P1", 2.2),
    ] {
        let mut m = mech::Mechanism::from_rust_source(TRIADS, name).unwrap();
        if stretch != 1.0 {
            let far = o + (a - o) * stretch;
            m.set_param(&format!("points.{pa}"), &[far.x, far.y])
                .unwrap();
        }
        let start = q0(o, a);
        let dq = std::f64::consts::TAU / 360.0;
        let q: Vec<f64> = (0..=360).map(|k| start + dq * k as f64).collect();
        let (qd, qdd) = (vec![1.0; q.len()], vec![0.0; q.len()]);
        let model = m.model().clone();
        let np = model.points.len();
        let drawing = m.pose(&[start]).unwrap();
        let size = drawing
            .points
            .iter()
            .map(|p| p.pos.norm())
            .fold(0.0, f64::max);
        // The batched forms.
        let mut poses = vec![m.nan_pose(); q.len()];
        let e_pose = m.pose_many(&q, &mut poses);
        let mut points = vec![0.0; 2 * np * q.len()];
        let e_points = m.points_many(&q, &mut points);
        let mut kin = m.kinematics_table(q.len());
        let e_kin = m.kinematics_many(&q, &qd, &qdd, &mut kin);
        let (mut inertia, mut slope, mut qdd_many) =
            (vec![0.0; q.len()], vec![0.0; q.len()], vec![0.0; q.len()]);
        let e_red = m.reduced_many(&q, &mut inertia, &mut slope);
        let driver = vec![0.7; q.len()];
        let loads = m.loads();
        let e_acc = m.acceleration_many(&q, &qd, &driver, &loads, &mut qdd_many);
        // The sweep's rows: positions and rates.
        let cols = Columns::new(&m, &[Part::Inputs, Part::Positions, Part::Rates]);
        let width = cols.names.len();
        let mut rows = vec![0.0; width * q.len()];
        let e_rows = cols.rows_many(&m, &q, &qd, &qdd, &|_| Cow::Borrowed(&loads), &mut rows);
        let col = |n: &str| cols.names.iter().position(|c| c == n).unwrap();
        let row = |i: usize, n: &str, x: &str, y: &str| {
            Vector2::new(
                rows[width * i + col(&format!("{n}.{x}"))],
                rows[width * i + col(&format!("{n}.{y}"))],
            )
        };
        let kin_at = |n: &str, c: &str, i: usize| kin.get(&format!("{n}.{c}"), i).unwrap();
        let scale = |v: &[f64]| v.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
        let (mut failed, mut other, mut jumps) = (0, 0, 0);
        for (i, &qi) in q.iter().enumerate() {
            let one = m.pose(&[qi]);
            // Each batched configuration is one call's.
            for e in [&e_pose, &e_points, &e_kin, &e_red, &e_acc] {
                assert_eq!(
                    e.get(i).is_some(),
                    one.is_err(),
                    "{name} ×{stretch} at step {i}"
                );
            }
            if let Ok(one) = &one {
                for (k, pt) in one.points.iter().enumerate() {
                    let n = &model.points[k].name;
                    for b in [
                        poses[i].points[k].pos,
                        Vector2::new(points[2 * (np * i + k)], points[2 * (np * i + k) + 1]),
                        Vector2::new(kin_at(n, "x", i), kin_at(n, "y", i)),
                    ] {
                        let d = (b - pt.pos).norm() / size;
                        assert!(within(d, 1e-12), "{name} {n} at step {i}: {d:e}");
                    }
                }
                let z = OneDof::reduced(&m, qi).unwrap();
                let a = OneDof::acceleration(&m, qi, 1.0, 0.7, &loads).unwrap();
                for (x, y, all) in [
                    (inertia[i], z.inertia, &inertia),
                    (slope[i], z.inertia_derivative, &slope),
                    (qdd_many[i], a, &qdd_many),
                ] {
                    let d = (x - y).abs() / scale(all);
                    assert!(within(d, 1e-12), "{name} at step {i}: {x} vs {y}");
                }
            }
            // The sweep solves wherever one call does.
            if e_rows.get(i).is_some() {
                assert!(
                    one.is_err(),
                    "{name} ×{stretch} at step {i}: the sweep failed"
                );
                failed += 1;
                continue;
            }
            let at = |k: usize| row(i, &model.points[k].name, "x", "y");
            // Rigid links: each link's points keep their drawing's distances.
            for link in &model.links {
                for (x, &j) in link.points.iter().enumerate() {
                    for &k in &link.points[x + 1..] {
                        let want = (drawing.points[j].pos - drawing.points[k].pos).norm();
                        let d = ((at(j) - at(k)).norm() - want).abs() / size;
                        assert!(
                            within(d, 1e-12),
                            "{name} at step {i}: a link stretched {d:e}"
                        );
                    }
                }
            }
            // Continued from the previous row when that one solved.
            if i > 0 && e_rows.get(i - 1).is_none() {
                for k in 0..np {
                    let n = &model.points[k].name;
                    let step = (at(k) - row(i - 1, n, "x", "y")).norm();
                    let v = [i - 1, i].map(|j| row(j, n, "vx", "vy").norm());
                    let acc = [i - 1, i].map(|j| row(j, n, "ax", "ay").norm());
                    let bound = 1.01 * (v[0].max(v[1]) * dq + acc[0].max(acc[1]) * dq * dq);
                    if stretch == 1.0 {
                        assert!(
                            step <= bound + 1e-12,
                            "{name} {n}: {step} > {bound} at step {i}"
                        );
                    } else if step > bound + 1e-12 {
                        jumps += 1;
                    }
                }
            }
            // One call from the drawing: the same root on the machines as drawn.
            let same = one.as_ref().is_ok_and(|one| {
                (0..np).all(|k| (one.points[k].pos - at(k)).norm() <= 1e-12 * size)
            });
            if stretch == 1.0 {
                assert!(same, "{name} at step {i}: {one:?}");
            } else if !same {
                other += 1;
            }
        }
        assert_eq!(
            failed > 0,
            stretch != 1.0,
            "{name} ×{stretch}: {failed} failed"
        );
        eprintln!(
            "{name} ×{stretch}: {failed} of 361 rows not assembled; one call elsewhere at {other}; \
             {jumps} point moves beyond the step's bound"
        );
    }
}
