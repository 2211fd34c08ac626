//! A link declared by what it is made of (`shape:` and `material:`): its section, its
//! material, and the mass, centre of gravity and moment of inertia I_G (about the cg,
//! normal to the plane) they give.
//!
//! Every shape is a prism of uniform density ρ normal to the plane of motion. The formulas
//! (m kg, lengths m, I_G kg·m²):
//!
//! - `bar(width W, thickness T)`: a rectangle L × W along the segment of the link's first
//!   two points (length L) with a half disc of radius r = W/2 at each end (a stadium, the
//!   ends rounded about the two points). Rectangle m_r = ρ T L W, I = m_r (L² + W²)/12;
//!   each half disc m_h = ρ T π r²/2, with I about its flat side's centre m_h r²/2 and
//!   its centroid e = 4r/(3π) outward, so about the bar's middle
//!   m_h (r²/2 + L²/4 + L e). cg at the middle.
//! - `rod(diameter D)`: a solid round bar along the first two points, m = ρ π D²/4 L,
//!   I_G = m (L²/12 + D²/16) (a cylinder about a diameter through its middle). cg at the
//!   middle.
//! - `tube(outer D, inner d)`: m = ρ π (D² − d²)/4 L, I_G = m (L²/12 + (D² + d²)/16).
//! - `disc(radius R, thickness T)`: centred on the link's first point, m = ρ T π R²,
//!   I_G = m R²/2.
//! - `plate(thickness T)`: the polygon of the link's points in declaration order (at least
//!   three), by the shoelace sums over its edges (x_i, y_i) → (x_j, y_j) with
//!   c = x_i y_j − x_j y_i: A = Σ c / 2, cg = Σ (p_i + p_j) c / (6A),
//!   I_O = ρ T Σ c (x_i² + x_i x_j + x_j² + y_i² + y_i y_j + y_j²) / 12 (sign of A
//!   taken), I_G = I_O − m |cg|².

/// The section of a link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A flat bar with rounded ends: width W and thickness T, m.
    Bar {
        /// W, m.
        width: f64,
        /// T, m.
        thickness: f64,
    },
    /// A solid round bar of diameter D, m.
    Rod {
        /// D, m.
        diameter: f64,
    },
    /// A round tube: outer and inner diameters, m.
    Tube {
        /// D, m.
        outer: f64,
        /// d < D, m.
        inner: f64,
    },
    /// A disc of radius R and thickness T about the link's first point, m.
    Disc {
        /// R, m.
        radius: f64,
        /// T, m.
        thickness: f64,
    },
    /// A plate of thickness T over the polygon of the link's points, m.
    Plate {
        /// T, m.
        thickness: f64,
    },
}

/// A link's mass properties.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProperties {
    /// m, kg.
    pub mass: f64,
    /// The centre of gravity in the drawing, m.
    pub cg: [f64; 2],
    /// I_G about the cg, normal to the plane, kg·m².
    pub inertia: f64,
}

/// How a link's mass lies along the shaft axis z, normal to the plane of motion (SPEC 3g,
/// `plane: z`): the axial position z̄ of its cg (m) and its products of inertia
/// P = Σ mᵢ (zᵢ − z̄)(rᵢ − G) (kg·m², a vector of the drawing: (I_xz, I_yz) up to sign),
/// zero for a body symmetric about its plane. Only the shaking couples about the
/// transverse axes depend on them ([`crate::kernel::energy::Shaking::add`]); the planar
/// kinematics and dynamics do not.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Axial {
    /// z̄, the axial position of the cg, m.
    pub plane: f64,
    /// P = Σ mᵢ (zᵢ − z̄)(rᵢ − G) in the drawing, kg·m².
    pub product: [f64; 2],
}

