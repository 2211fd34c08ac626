//! Hostile input (`docs/conventions.md#magnitudes`): the seven ways the promise "a clear
//! error, never a panic, never a hang, never a silent NaN" was broken, each reproduced:
//! a bounded continuation, a ground-only mechanism, raw identifiers, non-finite results
//! and absurd magnitudes, the parser's memory, size (tests/large.rs), and a drawing scaled
//! by 1e±200.

use crate::mechanisms;

use mech::prelude::*;
use mech::Mechanism;
use mech_oracle::GenericMechanism;
use mechanisms::*;

fn invalid(r: Result<impl std::fmt::Debug, MechError>, part: &str) {
    match r {
        Err(MechError::Invalid(m)) | Err(MechError::InvalidInput(m)) => {
            assert!(m.contains(part), "expected “{part}” in\n{m}")
        }
        other => panic!("expected an error with “{part}”, got {other:?}"),
    }
}

/// 1. The generic solver's continuation is bounded: an input it cannot reach ends in an
///    error after at most its step budget, not after 100 000 SVDs.
#[test]
fn an_unreachable_input_ends_in_an_error() {
    let text = mech_oracle::GenericMechanism::parse(
        &mechanism_text("FourBar").replace("input: O2,", "input: O4,"),
    )
    .unwrap();
    // The rocker cannot turn a full turn: somewhere past its limit the continuation stops.
    let r = (0..12)
        .map(|k| text.pose(&[0.5 * k as f64]))
        .find(|r| r.is_err());
    assert!(
        r.is_some(),
        "a rocker-driven four-bar does not assemble everywhere"
    );
}

/// The DSL text of a mechanism declared in tests/common/mechanisms.rs.
fn mechanism_text(name: &str) -> String {
    let source = include_str!("common/mechanisms.rs");
    let at = source.find(&format!("pub struct {name} ")).unwrap();
    let start = source[..at].rfind("mechanism! {").unwrap() + "mechanism! {".len();
    let end = at + source[at..].find("\n}\n").unwrap();
    source[start..end].to_string()
}

/// 2. A mechanism with no moving link is refused with the reason, by both loaders.
#[test]
fn a_ground_only_mechanism_is_refused() {
    for text in [
        "pub struct X { ground { O: (0.0, 0.0) } }",
        "pub struct X { ground { O: (0.0, 0.0), P: (1.0, 0.0) } }",
    ] {
        invalid(GenericMechanism::parse(text).map(|_| ()), "no moving link");
        invalid(Mechanism::from_dsl(text).map(|_| ()), "no moving link");
    }
}

/// 3. Raw identifiers are not names: both readers refuse them the same way.
#[test]
fn raw_identifiers_are_refused() {
    let text = mechanism_text("FourBar");
    for bad in [
        text.replace("link coupler", "link r#fn")
            .replace("(crank, coupler)", "(crank, r#fn)")
            .replace("(coupler, rocker)", "(r#fn, rocker)")
            .replace("on coupler", "on r#fn"),
        text.replace("pub struct FourBar", "pub struct r#FourBar"),
    ] {
        invalid(Mechanism::from_dsl(&bad).map(|_| ()), "raw identifier");
    }
}

