//! The check shared by `tests/generic.rs` (the dense generic solver) and
//! `tests/mechanism.rs` (the run-time `mech::Mechanism`): a solver loaded at run time from
//! the text of `tests/common/mechanisms.rs` agrees with the generated struct and with the
//! 50-digit table `tests/data/<name>.truth.json`, on every quantity, to the tolerances of
//! `tests/support/mod.rs` (`tol`: per kind, at most 100× the worst error measured).
//! A module of the suite, declared after `support` with `#[macro_use]`; a module using
//! `generic_test!` imports `motion_agrees` and `support::*` and defines `fn generic(name)`
//! returning the solver under test.

use crate::support::Kinds;
use mech::prelude::*;

/// A run-time motion: its links' and points' motion by name.
pub trait Solved {
    fn link(&self, name: &str) -> Option<&LinkMotion>;
    fn point(&self, name: &str) -> Option<&PointMotion>;
}

impl Solved for mech_oracle::GenericMotion {
    fn link(&self, name: &str) -> Option<&LinkMotion> {
        mech_oracle::GenericMotion::link(self, name)
    }
    fn point(&self, name: &str) -> Option<&PointMotion> {
        mech_oracle::GenericMotion::point(self, name)
    }
}

impl Solved for mech_core::runtime::Motion {
    fn link(&self, name: &str) -> Option<&LinkMotion> {
        mech_core::runtime::Motion::link(self, name)
    }
    fn point(&self, name: &str) -> Option<&PointMotion> {
        mech_core::runtime::Motion::point(self, name)
    }
}

/// Compare the generic motion with the reference table and with the generated motion.
pub fn motion_agrees<L, P>(
    ctx: &str,
    k: &Kinds,
    c: &serde_json::Value,
    gm: &impl Solved,
    gen_link: impl Fn(&str) -> Option<L>,
    gen_point: impl Fn(&str) -> Option<P>,
) where
    L: std::ops::Deref<Target = LinkMotion>,
    P: std::ops::Deref<Target = PointMotion>,
{
    for (lname, lt) in c["links"].as_object().unwrap() {
        let lm = gm
            .link(lname)
            .unwrap_or_else(|| panic!("{ctx}: no link {lname}"));
        let gl = gen_link(lname).unwrap();
        let ctx = format!("{ctx} link {lname}");
        k.angle(
            &ctx,
            "generic vs truth",
            lm.angle,
            lt["theta"].as_f64().unwrap(),
        );
        k.angle(&ctx, "generic vs generated", lm.angle, gl.angle);
        k.close(
            &ctx,
            "omega",
            lm.omega,
            lt["omega"].as_f64().unwrap(),
            k.omega,
        );
        k.close(&ctx, "omega vs generated", lm.omega, gl.omega, k.omega);
        k.close(
            &ctx,
            "alpha",
            lm.alpha,
            lt["alpha"].as_f64().unwrap(),
            k.alpha,
        );
        k.close(&ctx, "alpha vs generated", lm.alpha, gl.alpha, k.alpha);
        k.vec(&ctx, "cg", lm.cg, &lt["cg"]["pos"], k.pos);
        k.vec(&ctx, "cg_vel", lm.cg_vel, &lt["cg"]["vel"], k.vel);
        k.vec(&ctx, "cg_acc", lm.cg_acc, &lt["cg"]["acc"], k.acc);
        for (what, a, b, s) in [
            ("cg", lm.cg, gl.cg, k.pos),
            ("cg_vel", lm.cg_vel, gl.cg_vel, k.vel),
            ("cg_acc", lm.cg_acc, gl.cg_acc, k.acc),
        ] {
            k.close(&ctx, &format!("{what}.x vs generated"), a.x, b.x, s);
            k.close(&ctx, &format!("{what}.y vs generated"), a.y, b.y, s);
        }
        for (pname, pt) in lt["points"].as_object().unwrap() {
            let pm = gm.point(pname).unwrap();
            let gp = gen_point(pname).unwrap();
            k.vec(&ctx, pname, pm.pos, &pt["pos"], k.pos);
            k.vec(&ctx, pname, pm.vel, &pt["vel"], k.vel);
            k.vec(&ctx, pname, pm.acc, &pt["acc"], k.acc);
            for (what, a, b, s) in [
                ("pos", pm.pos, gp.pos, k.pos),
                ("vel", pm.vel, gp.vel, k.vel),
                ("acc", pm.acc, gp.acc, k.acc),
            ] {
                k.close(&ctx, &format!("{pname}.{what}.x vs generated"), a.x, b.x, s);
                k.close(&ctx, &format!("{pname}.{what}.y vs generated"), a.y, b.y, s);
            }
        }
    }
}

