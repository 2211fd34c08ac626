//! The plain-data description of a mechanism, shared by the `mechanism!` macro and the
//! run-time loader.
//!
//! Two layers:
//! - [`Description`]: what the user wrote, names unresolved, each item carrying the source
//!   location `S` of its tokens (a `proc_macro2::Span` in the macro, a line/column in text);
//! - [`Model`]: the resolved mechanism, every reference an index, ready for validation,
//!   planning and solving. Index 0 of [`Model::links`] is the ground.
//!
//! Units are SI throughout (m, kg, kg·m², N, N·m, rad, s).

/// A named item as written, with the location of its name.
#[derive(Clone, Debug, PartialEq)]
pub struct Name<S> {
    /// The identifier.
    pub text: String,
    /// Where it was written.
    pub span: S,
}

/// A numeric literal as written, with its location.
#[derive(Clone, Debug, PartialEq)]
pub struct Num<S> {
    /// The value.
    pub value: f64,
    /// Where it was written.
    pub span: S,
}

/// A number of the DSL evaluated to SI, with the dimension its unit words gave it (none
/// for a plain number): kept where the check of its unit needs the model (the zero of an
/// input is an angle on a revolute joint, a length on a prismatic one).
#[derive(Clone, Debug, PartialEq)]
pub struct Measure<S> {
    /// The value, SI.
    pub value: f64,
    /// Its dimension, `None` for a plain number.
    pub dim: Option<crate::model::units::Dim>,
    /// Where it was written.
    pub span: S,
}

/// An input as written: `O2` or `O2 from 90 deg`.
#[derive(Clone, Debug, PartialEq)]
pub struct InputDecl<S> {
    /// The driven joint.
    pub name: Name<S>,
    /// `from z`: the joint coordinate where q = 0 (rad or m); `None` = 0.
    pub from: Option<Measure<S>>,
}

/// A pair of numbers `(x, y)` as written (evaluated to SI).
#[derive(Clone, Debug, PartialEq)]
pub struct Pair<S> {
    /// The value, `[x, y]`.
    pub value: [f64; 2],
    /// Where it was written.
    pub span: S,
}

/// A point mentioned in a `points { ... }` list: either defined here (`A: (x, y)`) or reused (`A`).
#[derive(Clone, Debug, PartialEq)]
pub struct PointRef<S> {
    /// The point's name.
    pub name: Name<S>,
    /// `Some` when this mention defines the point's reference coordinates.
    pub at: Option<Pair<S>>,
}

/// A `link NAME { ... }` block (or the `ground { ... }` block) as written.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkDecl<S> {
    /// The link's name (`ground` for the ground block).
    pub name: Name<S>,
    /// Its points in order; the first two define the link angle.
    pub points: Vec<PointRef<S>>,
    /// `mass: m` (kg); `None` = massless.
    pub mass: Option<Num<S>>,
    /// `inertia: I` about the cg (kg·m²); `None` = 0.
    pub inertia: Option<Num<S>>,
    /// `cg: (x, y)` in the drawing (m).
    pub cg: Option<Pair<S>>,
    /// `shape: KIND(name value, ..)`: what the link is made of, instead of its mass.
    pub shape: Option<ShapeDecl<S>>,
    /// `material: NAME` or `material { .. }`.
    pub material: Option<MaterialDecl<S>>,
    /// Each `counterweight: (MASS, at (x, y))` or `(MASS, at (x, y), plane: Z)`: a point
    /// mass (kg) fixed to the link at a point of the drawing (m), in the plane z (m; `None`:
    /// the link's), in declaration order, with where it was written.
    pub counterweights: Vec<(Num<S>, Pair<S>, Option<Num<S>>, S)>,
    /// `plane: z`: the axial position of the link's plane along the z axis (m), for the
    /// shaking couples about the transverse axes; `None` = 0.
    pub plane: Option<Num<S>>,
}

/// A link's `shape:` as written: the keyword (`bar`, `rod`, `tube`, `disc`, `plate`) and
/// its dimensions (m) in the order of [`crate::model::shape::Shape::dimensions`].
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeDecl<S> {
    /// The keyword.
    pub keyword: String,
    /// The dimensions, m (a free one's lower bound).
    pub dims: Vec<f64>,
    /// Each dimension written `free(LO..HI)` (`mech size` chooses it), in the order of
    /// `dims`.
    pub free: Vec<Option<FreeDecl<S>>>,
    /// Where the keyword is.
    pub span: S,
}

