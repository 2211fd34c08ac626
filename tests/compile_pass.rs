//! Compile-pass suite: eleven textbook topologies declared with realistic numbers. Each test
//! asserts the generated constants against counts made by hand
//! (`docs/conventions.md#generated-api`: DOF = the number of inputs, LINKS = N with the
//! ground, LOWER_PAIRS = P_I, HIGHER_PAIRS = P_II, EQUATIONS = 3(N − 1),
//! UNKNOWNS = DOF + 2·P_I + P_II), and that
//! `new()` posed at the drawing's own input value reproduces every point of the drawing.
//!
//! The drawing's input value: θ_b − θ_a for a revolute input (here always a crank on the
//! ground, so the crank's angle atan2 of its first → second point), 0 for a prismatic input.

use crate::measure::within;
use mech::prelude::*;

/// Tolerance on reproduced points, m (the drawings are 0.1–1 m across): at most 100× the
/// worst error measured over every drawing (tests/README.md, "Tolerances").
// measured worst 5.0e-16 (be05608); 100×
const TOL: f64 = 5e-14;

/// The reference angle of the vector from `p` to `q` (rad).
fn angle(p: (f64, f64), q: (f64, f64)) -> f64 {
    (q.1 - p.1).atan2(q.0 - p.0)
}

/// Pose `$ty::new()` at `$q` and compare every point of the drawing (all of them must be
/// listed: the count is checked against `POINT_NAMES`).
macro_rules! assert_reproduces {
    ($ty:ident, $q:expr, [$($p:ident = $xy:expr),* $(,)?]) => {{
        let m = $ty::new();
        let pose = m.pose($q).expect("pose at the drawing's input value");
        let want: &[(&str, (f64, f64))] = &[$((stringify!($p), $xy)),*];
        assert_eq!(want.len(), $ty::POINT_NAMES.len(), "{}: every point of the drawing is checked", stringify!($ty));
        for &(n, (x, y)) in want {
            let got = pose.point(n).unwrap_or_else(|| panic!("{}: no point {n}", stringify!($ty))).pos;
            assert!(
                within((got.x - x).abs(), TOL) && within((got.y - y).abs(), TOL),
                "{}: point {n} posed at ({:e}, {:e}), drawn at ({x:e}, {y:e}); error ({:e}, {:e})",
                stringify!($ty), got.x, got.y, got.x - x, got.y - y
            );
        }
    }};
}

/// The constants against hand counts, and the identities of
/// `docs/conventions.md#generated-api` between them.
macro_rules! assert_counts {
    ($ty:ident, dof: $g:expr, links: $n:expr, lower: $p1:expr, higher: $p2:expr, equations: $e:expr, unknowns: $u:expr) => {{
        assert_eq!($ty::DOF, $g, "DOF");
        assert_eq!($ty::LINKS, $n, "LINKS");
        assert_eq!($ty::LOWER_PAIRS, $p1, "LOWER_PAIRS");
        assert_eq!($ty::HIGHER_PAIRS, $p2, "HIGHER_PAIRS");
        assert_eq!($ty::EQUATIONS, $e, "EQUATIONS");
        assert_eq!($ty::UNKNOWNS, $u, "UNKNOWNS");
        assert_eq!($ty::EQUATIONS, 3 * ($ty::LINKS - 1));
        assert_eq!(
            $ty::UNKNOWNS,
            $ty::DOF + 2 * $ty::LOWER_PAIRS + $ty::HIGHER_PAIRS
        );
    }};
}

/// Grübler's G = 3(N − 1) − 2·P_I − P_II from the constants (may differ from DOF only
/// under `#[allow(redundant)]`).
macro_rules! grubler {
    ($ty:ident) => {
        3 * ($ty::LINKS as i64 - 1) - 2 * $ty::LOWER_PAIRS as i64 - $ty::HIGHER_PAIRS as i64
    };
}

// ---------------------------------------------------------------------------------------
// 1. Four-bar crank-rocker (Grashof: s + l = 0.08 + 0.302 ≤ p + q).
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Crank-rocker four-bar with a coupler point P.
    pub struct CrankRocker {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.3, 0.04) },
        link crank {
            points { O2, A: (0.04, 0.06928203230275509) },
            mass: 0.65, inertia: 0.00052, cg: (0.011803847577293369, 0.03244486372867091),
        },
        link coupler {
            points { A, B: (0.2430191330116403, 0.23171119111114735), P: (0.08528408845676129, 0.22077246544174978) },
            mass: 1.45, inertia: 0.0112, cg: (0.11823879885921107, 0.17157910143510077),
        },
        link rocker {
            points { O4, B },
            mass: 0.95, inertia: 0.0036, cg: (0.28088744015991685, 0.13238349450177364),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
        loads {
            tool: force on coupler at P,
            resist: torque on rocker,
        },
    }
}

