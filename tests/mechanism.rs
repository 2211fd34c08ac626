//! The run-time mechanism (`mech::Mechanism`: the generated code's plan and kernels,
//! interpreted) on the ten example mechanisms: loaded at run time from the very DSL text the
//! macro compiled (`tests/common/mechanisms.rs`, read as text), it must agree with every
//! generated solver and with the high-precision tables of `tests/data/`, relative to the
//! largest entry of the same kind, to the tolerances of `tests/support/mod.rs` (`tol`): the
//! reference tables through the run-time path.

use crate::measure::within;
use crate::mechanisms;
use crate::support;

use mech::prelude::*;
use mech::Mechanism;
use mechanisms::*;
use support::*;

/// The text of the generated mechanisms, exactly as the macro saw it.
const MECHANISMS: &str = include_str!("common/mechanisms.rs");

/// The run-time mechanism `name`, loaded from the text of `tests/common/mechanisms.rs`.
fn generic(name: &str) -> Mechanism {
    Mechanism::from_rust_source(MECHANISMS, name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

use crate::against_reference;
use against_reference::motion_agrees;

generic_test!(
    public_slider_crank,
    PublicSliderCrank,
    PublicSliderCrankLoads,
    "public_slider_crank",
    |v: &[f64]| v[0],
    one_dof = true
);
generic_test!(
    public_four_bar,
    PublicFourBar,
    PublicFourBarLoads,
    "public_four_bar",
    |v: &[f64]| v[0],
    one_dof = true
);
generic_test!(
    four_bar,
    FourBar,
    FourBarLoads,
    "four_bar",
    |v: &[f64]| v[0],
    one_dof = true
);
generic_test!(
    slider_crank,
    SliderCrank,
    SliderCrankLoads,
    "slider_crank",
    |v: &[f64]| v[0],
    one_dof = true
);
generic_test!(
    quick_return,
    QuickReturn,
    QuickReturnLoads,
    "quick_return",
    |v: &[f64]| v[0],
    one_dof = true
);
generic_test!(
    watt2,
    Watt2,
    Watt2Loads,
    "watt2",
    |v: &[f64]| v[0],
    one_dof = true
);
generic_test!(
    stephenson3,
    Stephenson3,
    Stephenson3Loads,
    "stephenson3",
    |v: &[f64]| v[0],
    one_dof = true
);
generic_test!(
    scotch_yoke,
    ScotchYoke,
    ScotchYokeLoads,
    "scotch_yoke",
    |v: &[f64]| v[0],
    one_dof = true
);
generic_test!(
    five_bar,
    FiveBar,
    FiveBarLoads,
    "five_bar",
    |v: &[f64]| [v[0], v[1]],
    one_dof = false
);
generic_test!(
    hydraulic_lever,
    HydraulicLever,
    HydraulicLeverLoads,
    "hydraulic_lever",
    |v: &[f64]| v[0],
    one_dof = true
);

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
        rt.set_param(path, v)
            .unwrap_or_else(|e| panic!("{path}: {e}"));
    }
    let mut loads = FourBarLoads::default();
    let mut rloads = rt.loads();
    for (name, v) in [("tool", &[80.0, -60.0][..]), ("resist", &[2.0])] {
        assert!(loads.set_by_name(name, v) && rloads.set_by_name(name, v));
    }
    for k in 0..12 {
        let q = -3.0 + 0.5 * k as f64;
        let (m, rm) = (
            gen.kinematics(q, 7.0, -2.0).unwrap(),
            rt.kinematics(&[q], &[7.0], &[-2.0]).unwrap(),
        );
        let (d, rd) = (
            gen.kinetostatics(&m, &loads).unwrap().driver,
            rt.kinetostatics(&rm, &rloads).unwrap().driver[0],
        );
        assert!(
            within((d - rd).abs(), 1e-13 * d.abs().max(1.0)), // measured worst 2.0e-15 (be05608); 100×
            "q = {q}: driver {d} vs {rd}"
        );
        let (r, rr) = (gen.reduced(q).unwrap(), rt.reduced(q).unwrap());
        assert!(
            within((r.inertia - rr.inertia).abs(), 1e-15 * r.inertia.abs()), // measured worst 0 (be05608); exact; a few ulps
            "q = {q}: I*"
        );
        let (ms, rms) = (
            gen.reduced_moment(q, &loads).unwrap(),
            rt.reduced_moment(q, &rloads).unwrap(),
        );
        assert!(
            within((ms - rms).abs(), 1e-14 * ms.abs().max(1.0)), // measured worst 2.0e-16 (be05608); 100×
            "q = {q}: M* {ms} vs {rms}"
        );
    }
    // A bad value is refused and leaves the mechanism as it was.
    let before = rt.model().clone();
    assert!(matches!(
        rt.set_param("links.coupler.mass", &[-1.0]),
        Err(MechError::Invalid(_))
    ));
    assert!(matches!(
        rt.set_param("links.nothing.mass", &[1.0]),
        Err(MechError::InvalidInput(_))
    ));
    assert!(matches!(
        rt.set_param("points.A", &[f64::NAN, 0.0]),
        Err(MechError::InvalidInput(_))
    ));
    assert_eq!(rt.model(), &before);
}
