//! Units of the DSL (`docs/conventions.md#dimensions`): the unit words a number may carry,
//! their factor to SI and their physical dimension.
//!
//! A [`Dim`] is the vector of exponents of (m, kg, s, rad). A plain number has no
//! dimension of its own (it is SI of whatever goes there); a number with a unit word
//! carries that unit's dimension through the arithmetic of [`crate::front::expr`], so that a
//! length written where an angle goes, or a sum of a length and an angle, is an error
//! instead of a silently wrong drawing.

use std::fmt;

/// Exponents of (metre, kilogram, second, radian).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dim(pub [i8; 4]);

impl Dim {
    /// No dimension (a ratio, a sine).
    pub const NONE: Dim = Dim([0, 0, 0, 0]);
    /// Length, m.
    pub const LENGTH: Dim = Dim([1, 0, 0, 0]);
    /// Mass, kg.
    pub const MASS: Dim = Dim([0, 1, 0, 0]);
    /// Moment of inertia, kg·m².
    pub const INERTIA: Dim = Dim([2, 1, 0, 0]);
    /// Plane angle, rad.
    pub const ANGLE: Dim = Dim([0, 0, 0, 1]);
    /// Acceleration, m/s².
    pub const ACCELERATION: Dim = Dim([1, 0, -2, 0]);
    /// Force, N = kg·m/s².
    pub const FORCE: Dim = Dim([1, 1, -2, 0]);
    /// Torque, N·m.
    pub const TORQUE: Dim = Dim([2, 1, -2, 0]);
    /// Stiffness, N/m.
    pub const STIFFNESS: Dim = Dim([0, 1, -2, 0]);
    /// Torsional stiffness, N·m/rad.
    pub const TORSIONAL_STIFFNESS: Dim = Dim([2, 1, -2, -1]);
    /// Damping, N·s/m.
    pub const DAMPING: Dim = Dim([0, 1, -1, 0]);
    /// Torsional damping, N·m·s/rad.
    pub const TORSIONAL_DAMPING: Dim = Dim([2, 1, -1, -1]);
    /// Angular speed, rad/s.
    pub const SPEED: Dim = Dim([0, 0, -1, 1]);
    /// Density, kg/m³.
    pub const DENSITY: Dim = Dim([-3, 1, 0, 0]);
    /// Pressure and stress, Pa = N/m².
    pub const PRESSURE: Dim = Dim([-1, 1, -2, 0]);
    /// Power, W = N·m/s = kg·m²/s³ (a motor's rated power).
    pub const POWER: Dim = Dim([2, 1, -3, 0]);

    /// The dimension of a product: exponents added.
    pub fn times(self, o: Dim) -> Dim {
        Dim(std::array::from_fn(|i| self.0[i] + o.0[i]))
    }

    /// The dimension of a quotient: exponents subtracted.
    pub fn per(self, o: Dim) -> Dim {
        Dim(std::array::from_fn(|i| self.0[i] - o.0[i]))
    }

    /// The dimension of a square root; `None` when an exponent is odd.
    pub fn sqrt(self) -> Option<Dim> {
        self.0
            .iter()
            .all(|e| e % 2 == 0)
            .then(|| Dim(self.0.map(|e| e / 2)))
    }

    /// What a quantity of this dimension is, in words ("a length (m)").
    pub fn describe(self) -> String {
        const NAMED: [(Dim, &str); 16] = [
            (Dim::NONE, "a plain number"),
            (Dim::LENGTH, "a length (m)"),
            (Dim::MASS, "a mass (kg)"),
            (Dim::INERTIA, "a moment of inertia (kg·m²)"),
            (Dim::ANGLE, "an angle (rad)"),
            (Dim::ACCELERATION, "an acceleration (m/s²)"),
            (Dim::FORCE, "a force (N)"),
            (Dim::TORQUE, "a torque (N·m)"),
            (Dim::STIFFNESS, "a stiffness (N/m)"),
            (Dim::TORSIONAL_STIFFNESS, "a torsional stiffness (N·m/rad)"),
            (Dim::DAMPING, "a damping (N·s/m)"),
            (Dim::TORSIONAL_DAMPING, "a torsional damping (N·m·s/rad)"),
            (Dim::SPEED, "an angular speed (rad/s)"),
            (Dim::DENSITY, "a density (kg/m³)"),
            (Dim::PRESSURE, "a pressure or stress (Pa)"),
            (Dim::POWER, "a power (W)"),
        ];
        match NAMED.iter().find(|(d, _)| *d == self) {
            Some((_, name)) => name.to_string(),
            None => format!("a quantity in {self}"),
        }
    }

    /// The unit words that give this dimension, for messages ("`m`, `cm` or `mm`").
    pub fn words(self) -> String {
        let words: Vec<String> = UNITS
            .iter()
            .filter(|u| u.dim == self)
            .map(|u| format!("`{}`", u.word))
            .collect();
        match words.len() {
            0 => "no unit word (write it in SI)".to_string(),
            1 => words[0].clone(),
            n => format!("{} or {}", words[..n - 1].join(", "), words[n - 1]),
        }
    }
}

impl fmt::Display for Dim {
    /// SI base units with exponents: `m·kg·s^-2`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let parts: Vec<String> = ["m", "kg", "s", "rad"]
            .iter()
            .zip(self.0)
            .filter(|(_, e)| *e != 0)
            .map(|(u, e)| {
                if e == 1 {
                    u.to_string()
                } else {
                    format!("{u}^{e}")
                }
            })
            .collect();
        if parts.is_empty() {
            f.write_str("1")
        } else {
            f.write_str(&parts.join("·"))
        }
    }
}

