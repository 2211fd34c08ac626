//! The RPR, PRP and RPP dyads in natural coordinates ([`super::rpr`], [`super::prp`],
//! [`super::rpp`]) against the joint-screw route ([`crate::kernel::screw::chain_rates`],
//! [`crate::kernel::screw::chain_reactions`]) on random configurations: random solved
//! links (the ground or moving), random local vectors, each joint's links in either order
//! (an RPR's guide either link of the solver), both branches; the same rates, the same
//! reactions, and the same `Singular` verdict near a change point (RPR) or near parallel
//! axes (PRP, RPP).

use crate::kernel::constraints::{JointGeom, Level};
use crate::kernel::dyad::{position, Solver};
use crate::kernel::kinematics::{chain_reactions, solve_chain};
use crate::kernel::kinetostatics::{Reaction, Wrench};
use crate::kernel::link_state::{perp, rotate, LinkState, V2};
use crate::kernel::measure::within;
use crate::kernel::natural::DyadSystem;
use crate::kernel::screw::{self, Chain, JointScrew};
use crate::MechError;

/// A small deterministic generator (xorshift64*), uniform in [lo, hi).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn v2(&mut self, r: f64) -> V2 {
        V2::new(self.range(-r, r), self.range(-r, r))
    }
    /// A local vector: zero (the link's anchor) one time in three.
    fn local(&mut self, r: f64) -> V2 {
        if self.next() < 1.0 / 3.0 {
            V2::zeros()
        } else {
            self.v2(r)
        }
    }
    fn unit(&mut self) -> V2 {
        let t = self.range(-3.2, 3.2);
        V2::new(t.cos(), t.sin())
    }
}

/// One random RPR dyad: links 0 (ground), 1 and 2 (solved), 3 = b1 and 4 = b2; joints
/// ja = 0 (b1's pin), jp = 1 (the prismatic), jb = 2 (b2's pin).
struct Case {
    joints: Vec<JointGeom>,
    s: Vec<LinkState>,
    solver: Solver,
    chain: Chain,
    scale: f64,
}

/// The solved link `l`, or the ground one time in four.
fn ground_or(rng: &mut Rng, l: usize) -> usize {
    if rng.next() < 0.25 {
        0
    } else {
        l
    }
}

/// The pin between the solved link `solved` and the dyad's link `own`, in random order.
fn pin(rng: &mut Rng, solved: usize, own: usize) -> JointGeom {
    let (ds, dn) = (
        if solved == 0 {
            rng.v2(0.5)
        } else {
            rng.local(0.3)
        },
        rng.local(0.3),
    );
    let (a, b, da, db) = if rng.next() < 0.5 {
        (solved, own, ds, dn)
    } else {
        (own, solved, dn, ds)
    };
    JointGeom {
        a,
        b,
        da,
        db,
        axis: V2::zeros(),
        q_ref: 0.0,
        radius: 0.0,
        around: 0.0,
    }
}

/// A case of the dyad b1 = 3, b2 = 4 between the solved links `from` and `to`: its
/// joints 0, 1, 2 (`slides`: which of them slide), states and solver, the chain's pivot on
/// joint `pivot`, and a random scale.
fn dyad_case(
    rng: &mut Rng,
    joints: Vec<JointGeom>,
    s: Vec<LinkState>,
    solver: Solver,
    (from, to): (usize, usize),
    slides: [bool; 3],
    pivot: usize,
) -> Case {
    let chain = Chain {
        from,
        to,
        screws: [0, 1, 2].map(|joint| JointScrew {
            joint,
            slide: slides[joint],
        }),
        links: [3, 4],
        pivot,
    };
    Case {
        joints,
        s,
        solver,
        chain,
        scale: rng.range(0.2, 1.0),
    }
}

