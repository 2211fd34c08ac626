//! Shared helpers of the integration tests: reading the reference tables and comparing
//! with a tolerance relative to the largest entry of the same kind.
#![allow(dead_code)]

use mech::prelude::Vector2;
use serde_json::Value;

/// Relative tolerance of `docs/conventions.md#solver-requirements`.
pub const REL: f64 = 1e-12;

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

/// The largest entry of each kind in one configuration of a truth table.
pub struct Kinds {
    pub pos: f64,
    pub vel: f64,
    pub acc: f64,
    pub omega: f64,
    pub alpha: f64,
    pub force: f64,
    pub length: f64,
}

fn max_abs(v: &Value) -> f64 {
    nums(v).iter().fold(0.0, |a, x| a.max(x.abs()))
}

impl Kinds {
    pub fn of(c: &Value) -> Kinds {
        let mut k = Kinds {
            pos: 0.0,
            vel: 0.0,
            acc: 0.0,
            omega: 0.0,
            alpha: 0.0,
            force: 0.0,
            length: 0.0,
        };
        for (_, l) in c["links"].as_object().unwrap() {
            k.omega = k.omega.max(l["omega"].as_f64().unwrap().abs());
            k.alpha = k.alpha.max(l["alpha"].as_f64().unwrap().abs());
            let mut all = vec![&l["cg"]];
            all.extend(l["points"].as_object().unwrap().values());
            for p in all {
                k.pos = k.pos.max(max_abs(&p["pos"]));
                k.vel = k.vel.max(max_abs(&p["vel"]));
                k.acc = k.acc.max(max_abs(&p["acc"]));
            }
        }
        if let Some(r) = c.get("reactions").and_then(|r| r.as_object()) {
            for (_, j) in r {
                k.force = k.force.max(max_abs(&j["force"]));
            }
        }
        k.length = k.pos.max(1e-300);
        k
    }

    pub fn close(&self, ctx: &str, what: &str, got: f64, want: f64, scale: f64) {
        let tol = REL * scale.max(1e-300);
        assert!(
            (got - want).abs() <= tol,
            "{ctx}: {what}: got {got:.17e}, want {want:.17e}, error {:.3e} > {tol:.3e}",
            (got - want).abs()
        );
    }

    pub fn vec(&self, ctx: &str, what: &str, got: Vector2<f64>, want: &Value, scale: f64) {
        let w = nums(want);
        self.close(ctx, &format!("{what}.x"), got.x, w[0], scale);
        self.close(ctx, &format!("{what}.y"), got.y, w[1], scale);
    }

    /// Angles compare modulo 2π, absolute 1e-12 rad.
    pub fn angle(&self, ctx: &str, what: &str, got: f64, want: f64) {
        let d = (got - want).rem_euclid(std::f64::consts::TAU);
        let d = d.min(std::f64::consts::TAU - d);
        assert!(
            d <= 1e-12,
            "{ctx}: angle of {what}: got {got}, want {want}, error {d:.3e}"
        );
    }
}
