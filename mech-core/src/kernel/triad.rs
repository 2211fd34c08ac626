//! The class III Assur group of revolute joints (a triad: a ternary link pinned to three
//! binary links, each pinned to a solved link) by one eliminated unknown: the angle θ of
//! one binary link (the lead) places its inner pin; the ternary link and a second binary
//! link then close as an RRR dyad ([`crate::kernel::dyad::circle_circle`]), which places
//! the ternary link's third pin; the one scalar equation left is that the third binary
//! link reaches it, f(θ) = |A₃ − O₃|² − L₃² = 0 (m²). Newton on θ (safeguarded: the step
//! bounded, halved until |f| decreases and the dyad closes), f′ from the dyad's rates,
//! from the start's lead angle (the predictor) until a step would move no pin by more than
//! 3 % of the scale; from there, Newton on the two loop equations in θ and the ternary
//! link's angle φ together (a 2 × 2 system by Cramer's rule: no square root, no circle to
//! close: a step costs about half of one on θ alone), its root kept when its dyad is on
//! the same side and its assembly the drawing's (else the eliminated Newton goes on).
//! Started that close, it finds the root the eliminated Newton would (checked against it
//! over 300 random variants of the test machines, 180 angles each); from the drawing's
//! angle it may find another one on the same side and assembly sign. Each step turns the
//! angles by the rotation (den + i num)²/(den² + num²) of its half-angle tangent num/den:
//! unit, one division per step; a step that moves no pin by more than 1e-8 of the scale
//! is the last, taken unchecked. The other two binary links as the lead, then the general
//! Newton ([`crate::kernel::group::group_newton`]), are the fallbacks.
//!
//! The drawn assembly: the dyad's side σ is taken from the start configuration (the
//! drawing, or the caller's previous configuration, [`triad_solve`]'s `start`), the other
//! side tried when that fails; a root is accepted only when the sign of the group's
//! Jacobian determinant, det J ∝ (p × q)·f′ (p, q the dyad's two sides at its middle pin),
//! is the drawing's: that sign changes only through a dead point, so a root with the
//! other sign is another assembly and is rejected (`NoAssembly` when no root has it).

use crate::kernel::constraints::{Con, Drive, JointGeom, Level};
use crate::kernel::dyad::{circle_circle, pin, place_by_two_points};
use crate::kernel::group::{group_newton, group_rates, GroupSystem};
use crate::kernel::link_state::{cross, perp, quotient, rotate, LinkState, V2};
use crate::MechError;

/// A triad of revolute joints: the ternary link `mid`, and the binary links `links` =
/// [lead, dyad, close], each pinned to `mid` by `inner[k]` and to a solved link by
/// `outer[k]` (joint indices). The lead's angle is the unknown; the dyad link closes
/// with `mid` as an RRR dyad; the close link's length is the residual. Chosen by the plan
/// (`crate::plan::assur`) for the best-conditioned dyad and residual in the drawing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Triad {
    /// The ternary link.
    pub mid: usize,
    /// The binary links: [lead, dyad, close].
    pub links: [usize; 3],
    /// Their joints to solved links.
    pub outer: [usize; 3],
    /// Their joints to the ternary link.
    pub inner: [usize; 3],
}

/// The local vector of joint `g`'s point in `body` (one of its two links).
#[inline(always)]
fn side(g: &JointGeom, body: usize) -> V2 {
    if g.b == body {
        g.db
    } else {
        g.da
    }
}

/// The group's drawing geometry: local vectors and lengths (m, m²).
#[derive(Clone, Copy)]
struct Geom {
    /// The binary links' local vectors of their outer and inner pins.
    outer: [V2; 3],
    inner: [V2; 3],
    /// The ternary link's local vectors of its three pins.
    mid: [V2; 3],
    /// The lead's span (inner − outer), local, and its length.
    lead: V2,
    lead_len: f64,
    /// The ternary link's A₃ − A₁ over its B − A₁ as a complex number, (m/m), and
    /// |A₃ − A₁| (m): A₃ = A₁ + z (B − A₁).
    z: V2,
    arm: f64,
    /// The ternary link's B − A₁ and A₃ − A₁, local (m), and the longer one's length.
    m1: V2,
    m2: V2,
    reach: f64,
    /// |ternary B − A₁|², |dyad link|², |close link|² (m²).
    r_mid: f64,
    r_dyad: f64,
    r_close: f64,
}