#[test]
fn four_bar_crank_rocker() {
    // N = 4 (ground, crank, coupler, rocker); P_I = 4 pins; G = 3·3 − 2·4 = 1.
    assert_counts!(CrankRocker, dof: 1, links: 4, lower: 4, higher: 0, equations: 9, unknowns: 9);
    let a = (0.04, 0.06928203230275509);
    assert_reproduces!(
        CrankRocker,
        angle((0.0, 0.0), a),
        [
            O2 = (0.0, 0.0),
            O4 = (0.3, 0.04),
            A = a,
            B = (0.2430191330116403, 0.23171119111114735),
            P = (0.08528408845676129, 0.22077246544174978),
        ]
    );
}

// ---------------------------------------------------------------------------------------
// 2. Offset slider-crank (piston guide 15 mm above the crank centre).
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Offset slider-crank of a single-cylinder engine.
    pub struct OffsetSliderCrank {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.042132444371543794, 0.035353318532759664) },
            mass: 1.1, inertia: 0.00135, cg: (0.0061767322404058704, 0.009751819257468356),
        },
        link rod {
            points { A, B: (0.23103914733547787, 0.015) },
            mass: 0.85, inertia: 0.0032, cg: (0.1081811584228632, 0.032260201631147026),
        },
        link piston {
            points { B },
            mass: 0.62, inertia: 0.00036, cg: (0.22703914733547786, 0.0125),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, rod),
            B: revolute(rod, piston),
            guide: prismatic(ground, piston) at B along (1.0, 0.0),
        },
        input: O2,
        loads {
            gas: force on piston at B,
            shaft: torque on crank,
        },
    }
}

#[test]
fn offset_slider_crank() {
    // N = 4; P_I = 3 pins + 1 prismatic = 4; G = 9 − 8 = 1.
    assert_counts!(OffsetSliderCrank, dof: 1, links: 4, lower: 4, higher: 0, equations: 9, unknowns: 9);
    let a = (0.042132444371543794, 0.035353318532759664);
    assert_reproduces!(
        OffsetSliderCrank,
        angle((0.0, 0.0), a),
        [O2 = (0.0, 0.0), A = a, B = (0.23103914733547787, 0.015),]
    );
}

// ---------------------------------------------------------------------------------------
// 3. Quick-return crank-shaper: block pinned to the crank slides in the slotted lever
//    O4-C; link C-D drives the ram on a horizontal guide.
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Crank-shaper quick-return with its ram.
    pub struct CrankShaper {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.0, -0.3) },
        link crank {
            points { O2, A: (0.08660254037844388, 0.049999999999999996) },
            mass: 1.3, inertia: 0.0022, cg: (0.0433, 0.025),
        },
        link block {
            points { A },
            mass: 0.35, inertia: 0.00011, cg: (0.08660254037844388, 0.049999999999999996),
        },
        link lever {
            points { O4, C: (0.13210572688919694, 0.2338989388667831) },
            mass: 2.6, inertia: 0.068, cg: (0.06605286344459847, -0.03305053056660845),
        },
        link link5 {
            points { C, D: (0.27484567281321426, 0.28) },
            mass: 0.5, inertia: 0.00095, cg: (0.2034756998512056, 0.25694946943339155),
        },
        link ram {
            points { D },
            mass: 9.0, inertia: 0.12, cg: (0.3, 0.31),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, block),
            slot: prismatic(lever, block) at A along (0.24019223070763077, 0.970725343394151),
            O4: revolute(ground, lever),
            C: revolute(lever, link5),
            D: revolute(link5, ram),
            guide: prismatic(ground, ram) at D along (1.0, 0.0),
        },
        input: O2,
        loads {
            cut: force on ram at D,
        },
    }
}