/// 4. Every `Ok` is finite: overflowing inputs and loads are errors naming the quantity;
///    absurd parameters are refused with the accepted range.
#[test]
fn overflow_is_an_error_naming_the_quantity() {
    let m = FourBar::new();
    invalid(
        m.kinematics(0.3, 1e155, 0.0).map(|_| ()),
        "velocities or accelerations",
    );
    let mo = m.kinematics(0.3, 1e100, 0.0).unwrap();
    let huge = FourBarLoads {
        tool: Vector2::new(f64::MAX, -f64::MAX),
        resist: f64::MAX,
    };
    match m.kinetostatics(&mo, &huge) {
        Ok(f) => assert!(
            f.driver.is_finite()
                && [
                    f.joints.A.force,
                    f.joints.B.force,
                    f.joints.O2.force,
                    f.joints.O4.force
                ]
                .iter()
                .all(|v| v.iter().all(|x| x.is_finite())),
            "{f:?}"
        ),
        Err(e) => assert!(e.to_string().contains("overflow"), "{e}"),
    }
    match m.driver_action(&mo, &huge) {
        Ok(d) => assert!(d.is_finite()),
        Err(e) => assert!(e.to_string().contains("overflow"), "{e}"),
    }
    // Inertia forces at the edge of f64: q̇ = 1e154 (ω² ≈ 1e308): finite or an error.
    for qd in [1e153, 1e154, 3e154] {
        match m.kinematics(0.3, qd, 0.0).and_then(|mo| {
            Ok((
                m.kinetostatics(&mo, &FourBarLoads::default())?,
                m.driver_action(&mo, &FourBarLoads::default())?,
            ))
        }) {
            Ok((f, d)) => assert!(
                f.driver.is_finite()
                    && d.is_finite()
                    && f.joints.B.force.iter().all(|x| x.is_finite()),
                "q̇ = {qd}"
            ),
            Err(e) => assert!(e.to_string().contains("overflow"), "q̇ = {qd}: {e}"),
        }
    }
    let s = SliderCrank::new();
    invalid(
        s.acceleration(0.3, 0.0, f64::MAX, &SliderCrankLoads::default())
            .map(|_| ()),
        "acceleration",
    );
    for (what, change) in [
        (
            "mass",
            Box::new(|p: &mut FourBarParams| p.links.coupler.mass = f64::MAX)
                as Box<dyn Fn(&mut FourBarParams)>,
        ),
        (
            "cg",
            Box::new(|p: &mut FourBarParams| p.links.coupler.cg = Vector2::new(1e300, 0.0)),
        ),
        (
            "gravity",
            Box::new(|p: &mut FourBarParams| p.gravity = Vector2::new(0.0, -1e308)),
        ),
        (
            "moment of inertia",
            Box::new(|p: &mut FourBarParams| p.links.coupler.inertia = 5e-324),
        ),
        (
            "across",
            Box::new(|p: &mut FourBarParams| {
                p.points.O4 *= 1e200;
                p.points.A *= 1e200;
                p.points.B *= 1e200;
                p.points.P *= 1e200;
            }),
        ),
    ] {
        let mut p = m.params().clone();
        change(&mut p);
        invalid(FourBar::from_params(p).map(|_| ()), what);
    }
    // The run-time mechanism too.
    let mut rt = Mechanism::from_dsl(&mechanism_text("FourBar")).unwrap();
    invalid(rt.set_param("links.coupler.mass", &[1e300]), "mass");
    invalid(
        rt.kinematics(&[0.3], &[1e155], &[0.0]).map(|_| ()),
        "velocities or accelerations",
    );
    let r = rt.kinematics(&[0.3], &[1.0], &[0.0]).unwrap();
    let mut l = rt.loads();
    assert!(l.set_by_name("resist", &[f64::MAX]) && l.set_by_name("tool", &[f64::MAX, f64::MAX]));
    for result in [
        rt.kinetostatics(&r, &l).map(|f| f.driver),
        rt.driver_action(&r, &l),
    ] {
        match result {
            Ok(d) => assert!(d.iter().all(|x| x.is_finite())),
            Err(e) => assert!(e.to_string().contains("overflow"), "{e}"),
        }
    }
}