/// A dimension written `free(LO..HI)`: to be chosen by `mech size` within [LO, HI] (m);
/// until then it is LO.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeDecl<S> {
    /// LO, m.
    pub lo: f64,
    /// HI, m.
    pub hi: f64,
    /// Where `free` is.
    pub span: S,
    /// Where its closing parenthesis is.
    pub end: S,
}

/// A link's `material:` as written, resolved to its properties.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialDecl<S> {
    /// The material.
    pub material: crate::model::shape::Material,
    /// Where it is named (or the block's `material` keyword).
    pub span: S,
}

/// How a point is published ([`Model::point_owner`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointOwner {
    /// A point of the ground: at rest at its drawn place.
    Ground,
    /// The anchor (first point) of this moving link: its state's own position and motion.
    Anchor(usize),
    /// The material point of this moving link at the point's local vector.
    Local(usize),
}

/// The kind of a joint as written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// Pin: removes 2 DOF (lower pair).
    Revolute,
    /// Slider: removes 2 DOF (lower pair); axis fixed in `a`.
    Prismatic,
    /// Pin in a straight slot of `a`: removes 1 DOF (higher pair).
    PinInSlot,
    /// Gear pair `gear(a, b) radii (r_a, r_b)`: the pitch circles roll on each other,
    /// removes 1 DOF (higher pair).
    Gear,
    /// Rack and pinion `rack(pinion, bar) radius r`: the pinion's pitch circle rolls on
    /// the rack's pitch line, removes 1 DOF (higher pair).
    Rack,
    /// A wheel rolling without slipping on a straight line of a track,
    /// `rolling(track, wheel) at C radius r along (ux, uy)`: no penetration and no slip at
    /// the contact point, removes 2 DOF (a lower pair).
    Rolling,
    /// A cam and its follower, `cam(cam, follower) base_radius R_b [roller r | flat]
    /// law [..]`: the follower's slide (or a rocker's turn) is the motion law of the cam's
    /// turn, removes 1 DOF (a higher pair).
    Cam,
}

impl JointKind {
    /// DOF removed by the joint in the plane (its number of reaction components).
    pub const fn removed(self) -> usize {
        match self {
            JointKind::Revolute | JointKind::Prismatic | JointKind::Rolling => 2,
            JointKind::PinInSlot | JointKind::Gear | JointKind::Rack | JointKind::Cam => 1,
        }
    }
    /// The keyword of the DSL.
    pub const fn keyword(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
            JointKind::PinInSlot => "pin_in_slot",
            JointKind::Gear => "gear",
            JointKind::Rack => "rack",
            JointKind::Rolling => "rolling",
            JointKind::Cam => "cam",
        }
    }
    /// A gear pair or a rack and pinion: a mesh of toothed pitch curves.
    pub const fn mesh(self) -> bool {
        matches!(self, JointKind::Gear | JointKind::Rack)
    }
    /// A higher pair of Grübler's count (P_II): a pin in a slot, a gear pair, a rack.
    pub const fn higher(self) -> bool {
        matches!(
            self,
            JointKind::PinInSlot | JointKind::Gear | JointKind::Rack | JointKind::Cam
        )
    }
}

/// The teeth of a gear pair or rack as written: `radii (r_a, r_b) [internal]
/// [pressure_angle α]` or `radius r [pressure_angle α]`.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshDecl<S> {
    /// Pitch radii (m): (r_a, r_b) of a gear pair, (r, 0) of a rack's pinion.
    pub radii: Pair<S>,
    /// `internal`: one gear is a ring around the other.
    pub internal: bool,
    /// The pressure angle (rad), 20° when not written.
    pub pressure_angle: Option<Num<S>>,
}

/// A resolved gear pair or rack (`docs/conventions.md#gears`).
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Pitch radius of link a (the gear, or the rack's pinion), m.
    pub ra: f64,
    /// Pitch radius of link b (0 for a rack), m.
    pub rb: f64,
    /// An internal pair (the larger gear is a ring).
    pub internal: bool,
    /// The pressure angle α, rad.
    pub pressure_angle: f64,
    /// The carrier: the link that holds both centres (for a rack, the link it slides on).
    pub carrier: usize,
    /// The points at the centres of a and b (for a rack, b's: its sliding joint's point).
    pub centres: [usize; 2],
}