impl Geom {
    #[inline(always)]
    fn new(t: &Triad, joints: &[JointGeom]) -> Geom {
        let [l1, l2, l3] = t.links;
        let [go1, go2, go3] = t.outer.map(|j| &joints[j]);
        let [gi1, gi2, gi3] = t.inner.map(|j| &joints[j]);
        let outer = [side(go1, l1), side(go2, l2), side(go3, l3)];
        let inner = [side(gi1, l1), side(gi2, l2), side(gi3, l3)];
        let mid = [side(gi1, t.mid), side(gi2, t.mid), side(gi3, t.mid)];
        let lead = inner[0] - outer[0];
        let (e21, e31) = (mid[1] - mid[0], mid[2] - mid[0]);
        Geom {
            outer,
            inner,
            mid,
            lead,
            lead_len: lead.norm(),
            z: quotient(e31, e21),
            arm: e31.norm(),
            m1: e21,
            m2: e31,
            reach: e21.norm_squared().max(e31.norm_squared()).sqrt(),
            r_mid: e21.norm_squared(),
            r_dyad: (inner[1] - outer[1]).norm_squared(),
            r_close: (inner[2] - outer[2]).norm_squared(),
        }
    }
}

/// The triad's pins in one configuration: the lead's inner pin A₁ (and its outer O₁), the
/// dyad's middle pin B (and the dyad link's outer O₂), the ternary link's third pin A₃
/// (and the close link's outer O₃), m.
#[derive(Clone, Copy)]
struct Pins {
    a1: V2,
    o1: V2,
    b: V2,
    o2: V2,
    a3: V2,
    o3: V2,
}

/// A Newton step on the lead's angle θ: the residual f = |A₃ − O₃|² − L₃² (m²), n (below),
/// and the step as the tangent of its half, Δθ/2 = `num`/`den`, with `reach` such that the
/// step moves no pin by more than `reach`/|`den`| (m).
///
/// With Ȧ₁ = perp(A₁ − O₁) (θ̇ = 1), the dyad's rates (B fixed to both of its links) give
/// the ternary link's ω = −(Ȧ₁·q)/c, p = B − A₁, q = B − O₂, c = p × q; then
/// Ȧ₃ = Ȧ₁ + ω perp(A₃ − A₁) and f′ = 2 (A₃ − O₃)·Ȧ₃ = 2n/c with
/// n = c (w·Ȧ₁) − (Ȧ₁·q)(w·perp(A₃ − A₁)), w = A₃ − O₃. So Δθ = −f/f′ = −f c/(2n):
/// num = −f c, den = 4n, and the largest pin move |Δθ| |lead| + |ω Δθ| |A₃ − A₁| is
/// (2|f c| |lead| + 2|f (Ȧ₁·q)| |A₃ − A₁|)/|den|. No division: [`half_turn`] takes the
/// step's one. n is the group's Jacobian determinant up to a positive factor and a sign of
/// the topology: its sign is the assembly's (the module's docs).
#[derive(Clone, Copy)]
struct Step {
    f: f64,
    n: f64,
    num: f64,
    den: f64,
    reach: f64,
}

#[inline(always)]
fn newton_step(x: &Pins, g: &Geom) -> Step {
    let (p, q) = (x.b - x.a1, x.b - x.o2);
    let c = cross(p, q);
    let da1 = perp(x.a1 - x.o1);
    let w = x.a3 - x.o3;
    let f = w.norm_squared() - g.r_close;
    let dq = da1.dot(&q);
    let n = c * w.dot(&da1) - dq * w.dot(&perp(x.a3 - x.a1));
    let num = -f * c;
    Step {
        f,
        n,
        num,
        den: 4.0 * n,
        reach: 2.0 * (num.abs() * g.lead_len + (f * dq).abs() * g.arm),
    }
}

/// The sign of [`Step`]'s n at `x` alone: ±1, 0 at a dead point.
#[inline(always)]
fn det_sign(x: &Pins) -> f64 {
    let (p, q) = (x.b - x.a1, x.b - x.o2);
    let c = cross(p, q);
    let da1 = perp(x.a1 - x.o1);
    let w = x.a3 - x.o3;
    sign0(c * w.dot(&da1) - da1.dot(&q) * w.dot(&perp(x.a3 - x.a1)))
}

