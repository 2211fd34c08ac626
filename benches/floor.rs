//! The floor: the generated solvers against expert hand-written closed-form code of the
//! same machines (`benches/floor/hand.rs` and the `hand_*.rs` beside it), timed in the same
//! run so that the ratio generated / hand is meaningful. `tests/floor.rs` proves that both
//! compute the same numbers (1e-12 relative on a sweep of a full turn).
//!
//! Machines, by the kind of group that follows their driven crank, and their groups (each
//! with the functions `generated` and `hand`):
//!
//! - the crank-rocker four-bar (an RRR dyad): `four_bar/pose`, `four_bar/kinematics`,
//!   `four_bar/kinematics+kinetostatics`, `four_bar/kinematics+driver_action`;
//! - the offset slider-crank (an RRP dyad): `slider_crank/reduced`,
//!   `slider_crank/acceleration`;
//! - the crank-shaper quick-return (`QuickReturn`: the block on the crank pin slides in a
//!   lever pivoted on the ground, an RPR dyad whose guide is pinned to the ground),
//!   `quick_return/<op>`;
//! - the Scotch yoke (`ScotchYoke`: the crank pin in the slot of a yoke guided by the
//!   ground, a one-link group of a guide and a pin in a slot, the closed-form
//!   `SlottedSlider` of `mech_core::kernel::dyad`), `scotch_yoke/<op>`;
//! - the inverted slider-crank (`InvertedSliderCrank` of `benches/floor/machines.rs`: the
//!   rod pinned to the crank slides through a block pivoted on the ground, its slide line
//!   off the pin, an RPR dyad whose guide is pinned to the crank),
//!   `inverted_slider_crank/<op>`;
//! - the geared slider-crank (`GearedSliderCrank` of `benches/floor/machines.rs`: the
//!   input pinion drives, 3:1 down through a 20° gear pair, the gear that carries the
//!   crank of an offset slider-crank; a meshing group of one link, Willis' relation, then
//!   an RRP dyad), `geared_slider_crank/<op>`;
//! - the roller cam (`RollerCam` of `benches/floor/machines.rs`: a disc cam, the input,
//!   lifts an offset translating roller follower by a cycloidal rise–dwell–cycloidal
//!   fall–dwell law; a cam group of one link), `roller_cam/<op>`;
//! - the crank, rod and rolling wheel (`CrankRodWheel` of `benches/floor/machines.rs`: the
//!   rod drives the centre of a wheel that rolls without slipping on a straight track; a
//!   rolling group, the crank–rod–wheel dyad), `crank_rod_wheel/<op>`;
//! - the Scotch yoke with a block (`BlockScotchYoke` of `benches/floor/machines.rs`: the
//!   block pinned to the crank slides in the slanted slot of a yoke that slides on the
//!   ground; an RPP dyad, the closed-form `Rpp` of `mech_core::kernel::dyad`),
//!   `block_scotch_yoke/<op>`;
//! - the slotted crank and ram (`SlottedCrankRam` of `benches/floor/machines.rs`: the block
//!   sliding in the crank's slot is pinned to a ram that slides on a tilted ground guide off
//!   the crank's pivot; a PRP dyad, the closed-form `Prp`), `slotted_crank_ram/<op>`;
//! - the planetary reducer (`Planetary` of `benches/floor/machines.rs`: the input sun
//!   drives a planet, pinned to an arm, that rolls inside a fixed ring; the arm and the
//!   planet one gear-train group, Willis' relations of both meshes), `planetary/<op>`;
//! - the rack and pinion (`RackPinion` of `benches/floor/machines.rs`: the input pinion
//!   drives a rack on a tilted ground guide; a meshing group of one link, the rack's slide
//!   and the mesh), `rack_pinion/<op>`,
//!
//! where `<op>` is each of `pose`, `kinematics`, `kinematics+kinetostatics`,
//! `kinematics+driver_action`, `reduced`, `acceleration`. Inputs as in `benches/solvers.rs`:
//! q = 0.7, q̇ = 12, q̈ = −3; the four-bar carries the tool force (80, −60) N at P and a
//! 2 N·m resisting torque on the rocker; the slider-crank a −1500 N gas force on the piston
//! at B, a −4 N·m shaft torque and a 5 N·m driver (acceleration); the quick-return a cutting
//! force (−250, 30) N at the lever's end C and a −1.5 N·m friction torque on the crank; the
//! Scotch yoke a force (−120, 15) N on the yoke at Y and a −1.5 N·m drag on the crank; the
//! inverted slider-crank a force (−300, 40) N on the rod at P and a 2.5 N·m torque on the
//! block; the geared slider-crank a gas force (−900, −90) N on the piston at B and a
//! −4 N·m shaft torque on the gear (q, q̇, q̈ are the pinion's: the crank turns at −1/3 of
//! them); the roller cam a force (20, −250) N on the follower at its top T and a −1.5 N·m
//! drag on the cam; the crank, rod and wheel a pull (−150, 20) N on the wheel at its centre
//! and a −0.8 N·m brake on the wheel; the Scotch yoke with a block a force (−150, 20) N on
//! the yoke at its end T and a −0.6 N·m friction couple on the block; the slotted crank
//! and ram a force (−400, 60) N on the ram at its tool point P and a 1.8 N·m torque on the
//! block; the planetary a pull (40, −60) N on the arm's lever end T and a −2 N·m brake on the
//! arm (q, q̇, q̈ are the sun's: the arm turns at 2/9 of them); the rack and pinion a push
//! (−250, 30) N on the rack at L and a −2 N·m torque on the pinion (q, q̇, q̈ are the
//! pinion's: the rack travels 30 mm per radian); these ten a 5 N·m driver (acceleration).
//! All inputs, and the solver struct itself, go through `black_box` (no constant folding of
//! the drawing).
//!
//! Run and tabulate:
//!
//! ```text
//! export CARGO_TARGET_DIR=...                     # the same for both commands
//! cargo bench --bench floor -- --warm-up-time 1 --measurement-time 3
//! python3 tools/floor_ratios.py                   # markdown table of medians and ratios
//! ```
//!
//! Counting instructions per call (deterministic, insensitive to the load of a shared
//! machine) with callgrind: run one benchmark in criterion's profiling mode (no analysis,
//! no output files) under valgrind, then divide the instructions spent under criterion's
//! timing loop by the number of iterations.
//!
//! ```text
//! cargo bench --bench floor --no-run        # prints "Executable ... (target/release/deps/floor-<hash>)"
//! BIN=$(ls -t $CARGO_TARGET_DIR/release/deps/floor-* | grep -v '\.d$' | head -1)
//! valgrind --tool=callgrind --callgrind-out-file=cg.out \
//!     $BIN --bench --profile-time 1 '^four_bar/kinematics/hand$'
//! callgrind_annotate --inclusive=yes --tree=caller cg.out | grep -A1 'Bencher<M>::iter'
//! ```
//!
//! The filter is a regex on `group/function` (escape the `+` of `kinematics\+kinetostatics`).
//! In the `--tree=caller` listing, the line `N (..%) * ...Bencher<M>::iter` is the
//! inclusive count of the timing loop, and the solver it calls appears with
//! `< ...Bencher<M>::iter (Kx)`, K = the number of iterations: instructions per call
//! = N / K (criterion's loop and `black_box` add a handful). One awk line does it:
//!
//! ```text
//! callgrind_annotate --inclusive=yes --tree=caller cg.out | awk \
//!   '/\* .*Bencher<M>::iter/{gsub(",","",$1); n=$1}
//!    /< .*Bencher<M>::iter \(/{c=$0; sub(/.*\(/,"",c); sub(/x\).*/,"",c); gsub(",","",c); k=c}
//!    END{printf "%.0f instructions per call\n", n/k}'
//! ```
//!
//! Valgrind runs the code ~50× slower, so `--profile-time 1` is a few hundred thousand
//! iterations, plenty for a stable count.
//!
//! The group `ratio` measures the same operations as ratios generated / hand, the two
//! sides interleaved in blocks within every sample (`benches/floor/interleaved.rs`): the
//! estimate that a shared machine's drifting speed does not move. Its "time" is the ratio
//! (criterion prints `1.234×`); `tools/floor_ratios.py` tabulates it beside the medians.
//!
//! ```text
//! cargo bench --bench floor -- '^ratio/'          # the interleaved ratios alone
//! ```

