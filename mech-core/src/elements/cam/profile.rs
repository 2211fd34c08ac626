//! The cam profile (`docs/theory.md` §13): the follower's face, the pitch and contact
//! curves in the cam's frame, the pressure angle, the radius of curvature and the undercut
//! checks, for a translating follower or a rocker, from a [`MotionLaw`].

use std::f64::consts::TAU;

use crate::elements::cam::law::MotionLaw;
use crate::kernel::link_state::{cross, perp, rotate, V2};

/// The follower's contact face ([`Profile`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Face {
    /// A knife edge: the profile is the pitch curve.
    Knife,
    /// A roller of this radius (m): the profile is the pitch curve offset inward by it.
    Roller(f64),
    /// A flat face perpendicular to the follower's axis.
    Flat,
}

/// One point of a cam's profile (`docs/theory.md` §13), in the cam's own frame (the cam
/// turning counter-clockwise by θ; at θ = 0 the frame is the profile's axis frame: the
/// follower's axis (translating) or the cam's centre to the pitch point (oscillating) along
/// +y, a translating follower's axis offset by e along +x).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfilePoint {
    /// The cam angle θ, rad.
    pub theta: f64,
    /// The pitch point (the roller's centre, the knife's edge; for a flat face the
    /// face's foot on the axis, or for a rocker the face's point that touched the base
    /// circle in the drawing), cam frame, m.
    pub pitch: [f64; 2],
    /// The cam surface's contact point, cam frame, m.
    pub contact: [f64; 2],
    /// The pressure angle φ (rad): between the direction the follower's pitch point
    /// moves (along the axis; a rocker's: perpendicular to its arm) and the common normal
    /// at the contact; zero for a translating flat face.
    pub pressure_angle: f64,
    /// The radius of curvature of the cam surface at the contact (m, > 0 convex,
    /// < 0 concave); for a roller the pitch curve's less the roller's radius.
    pub curvature_radius: f64,
}

/// An oscillating follower (a rocker) of a [`Profile`]: pinned to the cam's carrier at its
/// pivot A and turned by the law's lift ψ(θ), an angle, from the drawing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rocker {
    /// The pivot A in the profile's axis frame (the cam's centre O at the origin, +y
    /// towards the pitch point P of the drawing), m.
    pub pivot: [f64; 2],
    /// σ = ±1: the rocker turns by σψ (counter-clockwise positive), the sense that moves
    /// its pitch point away from the cam's centre: σ = −sign(A_x).
    pub sign: f64,
}

/// A cam's profile (`docs/theory.md` §13): base circle R_b (to the cam surface), the
/// follower (translating with offset e, or a [`Rocker`]), its face, and the motion law
/// s(θ) (a length; a rocker's an angle ψ(θ)).
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// The motion law.
    pub law: MotionLaw,
    /// R_b, the base circle's radius (m).
    pub base_radius: f64,
    /// e, the offset of a translating follower's axis from the cam's centre (m; 0 for a
    /// flat face and for a rocker).
    pub offset: f64,
    /// The follower's face.
    pub face: Face,
    /// An oscillating follower's pivot; `None` for a translating one.
    pub rocker: Option<Rocker>,
}

/// The follower against the cam at one cam angle ([`Profile::contact`]), in the profile's
/// axis frame (fixed to the carrier: not turned with the cam).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// The law's (s, s′, s″, s‴) at θ (m or rad, per radian of cam angle).
    pub law: [f64; 4],
    /// The pitch point, m.
    pub pitch: V2,
    /// The contact point K, m.
    pub contact: V2,
    /// The common normal n at K (unit, from the cam towards the follower).
    pub normal: V2,
    /// The pressure angle φ, rad ([`ProfilePoint::pressure_angle`]).
    pub pressure_angle: f64,
    /// The cam surface's radius of curvature at K, m ([`ProfilePoint::curvature_radius`]).
    pub curvature_radius: f64,
}

impl Profile {
    /// The roller's radius (0 for a knife or a flat face), m.
    pub fn roller(&self) -> f64 {
        match self.face {
            Face::Roller(r) => r,
            _ => 0.0,
        }
    }