/// The pins at the lead's rotation `u` (unit, from the drawing), on the dyad's side
/// `sigma`: A₁ = O₁ + R(u) (lead's span), B on the circles (A₁, |ternary side|) and
/// (O₂, |dyad link|), A₃ = A₁ + z (B − A₁).
#[inline(always)]
fn pins_at(g: &Geom, o: [V2; 3], u: V2, sigma: f64) -> Result<Pins, MechError> {
    let a1 = o[0] + rotate(u, g.lead);
    let b = circle_circle(a1, g.r_mid, o[1], g.r_dyad, sigma)?;
    Ok(Pins {
        a1,
        o1: o[0],
        b,
        o2: o[1],
        a3: a1 + rotate(g.z, b - a1),
        o3: o[2],
    })
}

/// The pins of the group's links as they stand in `s` (each from its own link).
#[inline(always)]
fn pins_of(t: &Triad, g: &Geom, s: &[LinkState]) -> Pins {
    let [l1, l2, l3] = t.links;
    Pins {
        a1: s[t.mid].point(g.mid[0]),
        o1: s[l1].point(g.outer[0]),
        b: s[t.mid].point(g.mid[1]),
        o2: s[l2].point(g.outer[1]),
        a3: s[t.mid].point(g.mid[2]),
        o3: s[l3].point(g.outer[2]),
    }
}

/// The sign of the group's Jacobian determinant (±1, 0 at a dead point) in `s`.
#[inline(always)]
fn assembly(t: &Triad, g: &Geom, s: &[LinkState]) -> f64 {
    det_sign(&pins_of(t, g, s))
}

