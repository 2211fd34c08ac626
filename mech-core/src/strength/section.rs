//! A link's cross-section from its [`Shape`]: the section normal to the link's axis (the
//! segment of its first two points).
//!
//! Bending in the plane of motion is about the section's axis normal to that plane: for a
//! `bar(width W, thickness T)` the section is W (in the plane) × T (across it), so
//! I = T W³/12 and the extreme fibre is at c = W/2; a `rod(diameter D)` has
//! I = π D⁴/64, c = D/2; a `tube(outer D, inner d)` I = π (D⁴ − d⁴)/64, c = D/2.
//! Buckling takes the weaker axis: a bar's I_min = W T³/12 when T < W.

use crate::model::shape::Shape;

/// The properties of a cross-section, SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Section {
    /// A, m².
    pub area: f64,
    /// I about the axis normal to the plane of motion (in-plane bending), m⁴.
    pub inertia: f64,
    /// The distance from the neutral axis to the extreme fibre in in-plane bending, m.
    pub extreme_fibre: f64,
    /// The smaller principal second moment (buckling), m⁴.
    pub inertia_min: f64,
    /// The thickness a pin bears on (a bar's T; a rod's or a tube's outer diameter), m.
    pub bearing_length: f64,
    /// The size that sets Marin's size factor: a round section's diameter, a rectangle's
    /// equivalent diameter d_e = 0.808 √(W T), m.
    pub size: f64,
    /// k of the largest transverse shear stress k V/A: 3/2 for a rectangle, 4/3 for a
    /// solid circle, 2 for a thin tube.
    pub shear_factor: f64,
}

impl Section {
    /// The section of a link of shape `shape` normal to its axis; `None` for a disc or a
    /// plate (no beam section).
    pub fn of(shape: &Shape) -> Option<Section> {
        let pi = std::f64::consts::PI;
        Some(match *shape {
            Shape::Bar { width, thickness } => Section {
                area: width * thickness,
                inertia: thickness * width.powi(3) / 12.0,
                extreme_fibre: width / 2.0,
                inertia_min: (thickness * width.powi(3)).min(width * thickness.powi(3)) / 12.0,
                bearing_length: thickness,
                size: 0.808 * (width * thickness).sqrt(),
                shear_factor: 1.5,
            },
            Shape::Rod { diameter } => Section {
                area: pi * diameter * diameter / 4.0,
                inertia: pi * diameter.powi(4) / 64.0,
                extreme_fibre: diameter / 2.0,
                inertia_min: pi * diameter.powi(4) / 64.0,
                bearing_length: diameter,
                size: diameter,
                shear_factor: 4.0 / 3.0,
            },
            Shape::Tube { outer, inner } => {
                let i = pi * (outer.powi(4) - inner.powi(4)) / 64.0;
                Section {
                    area: pi * (outer * outer - inner * inner) / 4.0,
                    inertia: i,
                    extreme_fibre: outer / 2.0,
                    inertia_min: i,
                    bearing_length: outer,
                    size: outer,
                    shear_factor: 2.0,
                }
            }
            Shape::Disc { .. } | Shape::Plate { .. } => return None,
        })
    }

    /// The section modulus Z = I / c, m³: σ = M / Z at the extreme fibre.
    pub fn modulus(&self) -> f64 {
        self.inertia / self.extreme_fibre
    }

    /// The least radius of gyration r = √(I_min / A), m.
    pub fn radius_of_gyration(&self) -> f64 {
        (self.inertia_min / self.area).sqrt()
    }

    /// The normal stress at the extreme fibre under axial force N (N, tension positive) and
    /// bending moment M (N·m): N/A + |M|/Z, Pa (the fibre on the tension side of the
    /// bending when N ≥ 0, the compression side otherwise; signed like N).
    pub fn normal_stress(&self, axial: f64, moment: f64) -> f64 {
        let bending = moment.abs() / self.modulus();
        let direct = axial / self.area;
        if direct >= 0.0 {
            direct + bending
        } else {
            direct - bending
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 30 × 10 mm bar: A = 300 mm², I = 10·30³/12 mm⁴, Z = 10·30²/6 mm³; its weak axis
    /// 30·10³/12 mm⁴; a crank's root under a 500 N tip load at 0.1 m: σ = 50 N·m / Z.
    #[test]
    fn a_bar_section_and_a_cranks_bending_at_its_root() {
        let s = Section::of(&Shape::Bar {
            width: 0.03,
            thickness: 0.01,
        })
        .unwrap();
        assert!((s.area - 3e-4).abs() < 1e-18);
        assert!((s.inertia - 0.01 * 0.03f64.powi(3) / 12.0).abs() < 1e-22);
        assert!((s.modulus() - 0.01 * 0.03 * 0.03 / 6.0).abs() < 1e-20);
        assert!((s.inertia_min - 0.03 * 1e-6 / 12.0).abs() < 1e-24);
        let sigma = s.normal_stress(0.0, 500.0 * 0.1);
        assert!((sigma - 50.0 / 1.5e-6).abs() < 1e-6 * sigma, "{sigma}");
        assert!((sigma - 33.333333333e6).abs() < 1.0);
    }

    #[test]
    fn round_sections() {
        let pi = std::f64::consts::PI;
        let r = Section::of(&Shape::Rod { diameter: 0.02 }).unwrap();
        assert!((r.modulus() - pi * 0.02f64.powi(3) / 32.0).abs() < 1e-18);
        assert!((r.radius_of_gyration() - 0.005).abs() < 1e-15, "r = D/4");
        let t = Section::of(&Shape::Tube {
            outer: 0.02,
            inner: 0.016,
        })
        .unwrap();
        assert!(
            (t.radius_of_gyration() - (0.02f64.powi(2) + 0.016f64.powi(2)).sqrt() / 4.0).abs()
                < 1e-15
        );
        assert!(Section::of(&Shape::Plate { thickness: 0.01 }).is_none());
    }
}