/// 4b. A non-finite input or load is named as such, not reported as the overflow or the
///     failed assembly it causes: `kinematics`, `pose`, `kinetostatics` and
///     `driver_action` look at their inputs only once a solve has failed
///     (`mech_core::error::blame`), and must still blame them. Every input, every load
///     component, both routes of `driver_action` (the power balance at q̇ ≠ 0, the wrenches
///     at q̇ = 0), one and two inputs.
#[test]
fn a_non_finite_input_is_named_not_called_an_overflow() {
    let m = FourBar::new();
    for x in [f64::NAN, f64::INFINITY, -f64::INFINITY] {
        invalid(m.pose(x), "q must be finite");
        invalid(m.kinematics(x, 1.0, 0.0), "q, qd, qdd must be finite");
        invalid(m.kinematics(0.3, x, 0.0), "q, qd, qdd must be finite");
        invalid(m.kinematics(0.3, 1.0, x), "q, qd, qdd must be finite");
        for qd in [1.0, 0.0] {
            let mo = m.kinematics(0.3, qd, 2.0).unwrap();
            let ok = FourBarLoads::default();
            for loads in [
                FourBarLoads {
                    tool: Vector2::new(x, 0.0),
                    ..ok
                },
                FourBarLoads {
                    tool: Vector2::new(0.0, x),
                    ..ok
                },
                FourBarLoads { resist: x, ..ok },
            ] {
                invalid(m.kinetostatics(&mo, &loads), "loads must be finite");
                invalid(m.driver_action(&mo, &loads), "loads must be finite");
            }
        }
    }
    let five = FiveBar::new();
    invalid(five.pose([f64::NAN, 1.0]), "q must be finite");
    invalid(
        five.kinematics([2.0, 1.0], [0.0, f64::INFINITY], [0.0, 0.0]),
        "q, qd, qdd must be finite",
    );
    // Finite but enormous inputs are still the overflow they cause.
    invalid(m.kinematics(0.3, 1e155, 0.0), "overflow");
}

/// 7. A drawing scaled by 1e±200 is refused for its size, not called redundant.
#[test]
fn a_drawing_scaled_out_of_range_says_so() {
    let text = mechanism_text("SliderCrank");
    for (factor, word) in [("1e200", "e199 m across"), ("1e-200", "e-201 m across")] {
        let mut model = GenericMechanism::parse(&text).unwrap().model().clone();
        let f: f64 = factor.parse().unwrap();
        for p in &mut model.points {
            p.pos = [p.pos[0] * f, p.pos[1] * f];
        }
        for l in &mut model.links {
            l.cg = [l.cg[0] * f, l.cg[1] * f];
        }
        match Mechanism::from_model(model) {
            Err(MechError::Invalid(m)) => {
                assert!(
                    m.contains("across") && m.contains(word) && !m.contains("redundant"),
                    "{m}"
                );
            }
            other => panic!("{other:?}"),
        }
    }
}

/// 5. Loading many mechanisms in one thread keeps resident memory flat: the parser's
///    span table lives on a thread of its own per load.
///
///    Resident memory belongs to the whole process, and the suite runs its tests on many
///    threads at once: the test runs itself again in a process of its own, alone.
#[test]
fn loading_many_mechanisms_keeps_memory_flat() {
    const NAME: &str = "hostile::loading_many_mechanisms_keeps_memory_flat";
    if std::env::var_os("MECH_TEST_ALONE").is_none() {
        let out = std::process::Command::new(std::env::current_exe().unwrap())
            .args([NAME, "--exact", "--test-threads=1", "--nocapture"])
            .env("MECH_TEST_ALONE", "1")
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout).into_owned()
            + &String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success() && text.contains("1 passed"), "{text}");
        return;
    }
    fn resident_kb() -> usize {
        let s = std::fs::read_to_string("/proc/self/statm").expect("/proc/self/statm");
        let pages = s
            .split_whitespace()
            .nth(1)
            .and_then(|v| v.parse::<usize>().ok());
        pages.expect("resident pages in /proc/self/statm") * 4
    }
    let text = mechanism_text("SliderCrank");
    let round = |n: usize| {
        for k in 0..n {
            let m = Mechanism::from_dsl(&text).unwrap();
            m.pose(&[0.01 * k as f64]).unwrap();
        }
    };
    round(2_000);
    let before = resident_kb();
    round(98_000);
    let after = resident_kb();
    // 700 bytes a parse kept alive would be 69 MB here (10⁵ loads in all).
    assert!(
        after < before + 2_000,
        "resident memory grew from {before} kB to {after} kB"
    );
}

