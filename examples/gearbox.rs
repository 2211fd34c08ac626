//! A planetary gearbox lifting an unbalanced arm, with a return spring: gear pairs, a
//! fixed ring, Willis' ratios, tooth loads and flanks, and a spring, over a turn.
//!
//! ```text
//! cargo run --release --example gearbox
//! ```
//!
//! The motor drives the sun (30 mm) at 1500 rpm; the planet (30 mm) rolls inside the fixed
//! ring (90 mm, the ground), so the arm turns at a quarter of the sun's speed (Willis:
//! ω_arm = ω_sun · r_s / (r_s + r_r)). The arm carries an unbalanced mass (its cg 60 mm
//! out) under gravity, a spring from the ground pulls its planet pin, and the machine
//! brakes the arm with 20 N·m. The example prints, every 30° of the arm: the motor torque
//! by d'Alembert and by virtual power, Zhukovski's I* at the sun, the tooth loads with
//! the flank in contact, and the arm bearing's load; then writes the tooth loads over a
//! turn of the arm as an SVG into target/mech-figures/gearbox/.

#[path = "common/plot.rs"]
mod plot;

use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use mech::prelude::*;

mechanism! {
    /// A planetary reducer: sun (input) → planet in a fixed ring → arm (output, 4:1),
    /// the arm unbalanced and held by a spring.
    pub struct Planetary {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), H: (0.0, 150 mm) },
        link arm { points { O, P: (60 mm, 0.0) }, mass: 2.0, inertia: 4.0e-3, cg: (60 mm, 0.0) },
        link planet { points { P }, mass: 0.3, inertia: 1.4e-4, cg: (60 mm, 0.0) },
        link sun { points { O }, mass: 0.5, inertia: 2.3e-4, cg: (0.0, 0.0) },
        joints {
            O: revolute(ground, arm),
            P: revolute(arm, planet),
            S: revolute(ground, sun) at O,
            sp: gear(sun, planet) radii (30 mm, 30 mm),
            pr: gear(planet, ground) radii (30 mm, 90 mm) internal,
        },
        input: S,
        loads { brake: torque on arm },
        elements {
            lift: spring(ground at H, arm at P) stiffness 800 N_per_m free_length 120 mm,
        },
    }
}

/// Where the figure goes.
pub const FIGURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/mech-figures/gearbox");

fn main() -> ExitCode {
    plot::exit("gearbox", run(Path::new(FIGURES)))
}

/// One row of the table: the arm's angle, the motor torque by both routes, I*, the tooth
/// loads with their flanks and the arm bearing's load.
pub struct Row {
    /// The arm's turn, degrees.
    pub arm_deg: f64,
    /// Motor torque on the sun, N·m: d'Alembert, virtual power.
    pub driver: (f64, f64),
    /// I* at the sun, kg·m².
    pub inertia: f64,
    /// Tooth loads (N) and flanks of the sun–planet and planet–ring meshes.
    pub sp: (f64, f64),
    /// See `sp`.
    pub pr: (f64, f64),
    /// The arm bearing's load, N.
    pub bearing: f64,
}

/// The table over one turn of the arm (four of the sun) at a steady 1500 rpm, every
/// `step` degrees of the arm.
pub fn table(step: f64) -> Result<Vec<Row>, MechError> {
    let m = Planetary::new();
    let loads = PlanetaryLoads { brake: -20.0 };
    let qd = 1500.0 * std::f64::consts::TAU / 60.0;
    let n = (360.0 / step).round() as usize;
    (0..n)
        .map(|k| {
            let q = 4.0 * (k as f64 * step).to_radians();
            let mo = m.kinematics(q, qd, 0.0)?;
            let f = m.kinetostatics(&mo, &loads)?;
            Ok(Row {
                arm_deg: (q / 4.0).to_degrees(),
                driver: (f.driver, m.driver_action(&mo, &loads)?),
                inertia: m.reduced(q)?.inertia,
                sp: (f.joints.sp.tooth_load, f.joints.sp.flank),
                pr: (f.joints.pr.tooth_load, f.joints.pr.flank),
                bearing: f.joints.O.force.norm(),
            })
        })
        .collect()
}

/// Prints the ratios and the table, writes the tooth-load chart into `dir`; returns its path.
pub fn run(dir: &Path) -> Result<Vec<PathBuf>, Box<dyn Error>> {
    let m = Planetary::new();
    let mo = m.kinematics(0.3, 1.0, 0.0)?;
    println!(
        "Willis: ω_arm / ω_sun = {:.6} (1/4), ω_planet / ω_sun = {:.6} (−1/2)",
        mo.links.arm.omega, mo.links.planet.omega
    );
    println!(
        "{:>6} {:>11} {:>11} {:>11} {:>10} {:>4} {:>10} {:>4} {:>10}",
        "arm°",
        "T d'Al N·m",
        "T v.p. N·m",
        "I* kg·m²",
        "sun–pl N",
        "fl",
        "pl–ring N",
        "fl",
        "arm brg N"
    );
    let rows = table(30.0)?;
    for r in &rows {
        println!(
            "{:>6.0} {:>11.5} {:>11.5} {:>11.4e} {:>10.2} {:>+4.0} {:>10.2} {:>+4.0} {:>10.2}",
            r.arm_deg, r.driver.0, r.driver.1, r.inertia, r.sp.0, r.sp.1, r.pr.0, r.pr.1, r.bearing
        );
    }
    std::fs::create_dir_all(dir)?;
    let fine = table(2.0)?;
    let path = dir.join("tooth_loads.svg");
    plot::line_chart(
        &path,
        "Planetary gearbox: tooth loads over a turn of the arm (sun at 1500 rpm, 20 N·m brake)",
        "arm angle (deg)",
        "tooth load (N)",
        &[
            plot::Series {
                label: "sun–planet".into(),
                points: fine.iter().map(|r| (r.arm_deg, r.sp.0)).collect(),
            },
            plot::Series {
                label: "planet–ring".into(),
                points: fine.iter().map(|r| (r.arm_deg, r.pr.0)).collect(),
            },
        ],
    )?;
    println!("wrote {}", path.display());
    Ok(vec![path])
}
