//! Zero heap allocations in every generated solver
//! (`docs/conventions.md#solver-requirements`), proved with a counting global allocator,
//! for every example topology.

use crate::mechanisms;

use crate::counting;
use mechanisms::*;

// This thread's allocations are counted (`tests/common/counting.rs`, the global allocator
// of the suite, installed in `tests/suite.rs`): the harness's own threads, and the other
// tests running in them, which may allocate while a test runs, do not count.

/// Allocations made by `f` (the test harness runs other tests in other threads, so
/// this file holds a single test).
fn count<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let before = counting::count();
    let r = f();
    (counting::count() - before, r)
}

macro_rules! no_alloc {
    ($ty:ident, $loads:ident, $q:expr, one_dof) => {{
        let m = $ty::new();
        let loads = $loads::default();
        let q = $q;
        let (n, p) = count(|| m.pose(q));
        p.unwrap();
        assert_eq!(n, 0, "{}: pose allocated", stringify!($ty));
        let (n, mo) = count(|| m.kinematics(q, 3.0, -2.0));
        let mo = mo.unwrap();
        assert_eq!(n, 0, "{}: kinematics allocated", stringify!($ty));
        let (n, f) = count(|| m.kinetostatics(&mo, &loads));
        f.unwrap();
        assert_eq!(n, 0, "{}: kinetostatics allocated", stringify!($ty));
        let (n, d) = count(|| m.driver_action(&mo, &loads));
        d.unwrap();
        assert_eq!(n, 0, "{}: driver_action allocated", stringify!($ty));
        let (n, r) = count(|| m.reduced(q));
        r.unwrap();
        assert_eq!(n, 0, "{}: reduced allocated", stringify!($ty));
        let (n, r) = count(|| m.reduced_moment(q, &loads));
        r.unwrap();
        assert_eq!(n, 0, "{}: reduced_moment allocated", stringify!($ty));
        let (n, r) = count(|| m.acceleration(q, 3.0, 1.0, &loads));
        r.unwrap();
        assert_eq!(n, 0, "{}: acceleration allocated", stringify!($ty));
    }};
}

#[test]
fn generated_solvers_do_not_allocate() {
    no_alloc!(PublicSliderCrank, PublicSliderCrankLoads, 0.4, one_dof);
    no_alloc!(PublicFourBar, PublicFourBarLoads, 0.4, one_dof);
    no_alloc!(FourBar, FourBarLoads, 0.4, one_dof);
    no_alloc!(SliderCrank, SliderCrankLoads, 0.4, one_dof);
    no_alloc!(QuickReturn, QuickReturnLoads, 0.4, one_dof);
    no_alloc!(Watt2, Watt2Loads, 0.4, one_dof);
    no_alloc!(Stephenson3, Stephenson3Loads, 0.4, one_dof);
    no_alloc!(ScotchYoke, ScotchYokeLoads, 0.4, one_dof);
    no_alloc!(HydraulicLever, HydraulicLeverLoads, 0.02, one_dof);

    let m = FiveBar::new();
    let loads = FiveBarLoads::default();
    let q0 = mechanisms_five_bar_q0(&m);
    let (n, p) = count(|| m.pose(q0));
    p.unwrap();
    assert_eq!(n, 0, "FiveBar: pose allocated");
    let (n, mo) = count(|| m.kinematics(q0, [1.0, -2.0], [0.5, 0.3]));
    let mo = mo.unwrap();
    assert_eq!(n, 0, "FiveBar: kinematics allocated");
    let (n, f) = count(|| m.kinetostatics(&mo, &loads));
    f.unwrap();
    assert_eq!(n, 0, "FiveBar: kinetostatics allocated");
    let (n, d) = count(|| m.driver_action(&mo, &loads));
    d.unwrap();
    assert_eq!(n, 0, "FiveBar: driver_action allocated");

    // The counter works: a Vec allocates.
    let (n, _v) = count(|| vec![1.0f64; 4]);
    assert_eq!(n, 1);
}

/// The five-bar's inputs in the drawing: its crank angles.
fn mechanisms_five_bar_q0(m: &FiveBar) -> [f64; 2] {
    let p = m.params();
    let a = p.points.A - p.points.O1;
    let b = p.points.B - p.points.O5;
    [a.y.atan2(a.x), b.y.atan2(b.x)]
}
