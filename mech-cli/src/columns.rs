//! `--level`: how much of each configuration the tabular commands compute, as the parts
//! of [`mech_core::runtime::columns`] (which names the columns and computes a row).

pub use mech_core::runtime::columns::{Columns, Part};

/// How much of the solution a row holds; nothing beyond it is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, clap::ValueEnum)]
pub enum Level {
    /// Positions only.
    Pose,
    /// Positions, velocities, accelerations.
    Kinematics,
    /// Kinematics, reactions, motor actions (both routes), I* and M*.
    Forces,
}

impl Level {
    /// The parts of this level.
    pub fn parts(self) -> &'static [Part] {
        match self {
            Level::Pose => Part::POSE,
            Level::Kinematics => Part::KINEMATICS,
            Level::Forces => Part::ALL,
        }
    }

    /// The columns of mechanism `m` at this level.
    pub fn columns(self, m: &mech_core::Mechanism) -> Columns {
        Columns::new(m, self.parts())
    }
}