fn random_case(rng: &mut Rng) -> Case {
    let (b1, b2) = (3, 4);
    // The solved links: the ground one time in four each.
    let la = ground_or(rng, 1);
    let lb = ground_or(rng, 2);
    let s = random_states(rng);
    let guide_first = rng.next() < 0.5;
    let (guide, slider) = if guide_first { (b1, b2) } else { (b2, b1) };
    let joints = vec![
        pin(rng, la, b1),
        JointGeom {
            a: guide,
            b: slider,
            da: rng.local(0.2),
            db: rng.local(0.2),
            axis: rng.unit(),
            q_ref: 0.0,
            radius: 0.0,
            around: 0.0,
        },
        pin(rng, lb, b2),
    ];
    let solver = Solver::Rpr {
        b1,
        b2,
        ja: 0,
        jp: 1,
        jb: 2,
    };
    // As `plan::assur::kernel` builds it: the pivot on the first pin.
    dyad_case(rng, joints, s, solver, (la, lb), [false, true, false], 0)
}

const NO_DRIVE: (&[f64], &[f64], &[f64]) = (&[], &[], &[]);

/// Both routes' states to accelerations: (natural, what it kept), screws.
#[allow(clippy::type_complexity)]
fn both_rates(
    c: &Case,
    sign: f64,
) -> (
    Result<(Vec<LinkState>, DyadSystem), MechError>,
    Result<Vec<LinkState>, MechError>,
) {
    let mut sn = c.s.clone();
    let natural = solve_chain(
        c.solver,
        &c.chain,
        &c.joints,
        &mut sn,
        NO_DRIVE,
        sign,
        c.scale,
        Level::Acceleration,
    )
    .map(|kept| (sn, kept));
    let mut ss = c.s.clone();
    let screws = position(c.solver, &c.joints, &mut ss, NO_DRIVE, sign)
        .and_then(|_| {
            screw::chain_rates(&c.chain, &c.joints, &mut ss, c.scale, Level::Acceleration)
        })
        .map(|()| ss);
    (natural, screws)
}

/// The largest magnitude among `xs`, at least `floor`.
fn largest(xs: &[f64], floor: f64) -> f64 {
    xs.iter().fold(floor, |m, x| m.max(x.abs()))
}

/// The dyad's links 3 and 4 by the natural route (`sn`) and by the joint screws (`ss`):
/// the same position, and velocities and accelerations within `tol` (velocity,
/// acceleration) relative to the configuration's scale: the largest velocity (angular
/// times L), or acceleration, of the dyad's and the solved links' anchors and pins on the
/// screws' states. The worst relative differences are raised into `worst`.
fn compare_rates(
    c: &Case,
    sn: &[LinkState],
    ss: &[LinkState],
    (tol_v, tol_a): (f64, f64),
    (worst_v, worst_a): (&mut f64, &mut f64),
) {
    let l = c.scale;
    let pins: Vec<(usize, V2)> = c
        .joints
        .iter()
        .flat_map(|g| [(g.a, g.da), (g.b, g.db)])
        .filter(|&(k, _)| k != 0)
        .collect();
    let speeds: Vec<f64> = pins
        .iter()
        .flat_map(|&(k, d)| {
            let v = ss[k].vel_at(ss[k].r(d));
            [v.x, v.y, ss[k].vel.x, ss[k].vel.y, ss[k].omega * l]
        })
        .collect();
    let accels: Vec<f64> = pins
        .iter()
        .flat_map(|&(k, d)| {
            let a = ss[k].acc_at(ss[k].r(d));
            let o2 = ss[k].omega * ss[k].omega * l;
            [a.x, a.y, ss[k].acc.x, ss[k].acc.y, ss[k].alpha * l, o2]
        })
        .collect();
    for b in [3, 4] {
        let (n, s) = (&sn[b], &ss[b]);
        assert_eq!((n.pos, n.rot), (s.pos, s.rot), "the same position");
        let vs = largest(&speeds, 1e-3);
        for (x, y) in [
            (n.vel.x, s.vel.x),
            (n.vel.y, s.vel.y),
            (n.omega * l, s.omega * l),
        ] {
            let e = (x - y).abs() / vs;
            *worst_v = worst_v.max(e);
            assert!(within(e, tol_v), "velocity {x} vs {y}");
        }
        let as_ = largest(&accels, 1e-3);
        for (x, y) in [
            (n.acc.x, s.acc.x),
            (n.acc.y, s.acc.y),
            (n.alpha * l, s.alpha * l),
        ] {
            let e = (x - y).abs() / as_;
            *worst_a = worst_a.max(e);
            assert!(within(e, tol_a), "acceleration {x} vs {y}");
        }
    }
}

