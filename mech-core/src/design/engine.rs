//! Engines with several cylinders (SPEC 3g, issue 31, `docs/theory.md` §14): one
//! crankshaft with a crank train per cylinder at its phase angle, in-line, V or boxer, the
//! cylinders in parallel planes along the shaft; the mechanism file of such an engine
//! ([`Engine::to_mech`]) and the classical table of its primary and secondary shaking
//! forces and couples, from the exact solution ([`balance_table`]) beside the textbook's
//! first-order values ([`Engine::first_order`]).
//!
//! Geometry. The crankshaft turns counter-clockwise about the origin O by the input q
//! (rad). Cylinder i's axis is the unit vector eᵢ = (cos βᵢ, sin βᵢ) through O; its crank
//! pin (crank radius r, m) is at the angle β₁ + cₖ + q, cₖ the throw of its pin measured
//! from cylinder 1's axis at q = 0; the cylinder's own crank angle is
//! θᵢ = q + β₁ + cₖ − βᵢ (top dead centre at θᵢ = 0). The piston, of reciprocating mass
//! m (kg; the crank and the rods massless, the rotating masses taken as balanced), is at
//! xᵢ = r cos θᵢ + √(l² − r² sin² θᵢ) along eᵢ (rod l, m), in the plane zᵢ along the shaft
//! (m). With λ = r/l the textbook's first-order shaking force of a cylinder is
//! −m ẍᵢ eᵢ ≈ m r ω² (cos θᵢ + λ cos 2θᵢ) eᵢ, and its couple about the transverse axes
//! (Mx, My) = zᵢ (−F_y, F_x) ([`crate::kernel::energy::Shaking`]).

use crate::design::balance::{shaking_cycle, Harmonic};
use crate::runtime::mechanism::Mechanism;
use crate::MechError;
use std::f64::consts::{PI, TAU};

/// How the cylinders stand around the crankshaft.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Layout {
    /// In-line: every cylinder vertical (β = 90°), one crank pin each.
    Inline,
    /// V: two banks at ±bank/2 from the vertical (rad); the two cylinders of each pair (the
    /// left bank's first) share one crank pin and its plane.
    Vee {
        /// The angle between the banks, rad, in (0, π).
        bank: f64,
    },
    /// Boxer (flat): horizontal cylinders, alternately on the right (β = 0) and the left
    /// (β = π), one crank pin each.
    Boxer,
}

/// A counterweight on the crankshaft: a point mass (kg) at `radius` (m) from the axis, at
/// the angle `angle` (rad, counter-clockwise from cylinder 1's axis at q = 0), in the
/// plane `plane` along the shaft (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrankWeight {
    /// Mass, kg.
    pub mass: f64,
    /// Distance from the shaft's axis, m.
    pub radius: f64,
    /// Angle from cylinder 1's axis at q = 0, rad.
    pub angle: f64,
    /// Axial position, m.
    pub plane: f64,
}

/// An engine: its layout, cylinders, crank throws and numbers (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Engine {
    /// The layout.
    pub layout: Layout,
    /// The number of cylinders.
    pub cylinders: usize,
    /// The crank throws cₖ (rad, from cylinder 1's axis, counter-clockwise), one per crank
    /// pin ([`Engine::pins`]).
    pub throws: Vec<f64>,
    /// The firing order the throws came from (cylinders numbered from 1), if any.
    pub firing: Option<Vec<usize>>,
    /// The crank radius r, m.
    pub radius: f64,
    /// The connecting rod's length l, m.
    pub rod: f64,
    /// The reciprocating mass m of each cylinder (at the piston), kg.
    pub mass: f64,
    /// The distance between neighbouring crank pins along the shaft, m.
    pub spacing: f64,
    /// Counterweights on the crankshaft.
    pub counterweights: Vec<CrankWeight>,
}

/// The standard firing order of an in-line engine of n cylinders (four-stroke, even
/// firing): 1-3-2, 1-3-4-2, 1-2-4-5-3, 1-5-3-6-2-4, else 1-2-…-n; `None` for n = 2, whose
/// classical layout is the 180° crank (uneven firing).
pub fn standard_firing(n: usize) -> Option<Vec<usize>> {
    match n {
        2 => None,
        3 => Some(vec![1, 3, 2]),
        4 => Some(vec![1, 3, 4, 2]),
        5 => Some(vec![1, 2, 4, 5, 3]),
        6 => Some(vec![1, 5, 3, 6, 2, 4]),
        _ => Some((1..=n).collect()),
    }
}