    /// The pitch point F(θ) of a knife or roller follower in the axis frame, its
    /// derivatives F′, F″ per unit cam angle, and the unit direction d̂ a lift moves it in.
    /// Translating: F = (e, d + s), d = √(R_p² − e²), R_p = R_b + r, F′ = (0, s′),
    /// F″ = (0, s″), d̂ = (0, 1). A rocker with pivot A: w = R(σψ)(P₀ − A), P₀ = (0, R_p),
    /// F = A + w, F′ = σψ′ perp(w), F″ = σψ″ perp(w) − ψ′² w, d̂ = σ perp(w)/|w|.
    #[inline]
    fn pitch_motion(&self, law: [f64; 4]) -> [V2; 4] {
        let [s, s1, s2, _] = law;
        let rp = self.base_radius + self.roller();
        match self.rocker {
            None => {
                let e = self.offset;
                [
                    V2::new(e, (rp * rp - e * e).sqrt() + s),
                    V2::new(0.0, s1),
                    V2::new(0.0, s2),
                    V2::new(0.0, 1.0),
                ]
            }
            Some(k) => {
                let a = V2::new(k.pivot[0], k.pivot[1]);
                let (sn, cs) = (k.sign * s).sin_cos();
                let w = rotate(V2::new(cs, sn), V2::new(0.0, rp) - a);
                let jw = perp(w) * k.sign;
                [a + w, jw * s1, jw * s2 - w * (s1 * s1), jw / w.norm()]
            }
        }
    }

    /// The follower against the cam at cam angle θ ([`Contact`]).
    ///
    /// Knife and roller: seen from the cam (turned back by θ) the pitch point is
    /// P(θ) = R(−θ) F(θ), so P′ = R(−θ) v and P″ = R(−θ) a with v = F′ − perp(F),
    /// a = F″ − 2 perp(F′) − F (`Profile::pitch_motion` gives F, F′, F″). The pitch curve,
    /// traversed clockwise, has the radius of curvature ρ = −|v|³ / (v × a) (> 0 where
    /// convex); its outward normal n = perp(v)/|v| is the common normal, the contact is
    /// K = F − r n and the pressure angle is the angle from d̂ to n. A translating flat face
    /// (e = 0) touches the cam where the face's points move along it: K = (s′, R_b + s),
    /// ρ = R_b + s + s″. A rocker's flat face (tangent to the base circle at P₀ = (0, R_b)
    /// in the drawing) is the line m·x = p with m = R(σψ)(0, 1), p = m·A + R_b − A_y;
    /// seen from the cam its normal turns by β′ = σψ′ − 1 per unit cam angle, so the
    /// envelope (the cam surface) touches it at K = p m + p_β perp(m) with
    /// p_β = g w, g = σψ′/(σψ′ − 1), w = perp(m)·A, and ρ = p + p_ββ,
    /// p_ββ = (g′ w + g w′)/β′, g′ = −σψ″/β′², w′ = −σψ′ (m·A) (K is the foot of the
    /// perpendicular from the relative instant centre g A: Aronhold–Kennedy).
    pub fn contact(&self, theta: f64) -> Contact {
        let law = self.law.eval(theta);
        let [s, s1, s2, _] = law;
        match (self.face, self.rocker) {
            (Face::Flat, None) => {
                let y = self.base_radius + s;
                Contact {
                    law,
                    pitch: V2::new(0.0, y),
                    contact: V2::new(s1, y),
                    normal: V2::new(0.0, 1.0),
                    pressure_angle: 0.0,
                    curvature_radius: y + s2,
                }
            }
            (Face::Flat, Some(k)) => {
                let sg = k.sign;
                let a = V2::new(k.pivot[0], k.pivot[1]);
                let (sn, cs) = (sg * s).sin_cos();
                let rot = V2::new(cs, sn);
                let m = V2::new(-sn, cs);
                let jm = perp(m);
                let p = m.dot(&a) + self.base_radius - a.y;
                let w = jm.dot(&a);
                let beta1 = sg * s1 - 1.0;
                let g = sg * s1 / beta1;
                let g1 = -sg * s2 / (beta1 * beta1);
                let w1 = -sg * s1 * m.dot(&a);
                let contact = m * p + jm * (g * w);
                let arm = contact - a;
                let dir = perp(arm) * (sg / arm.norm());
                Contact {
                    law,
                    pitch: a + rotate(rot, V2::new(0.0, self.base_radius) - a),
                    contact,
                    normal: m,
                    pressure_angle: cross(dir, m).atan2(dir.dot(&m)),
                    curvature_radius: p + (g1 * w + g * w1) / beta1,
                }
            }
            _ => {
                let r = self.roller();
                let [f, f1, f2, dir] = self.pitch_motion(law);
                let v = f1 - perp(f);
                let acc = f2 - perp(f1) * 2.0 - f;
                let speed = v.norm();
                let n = perp(v) / speed;
                Contact {
                    law,
                    pitch: f,
                    contact: f - n * r,
                    normal: n,
                    pressure_angle: cross(dir, n).atan2(dir.dot(&n)),
                    curvature_radius: -speed * speed * speed / cross(v, acc) - r,
                }
            }
        }
    }