/// Random wrenches on the five links.
fn random_wrenches(rng: &mut Rng) -> Vec<Wrench> {
    (0..5)
        .map(|_| {
            Wrench::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-5.0, 5.0),
            )
        })
        .collect()
}

/// The reactions, and the wrenches left on the links, of each natural route (`natural`:
/// wrenches, reactions) against the joint screws' (`screws`), within `tol` relative to the
/// largest of the screws' (moments over L, at least 1e-3). The worst relative difference
/// is raised into `worst_r`.
fn compare_reactions(
    natural: &[(Vec<Wrench>, Vec<Reaction>)],
    (fs, outs): &(Vec<Wrench>, Vec<Reaction>),
    l: f64,
    tol: f64,
    worst_r: &mut f64,
) {
    let mut all: Vec<f64> = outs
        .iter()
        .flat_map(|r| [r.force.x, r.force.y, r.moment / l])
        .collect();
    all.extend(fs.iter().flat_map(|w| [w.x, w.y, w.z / l]));
    let rs = largest(&all, 1e-3);
    for (f, out) in natural {
        for (n, s) in out.iter().zip(outs) {
            for (x, y) in [
                (n.force.x, s.force.x),
                (n.force.y, s.force.y),
                (n.moment / l, s.moment / l),
            ] {
                let e = (x - y).abs() / rs;
                *worst_r = worst_r.max(e);
                assert!(within(e, tol), "reaction {x} vs {y}");
            }
        }
        for (n, s) in f.iter().zip(fs) {
            for (x, y) in [(n.x, s.x), (n.y, s.y), (n.z / l, s.z / l)] {
                let e = (x - y).abs() / rs;
                *worst_r = worst_r.max(e);
                assert!(within(e, tol), "wrench on a solved link {x} vs {y}");
            }
        }
    }
}

/// The condition estimate κ_F = (|d|² + L²)/|x L| of the case's RPR system once placed.
fn condition(c: &Case, s: &[LinkState]) -> f64 {
    let gp = &c.joints[1];
    let (pa, pb) = if gp.a == 3 {
        (&c.joints[0], &c.joints[2])
    } else {
        (&c.joints[2], &c.joints[0])
    };
    let pt = |g: &JointGeom| crate::kernel::link_state::point_of(s, g.b, g.db);
    let d = pt(pb) - pt(pa);
    let u = s[gp.a].r(gp.axis);
    (d.norm_squared() + c.scale * c.scale) / (d.dot(&u) * c.scale).abs()
}