/// A joint as written: `NAME: kind(a, b) [at P] [along (ux, uy)]`.
#[derive(Clone, Debug, PartialEq)]
pub struct JointDecl<S> {
    /// The joint's name.
    pub name: Name<S>,
    /// Its kind, with the span of the keyword.
    pub kind: JointKind,
    /// Span of the whole joint declaration (the keyword).
    pub kind_span: S,
    /// First link (the guide or slot for sliding joints).
    pub a: Name<S>,
    /// Second link (the slider or the pin's link).
    pub b: Name<S>,
    /// `at P`; `None` = the point named like the joint.
    pub at: Option<Name<S>>,
    /// `along (ux, uy)`: the sliding axis (sliding joints only).
    pub along: Option<Pair<S>>,
    /// The teeth of a gear pair or rack (a rolling wheel's radius in `radii[0]`).
    pub mesh: Option<MeshDecl<S>>,
    /// A rolling wheel's circular track: `around D [inside]`.
    pub around: Option<(Name<S>, bool)>,
    /// A cam's base radius, face and motion law.
    pub cam: Option<CamDecl<S>>,
    /// A revolute joint's pin: `pin D [double]`, its diameter (m) and whether it works in
    /// double shear.
    pub pin: Option<(Num<S>, bool)>,
}

/// A cam as written: `base_radius R_b [roller r | flat] law [segment, ..]`.
#[derive(Clone, Debug, PartialEq)]
pub struct CamDecl<S> {
    /// R_b, m.
    pub base_radius: Num<S>,
    /// The follower's face.
    pub face: crate::elements::cam::Face,
    /// The segments from the cam's angle 0 (the drawing), with where each was written.
    pub segments: Vec<(crate::elements::cam::Segment, S)>,
    /// A table of (θ, s) instead of segments (`table [(θ, s), ..]`), rad and m.
    pub table: Vec<[f64; 2]>,
    /// Where `law` was written.
    pub law_span: S,
    /// What the lifts were written in: `Some(true)` angles (an oscillating follower),
    /// `Some(false)` lengths (a translating one), `None` plain numbers (SI, either).
    pub angular: Option<bool>,
}

/// What a load is.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadDeclKind<S> {
    /// `force on LINK at POINT`: a global force vector (N) applied at a point.
    Force {
        /// The link it acts on.
        link: Name<S>,
        /// The point of that link it is applied at.
        point: Name<S>,
    },
    /// `torque on LINK`: a pure moment (N·m, CCW positive).
    Torque {
        /// The link it acts on.
        link: Name<S>,
    },
}

/// A load as written.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadDecl<S> {
    /// The load's name (the field of the `Loads` struct).
    pub name: Name<S>,
    /// Force or torque.
    pub kind: LoadDeclKind<S>,
}

/// What a force element is (`elements { }`, `docs/conventions.md#elements`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ElementKind {
    /// `spring(a at P, b at Q) stiffness k free_length L0` (or `preload F0`): a linear
    /// spring between two points, tension T = k (L − L₀).
    Spring,
    /// `damper(a at P, b at Q) damping c`: a linear viscous damper, tension T = c L̇.
    Damper,
    /// `torsion_spring(a, b) stiffness k free_angle φ₀`: moment −k (θ_b − θ_a − φ₀) on b.
    TorsionSpring,
    /// `rotary_damper(a, b) damping c`: moment −c (ω_b − ω_a) on b.
    RotaryDamper,
}

impl ElementKind {
    /// The DSL keyword.
    pub fn keyword(self) -> &'static str {
        match self {
            ElementKind::Spring => "spring",
            ElementKind::Damper => "damper",
            ElementKind::TorsionSpring => "torsion_spring",
            ElementKind::RotaryDamper => "rotary_damper",
        }
    }
    /// True for the elements between two points (spring, damper); false for the rotary ones.
    pub fn linear(self) -> bool {
        matches!(self, ElementKind::Spring | ElementKind::Damper)
    }
    /// True for the springs (a stiffness and a free length or angle).
    pub fn spring(self) -> bool {
        matches!(self, ElementKind::Spring | ElementKind::TorsionSpring)
    }
}

/// How the unloaded state of a spring is given.
#[derive(Clone, Debug, PartialEq)]
pub enum RestDecl<S> {
    /// `free_length L0` (m) or `free_angle φ0` (rad).
    Free(Num<S>),
    /// `preload F0`: the tension (N, or N·m for a torsion spring) in the drawing,
    /// negative for a compressed spring.
    Preload(Num<S>),
}

