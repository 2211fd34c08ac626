//! Motors: the driver action as a function of speed (`docs/theory.md` §6, the direct
//! problem: "the power and torque specifications of the motors are sufficient").
//!
//! A [`Motor`] gives the torque T(ω) on its own shaft (N·m, ω in rad/s) by one of four
//! curves ([`Curve`]), and drives the machine's input through an ideal reduction of ratio
//! n = ω_motor / q̇ (no losses): the action on the input is n·T(n·q̇)
//! ([`Motor::on_input`]). Negative speeds and torques keep their signs (an induction
//! machine driven above its synchronous speed is a generator: its torque is negative).

use crate::MechError;

/// The torque–speed curve of a motor, on its own shaft.
#[derive(Clone, Debug, PartialEq)]
pub enum Curve {
    /// T(ω) = T — a constant torque, N·m.
    Constant {
        /// The torque, N·m.
        torque: f64,
    },
    /// A DC motor (separately excited or permanent magnet, armature voltage fixed):
    /// T(ω) = T_s (1 − ω/ω₀), linear from the stall torque T_s (N·m) at rest to zero at the
    /// no-load speed ω₀ (rad/s).
    Dc {
        /// T_s, N·m.
        stall_torque: f64,
        /// ω₀, rad/s.
        no_load_speed: f64,
    },
    /// An induction motor by Kloss's formula: with the slip s = (ω_s − ω)/ω_s,
    /// T(ω) = 2 T_b / (s/s_b + s_b/s) = 2 T_b s s_b / (s² + s_b²), where the breakdown torque
    /// T_b = k T_r (k the breakdown ratio, T_r = P_r / ω_r the rated torque) and the breakdown
    /// slip s_b = s_r (k + √(k² − 1)) put the rated point (ω_r, T_r) on the curve.
    Induction {
        /// P_r, W.
        rated_power: f64,
        /// ω_s, rad/s.
        synchronous_speed: f64,
        /// ω_r, rad/s (0 < ω_r < ω_s).
        rated_speed: f64,
        /// k = T_b / T_r (> 1).
        breakdown_ratio: f64,
    },
    /// A measured curve: torque (N·m) against speed (rad/s, strictly increasing), linear
    /// between the points and constant beyond the first and last.
    Table {
        /// Speeds, rad/s.
        speed: Vec<f64>,
        /// Torques, N·m.
        torque: Vec<f64>,
    },
}

/// A motor: its curve and the reduction between it and the machine's input.
#[derive(Clone, Debug, PartialEq)]
pub struct Motor {
    curve: Curve,
    ratio: f64,
}

fn positive(what: &str, v: f64, fix: &str) -> Result<(), MechError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(MechError::InvalidInput(format!(
            "the motor's {what} must be a positive finite number, got {v}: {fix}"
        )))
    }
}

impl Motor {
    /// A constant torque T (N·m) on the motor's shaft.
    pub fn constant(torque: f64) -> Result<Motor, MechError> {
        crate::error::check_finite("the motor's torque", &[torque])?;
        Ok(Curve::Constant { torque }.into())
    }

    /// A DC motor, T = T_s (1 − ω/ω₀): stall torque T_s (N·m) and no-load speed ω₀ (rad/s).
    pub fn dc(stall_torque: f64, no_load_speed: f64) -> Result<Motor, MechError> {
        positive("stall torque", stall_torque, "the torque at rest, N·m")?;
        positive(
            "no-load speed",
            no_load_speed,
            "the speed at zero torque, rad/s",
        )?;
        Ok(Curve::Dc {
            stall_torque,
            no_load_speed,
        }
        .into())
    }

    /// An induction motor by Kloss's formula (see [`Curve::Induction`]): rated power (W),
    /// synchronous and rated speeds (rad/s, rated below synchronous) and the breakdown
    /// ratio T_b / T_r (> 1).
    pub fn induction(
        rated_power: f64,
        synchronous_speed: f64,
        rated_speed: f64,
        breakdown_ratio: f64,
    ) -> Result<Motor, MechError> {
        positive(
            "rated power",
            rated_power,
            "the output at the rated speed, W",
        )?;
        positive(
            "synchronous speed",
            synchronous_speed,
            "2π f / pole pairs, rad/s",
        )?;
        positive(
            "rated speed",
            rated_speed,
            "the speed at rated power, rad/s",
        )?;
        if !(rated_speed < synchronous_speed) {
            return Err(MechError::InvalidInput(format!(
                "the motor's rated speed {rated_speed} rad/s must be below its synchronous speed {synchronous_speed} rad/s (an induction motor runs with a slip)"
            )));
        }
        if !(breakdown_ratio.is_finite() && breakdown_ratio > 1.0) {
            return Err(MechError::InvalidInput(format!(
                "the motor's breakdown ratio T_b/T_r must be a finite number above 1, got {breakdown_ratio} (catalogues give 2 to 3)"
            )));
        }
        Ok(Curve::Induction {
            rated_power,
            synchronous_speed,
            rated_speed,
            breakdown_ratio,
        }
        .into())
    }