#[test]
fn quick_return_crank_shaper() {
    // N = 6 (ground, crank, block, lever, link5, ram); P_I = 5 pins + 2 prismatic = 7;
    // G = 15 − 14 = 1.
    assert_counts!(CrankShaper, dof: 1, links: 6, lower: 7, higher: 0, equations: 15, unknowns: 15);
    let a = (0.08660254037844388, 0.049999999999999996);
    assert_reproduces!(
        CrankShaper,
        angle((0.0, 0.0), a),
        [
            O2 = (0.0, 0.0),
            O4 = (0.0, -0.3),
            A = a,
            C = (0.13210572688919694, 0.2338989388667831),
            D = (0.27484567281321426, 0.28),
        ]
    );
}

// ---------------------------------------------------------------------------------------
// 4. Watt II six-bar: two four-bars in series through the ternary rocker.
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Watt II six-bar.
    pub struct WattII {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.26, 0.02), O6: (0.5, 0.16) },
        link crank {
            points { O2, A: (0.049497474683058325, 0.049497474683058325) },
            mass: 0.6, inertia: 0.00035, cg: (0.017677669529663688, 0.024748737341529162),
        },
        link coupler {
            points { A, B: (0.24457586704408874, 0.18929883674307502) },
            mass: 1.1, inertia: 0.0058, cg: (0.14295913113682304, 0.12508794215693006),
        },
        link rocker {
            points { O4, B, C: (0.38963382395689183, 0.09546569873998104) },
            mass: 1.6, inertia: 0.0061, cg: (0.3020698970003269, 0.09858817849435202),
        },
        link link5 {
            points { C, D: (0.442738473050409, 0.2986402449918539) },
            mass: 0.9, inertia: 0.0036, cg: (0.4207267391324297, 0.19069820698105808),
        },
        link rocker6 {
            points { O6, D },
            mass: 0.8, inertia: 0.0019, cg: (0.46495953939067963, 0.221263089379223),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
            C: revolute(rocker, link5),
            D: revolute(link5, rocker6),
            O6: revolute(ground, rocker6),
        },
        input: O2,
        loads {
            resist: torque on rocker6,
        },
    }
}

#[test]
fn watt_ii_six_bar() {
    // N = 6; P_I = 7 pins; G = 15 − 14 = 1.
    assert_counts!(WattII, dof: 1, links: 6, lower: 7, higher: 0, equations: 15, unknowns: 15);
    let a = (0.049497474683058325, 0.049497474683058325);
    assert_reproduces!(
        WattII,
        angle((0.0, 0.0), a),
        [
            O2 = (0.0, 0.0),
            O4 = (0.26, 0.02),
            O6 = (0.5, 0.16),
            A = a,
            B = (0.24457586704408874, 0.18929883674307502),
            C = (0.38963382395689183, 0.09546569873998104),
            D = (0.442738473050409, 0.2986402449918539),
        ]
    );
}

// ---------------------------------------------------------------------------------------
// 5. Stephenson III six-bar: dyad C-D-O6 hung on the ternary coupler of a four-bar.
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Stephenson III six-bar.
    pub struct StephensonIII {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.28, 0.0), O6: (-0.05, 0.36) },
        link crank {
            points { O2, A: (0.025651510749425156, 0.07047694655894313) },
            mass: 0.62, inertia: 0.00038, cg: (0.014703415069565033, 0.028702083291846394),
        },
        link coupler {
            points { A, B: (0.24168333561431513, 0.1962952705246736), C: (0.06173691110908896, 0.2072170060911913) },
            mass: 1.35, inertia: 0.0092, cg: (0.10669058582427642, 0.159996407724936),
        },
        link rocker {
            points { O4, B },
            mass: 0.9, inertia: 0.0031, cg: (0.253971333338794, 0.09680655200883782),
        },
        link link5 {
            points { C, D: (0.11992248500076413, 0.41938307074550024) },
            mass: 0.85, inertia: 0.0035, cg: (0.08504335083708175, 0.31488691770630056),
        },
        link link6 {
            points { O6, D },
            mass: 0.75, inertia: 0.0021, cg: (0.03255051511268585, 0.38143390899090096),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, coupler),
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
            C: revolute(coupler, link5),
            D: revolute(link5, link6),
            O6: revolute(ground, link6),
        },
        input: O2,
        loads {
            load: force on link5 at D,
        },
    }
}

