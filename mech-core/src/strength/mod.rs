//! Strength of the members of a machine from the reactions over its cycle
//! (`docs/theory.md` §5: the inverse dynamic problem gives the reactions; "if the
//! reactions predict a failure of any element, the materials or the sections are changed").
//!
//! The analysis ([`Mechanism::strength`](crate::Mechanism::strength)) goes through the
//! cycle: at each instant the kinetostatics gives every action on every link, a
//! [`diagram`] turns a link's actions into its N, V and M along it, and the [`track`]s
//! keep each member's worst; the [`report`] is the checks of every member.
//!
//! The formulas, by aspect: [`beam`] (shear and bending moment along a link under its end forces and
//! its distributed inertia load), [`section`] (a link's cross-section from its shape: area, second moments,
//! section modulus, radius of gyration), [`pin`] (a pin's shear and bearing stresses),
//! [`buckling`] (Euler and Johnson), [`fatigue`] (the endurance limit corrected by Marin's
//! factors, Goodman's and Soderberg's lines).

pub mod beam;
pub mod buckling;
pub mod diagram;
pub mod fatigue;
pub mod pin;
pub mod report;
pub mod section;
pub mod track;

pub use report::{Check, Criterion, Member, Strength};