/// −1, 0 or +1 (0 for zero and NaN).
#[inline(always)]
fn sign0(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The lead's rotation `u` moved, when the dyad cannot close there, to the nearest one
/// where it closes with a margin: with d = O₁ − O₂, the lead's span L₁ v (v unit) and R,
/// R₂ the dyad's radii, |A₁ − O₂|² = |d|² + L₁² + 2 L₁ (v·d) must lie in
/// [(R − R₂)², (R + R₂)²], an interval of k = L₁ (v·d); k is clamped into it less 5 % of its
/// width at each end, on the same side of d. `NoAssembly` when it is empty.
#[inline(always)]
fn feasible(g: &Geom, o: [V2; 3], u: V2) -> Result<V2, MechError> {
    let l1sq = g.lead.norm_squared();
    let d = o[0] - o[1];
    let dsq = d.norm_squared();
    let v = rotate(u, g.lead);
    let dv = d.dot(&v);
    let x = dsq + l1sq + 2.0 * dv;
    let (rr, r2) = (g.r_mid, g.r_dyad);
    let cross_term = 2.0 * (rr * r2).sqrt();
    let (lo, hi) = (rr + r2 - cross_term, rr + r2 + cross_term);
    if x > lo && x < hi {
        return Ok(u);
    }
    // x = |d|² + L₁² + 2k, |k| ≤ L₁ |d|.
    let span = (l1sq * dsq).sqrt();
    let (klo, khi) = (
        (0.5 * (lo - dsq - l1sq)).max(-span),
        (0.5 * (hi - dsq - l1sq)).min(span),
    );
    if !(klo < khi) {
        return Err(MechError::NoAssembly);
    }
    let m = 0.05 * (khi - klo);
    let k = dv.clamp(klo + m, khi - m);
    // v = (k d + s √(L₁²|d|² − k²) perp(d)) / |d|², s the side of v from d.
    let s = if cross(d, v) < 0.0 { -1.0 } else { 1.0 };
    let w = (d * k + perp(d) * (s * (span * span - k * k).max(0.0).sqrt())) * (1.0 / dsq);
    let u = quotient(w, g.lead);
    Ok(u * (1.0 / u.norm()))
}

/// The most Newton steps of one search.
const MAX_STEPS: usize = 40;
/// The largest step of the lead's angle (rad).
const MAX_TURN: f64 = 0.5;
/// The largest pin move of a step taken as the last one, unchecked (of the scale).
const FINAL_MOVE: f64 = 1e-8;

/// The rotation by 2 atan(num/den): (den + i num)²/(den² + num²), unit with no square root
/// and one division (the Newton step's, [`Step`]). For a step Δθ, num/den = Δθ/2 turns by
/// 2 atan(Δθ/2) = Δθ + O(Δθ³).
#[inline(always)]
fn half_turn(num: f64, den: f64) -> V2 {
    V2::new((den - num) * (den + num), 2.0 * den * num) * (1.0 / (den * den + num * num))
}

/// Newton on the lead's angle from rotation `u` on the dyad's side `sigma`: the pins at
/// the root and the sign of its assembly's n ([`Step`]); `NoAssembly` when the dyad cannot
/// close, the steps stall, or they do not converge. Each step is bounded by 0.5 rad, then
/// halved until |f| decreases and the dyad closes. Converged when the next step would move
/// no pin by more than 1e-14 `scale` (m); a step of at most 1e-8 `scale` is taken as the
/// last one without evaluating the next (Newton's error after it, O(step²), is below the
/// tolerance). Once a step would move no pin by more than [`SWITCH`] `scale`,
/// [`both_angles`] takes over from there (once), its root returned when its assembly sign
/// is `drawn` (0 accepts any).
#[inline(always)]
fn search(
    g: &Geom,
    o: [V2; 3],
    mut u: V2,
    sigma: f64,
    scale: f64,
    drawn: f64,
) -> Result<(Pins, f64), MechError> {
    let mut x = pins_at(g, o, u, sigma)?;
    let mut st = newton_step(&x, g);
    let (tol, final_move) = (1e-14 * scale, FINAL_MOVE * scale);
    let switch = SWITCH * scale;
    let mut both = true;
    for _ in 0..MAX_STEPS {
        if !(st.num.is_finite() && st.den.is_finite() && st.den != 0.0) {
            return Err(MechError::NoAssembly);
        }
        let big = st.den.abs();
        if st.reach <= tol * big {
            return Ok((x, sign0(st.n)));
        }
        if both && st.reach <= switch * big {
            both = false;
            if let Some(y) = both_angles(g, o, u, &x, sigma, scale) {
                let det = det_sign(&y);
                if drawn == 0.0 || det == drawn {
                    return Ok((y, det));
                }
            }
        }
        if st.reach <= final_move * big {
            if let Ok(y) = pins_at(g, o, rotate(u, half_turn(st.num, st.den)), sigma) {
                return Ok((y, det_sign(&y)));
            }
        }
        // |Δθ| ≤ MAX_TURN: |num| ≤ MAX_TURN/2 |den|.
        let lim = 0.5 * MAX_TURN * big;
        let mut num = st.num.clamp(-lim, lim);
        loop {
            let v = rotate(u, half_turn(num, st.den));
            if let Ok(y) = pins_at(g, o, v, sigma) {
                let next = newton_step(&y, g);
                if next.f.abs() < st.f.abs() {
                    (u, x, st) = (v, y, next);
                    break;
                }
            }
            num *= 0.5;
            // |Δθ| |lead| = 2 |num| |lead| / |den| ≤ 0.1 tol: stalled.
            if 2.0 * num.abs() * g.lead_len <= 0.1 * tol * big {
                return Err(MechError::NoAssembly);
            }
        }
    }
    Err(MechError::NoAssembly)
}

/// The largest pin move of a Newton step on the lead's angle from which [`search`] turns
/// to [`both_angles`] (of the scale).
const SWITCH: f64 = 0.03;
/// The most steps of [`both_angles`].
const MAX_BOTH: usize = 12;

/// Newton on the lead's and the ternary link's angles (θ, φ) together, from the pins `x`
/// (the lead at rotation `u`, the dyad closed on side `sigma`): the two loop equations
/// g₂ = |B − O₂|² − L₂² = 0 and g₃ = |A₃ − O₃|² − L₃² = 0, with A₁ = O₁ + R(θ) (lead's
/// span), B = A₁ + R(φ) m₁, A₃ = A₁ + R(φ) m₂ (m₁, m₂ the ternary link's local B − A₁,
/// A₃ − A₁). With e₂ = B − O₂, e₃ = A₃ − O₃, Ȧ₁ = perp(A₁ − O₁), the Jacobian is 2 j,
/// j = [e₂·Ȧ₁, e₂·perp(B − A₁); e₃·Ȧ₁, e₃·perp(A₃ − A₁)], and Cramer's rule gives the
/// half-angle tangents of the step, Δθ/2 = (g₃ j₁₂ − g₂ j₂₂)/(4 det j) and
/// Δφ/2 = (g₂ j₂₁ − g₃ j₁₁)/(4 det j), each turned by [`half_turn`]: no square root, and
/// the two divisions side by side. Each step is bounded by 0.5 rad in either angle.
/// Converged as [`search`] (no pin moved by more than 1e-14 `scale` by the next step, a
/// step of at most 1e-8 `scale` taken as the last); the root is kept only when its dyad is
/// on side `sigma` (B on that side of A₁ → O₂). `None` otherwise, or after
/// [`MAX_BOTH`] steps: then [`search`] goes on. Started close to the root (within
/// [`SWITCH`]), where it finds the one the eliminated Newton would: from farther (the
/// drawing's angle, say) it may find another root on the same side and assembly sign.
#[inline(always)]
fn both_angles(g: &Geom, o: [V2; 3], mut u: V2, x: &Pins, sigma: f64, scale: f64) -> Option<Pins> {
    // The ternary link's rotation: (B − A₁)/m₁, |B − A₁| = |m₁|.
    let mut v = V2::new(g.m1.dot(&(x.b - x.a1)), cross(g.m1, x.b - x.a1)) * (1.0 / g.r_mid);
    let (tol, final_move) = (1e-14 * scale, FINAL_MOVE * scale);
    let pins = |u: V2, v: V2| {
        let a1 = o[0] + rotate(u, g.lead);
        Pins {
            a1,
            o1: o[0],
            b: a1 + rotate(v, g.m1),
            o2: o[1],
            a3: a1 + rotate(v, g.m2),
            o3: o[2],
        }
    };
    let mut y = *x;
    for _ in 0..MAX_BOTH {
        let (e2, e3) = (y.b - y.o2, y.a3 - y.o3);
        let (g2, g3) = (e2.norm_squared() - g.r_dyad, e3.norm_squared() - g.r_close);
        let da1 = perp(y.a1 - y.o1);
        let (j11, j12) = (e2.dot(&da1), e2.dot(&perp(y.b - y.a1)));
        let (j21, j22) = (e3.dot(&da1), e3.dot(&perp(y.a3 - y.a1)));
        let den = 4.0 * (j11 * j22 - j12 * j21);
        let (nt, nf) = (g3 * j12 - g2 * j22, g2 * j21 - g3 * j11);
        if !(den.is_finite() && den != 0.0 && nt.is_finite() && nf.is_finite()) {
            return None;
        }
        let big = den.abs();
        let reach = 2.0 * (nt.abs() * g.lead_len + nf.abs() * g.reach);
        let last = reach <= final_move * big;
        if reach <= tol * big || last {
            if last {
                y = pins(rotate(u, half_turn(nt, den)), rotate(v, half_turn(nf, den)));
            }
            return (cross(y.o2 - y.a1, y.b - y.a1) * sigma >= 0.0).then_some(y);
        }
        let lim = 0.5 * MAX_TURN * big;
        u = rotate(u, half_turn(nt.clamp(-lim, lim), den));
        v = rotate(v, half_turn(nf.clamp(-lim, lim), den));
        y = pins(u, v);
    }
    None
}

/// The triad's positions: Newton on the lead's angle from the predictor `u` (the lead's
/// rotation in the start configuration, moved to where the dyad closes), on the dyad's
/// side of the start's pins `start`, then the other side; the root accepted when its
/// assembly sign is `drawn` (0 accepts any). Writes the four links' states into `s` on
/// success only.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn triad_pose(
    t: &Triad,
    g: &Geom,
    joints: &[JointGeom],
    s: &mut [LinkState],
    start: &Pins,
    u: V2,
    drawn: f64,
    scale: f64,
) -> Result<(), MechError> {
    let [l1, l2, l3] = t.links;
    let o = [
        pin(&joints[t.outer[0]], s, l1).0,
        pin(&joints[t.outer[1]], s, l2).0,
        pin(&joints[t.outer[2]], s, l3).0,
    ];
    let sigma = if cross(start.o2 - start.a1, start.b - start.a1) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let u = feasible(g, o, u)?;
    for side in [sigma, -sigma] {
        let Ok((x, det)) = search(g, o, u, side, scale, drawn) else {
            continue;
        };
        if drawn != 0.0 && det != drawn {
            continue;
        }
        place_by_two_points(&mut s[l1], g.outer[0], g.inner[0], x.o1, x.a1);
        place_by_two_points(&mut s[t.mid], g.mid[0], g.mid[1], x.a1, x.b);
        place_by_two_points(&mut s[l2], g.outer[1], g.inner[1], x.o2, x.b);
        place_by_two_points(&mut s[l3], g.outer[2], g.inner[2], x.o3, x.a3);
        return Ok(());
    }
    Err(MechError::NoAssembly)
}