impl Axial {
    /// Two bodies fixed together (a crankshaft and a counterweight in another plane), of
    /// mass properties `a` (self's) and `b` (other's), combined cg `g` (m): with
    /// m = m₁ + m₂, z̄ = (m₁ z₁ + m₂ z₂)/m and P = P₁ + P₂ + m₁ z₁ (G₁ − G) + m₂ z₂ (G₂ − G)
    /// (independent of the origin of z, since Σ mₖ (Gₖ − G) = 0). Massless: self's.
    pub fn combine(
        self,
        a: &MassProperties,
        other: Axial,
        b: &MassProperties,
        g: [f64; 2],
    ) -> Axial {
        let mass = a.mass + b.mass;
        if mass == 0.0 {
            return self;
        }
        let moment = |m: f64, z: f64, c: [f64; 2], i: usize| m * z * (c[i] - g[i]);
        Axial {
            plane: (a.mass * self.plane + b.mass * other.plane) / mass,
            product: [0, 1].map(|i| {
                self.product[i]
                    + other.product[i]
                    + moment(a.mass, self.plane, a.cg, i)
                    + moment(b.mass, other.plane, b.cg, i)
            }),
        }
    }
}

impl MassProperties {
    /// Two bodies fixed together (a link and a counterweight): m = m₁ + m₂,
    /// G = (m₁ G₁ + m₂ G₂)/m, and by the parallel-axis theorem
    /// I_G = I₁ + m₁ |G₁ − G|² + I₂ + m₂ |G₂ − G|² (kg, m, kg·m²). Two massless bodies
    /// give m = 0 at G₁.
    pub fn combine(self, other: MassProperties) -> MassProperties {
        let mass = self.mass + other.mass;
        if mass == 0.0 {
            return MassProperties {
                inertia: self.inertia + other.inertia,
                ..self
            };
        }
        let cg = [
            (self.mass * self.cg[0] + other.mass * other.cg[0]) / mass,
            (self.mass * self.cg[1] + other.mass * other.cg[1]) / mass,
        ];
        let d2 = |p: [f64; 2]| (p[0] - cg[0]).powi(2) + (p[1] - cg[1]).powi(2);
        MassProperties {
            mass,
            cg,
            inertia: self.inertia
                + self.mass * d2(self.cg)
                + other.inertia
                + other.mass * d2(other.cg),
        }
    }
}