#[path = "../tests/common/mechanisms.rs"]
#[allow(dead_code)]
mod mechanisms;

#[path = "floor/machines.rs"]
#[allow(dead_code)]
mod machines;

#[path = "floor/hand.rs"]
mod hand;

#[path = "floor/interleaved.rs"]
mod interleaved;

#[path = "floor/runtime.rs"]
mod runtime;

use criterion::measurement::Measurement;
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use hand::{
    BlockScotchYokeHand, CrankRodWheelHand, FourBarHand, GearedSliderCrankHand,
    InvertedSliderCrankHand, PlanetaryHand, QuickReturnHand, RackPinionHand, RollerCamHand,
    ScotchYokeHand, SliderCrankHand, SlottedCrankRamHand,
};
use interleaved::Interleaved;
use machines::*;
use mechanisms::*;

const Q: f64 = 0.7;
const QD: f64 = 12.0;
const QDD: f64 = -3.0;

/// The four-bar, its hand-written twin and its loads.
struct FourBarCase {
    m: FourBar,
    h: FourBarHand,
    loads: FourBarLoads,
}

impl FourBarCase {
    fn new() -> Self {
        let m = FourBar::new();
        let h = FourBarHand::new(m.params());
        let mut loads = FourBarLoads::default();
        assert!(loads.set_by_name("tool", &[80.0, -60.0]));
        assert!(loads.set_by_name("resist", &[2.0]));
        FourBarCase { m, h, loads }
    }
}