#[test]
fn rpr_rates_and_reactions_match_the_joint_screws() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut compared, mut skipped) = (0, 0);
    let (mut worst_v, mut worst_a, mut worst_r) = (0.0f64, 0.0f64, 0.0f64);
    for _ in 0..4000 {
        let c = random_case(&mut rng);
        let sign = if rng.next() < 0.5 { -1.0 } else { 1.0 };
        let (natural, screws) = both_rates(&c, sign);
        // Not assembled, or near a change point (κ ≥ 1e3, where the routes' rounding,
        // of order ε κ², is no longer that of the formulas): counted, not compared.
        let (Ok((sn, kept)), Ok(ss)) = (natural, screws) else {
            skipped += 1;
            continue;
        };
        if condition(&c, &sn) >= 1e3 {
            skipped += 1;
            continue;
        }
        assert!(matches!(kept, DyadSystem::Rpr(_)));
        let l = c.scale;
        // measured worst 1.5e-15 (velocity), 4.0e-15 (acceleration) (3d9e54b); 100×
        compare_rates(&c, &sn, &ss, (1e-13, 2e-13), (&mut worst_v, &mut worst_a));
        // The reactions from random wrenches on every link, on the same states, by the
        // kept system, by the system rebuilt, and by the joint screws.
        let f0 = random_wrenches(&mut rng);
        let mut results = Vec::new();
        for route in 0..3 {
            let (mut f, mut out) = (f0.clone(), vec![Reaction::default(); 3]);
            match route {
                0 | 1 => chain_reactions(
                    c.solver,
                    &c.chain,
                    &c.joints,
                    &sn,
                    &mut f,
                    c.scale,
                    if route == 0 { &kept } else { &DyadSystem::None },
                    &mut out,
                ),
                _ => screw::chain_reactions(&c.chain, &c.joints, &sn, &mut f, c.scale, &mut out),
            }
            .expect("reactions");
            results.push((f, out));
        }
        // measured worst 1.6e-15 (3d9e54b), the reactions and the wrenches; 100×
        compare_reactions(&results[..2], &results[2], l, 1e-13, &mut worst_r);
        compared += 1;
    }
    eprintln!(
        "rpr vs screws: {compared} compared, {skipped} skipped; worst relative \
         velocity {worst_v:.1e}, acceleration {worst_a:.1e}, reaction {worst_r:.1e}"
    );
    assert!(
        compared >= 2000,
        "only {compared} of 4000 compared ({skipped} skipped)"
    );
}

/// Place the solved link `l`'s point of local vector `d` (in `l`) at `p`, keeping its
/// rotation.
fn put(s: &mut [LinkState], l: usize, d: V2, p: V2) {
    s[l].pos = p - rotate(s[l].rot, d);
}

#[test]
fn rpr_is_singular_where_the_joint_screws_are() {
    // Configurations at a chosen κ near a change point: B placed at the distance from A
    // that gives x = D·u the small root of x² − κ L x + y² + L² = 0 (κ = (|D|² + L²)/|x L|).
    // Both routes place the links alike and estimate the same κ to a relative ~ε κ
    // (x from the square root and x = D·u of the rotation made from it), so their
    // verdicts agree but within ~1e-10 of the threshold; a 1% margin on either side.
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let mut counted = [0; 2];
    for k in 0..2000 {
        let mut c = random_case(&mut rng);
        // Both solved links moving, so that B can be put anywhere.
        c.chain.from = 1;
        c.chain.to = 2;
        for (j, l) in [(0, 1), (2, 2)] {
            let g = &mut c.joints[j];
            if g.a == 0 {
                g.a = l;
            } else if g.b == 0 {
                g.b = l;
            }
        }
        let kappa = [1e5, 0.99e6, 1.01e6, 1e7, 1e9][k % 5];
        let gp = c.joints[1];
        let (ga, gb) = if gp.a == 3 {
            (c.joints[0], c.joints[2])
        } else {
            (c.joints[2], c.joints[0])
        };
        let (sa, da) = if ga.a == gp.a {
            (ga.b, ga.db)
        } else {
            (ga.a, ga.da)
        };
        let (sb, db) = if gb.a == gp.b {
            (gb.b, gb.db)
        } else {
            (gb.a, gb.da)
        };
        let (dpa, dpb) = (
            if ga.a == gp.a { ga.da } else { ga.db },
            if gb.a == gp.b { gb.da } else { gb.db },
        );
        let w = -((gp.db - dpb) - (gp.da - dpa));
        let y = perp(gp.axis).dot(&w);
        let l = c.scale;
        let disc = (kappa * l).powi(2) - 4.0 * (y * y + l * l);
        let x = 2.0 * (y * y + l * l) / (kappa * l + disc.sqrt());
        let a = crate::kernel::link_state::point_of(&c.s, sa, da);
        let dir = rng.unit();
        put(&mut c.s, sb, db, a + dir * (x * x + y * y).sqrt());
        for sign in [-1.0, 1.0] {
            let (natural, screws) = both_rates(&c, sign);
            let want = kappa > 1e6;
            let n = matches!(natural, Err(MechError::Singular { .. }));
            let s = matches!(screws, Err(MechError::Singular { .. }));
            assert!(
                !matches!(natural, Err(MechError::NoAssembly)),
                "κ {kappa}: assembles by construction"
            );
            assert_eq!(n, s, "κ {kappa}: natural {natural:?} vs screws {screws:?}");
            assert_eq!(n, want, "κ {kappa}: {natural:?}");
            // The reactions' own estimate, rebuilt from the placed states, agrees too.
            let mut placed = c.s.clone();
            position(c.solver, &c.joints, &mut placed, NO_DRIVE, sign).expect("placed");
            let mut f = vec![Wrench::new(1.0, 2.0, 0.3); 5];
            let mut out = vec![Reaction::default(); 3];
            let rn = chain_reactions(
                c.solver,
                &c.chain,
                &c.joints,
                &placed,
                &mut f.clone(),
                l,
                &DyadSystem::None,
                &mut out,
            );
            let rs = screw::chain_reactions(&c.chain, &c.joints, &placed, &mut f, l, &mut out);
            assert_eq!(
                matches!(rn, Err(MechError::Singular { .. })),
                matches!(rs, Err(MechError::Singular { .. })),
                "κ {kappa}: reactions {rn:?} vs {rs:?}"
            );
            counted[usize::from(want)] += 1;
        }
    }
    assert!(counted.iter().all(|&n| n >= 1000), "{counted:?}");
}