/// The points and cgs derived from finite link states can still overflow (ω² r past f64's
/// range far from the anchor): the run-time `kinematics` says so, never `Ok` with an
/// infinity (issue 28: 328 such results were found by an outside fuzzer).
#[test]
fn point_accelerations_that_overflow_are_an_error() {
    let m = Mechanism::from_dsl(
        "pub struct Crank {
            ground { O: (0.0, 0.0) },
            link crank { points { O, A: (0.01, 0.0), B: (10.0, 0.0) } },
            joints { O: revolute(ground, crank) },
            input: O,
        }",
    )
    .unwrap();
    // ω² = 1e308 and ω² |OA| = 1e306 are finite, ω² |OB| = 1e309 is not.
    let w: f64 = 1e154;
    assert!((w * w * 0.01).is_finite() && !(w * w * 10.0).is_finite());
    match m.kinematics(&[0.0], &[w], &[0.0]) {
        Ok(k) => panic!("Ok with B.acc = {:?}", k.point("B").map(|p| p.acc)),
        Err(e) => assert!(e.to_string().contains("overflow"), "{e}"),
    }
    // At a speed where every point is finite, the same call is Ok.
    let k = m.kinematics(&[0.0], &[1e150], &[0.0]).unwrap();
    assert!(k.point("B").unwrap().acc.x.is_finite());
}

/// A one-crank mechanism with gravity, a torque load and the force element `element`
/// (its ends the ground's `C` and the crank's `A` or `O`).
fn crank_with(element: &str) -> String {
    format!(
        "pub struct Sprung {{
            gravity: (0.0, -9.81),
            ground {{ O: (0.0, 0.0), C: (0.1, 0.0) }},
            link crank {{ points {{ O, A: (0.1, 0.0) }}, mass: 1.0, inertia: 0.01, cg: (0.05, 0.01) }},
            joints {{ O: revolute(ground, crank) }},
            input: O,
            loads {{ t: torque on crank }},
            elements {{ {element} }},
        }}"
    )
}

