//! Points from dimensions (`docs/conventions.md#dimensions`): the constructions a
//! designer draws with compass and ruler, evaluated with the closed-form kernels the
//! solvers use ([`crate::kernel::dyad::circle_circle`], [`crate::kernel::dyad::circle_line`]).
//!
//! - `polar(r, θ)`: the vector r (cos θ, sin θ);
//! - `circle_circle(c1, r1, c2, r2, left|right)`: the intersection of two circles on the
//!   left (counter-clockwise side) or right of the directed line c1 → c2;
//! - `circle_line(c, r, p, θ, forward|backward)`: the intersection of the circle (c, r)
//!   with the line through p at direction θ, further along (or back along) that direction;
//! - `along(d)`, `local(u, v)`: a point in a link's own frame, the x axis from its first
//!   point P₀ to its second P₁: P₀ + u e + v perp(e), e = (P₁ − P₀)/|P₁ − P₀|.
//!
//! Each returns the point or a message with the numbers that say why there is none.

use crate::kernel::dyad;
use crate::kernel::link_state::{perp, V2};

/// Which of two intersections: +1 = `left` / `forward`, −1 = `right` / `backward`.
pub type Branch = Option<f64>;

/// The branch words of a construction: (word for +1, word for −1).
pub const CIRCLE_CIRCLE_WORDS: (&str, &str) = ("left", "right");
/// The branch words of `circle_line`.
pub const CIRCLE_LINE_WORDS: (&str, &str) = ("forward", "backward");

/// Relative gap under which two intersections are one (a tangency): no branch word needed.
const TANGENT: f64 = 1e-9;

fn fmt(x: f64) -> String {
    format!("{:.6}", x)
        .trim_end_matches('0')
        .trim_end_matches('.')
        .to_string()
}

fn point(p: V2) -> String {
    format!("({}, {})", fmt(p.x), fmt(p.y))
}

/// The vector of length `r` (m) at angle `theta` (rad): r (cos θ, sin θ).
pub fn polar(r: f64, theta: f64) -> V2 {
    let (s, c) = theta.sin_cos();
    V2::new(r * c, r * s)
}

/// Both intersections of the circles, or one when they touch; the message gives
/// |c1 c2|, r1 and r2 when they do not meet.
fn circles(c1: V2, r1: f64, c2: V2, r2: f64, names: (&str, &str)) -> Result<(V2, V2), String> {
    let d = (c2 - c1).norm();
    if !(r1 > 0.0 && r2 > 0.0) {
        return Err(format!(
            "the radii must be positive, got {} m and {} m",
            fmt(r1),
            fmt(r2)
        ));
    }
    let meet = |sign| dyad::circle_circle(c1, r1 * r1, c2, r2 * r2, sign);
    match (meet(1.0), meet(-1.0)) {
        (Ok(l), Ok(r)) => Ok((l, r)),
        _ if d == 0.0 => Err(format!("the circles of {} and {} have the same centre {}: they do not cross at a point", names.0, names.1, point(c1))),
        _ if d > r1 + r2 => Err(format!(
            "the circles do not meet: |{} {}| = {} m > {} m + {} m (too far apart for these lengths)",
            names.0,
            names.1,
            fmt(d),
            fmt(r1),
            fmt(r2)
        )),
        _ => Err(format!(
            "the circles do not meet: |{} {}| = {} m < |{} m − {} m| (one circle lies inside the other)",
            names.0,
            names.1,
            fmt(d),
            fmt(r1),
            fmt(r2)
        )),
    }
}

/// Pick one of two intersections `(plus, minus)` by `branch`; with no branch word the
/// two must coincide (a tangency), else the message lists both.
fn pick(
    (plus, minus): (V2, V2),
    branch: Branch,
    words: (&str, &str),
    scale: f64,
) -> Result<V2, String> {
    match branch {
        Some(s) if s > 0.0 => Ok(plus),
        Some(_) => Ok(minus),
        None if (plus - minus).norm() <= TANGENT * scale.max(f64::MIN_POSITIVE) => Ok(plus),
        None => Err(format!(
            "two points satisfy these lengths: {} ({}) and {} ({}); add `{}` or `{}` as the last argument",
            point(plus),
            words.0,
            point(minus),
            words.1,
            words.0,
            words.1
        )),
    }
}

/// The intersection of the circle (c1, r1) with the circle (c2, r2) on the side
/// `branch` of the directed line c1 → c2 (+1 = left). `names` name c1 and c2 in messages.
pub fn circle_circle(
    c1: V2,
    r1: f64,
    c2: V2,
    r2: f64,
    branch: Branch,
    names: (&str, &str),
) -> Result<V2, String> {
    let both = circles(c1, r1, c2, r2, names)?;
    pick(both, branch, CIRCLE_CIRCLE_WORDS, r1.max(r2))
}

