//! The lane mask (`mech_core::kernel::lanes::Mask`): one bit per lane, as the packed
//! compares give it. Every one of the sixteen masks against the four booleans it stands
//! for: the compares that build it, the reading of a lane, the set lanes in order, the
//! join and the "any lane" test.

use mech_core::kernel::lanes::{any, or, Base, Mask, ALL, L, LANES, NONE};

/// The sixteen masks as four booleans each, lane k set where bit k of `m` is.
fn every() -> impl Iterator<Item = [bool; LANES]> {
    (0u8..16).map(|m| std::array::from_fn(|k| m >> k & 1 != 0))
}

/// The mask of `lanes` as the baseline backend's packed compare builds it: x < 0 in the
/// set lanes. (The 256-bit backend runs only inside `with_simd`'s AVX2 path; the lane
/// kernels' own tests run every test on both and find them equal bit for bit.)
fn compared(lanes: [bool; LANES]) -> Mask {
    let x = L::<Base>::new(lanes.map(|set| if set { -1.0 } else { 1.0 }));
    x.less(L::splat(0.0)).mask()
}

#[test]
fn a_mask_reads_the_lanes_it_was_built_from() {
    for lanes in every() {
        let m = Mask::from_lanes(lanes);
        assert_eq!(m.lanes(), lanes);
        for (k, &set) in lanes.iter().enumerate() {
            assert_eq!(m[k], set, "lane {k} of {lanes:?}");
        }
        let set: Vec<usize> = (0..LANES).filter(|&k| lanes[k]).collect();
        assert_eq!(m.set().collect::<Vec<_>>(), set);
        assert_eq!(any(m), lanes.contains(&true));
        // The packed compare gives the same mask.
        assert_eq!(compared(lanes), m, "{lanes:?}");
        // `test`, the lane-by-lane scalar form, too.
        let x = L::<Base>::new(lanes.map(|set| if set { -1.0 } else { 1.0 }));
        assert_eq!(x.test(L::splat(0.0), |a, b| a < b), m);
    }
}

#[test]
fn masks_join_lane_by_lane() {
    for a in every() {
        for b in every() {
            let joined = or(Mask::from_lanes(a), Mask::from_lanes(b));
            assert_eq!(joined.lanes(), std::array::from_fn(|k| a[k] || b[k]));
        }
    }
    assert_eq!(NONE.lanes(), [false; LANES]);
    assert_eq!(ALL.lanes(), [true; LANES]);
    assert!(!any(NONE) && any(ALL));
    assert_eq!(
        format!("{:?}", Mask::from_lanes([true, false, false, true])),
        "[true, false, false, true]"
    );
}