    /// The contact point K and the common normal n at cam angle θ, in the axis frame, as
    /// [`Profile::contact`] gives them (bit for bit) but without the pressure angle and the
    /// radius of curvature: what the cam pair's reactions need
    /// ([`crate::elements::cam::cam_reactions`]), an `atan2` and a division less.
    #[inline]
    pub fn contact_normal(&self, theta: f64) -> (V2, V2) {
        self.contact_normal_of(theta, self.law.eval(theta))
    }

    /// [`Profile::contact_normal`] at cam angle θ with the law's values there, `law`
    /// (`self.law.eval(θ)`, which a motion keeps: [`crate::elements::cam::CamLaw`]), given.
    #[inline]
    pub fn contact_normal_of(&self, theta: f64, law: [f64; 4]) -> (V2, V2) {
        match (self.face, self.rocker) {
            (Face::Flat, None) => {
                let [s, s1, _, _] = law;
                (V2::new(s1, self.base_radius + s), V2::new(0.0, 1.0))
            }
            (Face::Flat, Some(_)) => {
                let c = self.contact(theta);
                (c.contact, c.normal)
            }
            _ => {
                let r = self.roller();
                let [f, f1, _, _] = self.pitch_motion(law);
                let v = f1 - perp(f);
                let n = perp(v) / v.norm();
                (f - n * r, n)
            }
        }
    }

    /// The profile at cam angle θ, in the cam's frame: [`Profile::contact`] turned back
    /// by θ.
    pub fn at(&self, theta: f64) -> ProfilePoint {
        let c = self.contact(theta);
        let (sn, cs) = (-theta).sin_cos();
        let back = |v: V2| {
            let r = rotate(V2::new(cs, sn), v);
            [r.x, r.y]
        };
        ProfilePoint {
            theta,
            pitch: back(c.pitch),
            contact: back(c.contact),
            pressure_angle: c.pressure_angle,
            curvature_radius: c.curvature_radius,
        }
    }
}

/// The design figures of a cam over a revolution ([`Profile::check`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileCheck {
    /// The largest |pressure angle| (rad) and the cam angle where it occurs (rad).
    pub max_pressure_angle: (f64, f64),
    /// The smallest radius of curvature of the cam surface where it is convex (m), and
    /// where; a concave cam has no limit there (∞ when the surface is nowhere convex).
    pub min_convex_radius: (f64, f64),
    /// True when the profile is undercut: the pitch curve's convex radius is smaller than
    /// the roller's (the cam surface's radius ≤ 0 somewhere it should be convex), or a flat
    /// face's R_b + s + s″ ≤ 0 (a cusp).
    pub undercut: bool,
    /// The first sampled cam angle (rad) where the profile does not exist (a contact
    /// point or radius that is not finite: a flat-faced rocker turning as fast as the
    /// cam, σψ′ = 1, has no envelope there); `None` when it exists at every sample.
    pub missing: Option<f64>,
}

/// The design figures in one line: the largest pressure angle and where, the smallest
/// convex radius of the surface (mm) and where, undercut or not, and where the profile
/// does not exist if it does not somewhere.
impl std::fmt::Display for ProfileCheck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "largest pressure angle {:.2}° at θ = {:.1}°; smallest convex radius of the surface {:.3} mm at θ = {:.1}°; {}",
            self.max_pressure_angle.0.to_degrees(),
            self.max_pressure_angle.1.to_degrees(),
            self.min_convex_radius.0 * 1e3,
            self.min_convex_radius.1.to_degrees(),
            if self.undercut { "UNDERCUT (a cusp)" } else { "not undercut" }
        )?;
        match self.missing {
            Some(t) => write!(f, "; no profile at θ = {:.1}°", t.to_degrees()),
            None => Ok(()),
        }
    }
}

impl Profile {
    /// The profile at `n` cam angles evenly over the revolution, from θ = 0.
    pub fn points(&self, n: usize) -> Vec<ProfilePoint> {
        (0..n).map(|k| self.at(TAU * k as f64 / n as f64)).collect()
    }

    /// The maximum pressure angle, the minimum convex radius of curvature, whether the
    /// profile is undercut and where it is missing, sampled at `n` cam angles
    /// ([`ProfileCheck`]).
    pub fn check(&self, n: usize) -> ProfileCheck {
        let r = self.roller();
        let mut out = ProfileCheck {
            max_pressure_angle: (0.0, 0.0),
            min_convex_radius: (f64::INFINITY, 0.0),
            undercut: false,
            missing: None,
        };
        for p in self.points(n) {
            if !(p.contact.iter().all(|x| x.is_finite()) && p.curvature_radius.is_finite()) {
                out.missing = out.missing.or(Some(p.theta));
            }
            if p.pressure_angle.abs() > out.max_pressure_angle.0 {
                out.max_pressure_angle = (p.pressure_angle.abs(), p.theta);
            }
            // The pitch curve's radius: convex where > 0.
            let pitch = p.curvature_radius + r;
            if pitch > 0.0 && p.curvature_radius < out.min_convex_radius.0 {
                out.min_convex_radius = (p.curvature_radius, p.theta);
            }
            let cusp = match self.face {
                Face::Flat => p.curvature_radius <= 0.0,
                Face::Roller(_) => pitch > 0.0 && p.curvature_radius <= 0.0,
                Face::Knife => false,
            };
            out.undercut |= cusp;
        }
        out
    }