/// A force element as written.
#[derive(Clone, Debug, PartialEq)]
pub struct ElementDecl<S> {
    /// The element's name.
    pub name: Name<S>,
    /// What it is.
    pub kind: ElementKind,
    /// Where its keyword was written.
    pub kind_span: S,
    /// First link and, for a spring or damper, its point P.
    pub a: Name<S>,
    /// `a at P`.
    pub pa: Option<Name<S>>,
    /// Second link and its point Q.
    pub b: Name<S>,
    /// `b at Q`.
    pub pb: Option<Name<S>>,
    /// Stiffness (N/m, N·m/rad) or damping (N·s/m, N·m·s/rad).
    pub coefficient: Num<S>,
    /// The spring's free length, free angle or preload; `None` for a damper.
    pub rest: Option<RestDecl<S>>,
}

/// A whole `mechanism! { ... }` body as written, names unresolved.
#[derive(Clone, Debug, PartialEq)]
pub struct Description<S> {
    /// Doc comment lines.
    pub docs: Vec<String>,
    /// The struct's name.
    pub name: Name<S>,
    /// `#[allow(redundant)]` was given.
    pub allow_redundant: bool,
    /// `gravity: (gx, gy)` (m/s²).
    pub gravity: Option<Pair<S>>,
    /// The ground block.
    pub ground: LinkDecl<S>,
    /// The moving links, in order.
    pub links: Vec<LinkDecl<S>>,
    /// The joints, in order.
    pub joints: Vec<JointDecl<S>>,
    /// The inputs (driven joints), in order.
    pub inputs: Vec<InputDecl<S>>,
    /// Span of the `input`/`inputs` keyword (whole-mechanism errors point here).
    pub inputs_span: S,
    /// The loads, in order.
    pub loads: Vec<LoadDecl<S>>,
    /// The force elements, in order.
    pub elements: Vec<ElementDecl<S>>,
}

// ---------------------------------------------------------------------------------------
// Resolved model
// ---------------------------------------------------------------------------------------

/// A point of the drawing.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// Name.
    pub name: String,
    /// Reference (drawing) coordinates, m.
    pub pos: [f64; 2],
}

/// A rigid link (index 0 = ground).
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Name.
    pub name: String,
    /// Indices into [`Model::points`]; the first two define the link angle.
    pub points: Vec<usize>,
    /// Mass, kg; `None` = massless (no inertia terms at all).
    pub mass: Option<f64>,
    /// Moment of inertia about the cg, kg·m².
    pub inertia: f64,
    /// A flywheel keyed to the link: a pure rotor of this inertia (kg·m²) added to the
    /// link's rotational inertia on every route (0 = none). A run-time parameter.
    pub flywheel: f64,
    /// Centre of gravity in the drawing, m.
    pub cg: [f64; 2],
    /// The shape and material the mass, cg and inertia came from, when the link was
    /// declared by them.
    pub body: Option<(crate::model::shape::Shape, crate::model::shape::Material)>,
    /// `plane: z` and the counterweights in other planes: the axial position of the cg
    /// (m) and the products of inertia (kg·m²) ([`crate::model::shape::Axial`]); zero for
    /// a mechanism in one plane.
    pub axial: crate::model::shape::Axial,
}

impl Link {
    /// True when the link carries mass or inertia (its own or a flywheel's).
    pub fn has_inertia(&self) -> bool {
        self.mass.is_some_and(|m| m != 0.0) || self.inertia != 0.0 || self.flywheel != 0.0
    }

    /// The rotational inertia the solvers use: I_G plus the flywheel's, kg·m².
    pub fn rotational_inertia(&self) -> f64 {
        self.inertia + self.flywheel
    }
}

/// A resolved joint.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Name.
    pub name: String,
    /// Kind.
    pub kind: JointKind,
    /// First link (guide / slot for sliding joints).
    pub a: usize,
    /// Second link (slider / pin).
    pub b: usize,
    /// The joint point (a point of `b`).
    pub point: usize,
    /// Sliding axis in reference global coordinates (not normalised); `[0, 0]` for a revolute.
    pub axis: [f64; 2],
    /// The teeth of a gear pair or rack (`None` for the other joints).
    pub mesh: Option<Mesh>,
    /// A rolling wheel's radius, m (0 for the other joints).
    pub radius: f64,
    /// A rolling wheel's circular track: the point of the track at its centre D, and
    /// whether the wheel rolls inside it (`None`: a straight track along `axis`).
    pub around: Option<(usize, bool)>,
    /// A cam's data (`None` for the other joints).
    pub cam: Option<Box<CamSpec>>,
    /// A revolute joint's pin, when declared.
    pub pin: Option<Pin>,
}