// PRP and RPP: the two slides of dyads whose rotations are their guides' ([`super::prp`],
// [`super::rpp`]) against the joint screws, the same way.

/// A prismatic joint between the solved link `solved` and the dyad's link `own`, in
/// random order, its axis a random unit vector.
fn prismatic(rng: &mut Rng, solved: usize, own: usize) -> JointGeom {
    let mut g = pin(rng, solved, own);
    g.axis = rng.unit();
    g
}

/// Random states of the solved links 1 and 2 (0 is the ground), 3 and 4 (the dyad's)
/// left to be placed.
fn random_states(rng: &mut Rng) -> Vec<LinkState> {
    let mut s = vec![LinkState::default(); 5];
    for l in [1, 2] {
        let st = &mut s[l];
        st.pos = rng.v2(0.4);
        st.rot = rng.unit();
        st.vel = rng.v2(3.0);
        st.omega = rng.range(-8.0, 8.0);
        st.acc = rng.v2(40.0);
        st.alpha = rng.range(-50.0, 50.0);
    }
    s
}

/// One random PRP dyad: b1 = 3 slides on L₁ (the ground or 1) by jp1 = 0, b2 = 4 on L₂
/// (the ground or 2) by jp2 = 2, pinned together by jc = 1.
fn random_prp(rng: &mut Rng) -> Case {
    let (b1, b2) = (3, 4);
    let l1 = ground_or(rng, 1);
    let l2 = ground_or(rng, 2);
    let s = random_states(rng);
    let joints = vec![
        prismatic(rng, l1, b1),
        pin(rng, b1, b2),
        prismatic(rng, l2, b2),
    ];
    let solver = Solver::Prp {
        b1,
        b2,
        jp1: 0,
        jc: 1,
        jp2: 2,
    };
    // As `plan::assur::kernel` builds it: the pivot on the middle pin.
    dyad_case(rng, joints, s, solver, (l1, l2), [true, false, true], 1)
}

