//! The traits every generated struct implements, so the generic algorithms (dynamics,
//! flywheel sizing, cycle sweeps, the stress suite) are written once, in mech-core.

use crate::kernel::energy::Shaking;
use crate::solvers::batch::{serial, BatchErrors, Block};
use crate::solvers::zhukovski::Reduced;
use crate::MechError;

/// Any mechanism, generated or loaded at run time ([`crate::runtime::mechanism::Mechanism`]), any
/// number of inputs G.
pub trait Machine {
    /// G, the number of inputs (a generated struct's `DOF`).
    fn dof(&self) -> usize;
    /// N, links including the ground (a generated struct's `LINKS`).
    fn links(&self) -> usize;
    /// The loads struct (`<Name>Loads`).
    type Loads: Clone + Default;
    /// The kinematics result (`<Name>Motion`).
    type Motion: Clone;
    /// Kinematics at (q, q̇, q̈), slices of length G.
    fn motion(&self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<Self::Motion, MechError>;
    /// The motor actions by virtual power into `out` (length G): torque (N·m) or force (N).
    fn driver_actions(
        &self,
        m: &Self::Motion,
        loads: &Self::Loads,
        out: &mut [f64],
    ) -> Result<(), MechError>;
    /// Kinetic energy of each link (J) into `out` (length N, the ground's is 0).
    fn link_kinetic_energies(&self, m: &Self::Motion, out: &mut [f64]);
    /// Potential energy of gravity Σ −m g·r_G (J); 0 without gravity.
    fn potential_energy(&self, m: &Self::Motion) -> f64;
    /// The shaking force and moment on the frame at this motion (SPEC 3g, `docs/theory.md`
    /// §14): F = −Σ m a_G (N), M = −Σ (r_G × m a_G + I_G α) about the origin (N·m), summed
    /// over the links with inertia terms by [`Shaking::add`]; loads and gravity play no part.
    fn shaking(&self, m: &Self::Motion) -> Shaking;
}

/// A generated one-DOF mechanism: Zhukovski's reduction and the direct problem.
pub trait OneDof: Machine {
    /// I*(q) and dI*/dq.
    fn reduced(&self, q: f64) -> Result<Reduced, MechError>;
    /// I*(q_k) (kg·m²) and dI*/dq(q_k) (kg·m²/rad) for many configurations: configuration k
    /// into `inertia[k]` and `derivative[k]`; a failed one gets NaN and its index in the
    /// returned errors, slices of other lengths than `q` are a refusal. The default calls
    /// [`OneDof::reduced`] configuration by configuration on the calling thread; generated
    /// structs and the run-time mechanism answer with their batched form (`reduced_many`,
    /// lanes of four configurations, threads above [`crate::solvers::batch::PARALLEL_FROM`]).
    fn reduced_many(&self, q: &[f64], inertia: &mut [f64], derivative: &mut [f64]) -> BatchErrors {
        let n = q.len();
        let rows = match Block::new("inertia", inertia, 1, n)
            .and_then(|a| Ok((a, Block::new("derivative", derivative, 1, n)?)))
        {
            Ok(rows) => rows,
            Err(e) => return BatchErrors::refused(e),
        };
        serial(n, rows, |i, (a, b): &mut (Block<f64>, Block<f64>)| {
            let z = self.reduced(q[i])?;
            (*a.at(i), *b.at(i)) = (z.inertia, z.inertia_derivative);
            Ok(())
        })
    }
    /// M*(q) (N·m), loads and gravity included.
    fn reduced_moment(&self, q: f64, loads: &Self::Loads) -> Result<f64, MechError>;
    /// q̈ from I* q̈ + ½ dI*/dq q̇² = driver + M*.
    fn acceleration(
        &self,
        q: f64,
        qd: f64,
        driver: f64,
        loads: &Self::Loads,
    ) -> Result<f64, MechError>;
}

mod sealed {
    pub trait Sealed {}
}

/// No type implements this trait: it is the bound of the `kinetostatics` method of a
/// mechanism accepted with `#[allow(redundant)]`, so that calling it fails to compile
/// with an explanation instead of "no method found".
#[diagnostic::on_unimplemented(
    message = "this mechanism has redundant constraints (`#[allow(redundant)]`): its reactions are statically indeterminate, so it has no `kinetostatics`",
    label = "reactions cannot be computed for a redundant mechanism",
    note = "the motor actions are still determined: call `driver_action(&motion, &loads)` (virtual power, docs/theory.md §5.3)"
)]
pub trait DeterminateReactions: sealed::Sealed {
    /// Uninhabited: proves the method can never run.
    fn never(&self) -> std::convert::Infallible;
}