#[test]
fn stephenson_iii_six_bar() {
    // N = 6; P_I = 7 pins; G = 15 − 14 = 1.
    assert_counts!(StephensonIII, dof: 1, links: 6, lower: 7, higher: 0, equations: 15, unknowns: 15);
    let a = (0.025651510749425156, 0.07047694655894313);
    assert_reproduces!(
        StephensonIII,
        angle((0.0, 0.0), a),
        [
            O2 = (0.0, 0.0),
            O4 = (0.28, 0.0),
            O6 = (-0.05, 0.36),
            A = a,
            B = (0.24168333561431513, 0.1962952705246736),
            C = (0.06173691110908896, 0.2072170060911913),
            D = (0.11992248500076413, 0.41938307074550024),
        ]
    );
}

// ---------------------------------------------------------------------------------------
// 6. Scotch yoke: the crank pin runs in the yoke's vertical slot (higher pair).
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Scotch yoke of a reciprocating pump.
    pub struct ScotchYoke {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.03856725658119236, 0.045962666587138684) },
            mass: 0.7, inertia: 0.00031, cg: (0.011077149640627953, 0.019424128187363675),
        },
        link yoke {
            points { Y: (0.2, 0.0) },
            mass: 1.9, inertia: 0.0068, cg: (0.13, 0.004),
        },
        joints {
            O2: revolute(ground, crank),
            guide: prismatic(ground, yoke) at Y along (1.0, 0.0),
            slot: pin_in_slot(yoke, crank) at A along (0.0, 1.0),
        },
        input: O2,
        loads {
            pressure: force on yoke at Y,
        },
    }
}

#[test]
fn scotch_yoke() {
    // N = 3; P_I = 1 pin + 1 prismatic = 2; P_II = 1 slot; G = 6 − 4 − 1 = 1;
    // unknowns 1 + 4 + 1 = 6.
    assert_counts!(ScotchYoke, dof: 1, links: 3, lower: 2, higher: 1, equations: 6, unknowns: 6);
    let a = (0.03856725658119236, 0.045962666587138684);
    assert_reproduces!(
        ScotchYoke,
        angle((0.0, 0.0), a),
        [O2 = (0.0, 0.0), A = a, Y = (0.2, 0.0),]
    );
}

// ---------------------------------------------------------------------------------------
// 7. Two-DOF five-bar: both ground cranks driven.
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Two-crank five-bar of a plotter.
    pub struct FiveBar {
        gravity: (0.0, -9.81),
        ground { O1: (0.0, 0.0), O5: (0.2, 0.0) },
        link crank1 {
            points { O1, A: (-0.03420201433256687, 0.09396926207859084) },
            mass: 0.55, inertia: 0.0006, cg: (-0.020089369553584636, 0.040576067218737535),
        },
        link link2 {
            points { A, C: (0.11881875982892463, 0.2788601560539779) },
            mass: 0.8, inertia: 0.0042, cg: (0.04055477950750141, 0.1748854024632726),
        },
        link link3 {
            points { B: (0.24648800879147695, 0.0996938565740315), C },
            mass: 0.75, inertia: 0.0034, cg: (0.18438457063849983, 0.17823150977031277),
        },
        link crank4 {
            points { O5, B },
            mass: 0.6, inertia: 0.0007, cg: (0.22475614423518156, 0.0436249163048697),
        },
        joints {
            O1: revolute(ground, crank1),
            A: revolute(crank1, link2),
            C: revolute(link2, link3),
            B: revolute(link3, crank4),
            O5: revolute(ground, crank4),
        },
        inputs: [O1, O5],
        loads {
            pen: force on link2 at C,
        },
    }
}

#[test]
fn five_bar_two_dof() {
    // N = 5; P_I = 5 pins; G = 12 − 10 = 2; unknowns 2 + 10 = 12.
    assert_counts!(FiveBar, dof: 2, links: 5, lower: 5, higher: 0, equations: 12, unknowns: 12);
    let a = (-0.03420201433256687, 0.09396926207859084);
    let b = (0.24648800879147695, 0.0996938565740315);
    let q = [angle((0.0, 0.0), a), angle((0.2, 0.0), b)];
    assert_reproduces!(
        FiveBar,
        q,
        [
            O1 = (0.0, 0.0),
            O5 = (0.2, 0.0),
            A = a,
            C = (0.11881875982892463, 0.2788601560539779),
            B = b,
        ]
    );
}