/// The slider-crank, its hand-written twin, its loads and the driver torque.
struct SliderCrankCase {
    m: SliderCrank,
    h: SliderCrankHand,
    loads: SliderCrankLoads,
    driver: f64,
}

impl SliderCrankCase {
    fn new() -> Self {
        let m = SliderCrank::new();
        let h = SliderCrankHand::new(m.params());
        let mut loads = SliderCrankLoads::default();
        assert!(loads.set_by_name("gas", &[-1500.0, 0.0]));
        assert!(loads.set_by_name("shaft", &[-4.0]));
        SliderCrankCase {
            m,
            h,
            loads,
            driver: 5.0,
        }
    }
}

/// One of the machines that bench all six operations: the generated solver, its
/// hand-written twin, its loads and the driver torque of `acceleration`.
struct Case<M, H, L> {
    m: M,
    h: H,
    loads: L,
    driver: f64,
}

/// The constructor `Case::$ctor` of one machine of the six operations: the generated
/// `$machine`, its hand-written twin `$hand` on the same parameters, the loads `$loads` with
/// a force and a torque set by name, and a 5 N·m driver.
macro_rules! case {
    (
        $(#[$attr:meta])*
        $ctor:ident: $machine:ident, $hand:ident, $loads:ident,
        $force:literal = $force_value:expr, $torque:literal = $torque_value:expr $(,)?
    ) => {
        impl Case<$machine, $hand, $loads> {
            $(#[$attr])*
            fn $ctor() -> Self {
                let m = $machine::new();
                let h = $hand::new(m.params());
                let mut loads = $loads::default();
                assert!(loads.set_by_name($force, &$force_value));
                assert!(loads.set_by_name($torque, &$torque_value));
                Case {
                    m,
                    h,
                    loads,
                    driver: 5.0,
                }
            }
        }
    };
}

case!(
    /// A cutting force (−250, 30) N on the ram's end C of the lever, a −1.5 N·m friction
    /// torque on the crank.
    quick_return: QuickReturn, QuickReturnHand, QuickReturnLoads,
    "cut" = [-250.0, 30.0], "friction" = [-1.5],
);

case!(
    /// A resisting force (−120, 15) N on the yoke at Y, a −1.5 N·m drag on the crank.
    scotch_yoke: ScotchYoke, ScotchYokeHand, ScotchYokeLoads,
    "resist" = [-120.0, 15.0], "drag" = [-1.5],
);

case!(
    /// A force (−300, 40) N on the rod at P, a 2.5 N·m resisting torque on the block.
    inverted_slider_crank: InvertedSliderCrank, InvertedSliderCrankHand, InvertedSliderCrankLoads,
    "push" = [-300.0, 40.0], "resist" = [2.5],
);

case!(
    /// A −900 N gas force on the piston at B (along the guide, mostly), a −4 N·m shaft
    /// torque on the gear.
    geared_slider_crank: GearedSliderCrank, GearedSliderCrankHand, GearedSliderCrankLoads,
    "gas" = [-900.0, -90.0], "shaft" = [-4.0],
);

case!(
    /// A (20, −250) N force on the follower at its top T (a valve spring and the gas
    /// load, mostly along the axis), a −1.5 N·m drag on the cam.
    roller_cam: RollerCam, RollerCamHand, RollerCamLoads,
    "push" = [20.0, -250.0], "drag" = [-1.5],
);

case!(
    /// A (−150, 20) N pull on the wheel at its centre C, a −0.8 N·m brake on the wheel.
    crank_rod_wheel: CrankRodWheel, CrankRodWheelHand, CrankRodWheelLoads,
    "pull" = [-150.0, 20.0], "brake" = [-0.8],
);

case!(
    /// A (−150, 20) N resisting force on the yoke at its end T, a −0.6 N·m friction couple
    /// on the block.
    block_scotch_yoke: BlockScotchYoke, BlockScotchYokeHand, BlockScotchYokeLoads,
    "resist" = [-150.0, 20.0], "friction" = [-0.6],
);

case!(
    /// A (−400, 60) N force on the ram at its tool point P, a 1.8 N·m torque on the block.
    slotted_crank_ram: SlottedCrankRam, SlottedCrankRamHand, SlottedCrankRamLoads,
    "push" = [-400.0, 60.0], "resist" = [1.8],
);

case!(
    /// A (40, −60) N pull on the arm at its lever end T, a −2 N·m brake on the arm.
    planetary: Planetary, PlanetaryHand, PlanetaryLoads,
    "pull" = [40.0, -60.0], "brake" = [-2.0],
);

case!(
    /// A (−250, 30) N push on the rack at L, a −2 N·m torque on the pinion.
    rack_pinion: RackPinion, RackPinionHand, RackPinionLoads,
    "push" = [-250.0, 30.0], "resist" = [-2.0],
);

// One function per operation and side; every input through `black_box`.

/// The functions of the four operations on a pose and its motion, both sides, for the case
/// type `C` (the one of the scope): `pose_gen`, `pose_hand`, `kin_gen`, `kin_hand`,
/// `kinetostatics_gen`, `kinetostatics_hand`, `driver_gen`, `driver_hand`.
macro_rules! motion_functions {
    (
        pose: $pose:ty, $hand_pose:ty,
        motion: $motion:ty, $hand_motion:ty,
        forces: $forces:ty, $hand_forces:ty $(,)?
    ) => {
        pub(crate) fn pose_gen(c: &C) -> $pose {
            black_box(&c.m).pose(black_box(Q)).unwrap()
        }
        pub(crate) fn pose_hand(c: &C) -> $hand_pose {
            black_box(&c.h).pose(black_box(Q)).unwrap()
        }
        pub(crate) fn kin_gen(c: &C) -> $motion {
            black_box(&c.m)
                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                .unwrap()
        }
        pub(crate) fn kin_hand(c: &C) -> $hand_motion {
            black_box(&c.h)
                .kinematics(black_box(Q), black_box(QD), black_box(QDD))
                .unwrap()
        }
        pub(crate) fn kinetostatics_gen(c: &C) -> $forces {
            let mo = kin_gen(c);
            black_box(&c.m)
                .kinetostatics(&mo, black_box(&c.loads))
                .unwrap()
        }
        pub(crate) fn kinetostatics_hand(c: &C) -> $hand_forces {
            let mo = kin_hand(c);
            black_box(&c.h).kinetostatics(&mo, black_box(&c.loads))
        }
        pub(crate) fn driver_gen(c: &C) -> f64 {
            let mo = kin_gen(c);
            black_box(&c.m)
                .driver_action(&mo, black_box(&c.loads))
                .unwrap()
        }
        pub(crate) fn driver_hand(c: &C) -> f64 {
            let mo = kin_hand(c);
            black_box(&c.h).driver_action(&mo, black_box(&c.loads))
        }
    };
}

/// The functions of the two operations of the direct dynamics, both sides, for the case
/// type `C` (the one of the scope, with a `driver`): `reduced_gen`, `reduced_hand`,
/// `acceleration_gen`, `acceleration_hand`.
macro_rules! dynamics_functions {
    () => {
        pub(crate) fn reduced_gen(c: &C) -> mech::Reduced {
            black_box(&c.m).reduced(black_box(Q)).unwrap()
        }
        pub(crate) fn reduced_hand(c: &C) -> hand::HandReduced {
            black_box(&c.h).reduced(black_box(Q)).unwrap()
        }
        pub(crate) fn acceleration_gen(c: &C) -> f64 {
            black_box(&c.m)
                .acceleration(
                    black_box(Q),
                    black_box(QD),
                    black_box(c.driver),
                    black_box(&c.loads),
                )
                .unwrap()
        }
        pub(crate) fn acceleration_hand(c: &C) -> f64 {
            black_box(&c.h)
                .acceleration(
                    black_box(Q),
                    black_box(QD),
                    black_box(c.driver),
                    black_box(&c.loads),
                )
                .unwrap()
        }
    };
}

/// The four-bar's [`motion_functions`].
mod four_bar_ops {
    use super::*;

    type C = FourBarCase;
    motion_functions!(
        pose: FourBarPose, hand::FourBarHandPose,
        motion: FourBarMotion, hand::FourBarHandMotion,
        forces: FourBarForces, hand::FourBarHandForces,
    );
}
use four_bar_ops::{
    driver_gen, driver_hand, kin_gen, kin_hand, kinetostatics_gen, kinetostatics_hand, pose_gen,
    pose_hand,
};

/// The slider-crank's [`dynamics_functions`].
mod slider_crank_ops {
    use super::*;

    type C = SliderCrankCase;
    dynamics_functions!();
}
use slider_crank_ops::{acceleration_gen, acceleration_hand, reduced_gen, reduced_hand};

/// `$run($c, "$name/<op>", $k, <op>_gen, <op>_hand)` for each of the four operations on a
/// pose and its motion, in order: `$run` is `pair` or `ratio`.
macro_rules! motion_operations {
    ($run:ident, $c:ident, $name:literal, $k:ident) => {
        $run($c, concat!($name, "/pose"), $k, pose_gen, pose_hand);
        $run($c, concat!($name, "/kinematics"), $k, kin_gen, kin_hand);
        $run(
            $c,
            concat!($name, "/kinematics+kinetostatics"),
            $k,
            kinetostatics_gen,
            kinetostatics_hand,
        );
        $run(
            $c,
            concat!($name, "/kinematics+driver_action"),
            $k,
            driver_gen,
            driver_hand,
        );
    };
}

/// [`motion_operations`] for the two operations of the direct dynamics.
macro_rules! dynamics_operations {
    ($run:ident, $c:ident, $name:literal, $k:ident) => {
        $run(
            $c,
            concat!($name, "/reduced"),
            $k,
            reduced_gen,
            reduced_hand,
        );
        $run(
            $c,
            concat!($name, "/acceleration"),
            $k,
            acceleration_gen,
            acceleration_hand,
        );
    };
}

/// The six operations of one machine of [`Case`], both sides ([`motion_functions`] and
/// [`dynamics_functions`]: every input through `black_box`), in the module `$module`, with
/// `pairs` (the groups `$name/<op>`) and `ratios` (the entries `ratio/$name/<op>`).
macro_rules! six_operations {
    (
        $module:ident, $name:literal, $case:ty,
        pose: $pose:ty, $hand_pose:ty,
        motion: $motion:ty, $hand_motion:ty,
        forces: $forces:ty, $hand_forces:ty $(,)?
    ) => {
        mod $module {
            use super::*;

            type C = $case;
            motion_functions!(
                pose: $pose, $hand_pose,
                motion: $motion, $hand_motion,
                forces: $forces, $hand_forces,
            );
            dynamics_functions!();

            /// The groups `$name/<op>`, generated then hand.
            pub fn pairs(c: &mut Criterion, k: &C) {
                motion_operations!(pair, c, $name, k);
                dynamics_operations!(pair, c, $name, k);
            }

            /// The entries `ratio/$name/<op>`, interleaved.
            pub fn ratios(c: &mut Criterion<Interleaved>, k: &C) {
                motion_operations!(ratio, c, $name, k);
                dynamics_operations!(ratio, c, $name, k);
            }
        }
    };
}

six_operations!(
    quick_return_ops,
    "quick_return",
    Case<QuickReturn, QuickReturnHand, QuickReturnLoads>,
    pose: QuickReturnPose, hand::QuickReturnHandPose,
    motion: QuickReturnMotion, hand::QuickReturnHandMotion,
    forces: QuickReturnForces, hand::QuickReturnHandForces,
);
six_operations!(
    scotch_yoke_ops,
    "scotch_yoke",
    Case<ScotchYoke, ScotchYokeHand, ScotchYokeLoads>,
    pose: ScotchYokePose, hand::ScotchYokeHandPose,
    motion: ScotchYokeMotion, hand::ScotchYokeHandMotion,
    forces: ScotchYokeForces, hand::ScotchYokeHandForces,
);
six_operations!(
    inverted_slider_crank_ops,
    "inverted_slider_crank",
    Case<InvertedSliderCrank, InvertedSliderCrankHand, InvertedSliderCrankLoads>,
    pose: InvertedSliderCrankPose, hand::InvertedSliderCrankHandPose,
    motion: InvertedSliderCrankMotion, hand::InvertedSliderCrankHandMotion,
    forces: InvertedSliderCrankForces, hand::InvertedSliderCrankHandForces,
);
six_operations!(
    geared_slider_crank_ops,
    "geared_slider_crank",
    Case<GearedSliderCrank, GearedSliderCrankHand, GearedSliderCrankLoads>,
    pose: GearedSliderCrankPose, hand::GearedSliderCrankHandPose,
    motion: GearedSliderCrankMotion, hand::GearedSliderCrankHandMotion,
    forces: GearedSliderCrankForces, hand::GearedSliderCrankHandForces,
);
six_operations!(
    roller_cam_ops,
    "roller_cam",
    Case<RollerCam, RollerCamHand, RollerCamLoads>,
    pose: RollerCamPose, hand::RollerCamHandPose,
    motion: RollerCamMotion, hand::RollerCamHandMotion,
    forces: RollerCamForces, hand::RollerCamHandForces,
);
six_operations!(
    crank_rod_wheel_ops,
    "crank_rod_wheel",
    Case<CrankRodWheel, CrankRodWheelHand, CrankRodWheelLoads>,
    pose: CrankRodWheelPose, hand::CrankRodWheelHandPose,
    motion: CrankRodWheelMotion, hand::CrankRodWheelHandMotion,
    forces: CrankRodWheelForces, hand::CrankRodWheelHandForces,
);
six_operations!(
    block_scotch_yoke_ops,
    "block_scotch_yoke",
    Case<BlockScotchYoke, BlockScotchYokeHand, BlockScotchYokeLoads>,
    pose: BlockScotchYokePose, hand::BlockScotchYokeHandPose,
    motion: BlockScotchYokeMotion, hand::BlockScotchYokeHandMotion,
    forces: BlockScotchYokeForces, hand::BlockScotchYokeHandForces,
);
six_operations!(
    slotted_crank_ram_ops,
    "slotted_crank_ram",
    Case<SlottedCrankRam, SlottedCrankRamHand, SlottedCrankRamLoads>,
    pose: SlottedCrankRamPose, hand::SlottedCrankRamHandPose,
    motion: SlottedCrankRamMotion, hand::SlottedCrankRamHandMotion,
    forces: SlottedCrankRamForces, hand::SlottedCrankRamHandForces,
);
six_operations!(
    planetary_ops,
    "planetary",
    Case<Planetary, PlanetaryHand, PlanetaryLoads>,
    pose: PlanetaryPose, hand::PlanetaryHandPose,
    motion: PlanetaryMotion, hand::PlanetaryHandMotion,
    forces: PlanetaryForces, hand::PlanetaryHandForces,
);
six_operations!(
    rack_pinion_ops,
    "rack_pinion",
    Case<RackPinion, RackPinionHand, RackPinionLoads>,
    pose: RackPinionPose, hand::RackPinionHandPose,
    motion: RackPinionMotion, hand::RackPinionHandMotion,
    forces: RackPinionForces, hand::RackPinionHandForces,
);

/// The group `name` with the functions `generated` and `hand`, timed one after the other.
/// (Each function is passed as its own zero-sized type, so the calls are direct and inline
/// as the closures of a hand-written bench would.)
fn pair<C, A, B>(
    c: &mut Criterion,
    name: &str,
    case: &C,
    generated: impl Fn(&C) -> A,
    hand: impl Fn(&C) -> B,
) {
    let mut g = c.benchmark_group(name);
    g.bench_function("generated", |b| b.iter(|| generated(case)));
    g.bench_function("hand", |b| b.iter(|| hand(case)));
    g.finish();
}

/// `ratio/<name>`: generated / hand, interleaved (`interleaved::ratio`).
fn ratio<C, A, B, M: Measurement<Value = f64>>(
    c: &mut Criterion<M>,
    name: &str,
    case: &C,
    generated: impl Fn(&C) -> A,
    hand: impl Fn(&C) -> B,
) {
    c.benchmark_group("ratio").bench_function(name, |b| {
        b.iter_custom(|n| interleaved::ratio(n, || generated(case), || hand(case)))
    });
}

fn four_bar(c: &mut Criterion) {
    let k = &FourBarCase::new();
    motion_operations!(pair, c, "four_bar", k);
}

fn slider_crank(c: &mut Criterion) {
    let k = &SliderCrankCase::new();
    dynamics_operations!(pair, c, "slider_crank", k);
}

fn quick_return(c: &mut Criterion) {
    quick_return_ops::pairs(c, &Case::quick_return());
}

fn scotch_yoke(c: &mut Criterion) {
    scotch_yoke_ops::pairs(c, &Case::scotch_yoke());
}

fn inverted_slider_crank(c: &mut Criterion) {
    inverted_slider_crank_ops::pairs(c, &Case::inverted_slider_crank());
}

fn geared_slider_crank(c: &mut Criterion) {
    geared_slider_crank_ops::pairs(c, &Case::geared_slider_crank());
}

fn roller_cam(c: &mut Criterion) {
    roller_cam_ops::pairs(c, &Case::roller_cam());
}

fn crank_rod_wheel(c: &mut Criterion) {
    crank_rod_wheel_ops::pairs(c, &Case::crank_rod_wheel());
}

fn block_scotch_yoke(c: &mut Criterion) {
    block_scotch_yoke_ops::pairs(c, &Case::block_scotch_yoke());
}

fn slotted_crank_ram(c: &mut Criterion) {
    slotted_crank_ram_ops::pairs(c, &Case::slotted_crank_ram());
}

fn planetary(c: &mut Criterion) {
    planetary_ops::pairs(c, &Case::planetary());
}

fn rack_pinion(c: &mut Criterion) {
    rack_pinion_ops::pairs(c, &Case::rack_pinion());
}

fn ratios(c: &mut Criterion<Interleaved>) {
    let k = &FourBarCase::new();
    motion_operations!(ratio, c, "four_bar", k);
    let k = &SliderCrankCase::new();
    dynamics_operations!(ratio, c, "slider_crank", k);
    quick_return_ops::ratios(c, &Case::quick_return());
    scotch_yoke_ops::ratios(c, &Case::scotch_yoke());
    inverted_slider_crank_ops::ratios(c, &Case::inverted_slider_crank());
    geared_slider_crank_ops::ratios(c, &Case::geared_slider_crank());
    roller_cam_ops::ratios(c, &Case::roller_cam());
    crank_rod_wheel_ops::ratios(c, &Case::crank_rod_wheel());
    block_scotch_yoke_ops::ratios(c, &Case::block_scotch_yoke());
    slotted_crank_ram_ops::ratios(c, &Case::slotted_crank_ram());
    planetary_ops::ratios(c, &Case::planetary());
    rack_pinion_ops::ratios(c, &Case::rack_pinion());
}

// ---------------------------------------------------------------------------------------
// Many configurations per call (`docs/batch.md`): the generated `*_many` over BATCH
// configurations against the hand-written scalar code called BATCH times into the same
// kind of buffer; the time per iteration is that of BATCH configurations, the interleaved
// ratio the per-configuration ratio.

/// Configurations per batched call: below `mech::batch::PARALLEL_FROM`, on one thread.
const BATCH: usize = 1024;

/// The four-bar and the slider-crank with BATCH configurations spread over a turn and an
/// output buffer per side.
struct BatchCase {
    fb: FourBarCase,
    sc: SliderCrankCase,
    q: Vec<f64>,
    qd: Vec<f64>,
    driver: Vec<f64>,
    out: std::cell::RefCell<Vec<f64>>,
    out2: std::cell::RefCell<Vec<f64>>,
}

impl BatchCase {
    fn new() -> Self {
        // The golden-ratio sequence over a turn: every angle different, no pattern.
        let q: Vec<f64> = (0..BATCH)
            .map(|i| std::f64::consts::TAU * ((i as f64 * 0.618_033_988_749_895) % 1.0) - 3.0)
            .collect();
        BatchCase {
            fb: FourBarCase::new(),
            sc: SliderCrankCase::new(),
            qd: q.iter().map(|x| QD + x).collect(),
            driver: q.iter().map(|x| 5.0 + x).collect(),
            q,
            out: std::cell::RefCell::new(vec![0.0; 10 * BATCH]),
            out2: std::cell::RefCell::new(vec![0.0; BATCH]),
        }
    }
}

fn batch_points_gen(c: &BatchCase) -> usize {
    let mut out = c.out.borrow_mut();
    black_box(&c.fb.m)
        .points_many(black_box(&c.q), &mut out)
        .len()
}
fn batch_points_hand(c: &BatchCase) -> usize {
    let mut out = c.out.borrow_mut();
    let h = black_box(&c.fb.h);
    let mut failed = 0;
    for (&q, row) in black_box(&c.q).iter().zip(out.chunks_exact_mut(10)) {
        match h.points(q) {
            Some(p) => {
                for (xy, v) in row.chunks_exact_mut(2).zip(p) {
                    xy[0] = v.x;
                    xy[1] = v.y;
                }
            }
            None => failed += 1,
        }
    }
    failed
}
fn batch_reduced_gen(c: &BatchCase) -> usize {
    let (mut a, mut b) = (c.out.borrow_mut(), c.out2.borrow_mut());
    black_box(&c.fb.m)
        .reduced_many(black_box(&c.q), &mut a[..BATCH], &mut b)
        .len()
}
fn batch_reduced_hand(c: &BatchCase) -> usize {
    let (mut a, mut b) = (c.out.borrow_mut(), c.out2.borrow_mut());
    let h = black_box(&c.fb.h);
    let mut failed = 0;
    for (i, &q) in black_box(&c.q).iter().enumerate() {
        match h.reduced(q) {
            Some(r) => (a[i], b[i]) = (r.inertia, r.inertia_derivative),
            None => failed += 1,
        }
    }
    failed
}
fn batch_acceleration_gen(c: &BatchCase) -> usize {
    let mut out = c.out2.borrow_mut();
    black_box(&c.fb.m)
        .acceleration_many(black_box(&c.q), &c.qd, &c.driver, &c.fb.loads, &mut out)
        .len()
}
fn batch_acceleration_hand(c: &BatchCase) -> usize {
    let mut out = c.out2.borrow_mut();
    let h = black_box(&c.fb.h);
    let mut failed = 0;
    for i in 0..BATCH {
        match h.acceleration(black_box(c.q[i]), c.qd[i], c.driver[i], &c.fb.loads) {
            Some(a) => out[i] = a,
            None => failed += 1,
        }
    }
    failed
}
fn batch_sc_acceleration_gen(c: &BatchCase) -> usize {
    let mut out = c.out2.borrow_mut();
    black_box(&c.sc.m)
        .acceleration_many(black_box(&c.q), &c.qd, &c.driver, &c.sc.loads, &mut out)
        .len()
}
fn batch_sc_acceleration_hand(c: &BatchCase) -> usize {
    let mut out = c.out2.borrow_mut();
    let h = black_box(&c.sc.h);
    let mut failed = 0;
    for i in 0..BATCH {
        match h.acceleration(black_box(c.q[i]), c.qd[i], c.driver[i], &c.sc.loads) {
            Some(a) => out[i] = a,
            None => failed += 1,
        }
    }
    failed
}

fn batch(c: &mut Criterion) {
    let k = BatchCase::new();
    pair(
        c,
        "batch/four_bar/points",
        &k,
        batch_points_gen,
        batch_points_hand,
    );
    pair(
        c,
        "batch/four_bar/reduced",
        &k,
        batch_reduced_gen,
        batch_reduced_hand,
    );
    pair(
        c,
        "batch/four_bar/acceleration",
        &k,
        batch_acceleration_gen,
        batch_acceleration_hand,
    );
    pair(
        c,
        "batch/slider_crank/acceleration",
        &k,
        batch_sc_acceleration_gen,
        batch_sc_acceleration_hand,
    );
}

fn batch_ratios(c: &mut Criterion<Interleaved>) {
    let k = BatchCase::new();
    ratio(
        c,
        "batch/four_bar/points",
        &k,
        batch_points_gen,
        batch_points_hand,
    );
    ratio(
        c,
        "batch/four_bar/reduced",
        &k,
        batch_reduced_gen,
        batch_reduced_hand,
    );
    ratio(
        c,
        "batch/four_bar/acceleration",
        &k,
        batch_acceleration_gen,
        batch_acceleration_hand,
    );
    ratio(
        c,
        "batch/slider_crank/acceleration",
        &k,
        batch_sc_acceleration_gen,
        batch_sc_acceleration_hand,
    );
}

criterion_group!(
    benches,
    four_bar,
    slider_crank,
    quick_return,
    scotch_yoke,
    inverted_slider_crank,
    geared_slider_crank,
    roller_cam,
    crank_rod_wheel,
    block_scotch_yoke,
    slotted_crank_ram,
    planetary,
    rack_pinion,
    batch,
    runtime::pairs
);
criterion_group! {
    name = interleaved_ratios;
    config = Criterion::default().with_measurement(Interleaved);
    targets = ratios, batch_ratios, runtime::ratios
}
criterion_main!(benches, interleaved_ratios);
