//! A windscreen-wiper drive: a spatial RSSR declared with `mechanism!` (`space` first).
//!
//! ```text
//! cargo run --release --example wiper
//! ```
//!
//! The motor's crank turns about x; a rod with a ball joint at each end drives the wiper's
//! spindle, which turns about z. The macro checks Kutzbach's count at compile time
//! (G = 6·3 − 5·2 − 3·2 = 2, one of them the rod's idle spin about its own axis: one input)
//! and generates `Wiper` with typed results. At 60 rpm, with the blade's friction on the
//! glass resisting the spindle by 1.5 N·m, the example prints every 30° the spindle's angle,
//! the motor torque (d'Alembert and virtual power), and the ball joints' loads, then writes
//! the spindle's angle and the motor torque over a turn to `target/mech-figures/wiper/`.

#[path = "common/plot.rs"]
mod plot;

use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use mech::prelude::*;
use plot::Series;

mechanism! {
    /// A windscreen-wiper drive: crank about x, rod with two ball joints, spindle about z.
    pub struct Wiper {
        space,
        gravity: (0.0, 0.0, -9.81),
        ground { O: (0.0, 0.0, 0.0), C: (250 mm, 120 mm, 80 mm) },
        link crank { points { O, A: (0.0, 50 mm, 0.0) }, mass: 1.0, cg: (10 mm, 25 mm, 4 mm),
                     inertia: (1e-3, 4e-4, 9e-4, 1e-4, -2e-5, 5e-5) },
        link rod { points { A, B: (250 mm, 20 mm, 80 mm) }, mass: 0.5, cg: (125 mm, 35 mm, 40 mm),
                   inertia: (2e-4, 3e-3, 2.5e-3, 3e-5, 1e-5, -4e-5) },
        link spindle { points { C, B }, mass: 0.8, cg: (250 mm, 70 mm, 90 mm),
                       inertia: (1.2e-3, 6e-4, 1.1e-3, 0.0, 2e-5, 0.0) },
        joints {
            O: revolute(ground, crank) axis (1.0, 0.0, 0.0),
            A: spherical(crank, rod),
            B: spherical(rod, spindle),
            C: revolute(ground, spindle) axis (0.0, 0.0, 1.0),
        },
        input: O,
        loads { blade: torque on spindle },
    }
}

/// Where the figures go.
pub const FIGURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/mech-figures/wiper");
/// The crank's speed, rad/s (60 rpm).
const SPEED: f64 = std::f64::consts::TAU;
/// The blade's friction torque on the spindle, N·m, against its turning.
const FRICTION: f64 = 1.5;

fn main() -> ExitCode {
    plot::exit("wiper", run(Path::new(FIGURES)))
}

fn run(dir: &Path) -> Result<Vec<PathBuf>, Box<dyn Error>> {
    let wiper = Wiper::new();
    println!(
        "Wiper: N = {} links, {} equations against {} unknowns, {} idle spin",
        Wiper::LINKS,
        Wiper::EQUATIONS,
        Wiper::UNKNOWNS,
        Wiper::IDLE
    );
    println!(
        "{:>6} {:>10} {:>12} {:>12} {:>10} {:>10}",
        "q°", "spindle°", "τ d'Al. N·m", "τ v.p. N·m", "|F_A| N", "|F_B| N"
    );
    let (mut angle, mut torque) = (Vec::new(), Vec::new());
    for k in 0..=360 {
        let q = (k as f64).to_radians();
        let m = wiper.kinematics(q, SPEED, 0.0)?;
        let spindle = m.links.spindle;
        let turn = spindle.rotation.scaled_axis().z;
        let loads = WiperLoads {
            blade: Vector3::new(0.0, 0.0, -FRICTION * spindle.omega.z.signum()),
        };
        let f = wiper.kinetostatics(&m, &loads)?;
        angle.push((k as f64, turn.to_degrees()));
        torque.push((k as f64, f.driver));
        if k % 30 == 0 {
            let power = wiper.driver_action(&m, &loads)?;
            println!(
                "{:>6} {:>10.3} {:>12.5} {:>12.5} {:>10.3} {:>10.3}",
                k,
                turn.to_degrees(),
                f.driver,
                power,
                f.joints.A.force.norm(),
                f.joints.B.force.norm()
            );
        }
    }
    std::fs::create_dir_all(dir)?;
    let (a, t) = (dir.join("spindle_angle.svg"), dir.join("motor_torque.svg"));
    plot::line_chart(
        &a,
        "Wiper: the spindle's turn",
        "crank angle, °",
        "spindle, °",
        &[Series {
            label: "spindle".into(),
            points: angle,
        }],
    )?;
    plot::line_chart(
        &t,
        "Wiper: the motor torque at 60 rpm",
        "crank angle, °",
        "torque, N·m",
        &[Series {
            label: "d'Alembert".into(),
            points: torque,
        }],
    )?;
    println!("figures: {} {}", a.display(), t.display());
    Ok(vec![a, t])
}