/// A firing order written `1-3-4-2` (or with commas): a permutation of 1..=n starting
/// anywhere; an error otherwise.
pub fn parse_firing(text: &str, n: usize) -> Result<Vec<usize>, MechError> {
    let order: Vec<usize> = text
        .split(['-', ','])
        .map(|s| {
            s.trim().parse::<usize>().map_err(|_| {
                MechError::InvalidInput(format!(
                    "firing order `{text}`: write the cylinders' numbers in firing order, e.g. 1-3-4-2"
                ))
            })
        })
        .collect::<Result<_, _>>()?;
    let mut seen = vec![false; n + 1];
    let ok = order.len() == n
        && order.iter().all(|&c| {
            let fresh = (1..=n).contains(&c) && !seen[c];
            if fresh {
                seen[c] = true;
            }
            fresh
        });
    if !ok {
        return Err(MechError::InvalidInput(format!(
            "firing order `{text}`: give each of the {n} cylinders 1..{n} once"
        )));
    }
    Ok(order)
}

/// The angle brought into [0, 2π).
fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if (TAU - w) < 1e-12 {
        0.0
    } else {
        w
    }
}

impl Engine {
    /// An engine of `layout` with `cylinders` cylinders and the default throws: in-line,
    /// those of [`standard_firing`] (n = 2: 0°, 180°); V, the in-line throws of its
    /// n/2 pins, but the cross-plane 0°, 90°, 270°, 180° of a V8; boxer, each opposed pair p
    /// (cylinders 2p + 1, 2p + 2) on the in-line throws ψₚ of n/2 pins, ψₚ and ψₚ + 180°
    /// (both pistons at top dead centre together). The numbers: r = 45 mm, l = 150 mm,
    /// m = 0.5 kg, pin spacing 90 mm. Errors: no cylinder, an odd V or boxer, a bank angle
    /// outside (0°, 180°).
    pub fn new(layout: Layout, cylinders: usize) -> Result<Engine, MechError> {
        if cylinders == 0 {
            return Err(MechError::InvalidInput(
                "an engine needs at least one cylinder".into(),
            ));
        }
        if let Layout::Vee { bank } = layout {
            if !(bank > 0.0 && bank < PI) {
                return Err(MechError::InvalidInput(format!(
                    "bank angle {}°: give the angle between the banks of a V, between 0° and 180° (a boxer is `boxer`)",
                    bank.to_degrees()
                )));
            }
        }
        if layout != Layout::Inline && !cylinders.is_multiple_of(2) {
            return Err(MechError::InvalidInput(format!(
                "a V or boxer engine has its cylinders in pairs: {cylinders} is odd"
            )));
        }
        let inline_throws = |n: usize| -> Vec<f64> {
            match standard_firing(n) {
                None => vec![0.0, PI],
                Some(f) => throws_inline(&f),
            }
        };
        let (throws, firing) = match layout {
            Layout::Inline => (inline_throws(cylinders), standard_firing(cylinders)),
            Layout::Vee { .. } if cylinders == 8 => (
                [0.0, 90.0, 270.0, 180.0].map(f64::to_radians).to_vec(),
                None,
            ),
            Layout::Vee { .. } => (inline_throws(cylinders / 2), None),
            Layout::Boxer => (
                inline_throws(cylinders / 2)
                    .into_iter()
                    .flat_map(|p| [p, wrap(p + PI)])
                    .collect(),
                None,
            ),
        };
        let mut e = Engine {
            layout,
            cylinders,
            throws,
            firing,
            radius: 0.045,
            rod: 0.150,
            mass: 0.5,
            spacing: 0.090,
            counterweights: Vec::new(),
        };
        if e.firing.is_none() {
            e.firing = e.even_firing();
        }
        Ok(e)
    }