impl Joint {
    /// The link on the other side of the joint from `link` (one of its two links).
    #[inline]
    pub fn across(&self, link: usize) -> usize {
        if self.a == link {
            self.b
        } else {
            self.a
        }
    }
}

/// The pin of a revolute joint (`pin 12 mm` or `pin 12 mm double`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pin {
    /// Diameter d, m.
    pub diameter: f64,
    /// In double shear (a fork: two sections carry the load) rather than single.
    pub double: bool,
}

/// A resolved cam (`docs/conventions.md#cams`): a translating follower sliding on the
/// carrier the cam is pinned to, or an oscillating one pinned to it.
#[derive(Clone, Debug, PartialEq)]
pub struct CamSpec {
    /// R_b, the base circle's radius, m.
    pub base_radius: f64,
    /// The follower's face.
    pub face: crate::elements::cam::Face,
    /// The motion law's segments, from the cam's angle 0 (the drawing).
    pub segments: Vec<crate::elements::cam::Segment>,
    /// Or a table of (θ, s), rad and m, through a periodic spline (empty: the segments).
    pub table: Vec<[f64; 2]>,
    /// The carrier: the link the cam is pinned to and the follower slides on.
    pub carrier: usize,
    /// The cam's centre (the point of its pin to the carrier).
    pub centre: usize,
    /// The follower's joint on the carrier: its prismatic joint (translating) or its pin
    /// (oscillating: a rocker).
    pub slide: usize,
    /// The lifts are angles (a rocker's law ψ(θ)), not lengths.
    pub angular: bool,
}

/// A resolved load.
#[derive(Clone, Debug, PartialEq)]
pub enum Load {
    /// A force (N, global vector) on `link` at `point`.
    Force {
        /// Name.
        name: String,
        /// Link index.
        link: usize,
        /// Point index.
        point: usize,
    },
    /// A torque (N·m, CCW) on `link`.
    Torque {
        /// Name.
        name: String,
        /// Link index.
        link: usize,
    },
}

impl Load {
    /// The load's name.
    pub fn name(&self) -> &str {
        match self {
            Load::Force { name, .. } | Load::Torque { name, .. } => name,
        }
    }
    /// The link it acts on.
    pub fn link(&self) -> usize {
        match self {
            Load::Force { link, .. } | Load::Torque { link, .. } => *link,
        }
    }
}

/// A resolved force element (`docs/conventions.md#elements`): a spring–damper, its
/// tension T = k (x − x₀) + c ẋ along its extension x (the distance |Q − P| of a linear
/// element, the relative angle θ_b − θ_a of a rotary one). A spring has c = 0, a damper
/// k = 0 and x₀ = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// Name.
    pub name: String,
    /// What it was declared as.
    pub kind: ElementKind,
    /// First link.
    pub a: usize,
    /// Second link.
    pub b: usize,
    /// The points P (of a) and Q (of b) of a linear element; `None` for a rotary one.
    pub points: Option<[usize; 2]>,
    /// k: N/m (linear) or N·m/rad (rotary); 0 for a damper.
    pub stiffness: f64,
    /// c: N·s/m (linear) or N·m·s/rad (rotary); 0 for a spring.
    pub damping: f64,
    /// x₀: the free length (m) or free angle (rad); 0 for a damper.
    pub free: f64,
}

/// A resolved mechanism: plain data, indices only.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// The struct's name.
    pub name: String,
    /// Gravity (m/s²), `None` = no gravity terms.
    pub gravity: Option<[f64; 2]>,
    /// Redundant constraints accepted.
    pub allow_redundant: bool,
    /// Points.
    pub points: Vec<Point>,
    /// Links; index 0 is the ground.
    pub links: Vec<Link>,
    /// Joints.
    pub joints: Vec<Joint>,
    /// Driven joints (indices into `joints`).
    pub inputs: Vec<usize>,
    /// The zero of each input (`input: O2 from 90 deg`): the joint coordinate where q = 0
    /// (rad for a revolute input, m for a prismatic one), so that the joint's angle
    /// θ_b − θ_a (or its slide from the drawing) is q + zero.
    pub input_zero: Vec<f64>,
    /// Loads.
    pub loads: Vec<Load>,
    /// Force elements (springs, dampers).
    pub elements: Vec<Element>,
}