    /// The names of [`Profile::row`]'s columns (SI: rad, m; the lift and its derivatives
    /// per radian of cam angle, in m or, for a rocker, rad).
    pub const COLUMNS: [&'static str; 10] = [
        "theta",
        "lift",
        "lift_velocity",
        "lift_acceleration",
        "pitch_x",
        "pitch_y",
        "contact_x",
        "contact_y",
        "pressure_angle",
        "curvature_radius",
    ];

    /// One row of the profile's table at cam angle θ ([`Profile::COLUMNS`]): θ, the law's
    /// s, s′, s″, the pitch and contact points in the cam's frame, the pressure angle and
    /// the surface's radius of curvature.
    pub fn row(&self, theta: f64) -> [f64; 10] {
        let p = self.at(theta);
        let [s, s1, s2, _] = self.law.eval(theta);
        [
            theta,
            s,
            s1,
            s2,
            p.pitch[0],
            p.pitch[1],
            p.contact[0],
            p.contact[1],
            p.pressure_angle,
            p.curvature_radius,
        ]
    }

    /// [`Profile::row`] at `n` cam angles evenly over the revolution, from θ = 0.
    pub fn table(&self, n: usize) -> Vec<[f64; 10]> {
        (0..n)
            .map(|k| self.row(TAU * k as f64 / n as f64))
            .collect()
    }

    /// The cam surface as CSV, one contact point per row: `theta_deg,x_m,y_m`
    /// (the cam's frame), `n` points over the revolution.
    pub fn to_csv(&self, n: usize) -> String {
        let mut out = String::from("theta_deg,x_m,y_m\n");
        for p in self.points(n) {
            out.push_str(&format!(
                "{:.6},{:.9},{:.9}\n",
                p.theta.to_degrees(),
                p.contact[0],
                p.contact[1]
            ));
        }
        out
    }

    /// The cam surface as the `d` attribute of an SVG path (a closed polygon through `n`
    /// contact points), in mm with y up turned to SVG's y down.
    pub fn svg_path(&self, n: usize) -> String {
        let mut d = String::new();
        for (k, p) in self.points(n).iter().enumerate() {
            d.push_str(&format!(
                "{}{:.4},{:.4} ",
                if k == 0 { "M" } else { "L" },
                p.contact[0] * 1e3,
                -p.contact[1] * 1e3
            ));
        }
        d.push('Z');
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elements::cam::law::{Law, Segment};

    /// `contact_normal` is `contact`'s contact point and normal bit for bit, for every
    /// face, translating (with an offset) and oscillating, over a turn and beyond.
    #[test]
    fn contact_normal_is_contact() {
        let seg = |law, start: f64, end: f64, from, to| Segment {
            law,
            start: start.to_radians(),
            end: end.to_radians(),
            from,
            to,
        };
        let law = |lift: f64| {
            MotionLaw::from_segments(vec![
                seg(Law::Cycloidal, 0.0, 120.0, 0.0, lift),
                seg(Law::Dwell, 120.0, 180.0, lift, lift),
                seg(Law::Poly345, 180.0, 270.0, lift, 0.0),
                seg(Law::Dwell, 270.0, 360.0, 0.0, 0.0),
            ])
            .unwrap()
        };
        let rocker = Some(Rocker {
            pivot: [0.06, 0.03],
            sign: -1.0,
        });
        let mut profiles = Vec::new();
        for face in [Face::Knife, Face::Roller(0.01), Face::Flat] {
            let offset = if face == Face::Flat { 0.0 } else { 0.01 };
            profiles.push(Profile {
                law: law(0.015),
                base_radius: 0.04,
                offset,
                face,
                rocker: None,
            });
            profiles.push(Profile {
                law: law(0.2),
                base_radius: 0.03,
                offset: 0.0,
                face,
                rocker,
            });
        }
        for p in &profiles {
            for k in -40..80 {
                let theta = 0.1 * k as f64 + 0.013;
                let c = p.contact(theta);
                let (contact, normal) = p.contact_normal(theta);
                for (a, b) in [
                    (contact.x, c.contact.x),
                    (contact.y, c.contact.y),
                    (normal.x, c.normal.x),
                    (normal.y, c.normal.y),
                ] {
                    assert_eq!(a.to_bits(), b.to_bits(), "{:?} at {theta}", p.face);
                }
            }
        }
    }
}
