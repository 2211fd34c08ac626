//! Every generated solver against the high-precision tables of `tests/data/` (computed by
//! `tools/reference.py` with mpmath at 50 digits, by a different formulation: the whole
//! constraint system in absolute coordinates and one dense Newton–Euler system).
//!
//! Tolerance: relative to the largest entry of the same kind in the configuration
//! (positions, velocities, accelerations, angles, forces ...), per kind at most 100× the
//! worst error measured (`tests/support/mod.rs`, `tol`), well inside the 1e-12 of
//! `docs/conventions.md#solver-requirements`.

use crate::mechanisms;
use crate::support;

use mechanisms::*;
use support::*;

macro_rules! reference_test {
    ($test:ident, $ty:ident, $loads:ident, $file:literal, $q:expr, one_dof = $one:tt) => {
        #[test]
        fn $test() {
            let t = truth($file);
            let m = $ty::new();
            let mut loads = $loads::default();
            for (name, l) in t["loads"].as_object().unwrap() {
                assert!(loads.set_by_name(name, &nums(&l["value"])), "load {name}");
            }
            let to_q = $q;
            for c in t["configs"].as_array().unwrap() {
                let (q, qd, qdd) = (to_q(&nums(&c["q"])), to_q(&nums(&c["qd"])), to_q(&nums(&c["qdd"])));
                let ctx = format!("{} config {}", $file, c["index"]);

                // Positions, velocities, accelerations.
                let mo = m.kinematics(q, qd, qdd).unwrap();
                let po = m.pose(q).unwrap();
                let k = Kinds::of(c);
                for (lname, lt) in c["links"].as_object().unwrap() {
                    let lm = mo.link(lname).unwrap_or_else(|| panic!("{ctx}: no link {lname}"));
                    k.angle(&ctx, lname, lm.angle, lt["theta"].as_f64().unwrap());
                    k.angle(&ctx, lname, po.link(lname).unwrap().angle, lt["theta"].as_f64().unwrap());
                    k.close(&ctx, "omega", lm.omega, lt["omega"].as_f64().unwrap(), k.omega);
                    k.close(&ctx, "alpha", lm.alpha, lt["alpha"].as_f64().unwrap(), k.alpha);
                    k.vec(&ctx, "cg", lm.cg, &lt["cg"]["pos"], k.pos);
                    k.vec(&ctx, "cg pose", po.link(lname).unwrap().cg, &lt["cg"]["pos"], k.pos);
                    k.vec(&ctx, "cg_vel", lm.cg_vel, &lt["cg"]["vel"], k.vel);
                    k.vec(&ctx, "cg_acc", lm.cg_acc, &lt["cg"]["acc"], k.acc);
                    for (pname, pt) in lt["points"].as_object().unwrap() {
                        let pm = mo.point(pname).unwrap();
                        k.vec(&ctx, pname, pm.pos, &pt["pos"], k.pos);
                        k.vec(&ctx, pname, po.point(pname).unwrap().pos, &pt["pos"], k.pos);
                        k.vec(&ctx, pname, pm.vel, &pt["vel"], k.vel);
                        k.vec(&ctx, pname, pm.acc, &pt["acc"], k.acc);
                    }
                }

                // Driver actions and every reaction.
                let drivers: Vec<f64> = c["drivers"].as_array().unwrap().iter().map(|d| d["value"].as_f64().unwrap()).collect();
                let fs = m.kinetostatics(&mo, &loads).unwrap();
                let vp = m.driver_action(&mo, &loads).unwrap();
                // The motor actions on their own scale (the largest of them, N·m or N), not
                // on the reactions' (issue 28: that was 8-370x looser).
                let dscale = drivers.iter().fold(0.0f64, |a, d| a.max(d.abs()));
                for (i, d) in drivers.iter().enumerate() {
                    k.close(&ctx, "driver (d'Alembert)", as_vec(&fs.driver)[i], *d, Scale::driver(dscale));
                    k.close(&ctx, "driver (virtual power)", as_vec(&vp)[i], *d, Scale::driver(dscale));
                }
                for (jname, rt) in c["reactions"].as_object().unwrap() {
                    let (f, mom) = fs.reaction(jname).unwrap_or_else(|| panic!("{ctx}: no joint {jname}"));
                    k.vec(&ctx, jname, f, &rt["force"], k.force);
                    if let Some(mt) = rt.get("moment") {
                        k.close(&ctx, "moment", mom.unwrap(), mt.as_f64().unwrap(), k.moment);
                    }
                }
                reference_test!(@zhukovski $one, m, c, q, qd, qdd, loads, k, ctx, drivers);
            }
        }
    };
    (@zhukovski true, $m:ident, $c:ident, $q:ident, $qd:ident, $qdd:ident, $loads:ident, $k:ident, $ctx:ident, $drivers:ident) => {{
        let z = &$c["zhukovski"];
        let r = $m.reduced($q).unwrap();
        let i_star = z["I_star"].as_f64().unwrap();
        let di = z["dI_star_dq"].as_f64().unwrap();
        let m_star = z["M_star"].as_f64().unwrap();
        $k.close(&$ctx, "I*", r.inertia, i_star, Scale::inertia(i_star.abs()));
        $k.close(&$ctx, "dI*/dq", r.inertia_derivative, di, Scale::inertia_derivative(i_star.abs().max(di.abs())));
        let ms = $m.reduced_moment($q, &$loads).unwrap();
        $k.close(&$ctx, "M*", ms, m_star, Scale::reduced_moment(m_star.abs().max($drivers[0].abs())));
        // The third route to the driver torque: I* q'' + 1/2 I*' q'^2 - M*.
        let zh = r.inertia * $qdd + 0.5 * r.inertia_derivative * $qd * $qd - ms;
        $k.close(&$ctx, "driver (Zhukovski)", zh, $drivers[0], Scale::driver($drivers[0].abs().max(m_star.abs())));
        // The direct problem inverts it.
        let acc = $m.acceleration($q, $qd, $drivers[0], &$loads).unwrap();
        $k.close(&$ctx, "q'' (direct problem)", acc, $qdd, Scale::qdd($qdd.abs().max(1.0)));
    }};
    (@zhukovski false, $($rest:tt)*) => {{}};
}

