// Mistake (structure): a mechanism with no moving link.
use mech::prelude::*;

mechanism! {
    /// Only the frame.
    pub struct Frame {
        ground { O: (0.0, 0.0), P: (1.0, 0.0) },
    }
}

fn main() {}