/// 8. What the fuzzer of the run-time path found (issue 28, `mech-fuzz`), each an `Ok`
///    holding a non-finite number before, or an error naming the wrong cause.
///
///    A linear spring or damper whose ends are at the same place has no direction: its
///    force is undefined there. The run-time solvers reported it as an overflow ("the
///    inputs are too large for f64"); the dense oracle returned `Ok(NaN)` from
///    `reduced_moment`, `kinetostatics` and `driver_action` (589 of the 673 non-finite
///    results of a minute of outside fuzzing). Both now name the element, where its ends
///    are and the fix; a spring of zero free length and no damper, whose force k (Q − P)
///    vanishes there, is accepted and adds nothing.
#[test]
fn a_spring_of_zero_length_is_named_not_called_an_overflow() {
    for element in [
        // Ends on the same point of the pin: zero length in every configuration.
        "k1: spring(ground at O, crank at O) stiffness 2 kN_per_m free_length 80 mm,",
        "k1: damper(ground at O, crank at O) damping 5 N_s_per_m,",
        // Ends that meet in the drawing, q = 0.
        "k1: spring(ground at C, crank at A) stiffness 2 kN_per_m free_length 80 mm,",
    ] {
        let text = crank_with(element);
        let kind = if element.contains("damper") {
            "damper"
        } else {
            "spring"
        };
        let named = |r: Result<f64, MechError>, what: &str| match r {
            Err(MechError::InvalidInput(m)) => assert!(
                m.contains(&format!("{kind} `k1`")) && m.contains("same place"),
                "{element} {what}: {m}"
            ),
            other => panic!("{element} {what}: expected the spring named, got {other:?}"),
        };
        let m = Mechanism::from_dsl(&text).unwrap();
        let mut l = m.loads();
        assert!(l.set_by_name("t", &[1.0]));
        for qd in [0.0, 2.0] {
            let mo = m.kinematics(&[0.0], &[qd], &[0.0]).unwrap();
            named(
                m.kinetostatics(&mo, &l).map(|f| f.driver[0]),
                "kinetostatics",
            );
            named(m.driver_action(&mo, &l).map(|d| d[0]), "driver_action");
        }
        named(m.reduced_moment(0.0, &l), "reduced_moment");
        named(m.acceleration(0.0, 1.0, 0.0, &l), "acceleration");
        let o = GenericMechanism::parse(&text).unwrap();
        let mut l = o.loads();
        assert!(l.set_by_name("t", &[1.0]));
        for qd in [0.0, 2.0] {
            let mo = o.kinematics(&[0.0], &[qd], &[0.0]).unwrap();
            named(
                o.kinetostatics(&mo, &l).map(|f| f.driver[0]),
                "oracle kinetostatics",
            );
            named(
                o.driver_action(&mo, &l).map(|d| d[0]),
                "oracle driver_action",
            );
        }
        named(o.reduced_moment(0.0, &l), "oracle reduced_moment");
        named(o.acceleration(0.0, 1.0, 0.0, &l), "oracle acceleration");
        // Away from the coincidence every solver answers.
        if element.contains("at C") {
            let mo = m.kinematics(&[0.5], &[2.0], &[0.0]).unwrap();
            assert!(m.driver_action(&mo, &m.loads()).unwrap()[0].is_finite());
            assert!(m.reduced_moment(0.5, &m.loads()).unwrap().is_finite());
        }
    }
    // A spring of zero free length and no damper: its force k (Q − P) is zero where its
    // ends meet; every route gives the results of the crank without it.
    let zero = Mechanism::from_dsl(&crank_with(
        "k1: spring(ground at O, crank at O) stiffness 2 kN_per_m free_length 0 mm,",
    ))
    .unwrap();
    let bare = Mechanism::from_dsl(&crank_with("")).unwrap();
    let (mut lz, mut lb) = (zero.loads(), bare.loads());
    assert!(lz.set_by_name("t", &[1.0]) && lb.set_by_name("t", &[1.0]));
    for (q, qd) in [(0.0, 0.0), (0.7, 2.0)] {
        let (mz, mb) = (
            zero.kinematics(&[q], &[qd], &[1.0]).unwrap(),
            bare.kinematics(&[q], &[qd], &[1.0]).unwrap(),
        );
        assert_eq!(
            zero.kinetostatics(&mz, &lz).unwrap().driver,
            bare.kinetostatics(&mb, &lb).unwrap().driver
        );
        assert_eq!(
            zero.driver_action(&mz, &lz).unwrap(),
            bare.driver_action(&mb, &lb).unwrap()
        );
        assert_eq!(
            zero.reduced_moment(q, &lz).unwrap(),
            bare.reduced_moment(q, &lb).unwrap()
        );
        assert_eq!(zero.potential_energy(&mz), bare.potential_energy(&mb));
    }
}

/// 8b. The energies: a finite speed whose kinetic energy overflows f64 (I ω² with
///     ω = 1e153 rad/s, I = 1e3 kg·m², while ω² r = 1e305 m/s² is finite) is an error
///     naming the energy, not `Ok(inf)` from `total_energy`.
#[test]
fn an_energy_that_overflows_is_an_error() {
    let m = Mechanism::from_dsl(
        "pub struct Heavy {
            ground { O: (0.0, 0.0) },
            link crank { points { O, A: (0.1, 0.0) }, mass: 1.0, inertia: 1000.0, cg: (0.05, 0.0) },
            joints { O: revolute(ground, crank) },
            input: O,
        }",
    )
    .unwrap();
    let w = 1e153;
    assert!(m.kinematics(&[0.3], &[w], &[0.0]).is_ok());
    invalid(
        mech::dynamics::total_energy(&m, &[0.3], &[w]),
        "kinetic and potential energy overflow",
    );
    let e = mech::dynamics::total_energy(&m, &[0.3], &[1e150]).unwrap();
    assert!(e.is_finite() && e > 0.0);
}

