//! Cams (`docs/theory.md` §13, `docs/conventions.md#cams`), in three parts, each building
//! on the one before:
//!
//! - [`law`]: the follower's motion law — the lift s(θ) (or a rocker's angle ψ(θ)) as a
//!   function of the cam angle and its derivatives, segment by segment ([`Law`],
//!   [`Segment`], [`MotionLaw`]) or a periodic spline through a table ([`Spline`]); its
//!   jumps ([`Jump`]) and the declaration's checks ([`law_of`]). Plain mathematics.
//! - [`profile`]: the cam's profile for a follower's face ([`Face`]) — translating or a
//!   [`Rocker`] — the pitch and contact curves ([`Profile`], [`ProfilePoint`],
//!   [`Contact`]), the pressure angle, the radius of curvature and undercut
//!   ([`ProfileCheck`]), tables, CSV and SVG.
//! - [`pair`]: the cam-follower pair kernel that the generated solvers and the run-time
//!   `Mechanism` call ([`CamGeom`], [`CamGroup`], [`solve_cam`], [`cam_reactions`]).
//!
//! Every item is re-exported here: `crate::elements::cam::X` (`mech::cam::X`) is the path.

pub mod law;
pub mod pair;
pub mod profile;

pub use law::{law_of, lift_text, Jump, Law, MotionLaw, Segment, SegmentLaw, Spline, ANGLE_TOL};
pub use pair::{cam_reactions, solve_cam, CamGeom, CamGroup, CamLaw};
pub use profile::{Contact, Face, Profile, ProfileCheck, ProfilePoint, Rocker};