impl Shape {
    /// The shape's keyword in the DSL.
    pub fn keyword(&self) -> &'static str {
        match self {
            Shape::Bar { .. } => "bar",
            Shape::Rod { .. } => "rod",
            Shape::Tube { .. } => "tube",
            Shape::Disc { .. } => "disc",
            Shape::Plate { .. } => "plate",
        }
    }

    /// The names of the dimensions of the shape `keyword`, in the DSL's order; `None` for
    /// an unknown keyword.
    pub fn dimension_names(keyword: &str) -> Option<&'static [&'static str]> {
        Some(match keyword {
            "bar" => &["width", "thickness"],
            "rod" => &["diameter"],
            "tube" => &["outer", "inner"],
            "disc" => &["radius", "thickness"],
            "plate" => &["thickness"],
            _ => return None,
        })
    }

    /// The forms, for messages.
    pub const FORMS: &'static str = "`bar(width W, thickness T)`, `rod(diameter D)`, `tube(outer D, inner d)`, `disc(radius R, thickness T)` or `plate(thickness T)`";

    /// The dimensions by name, m, in the order the DSL writes them.
    pub fn dimensions(&self) -> Vec<(&'static str, f64)> {
        match *self {
            Shape::Bar { width, thickness } => vec![("width", width), ("thickness", thickness)],
            Shape::Rod { diameter } => vec![("diameter", diameter)],
            Shape::Tube { outer, inner } => vec![("outer", outer), ("inner", inner)],
            Shape::Disc { radius, thickness } => vec![("radius", radius), ("thickness", thickness)],
            Shape::Plate { thickness } => vec![("thickness", thickness)],
        }
    }

    /// The shape `keyword` with the dimensions `dims` (SI, in [`Shape::dimensions`]'s
    /// order), or what is wrong.
    pub fn from_dimensions(keyword: &str, dims: &[f64]) -> Result<Shape, String> {
        let s = match (keyword, dims) {
            ("bar", &[width, thickness]) => Shape::Bar { width, thickness },
            ("rod", &[diameter]) => Shape::Rod { diameter },
            ("tube", &[outer, inner]) => Shape::Tube { outer, inner },
            ("disc", &[radius, thickness]) => Shape::Disc { radius, thickness },
            ("plate", &[thickness]) => Shape::Plate { thickness },
            _ => return Err(format!("`{keyword}` with {} dimensions", dims.len())),
        };
        s.check()?;
        Ok(s)
    }

    /// This shape with its dimension `name` (one of [`Shape::dimensions`]'s names) set to
    /// `value`, m, checked ([`Shape::check`]); or what is wrong, naming the dimensions the
    /// shape has.
    pub fn with_dimension(&self, name: &str, value: f64) -> Result<Shape, String> {
        let mut dims = self.dimensions();
        let Some(d) = dims.iter_mut().find(|(n, _)| *n == name) else {
            let names: Vec<&str> = dims.iter().map(|(n, _)| *n).collect();
            return Err(format!(
                "no dimension `{name}`: a `{}` has {}",
                self.keyword(),
                names.join(", ")
            ));
        };
        d.1 = value;
        let values: Vec<f64> = dims.iter().map(|(_, v)| *v).collect();
        Shape::from_dimensions(self.keyword(), &values)
    }

    /// Every dimension positive and finite, a tube's bore inside its outer diameter.
    pub fn check(&self) -> Result<(), String> {
        for (name, v) in self.dimensions() {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!(
                    "the {} `{name}` must be a positive length, got {v} m",
                    self.keyword()
                ));
            }
        }
        if let Shape::Tube { outer, inner } = *self {
            if !(inner < outer) {
                return Err(format!(
                    "the tube's inner diameter {inner} m must be smaller than its outer diameter {outer} m"
                ));
            }
        }
        Ok(())
    }

    /// The mass properties for density ρ (kg/m³) over the link's points (drawing, m), or
    /// what is wrong (too few points, a zero length, a degenerate polygon).
    pub fn mass_properties(
        &self,
        density: f64,
        points: &[[f64; 2]],
    ) -> Result<MassProperties, String> {
        self.check()?;
        let pi = std::f64::consts::PI;
        let segment = || -> Result<([f64; 2], f64), String> {
            let (a, b) = match points {
                [a, b, ..] => (a, b),
                _ => {
                    return Err(format!(
                        "a {} lies along the link's first two points; this link has {}",
                        self.keyword(),
                        points.len()
                    ))
                }
            };
            let l = (b[0] - a[0]).hypot(b[1] - a[1]);
            if !(l > 0.0) {
                return Err(format!(
                    "a {} needs its first two points apart",
                    self.keyword()
                ));
            }
            Ok(([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])], l))
        };
        let (mass, cg, inertia) = match *self {
            Shape::Bar { width, thickness } => {
                let (mid, l) = segment()?;
                let r = 0.5 * width;
                let rect = density * thickness * l * width;
                let half = density * thickness * pi * r * r / 2.0;
                let e = 4.0 * r / (3.0 * pi);
                let i = rect * (l * l + width * width) / 12.0
                    + 2.0 * half * (r * r / 2.0 + l * l / 4.0 + l * e);
                (rect + 2.0 * half, mid, i)
            }
            Shape::Rod { diameter } => {
                let (mid, l) = segment()?;
                let m = density * pi * diameter * diameter / 4.0 * l;
                (m, mid, m * (l * l / 12.0 + diameter * diameter / 16.0))
            }
            Shape::Tube { outer, inner } => {
                let (mid, l) = segment()?;
                let m = density * pi * (outer * outer - inner * inner) / 4.0 * l;
                (
                    m,
                    mid,
                    m * (l * l / 12.0 + (outer * outer + inner * inner) / 16.0),
                )
            }
            Shape::Disc { radius, thickness } => {
                let Some(&c) = points.first() else {
                    return Err(
                        "a disc is centred on the link's first point; this link has none".into(),
                    );
                };
                let m = density * thickness * pi * radius * radius;
                (m, c, m * radius * radius / 2.0)
            }
            Shape::Plate { thickness } => plate(density * thickness, points)?,
        };
        Ok(MassProperties { mass, cg, inertia })
    }
}

