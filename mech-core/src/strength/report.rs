//! What a strength analysis returns: for each member (a link with a beam section, or a
//! joint's pin) the check of each criterion over the cycle, and the one that governs.

/// What a check compares with the material's strength.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Criterion {
    /// The normal stress N/A of a link that carries no bending (a two-force member),
    /// against the yield strength S_y.
    Axial,
    /// The normal stress N/A ± M/Z at the extreme fibres, against S_y.
    Bending,
    /// A shear stress against the yield strength in shear S_sy = S_y/√3 (distortion
    /// energy): a link's transverse shear k V/A, a pin's R/(n π d²/4).
    Shear,
    /// A pin's bearing pressure R/(d t) on the link's bore, against the link's S_y.
    Bearing,
    /// The compressive stress −N/A of a link against its critical stress (Euler / Johnson).
    Buckling,
    /// The cycle's alternating and mean stress at the worst fibre, Goodman's line.
    Fatigue,
}

impl Criterion {
    /// The name in tables (`axial`, `bending`, `shear`, `bearing`, `buckling`, `fatigue`).
    pub fn name(self) -> &'static str {
        match self {
            Criterion::Axial => "axial",
            Criterion::Bending => "bending",
            Criterion::Shear => "shear",
            Criterion::Bearing => "bearing",
            Criterion::Buckling => "buckling",
            Criterion::Fatigue => "fatigue",
        }
    }
}

/// One criterion over the cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Check {
    /// The criterion.
    pub criterion: Criterion,
    /// The largest magnitude of the stress over the cycle, Pa.
    pub stress_max: f64,
    /// The mean stress of the cycle where the check is worst, Pa.
    pub stress_mean: f64,
    /// The alternating stress of the cycle there, Pa.
    pub stress_alt: f64,
    /// The smallest factor of safety over the cycle (the strength over the stress);
    /// infinite when the member is never loaded in this way.
    pub safety: f64,
    /// The input q (rad) where the factor is smallest.
    pub q: f64,
    /// Where along the link (m from its first point) the check is worst; 0 for a pin.
    pub at: f64,
}

/// The checks of one member.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// `<link>` or `<joint>.pin`.
    pub name: String,
    /// Each criterion that applies, in [`Criterion`] order.
    pub checks: Vec<Check>,
}

impl Member {
    /// The check with the smallest factor (the first of equal ones).
    pub fn governing(&self) -> Option<&Check> {
        self.checks
            .iter()
            .fold(None, |best: Option<&Check>, c| match best {
                Some(b) if b.safety <= c.safety => Some(b),
                _ => Some(c),
            })
    }

    /// The check of criterion `c`, if it applies.
    pub fn check(&self, c: Criterion) -> Option<&Check> {
        self.checks.iter().find(|k| k.criterion == c)
    }
}

/// The strength of a machine over its cycle: every member's checks.
#[derive(Clone, Debug, PartialEq)]
pub struct Strength {
    /// The members: the links with a beam section (`bar`, `rod`, `tube`) in declaration
    /// order, then the joints with a pin.
    pub members: Vec<Member>,
    /// The largest magnitude of the motor's action on the input over the cycle, N·m.
    pub driver_peak: f64,
}

impl Strength {
    /// The member named `name` (`crank`, `O2.pin`), if any.
    pub fn member(&self, name: &str) -> Option<&Member> {
        self.members.iter().find(|m| m.name == name)
    }

    /// The smallest factor of any member, and that member (`None` with no member).
    pub fn worst(&self) -> Option<(&Member, &Check)> {
        self.members
            .iter()
            .filter_map(|m| m.governing().map(|c| (m, c)))
            .fold(None, |best: Option<(&Member, &Check)>, x| match best {
                Some(b) if b.1.safety <= x.1.safety => Some(b),
                _ => Some(x),
            })
    }
}