impl Model {
    /// True when some link lies out of the plane z = 0 or has products of inertia
    /// (`plane: z`, a counterweight in another plane, [`crate::model::shape::Axial`]):
    /// then the shaking has couples about the x and y axes (SPEC 3g).
    pub fn has_planes(&self) -> bool {
        self.links
            .iter()
            .any(|l| l.axial != crate::model::shape::Axial::default())
    }
    /// N: the number of links, ground included.
    pub fn n_links(&self) -> usize {
        self.links.len()
    }
    /// True when moving link `l` never turns: it slides on the ground (a prismatic joint
    /// with link 0), or on a link that never turns (a block in the slot of a yoke that
    /// slides on the ground): a prismatic joint keeps its two links' relative rotation,
    /// so ω = α = 0, the rotation the drawing's, and the cg moves as the anchor.
    pub fn translates(&self, l: usize) -> bool {
        if l == 0 || l >= self.links.len() {
            return false;
        }
        // The links reached from the ground through prismatic joints alone.
        let mut fixed = vec![false; self.links.len()];
        fixed[0] = true;
        let mut grew = true;
        while grew && !fixed[l] {
            grew = false;
            for j in self
                .joints
                .iter()
                .filter(|j| j.kind == JointKind::Prismatic)
            {
                if fixed[j.a] != fixed[j.b] {
                    fixed[j.a] = true;
                    fixed[j.b] = true;
                    grew = true;
                }
            }
        }
        fixed[l]
    }
    /// True when moving link `l` turns about its anchor (its first point) on a revolute
    /// joint with the ground: that point never moves, so the link's inertia about it,
    /// I_O = I_G + m |G − O|², is all Zhukovski's route needs.
    pub fn pinned_at_anchor(&self, l: usize) -> bool {
        let Some(&first) = self.links[l].points.first() else {
            return false;
        };
        l != 0
            && self.joints.iter().any(|j| {
                j.kind == JointKind::Revolute
                    && ((j.a == 0 && j.b == l) || (j.a == l && j.b == 0))
                    && j.point == first
            })
    }
    /// The point about which moving link `l` turns on a revolute joint with the ground
    /// (a plain pin: no cam, no rolling, no mesh), if it has one: that point never moves,
    /// so Zhukovski's route needs only the link's inertia about it, I_O = I_G + m |G − O|²
    /// ([`crate::kernel::link_state::LinkGeom::inertia_pivot`]), at any anchor.
    pub fn ground_pivot(&self, l: usize) -> Option<usize> {
        if l == 0 {
            return None;
        }
        self.joints
            .iter()
            .find(|j| {
                j.kind == JointKind::Revolute
                    && ((j.a == 0 && j.b == l) || (j.a == l && j.b == 0))
                    && j.cam.is_none()
                    && j.around.is_none()
                    && j.mesh.is_none()
            })
            .map(|j| j.point)
    }
    /// A moving link whose anchor (first point) is the second point of moving link `l`:
    /// its state's position minus `l`'s is then `l`'s span P₂ − P₁
    /// ([`crate::kernel::link_state::LinkGeom::cg_by_span`]), known without `l`'s rotation.
    pub fn span_partner(&self, l: usize) -> Option<usize> {
        let &p2 = self.links.get(l)?.points.get(1)?;
        if l == 0 {
            return None;
        }
        (1..self.links.len()).find(|&m| m != l && self.links[m].points.first() == Some(&p2))
    }
    /// How point `pt` is published, the one rule of the generated code and the run-time
    /// mechanism ([`PointOwner`]): a point of the ground at rest; else the anchor (first
    /// point) of a moving link, that link's state itself (nothing rotated); else the
    /// material point of the first link that carries it.
    pub fn point_owner(&self, pt: usize) -> PointOwner {
        if self.links.first().is_some_and(|g| g.points.contains(&pt)) {
            return PointOwner::Ground;
        }
        if let Some(l) = (1..self.links.len()).find(|&l| self.links[l].points.first() == Some(&pt))
        {
            return PointOwner::Anchor(l);
        }
        PointOwner::Local(
            (0..self.links.len())
                .find(|&l| self.links[l].points.contains(&pt))
                .unwrap_or(0),
        )
    }
    /// For joint `j`, whether its point is the anchor (first point) of link a and of
    /// link b: there its local vector ([`crate::plan::geometry::joint_geom`]) is exactly zero,
    /// p − p, for any numbers of the drawing. False on the ground (anchored at the
    /// origin) and for the joints whose vectors are not their point's (cams, rolling
    /// around a circle, gear meshes).
    pub fn at_anchor(&self, j: usize) -> [bool; 2] {
        let jt = &self.joints[j];
        let plain = jt.cam.is_none() && jt.around.is_none() && jt.mesh.is_none();
        let first = |l: usize| plain && l != 0 && self.links[l].points.first() == Some(&jt.point);
        [first(jt.a), first(jt.b)]
    }
    /// P_I: lower pairs (revolute and prismatic joints).
    pub fn lower_pairs(&self) -> usize {
        self.joints.iter().filter(|j| !j.kind.higher()).count()
    }
    /// P_II: higher pairs (pins in slots, gear pairs, racks).
    pub fn higher_pairs(&self) -> usize {
        self.joints.iter().filter(|j| j.kind.higher()).count()
    }
    /// The index of the link named `name`.
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }
    /// The index of the joint named `name`.
    pub fn joint_index(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }
    /// The index of the point named `name`.
    pub fn point_index(&self, name: &str) -> Option<usize> {
        self.points.iter().position(|p| p.name == name)
    }
    /// Reference link angle θ (rad): atan2 of first → second point; 0 for a link with
    /// fewer than two points and for the ground (the fixed frame).
    pub fn reference_angle(&self, link: usize) -> f64 {
        let l = &self.links[link];
        if link == 0 || l.points.len() < 2 {
            return 0.0;
        }
        let p0 = self.points[l.points[0]].pos;
        let p1 = self.points[l.points[1]].pos;
        (p1[1] - p0[1]).atan2(p1[0] - p0[0])
    }
    /// The value of input `k` in the drawing: θ_b − θ_a for a revolute driver, 0 for a
    /// prismatic driver (its slide from the drawing), less the input's zero.
    pub fn reference_input(&self, k: usize) -> f64 {
        let j = &self.joints[self.inputs[k]];
        let joint = match j.kind {
            JointKind::Revolute => self.reference_angle(j.b) - self.reference_angle(j.a),
            _ => 0.0,
        };
        joint - self.input_zero.get(k).copied().unwrap_or(0.0)
    }
    /// A length scale of the drawing (m): the largest distance between two points, at
    /// least 1e-300. Tolerances of the numeric checks are relative to it.
    pub fn scale(&self) -> f64 {
        let mut s: f64 = 0.0;
        for p in &self.points {
            for r in &self.points {
                s = s.max((p.pos[0] - r.pos[0]).hypot(p.pos[1] - r.pos[1]));
            }
        }
        s.max(1e-300)
    }
}