/// [`triad_pose`] with each of the two other binary links as the lead (the order turned
/// once, then twice), each with its own assembly sign from the drawing: the second try
/// when the plan's lead finds no root on the drawn assembly from the start (a dyad that
/// changed side since the drawing, or a start far from the root). Off the common path.
#[inline(never)]
#[cold]
fn other_leads(
    t: &Triad,
    joints: &[JointGeom],
    s: &mut [LinkState],
    drawing: &[LinkState],
    from: &[LinkState],
    scale: f64,
) -> Result<(), MechError> {
    let turn = |x: [usize; 3]| [x[1], x[2], x[0]];
    let mut order = *t;
    for _ in 0..2 {
        order = Triad {
            mid: t.mid,
            links: turn(order.links),
            outer: turn(order.outer),
            inner: turn(order.inner),
        };
        let g = Geom::new(&order, joints);
        let drawn = assembly(&order, &g, drawing);
        let (pins, u) = (pins_of(&order, &g, from), from[order.links[0]].rot);
        if triad_pose(&order, &g, joints, s, &pins, u, drawn, scale).is_ok() {
            return Ok(());
        }
    }
    Err(MechError::NoAssembly)
}

/// [`triad_solve`]'s positions: the plan's lead from `start`, then the other leads, then
/// (a `start` that found nothing) the same from the drawing. Whether they were found, and
/// the drawing's assembly sign.
#[inline(always)]
fn positions(
    t: &Triad,
    joints: &[JointGeom],
    s: &mut [LinkState],
    scale: f64,
    drawing: &[LinkState],
    start: Option<&[LinkState]>,
) -> (bool, f64) {
    let g = Geom::new(t, joints);
    // The drawing's pins: its assembly sign, and the start of a call without `start`.
    let drawn_pins = pins_of(t, &g, drawing);
    let drawn = det_sign(&drawn_pins);
    // From `start`, then (a warm start that found nothing) from the drawing, as a call
    // without one would: a warm start never fails where the drawing's start succeeds.
    let attempt = |s: &mut [LinkState], pins: &Pins, from: &[LinkState]| {
        triad_pose(t, &g, joints, s, pins, from[t.links[0]].rot, drawn, scale).is_ok()
            || other_leads(t, joints, s, drawing, from, scale).is_ok()
    };
    let solved = match start {
        Some(from) => attempt(s, &pins_of(t, &g, from), from) || attempt(s, &drawn_pins, drawing),
        None => attempt(s, &drawn_pins, drawing),
    };
    (solved, drawn)
}