/// Recompute the mass, cg and I_G of every link declared by its shape and material from
/// the current drawing (after a point or a dimension changed at run time).
pub fn update_bodies(links: &mut [super::Link], points: &[super::Point]) -> Result<(), String> {
    for link in links.iter_mut() {
        let Some((shape, material)) = link.body else {
            continue;
        };
        let at: Vec<[f64; 2]> = link.points.iter().map(|&i| points[i].pos).collect();
        let p = shape
            .mass_properties(material.density, &at)
            .map_err(|why| format!("link `{}`: {why}", link.name))?;
        link.mass = Some(p.mass);
        link.cg = p.cg;
        link.inertia = p.inertia;
    }
    Ok(())
}

/// A polygon's mass, cg and I_G for mass per area σ, by the shoelace sums (see the module
/// documentation), taken about the first vertex for accuracy.
fn plate(sigma: f64, points: &[[f64; 2]]) -> Result<(f64, [f64; 2], f64), String> {
    if points.len() < 3 {
        return Err(format!(
            "a plate is the polygon of the link's points, at least three; this link has {}",
            points.len()
        ));
    }
    let o = points[0];
    let (mut a2, mut sx, mut sy, mut s2) = (0.0, 0.0, 0.0, 0.0);
    for k in 0..points.len() {
        let p = points[k];
        let q = points[(k + 1) % points.len()];
        let (xi, yi, xj, yj) = (p[0] - o[0], p[1] - o[1], q[0] - o[0], q[1] - o[1]);
        let c = xi * yj - xj * yi;
        a2 += c;
        sx += (xi + xj) * c;
        sy += (yi + yj) * c;
        s2 += c * (xi * xi + xi * xj + xj * xj + yi * yi + yi * yj + yj * yj);
    }
    let scale = points
        .iter()
        .map(|p| (p[0] - o[0]).hypot(p[1] - o[1]))
        .fold(0.0, f64::max);
    if !(a2.abs() > 1e-12 * scale * scale) {
        return Err("the plate's points enclose no area: list them around its outline".into());
    }
    let area = a2 / 2.0;
    let (gx, gy) = (sx / (3.0 * a2), sy / (3.0 * a2));
    let mass = sigma * area.abs();
    let io = sigma * s2 / 12.0 * area.signum();
    Ok((
        mass,
        [o[0] + gx, o[1] + gy],
        io - mass * (gx * gx + gy * gy),
    ))
}

/// A material's properties, SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// The name (`steel`, ..., or `custom` for a `material { .. }` block).
    pub name: &'static str,
    /// ρ, kg/m³.
    pub density: f64,
    /// Young's modulus E, Pa.
    pub youngs: f64,
    /// Yield strength S_y, Pa.
    pub yield_strength: f64,
    /// Ultimate tensile strength S_u, Pa.
    pub ultimate: f64,
    /// Endurance limit S_e' of a polished specimen in reversed bending, Pa (before the
    /// Marin factors).
    pub endurance: f64,
}

const fn material(
    name: &'static str,
    density: f64,
    youngs: f64,
    yield_strength: f64,
    ultimate: f64,
    endurance: f64,
) -> Material {
    Material {
        name,
        density,
        youngs,
        yield_strength,
        ultimate,
        endurance,
    }
}

/// The named materials: typical values (a medium-carbon steel such as AISI 1045 hot
/// rolled; grey cast iron class 30; aluminium 6061-T6; titanium Ti-6Al-4V; a cartridge
/// brass), from the usual machine-design tables. S_e' = 0.5 S_u for the steel, the
/// published fatigue strengths (10⁸ cycles or the stated limit) for the others.
pub const MATERIALS: [Material; 5] = [
    material("steel", 7850.0, 205e9, 310e6, 565e6, 282e6),
    material("cast_iron", 7200.0, 100e9, 150e6, 214e6, 97e6),
    material("aluminium", 2700.0, 69e9, 276e6, 310e6, 96e6),
    material("titanium", 4430.0, 114e9, 880e6, 950e6, 510e6),
    material("brass", 8530.0, 110e9, 200e6, 340e6, 100e6),
];

/// The named material `name`, if any.
pub fn material_named(name: &str) -> Option<Material> {
    MATERIALS.iter().find(|m| m.name == name).copied()
}

