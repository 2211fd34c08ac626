//! # mech — dynamics of planar machines
//!
//! Describe a linkage once with [`mechanism!`]; at compile time the macro checks its
//! structure (Grübler's count, over-constrained sub-chains, the rank of the constraint
//! Jacobian at the drawing, input determinacy) and generates a struct with solvers
//! specialised to that topology and free of heap allocation: `pose`, `kinematics`,
//! `kinetostatics` (every reaction, d'Alembert), `driver_action` (virtual power), and for
//! one DOF `reduced` (Zhukovski's I*, dI*/dq), `reduced_moment` (M*) and `acceleration`.
//!
//! ```
//! use mech::prelude::*;
//!
//! mechanism! {
//!     /// A crank-rocker four-bar.
//!     pub struct FourBar {
//!         ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
//!         link crank { points { O2, A: (0.0, 0.1) }, mass: 0.5, inertia: 1e-3, cg: (0.0, 0.05) },
//!         link coupler { points { A, B: (0.25, 0.25) }, mass: 1.0, inertia: 5e-3, cg: (0.12, 0.17) },
//!         link rocker { points { O4, B }, mass: 0.8, inertia: 3e-3, cg: (0.28, 0.12) },
//!         joints {
//!             O2: revolute(ground, crank),
//!             A: revolute(crank, coupler),
//!             B: revolute(coupler, rocker),
//!             O4: revolute(ground, rocker),
//!         },
//!         input: O2,
//!     }
//! }
//!
//! let m = FourBar::new();
//! assert_eq!(FourBar::DOF, 1);
//! let motion = m.kinematics(1.0, 10.0, 0.0).unwrap();
//! let forces = m.kinetostatics(&motion, &FourBarLoads::default()).unwrap();
//! let virtual_power = m.driver_action(&motion, &FourBarLoads::default()).unwrap();
//! assert!((forces.driver - virtual_power).abs() < 1e-9 * forces.driver.abs().max(1.0));
//! ```
#![deny(missing_docs)]

pub use mech_macros::mechanism;

// The run-time mechanism (`docs/guide.md`): the same text loaded and solved at run time.
pub use mech_core::runtime::{Forces, JointReaction, LoadValue, Loads, Motion, Pose};
pub use mech_core::{MechError, Mechanism, UnitQuaternion, Vector2, Vector3};

// What a solver returns and takes, by concept.
pub use mech_core::kernel::energy::Shaking;
pub use mech_core::kernel::kinetostatics::{
    CamReaction, MeshReaction, PrismaticReaction, RevoluteReaction, RollingReaction, SlotReaction,
};
pub use mech_core::kernel::link_state::{LinkMotion, LinkPose, PointMotion, PointPose};
pub use mech_core::solvers::instance::{
    DamperParams, LinkParams, RotaryDamperParams, ShapeParams, SpringParams, TorsionSpringParams,
};
pub use mech_core::solvers::traits::{DeterminateReactions, Machine, OneDof};
pub use mech_core::solvers::zhukovski::Reduced;

/// Many configurations per call (`docs/batch.md`): what the `*_many` methods return, and
/// the size from which they run on rayon's pool.
pub mod batch {
    pub use mech_core::solvers::batch::{BatchErrors, Table, CHUNK, PARALLEL_FROM};
}
pub use batch::BatchErrors;

// The algorithms written once over the traits, and the machine elements.
pub use mech_core::checks::grubler;
pub use mech_core::dynamics::{self, equivalent_mass, flywheel, motor, ode, regime};
pub use mech_core::elements::cam;
pub use mech_core::model::{self, units};
pub use mech_core::runtime::columns;
pub use mech_core::solvers::friction;
pub use mech_core::{design, strength};

/// Spatial mechanisms (SPEC 3i, `docs/spatial.md`): `mechanism!` with `space` first, or
/// [`spatial::SpatialMechanism::from_dsl`] at run time.
pub mod spatial {
    pub use mech_core::spatial::dsl::parse;
    pub use mech_core::spatial::kutzbach::Kutzbach;
    pub use mech_core::spatial::results::{LinkPose, PointMotion, PointPose};
    pub use mech_core::spatial::{
        BodyMotion, Finding, Joint, JointKind, LinkMotion, Load, LoadKind, Reaction, Site,
        SpatialForces, SpatialLoads, SpatialMechanism, SpatialModel, SpatialMotion,
    };
}

/// The paths the generated code uses (`mech_core::__private`). Not part of the public API.
#[doc(hidden)]
pub mod __private {
    pub use mech_core::__private::*;
}

/// Everything a user of a generated struct needs.
pub mod prelude {
    pub use crate::{
        mechanism, BatchErrors, CamReaction, DamperParams, DeterminateReactions, LinkMotion,
        LinkPose, Machine, MechError, Mechanism, MeshReaction, OneDof, PointMotion, PointPose,
        PrismaticReaction, Reduced, RevoluteReaction, RollingReaction, RotaryDamperParams, Shaking,
        SlotReaction, SpringParams, TorsionSpringParams, UnitQuaternion, Vector2, Vector3,
    };
}

/// The README's Rust example, compiled and run as a doctest (`cargo test --doc`).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
