//! Design: the machine's numbers chosen rather than checked. [`sizing`]: the dimensions
//! written `free(LO..HI)` chosen so that every member meets a factor of safety, the
//! dynamics re-run with each change (the design cycle of `docs/theory.md`).

pub mod sizing;