    /// An even four-stroke firing order of the crank as it is, if it has one: cylinder i
    /// is at top dead centre at q = tᵢ = βᵢ − β₁ − cₖ (mod 360°) and fires at tᵢ or
    /// tᵢ + 360°; the order is even when these can be chosen, cylinder 1 at 0, to fill every
    /// multiple of 720°/n once. The first such choice, cylinder by cylinder, the earlier turn
    /// first; `None` for an uneven crank (a 180° twin, a 90° V-twin).
    pub fn even_firing(&self) -> Option<Vec<usize>> {
        let n = self.cylinders;
        let interval = 2.0 * TAU / n as f64;
        let tdc: Vec<f64> = (0..n)
            .map(|i| wrap(self.axis(i) - self.axis(0) - self.throws[self.pin(i)]))
            .collect();
        fn place(i: usize, tdc: &[f64], interval: f64, slots: &mut Vec<Option<usize>>) -> bool {
            if i == tdc.len() {
                return true;
            }
            let turns: &[f64] = if i == 0 { &[0.0] } else { &[0.0, TAU] };
            for &turn in turns {
                let x = tdc[i] + turn;
                let k = (x / interval).round();
                if (x - k * interval).abs() > 1e-9 || k < 0.0 || k as usize >= slots.len() {
                    continue;
                }
                let k = k as usize;
                if slots[k].is_none() {
                    slots[k] = Some(i);
                    if place(i + 1, tdc, interval, slots) {
                        return true;
                    }
                    slots[k] = None;
                }
            }
            false
        }
        let mut slots = vec![None; n];
        place(0, &tdc, interval, &mut slots)
            .then(|| slots.into_iter().map(|c| c.unwrap_or(0) + 1).collect())
    }

    /// The number of crank pins: n/2 for a V, else n.
    pub fn pins(&self) -> usize {
        match self.layout {
            Layout::Vee { .. } => self.cylinders / 2,
            _ => self.cylinders,
        }
    }

    /// The crank pin of cylinder i (from 0).
    pub fn pin(&self, i: usize) -> usize {
        match self.layout {
            Layout::Vee { .. } => i / 2,
            _ => i,
        }
    }

    /// The point of the drawing that stands for crank pin k: the first pin with the same
    /// throw (pins in one line along the shaft are one point of the plane; their rods keep
    /// their own planes).
    fn pin_point(&self, k: usize) -> usize {
        let same = |a: f64, b: f64| {
            let d = wrap(a - b);
            d < 1e-9 || TAU - d < 1e-9
        };
        (0..k)
            .find(|&j| same(self.throws[j], self.throws[k]))
            .unwrap_or(k)
    }

    /// The axis angle βᵢ of cylinder i (from 0), rad: in-line π/2; V π/2 ± bank/2 (the
    /// left, +, first); boxer 0 and π alternately.
    pub fn axis(&self, i: usize) -> f64 {
        match self.layout {
            Layout::Inline => PI / 2.0,
            Layout::Vee { bank } => {
                PI / 2.0
                    + if i.is_multiple_of(2) {
                        bank / 2.0
                    } else {
                        -bank / 2.0
                    }
            }
            Layout::Boxer => {
                if i.is_multiple_of(2) {
                    0.0
                } else {
                    PI
                }
            }
        }
    }

    /// The plane zᵢ of cylinder i (from 0), m: its pin k's, (k − (P − 1)/2) × spacing for P
    /// pins, the shaft centred on z = 0.
    pub fn plane(&self, i: usize) -> f64 {
        (self.pin(i) as f64 - (self.pins() as f64 - 1.0) / 2.0) * self.spacing
    }

    /// The crank angle θᵢ = q + β₁ + cₖ − βᵢ of cylinder i (from 0) at the input q, rad.
    pub fn crank_angle(&self, i: usize, q: f64) -> f64 {
        q + self.axis(0) + self.throws[self.pin(i)] - self.axis(i)
    }

