//! A valve train: a cam lifts a roller follower against a return spring. Design checks,
//! the follower's jump, and the contact force over a revolution at two speeds.
//!
//! ```text
//! cargo run --release --example valve_train
//! ```
//!
//! The camshaft turns at constant speed; the follower rises 10 mm by a cycloidal law over
//! 90°, dwells 60° and falls by a 3-4-5 polynomial over 120°; a 5 kN/m spring preloaded to
//! 50 N holds it on the cam (the same machine as `examples/mech/valve_train.mech`). The
//! example prints the profile's design figures (largest pressure angle, smallest radius of
//! curvature, undercut), the speed at which the follower first leaves the cam (where the
//! contact force, a + b ω² at each angle, reaches zero), the smallest preload that keeps
//! contact at the higher speed, and a table of lift, pressure angle and contact force at
//! 150 rad/s (below the jump) and 250 rad/s (above it); it writes the cam's profile and
//! the contact force over a revolution as SVG into target/mech-figures/valve_train/.

#[path = "common/plot.rs"]
mod plot;

use std::error::Error;
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use mech::prelude::*;

mechanism! {
    /// A cam on the camshaft lifts a roller follower against a compression spring.
    pub struct ValveTrain {
        gravity: (0.0, -9.81),
        ground { O: (0.0, 0.0), S: (0.0, 150 mm) },
        link cam { points { O }, mass: 0.5, inertia: 2.0e-4, cg: (0.0, 0.0) },
        link follower { points { P: (0.0, 50 mm) }, mass: 0.08, cg: (0.0, 50 mm) },
        joints {
            O: revolute(ground, cam),
            slide: prismatic(ground, follower) at P along (0.0, 1.0),
            lobe: cam(cam, follower) base_radius 40 mm roller 10 mm
                law [dwell 90 deg, cycloidal 90 deg rise 10 mm, dwell 60 deg, poly345 120 deg fall 10 mm],
        },
        input: O,
        elements {
            spring: spring(ground at S, follower at P) stiffness 5 kN_per_m preload -50 N,
        },
    }
}

/// Where the figures go.
pub const FIGURES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/target/mech-figures/valve_train"
);

/// The two speeds of the table, rad/s: below and above the jump.
pub const SPEEDS: [f64; 2] = [150.0, 250.0];

fn main() -> ExitCode {
    plot::exit("valve_train", run(Path::new(FIGURES)))
}

/// The contact force (N) at cam angle `th` and constant speed `w`.
pub fn contact(m: &ValveTrain, th: f64, w: f64) -> Result<f64, MechError> {
    let mo = m.kinematics(th, w, 0.0)?;
    Ok(m.kinetostatics(&mo, &ValveTrainLoads::default())?
        .joints
        .lobe
        .normal_force)
}

/// The speed (rad/s) at which the contact force first reaches zero over `n` cam angles:
/// min over the angles where b < 0 of √(−a/b), the force being a + b ω².
pub fn jump_speed(m: &ValveTrain, n: usize) -> Result<f64, MechError> {
    let mut w = f64::INFINITY;
    for k in 0..n {
        let th = TAU * k as f64 / n as f64;
        let a = contact(m, th, 0.0)?;
        let b = contact(m, th, 1.0)? - a;
        if b < 0.0 {
            w = w.min((-a / b).sqrt());
        }
    }
    Ok(w)
}

/// Prints the report, writes the SVGs into `dir`; returns their paths.
pub fn run(dir: &Path) -> Result<Vec<PathBuf>, Box<dyn Error>> {
    let m = ValveTrain::new();
    let profile = &m.cams()[0].profile;
    let chk = profile.check(3600);
    println!("{chk}");
    let jump = jump_speed(&m, 3600)?;
    println!(
        "the follower leaves the cam above {:.1} rad/s ({:.0} rpm of the camshaft)",
        jump,
        jump * 60.0 / TAU
    );
    // The contact force is linear in the preload F0 (free length 100 mm + F0/k).
    let with = |f0: f64| -> Result<ValveTrain, MechError> {
        let mut p = ValveTrainParams::default();
        p.elements.spring.free_length = 0.1 + f0 / 5000.0;
        ValveTrain::from_params(p)
    };
    let (m0, m1) = (with(0.0)?, with(1.0)?);
    let mut need = f64::NEG_INFINITY;
    for k in 0..3600 {
        let th = TAU * k as f64 / 3600.0;
        let a = contact(&m0, th, SPEEDS[1])?;
        need = need.max(-a / (contact(&m1, th, SPEEDS[1])? - a));
    }
    println!(
        "at {} rad/s the spring needs a preload of at least {:.1} N (it has 50 N)",
        SPEEDS[1], need
    );
    println!(
        "{:>6} {:>9} {:>8} {:>14} {:>14}",
        "cam°", "lift mm", "φ°", "F_n 150 rad/s", "F_n 250 rad/s"
    );
    for k in 0..12 {
        let th = TAU * k as f64 / 12.0 + 0.2;
        let p = profile.at(th);
        let s = profile.law.eval(th)[0];
        println!(
            "{:>6.1} {:>9.4} {:>8.2} {:>14.2} {:>14.2}",
            th.to_degrees(),
            s * 1e3,
            p.pressure_angle.to_degrees(),
            contact(&m, th, SPEEDS[0])?,
            contact(&m, th, SPEEDS[1])?
        );
    }
    std::fs::create_dir_all(dir)?;
    let profile_svg = dir.join("profile.svg");
    std::fs::write(
        &profile_svg,
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"-70 -70 140 140\" width=\"420\" height=\"420\">\n<path d=\"{}\" fill=\"#e8d9b5\" stroke=\"#8a6d3b\" stroke-width=\"0.6\"/>\n<circle cx=\"0\" cy=\"0\" r=\"1.5\" fill=\"#000\"/>\n</svg>\n",
            profile.svg_path(720)
        ),
    )?;
    let force_svg = dir.join("contact_force.svg");
    let series = SPEEDS
        .iter()
        .map(|&w| -> Result<plot::Series, MechError> {
            Ok(plot::Series {
                label: format!("{w} rad/s"),
                points: (0..720)
                    .map(|k| {
                        let th = TAU * k as f64 / 720.0;
                        contact(&m, th, w).map(|f| (th.to_degrees(), f))
                    })
                    .collect::<Result<_, _>>()?,
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    plot::line_chart(
        &force_svg,
        "Valve train: contact force between cam and follower over a revolution",
        "cam angle (deg)",
        "contact force (N; < 0: the follower leaves the cam)",
        &series,
    )?;
    println!(
        "wrote {} and {}",
        profile_svg.display(),
        force_svg.display()
    );
    Ok(vec![profile_svg, force_svg])
}