/// The names of the materials, for messages.
pub fn material_names() -> String {
    MATERIALS
        .iter()
        .map(|m| format!("`{}`", m.name))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    const PI: f64 = std::f64::consts::PI;

    fn close(a: f64, b: f64, what: &str) {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs().max(1e-300),
            "{what}: {a} vs {b}"
        );
    }

    /// Disc, rod, tube against their textbook forms, written out independently.
    #[test]
    fn round_shapes_against_their_closed_forms() {
        let rho = 7850.0;
        let d = Shape::Disc {
            radius: 0.1,
            thickness: 0.02,
        }
        .mass_properties(rho, &[[0.3, -0.2], [1.0, 1.0]])
        .unwrap();
        close(d.mass, rho * 0.02 * PI * 0.01, "disc mass");
        close(d.inertia, 0.5 * d.mass * 0.01, "disc I");
        assert_eq!(d.cg, [0.3, -0.2]);
        let pts = [[0.0, 0.0], [0.3, 0.4]];
        let r = Shape::Rod { diameter: 0.02 }
            .mass_properties(rho, &pts)
            .unwrap();
        let m = rho * PI * 0.0001 * 0.5;
        close(r.mass, m, "rod mass");
        close(
            r.inertia,
            m * (3.0 * 0.0001 + 0.25) / 12.0,
            "rod I = m (3r² + L²)/12",
        );
        close(r.cg[0], 0.15, "rod cg");
        let t = Shape::Tube {
            outer: 0.04,
            inner: 0.03,
        }
        .mass_properties(rho, &pts)
        .unwrap();
        let (mo, mi) = (rho * PI * 0.0004 * 0.5, rho * PI * 0.000225 * 0.5);
        close(t.mass, mo - mi, "tube mass");
        let io = mo * (3.0 * 0.0004 + 0.25) / 12.0;
        let ii = mi * (3.0 * 0.000225 + 0.25) / 12.0;
        close(t.inertia, io - ii, "tube I = outer rod − inner rod");
    }

    /// A rectangle and an L-shaped plate against composite rectangles; the result does not
    /// depend on the orientation or the starting vertex.
    #[test]
    fn plates_against_rectangles() {
        let rect = |x0: f64, y0: f64, a: f64, b: f64| -> (f64, [f64; 2], f64) {
            let m = a * b;
            (m, [x0 + a / 2.0, y0 + b / 2.0], m * (a * a + b * b) / 12.0)
        };
        let p = Shape::Plate { thickness: 1.0 }
            .mass_properties(1.0, &[[1.0, 2.0], [4.0, 2.0], [4.0, 3.0], [1.0, 3.0]])
            .unwrap();
        let (m, g, i) = rect(1.0, 2.0, 3.0, 1.0);
        close(p.mass, m, "mass");
        close(p.cg[0], g[0], "x");
        close(p.cg[1], g[1], "y");
        close(p.inertia, i, "I");
        // An L: [0,2]×[0,1] ∪ [0,1]×[1,3].
        let l = [
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        let (m1, g1, i1) = rect(0.0, 0.0, 2.0, 1.0);
        let (m2, g2, i2) = rect(0.0, 1.0, 1.0, 2.0);
        let m = m1 + m2;
        let g = [(m1 * g1[0] + m2 * g2[0]) / m, (m1 * g1[1] + m2 * g2[1]) / m];
        let d2 = |a: [f64; 2]| (a[0] - g[0]).powi(2) + (a[1] - g[1]).powi(2);
        let i = i1 + m1 * d2(g1) + i2 + m2 * d2(g2);
        let rho = 2700.0;
        for pts in [
            l.to_vec(),
            l.iter().rev().copied().collect(),
            [&l[3..], &l[..3]].concat(),
        ] {
            let p = Shape::Plate { thickness: 0.01 }
                .mass_properties(rho, &pts)
                .unwrap();
            close(p.mass, rho * 0.01 * m, "L mass");
            close(p.cg[0], g[0], "L x");
            close(p.cg[1], g[1], "L y");
            close(p.inertia, rho * 0.01 * i, "L I");
        }
    }

    /// The rounded bar against the stadium as a polygon of n vertices, extrapolated to
    /// n → ∞ (Richardson on n = 2¹⁴, 2¹⁵, 2¹⁶: the inscribed polygon's error is a series
    /// in 1/n²).
    #[test]
    fn the_rounded_bar_is_the_limit_of_its_polygons() {
        let (l, w) = (0.25, 0.04);
        let (a, b) = ([0.1, 0.05], [0.1 + l * 0.6, 0.05 + l * 0.8]);
        let bar = Shape::Bar {
            width: w,
            thickness: 0.01,
        }
        .mass_properties(7850.0, &[a, b])
        .unwrap();
        let polygon = |n: usize| -> MassProperties {
            // Half the vertices on each end's semicircle, the flat sides joining them.
            let (ux, uy) = (0.6, 0.8);
            let r = w / 2.0;
            let mut pts = Vec::new();
            for (c, start) in [(b, -PI / 2.0), (a, PI / 2.0)] {
                for k in 0..=n / 2 {
                    let t = start + PI * k as f64 / (n / 2) as f64;
                    // In the bar's frame (u along, v across), rotated into the drawing.
                    let (pu, pv) = (r * t.cos(), r * t.sin());
                    pts.push([c[0] + pu * ux - pv * uy, c[1] + pu * uy + pv * ux]);
                }
            }
            Shape::Plate { thickness: 0.01 }
                .mass_properties(7850.0, &pts)
                .unwrap()
        };
        let extrapolate = |f: &dyn Fn(&MassProperties) -> f64| -> f64 {
            let (p1, p2, p3) = (polygon(1 << 14), polygon(1 << 15), polygon(1 << 16));
            let (f1, f2, f3) = (f(&p1), f(&p2), f(&p3));
            let (r1, r2) = ((4.0 * f2 - f1) / 3.0, (4.0 * f3 - f2) / 3.0);
            (16.0 * r2 - r1) / 15.0
        };
        let tol = |x: f64, y: f64, what: &str| {
            assert!((x - y).abs() <= 1e-11 * y.abs(), "{what}: {x} vs {y}")
        };
        tol(bar.mass, extrapolate(&|p| p.mass), "mass");
        tol(bar.inertia, extrapolate(&|p| p.inertia), "I_G");
        assert!((bar.cg[0] - (a[0] + b[0]) / 2.0).abs() < 1e-15);
    }

    #[test]
    fn bad_shapes_say_what_is_wrong() {
        let e = Shape::Bar {
            width: -0.01,
            thickness: 0.01,
        }
        .check()
        .unwrap_err();
        assert!(e.contains("`width` must be a positive length"), "{e}");
        let bar = Shape::Bar {
            width: 0.02,
            thickness: 0.01,
        };
        assert_eq!(
            bar.with_dimension("width", 0.03),
            Ok(Shape::Bar {
                width: 0.03,
                thickness: 0.01
            })
        );
        let e = bar.with_dimension("diameter", 0.03).unwrap_err();
        assert!(
            e.contains("no dimension `diameter`: a `bar` has width, thickness"),
            "{e}"
        );
        let e = bar.with_dimension("thickness", 0.0).unwrap_err();
        assert!(e.contains("`thickness` must be a positive length"), "{e}");
        let e = Shape::Tube {
            outer: 0.04,
            inner: 0.03,
        }
        .with_dimension("outer", 0.02)
        .unwrap_err();
        assert!(e.contains("smaller than its outer"), "{e}");
        let e = Shape::Tube {
            outer: 0.02,
            inner: 0.03,
        }
        .check()
        .unwrap_err();
        assert!(e.contains("smaller than its outer"), "{e}");
        let e = Shape::Plate { thickness: 0.01 }
            .mass_properties(1.0, &[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
            .unwrap_err();
        assert!(e.contains("enclose no area"), "{e}");
        let e = Shape::Rod { diameter: 0.01 }
            .mass_properties(1.0, &[[0.0, 0.0]])
            .unwrap_err();
        assert!(e.contains("first two points"), "{e}");
        assert!(material_named("unobtainium").is_none());
        assert_eq!(material_named("steel").unwrap().density, 7850.0);
    }
}
