//! Strength of the members of a machine from the reactions over its cycle
//! (`docs/theory.md` §5: the inverse dynamic problem gives the reactions; "if the
//! reactions predict a failure of any element, the materials or the sections are changed").
//!
//! By aspect: [`beam`] (shear and bending moment along a link under its end forces and
//! its distributed inertia load), [`section`] (a link's cross-section from its shape: area, second moments,
//! section modulus, radius of gyration), [`pin`] (a pin's shear and bearing stresses),
//! [`buckling`] (Euler and Johnson), [`fatigue`] (the endurance limit corrected by Marin's
//! factors, Goodman's and Soderberg's lines).

pub mod beam;
pub mod buckling;
pub mod fatigue;
pub mod pin;
pub mod section;
