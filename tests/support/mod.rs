//! Shared helpers of the integration tests: reading the reference tables and comparing
//! with a tolerance relative to the largest entry of the same kind.
#![allow(dead_code)]

use crate::measure::within_at;
use mech::prelude::Vector2;
use serde_json::Value;

/// A truth or mechanism file of `tests/data/`.
pub fn truth(name: &str) -> Value {
    let path = format!(
        "{}/tests/data/{name}.truth.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}")))
        .unwrap()
}

/// A number or a list of numbers as a Vec.
pub fn nums(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().map(|x| x.as_f64().unwrap()).collect(),
        x => vec![x.as_f64().unwrap()],
    }
}

/// A motor action (one DOF: f64; several: an array) as a slice.
pub trait AsVec {
    fn to_vec(&self) -> Vec<f64>;
}
impl AsVec for f64 {
    fn to_vec(&self) -> Vec<f64> {
        vec![*self]
    }
}
impl<const N: usize> AsVec for [f64; N] {
    fn to_vec(&self) -> Vec<f64> {
        self.as_slice().to_vec()
    }
}
pub fn as_vec<T: AsVec>(t: &T) -> Vec<f64> {
    t.to_vec()
}

/// Tolerances against the 50-digit tables of `tests/data/` (`reference.rs`: the generated
/// structs; `generic.rs`, `mechanism.rs` through `against_reference.rs`: the run-time
/// solvers against the tables and against the generated structs), relative to the largest
/// entry of the same kind in the configuration (an angle: absolute, rad). Each is at most
/// 100× the worst error measured over every comparison that uses it (issue 28; the rule
/// and how to re-measure: `tests/README.md`, "Tolerances"). The relative tolerance of
/// `docs/conventions.md#solver-requirements`, 1e-12, is the requirement; these are what
/// the solvers achieve.
pub mod tol {
    /// Link angles, rad. Measured worst 1.3e-15 (be05608); 100× = 1.3e-13.
    pub const ANGLE: f64 = 1e-13;
    /// Point and cg positions. Measured worst 5.0e-16 (be05608); 100× = 5.0e-14.
    pub const POS: f64 = 5e-14;
    /// Point and cg velocities. Measured worst 1.3e-15 (be05608); 100× = 1.3e-13.
    pub const VEL: f64 = 1e-13;
    /// Point and cg accelerations. Measured worst 2.3e-15 (be05608); 100× = 2.3e-13.
    pub const ACC: f64 = 2e-13;
    /// Angular velocities. Measured worst 5.6e-16 (be05608); 100× = 5.6e-14.
    pub const OMEGA: f64 = 5e-14;
    /// Angular accelerations. Measured worst 2.3e-15 (be05608); 100× = 2.3e-13.
    pub const ALPHA: f64 = 2e-13;
    /// Reaction forces. Measured worst 1.6e-15 (be05608); 100× = 1.6e-13.
    pub const FORCE: f64 = 1e-13;
    /// Prismatic reaction moments, on the largest force times the largest position.
    /// Measured worst 2.3e-16 (be05608); 100× = 2.3e-14.
    pub const MOMENT: f64 = 2e-14;
    /// Motor actions of the generated structs (d'Alembert, virtual power, Zhukovski), on
    /// the largest motor action (Zhukovski: or M*). Measured worst 7.3e-15 (be05608);
    /// 100× = 7.3e-13.
    pub const DRIVER: f64 = 5e-13;
    /// Motor actions of the run-time solvers (`generic.rs`, `mechanism.rs`). Measured
    /// worst 1.5e-14 (be05608); 100× = 1.5e-12.
    pub const RUNTIME_DRIVER: f64 = 1e-12;
    /// I*, on itself. Measured worst 1.7e-15 (be05608); 100× = 1.7e-13.
    pub const INERTIA: f64 = 1e-13;
    /// dI*/dq, on the larger of I* and |dI*/dq|. Measured worst 5.0e-15 (be05608);
    /// 100× = 5.0e-13.
    pub const INERTIA_DERIVATIVE: f64 = 2e-13;
    /// M*, on the larger of |M*| and the motor torque. Measured worst 7.0e-15 (be05608);
    /// 100× = 7.0e-13.
    pub const REDUCED_MOMENT: f64 = 5e-13;
    /// q̈ of the direct problem, on max(|q̈|, 1). Measured worst 4.6e-13 (be05608);
    /// 100× = 4.6e-11.
    pub const QDD: f64 = 2e-11;
}

