//! Links declared by their shapes and materials (`mech_core::model::shape`): the mass, cg
//! and I_G the macro and the loader give, against closed forms written here (a triangle's
//! I_G = m (a² + b² + c²)/36, a rod's and a tube's about a diameter, a disc's m R²/2), the
//! generated struct's parameters equal to the loader's model, and the same answers on both
//! routes. The rounded bar's formula is checked against the limit of its polygons in the
//! unit tests of `shape`; the errors are compile-fail cases (`tests/ui/shape_*.rs`).

use mech::prelude::*;

mechanism! {
    /// A four-bar built from stock: a steel bar crank, an aluminium triangular plate
    /// coupler, a titanium tube rocker.
    pub struct Shaped {
        ground { O2: (0.0, 0.0), O4: (0.3, 0.0) },
        link crank {
            points { O2, A: (0.0, 0.1) },
            shape: bar(width 20 mm, thickness 8 mm), material: steel,
        },
        link coupler {
            points { A, B: (0.25, 0.2), P: (0.1, 0.3) },
            shape: plate(thickness 5 mm), material: aluminium,
        },
        link rocker {
            points { O4, B },
            shape: tube(outer 20 mm, inner 14 mm),
            material { density 4430 kg_per_m3, youngs 114 GPa, yield 880 MPa, ultimate 950 MPa, endurance 510 MPa },
        },
        joints {
            O2: revolute(ground, crank) pin 12 mm,
            A: revolute(crank, coupler) pin 10 mm double,
            B: revolute(coupler, rocker),
            O4: revolute(ground, rocker),
        },
        input: O2,
    }
}

mechanism! {
    /// A disc crank (a flywheel) on its pivot and a round connecting rod.
    pub struct DiscCrank {
        ground { O: (0.0, 0.0) },
        link wheel {
            points { O, A: (0.05, 0.0) },
            shape: disc(radius 80 mm, thickness 12 mm), material: cast_iron,
        },
        link rod {
            points { A, B: (0.25, 0.0) },
            shape: rod(diameter 10 mm), material: brass,
        },
        link slider { points { B }, mass: 0.2, cg: B },
        joints {
            O: revolute(ground, wheel),
            A: revolute(wheel, rod),
            B: revolute(rod, slider),
            guide: prismatic(ground, slider) at B along (1.0, 0.0),
        },
        input: O,
    }
}

const PI: f64 = std::f64::consts::PI;

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() <= 1e-12 * b.abs(), "{what}: {a} vs {b}");
}

/// Both routes: the generated parameters and the loader's model.
fn routes<P>(
    source: &str,
    generated: &P,
    name: &str,
    get: impl Fn(&P, &str) -> (f64, [f64; 2], f64),
    links: &[&str],
) -> Vec<(f64, [f64; 2], f64)> {
    let m = mech::Mechanism::from_rust_source(source, name).unwrap();
    links
        .iter()
        .map(|l| {
            let g = get(generated, l);
            let k = m.model().links.iter().position(|x| x.name == *l).unwrap();
            let r = &m.model().links[k];
            assert_eq!(r.mass, Some(g.0), "{l}: loader and macro");
            assert_eq!(r.inertia, g.2, "{l}");
            assert_eq!(r.cg, g.1, "{l}");
            g
        })
        .collect()
}