// ---------------------------------------------------------------------------------------
// 8. Lever driven by a hydraulic cylinder: the stroke (prismatic joint) is the input.
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Boom lever lifted by a hydraulic cylinder pinned to the ground at C0.
    pub struct HydraulicLever {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), C0: (0.12, -0.42) },
        link lever {
            points { O, L: (0.26, 0.04), E: (0.72, 0.15) },
            mass: 4.8, inertia: 0.23, cg: (0.32857030337443366, 0.08990303521257006),
        },
        link cylinder {
            points { C0 },
            mass: 3.2, inertia: 0.045, cg: (0.16658585852523136, -0.2669321791313827),
        },
        link rod {
            points { L },
            mass: 1.3, inertia: 0.012, cg: (0.2163257576325956, -0.10350108206432876),
        },
        joints {
            O: revolute(ground, lever),
            C0: revolute(ground, cylinder),
            L: revolute(lever, rod),
            stroke: prismatic(cylinder, rod) at L along (0.29116161578269606, 0.9566738804288584),
        },
        input: stroke,
        loads {
            payload: force on lever at E,
        },
    }
}

#[test]
fn hydraulic_lever_prismatic_input() {
    // N = 4 (ground, lever, cylinder, rod); P_I = 3 pins + 1 prismatic = 4; G = 9 − 8 = 1.
    assert_counts!(HydraulicLever, dof: 1, links: 4, lower: 4, higher: 0, equations: 9, unknowns: 9);
    // A prismatic input is 0 in the drawing.
    assert_reproduces!(
        HydraulicLever,
        0.0,
        [
            O = (0.0, 0.0),
            C0 = (0.12, -0.42),
            L = (0.26, 0.04),
            E = (0.72, 0.15),
        ]
    );
}

// ---------------------------------------------------------------------------------------
// 9. Theo Jansen's leg with his "holy numbers" (cm, here in m: a = 0.38, b = 0.415,
//    c = 0.393, d = 0.401, e = 0.558, f = 0.394, g = 0.367, h = 0.657, i = 0.49,
//    j = 0.50, k = 0.619, l = 0.078, m = 0.15), crank at 60°.
//    Ground: crank axle O and frame pivot B = (−a, −l). Binary bars: crank O-A (m),
//    upper A-C (j), lower A-E (k), rocker B-E (c), back D-F (f). Ternary links: the top
//    triangle B-C-D (b, d, e) and the foot triangle E-F-G (g, i, h). Three pins join three
//    links each (A: crank, upper, lower; B: ground, top, rocker; E: rocker, lower, foot):
//    each is two revolute joints at the same point, a ternary pin (`docs/theory.md` §4.3).
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Theo Jansen's strandbeest leg: one crank, seven moving links, foot point G.
    pub struct JansenLeg {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), B: (-0.38, -0.078) },
        link crank {
            points { O, A: (0.07500000000000001, 0.12990381056766578) },
            mass: 0.9, inertia: 2.0e-3, cg: (0.037500000000000006, 0.06495190528383289),
        },
        link upper {
            points { A, C: (-0.38009468552880044, 0.3369999891983742) },
            mass: 0.35, inertia: 7.3e-3, cg: (-0.1525473427644002, 0.23345189988302),
        },
        link top {
            points { B, C, D: (-0.7801557322982775, -0.051992502834197214) },
            mass: 0.8, inertia: 0.021, cg: (-0.5134168059423593, 0.06900249545472566),
        },
        link lower {
            points { A, E: (-0.19733495562067804, -0.42596908133036826) },
            mass: 0.42, inertia: 0.0134, cg: (-0.061167477810339016, -0.14803263538135125),
        },
        link rocker {
            points { B, E },
            mass: 0.3, inertia: 3.9e-3, cg: (-0.288667477810339, -0.2519845406651841),
        },
        link back {
            points { D, F: (-0.5614050494921081, -0.3796876946998007) },
            mass: 0.3, inertia: 3.9e-3, cg: (-0.6707803908951928, -0.21584009876699894),
        },
        link foot {
            points { E, F, G: (-0.18150294681173765, -0.9157132466831304) },
            mass: 0.95, inertia: 0.032, cg: (-0.3134143173081746, -0.5737900075710998),
        },
        joints {
            O: revolute(ground, crank),
            A1: revolute(crank, upper) at A,
            A2: revolute(crank, lower) at A,
            B1: revolute(ground, top) at B,
            B2: revolute(ground, rocker) at B,
            C: revolute(upper, top),
            D: revolute(top, back),
            E1: revolute(rocker, lower) at E,
            E2: revolute(rocker, foot) at E,
            F: revolute(back, foot),
        },
        input: O,
        loads {
            soil: force on foot at G,
        },
    }
}

