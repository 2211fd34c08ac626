//! The compile-time checks, shared by the macro and the run-time loader: Grübler's count,
//! equations against unknowns, over-constrained sub-chains, the drawing's magnitudes, the
//! rank of the constraint Jacobian, input determinacy.

pub mod grubler;
pub mod load;
pub(crate) mod magnitudes;
pub mod pebble;
pub mod validate;