/// One kind of quantity in one configuration: its name, its scale (the largest entry of the
/// kind), and its relative tolerance (`tol`).
#[derive(Clone, Copy, Debug)]
pub struct Scale {
    pub kind: &'static str,
    pub value: f64,
    pub rel: f64,
}

impl Scale {
    pub fn new(kind: &'static str, value: f64, rel: f64) -> Scale {
        Scale { kind, value, rel }
    }
    pub fn driver(value: f64) -> Scale {
        Scale::new("driver", value, tol::DRIVER)
    }
    pub fn runtime_driver(value: f64) -> Scale {
        Scale::new("run-time driver", value, tol::RUNTIME_DRIVER)
    }
    pub fn inertia(value: f64) -> Scale {
        Scale::new("I*", value, tol::INERTIA)
    }
    pub fn inertia_derivative(value: f64) -> Scale {
        Scale::new("dI*/dq", value, tol::INERTIA_DERIVATIVE)
    }
    pub fn reduced_moment(value: f64) -> Scale {
        Scale::new("M*", value, tol::REDUCED_MOMENT)
    }
    pub fn qdd(value: f64) -> Scale {
        Scale::new("q''", value, tol::QDD)
    }
}

/// The largest entry of each kind in one configuration of a truth table.
pub struct Kinds {
    pub pos: Scale,
    pub vel: Scale,
    pub acc: Scale,
    pub omega: Scale,
    pub alpha: Scale,
    pub force: Scale,
    /// Prismatic moments: the largest force times the largest position.
    pub moment: Scale,
}

fn max_abs(v: &Value) -> f64 {
    nums(v).iter().fold(0.0, |a, x| a.max(x.abs()))
}

impl Kinds {
    pub fn of(c: &Value) -> Kinds {
        let (mut pos, mut vel, mut acc, mut omega, mut alpha, mut force) =
            (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for (_, l) in c["links"].as_object().unwrap() {
            omega = omega.max(l["omega"].as_f64().unwrap().abs());
            alpha = alpha.max(l["alpha"].as_f64().unwrap().abs());
            let mut all = vec![&l["cg"]];
            all.extend(l["points"].as_object().unwrap().values());
            for p in all {
                pos = pos.max(max_abs(&p["pos"]));
                vel = vel.max(max_abs(&p["vel"]));
                acc = acc.max(max_abs(&p["acc"]));
            }
        }
        if let Some(r) = c.get("reactions").and_then(|r| r.as_object()) {
            for (_, j) in r {
                force = force.max(max_abs(&j["force"]));
            }
        }
        Kinds {
            pos: Scale::new("pos", pos, tol::POS),
            vel: Scale::new("vel", vel, tol::VEL),
            acc: Scale::new("acc", acc, tol::ACC),
            omega: Scale::new("omega", omega, tol::OMEGA),
            alpha: Scale::new("alpha", alpha, tol::ALPHA),
            force: Scale::new("force", force, tol::FORCE),
            moment: Scale::new("moment", force * pos.max(1e-300), tol::MOMENT),
        }
    }

    /// |got − want| ≤ the kind's tolerance × its scale; measured under the kind's name.
    #[track_caller]
    pub fn close(&self, ctx: &str, what: &str, got: f64, want: f64, scale: Scale) {
        let tol = scale.rel * scale.value.max(1e-300);
        assert!(
            within_at(scale.kind, (got - want).abs(), tol),
            "{ctx}: {what}: got {got:.17e}, want {want:.17e}, error {:.3e} > {tol:.3e}",
            (got - want).abs()
        );
    }

    #[track_caller]
    pub fn vec(&self, ctx: &str, what: &str, got: Vector2<f64>, want: &Value, scale: Scale) {
        let w = nums(want);
        self.close(ctx, &format!("{what}.x"), got.x, w[0], scale);
        self.close(ctx, &format!("{what}.y"), got.y, w[1], scale);
    }

    /// Angles compare modulo 2π, absolute `tol::ANGLE` rad.
    #[track_caller]
    pub fn angle(&self, ctx: &str, what: &str, got: f64, want: f64) {
        let d = (got - want).rem_euclid(std::f64::consts::TAU);
        let d = d.min(std::f64::consts::TAU - d);
        assert!(
            within_at("angle", d, tol::ANGLE),
            "{ctx}: angle of {what}: got {got}, want {want}, error {d:.3e}"
        );
    }
}