#[test]
fn jansen_leg() {
    // N = 8 (ground + 7); P_I = 4 simple pins (O, C, D, F) + 3 ternary pins × 2 = 10;
    // G = 3·7 − 2·10 = 1; equations 21; unknowns 1 + 20 = 21.
    assert_counts!(JansenLeg, dof: 1, links: 8, lower: 10, higher: 0, equations: 21, unknowns: 21);
    let a = (0.07500000000000001, 0.12990381056766578);
    assert_reproduces!(
        JansenLeg,
        angle((0.0, 0.0), a),
        [
            O = (0.0, 0.0),
            B = (-0.38, -0.078),
            A = a,
            C = (-0.38009468552880044, 0.3369999891983742),
            D = (-0.7801557322982775, -0.051992502834197214),
            E = (-0.19733495562067804, -0.42596908133036826),
            F = (-0.5614050494921081, -0.3796876946998007),
            G = (-0.18150294681173765, -0.9157132466831304),
        ]
    );
    // The holy numbers are the link lengths of the drawing (cm → m, to the 17 digits the
    // drawing's coordinates carry), at the drawing and around the crank's revolution.
    let m = JansenLeg::new();
    for k in 0..12 {
        let q = angle((0.0, 0.0), a) + k as f64 * std::f64::consts::TAU / 12.0;
        let p = m
            .pose(q)
            .unwrap_or_else(|e| panic!("crank at {q} rad: {e}"));
        let d = |u: &str, v: &str| (p.point(u).unwrap().pos - p.point(v).unwrap().pos).norm();
        for (u, v, len) in [
            ("O", "A", 0.15),
            ("A", "C", 0.50),
            ("B", "C", 0.415),
            ("B", "D", 0.401),
            ("C", "D", 0.558),
            ("A", "E", 0.619),
            ("B", "E", 0.393),
            ("D", "F", 0.394),
            ("E", "F", 0.367),
            ("F", "G", 0.657),
            ("E", "G", 0.49),
        ] {
            assert!(
                within((d(u, v) - len).abs(), 2e-14), // measured worst 3.3e-16 (be05608); 100×
                "crank at {q} rad: |{u}{v}| = {} m, holy number {len} m",
                d(u, v)
            );
        }
        // The frame stays put.
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within(
            (p.point("B").unwrap().pos - Vector2::new(-0.38, -0.078)).norm(),
            1e-15
        ));
    }
}

// ---------------------------------------------------------------------------------------
// 10. Crank-slider whose guide is on a moving link: the slider B runs on a guide carried
//     by the rocker O4-C, which a second coupler D-C drives from the same crank.
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Crank-slider with its guide on an oscillating rocker (variable-stroke drive).
    pub struct RockingGuide {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0), O4: (0.25, 0.2) },
        link crank {
            points { O2, A: (0.0383022221559489, 0.03213938048432696), D: (-0.037587704831436336, 0.013680805733026755) },
            mass: 0.8, inertia: 6.0e-4, cg: (0.0, 0.0),
        },
        link link2 {
            points { D, C: (0.14260434302204866, 0.25353664971096146) },
            mass: 0.6, inertia: 4.5e-3, cg: (0.05250831909530616, 0.1336087277219941),
        },
        link rocker {
            points { O4, C },
            mass: 1.1, inertia: 2.9e-3, cg: (0.22, 0.215),
        },
        link rod {
            points { A, B: (0.3394963808149595, 0.15538612524086548) },
            mass: 0.7, inertia: 6.2e-3, cg: (0.1888993014854542, 0.09376275286259622),
        },
        link slider {
            points { B },
            mass: 0.4, inertia: 1.0e-4, cg: (0.3394963808149595, 0.15538612524086548),
        },
        joints {
            O2: revolute(ground, crank),
            D: revolute(crank, link2),
            C: revolute(link2, rocker),
            O4: revolute(ground, rocker),
            A: revolute(crank, rod),
            B: revolute(rod, slider),
            guide: prismatic(rocker, slider) at B along (-0.8949638081495945, 0.4461387475913454),
        },
        input: O2,
        loads {
            push: force on slider at B,
        },
    }
}