    /// Set the throws (rad, one per pin), and the firing order to [`Engine::even_firing`];
    /// an error when their number is not the pins'.
    pub fn with_throws(mut self, throws: &[f64]) -> Result<Engine, MechError> {
        if throws.len() != self.pins() {
            return Err(MechError::InvalidInput(format!(
                "{} phase angles for {} crank pins: give one throw angle per crank pin ({} for this {})",
                throws.len(),
                self.pins(),
                self.pins(),
                self.describe()
            )));
        }
        if throws.iter().any(|t| !t.is_finite()) {
            return Err(MechError::InvalidInput(
                "the phase angles must be finite".into(),
            ));
        }
        self.throws = throws.iter().map(|&t| wrap(t)).collect();
        self.firing = self.even_firing();
        Ok(self)
    }

    /// Set the throws from a four-stroke firing order (cylinders from 1, a permutation of
    /// 1..=n, even firing every 720°/n): the cylinder fired k-th reaches its top dead centre
    /// at q = k·720°/n, so its pin's throw is cₖ = βᵢ − β₁ − k·720°/n (mod 360°). A V's two
    /// cylinders on one pin must agree; an error otherwise.
    pub fn with_firing(mut self, firing: &[usize]) -> Result<Engine, MechError> {
        let n = self.cylinders;
        let text = firing
            .iter()
            .map(|c| c.to_string())
            .collect::<Vec<_>>()
            .join("-");
        parse_firing(&text, n)?;
        let interval = 2.0 * TAU / n as f64;
        let mut throws: Vec<Option<f64>> = vec![None; self.pins()];
        for (k, &c) in firing.iter().enumerate() {
            let i = c - 1;
            let t = wrap(self.axis(i) - self.axis(0) - k as f64 * interval);
            let slot = &mut throws[self.pin(i)];
            match *slot {
                Some(old) if (wrap(old - t + 1e-9) - 1e-9).abs() > 1e-9 => {
                    return Err(MechError::InvalidInput(format!(
                        "firing order {text}: cylinders {} and {} share crank pin {} but would need throws {:.1}° and {:.1}°; give the throws instead",
                        2 * self.pin(i) + 1,
                        2 * self.pin(i) + 2,
                        self.pin(i) + 1,
                        old.to_degrees(),
                        t.to_degrees()
                    )))
                }
                _ => *slot = Some(t),
            }
        }
        self.throws = throws.into_iter().map(|t| t.unwrap_or(0.0)).collect();
        self.firing = Some(firing.to_vec());
        Ok(self)
    }

    /// "in-line 4", "90° V8", "boxer 2".
    pub fn describe(&self) -> String {
        match self.layout {
            Layout::Inline => format!("in-line {}", self.cylinders),
            Layout::Vee { bank } => format!("{}° V{}", fmt(bank.to_degrees()), self.cylinders),
            Layout::Boxer => format!("boxer {}", self.cylinders),
        }
    }

    /// Check the numbers: r, l, m, the spacing positive and finite, r < l, the
    /// counterweights' masses ≥ 0.
    fn check(&self) -> Result<(), MechError> {
        for (what, v) in [
            ("crank radius", self.radius),
            ("rod length", self.rod),
            ("reciprocating mass", self.mass),
            ("cylinder spacing", self.spacing),
        ] {
            if !(v > 0.0 && v.is_finite()) {
                return Err(MechError::InvalidInput(format!(
                    "the {what} must be positive, got {v}"
                )));
            }
        }
        if self.radius >= self.rod {
            return Err(MechError::InvalidInput(format!(
                "the crank radius {} m must be shorter than the rod {} m",
                self.radius, self.rod
            )));
        }
        if self.throws.len() != self.pins() {
            return Err(MechError::InvalidInput(format!(
                "{} phase angles for {} crank pins",
                self.throws.len(),
                self.pins()
            )));
        }
        for w in &self.counterweights {
            if !(w.mass >= 0.0 && w.mass.is_finite()) {
                return Err(MechError::InvalidInput(format!(
                    "a counterweight of negative mass ({} kg): give its mass, 0 or more",
                    w.mass
                )));
            }
        }
        Ok(())
    }