    /// A torque–speed table: speeds (rad/s, strictly increasing) and torques (N·m), at
    /// least two points.
    pub fn table(speed: Vec<f64>, torque: Vec<f64>) -> Result<Motor, MechError> {
        crate::error::check_finite("the motor table's speeds", &speed)?;
        crate::error::check_finite("the motor table's torques", &torque)?;
        if speed.len() != torque.len() || speed.len() < 2 {
            return Err(MechError::InvalidInput(format!(
                "a motor table needs at least two (speed, torque) rows of equal length, got {} speeds and {} torques",
                speed.len(),
                torque.len()
            )));
        }
        if let Some(w) = speed.windows(2).find(|w| !(w[1] > w[0])) {
            return Err(MechError::InvalidInput(format!(
                "the motor table's speeds must increase strictly, but {} is followed by {}: sort the rows by speed",
                w[0], w[1]
            )));
        }
        Ok(Curve::Table { speed, torque }.into())
    }

    /// The same motor through a reduction of ratio n = ω_motor / q̇ (> 0; 1 is direct drive).
    pub fn through(mut self, ratio: f64) -> Result<Motor, MechError> {
        positive(
            "reduction ratio",
            ratio,
            "n = motor speed / input speed, e.g. 20 for a 20:1 gearbox",
        )?;
        self.ratio = ratio;
        Ok(self)
    }

    /// The curve.
    pub fn curve(&self) -> &Curve {
        &self.curve
    }

    /// The reduction ratio n = ω_motor / q̇.
    pub fn ratio(&self) -> f64 {
        self.ratio
    }

    /// The torque on the motor's shaft at its speed ω, N·m.
    pub fn torque(&self, omega: f64) -> f64 {
        match &self.curve {
            Curve::Constant { torque } => *torque,
            Curve::Dc {
                stall_torque,
                no_load_speed,
            } => stall_torque * (1.0 - omega / no_load_speed),
            Curve::Induction {
                synchronous_speed, ..
            } => {
                let (tb, sb) = self.breakdown().expect("an induction curve");
                let s = (synchronous_speed - omega) / synchronous_speed;
                2.0 * tb * s * sb / (s * s + sb * sb)
            }
            Curve::Table { speed, torque } => {
                let k = speed.partition_point(|&w| w <= omega);
                if k == 0 {
                    torque[0]
                } else if k == speed.len() {
                    torque[k - 1]
                } else {
                    let t = (omega - speed[k - 1]) / (speed[k] - speed[k - 1]);
                    torque[k - 1] + t * (torque[k] - torque[k - 1])
                }
            }
        }
    }

    /// The action on the machine's input at its speed q̇: n·T(n·q̇), N·m.
    pub fn on_input(&self, qd: f64) -> f64 {
        self.ratio * self.torque(self.ratio * qd)
    }

    /// An induction motor's breakdown torque T_b (N·m) and slip s_b; `None` for the other
    /// curves.
    pub fn breakdown(&self) -> Option<(f64, f64)> {
        match self.curve {
            Curve::Induction {
                rated_power,
                synchronous_speed,
                rated_speed,
                breakdown_ratio: k,
            } => {
                let rated_torque = rated_power / rated_speed;
                let rated_slip = (synchronous_speed - rated_speed) / synchronous_speed;
                Some((k * rated_torque, rated_slip * (k + (k * k - 1.0).sqrt())))
            }
            _ => None,
        }
    }

    /// The rated (continuous) torque and speed on the motor's shaft (N·m, rad/s) where the
    /// curve states them: an induction motor's rated point; a DC motor's point of largest
    /// power (T_s/2, ω₀/2); none for a constant or a table.
    pub fn rating(&self) -> Option<(f64, f64)> {
        match self.curve {
            Curve::Induction {
                rated_power,
                rated_speed,
                ..
            } => Some((rated_power / rated_speed, rated_speed)),
            Curve::Dc {
                stall_torque,
                no_load_speed,
            } => Some((stall_torque / 2.0, no_load_speed / 2.0)),
            _ => None,
        }
    }