#[test]
fn crank_slider_guide_on_moving_link() {
    // N = 6 (ground, crank, link2, rocker, rod, slider); P_I = 6 pins + 1 prismatic = 7;
    // G = 15 − 14 = 1.
    assert_counts!(RockingGuide, dof: 1, links: 6, lower: 7, higher: 0, equations: 15, unknowns: 15);
    let a = (0.0383022221559489, 0.03213938048432696);
    assert_reproduces!(
        RockingGuide,
        angle((0.0, 0.0), a),
        [
            O2 = (0.0, 0.0),
            O4 = (0.25, 0.2),
            A = a,
            D = (-0.037587704831436336, 0.013680805733026755),
            C = (0.14260434302204866, 0.25353664971096146),
            B = (0.3394963808149595, 0.15538612524086548),
        ]
    );
}

// ---------------------------------------------------------------------------------------
// 11. Double parallelogram (coupled wheels), accepted with #[allow(redundant)].
// ---------------------------------------------------------------------------------------

mechanism! {
    /// Coupled wheels: three equal parallel cranks and one coupling rod.
    #[allow(redundant)]
    pub struct CoupledWheels {
        ground { O1: (0.0, 0.0), O2: (0.8, 0.0), O3: (1.6, 0.0) },
        link wheel1 {
            points { O1, A1: (0.05, 0.08660254037844387) },
            mass: 120.0, inertia: 9.0, cg: (0.0, 0.0),
        },
        link wheel2 {
            points { O2, A2: (0.85, 0.08660254037844387) },
            mass: 120.0, inertia: 9.0, cg: (0.8, 0.0),
        },
        link wheel3 {
            points { O3, A3: (1.65, 0.08660254037844387) },
            mass: 120.0, inertia: 9.0, cg: (1.6, 0.0),
        },
        link rod {
            points { A1, A2, A3 },
            mass: 35.0, inertia: 7.5, cg: (0.85, 0.08660254037844387),
        },
        joints {
            O1: revolute(ground, wheel1),
            O2: revolute(ground, wheel2),
            O3: revolute(ground, wheel3),
            A1: revolute(wheel1, rod),
            A2: revolute(wheel2, rod),
            A3: revolute(wheel3, rod),
        },
        input: O1,
        loads {
            traction: torque on wheel3,
        },
    }
}

#[test]
fn double_parallelogram_allow_redundant() {
    // N = 5; P_I = 6 pins. Grübler gives G = 3·4 − 2·6 = 0, but the drawing moves with one
    // redundant constraint. The library defines DOF as the number of declared inputs (the
    // true mobility, checked at the drawing under #[allow(redundant)]): DOF = 1, not G = 0.
    // Hence UNKNOWNS = 1 + 12 = 13 > EQUATIONS = 12: the reactions are indeterminate (the
    // struct has no reaction solver), the driver action is still determinate.
    assert_counts!(CoupledWheels, dof: 1, links: 5, lower: 6, higher: 0, equations: 12, unknowns: 13);
    assert_eq!(grubler!(CoupledWheels), 0);
    assert_eq!(
        CoupledWheels::UNKNOWNS - CoupledWheels::EQUATIONS,
        1,
        "one redundant constraint"
    );
    let a1 = (0.05, 0.08660254037844387);
    assert_reproduces!(
        CoupledWheels,
        angle((0.0, 0.0), a1),
        [
            O1 = (0.0, 0.0),
            O2 = (0.8, 0.0),
            O3 = (1.6, 0.0),
            A1 = a1,
            A2 = (0.85, 0.08660254037844387),
            A3 = (1.65, 0.08660254037844387),
        ]
    );
}

#[test]
fn grubler_matches_dof_without_redundancy() {
    assert_eq!(grubler!(CrankRocker), 1);
    assert_eq!(grubler!(OffsetSliderCrank), 1);
    assert_eq!(grubler!(CrankShaper), 1);
    assert_eq!(grubler!(WattII), 1);
    assert_eq!(grubler!(StephensonIII), 1);
    assert_eq!(grubler!(ScotchYoke), 1);
    assert_eq!(grubler!(FiveBar), 2);
    assert_eq!(grubler!(HydraulicLever), 1);
    assert_eq!(grubler!(JansenLeg), 1);
    assert_eq!(grubler!(RockingGuide), 1);
}