    /// The mechanism file of the engine, named `name` (a Rust type name): the crankshaft
    /// (massless, with its counterweights in their planes; pins of the same throw are one
    /// point `A` of the drawing, named after the first) on the ground pivot O, and per
    /// cylinder a massless rod and a piston of mass m in the cylinder's plane, on a guide
    /// along its axis, drawn at q = 0; the input is the main bearing, q the crank's turn
    /// from the drawing (`from` the first pin's angle).
    pub fn to_mech(&self, name: &str) -> Result<String, MechError> {
        self.check()?;
        let mut t = format!(
            "/// {}: {} crank pins at {}, {} mm crank, {} mm rod, {} kg reciprocating mass per\n/// cylinder, {} mm between the pins; drawn at q = 0 (cylinder 1 at top dead centre).\n",
            self.describe(),
            self.pins(),
            self.throws
                .iter()
                .map(|c| format!("{}°", fmt(c.to_degrees())))
                .collect::<Vec<_>>()
                .join(", "),
            fmt(self.radius * 1e3),
            fmt(self.rod * 1e3),
            fmt(self.mass),
            fmt(self.spacing * 1e3)
        );
        if let Some(f) = &self.firing {
            t += &format!(
                "/// Firing order {}.\n",
                f.iter()
                    .map(|c| c.to_string())
                    .collect::<Vec<_>>()
                    .join("-")
            );
        }
        t += &format!(
            "pub struct {name} {{\n    consts {{ r: {} mm, l: {} mm, mp: {} kg }},\n    ground {{ O: (0.0, 0.0) }},\n    link crank {{\n        points {{ O",
            fmt(self.radius * 1e3),
            fmt(self.rod * 1e3),
            fmt(self.mass)
        );
        let b1 = self.axis(0);
        for (k, c) in self.throws.iter().enumerate() {
            if self.pin_point(k) == k {
                t += &format!(
                    ", A{}: O + polar(r, {} deg)",
                    k + 1,
                    fmt((b1 + c).to_degrees())
                );
            }
        }
        t += " },\n";
        for w in &self.counterweights {
            let a = b1 + w.angle;
            t += &format!(
                "        counterweight: ({} kg, at ({}, {}), plane: {} mm),\n",
                fmt(w.mass),
                fmt(w.radius * a.cos()),
                fmt(w.radius * a.sin()),
                fmt(w.plane * 1e3)
            );
        }
        t += "    },\n";
        for i in 0..self.cylinders {
            let (n, k) = (i + 1, self.pin_point(self.pin(i)) + 1);
            let z = fmt(self.plane(i) * 1e3);
            t += &format!(
                "    link rod{n} {{ points {{ A{k}, B{n}: circle_line(A{k}, l, O, {} deg, forward) }}, plane: {z} mm }},\n    link piston{n} {{ points {{ B{n} }}, mass: mp, cg: B{n}, plane: {z} mm }},\n",
                fmt(self.axis(i).to_degrees())
            );
        }
        t += "    joints {\n        main: revolute(ground, crank) at O,\n";
        for i in 0..self.cylinders {
            let (n, k) = (i + 1, self.pin_point(self.pin(i)) + 1);
            let b = self.axis(i);
            t += &format!(
                "        pin{n}: revolute(crank, rod{n}) at A{k},\n        wrist{n}: revolute(rod{n}, piston{n}) at B{n},\n        bore{n}: prismatic(ground, piston{n}) at B{n} along ({}, {}),\n",
                fmt(b.cos()),
                fmt(b.sin())
            );
        }
        // q = 0 in the drawing: the crank's angle (O → its first pin) is β₁ + c₁ there.
        t += &format!(
            "    }},\n    input: main from {} deg,\n}}\n",
            fmt((b1 + self.throws[0]).to_degrees())
        );
        Ok(t)
    }