#[test]
fn mass_properties_of_shapes_through_the_macro_and_the_loader() {
    let source = include_str!("shapes.rs");
    let p = Shaped::new().params().clone();
    let got = routes(
        source,
        &p,
        "Shaped",
        |p, l| {
            let x = match l {
                "crank" => &p.links.crank,
                "coupler" => &p.links.coupler,
                _ => &p.links.rocker,
            };
            (x.mass, [x.cg.x, x.cg.y], x.inertia)
        },
        &["crank", "coupler", "rocker"],
    );
    // The triangle A B P of 5 mm aluminium: m = ρ T |cross|/2, cg the mean of the
    // vertices, I_G = m (a² + b² + c²)/36.
    let (a, b, c): ([f64; 2], [f64; 2], [f64; 2]) = ([0.0, 0.1], [0.25, 0.2], [0.1, 0.3]);
    let area = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs() / 2.0;
    let m = 2700.0 * 0.005 * area;
    let d2 = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
    close(got[1].0, m, "plate mass");
    close(got[1].1[0], (a[0] + b[0] + c[0]) / 3.0, "plate cg x");
    close(got[1].1[1], (a[1] + b[1] + c[1]) / 3.0, "plate cg y");
    close(
        got[1].2,
        m * (d2(a, b) + d2(b, c) + d2(c, a)) / 36.0,
        "plate I_G",
    );
    // The tube O4 B: outer solid rod less the bore, each m (3 r² + L²)/12.
    let l2 = d2([0.3, 0.0], [0.25, 0.2]);
    let rod = |d: f64| {
        let m = 4430.0 * PI * d * d / 4.0 * l2.sqrt();
        (m, m * (3.0 * d * d / 4.0 + l2) / 12.0)
    };
    let ((mo, io), (mi, ii)) = (rod(0.02), rod(0.014));
    close(got[2].0, mo - mi, "tube mass");
    close(got[2].2, io - ii, "tube I_G");
    close(got[2].1[0], 0.275, "tube cg");
    // The bar: at least the rectangle and the two end discs' mass.
    close(
        got[0].0,
        7850.0 * 0.008 * (0.1 * 0.02 + PI * 0.01 * 0.01),
        "bar mass",
    );
    close(got[0].1[1], 0.05, "bar cg");

    let p = DiscCrank::new().params().clone();
    let got = routes(
        source,
        &p,
        "DiscCrank",
        |p, l| {
            let x = if l == "wheel" {
                &p.links.wheel
            } else {
                &p.links.rod
            };
            (x.mass, [x.cg.x, x.cg.y], x.inertia)
        },
        &["wheel", "rod"],
    );
    let m = 7200.0 * 0.012 * PI * 0.08 * 0.08;
    close(got[0].0, m, "disc mass");
    close(got[0].2, m * 0.08 * 0.08 / 2.0, "disc I_G");
    assert_eq!(got[0].1, [0.0, 0.0]);
    let (m, l) = (8530.0 * PI * 0.0001 / 4.0 * 0.2, 0.2);
    close(got[1].0, m, "rod mass");
    close(got[1].2, m * (l * l / 12.0 + 0.0001 / 16.0), "rod I_G");
}

/// The shaped four-bar solves the same on both routes: I* at a few angles to 1e-12, and
/// the disc crank's I* at q = 0 includes the disc's m R²/2.
#[test]
fn shaped_mechanisms_solve_the_same_on_both_routes() {
    let source = include_str!("shapes.rs");
    let g = Shaped::new();
    let r = mech::Mechanism::from_rust_source(source, "Shaped").unwrap();
    for q in [0.3, 1.9, 4.0] {
        let (a, b) = (
            g.reduced(q).unwrap().inertia,
            OneDof::reduced(&r, q).unwrap().inertia,
        );
        close(b, a, "I*");
    }
}

/// A dimension changed at run time changes the mass properties, and so does a moved point
/// of a link made of a shape; setting the mass of such a link is refused with the fix.
#[test]
fn a_new_width_or_a_moved_point_changes_the_mass() {
    let source = include_str!("shapes.rs");
    let mut m = mech::Mechanism::from_rust_source(source, "Shaped").unwrap();
    let crank = |m: &mech::Mechanism| m.model().links[1].clone();
    let bar = |w: f64, l: f64| 7850.0 * 0.008 * (l * w + PI * w * w / 4.0);
    close(crank(&m).mass.unwrap(), bar(0.02, 0.1), "drawn");
    let before = OneDof::reduced(&m, 0.7).unwrap().inertia;
    m.set_param("links.crank.shape.width", &[0.03]).unwrap();
    close(crank(&m).mass.unwrap(), bar(0.03, 0.1), "wider");
    assert!(OneDof::reduced(&m, 0.7).unwrap().inertia > before);
    m.set_param("points.A", &[0.0, 0.12]).unwrap();
    close(crank(&m).mass.unwrap(), bar(0.03, 0.12), "longer");
    close(crank(&m).cg[1], 0.06, "the cg follows");
    let e = m
        .set_param("links.crank.mass", &[1.0])
        .unwrap_err()
        .to_string();
    assert!(e.contains("shape.<dimension>"), "{e}");
    let e = m
        .set_param("links.crank.shape.width", &[-0.01])
        .unwrap_err()
        .to_string();
    assert!(e.contains("positive length"), "{e}");
    let e = m
        .set_param("links.crank.shape.diameter", &[0.01])
        .unwrap_err()
        .to_string();
    assert!(e.contains("width, thickness"), "{e}");
}

