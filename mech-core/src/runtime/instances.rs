//! Per-topology instances of the run-time dispatch: the macros and rebuilt joints through
//! which [`super::dispatch`] calls a group's kernels with the facts the generated code
//! knows as constants (the dyad's variant, each joint's side, which link is the ground)
//! written as literals, so that the kernels' own tests of them fold. The same kernels run
//! on the same numbers: only the branches differ (`tests/runtime_peer.rs` holds every
//! instance to the generated struct bit for bit).

/// `$call` with the closed-form dyad `$solver` (a [`crate::kernel::dyad::Solver`]) bound
/// to `$name` as a literal of its variant, for each dyad the dispatch writes out (RRR,
/// RRP, RPR, the slotted slider, PRP, RPP), so that the kernel's own `match` on the
/// solver folds in each arm; `$other` for any other.
macro_rules! written_out {
    ($solver:expr, |$name:ident| $call:expr, $other:expr) => {{
        use crate::kernel::dyad::Solver;
        match $solver {
            Solver::Rrr { b1, b2, ja, jc, jb } => {
                let $name = Solver::Rrr { b1, b2, ja, jc, jb };
                $call
            }
            Solver::Rrp { b1, b2, ja, jc, jp } => {
                let $name = Solver::Rrp { b1, b2, ja, jc, jp };
                $call
            }
            Solver::Rpr { b1, b2, ja, jp, jb } => {
                let $name = Solver::Rpr { b1, b2, ja, jp, jb };
                $call
            }
            Solver::SlottedSlider { body, jq, js } => {
                let $name = Solver::SlottedSlider { body, jq, js };
                $call
            }
            Solver::Prp {
                b1,
                b2,
                jp1,
                jc,
                jp2,
            } => {
                let $name = Solver::Prp {
                    b1,
                    b2,
                    jp1,
                    jc,
                    jp2,
                };
                $call
            }
            Solver::Rpp { b1, b2, ja, jp, jq } => {
                let $name = Solver::Rpp { b1, b2, ja, jp, jq };
                $call
            }
            _ => $other,
        }
    }};
}

/// A crank driven on the ground (`g` its joint, `d.body` ≠ 0 the crank) as the generated
/// code sees it: its joint rebuilt alone, as joint 0, with its sides as literals
/// (`JointGeom::with_links`: the ground on side a when `GROUND_A`, the crank's local vector
/// a literal zero when `PINNED`, the pin then its anchor), so that every side and "is it
/// the ground" test of the kernels folds; the kernels then run on the same numbers.
#[inline(always)]
pub(super) fn crank_alone<const GROUND_A: bool, const PINNED: bool>(
    d: &crate::kernel::screw::Driven,
    g: &crate::kernel::constraints::JointGeom,
) -> (
    crate::kernel::screw::Driven,
    [crate::kernel::constraints::JointGeom; 1],
) {
    let joint = if GROUND_A {
        g.with_links(0, d.body, [false, PINNED])
    } else {
        g.with_links(d.body, 0, [PINNED, false])
    };
    let driven = crate::kernel::screw::Driven {
        from: 0,
        screw: crate::kernel::screw::JointScrew {
            joint: 0,
            slide: false,
        },
        pinned: PINNED,
        ..*d
    };
    (driven, [joint])
}

/// `$call` with `$d` and `$joints` bound to [`crank_alone`]'s crank when the driven group
/// `$d` (joint geometry `$joints`) is a crank on the ground (the four combinations of its
/// side and its anchor, each a literal), else `$other`.
macro_rules! crank_alone {
    ($d:expr, $joints:expr, |$dn:ident, $jn:ident| $call:expr, $other:expr) => {{
        let (d0, joints0) = ($d, $joints);
        if d0.from == 0 && !d0.screw.slide && d0.body != 0 {
            let g = &joints0[d0.screw.joint];
            match (g.a == 0, d0.pinned) {
                (true, true) => {
                    let ($dn, $jn) = crank_alone::<true, true>(d0, g);
                    $call
                }
                (true, false) => {
                    let ($dn, $jn) = crank_alone::<true, false>(d0, g);
                    $call
                }
                (false, true) => {
                    let ($dn, $jn) = crank_alone::<false, true>(d0, g);
                    $call
                }
                (false, false) => {
                    let ($dn, $jn) = crank_alone::<false, false>(d0, g);
                    $call
                }
            }
        } else {
            $other
        }
    }};
}

/// `$m!(b₁, …, bₙ,)` with each bᵢ the literal `true` or `false` of the condition `$c`ᵢ,
/// as nested `if`s: in each of the 2ⁿ leaves every condition is known, both as the
/// literal passed to `$m` and, to the compiler, as a branch taken (so that a kernel's
/// own test of the same condition folds).
macro_rules! by_conditions {
    ($m:ident [$($acc:tt)*]) => { $m!($($acc)*) };
    ($m:ident [$($acc:tt)*] $c:expr $(, $rest:expr)*) => {
        if $c {
            by_conditions!($m [$($acc)* true,] $($rest),*)
        } else {
            by_conditions!($m [$($acc)* false,] $($rest),*)
        }
    };
}

/// A slotted slider's two joints (its guide `gq`, its slot joint `gs`; `body` the link,
/// `guide` and `k` the solved links across them) rebuilt as joints 0 and 1 with their
/// sides as literals: `body` on side b of the guide when `GQ_B`, on side a of the slot
/// joint when `GS_A`, the guide and K the ground (a literal 0) when `G0`, `K0`. The
/// kernels' side and ground tests then fold, as in the generated code, on the same numbers.
#[inline(always)]
pub(super) fn slotted_alone<const GQ_B: bool, const GS_A: bool, const G0: bool, const K0: bool>(
    gq: &crate::kernel::constraints::JointGeom,
    gs: &crate::kernel::constraints::JointGeom,
    body: usize,
    guide: usize,
    k: usize,
) -> [crate::kernel::constraints::JointGeom; 2] {
    let (guide, k) = (if G0 { 0 } else { guide }, if K0 { 0 } else { k });
    [
        if GQ_B {
            gq.with_links(guide, body, [false; 2])
        } else {
            gq.with_links(body, guide, [false; 2])
        },
        if GS_A {
            gs.with_links(body, k, [false; 2])
        } else {
            gs.with_links(k, body, [false; 2])
        },
    ]
}

/// `$call` with `$local` bound to [`slotted_alone`]'s joints of the slotted slider
/// (`$body`, joints `$jq`, `$js` of `$joints`), the sixteen combinations of its sides and
/// grounds each an instance; `$other` if the joints are not a slotted slider's.
macro_rules! slotted_alone {
    ($joints:expr, $body:expr, $jq:expr, $js:expr, |$local:ident| $call:expr, $other:expr) => {{
        let (body, gq, gs) = ($body, &$joints[$jq], &$joints[$js]);
        let guide = if gq.b == body { gq.a } else { gq.b };
        let k = if gs.a == body { gs.b } else { gs.a };
        if guide == body || k == body || body == 0 {
            $other
        } else {
            macro_rules! leaf {
                ($qb:expr, $sa:expr, $g0:expr, $k0:expr,) => {{
                    let $local = slotted_alone::<$qb, $sa, $g0, $k0>(gq, gs, body, guide, k);
                    $call
                }};
            }
            by_conditions!(leaf [] gq.b == body, gs.a == body, guide == 0, k == 0)
        }
    }};
}