    /// The textbook's first-order harmonic of order 1 (primary) or 2 (secondary) of the
    /// shaking at ω = 1 rad/s, as the [`Harmonic`] of [`crate::design::balance`]: with
    /// F(q) = Σᵢ m r kₙ cos(n θᵢ) eᵢ, k₁ = 1, k₂ = λ = r/l, a = Σᵢ m r kₙ cos(n θᵢ(0)) eᵢ and
    /// b = −Σᵢ m r kₙ sin(n θᵢ(0)) eᵢ (N), and the couples (Mx, My) = Σᵢ zᵢ (−F_yᵢ, F_xᵢ)
    /// (N·m); the moment about z is zero (the forces pass through the axis). Other orders
    /// are zero to first order.
    pub fn first_order(&self, order: usize) -> Harmonic {
        let k = match order {
            1 => 1.0,
            2 => self.radius / self.rod,
            _ => 0.0,
        };
        let mut h = Harmonic {
            order,
            ..Harmonic::default()
        };
        for i in 0..self.cylinders {
            let (s, c) = (order as f64 * self.crank_angle(i, 0.0)).sin_cos();
            let (ey, ex) = self.axis(i).sin_cos();
            let amp = self.mass * self.radius * k;
            let z = self.plane(i);
            for (slot, coef) in [(0, c), (1, -s)] {
                let (fx, fy) = (amp * coef * ex, amp * coef * ey);
                h.fx[slot] += fx;
                h.fy[slot] += fy;
                h.mx[slot] -= z * fy;
                h.my[slot] += z * fx;
            }
        }
        h
    }
}

/// A number for the mechanism file: at most 12 decimals, no trailing zeros.
fn fmt(x: f64) -> String {
    let s = format!("{:.12}", x);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    match s {
        "-0" | "" => "0".into(),
        _ => s.to_string(),
    }
}

/// One line of the classical table: exact and first-order amplitudes of the primary and
/// secondary shaking forces and couples, each over its classical unit.
#[derive(Clone, Debug, PartialEq)]
pub struct BalanceRow {
    /// The engine.
    pub engine: String,
    /// The firing order as written in the table ("1-3-4-2"), "uneven" when there is none.
    pub firing: String,
    /// The crank throws as written in the table ("0/180/180/0°").
    pub throws: String,
    /// The primary force's amplitude over m r ω²: [exact, first order].
    pub primary_force: [f64; 2],
    /// The secondary force's amplitude over m r ω² λ: [exact, first order].
    pub secondary_force: [f64; 2],
    /// The primary couple's amplitude over m r ω² a (a the pin spacing): [exact, first
    /// order].
    pub primary_couple: [f64; 2],
    /// The secondary couple's amplitude over m r ω² λ a: [exact, first order].
    pub secondary_couple: [f64; 2],
    /// The harmonics of the exact shaking, orders 1 and 2, at ω = 1 rad/s (N, N·m).
    pub exact: [Harmonic; 2],
}

/// The classical balance table's line of `engine`: the exact shaking of its mechanism
/// file ([`Engine::to_mech`], the run-time [`Mechanism`]) over one turn at ω = 1 rad/s in
/// `steps` samples ([`shaking_cycle`]), its harmonics of orders 1 and 2
/// ([`crate::design::balance::ShakingCycle::harmonic`]) and their amplitudes
/// ([`Harmonic::force_amplitude`], [`Harmonic::couple_amplitude`]), beside the first-order
/// values ([`Engine::first_order`]), each over m r ω² (forces) or m r ω² a (couples), and λ
/// for the secondary ones. The Fourier sums are exact for the harmonics below steps/2.
pub fn balance_table(engine: &Engine, steps: usize) -> Result<BalanceRow, MechError> {
    if steps < 8 {
        return Err(MechError::InvalidInput(format!(
            "{steps} steps: give at least 8 over the turn"
        )));
    }
    let m = Mechanism::from_dsl(&engine.to_mech("Engine")?)?;
    let cycle = shaking_cycle(&m, (0.0, TAU, steps), &[0.0], &[1.0])?;
    let exact = [cycle.harmonic(1), cycle.harmonic(2)];
    let first = [engine.first_order(1), engine.first_order(2)];
    let unit = engine.mass * engine.radius;
    let lambda = engine.radius / engine.rod;
    let a = engine.spacing;
    let pair = |f: &dyn Fn(&Harmonic) -> f64, k: usize, scale: f64| {
        [f(&exact[k]) / scale, f(&first[k]) / scale]
    };
    Ok(BalanceRow {
        engine: engine.describe(),
        firing: match &engine.firing {
            Some(f) => f
                .iter()
                .map(|c| c.to_string())
                .collect::<Vec<_>>()
                .join("-"),
            None => "uneven".into(),
        },
        throws: engine
            .throws
            .iter()
            .map(|c| fmt(c.to_degrees()))
            .collect::<Vec<_>>()
            .join("/")
            + "°",
        primary_force: pair(&Harmonic::force_amplitude, 0, unit),
        secondary_force: pair(&Harmonic::force_amplitude, 1, unit * lambda),
        primary_couple: pair(&Harmonic::couple_amplitude, 0, unit * a),
        secondary_couple: pair(&Harmonic::couple_amplitude, 1, unit * lambda * a),
        exact,
    })
}

