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
        let pages = s.split_whitespace().nth(1).and_then(|v| v.parse::<usize>().ok());
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