    /// The motor's speed at zero torque (rad/s, on its shaft): ω₀ for DC, ω_s for
    /// induction, the table's first zero crossing; `None` for a constant torque or a table
    /// that does not cross zero.
    pub fn free_speed(&self) -> Option<f64> {
        match &self.curve {
            Curve::Constant { .. } => None,
            Curve::Dc { no_load_speed, .. } => Some(*no_load_speed),
            Curve::Induction {
                synchronous_speed, ..
            } => Some(*synchronous_speed),
            Curve::Table { speed, torque } => (1..speed.len()).find_map(|k| {
                let (a, b) = (torque[k - 1], torque[k]);
                (a > 0.0 && b <= 0.0)
                    .then(|| speed[k - 1] + (speed[k] - speed[k - 1]) * a / (a - b))
            }),
        }
    }
}

impl From<Curve> for Motor {
    fn from(curve: Curve) -> Motor {
        Motor { curve, ratio: 1.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kloss's curve passes through the rated point, peaks at (s_b, T_b), is zero at the
    /// synchronous speed and odd in the slip (a generator above it).
    #[test]
    fn the_induction_curve_is_kloss_through_its_rated_and_breakdown_points() {
        let ws = 1500.0 * std::f64::consts::PI / 30.0;
        let wr = 1440.0 * std::f64::consts::PI / 30.0;
        let m = Motor::induction(4000.0, ws, wr, 2.6).unwrap();
        let tr = 4000.0 / wr;
        assert!((m.torque(wr) - tr).abs() < 1e-12 * tr);
        let (tb, sb) = m.breakdown().unwrap();
        assert!((tb - 2.6 * tr).abs() < 1e-12 * tb);
        let wb = ws * (1.0 - sb);
        assert!((m.torque(wb) - tb).abs() < 1e-12 * tb);
        for d in [1e-3, 1e-2, 0.1] {
            assert!(m.torque(wb * (1.0 + d)) < tb && m.torque(wb * (1.0 - d)) < tb);
        }
        assert_eq!(m.torque(ws), 0.0);
        let s = 0.013;
        assert!((m.torque(ws * (1.0 - s)) + m.torque(ws * (1.0 + s))).abs() < 1e-12 * tb);
        // At rest (s = 1) Kloss's starting torque 2 T_b / (1/s_b + s_b).
        assert!((m.torque(0.0) - 2.0 * tb / (1.0 / sb + sb)).abs() < 1e-12 * tb);
    }

    /// The DC line, the reduction n T(n q̇), the table's interpolation and clamping.
    #[test]
    fn curves_and_the_reduction() {
        let m = Motor::dc(2.0, 300.0).unwrap().through(10.0).unwrap();
        assert_eq!(m.on_input(0.0), 20.0);
        assert!((m.on_input(15.0) - 10.0 * 2.0 * 0.5).abs() < 1e-15);
        assert_eq!(m.free_speed(), Some(300.0));
        let t = Motor::table(vec![0.0, 100.0, 200.0], vec![5.0, 3.0, -1.0]).unwrap();
        assert_eq!(t.torque(-5.0), 5.0);
        assert!((t.torque(150.0) - 1.0).abs() < 1e-15);
        assert_eq!(t.torque(900.0), -1.0);
        assert!((t.free_speed().unwrap() - 175.0).abs() < 1e-12);
    }

    /// Bad parameters are errors that name the fix.
    #[test]
    fn bad_motors_are_refused() {
        let e = Motor::induction(1e3, 100.0, 120.0, 2.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("below its synchronous speed"), "{e}");
        let e = Motor::induction(1e3, 100.0, 95.0, 0.8)
            .unwrap_err()
            .to_string();
        assert!(e.contains("above 1"), "{e}");
        let e = Motor::dc(-1.0, 10.0).unwrap_err().to_string();
        assert!(e.contains("stall torque"), "{e}");
        let e = Motor::table(vec![0.0, 0.0], vec![1.0, 2.0])
            .unwrap_err()
            .to_string();
        assert!(e.contains("increase strictly"), "{e}");
        let e = Motor::dc(1.0, 10.0)
            .unwrap()
            .through(0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("gearbox"), "{e}");
    }
}