/// The classical table as text: one line per row, the firing order, each amplitude as
/// "exact (first order)", and the throws; forces over m r ω² (primary) and m r ω² λ (secondary), couples over m r ω² a
/// and m r ω² λ a.
pub fn table_text(rows: &[BalanceRow]) -> String {
    let mut t = format!(
        "{:<16} {:<16} {:>17} {:>17} {:>17} {:>17}  {}\n",
        "engine", "firing order", "primary F", "secondary F", "primary M", "secondary M", "throws"
    );
    t += &format!(
        "{:<16} {:<16} {:>17} {:>17} {:>17} {:>17}\n",
        "", "", "[m r ω²]", "[m r ω² r/l]", "[m r ω² a]", "[m r ω² a r/l]"
    );
    let cell = |v: [f64; 2]| {
        let c = |x: f64| if x.abs() < 5e-10 { 0.0 } else { x };
        format!("{:.4} ({:.4})", c(v[0]), c(v[1]))
    };
    for r in rows {
        t += &format!(
            "{:<16} {:<16} {:>17} {:>17} {:>17} {:>17}  {}\n",
            r.engine,
            r.firing,
            cell(r.primary_force),
            cell(r.secondary_force),
            cell(r.primary_couple),
            cell(r.secondary_couple),
            r.throws
        );
    }
    t
}

/// Two crankshaft counterweights of equal mass at `radius` (m) in the planes `planes`
/// (m, z₁ ≠ z₂), opposite each other, that cancel a primary couple which rotates with the
/// crank, (Mx, My) = a cos q + b sin q with b = a turned by +90° (`h`, the exact harmonic of
/// order 1 at ω = 1 rad/s): the pair's inertia forces cancel and its couple is
/// (z₂ − z₁) m_c ρ ω² (cos(q + γ + 90°), sin(q + γ + 90°)) for the weight in z₂ at the angle
/// γ (the one in z₁ at γ + 180°), so m_c = |a|/(|z₂ − z₁| ρ) and γ + 90° the direction of
/// −a (for z₂ > z₁). The angles are from cylinder 1's axis ([`CrankWeight`]). No couple
/// (|a|, |b| ≤ 1e-12 m r a): two weights of zero mass. An error when the couple does not
/// rotate forward (b ≠ a turned by 90° within 1e-6 |a|: a boxer twin's, which swings).
pub fn primary_couple_counterweights(
    engine: &Engine,
    h: &Harmonic,
    radius: f64,
    planes: (f64, f64),
) -> Result<[CrankWeight; 2], MechError> {
    let (z1, z2) = planes;
    if !(radius > 0.0 && radius.is_finite() && z1 != z2 && (z2 - z1).is_finite()) {
        return Err(MechError::InvalidInput(
            "give a positive radius and two different planes for the counterweights".into(),
        ));
    }
    let a = [h.mx[0], h.my[0]];
    let b = [h.mx[1], h.my[1]];
    let size = a[0].hypot(a[1]).max(b[0].hypot(b[1]));
    let (lo, hi) = if z2 > z1 { (z1, z2) } else { (z2, z1) };
    if size <= 1e-12 * engine.mass * engine.radius * engine.spacing {
        // No primary couple (to rounding): nothing to cancel.
        return Ok([lo, hi].map(|plane| CrankWeight {
            mass: 0.0,
            radius,
            angle: 0.0,
            plane,
        }));
    }
    if (b[0] + a[1]).hypot(b[1] - a[0]) > 1e-6 * size {
        return Err(MechError::InvalidInput(
            "the primary couple does not rotate with the crank at a constant magnitude: two crankshaft counterweights cannot cancel it".into(),
        ));
    }
    let mass = size / ((hi - lo) * radius);
    let gamma = (-a[1]).atan2(-a[0]) - PI / 2.0 - engine.axis(0);
    Ok([
        CrankWeight {
            mass,
            radius,
            angle: wrap(gamma + PI),
            plane: lo,
        },
        CrankWeight {
            mass,
            radius,
            angle: wrap(gamma),
            plane: hi,
        },
    ])
}

