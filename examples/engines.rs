//! Engines with several cylinders (SPEC 3g, issue 31): the classical table of primary and
//! secondary shaking forces and couples, reproduced from the exact solution.
//!
//! ```text
//! cargo run --example engines
//! ```
//!
//! Each engine is an ordinary one-input mechanism file written by
//! `mech::design::engine::Engine::to_mech` (one crankshaft, a rod and a piston per cylinder
//! on a guide at its bank angle, each in its plane along the shaft); its exact shaking over a
//! turn is split into harmonics, and the amplitudes of the primary (1×) and secondary (2×
//! crank speed) forces and couples about the transverse axes are printed over their classical
//! units, the exact value first and the textbook's first-order one in parentheses. Then the
//! in-line four declared below by the `mechanism!` macro (the same file as
//! `mech engine --layout inline --cylinders 4` writes), its secondary force beside
//! 4 m r ω² (r/l) cos 2θ, and a cross-plane V8's primary couple cancelled by two crankshaft
//! counterweights at the end planes.

use mech::design::balance::shaking_cycle;
use mech::design::engine::{
    balance_table, primary_couple_counterweights, table_text, Engine, Layout,
};
use mech::prelude::*;
use std::error::Error;

mechanism! {
    /// In-line 4: 4 crank pins at 0°, 180°, 180°, 0°, 45 mm crank, 150 mm rod, 0.5 kg
    /// reciprocating mass per cylinder, 90 mm between the pins; drawn at q = 0 (cylinder 1
    /// at top dead centre). Firing order 1-3-4-2.
    pub struct Inline4 {
        consts { r: 45 mm, l: 150 mm, mp: 0.5 kg },
        ground { O: (0.0, 0.0) },
        link crank {
            points { O, A1: O + polar(r, 90 deg), A2: O + polar(r, 270 deg) },
        },
        link rod1 { points { A1, B1: circle_line(A1, l, O, 90 deg, forward) }, plane: -135 mm },
        link piston1 { points { B1 }, mass: mp, cg: B1, plane: -135 mm },
        link rod2 { points { A2, B2: circle_line(A2, l, O, 90 deg, forward) }, plane: -45 mm },
        link piston2 { points { B2 }, mass: mp, cg: B2, plane: -45 mm },
        link rod3 { points { A2, B3: circle_line(A2, l, O, 90 deg, forward) }, plane: 45 mm },
        link piston3 { points { B3 }, mass: mp, cg: B3, plane: 45 mm },
        link rod4 { points { A1, B4: circle_line(A1, l, O, 90 deg, forward) }, plane: 135 mm },
        link piston4 { points { B4 }, mass: mp, cg: B4, plane: 135 mm },
        joints {
            main: revolute(ground, crank) at O,
            pin1: revolute(crank, rod1) at A1,
            wrist1: revolute(rod1, piston1) at B1,
            bore1: prismatic(ground, piston1) at B1 along (0, 1),
            pin2: revolute(crank, rod2) at A2,
            wrist2: revolute(rod2, piston2) at B2,
            bore2: prismatic(ground, piston2) at B2 along (0, 1),
            pin3: revolute(crank, rod3) at A2,
            wrist3: revolute(rod3, piston3) at B3,
            bore3: prismatic(ground, piston3) at B3 along (0, 1),
            pin4: revolute(crank, rod4) at A1,
            wrist4: revolute(rod4, piston4) at B4,
            bore4: prismatic(ground, piston4) at B4 along (0, 1),
        },
        input: main from 90 deg,
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let deg = f64::to_radians;
    let engines = [
        Engine::new(Layout::Inline, 2)?,
        Engine::new(Layout::Inline, 2)?.with_throws(&[0.0, 0.0])?,
        Engine::new(Layout::Inline, 3)?,
        Engine::new(Layout::Inline, 4)?,
        Engine::new(Layout::Inline, 6)?,
        Engine::new(Layout::Vee { bank: deg(90.0) }, 2)?,
        Engine::new(Layout::Vee { bank: deg(60.0) }, 6)?,
        Engine::new(Layout::Vee { bank: deg(90.0) }, 8)?,
        Engine::new(Layout::Vee { bank: deg(90.0) }, 8)?.with_throws(&[0.0, PI, PI, 0.0])?,
        Engine::new(Layout::Boxer, 2)?,
        Engine::new(Layout::Boxer, 4)?,
        Engine::new(Layout::Boxer, 6)?,
    ];
    let rows = engines
        .iter()
        .map(|e| balance_table(e, 360))
        .collect::<Result<Vec<_>, _>>()?;
    println!(
        "Shaking forces and couples of engines: exact (first order), r/l = 0.3, a = pin spacing\n"
    );
    print!("{}", table_text(&rows));

    // The in-line four of the macro: its declaration is the file `Engine::to_mech` writes.
    let e4 = &engines[3];
    println!(
        "\nThe in-line four as a mechanism file:\n\n{}",
        e4.to_mech("Inline4")?
    );
    let machine = Inline4::new();
    let (m, r, lambda, w) = (e4.mass, e4.radius, e4.radius / e4.rod, 100.0);
    println!("In-line four at {w} rad/s: the shaking force F_y against 4 m r ω² (r/l) cos 2θ");
    println!(
        "{:>8} {:>14} {:>14} {:>12}",
        "θ, deg", "exact F_y, N", "4mrω²λcos2θ", "|M_x|+|M_y|"
    );
    for k in 0..=8 {
        let th = PI * k as f64 / 8.0;
        let s = machine.shaking(&machine.motion(&[th], &[w], &[0.0])?);
        let textbook = 4.0 * m * r * w * w * lambda * (2.0 * th).cos();
        println!(
            "{:>8.1} {:>14.4} {:>14.4} {:>12.2e}",
            th.to_degrees(),
            s.force.y,
            textbook,
            s.mx.abs() + s.my.abs()
        );
    }

    // The cross-plane V8: its primary couple rotates with the crank; two counterweights on the
    // crankshaft at the end planes cancel it.
    let v8 = &engines[7];
    let before = &rows[7];
    let ends = 1.5 * v8.spacing;
    let weights = primary_couple_counterweights(v8, &before.exact[0], 0.06, (-ends, ends))?;
    let mut balanced = v8.clone();
    balanced.counterweights = weights.to_vec();
    let after = balance_table(&balanced, 360)?;
    println!(
        "\nCross-plane V8: primary couple {:.4} m r ω² a (√10 = {:.4}); with {:.4} kg at 60 mm in the planes ±{:.0} mm (at {:.1}° and {:.1}°): {:.2e} m r ω² a",
        before.primary_couple[0],
        10f64.sqrt(),
        weights[0].mass,
        ends * 1e3,
        weights[0].angle.to_degrees(),
        weights[1].angle.to_degrees(),
        after.primary_couple[0]
    );
    let file = balanced.to_mech("V8")?;
    let cycle = shaking_cycle(
        &Mechanism::from_dsl(&file)?,
        (0.0, 2.0 * PI, 360),
        &[0.0],
        &[1.0],
    )?;
    println!(
        "its peak couple over the turn {:.4e} N·m at 1 rad/s (without: {:.4e})",
        cycle.summary().peak_couple,
        shaking_cycle(
            &Mechanism::from_dsl(&v8.to_mech("V8")?)?,
            (0.0, 2.0 * PI, 360),
            &[0.0],
            &[1.0]
        )?
        .summary()
        .peak_couple
    );
    Ok(())
}

const PI: f64 = std::f64::consts::PI;