reference_test!(
    public_slider_crank,
    PublicSliderCrank,
    PublicSliderCrankLoads,
    "public_slider_crank",
    |v: &[f64]| v[0],
    one_dof = true
);
reference_test!(
    public_four_bar,
    PublicFourBar,
    PublicFourBarLoads,
    "public_four_bar",
    |v: &[f64]| v[0],
    one_dof = true
);
reference_test!(
    four_bar,
    FourBar,
    FourBarLoads,
    "four_bar",
    |v: &[f64]| v[0],
    one_dof = true
);
reference_test!(
    slider_crank,
    SliderCrank,
    SliderCrankLoads,
    "slider_crank",
    |v: &[f64]| v[0],
    one_dof = true
);
reference_test!(
    quick_return,
    QuickReturn,
    QuickReturnLoads,
    "quick_return",
    |v: &[f64]| v[0],
    one_dof = true
);
reference_test!(
    watt2,
    Watt2,
    Watt2Loads,
    "watt2",
    |v: &[f64]| v[0],
    one_dof = true
);
reference_test!(
    stephenson3,
    Stephenson3,
    Stephenson3Loads,
    "stephenson3",
    |v: &[f64]| v[0],
    one_dof = true
);
reference_test!(
    scotch_yoke,
    ScotchYoke,
    ScotchYokeLoads,
    "scotch_yoke",
    |v: &[f64]| v[0],
    one_dof = true
);
reference_test!(
    five_bar,
    FiveBar,
    FiveBarLoads,
    "five_bar",
    |v: &[f64]| [v[0], v[1]],
    one_dof = false
);
reference_test!(
    hydraulic_lever,
    HydraulicLever,
    HydraulicLeverLoads,
    "hydraulic_lever",
    |v: &[f64]| v[0],
    one_dof = true
);