/// One unit word: x (in the word) = `factor` × x (in SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unit {
    /// The word as written after a number.
    pub word: &'static str,
    /// Its value in SI units.
    pub factor: f64,
    /// Its dimension.
    pub dim: Dim,
}

const fn unit(word: &'static str, factor: f64, dim: Dim) -> Unit {
    Unit { word, factor, dim }
}

/// Every unit word of the DSL, with its factor to SI.
pub const UNITS: [Unit; 30] = [
    unit("m", 1.0, Dim::LENGTH),
    unit("cm", 1e-2, Dim::LENGTH),
    unit("mm", 1e-3, Dim::LENGTH),
    unit("kg", 1.0, Dim::MASS),
    unit("g", 1e-3, Dim::MASS),
    unit("kg_m2", 1.0, Dim::INERTIA),
    unit("g_cm2", 1e-7, Dim::INERTIA),
    unit("g_mm2", 1e-9, Dim::INERTIA),
    unit("deg", std::f64::consts::PI / 180.0, Dim::ANGLE),
    unit("rad", 1.0, Dim::ANGLE),
    unit("N", 1.0, Dim::FORCE),
    unit("kN", 1e3, Dim::FORCE),
    unit("N_m", 1.0, Dim::TORQUE),
    unit("N_per_m", 1.0, Dim::STIFFNESS),
    unit("N_per_mm", 1e3, Dim::STIFFNESS),
    unit("kN_per_m", 1e3, Dim::STIFFNESS),
    unit("N_m_per_rad", 1.0, Dim::TORSIONAL_STIFFNESS),
    unit("N_s_per_m", 1.0, Dim::DAMPING),
    unit("N_m_s_per_rad", 1.0, Dim::TORSIONAL_DAMPING),
    unit("rpm", std::f64::consts::PI / 30.0, Dim::SPEED),
    unit("rad_per_s", 1.0, Dim::SPEED),
    unit("kg_per_m3", 1.0, Dim::DENSITY),
    unit("Pa", 1.0, Dim::PRESSURE),
    unit("kPa", 1e3, Dim::PRESSURE),
    unit("MPa", 1e6, Dim::PRESSURE),
    unit("GPa", 1e9, Dim::PRESSURE),
    unit("W", 1.0, Dim::POWER),
    unit("kW", 1e3, Dim::POWER),
    // Accepted as Rust's own literal suffixes (`2f64`): no unit.
    unit("f64", 1.0, Dim::NONE),
    unit("f32", 1.0, Dim::NONE),
];

/// The unit named `word`, if any.
pub fn lookup(word: &str) -> Option<&'static Unit> {
    UNITS.iter().find(|u| u.word == word)
}

/// The unit words, for an "unknown unit" message.
pub fn all_words() -> String {
    UNITS
        .iter()
        .filter(|u| u.dim != Dim::NONE)
        .map(|u| u.word)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::measure::within;

    #[test]
    fn factors_to_si() {
        let f = |w: &str| lookup(w).unwrap().factor;
        // measured worst 0 (be05608); exact; a fraction of an ulp
        assert!(within((f("mm") * 200.0 - 0.2).abs(), f64::EPSILON * 0.2));
        assert_eq!(f("g_cm2"), 1e-7, "1 g·cm² = 1e-3 kg × 1e-4 m²");
        assert_eq!(f("g_mm2"), 1e-9, "1 g·mm² = 1e-3 kg × 1e-6 m²");
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within(
            (f("rpm") * 60.0 - 2.0 * std::f64::consts::PI).abs(),
            1e-15
        ));
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within(
            (f("deg") * 180.0 - std::f64::consts::PI).abs(),
            1e-15
        ));
        assert_eq!(lookup("furlong"), None);
    }

    /// `W` and `kW` are powers (N·m/s): a torque times an angular speed, a force times a
    /// velocity (their use in an expression: `dynamics::motor_parse`'s tests).
    #[test]
    fn watts_are_torque_times_speed() {
        assert_eq!(Dim::TORQUE.per(Dim::ANGLE).times(Dim::SPEED), Dim::POWER);
        assert_eq!(
            Dim::FORCE.times(Dim::LENGTH).per(Dim([0, 0, 1, 0])),
            Dim::POWER
        );
        assert_eq!(
            lookup("W").map(|u| (u.factor, u.dim)),
            Some((1.0, Dim::POWER))
        );
        assert_eq!(
            lookup("kW").map(|u| (u.factor, u.dim)),
            Some((1e3, Dim::POWER))
        );
        assert_eq!(Dim::POWER.describe(), "a power (W)");
        assert_eq!(Dim::POWER.words(), "`W` or `kW`");
    }

    #[test]
    fn dimensions_compose() {
        assert_eq!(Dim::FORCE.times(Dim::LENGTH), Dim::TORQUE);
        assert_eq!(Dim::TORQUE.per(Dim::ANGLE), Dim::TORSIONAL_STIFFNESS);
        assert_eq!(Dim::INERTIA.per(Dim::MASS).sqrt(), Some(Dim::LENGTH));
        assert_eq!(Dim::LENGTH.sqrt(), None);
        assert_eq!(Dim::LENGTH.describe(), "a length (m)");
        assert_eq!(Dim::LENGTH.words(), "`m`, `cm` or `mm`");
        assert_eq!(Dim::LENGTH.times(Dim::LENGTH).to_string(), "m^2");
    }
}