#[macro_export]
macro_rules! generic_test {
    ($test:ident, $ty:ident, $loads:ident, $file:literal, $q:expr, one_dof = $one:tt) => {
        #[test]
        fn $test() {
            let t = truth($file);
            let gen = $ty::new();
            let g = generic(stringify!($ty));
            assert_eq!(g.dof(), $ty::DOF);
            assert_eq!(g.model().n_links(), $ty::LINKS);
            let mut loads = $loads::default();
            let mut gloads = g.loads();
            for (name, l) in t["loads"].as_object().unwrap() {
                assert!(loads.set_by_name(name, &nums(&l["value"])), "load {name}");
                assert!(gloads.set_by_name(name, &nums(&l["value"])), "generic load {name}");
            }
            let to_q = $q;
            for c in t["configs"].as_array().unwrap() {
                let (qv, qdv, qddv) = (nums(&c["q"]), nums(&c["qd"]), nums(&c["qdd"]));
                let (q, qd, qdd) = (to_q(&qv), to_q(&qdv), to_q(&qddv));
                let ctx = format!("{} config {}", $file, c["index"]);
                let k = Kinds::of(c);

                let mo = gen.kinematics(q, qd, qdd).unwrap();
                let gm = g.kinematics(&qv, &qdv, &qddv).unwrap_or_else(|e| panic!("{ctx}: {e}"));
                motion_agrees(&ctx, &k, c, &gm, |n| mo.link(n), |n| mo.point(n));
                let gp = g.pose(&qv).unwrap();
                for (lname, lt) in c["links"].as_object().unwrap() {
                    k.angle(&ctx, lname, gp.link(lname).unwrap().angle, lt["theta"].as_f64().unwrap());
                    k.vec(&ctx, "cg pose", gp.link(lname).unwrap().cg, &lt["cg"]["pos"], k.pos);
                    for (pname, pt) in lt["points"].as_object().unwrap() {
                        k.vec(&ctx, pname, gp.point(pname).unwrap().pos, &pt["pos"], k.pos);
                    }
                }

                let drivers: Vec<f64> = c["drivers"].as_array().unwrap().iter().map(|d| d["value"].as_f64().unwrap()).collect();
                let fs = gen.kinetostatics(&mo, &loads).unwrap();
                let gf = g.kinetostatics(&gm, &gloads).unwrap();
                let gvp = g.driver_action(&gm, &gloads).unwrap();
                // The motor actions on their own scale (issue 28).
                let fscale = drivers.iter().fold(0.0f64, |a, d| a.max(d.abs()));
                for (i, d) in drivers.iter().enumerate() {
                    k.close(&ctx, "generic driver (d'Alembert)", gf.driver[i], *d, Scale::runtime_driver(fscale));
                    k.close(&ctx, "generic driver (virtual power)", gvp[i], *d, Scale::runtime_driver(fscale));
                    k.close(&ctx, "generic vs generated driver", gf.driver[i], as_vec(&fs.driver)[i], Scale::runtime_driver(fscale));
                }
                for (jname, rt) in c["reactions"].as_object().unwrap() {
                    let (f, mom) = gf.reaction(jname).unwrap_or_else(|| panic!("{ctx}: no joint {jname}"));
                    let (gf_, gmom) = fs.reaction(jname).unwrap();
                    k.vec(&ctx, jname, f, &rt["force"], k.force);
                    k.close(&ctx, &format!("{jname}.x vs generated"), f.x, gf_.x, k.force);
                    k.close(&ctx, &format!("{jname}.y vs generated"), f.y, gf_.y, k.force);
                    assert_eq!(mom.is_some(), gmom.is_some(), "{ctx}: {jname}");
                    if let Some(mt) = rt.get("moment") {
                        k.close(&ctx, "moment", mom.unwrap(), mt.as_f64().unwrap(), k.moment);
                        k.close(&ctx, "moment vs generated", mom.unwrap(), gmom.unwrap(), k.moment);
                    }
                }
                generic_test!(@zhukovski $one, gen, g, c, q, qd, qdd, loads, gloads, k, ctx, drivers);
            }
        }
    };
    (@zhukovski true, $gen:ident, $g:ident, $c:ident, $q:ident, $qd:ident, $qdd:ident, $loads:ident, $gloads:ident, $k:ident, $ctx:ident, $drivers:ident) => {{
        let z = &$c["zhukovski"];
        let (i_star, di, m_star) = (z["I_star"].as_f64().unwrap(), z["dI_star_dq"].as_f64().unwrap(), z["M_star"].as_f64().unwrap());
        let r = $g.reduced($q).unwrap();
        let rg = $gen.reduced($q).unwrap();
        let (iscale, mscale) = (i_star.abs().max(di.abs()), m_star.abs().max($drivers[0].abs()));
        $k.close(&$ctx, "I*", r.inertia, i_star, Scale::inertia(i_star.abs()));
        $k.close(&$ctx, "I* vs generated", r.inertia, rg.inertia, Scale::inertia(i_star.abs()));
        $k.close(&$ctx, "dI*/dq", r.inertia_derivative, di, Scale::inertia_derivative(iscale));
        $k.close(&$ctx, "dI*/dq vs generated", r.inertia_derivative, rg.inertia_derivative, Scale::inertia_derivative(iscale));
        let ms = $g.reduced_moment($q, &$gloads).unwrap();
        $k.close(&$ctx, "M*", ms, m_star, Scale::reduced_moment(mscale));
        $k.close(&$ctx, "M* vs generated", ms, $gen.reduced_moment($q, &$loads).unwrap(), Scale::reduced_moment(mscale));
        let zh = r.inertia * $qdd + 0.5 * r.inertia_derivative * $qd * $qd - ms;
        $k.close(&$ctx, "generic driver (Zhukovski)", zh, $drivers[0], Scale::runtime_driver($drivers[0].abs().max(m_star.abs())));
        let acc = $g.acceleration($q, $qd, $drivers[0], &$gloads).unwrap();
        $k.close(&$ctx, "q'' (direct problem)", acc, $qdd, Scale::qdd($qdd.abs().max(1.0)));
        $k.close(&$ctx, "q'' vs generated", acc, $gen.acceleration($q, $qd, $drivers[0], &$loads).unwrap(), Scale::qdd($qdd.abs().max(1.0)));
    }};
    (@zhukovski false, $gen:ident, $g:ident, $($rest:tt)*) => {{
        assert!(matches!($g.reduced(0.0), Err(MechError::InvalidInput(_))));
    }};
}