/// One random RPP dyad: b1 = 3 pinned to L_A (the ground or 1) by ja = 0, sliding on
/// b2 = 4 by jp = 1, b2 sliding on G (the ground or 2) by jq = 2.
fn random_rpp(rng: &mut Rng) -> Case {
    let (b1, b2) = (3, 4);
    let la = ground_or(rng, 1);
    let lg = ground_or(rng, 2);
    let s = random_states(rng);
    let joints = vec![
        pin(rng, la, b1),
        prismatic(rng, b1, b2),
        prismatic(rng, lg, b2),
    ];
    let solver = Solver::Rpp {
        b1,
        b2,
        ja: 0,
        jp: 1,
        jq: 2,
    };
    // As `plan::assur::kernel` builds it: the pivot on the one rotation, the pin.
    dyad_case(rng, joints, s, solver, (la, lg), [false, true, true], 0)
}

/// The condition estimate κ_F = 2/|u × w| of a PRP or RPP system once placed: its two
/// prismatics' current axes (joints 0 and 2, or 1 and 2).
fn slides_condition(c: &Case, s: &[LinkState]) -> f64 {
    let (j, k) = match c.solver {
        Solver::Prp { jp1, jp2, .. } => (jp1, jp2),
        Solver::Rpp { jp, jq, .. } => (jp, jq),
        _ => unreachable!(),
    };
    let dir = |g: &JointGeom| crate::kernel::link_state::dir_of(s, g.a, g.axis);
    2.0 / crate::kernel::link_state::cross(dir(&c.joints[j]), dir(&c.joints[k])).abs()
}

/// Compare the natural route with the joint screws on `n` random cases of `make`; the
/// worst relative differences (velocity, acceleration, reaction) and the number compared.
fn slides_match_the_joint_screws(
    name: &str,
    make: fn(&mut Rng) -> Case,
    seed: u64,
    n: usize,
) -> usize {
    let mut rng = Rng(seed);
    let (mut compared, mut skipped) = (0, 0);
    let (mut worst_v, mut worst_a, mut worst_r) = (0.0f64, 0.0f64, 0.0f64);
    for _ in 0..n {
        let c = make(&mut rng);
        let (natural, screws) = both_rates(&c, 1.0);
        let (Ok((sn, kept)), Ok(ss)) = (natural, screws) else {
            skipped += 1;
            continue;
        };
        // Near parallel axes (κ ≥ 1e3), where the routes' rounding, of order ε κ², is no
        // longer that of the formulas: counted, not compared.
        if slides_condition(&c, &sn) >= 1e3 {
            skipped += 1;
            continue;
        }
        assert_eq!(kept, DyadSystem::None);
        // measured worst velocity 7.5e-16 (PRP), 1.0e-15 (RPP); acceleration 5.1e-15
        // (PRP), 3.1e-14 (RPP)
        compare_rates(&c, &sn, &ss, (1e-12, 1e-12), (&mut worst_v, &mut worst_a));
        let f0 = random_wrenches(&mut rng);
        let (mut fn_, mut out_n) = (f0.clone(), vec![Reaction::default(); 3]);
        chain_reactions(
            c.solver, &c.chain, &c.joints, &sn, &mut fn_, c.scale, &kept, &mut out_n,
        )
        .expect("reactions");
        let (mut fs, mut out_s) = (f0.clone(), vec![Reaction::default(); 3]);
        screw::chain_reactions(&c.chain, &c.joints, &sn, &mut fs, c.scale, &mut out_s)
            .expect("reactions");
        // measured worst 5.0e-15 (PRP), 4.0e-15 (RPP), the reactions and the wrenches
        compare_reactions(&[(fn_, out_n)], &(fs, out_s), c.scale, 1e-12, &mut worst_r);
        compared += 1;
    }
    eprintln!(
        "{name} vs screws: {compared} compared, {skipped} skipped; worst relative \
         velocity {worst_v:.1e}, acceleration {worst_a:.1e}, reaction {worst_r:.1e}"
    );
    compared
}

#[test]
fn prp_rates_and_reactions_match_the_joint_screws() {
    let compared = slides_match_the_joint_screws("prp", random_prp, 0x2545_f491_4f6c_dd1d, 4000);
    assert!(compared >= 3000, "only {compared} of 4000 compared");
}

