//! Design: the machine's numbers chosen rather than checked. [`sizing`]: the dimensions
//! written `free(LO..HI)` chosen so that every member meets a factor of safety, the
//! dynamics re-run with each change (the design cycle of `docs/theory.md`); [`synthesis`]:
//! four-bars from the motion they must make; [`optimize`]: any mechanism's named numbers
//! varied against an objective of its dynamics, written back by [`rewrite`]; [`balance`]:
//! the shaking force and moment over a cycle, and the counterweights that reduce them;
//! `nelder_mead`: the local search the last two share; [`engine`]: engines of several
//! cylinders, their files and classical balance tables.

pub mod balance;
pub mod engine;
pub(crate) mod nelder_mead;
pub mod optimize;
pub mod rewrite;
pub mod sizing;
pub mod synthesis;