#[cfg(test)]
mod tests {
    use crate::front::resolve::model_of;
    use crate::kernel::measure::within;

    /// Which links turn about a ground pin at their anchor, and which slide on the ground:
    /// what the solvers' shortcuts rest on.
    #[test]
    fn pinned_and_translating_links() {
        let m = model_of(
            "pub struct S { ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
              link crank { points { O2, A: (0.0, 0.1) } },
              link rod { points { A, B: (0.25, 0.0) } },
              link piston { points { B } },
              link lever { points { C: (0.3, 0.2), O4 } },
              link arm { points { O4, D: (0.3, -0.2) } },
              joints { O2: revolute(ground, crank), A: revolute(crank, rod), B: revolute(rod, piston),
                       guide: prismatic(ground, piston) at B along (1.0, 0.0),
                       O4: revolute(lever, ground), O4b: revolute(ground, arm) at O4 },
              input: O2 }",
        );
        let l = |name: &str| m.link_index(name).unwrap();
        assert!(m.pinned_at_anchor(l("crank")));
        // The arm's first point is the ground pin O4, declared (ground, arm).
        assert!(m.pinned_at_anchor(l("arm")));
        // The lever turns about O4 too, but its anchor is C, its first point.
        assert!(!m.pinned_at_anchor(l("lever")));
        // ... and so about a ground pivot, as the crank and the arm.
        let o4 = m.points.iter().position(|p| p.name == "O4");
        assert_eq!(m.ground_pivot(l("lever")), o4);
        assert_eq!(m.ground_pivot(l("arm")), o4);
        assert!(m.ground_pivot(l("crank")).is_some() && m.ground_pivot(l("rod")).is_none());
        assert!(
            !m.pinned_at_anchor(l("rod"))
                && !m.pinned_at_anchor(l("piston"))
                && !m.pinned_at_anchor(0)
        );
        assert!(m.translates(l("piston")));
        assert!(!m.translates(l("rod")) && !m.translates(l("crank")) && !m.translates(0));
        // Spans: the crank's second point A is the rod's anchor, the rod's B the piston's;
        // the lever's second point O4 anchors the arm; the arm's D anchors nothing.
        assert_eq!(m.span_partner(l("crank")), Some(l("rod")));
        assert_eq!(m.span_partner(l("rod")), Some(l("piston")));
        assert_eq!(m.span_partner(l("lever")), Some(l("arm")));
        assert_eq!(m.span_partner(l("arm")), None);
        assert_eq!(m.span_partner(l("piston")), None);
        assert_eq!(m.span_partner(0), None);
        // Joints at a moving link's first point: their local vector there is zero.
        let j = |name: &str| m.joint_index(name).unwrap();
        assert_eq!(m.at_anchor(j("O2")), [false, true]);
        assert_eq!(m.at_anchor(j("A")), [false, true]);
        assert_eq!(m.at_anchor(j("guide")), [false, true]);
        assert_eq!(m.at_anchor(j("O4")), [false, false]);
        assert_eq!(m.at_anchor(j("O4b")), [false, true]);
    }

    /// A link sliding on a link that slides on the ground never turns either (the block
    /// in a Scotch yoke's slanted slot); a block sliding in a turning crank's slot does.
    #[test]
    fn sliding_on_a_translating_link_translates() {
        let m = model_of(
            "pub struct S { ground { O2: (0.0, 0.0) },
              link crank { points { O2, A: (0.04, 0.03) } },
              link block { points { A } },
              link yoke { points { Y: (0.16, 0.01), E } },
              link slider { points { E: (0.02, 0.05) } },
              joints { O2: revolute(ground, crank), A: revolute(crank, block),
                       slot: prismatic(yoke, block) at A along (0.1, 1.0),
                       guide: prismatic(ground, yoke) at Y along (1.0, 0.0),
                       rail: prismatic(crank, slider) at E along (1.0, 0.0),
                       E: revolute(slider, yoke) },
              input: O2 }",
        );
        let l = |name: &str| m.link_index(name).unwrap();
        assert!(m.translates(l("yoke")) && m.translates(l("block")));
        assert!(!m.translates(l("crank")) && !m.translates(l("slider")));
    }

    /// A link's cg from its span (the vector between its first two points) equals the cg
    /// rotated with the link, in any pose: G − P₁ = κ₁ e + κ₂ perp(e) with e = R(φ)(P₂ − P₁).
    #[test]
    fn cg_from_the_span() {
        use crate::kernel::link_state::{LinkState, V2};
        let m = model_of(
            "pub struct S { ground { O: (0.0, 0.0) },
              link bar { points { O, A: (0.3, 0.1) }, mass: 1.0, inertia: 0.01, cg: (0.12, 0.18) },
              joints { O: revolute(ground, bar) }, input: O }",
        );
        let inst = crate::solvers::instance::instance(&m).unwrap();
        let bar = &inst.links[1];
        let a = inst.points[m.point_index("A").unwrap()].1;
        for phi in [0.0f64, 0.7, -2.4, 3.1] {
            let mut s = LinkState::at(V2::new(0.4, -0.2));
            s.rot = V2::new(phi.cos(), phi.sin());
            let e = s.point(a) - s.pos;
            let (r, expected) = (bar.cg_by_span(e), s.r(bar.dcg));
            // measured worst 6.9e-17 (be05608); 100×
            assert!(
                within((r - expected).norm(), 1e-15),
                "{phi}: {r} vs {expected}"
            );
        }
        // The joint at the bar's first point has a zero local vector in the bar.
        assert_eq!(m.at_anchor(0), [false, true]);
        assert_eq!(inst.joints[0].db, V2::zeros());
    }
}