#[test]
fn rpp_rates_and_reactions_match_the_joint_screws() {
    let compared = slides_match_the_joint_screws("rpp", random_rpp, 0x0bad_5eed_1234_5678, 4000);
    assert!(compared >= 3000, "only {compared} of 4000 compared");
}

/// Turn the second axis of `c` (PRP: L₂'s rotation; RPP: jp's axis, both axes turning
/// with G) so that the placed system's κ_F = 2/|u × w| is `kappa`; both solved links
/// moving.
fn at_condition(c: &mut Case, rng: &mut Rng, kappa: f64) {
    c.chain.from = 1;
    c.chain.to = 2;
    for (j, l) in [(0, 1), (2, 2)] {
        let g = &mut c.joints[j];
        if g.a == 0 {
            g.a = l;
        } else if g.b == 0 {
            g.b = l;
        }
    }
    let sn = (2.0 / kappa) * if rng.next() < 0.5 { -1.0 } else { 1.0 };
    let turn = V2::new(
        (1.0 - sn * sn).sqrt() * if rng.next() < 0.5 { -1.0 } else { 1.0 },
        sn,
    );
    match c.solver {
        Solver::Prp { .. } => {
            // u₂ = turn u₁: L₂'s rotation from its axis to there.
            let u1 = rotate(c.s[1].rot, c.joints[0].axis);
            let u2 = rotate(turn, u1);
            c.s[2].rot = crate::kernel::link_state::quotient(u2, c.joints[2].axis);
        }
        _ => c.joints[1].axis = rotate(turn, c.joints[2].axis),
    }
}

#[test]
fn prp_and_rpp_are_singular_where_the_joint_screws_are() {
    // Both routes estimate κ_F = 2/|u × w| from the same two unit vectors (to a relative
    // ~ε in |u|² + |w|²); a 1% margin on either side of the threshold.
    let mut rng = Rng(0x5eed_cafe_f00d_0001);
    for make in [random_prp as fn(&mut Rng) -> Case, random_rpp] {
        let mut counted = [0; 2];
        for k in 0..2000 {
            let mut c = make(&mut rng);
            let kappa = [1e5, 0.99e6, 1.01e6, 1e7, 1e9][k % 5];
            at_condition(&mut c, &mut rng, kappa);
            let (natural, screws) = both_rates(&c, 1.0);
            let want = kappa > 1e6;
            let n = matches!(natural, Err(MechError::Singular { .. }));
            let s = matches!(screws, Err(MechError::Singular { .. }));
            assert_eq!(n, s, "κ {kappa}: natural {natural:?} vs screws {screws:?}");
            assert_eq!(n, want, "κ {kappa}: {natural:?}");
            // The reactions' own estimate, from the placed states, agrees too.
            let mut placed = c.s.clone();
            position(c.solver, &c.joints, &mut placed, NO_DRIVE, 1.0).expect("placed");
            let mut f = vec![Wrench::new(1.0, 2.0, 0.3); 5];
            let mut out = vec![Reaction::default(); 3];
            let rn = chain_reactions(
                c.solver,
                &c.chain,
                &c.joints,
                &placed,
                &mut f.clone(),
                c.scale,
                &DyadSystem::None,
                &mut out,
            );
            let rs =
                screw::chain_reactions(&c.chain, &c.joints, &placed, &mut f, c.scale, &mut out);
            assert_eq!(
                matches!(rn, Err(MechError::Singular { .. })),
                matches!(rs, Err(MechError::Singular { .. })),
                "κ {kappa}: reactions {rn:?} vs {rs:?}"
            );
            assert_eq!(matches!(rn, Err(MechError::Singular { .. })), want);
            counted[usize::from(want)] += 1;
        }
        assert!(counted.iter().all(|&n| n >= 800), "{counted:?}");
    }
}
