//! The closed-form PRP and RPP dyads against independent references: a Scotch yoke driven
//! through a sliding block (RPP) must move and load exactly like the pin-in-slot Scotch
//! yoke of the reference tables, and a slotted crank driving a slider on a fixed line (PRP)
//! against the textbook solution x = h cot q.

use crate::measure::within;
use crate::mechanisms;

use mech::prelude::*;
use mechanisms::{ScotchYoke, ScotchYokeLoads};

mechanism! {
    /// The Scotch yoke of the reference tables with a massless block on the crank pin
    /// sliding in the yoke's slot: an RPP dyad (block, yoke).
    pub struct YokeWithBlock {
        gravity: (0.0, -9.81),
        ground { O2: (0.0, 0.0) },
        link crank {
            points { O2, A: (0.03856725658119236, 0.045962666587138684) },
            mass: 0.7, inertia: 0.00031, cg: (0.011077149640627953, 0.019424128187363675),
        },
        link block { points { A } },
        link yoke {
            points { Y: (0.2, 0.0) },
            mass: 1.9, inertia: 0.0068, cg: (0.13, 0.004),
        },
        joints {
            O2: revolute(ground, crank),
            A: revolute(crank, block),
            slot: prismatic(yoke, block) at A along (0.0, 1.0),
            guide: prismatic(ground, yoke) at Y along (1.0, 0.0),
        },
        input: O2,
        loads { resist: force on yoke at Y, drag: torque on crank },
    }
}

mechanism! {
    /// A slotted crank whose block is pinned to a slider on the line y = h: a PRP dyad.
    pub struct SlottedCrankSlider {
        ground { O: (0.0, 0.0) },
        link crank { points { O, T: (0.1, 0.1) }, mass: 0.5, inertia: 1e-3, cg: (0.05, 0.05) },
        link block { points { S: (0.08, 0.08) }, mass: 0.1, cg: (0.08, 0.08) },
        link slider { points { S }, mass: 0.3, cg: (0.08, 0.08) },
        joints {
            O: revolute(ground, crank),
            radial: prismatic(crank, block) at S along (1.0, 1.0),
            S: revolute(block, slider),
            rail: prismatic(ground, slider) at S along (1.0, 0.0),
        },
        input: O,
    }
}

#[test]
fn rpp_block_yoke_matches_pin_in_slot_yoke() {
    let (a, b) = (ScotchYoke::new(), YokeWithBlock::new());
    let la = ScotchYokeLoads {
        resist: Vector2::new(-120.0, 15.0),
        drag: -1.5,
    };
    let lb = YokeWithBlockLoads {
        resist: la.resist,
        drag: la.drag,
    };
    for k in 0..24 {
        let q = 0.26 * k as f64;
        let (ma, mb) = (
            a.kinematics(q, 14.0, -5.0).unwrap(),
            b.kinematics(q, 14.0, -5.0).unwrap(),
        );
        let (ya, yb) = (ma.links.yoke, mb.links.yoke);
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((ya.cg - yb.cg).norm(), 1e-15), "q={q}");
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((ya.cg_vel - yb.cg_vel).norm(), 1e-14));
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((ya.cg_acc - yb.cg_acc).norm(), 1e-13));
        assert!(
            within((mb.links.block.angle - 0.0).abs(), 1e-15), // measured worst 0 (be05608); exact; a few ulps
            "the block keeps the yoke's orientation"
        );
        let (fa, fb) = (
            a.kinetostatics(&ma, &la).unwrap(),
            b.kinetostatics(&mb, &lb).unwrap(),
        );
        let scale = fa.joints.guide.force.norm().max(1.0);
        // The motor torque on its own scale (issue 28), the reactions on theirs.
        let dscale = fa.driver.abs().max(fb.driver.abs()).max(1e-3);
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((fa.driver - fb.driver).abs(), 1e-15 * dscale));
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within(
            (fa.joints.guide.force - fb.joints.guide.force).norm(),
            1e-15 * scale
        ));
        // measured worst 4.9e-16 (be05608); 100×
        assert!(within(
            (fa.joints.guide.moment - fb.joints.guide.moment).abs(),
            2e-14 * scale
        ));
        // The slot's normal force on the crank pin is what the massless block passes on.
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within(
            (fa.joints.slot.force + fb.joints.A.force).norm(),
            1e-15 * scale
        ));
        // measured worst 6.5e-16 (be05608); 100×
        assert!(within(
            (fb.driver - b.driver_action(&mb, &lb).unwrap()).abs(),
            5e-14 * dscale
        ));
    }
}

#[test]
fn prp_slider_follows_cotangent() {
    let m = SlottedCrankSlider::new();
    let h = 0.08;
    for k in 1..12 {
        let q = 0.25 + 0.22 * k as f64; // within (0, π): the radial line meets y = h
        let (qd, qdd) = (3.0, -2.0);
        let mo = m.kinematics(q, qd, qdd).unwrap();
        let s = mo.points.S;
        let (sn, cs) = q.sin_cos();
        let x = h * cs / sn;
        let xd = -h * qd / (sn * sn);
        let xdd = -h * qdd / (sn * sn) + 2.0 * h * qd * qd * cs / (sn * sn * sn);
        assert!(
            within((s.pos - Vector2::new(x, h)).norm(), 1e-15 * (1.0 + x.abs())), // measured worst 1.4e-17 (be05608); 100×
            "q={q}"
        );
        // measured worst 1.4e-16 (be05608); 100×
        assert!(within(
            (s.vel - Vector2::new(xd, 0.0)).norm(),
            1e-14 * (1.0 + xd.abs())
        ));
        // measured worst 5.5e-16 (be05608); 100×
        assert!(within(
            (s.acc - Vector2::new(xdd, 0.0)).norm(),
            5e-14 * (1.0 + xdd.abs())
        ));
        // A one-point link's angle is its rotation since the drawing: the crank's.
        let turned = mo.links.crank.angle - std::f64::consts::FRAC_PI_4;
        assert!(
            within((mo.links.block.angle - turned).abs(), 1e-15), // measured worst 1.4e-17 (be05608); 100×
            "block {} crank {}",
            mo.links.block.angle,
            turned
        );
        let f = m
            .kinetostatics(&mo, &SlottedCrankSliderLoads::default())
            .unwrap();
        let vp = m
            .driver_action(&mo, &SlottedCrankSliderLoads::default())
            .unwrap();
        // measured worst 2.8e-16 (be05608); 100×
        assert!(within(
            (f.driver - vp).abs(),
            2e-14 * f.driver.abs().max(1e-3)
        ));
    }
}