/// 8c. The flywheel of a cycle: a mean speed of 1e200 rad/s gave `Ok` with an infinite
///     energy, an irregularity of 1e-300 `Ok` with an infinite inertia (a − b =
///     (1 + ε/2)² − (1 − ε/2)² rounded to 0). The difference is now 2ε exactly (it lost
///     the digits of any small ε: a relative error of 1e-6 at ε = 1e-10), and a result
///     that still overflows is an error naming it.
#[test]
fn a_flywheel_of_extreme_speed_or_irregularity_is_finite_or_an_error() {
    use mech::flywheel::Cycle;
    // A crank with its cg off the pin under gravity: M*(q) = −m g r cos q, I* = I_O.
    let m = Mechanism::from_dsl(
        "pub struct Pendulum {
            gravity: (0.0, -9.81),
            ground { O: (0.0, 0.0) },
            link crank { points { O, A: (0.1, 0.0) }, mass: 2.0, inertia: 0.01, cg: (0.05, 0.0) },
            joints { O: revolute(ground, crank) },
            input: O,
        }",
    )
    .unwrap();
    let cycle = Cycle::of(&m, std::f64::consts::TAU, |_| Ok(m.loads())).unwrap();
    invalid(
        cycle.flywheel(1e200, 0.05).map(|_| ()),
        "flywheel's inertia and energy overflow",
    );
    // I* is constant (I_O = I_G + m r² = 0.015 kg·m²), so Wittenbauer's inertia is the
    // approximate one less I*, to the digits of the extremes.
    let i_o = 0.01 + 2.0 * 0.05 * 0.05;
    for eps in [0.05, 1e-10, 1e-300] {
        let fw = cycle.flywheel(10.0, eps).unwrap();
        let (exact, approx) = (fw.exact.inertia, fw.approximate.inertia);
        assert!(
            exact.is_finite() && fw.exact.state.energy.is_finite() && fw.exact.c.is_finite(),
            "ε = {eps}: {fw:?}"
        );
        assert!(
            (exact - (approx - i_o)).abs() <= 1e-9 * approx,
            "ε = {eps}: exact {exact}, approximate {approx} − I* {i_o}"
        );
    }
}

/// 8d. Lagrange's equations: q̈ = M⁻¹ (τ − b) of finite terms overflowed inside `Ok`
///     (a damper of 1e308 N·m·s/rad: b = c q̇ = 1e308, over a mass matrix of 0.0125
///     kg·m², gave q̈ = −inf). An error naming q̈ now; the mass matrix likewise.
#[test]
fn a_lagrange_acceleration_that_overflows_is_an_error() {
    let m = Mechanism::from_dsl(&crank_with(
        "k1: rotary_damper(ground, crank) damping 1e308 N_m_s_per_rad,",
    ))
    .unwrap();
    let l = m.loads();
    let b = mech::dynamics::velocity_terms::<_, 1>(&m, &[0.3], &[1.0], &l).unwrap();
    assert!(b[0].is_finite() && b[0] > 1e307, "{b:?}");
    invalid(
        mech::dynamics::lagrange_acceleration::<_, 1>(&m, &[0.3], &[1.0], &[0.0], &l),
        "accelerations q̈",
    );
    let a = mech::dynamics::lagrange_acceleration::<_, 1>(&m, &[0.3], &[1e-300], &[0.0], &l);
    assert!(a.unwrap()[0].is_finite());
}

mechanism! {
    /// A crank with a point far from its pivot (`point_accelerations_that_overflow_are_an_error`,
    /// generated).
    pub struct FarCrank {
        ground { O: (0.0, 0.0) },
        link crank { points { O, A: (0.01, 0.0), B: (10.0, 0.0) } },
        joints { O: revolute(ground, crank) },
        input: O,
    }
}

/// The generated struct, as the run-time mechanism above: a point acceleration that
/// overflows (ω² |OB| = 1e309 where the link's own state is finite) is an error naming
/// the overflow, never `Ok` with an infinity; the same call at a speed where every point
/// is finite is `Ok`.
#[test]
fn generated_point_accelerations_that_overflow_are_an_error() {
    let m = FarCrank::new();
    let w: f64 = 1e154;
    match m.kinematics(0.0, w, 0.0) {
        Ok(k) => panic!("Ok with B.acc = {:?}", k.point("B").map(|p| p.acc)),
        Err(e) => assert!(e.to_string().contains("overflow"), "{e}"),
    }
    let k = m.kinematics(0.0, 1e150, 0.0).unwrap();
    assert!(k.point("B").unwrap().acc.x.is_finite());
}
