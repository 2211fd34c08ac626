//! Run-time parameters of a generated mechanism against its declaration.
//!
//! The `mechanism!` macro decides from the declaration which inertia and gravity terms
//! each link has, and generates exactly those; the numbers in them (mass, inertia, cg,
//! gravity) are the run-time parameters (`<Name>Params`, `from_params`). So that the
//! numbers cannot say what the structure does not compute, `from_params` refuses a
//! non-zero mass or inertia on a link whose declaration has no term for it
//! ([`LinkTerms::check`]). Every route — d'Alembert (`kinetostatics`), virtual power
//! (`driver_action`), Zhukovski (`reduced`, `reduced_moment`, `acceleration`), the kinetic
//! and potential energies — uses the same [`LinkTerms`] of each link.

use crate::model::Link;
use crate::solvers::instance::LinkParams;
use crate::MechError;

/// Which inertia and gravity terms a link's declaration gives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinkTerms {
    /// Declared without `mass` and without (non-zero) `inertia`: massless by structure.
    /// No term is generated; its mass and inertia stay 0.
    Massless,
    /// Declared with `inertia` but without `mass` ([`Link::has_inertia`] without a mass):
    /// the inertia moment −I_G·α, the kinetic energy ½ I_G ω² and its share of I*, with
    /// the run-time inertia; its mass stays 0 (no −m·a_G, no gravity).
    InertiaOnly,
    /// Declared with `mass` (even `mass: 0.0`): every term — −m·a_G, −I_G·α, gravity m·g
    /// when gravity is declared, kinetic and potential energy, its share of I* — with the
    /// run-time mass, inertia and cg.
    Massive,
}

impl LinkTerms {
    /// The terms of a declared (compile-time) link.
    pub fn of(link: &Link) -> Self {
        if link.mass.is_some() {
            LinkTerms::Massive
        } else if link.has_inertia() {
            LinkTerms::InertiaOnly
        } else {
            LinkTerms::Massless
        }
    }

    /// d'Alembert's inertia wrench, the kinetic energy and the share of I* are generated.
    pub fn inertia(self) -> bool {
        self != LinkTerms::Massless
    }

    /// Gravity m·g (when declared) and the potential energy are generated.
    pub fn gravity(self) -> bool {
        self == LinkTerms::Massive
    }

    /// Refuse run-time numbers `p` of link `link` that its terms would ignore: a non-zero
    /// mass unless [`Massive`](LinkTerms::Massive), a non-zero inertia when
    /// [`Massless`](LinkTerms::Massless). `MechError::InvalidInput` names the link, the
    /// numbers given and the fix.
    pub fn check(self, link: &str, p: &LinkParams) -> Result<(), MechError> {
        let (mass_ok, inertia_ok) = match self {
            LinkTerms::Massive => (true, true),
            LinkTerms::InertiaOnly => (p.mass == 0.0, true),
            LinkTerms::Massless => (p.mass == 0.0, p.inertia == 0.0 && p.flywheel == 0.0),
        };
        if mass_ok && inertia_ok {
            return Ok(());
        }
        let declared = match self {
            LinkTerms::InertiaOnly => "is declared with `inertia` but without `mass`, so it has no mass terms (−m·a_G, gravity)",
            _ => "is declared without `mass`, so it is massless by structure: it has no inertia or gravity terms",
        };
        Err(MechError::InvalidInput(format!(
            "link `{link}` {declared}, but the parameters give it mass {} kg, inertia {} kg·m² and a flywheel of {} kg·m²; \
             declare `mass: 0.0` on link `{link}` in `mechanism!` to vary its mass at run time",
            p.mass, p.inertia, p.flywheel
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::link_state::V2;

    fn link(mass: Option<f64>, inertia: f64) -> Link {
        Link {
            name: "coupler".into(),
            points: vec![],
            mass,
            inertia,
            flywheel: 0.0,
            cg: [0.0, 0.0],
            body: None,
            axial: Default::default(),
        }
    }

    fn params(mass: f64, inertia: f64) -> LinkParams {
        LinkParams {
            mass,
            inertia,
            flywheel: 0.0,
            cg: V2::new(0.1, 0.2),
        }
    }

    #[test]
    fn terms_follow_the_declaration() {
        assert_eq!(LinkTerms::of(&link(Some(0.0), 0.0)), LinkTerms::Massive);
        assert_eq!(LinkTerms::of(&link(Some(2.0), 0.0)), LinkTerms::Massive);
        assert_eq!(LinkTerms::of(&link(None, 1e-3)), LinkTerms::InertiaOnly);
        assert_eq!(LinkTerms::of(&link(None, 0.0)), LinkTerms::Massless);
        assert!(LinkTerms::InertiaOnly.inertia() && !LinkTerms::InertiaOnly.gravity());
        assert!(!LinkTerms::Massless.inertia() && !LinkTerms::Massless.gravity());
        assert!(LinkTerms::Massive.inertia() && LinkTerms::Massive.gravity());
    }

    #[test]
    fn numbers_the_structure_ignores_are_refused() {
        assert!(LinkTerms::Massive
            .check("coupler", &params(3.0, 1e-2))
            .is_ok());
        assert!(LinkTerms::Massless
            .check("coupler", &params(0.0, 0.0))
            .is_ok());
        assert!(LinkTerms::InertiaOnly
            .check("coupler", &params(0.0, 4e-3))
            .is_ok());
        match LinkTerms::Massless.check("coupler", &params(1.0, 5e-3)) {
            Err(MechError::InvalidInput(msg)) => {
                for part in [
                    "link `coupler`",
                    "mass 1 kg",
                    "inertia 0.005 kg·m²",
                    "declare `mass: 0.0` on link `coupler` in `mechanism!`",
                ] {
                    assert!(msg.contains(part), "{part} in {msg}");
                }
            }
            other => panic!("{other:?}"),
        }
        assert!(LinkTerms::Massless
            .check("coupler", &params(0.0, 5e-3))
            .is_err());
        assert!(LinkTerms::Massless
            .check("coupler", &params(f64::NAN, 0.0))
            .is_err());
        assert!(LinkTerms::InertiaOnly
            .check("coupler", &params(1.0, 0.0))
            .is_err());
    }
}
