//! The run-time mechanism (`mech::Mechanism`: the generated code's plan and kernels,
//! interpreted) on the ten example mechanisms: loaded at run time from the very DSL text the
//! macro compiled (`tests/common/mechanisms.rs`, read as text), it must agree with every
//! generated solver and with the high-precision tables of `tests/data/` to 1e-12 relative
//! (scaled by the largest entry of the same kind): the reference tables through the
//! run-time path.

#[path = "common/mechanisms.rs"]
mod mechanisms;
mod support;

use mech::mechanism::Motion as RtMotion;
use mech::Mechanism;
use mech::prelude::*;
use mechanisms::*;
use support::*;

/// The text of the generated mechanisms, exactly as the macro saw it.
const MECHANISMS: &str = include_str!("common/mechanisms.rs");

/// The run-time mechanism `name`, loaded from the text of `tests/common/mechanisms.rs`.
fn generic(name: &str) -> Mechanism {
    Mechanism::from_rust_source(MECHANISMS, name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Compare the generic motion with the reference table and with the generated motion.
fn motion_agrees<L, P>(
    ctx: &str,
    k: &Kinds,
    c: &serde_json::Value,
    gm: &RtMotion,
    gen_link: impl Fn(&str) -> Option<L>,
    gen_point: impl Fn(&str) -> Option<P>,
) where
    L: std::ops::Deref<Target = LinkMotion>,
    P: std::ops::Deref<Target = PointMotion>,
{
    for (lname, lt) in c["links"].as_object().unwrap() {
        let lm = gm.link(lname).unwrap_or_else(|| panic!("{ctx}: no link {lname}"));
        let gl = gen_link(lname).unwrap();
        let ctx = format!("{ctx} link {lname}");
        k.angle(&ctx, "run-time vs truth", lm.angle, lt["theta"].as_f64().unwrap());
        k.angle(&ctx, "run-time vs generated", lm.angle, gl.angle);
        k.close(&ctx, "omega", lm.omega, lt["omega"].as_f64().unwrap(), k.omega);
        k.close(&ctx, "omega vs generated", lm.omega, gl.omega, k.omega);
        k.close(&ctx, "alpha", lm.alpha, lt["alpha"].as_f64().unwrap(), k.alpha);
        k.close(&ctx, "alpha vs generated", lm.alpha, gl.alpha, k.alpha);
        k.vec(&ctx, "cg", lm.cg, &lt["cg"]["pos"], k.pos);
        k.vec(&ctx, "cg_vel", lm.cg_vel, &lt["cg"]["vel"], k.vel);
        k.vec(&ctx, "cg_acc", lm.cg_acc, &lt["cg"]["acc"], k.acc);
        for (what, a, b, s) in [("cg", lm.cg, gl.cg, k.pos), ("cg_vel", lm.cg_vel, gl.cg_vel, k.vel), ("cg_acc", lm.cg_acc, gl.cg_acc, k.acc)] {
            k.close(&ctx, &format!("{what}.x vs generated"), a.x, b.x, s);
            k.close(&ctx, &format!("{what}.y vs generated"), a.y, b.y, s);
        }
        for (pname, pt) in lt["points"].as_object().unwrap() {
            let pm = gm.point(pname).unwrap();
            let gp = gen_point(pname).unwrap();
            k.vec(&ctx, pname, pm.pos, &pt["pos"], k.pos);
            k.vec(&ctx, pname, pm.vel, &pt["vel"], k.vel);
            k.vec(&ctx, pname, pm.acc, &pt["acc"], k.acc);
            for (what, a, b, s) in [("pos", pm.pos, gp.pos, k.pos), ("vel", pm.vel, gp.vel, k.vel), ("acc", pm.acc, gp.acc, k.acc)] {
                k.close(&ctx, &format!("{pname}.{what}.x vs generated"), a.x, b.x, s);
                k.close(&ctx, &format!("{pname}.{what}.y vs generated"), a.y, b.y, s);
            }
        }
    }
}

macro_rules! runtime_test {
    ($test:ident, $ty:ident, $loads:ident, $file:literal, $q:expr, one_dof = $one:tt) => {
        #[test]
        fn $test() {
            let t = truth($file);
            let gen = $ty::new();
            let g = generic(stringify!($ty));
            assert_eq!(g.dof(), $ty::DOF);
            assert_eq!(g.model().n_links(), $ty::LINKS);
            assert_eq!(Machine::links(&g), $ty::LINKS);
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
                let fscale = k.force.max(drivers.iter().fold(0.0f64, |a, d| a.max(d.abs())));
                for (i, d) in drivers.iter().enumerate() {
                    k.close(&ctx, "generic driver (d'Alembert)", gf.driver[i], *d, fscale);
                    k.close(&ctx, "generic driver (virtual power)", gvp[i], *d, fscale);
                    k.close(&ctx, "generic vs generated driver", gf.driver[i], as_vec(&fs.driver)[i], fscale);
                }
                for (jname, rt) in c["reactions"].as_object().unwrap() {
                    let (f, mom) = gf.reaction(jname).unwrap_or_else(|| panic!("{ctx}: no joint {jname}"));
                    let (gf_, gmom) = fs.reaction(jname).unwrap();
                    k.vec(&ctx, jname, f, &rt["force"], k.force);
                    k.close(&ctx, &format!("{jname}.x vs generated"), f.x, gf_.x, k.force);
                    k.close(&ctx, &format!("{jname}.y vs generated"), f.y, gf_.y, k.force);
                    assert_eq!(mom.is_some(), gmom.is_some(), "{ctx}: {jname}");
                    if let Some(mt) = rt.get("moment") {
                        k.close(&ctx, "moment", mom.unwrap(), mt.as_f64().unwrap(), k.force * k.length);
                        k.close(&ctx, "moment vs generated", mom.unwrap(), gmom.unwrap(), k.force * k.length);
                    }
                }
                runtime_test!(@zhukovski $one, gen, g, c, q, qd, qdd, loads, gloads, k, ctx, drivers);
            }
        }
    };
    (@zhukovski true, $gen:ident, $g:ident, $c:ident, $q:ident, $qd:ident, $qdd:ident, $loads:ident, $gloads:ident, $k:ident, $ctx:ident, $drivers:ident) => {{
        let z = &$c["zhukovski"];
        let (i_star, di, m_star) = (z["I_star"].as_f64().unwrap(), z["dI_star_dq"].as_f64().unwrap(), z["M_star"].as_f64().unwrap());
        let r = $g.reduced($q).unwrap();
        let rg = $gen.reduced($q).unwrap();
        let (iscale, mscale) = (i_star.abs().max(di.abs()), m_star.abs().max($drivers[0].abs()));
        $k.close(&$ctx, "I*", r.inertia, i_star, i_star.abs());
        $k.close(&$ctx, "I* vs generated", r.inertia, rg.inertia, i_star.abs());
        $k.close(&$ctx, "dI*/dq", r.inertia_derivative, di, iscale);
        $k.close(&$ctx, "dI*/dq vs generated", r.inertia_derivative, rg.inertia_derivative, iscale);
        let ms = $g.reduced_moment($q, &$gloads).unwrap();
        $k.close(&$ctx, "M*", ms, m_star, mscale);
        $k.close(&$ctx, "M* vs generated", ms, $gen.reduced_moment($q, &$loads).unwrap(), mscale);
        let zh = r.inertia * $qdd + 0.5 * r.inertia_derivative * $qd * $qd - ms;
        $k.close(&$ctx, "generic driver (Zhukovski)", zh, $drivers[0], $drivers[0].abs().max(m_star.abs()));
        let acc = $g.acceleration($q, $qd, $drivers[0], &$gloads).unwrap();
        $k.close(&$ctx, "q'' (direct problem)", acc, $qdd, $qdd.abs().max(1.0));
        $k.close(&$ctx, "q'' vs generated", acc, $gen.acceleration($q, $qd, $drivers[0], &$loads).unwrap(), $qdd.abs().max(1.0));
    }};
    (@zhukovski false, $gen:ident, $g:ident, $($rest:tt)*) => {{
        assert!(matches!($g.reduced(0.0), Err(MechError::InvalidInput(_))));
    }};
}

runtime_test!(public_slider_crank, PublicSliderCrank, PublicSliderCrankLoads, "public_slider_crank", |v: &[f64]| v[0], one_dof = true);
runtime_test!(public_four_bar, PublicFourBar, PublicFourBarLoads, "public_four_bar", |v: &[f64]| v[0], one_dof = true);
runtime_test!(four_bar, FourBar, FourBarLoads, "four_bar", |v: &[f64]| v[0], one_dof = true);
runtime_test!(slider_crank, SliderCrank, SliderCrankLoads, "slider_crank", |v: &[f64]| v[0], one_dof = true);
runtime_test!(quick_return, QuickReturn, QuickReturnLoads, "quick_return", |v: &[f64]| v[0], one_dof = true);
runtime_test!(watt2, Watt2, Watt2Loads, "watt2", |v: &[f64]| v[0], one_dof = true);
runtime_test!(stephenson3, Stephenson3, Stephenson3Loads, "stephenson3", |v: &[f64]| v[0], one_dof = true);
runtime_test!(scotch_yoke, ScotchYoke, ScotchYokeLoads, "scotch_yoke", |v: &[f64]| v[0], one_dof = true);
runtime_test!(five_bar, FiveBar, FiveBarLoads, "five_bar", |v: &[f64]| [v[0], v[1]], one_dof = false);
runtime_test!(hydraulic_lever, HydraulicLever, HydraulicLeverLoads, "hydraulic_lever", |v: &[f64]| v[0], one_dof = true);


/// Parameters changed by name at run time (`set_param`, re-validated) give the mechanism
/// that the generated struct's `from_params` gives with the same numbers.
#[test]
fn parameters_by_name_match_from_params() {
    let mut p = FourBarParams::default();
    p.points.A = Vector2::new(0.045, 0.068);
    p.links.coupler.mass = 1.9;
    p.links.coupler.inertia = 0.013;
    p.links.rocker.cg = Vector2::new(0.27, 0.14);
    p.gravity = Vector2::new(0.5, -9.7);
    let gen = FourBar::from_params(p).unwrap();
    let mut rt = generic("FourBar");
    for (path, v) in [
        ("points.A", &[0.045, 0.068][..]),
        ("links.coupler.mass", &[1.9]),
        ("links.coupler.inertia", &[0.013]),
        ("links.rocker.cg", &[0.27, 0.14]),
        ("gravity", &[0.5, -9.7]),
    ] {
        rt.set_param(path, v).unwrap_or_else(|e| panic!("{path}: {e}"));
    }
    let mut loads = FourBarLoads::default();
    let mut rloads = rt.loads();
    for (name, v) in [("tool", &[80.0, -60.0][..]), ("resist", &[2.0])] {
        assert!(loads.set_by_name(name, v) && rloads.set_by_name(name, v));
    }
    for k in 0..12 {
        let q = -3.0 + 0.5 * k as f64;
        let (m, rm) = (gen.kinematics(q, 7.0, -2.0).unwrap(), rt.kinematics(&[q], &[7.0], &[-2.0]).unwrap());
        let (d, rd) = (gen.kinetostatics(&m, &loads).unwrap().driver, rt.kinetostatics(&rm, &rloads).unwrap().driver[0]);
        assert!((d - rd).abs() <= 1e-12 * d.abs().max(1.0), "q = {q}: driver {d} vs {rd}");
        let (r, rr) = (gen.reduced(q).unwrap(), rt.reduced(q).unwrap());
        assert!((r.inertia - rr.inertia).abs() <= 1e-12 * r.inertia.abs(), "q = {q}: I*");
        let (ms, rms) = (gen.reduced_moment(q, &loads).unwrap(), rt.reduced_moment(q, &rloads).unwrap());
        assert!((ms - rms).abs() <= 1e-12 * ms.abs().max(1.0), "q = {q}: M* {ms} vs {rms}");
    }
    // A bad value is refused and leaves the mechanism as it was.
    let before = rt.model().clone();
    assert!(matches!(rt.set_param("links.coupler.mass", &[-1.0]), Err(MechError::Invalid(_))));
    assert!(matches!(rt.set_param("links.nothing.mass", &[1.0]), Err(MechError::InvalidInput(_))));
    assert!(matches!(rt.set_param("points.A", &[f64::NAN, 0.0]), Err(MechError::InvalidInput(_))));
    assert_eq!(rt.model(), &before);
}