/// Pins: single or double shear (the generated struct's model carries them for
/// `from_params`; a pin wider than its link is the compile-fail case
/// `tests/ui/shape_pin_larger_than_link.rs`).
#[test]
fn pins_are_read_on_both_routes() {
    let m = mech::Mechanism::from_rust_source(include_str!("shapes.rs"), "Shaped").unwrap();
    let pin = |name: &str| {
        m.model()
            .joints
            .iter()
            .find(|j| j.name == name)
            .unwrap()
            .pin
    };
    assert_eq!(
        pin("O2"),
        Some(mech::model::Pin {
            diameter: 0.012,
            double: false
        })
    );
    assert_eq!(
        pin("A"),
        Some(mech::model::Pin {
            diameter: 0.010,
            double: true
        })
    );
    assert_eq!(pin("B"), None);
}

/// The stadium bar of thickness T and width W = 2r over a length L, by parts written out
/// here: the rectangle L × W about its centre, each half disc about its own centroid
/// (e = 4r/(3π) out from its flat side, I = m r²/2 − m e²) moved out to L/2 + e by the
/// parallel axes: (m, I_G) = (ρ T (W L + π W²/4), ...).
fn stadium(rho: f64, t: f64, w: f64, l: f64) -> (f64, f64) {
    let r = w / 2.0;
    let (m_rect, m_half) = (rho * t * w * l, rho * t * PI * r * r / 2.0);
    let e = 4.0 * r / (3.0 * PI);
    let half = m_half * (r * r / 2.0 - e * e) + m_half * (l / 2.0 + e).powi(2);
    (
        m_rect + 2.0 * m_half,
        m_rect * (l * l + w * w) / 12.0 + 2.0 * half,
    )
}

/// The generated struct and the run-time mechanism after the same change agree on every
/// link's mass, I_G and cg and on the motor torque by d'Alembert at a few angles; returns
/// the crank's (mass, I_G, cg) and the torque at q = 0.7.
fn same_on_both_routes(g: &Shaped, r: &mech::Mechanism) -> (f64, f64, [f64; 2], f64) {
    let p = g.params();
    for (name, x) in [
        ("crank", &p.links.crank),
        ("coupler", &p.links.coupler),
        ("rocker", &p.links.rocker),
    ] {
        let k = r.model().links.iter().position(|l| l.name == name).unwrap();
        let l = &r.model().links[k];
        close(x.mass, l.mass.unwrap(), &format!("{name} mass"));
        close(x.inertia, l.inertia, &format!("{name} I_G"));
        for (a, b) in [(x.cg.x, l.cg[0]), (x.cg.y, l.cg[1])] {
            assert!(
                (a - b).abs() <= 1e-12 * l.cg[0].hypot(l.cg[1]),
                "{name} cg: {a} vs {b}"
            );
        }
    }
    let mut at = 0.0;
    for q in [0.7, 2.1, 4.4] {
        let d = g
            .kinetostatics(
                &g.kinematics(q, 12.0, -3.0).unwrap(),
                &ShapedLoads::default(),
            )
            .unwrap()
            .driver;
        let motion = r.kinematics(&[q], &[12.0], &[-3.0]).unwrap();
        let rd = r.kinetostatics(&motion, &r.loads()).unwrap().driver[0];
        close(d, rd, &format!("driver torque at q = {q}"));
        if q == 0.7 {
            at = d;
        }
    }
    let c = &p.links.crank;
    (c.mass, c.inertia, [c.cg.x, c.cg.y], at)
}