/// The throws of an in-line engine from its firing order: cylinder c fired k-th (from 0) has
/// cₖ = −k·720°/n (mod 360°).
fn throws_inline(firing: &[usize]) -> Vec<f64> {
    let n = firing.len();
    let mut t = vec![0.0; n];
    for (k, &c) in firing.iter().enumerate() {
        t[c - 1] = wrap(-(k as f64) * 2.0 * TAU / n as f64);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn firing_orders_give_the_classical_throws() {
        let deg = |e: &Engine| {
            e.throws
                .iter()
                .map(|t| t.to_degrees().round())
                .collect::<Vec<_>>()
        };
        let e4 = Engine::new(Layout::Inline, 4).unwrap();
        assert_eq!(deg(&e4), vec![0.0, 180.0, 180.0, 0.0]);
        let e6 = Engine::new(Layout::Inline, 6).unwrap();
        assert_eq!(deg(&e6), vec![0.0, 240.0, 120.0, 120.0, 240.0, 0.0]);
        let b4 = Engine::new(Layout::Boxer, 4).unwrap();
        assert_eq!(deg(&b4), vec![0.0, 180.0, 180.0, 0.0]);
        assert!(parse_firing("1-3-3-2", 4).is_err());
        assert!(e4.clone().with_throws(&[0.0, 1.0]).is_err());
        assert!(Engine::new(Layout::Vee { bank: 0.0 }, 8).is_err());
        assert!(Engine::new(Layout::Boxer, 3).is_err());
        // A 90° V-twin on one pin cannot fire every 360°: the pin would need 0° and 270°.
        let v2 = Engine::new(Layout::Vee { bank: PI / 2.0 }, 2).unwrap();
        let e = v2.with_firing(&[1, 2]).unwrap_err().to_string();
        assert!(e.contains("share crank pin 1"), "{e}");
        // In-line 4 fired 1-2-4-3, by cₖ = −k·180° (cylinder 1 k = 0, 2 k = 1, 4 k = 2,
        // 3 k = 3): the same crank as 1-3-4-2.
        let f = Engine::new(Layout::Inline, 4)
            .unwrap()
            .with_firing(&[1, 2, 4, 3])
            .unwrap();
        assert_eq!(deg(&f), vec![0.0, 180.0, 180.0, 0.0]);
        // The even firing order found for a crank gives that crank back.
        for e in [
            Engine::new(Layout::Vee { bank: PI / 2.0 }, 8).unwrap(),
            Engine::new(
                Layout::Vee {
                    bank: 2.0 * PI / 3.0,
                },
                6,
            )
            .unwrap(),
            Engine::new(Layout::Boxer, 4).unwrap(),
            Engine::new(Layout::Boxer, 6).unwrap(),
            Engine::new(Layout::Inline, 6).unwrap(),
        ] {
            let order = e
                .even_firing()
                .unwrap_or_else(|| panic!("{}", e.describe()));
            if e.layout != Layout::Inline {
                assert_eq!(e.firing.as_ref(), Some(&order));
            }
            let again = e.clone().with_firing(&order).unwrap();
            assert_eq!(deg(&again), deg(&e), "{} {order:?}", e.describe());
        }
        // A 60° V6 on three shared pins fires 60° and 180° apart: uneven.
        let v6 = Engine::new(Layout::Vee { bank: PI / 3.0 }, 6).unwrap();
        assert_eq!(v6.firing, None);
        let v8 = Engine::new(Layout::Vee { bank: PI / 2.0 }, 8).unwrap();
        assert_eq!(v8.firing, Some(vec![1, 5, 4, 2, 6, 8, 7, 3]));
        assert_eq!(Engine::new(Layout::Inline, 2).unwrap().even_firing(), None);
        assert_eq!(
            Engine::new(Layout::Vee { bank: PI / 2.0 }, 2)
                .unwrap()
                .even_firing(),
            None
        );
    }
}