/// The intersection of the circle (c, r) with the line through p at angle `theta` (rad),
/// the one further along the direction when `branch` = +1.
pub fn circle_line(
    c: V2,
    r: f64,
    p: V2,
    theta: f64,
    branch: Branch,
    centre: &str,
) -> Result<V2, String> {
    if !(r > 0.0) {
        return Err(format!("the radius must be positive, got {} m", fmt(r)));
    }
    let u = polar(1.0, theta);
    match (
        dyad::circle_line(c, r * r, p, u, 1.0),
        dyad::circle_line(c, r * r, p, u, -1.0),
    ) {
        (Ok(f), Ok(b)) => pick((f, b), branch, CIRCLE_LINE_WORDS, r),
        _ => {
            let dist = crate::kernel::link_state::cross(u, c - p).abs();
            Err(format!(
                "the circle of {centre} (radius {} m) does not reach the line through {} at {}°: the line is {} m from {centre}",
                fmt(r),
                point(p),
                fmt(theta.to_degrees()),
                fmt(dist)
            ))
        }
    }
}

/// The point (u, v) in the frame of a link whose first two points are `p0`, `p1`: x
/// along p0 → p1, y to its left.
pub fn local(p0: V2, p1: V2, u: f64, v: f64) -> Result<V2, String> {
    let d = p1 - p0;
    let n = d.norm();
    if !(n > 0.0) {
        return Err(format!(
            "the link's first two points coincide at {}: its frame has no direction",
            point(p0)
        ));
    }
    let e = d / n;
    Ok(p0 + e * u + perp(e) * v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::measure::within;

    #[test]
    fn circles_on_each_side() {
        // A four-bar's B: |AB| = 0.5, |O4 B| = 0.5 with A = (0, 0), O4 = (0.6, 0).
        let (a, o4) = (V2::new(0.0, 0.0), V2::new(0.6, 0.0));
        let l = circle_circle(a, 0.5, o4, 0.5, Some(1.0), ("A", "O4")).unwrap();
        let r = circle_circle(a, 0.5, o4, 0.5, Some(-1.0), ("A", "O4")).unwrap();
        // measured worst 5.6e-17 (be05608); 100×
        assert!(
            within((l - V2::new(0.3, 0.4)).norm(), 1e-15)
                && within((r - V2::new(0.3, -0.4)).norm(), 1e-15)
        );
        let e = circle_circle(a, 0.5, o4, 0.5, None, ("A", "O4")).unwrap_err();
        assert!(
            e.contains("(0.3, 0.4) (left) and (0.3, -0.4) (right)")
                && e.contains("add `left` or `right`"),
            "{e}"
        );
        // Touching circles need no word.
        assert!(
            within(
                (circle_circle(a, 0.3, o4, 0.3, None, ("A", "O4")).unwrap() - V2::new(0.3, 0.0))
                    .norm(),
                1e-15
            ) // measured worst 0 (be05608); exact; a few ulps
        );
        let e = circle_circle(
            V2::new(0.0, 0.0),
            0.6,
            V2::new(1.52, 0.0),
            0.8,
            Some(1.0),
            ("A", "O4"),
        )
        .unwrap_err();
        assert_eq!(e, "the circles do not meet: |A O4| = 1.52 m > 0.6 m + 0.8 m (too far apart for these lengths)");
        let e = circle_circle(a, 0.1, o4, 0.8, Some(1.0), ("A", "O4")).unwrap_err();
        assert!(e.contains("0.6 m < |0.1 m − 0.8 m|"), "{e}");
    }

    #[test]
    fn circle_and_line() {
        // A slider-crank's B: |AB| = 0.5 from A = (0.3, 0.4) on the x axis.
        let a = V2::new(0.3, 0.4);
        let f = circle_line(a, 0.5, V2::zeros(), 0.0, Some(1.0), "A").unwrap();
        let b = circle_line(a, 0.5, V2::zeros(), 0.0, Some(-1.0), "A").unwrap();
        // measured worst 1.1e-16, 5.6e-17 (be05608); 100×
        assert!(
            within((f - V2::new(0.6, 0.0)).norm(), 1e-15)
                && within((b - V2::new(0.0, 0.0)).norm(), 1e-15)
        );
        let e = circle_line(a, 0.3, V2::zeros(), 0.0, Some(1.0), "A").unwrap_err();
        assert!(
            e.contains("radius 0.3 m") && e.contains("the line is 0.4 m from A"),
            "{e}"
        );
    }

    #[test]
    fn link_frame() {
        let p = local(V2::new(1.0, 1.0), V2::new(1.0, 3.0), 0.5, 0.25).unwrap();
        // measured worst 0 (be05608); exact; a few ulps
        assert!(within((p - V2::new(0.75, 1.5)).norm(), 1e-15));
        assert!(local(V2::new(1.0, 1.0), V2::new(1.0, 1.0), 0.5, 0.0).is_err());
    }
}