/// A shaped link's dimensions through the generated `Params` (`shapes`): a new bar width,
/// then a moved point, then another density go through `from_params`, which recomputes the
/// mass, I_G and cg with `mech_core`'s function; each equals the run-time
/// `Mechanism::set_param` of the same change and the closed form of the stadium (to 1e-12),
/// and the motor torque by d'Alembert follows.
#[test]
fn from_params_recomputes_the_mass_of_a_shaped_link() {
    let source = include_str!("shapes.rs");
    let mut r = mech::Mechanism::from_rust_source(source, "Shaped").unwrap();
    let drawn = same_on_both_routes(&Shaped::new(), &r);
    let (m, i) = stadium(7850.0, 0.008, 0.02, 0.1);
    close(drawn.0, m, "drawn mass");
    close(drawn.1, i, "drawn I_G");

    // A wider bar: the mass, I_G and the torque change, the cg stays at the middle.
    let mut p = Shaped::new().params().clone();
    p.shapes.crank.set_dimension("width", 0.03).unwrap();
    let g = Shaped::from_params(p).unwrap();
    r.set_param("links.crank.shape.width", &[0.03]).unwrap();
    let wider = same_on_both_routes(&g, &r);
    let (m, i) = stadium(7850.0, 0.008, 0.03, 0.1);
    close(wider.0, m, "wider mass");
    close(wider.1, i, "wider I_G");
    assert_eq!(wider.2, [0.0, 0.05], "the cg at the middle of O2 A");
    assert!(
        (wider.3 - drawn.3).abs() > 1e-3 * drawn.3.abs(),
        "{} vs {}",
        wider.3,
        drawn.3
    );

    // A moved crank pin: the bar is longer, its cg moves with it; the coupler plate
    // (A, B, P) changes too.
    let mut p = g.params().clone();
    p.points.A = Vector2::new(0.0, 0.12);
    let g = Shaped::from_params(p).unwrap();
    r.set_param("points.A", &[0.0, 0.12]).unwrap();
    let longer = same_on_both_routes(&g, &r);
    let (m, i) = stadium(7850.0, 0.008, 0.03, 0.12);
    close(longer.0, m, "longer mass");
    close(longer.1, i, "longer I_G");
    close(longer.2[1], 0.06, "the cg follows");

    // Another material: the mass and I_G scale with ρ (the run-time route has no
    // parameter for the density: the closed form alone).
    let mut p = g.params().clone();
    p.shapes.crank.material = mech::model::shape::material_named("aluminium").unwrap();
    let g = Shaped::from_params(p).unwrap();
    let (m, i) = stadium(2700.0, 0.008, 0.03, 0.12);
    close(g.params().links.crank.mass, m, "aluminium mass");
    close(g.params().links.crank.inertia, i, "aluminium I_G");
}

/// What `from_params` refuses on a shaped link, each with the fix: a mass written by hand
/// (the shape gives it), a non-positive dimension, a dimension the shape does not have, a
/// density that is not positive, points that cannot carry the shape.
#[test]
fn from_params_refuses_numbers_the_shape_gives() {
    let p = Shaped::new().params().clone();
    let mut bad = p.clone();
    bad.links.crank.mass = 1.0;
    let e = Shaped::from_params(bad).unwrap_err().to_string();
    assert!(
        e.contains("link `crank` is declared by its shape") && e.contains("`shapes.crank`"),
        "{e}"
    );
    let mut bad = p.clone();
    bad.links.coupler.cg.x += 1e-3;
    let e = Shaped::from_params(bad).unwrap_err().to_string();
    assert!(e.contains("link `coupler`"), "{e}");
    // The flywheel of a shaped link stays a parameter.
    let mut fly = p.clone();
    fly.links.crank.flywheel = 0.01;
    assert!(Shaped::from_params(fly).is_ok());

    let mut bad = p.clone();
    let e = bad
        .shapes
        .crank
        .set_dimension("width", -0.01)
        .unwrap_err()
        .to_string();
    assert!(e.contains("positive length"), "{e}");
    assert_eq!(bad.shapes.crank, p.shapes.crank, "unchanged on error");
    let e = bad
        .shapes
        .crank
        .set_dimension("diameter", 0.01)
        .unwrap_err()
        .to_string();
    assert!(e.contains("a `bar` has width, thickness"), "{e}");
    bad.shapes.crank.shape = mech::model::shape::Shape::Bar {
        width: 0.0,
        thickness: 0.008,
    };
    let e = Shaped::from_params(bad).unwrap_err().to_string();
    assert!(
        e.contains("link `crank`") && e.contains("positive length"),
        "{e}"
    );

    let mut bad = p.clone();
    bad.shapes.rocker.material.density = -4430.0;
    let e = Shaped::from_params(bad).unwrap_err().to_string();
    assert!(
        e.contains("link `rocker`") && e.contains("shapes.rocker.material.density"),
        "{e}"
    );

    // A plate is a polygon: the crank's two points enclose no area.
    let mut bad = p.clone();
    bad.shapes.crank.shape = mech::model::shape::Shape::Plate { thickness: 0.008 };
    let e = Shaped::from_params(bad).unwrap_err().to_string();
    assert!(
        e.contains("link `crank`") && e.contains("at least three"),
        "{e}"
    );
}