/// Solve a triad ([`Triad`], its group's `bodies` and `cons`) up to `upto`: positions by
/// Newton on the lead's angle (the module's docs), started from `start` (a previous
/// configuration's states, every link; only the group's are read) or else from
/// `drawing` (the drawing's states, every link); with each of the other two binary links
/// as the lead when that fails, then (a `start` that found nothing) all of it again from
/// the drawing, and then the general Newton from the drawing, its root kept only on the
/// drawing's assembly. `s` holds the solved
/// links' states on entry (the group's own are not read). Then, when asked, velocities
/// and accelerations from the group's linear system, which is returned for the
/// reactions (as [`crate::kernel::group::group_solve`]).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn triad_solve<const N: usize>(
    t: &Triad,
    bodies: &[usize],
    cons: &[Con],
    joints: &[JointGeom],
    s: &mut [LinkState],
    drive: Drive,
    scale: f64,
    upto: Level,
    drawing: &[LinkState],
    start: Option<&[LinkState]>,
) -> Result<Option<GroupSystem<N>>, MechError> {
    let (solved, drawn) = positions(t, joints, s, scale, drawing, start);
    if !solved {
        for &b in bodies {
            s[b] = drawing[b];
        }
        group_newton::<N>(bodies, cons, joints, s, drive, scale)?;
        if drawn != 0.0 && assembly(t, &Geom::new(t, joints), s) == -drawn {
            return Err(MechError::NoAssembly);
        }
    }
    if matches!(upto, Level::Velocity | Level::Acceleration) {
        let sys = GroupSystem::<N>::new(bodies, cons, joints, s, scale)?;
        group_rates(&sys, bodies, cons, joints, s, drive, Level::Velocity);
        if upto == Level::Acceleration {
            group_rates(&sys, bodies, cons, joints, s, drive, Level::Acceleration);
        }
        return Ok(Some(sys));
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    //! The triad's elimination against the general Newton it replaces, over full turns of
    //! the crank: the same positions (1e-12 of the drawing's size), the drawn assembly
    //! kept (against Newton continued step by step from the drawing), the warm start from
    //! the previous configuration the same, and `NoAssembly` past a dead point.

    use super::*;
    use crate::front::resolve::model_of;
    use crate::kernel::kinematics::solve_driven;
    use crate::kernel::measure::within;
    use crate::plan::assur::{plan, Group, Kernel};
    use crate::solvers::instance::{instance, Instance};

    /// pyslvs's Stephenson III (`examples/mech/stephenson_iii.mech`, in mm scaled to m):
    /// the crank L1, then the triad L2, L3 (ternary), L4, L5. And a Stephenson II-like
    /// triad whose outer pins are all on the ground but one on the crank's far end, the
    /// crank turning a full turn in both.
    pub(crate) const TRIADS: [&str; 2] = [
        "pub struct StephensonIII {
            ground { P0: (0.00025, -0.000625), P4: (0.117125, 0.023375), P6: (0.138875, 0.033125) },
            link L1 { points { P0, P1: (0.015375, 0.041125) } },
            link L2 { points { P1, P2: (0.061375, 0.095125) } },
            link L3 { points { P2, P3: (0.102875, 0.084375), P5: (0.134625, 0.119875) } },
            link L4 { points { P3, P4 } },
            link L5 { points { P5, P6 } },
            joints { J0: revolute(ground, L1) at P0, J1: revolute(L1, L2) at P1,
                     J2: revolute(L2, L3) at P2, J3: revolute(L3, L4) at P3,
                     J4: revolute(ground, L4) at P4, J5: revolute(L3, L5) at P5,
                     J6: revolute(ground, L5) at P6 },
            input: J0 }",
        "pub struct Tilted {
            ground { O: (0.0, 0.0), G1: (0.32, 0.05), G2: (0.12, 0.33) },
            link crank { points { O, A: (0.02, 0.01) } },
            link l1 { points { A, B: (0.17, 0.1) } },
            link tri { points { B, C: (0.25, 0.17), D: (0.16, 0.22) } },
            link l2 { points { C, G1 } },
            link l3 { points { D, G2 } },
            joints { O: revolute(ground, crank), A: revolute(crank, l1), B: revolute(l1, tri),
                     C: revolute(tri, l2), G1: revolute(ground, l2), D: revolute(tri, l3),
                     G2: revolute(ground, l3) },
            input: O }",
    ];

    /// The model's instance and plan, the plan's one triad group.
    fn setup(text: &str) -> (Instance, Vec<Group>, usize) {
        let model = model_of(text);
        let inst = instance(&model).unwrap();
        let groups = plan(&model).unwrap();
        let t = groups
            .iter()
            .position(|g| g.triad.is_some())
            .expect("a triad");
        assert_eq!(groups[t].kernel, Kernel::System);
        (inst, groups, t)
    }

    /// The states at input `q`: the crank, then the triad by `route` (0 the triad's
    /// elimination from the drawing, 1 the same from `prev`, 2 the general Newton from
    /// the drawing, 3 the general Newton from `prev`).
    fn solve(
        inst: &Instance,
        groups: &[Group],
        q: f64,
        route: u8,
        prev: &[LinkState],
    ) -> Result<Vec<LinkState>, MechError> {
        let mut s = inst.drawing.clone();
        let drive = (&[q][..], &[0.0][..], &[0.0][..]);
        for g in groups {
            match (&g.kernel, g.triad) {
                (Kernel::Driven(d), _) => {
                    solve_driven(g.solver, d, &inst.joints, &mut s, drive, Level::Position)?
                }
                (Kernel::System, Some(t)) => {
                    let (b, c, j, l) = (&g.bodies, &g.cons, &inst.joints, inst.scale);
                    if route >= 2 {
                        if route == 3 {
                            for &k in b {
                                s[k] = prev[k];
                            }
                        }
                        group_newton::<12>(b, c, j, &mut s, drive, l)?;
                    } else {
                        let start = (route == 1).then_some(prev);
                        triad_solve::<12>(
                            &t,
                            b,
                            c,
                            j,
                            &mut s,
                            drive,
                            l,
                            Level::Position,
                            &inst.drawing,
                            start,
                        )?;
                    }
                }
                _ => unreachable!(),
            }
        }
        Ok(s)
    }

    /// The largest distance between the pins of two solutions, over the drawing's size.
    fn distance(inst: &Instance, a: &[LinkState], b: &[LinkState]) -> f64 {
        inst.joints
            .iter()
            .map(|j| (a[j.b].point(j.db) - b[j.b].point(j.db)).norm())
            .fold(0.0, f64::max)
            / inst.scale
    }

    #[test]
    fn triads_match_newton_over_a_turn_on_the_drawn_assembly() {
        for text in TRIADS {
            let (inst, groups, _) = setup(text);
            let q0 = inst.joints[0].q_ref;
            let mut cont = inst.drawing.clone();
            let mut warm = inst.drawing.clone();
            let (mut worst, mut worst_warm) = (0.0f64, 0.0f64);
            for k in 0..=720 {
                let q = q0 + std::f64::consts::TAU * k as f64 / 720.0;
                // The drawn assembly: Newton continued from the previous step.
                cont = solve(&inst, &groups, q, 3, &cont).unwrap();
                let cold = solve(&inst, &groups, q, 0, &inst.drawing).unwrap();
                let newton = solve(&inst, &groups, q, 2, &inst.drawing).unwrap();
                warm = solve(&inst, &groups, q, 1, &warm).unwrap();
                let d = distance(&inst, &cold, &cont);
                assert!(within(d, 1e-12), "{text}: {d} at step {k}");
                let dn = distance(&inst, &cold, &newton);
                assert!(within(dn, 1e-12), "{text}: against Newton {dn} at step {k}");
                worst = worst.max(d);
                worst_warm = worst_warm.max(distance(&inst, &warm, &cold));
            }
            assert!(within(worst_warm, 1e-12), "{text}: warm {worst_warm}");
        }
    }

    /// A crank too long for the triad: past its dead points there is no assembly, and the
    /// solver says so (no panic, no NaN); where it assembles, on the drawn assembly.
    #[test]
    fn past_a_dead_point_no_assembly() {
        let text = TRIADS[0].replace("P1: (0.015375, 0.041125)", "P1: (0.03, 0.08)");
        let (inst, groups, _) = setup(&text);
        let q0 = inst.joints[0].q_ref;
        let (mut ok, mut none) = (0, 0);
        let mut cont = inst.drawing.clone();
        let mut lost = false;
        for k in 0..=360 {
            let q = q0 + std::f64::consts::TAU * k as f64 / 360.0;
            let c = solve(&inst, &groups, q, 3, &cont);
            match solve(&inst, &groups, q, 0, &inst.drawing) {
                Ok(s) => {
                    ok += 1;
                    assert!(s.iter().all(|x| x.pos.x.is_finite() && x.rot.x.is_finite()));
                    if let (false, Ok(c)) = (lost, &c) {
                        let d = distance(&inst, &s, c);
                        assert!(within(d, 1e-12), "{d} at step {k}");
                    }
                }
                Err(e) => {
                    assert_eq!(e, MechError::NoAssembly, "step {k}");
                    none += 1;
                }
            }
            match c {
                Ok(c) => cont = c,
                Err(_) => lost = true,
            }
        }
        assert!(ok > 0 && none > 0, "{ok} assembled, {none} not");
    }
}
