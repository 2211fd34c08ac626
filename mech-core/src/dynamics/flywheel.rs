//! Flywheel design of a one-DOF machine in steady state (`docs/theory.md` §7),
//! written once over [`OneDof`].
//!
//! A [`Cycle`] is the machine with its actions over one period λ of its steady state
//! (2π, or 4π for a four-stroke engine), from the input position q0: the loads as a
//! function of q and the driver action (N·m on a revolute input) as a function of q.
//! With M*(q) the reduced moment of every action (driver included, gravity included) and
//! I*(q) the machine's reduced inertia (Zhukovski), a flywheel of constant inertia I on the
//! input gives, by the energy theorem,
//!
//! ```text
//! S(q) = ∫_{q0}^{q} M* dq = ½ (I + I*(q)) ω(q)² − ½ (I + I*(q0)) ω0²          (J)
//! ```
//!
//! - steady state needs a zero net work W = S(q0 + λ) ([`Cycle::check_periodic`],
//!   [`MechError::NotPeriodic`]); [`Cycle::balancing_torque`] is the constant torque
//!   T = −W/λ on the input that makes it zero, [`Cycle::balanced`] adds it to the driver;
//! - ω_a = (ω_max + ω_min)/2, ε = (ω_max − ω_min)/ω_a, so ω_max,min = ω_a (1 ± ε/2);
//! - approximate inertia (I ≫ I*): I = (S_max − S_min)/(ε ω_a²) ([`Cycle::approximate`]);
//! - exact inertia, Wittenbauer ([`Cycle::wittenbauer`]): with F(q) = 2 S(q)/ω_a² and
//!   z = (ω/ω_a)² = (F(q) + C)/(I + I*(q)), C = (I + I*(q0)) z0, the bound z ≤ (1 + ε/2)² =: a
//!   touches at the tangent point of slope a to the F–I* curve and z ≥ (1 − ε/2)² =: b at
//!   the tangent of slope b; both lines pass through P = (−I, −C), hence
//!   `I = (max_q (F − a I*) − min_q (F − b I*)) / (a − b)`, `C = a I − max_q (F − a I*)`;
//! - ω(q) for any flywheel ([`Cycle::steady_state`], [`Cycle::speed`]) and the check by
//!   time integration of the machine with the flywheel ([`Cycle::simulate`], with
//!   [`crate::dynamics::ode::Dop853`] and the event and dense output of [`crate::dynamics::ode::solve`]).
//!
//! Numerics: the cycle is cut into panels (at most λ/720 wide) whose ends include the
//! caller's breakpoints (where the loads are not smooth); S at the panel ends comes from
//! adaptive Gauss–Kronrod quadrature ([`crate::dynamics::gauss_kronrod`], relative
//! tolerance 1e-13), and S(q) inside a panel from the same quadrature over the rest. The
//! extremes over the cycle (tangent points, S_max, S_min, ω_max, ω_min) are bracketed on the
//! panel ends and located by golden-section search to 1e-13 rad: the flywheel inertias are
//! accurate to about 1e-12 relative, not read off a drawing.

use crate::dynamics::ode::{self, Dense, Dop853, Event, Stats};
use crate::dynamics::{gauss_kronrod, speed_from_energy};
use crate::solvers::traits::OneDof;
use crate::solvers::zhukovski::{self, Reduced};
use crate::MechError;

/// Panels per cycle: the panel width is at most λ / `PANELS_PER_CYCLE`.
pub const PANELS_PER_CYCLE: usize = 720;

/// Relative tolerance of the cycle's work quadratures.
pub const QUADRATURE_RTOL: f64 = 1e-13;

/// [`Cycle::check_periodic`] accepts |W| ≤ `PERIODIC_TOLERANCE` × the gross work Σ|∫M* dq|
/// of the panels.
pub const PERIODIC_TOLERANCE: f64 = 1e-9;

/// The loads of a cycle as a function of the input position q.
type LoadsFn<'a, M> =
    Box<dyn Fn(f64) -> Result<<M as crate::solvers::traits::Machine>::Loads, MechError> + 'a>;

/// A panel end: position, work and reduced inertia there.
#[derive(Clone, Copy, Debug)]
struct Node {
    q: f64,
    work: f64,
    inertia: f64,
}

/// A one-DOF machine with its actions over one cycle of its steady state (see the module
/// documentation), and the table of the work S(q) on the cycle's panels.
pub struct Cycle<'a, M: OneDof> {
    machine: &'a M,
    loads: LoadsFn<'a, M>,
    driver: Box<dyn Fn(f64) -> f64 + 'a>,
    start: f64,
    period: f64,
    breakpoints: Vec<f64>,
    nodes: Vec<Node>,
    /// Absolute tolerance of the quadratures per unit of q, N·m.
    atol_rate: f64,
    /// Σ over the panels of |∫ M* dq|, J.
    gross_work: f64,
}

/// One sample of a cycle ([`Cycle::sample`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CyclePoint {
    /// Input position q, rad.
    pub q: f64,
    /// Reduced moment M*(q) of every action, driver included, N·m.
    pub moment: f64,
    /// Reduced inertia I*(q), kg·m².
    pub inertia: f64,
    /// dI*/dq, kg·m²/rad.
    pub inertia_derivative: f64,
    /// Accumulated work S(q) = ∫_{q0}^{q} M* dq, J.
    pub work: f64,
}

/// An extreme of a function of (S, I*) over the cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Extreme {
    /// Where, rad (in [q0, q0 + λ)).
    pub q: f64,
    /// S(q), J.
    pub work: f64,
    /// I*(q), kg·m².
    pub inertia: f64,
    /// The function's value there.
    pub value: f64,
}

/// A tangent of the Wittenbauer diagram: the line F = slope · I*_axis + intercept touching
/// the curve (I*(q), F(q)) at `point`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tangent {
    /// tan θ = (1 ± ε/2)², the squared speed ratio (ω/ω_a)² reached at the tangent point.
    pub slope: f64,
    /// F at I* = 0, rad: max (or min) over the cycle of F(q) − slope · I*(q), plus 0.
    pub intercept: f64,
    /// Position of the tangent point, rad.
    pub q: f64,
    /// I* at the tangent point, kg·m².
    pub reduced_inertia: f64,
    /// F = 2 S / ω_a² at the tangent point, kg·m² (F has the units of an inertia).
    pub f: f64,
}

/// The speed extremes of a periodic motion over one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpeedRange {
    /// ω_max, rad/s.
    pub omega_max: f64,
    /// Where ω_max is reached, rad.
    pub q_max: f64,
    /// ω_min, rad/s.
    pub omega_min: f64,
    /// Where ω_min is reached, rad.
    pub q_min: f64,
    /// ω_a = (ω_max + ω_min)/2, rad/s.
    pub omega_mean: f64,
    /// ε = (ω_max − ω_min)/ω_a.
    pub irregularity: f64,
}

impl SpeedRange {
    /// From the extremes (rad/s) and where they are reached (rad): ω_a and ε.
    pub fn new(omega_max: f64, q_max: f64, omega_min: f64, q_min: f64) -> Self {
        let omega_mean = 0.5 * (omega_max + omega_min);
        SpeedRange {
            omega_max,
            q_max,
            omega_min,
            q_min,
            omega_mean,
            irregularity: (omega_max - omega_min) / omega_mean,
        }
    }
}

/// A periodic motion of the machine with a flywheel: ω(q)² = 2 (E + S(q)) / (I + I*(q)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SteadyState {
    /// Flywheel inertia I added to I* on the input, kg·m².
    pub flywheel: f64,
    /// Kinetic energy at q0, E = ½ (I + I*(q0)) ω0², J.
    pub energy: f64,
    /// ω_max, ω_min, ω_a, ε of the motion.
    pub speeds: SpeedRange,
}

/// The exact flywheel by Wittenbauer's method ([`Cycle::wittenbauer`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wittenbauer {
    /// Flywheel inertia I, kg·m²: the abscissa of P is −I. Negative when the machine's
    /// own inertia already keeps the irregularity below ε.
    pub inertia: f64,
    /// C = (I + I*(q0)) (ω0/ω_a)², kg·m²: the ordinate of P is −C.
    pub c: f64,
    /// The tangent of slope (1 + ε/2)² (ω_max).
    pub upper: Tangent,
    /// The tangent of slope (1 − ε/2)² (ω_min).
    pub lower: Tangent,
    /// The motion with this flywheel: ω_a and ε as requested, E = C ω_a²/2.
    pub state: SteadyState,
}

/// The approximate flywheel (I ≫ I*, [`Cycle::approximate`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Approximate {
    /// I = (S_max − S_min)/(ε ω_a²), kg·m².
    pub inertia: f64,
    /// Largest accumulated work over the cycle, J, and where (rad).
    pub s_max: f64,
    /// Where S_max is reached, rad.
    pub q_s_max: f64,
    /// Smallest accumulated work, J.
    pub s_min: f64,
    /// Where S_min is reached, rad.
    pub q_s_min: f64,
}

/// The maximum fluctuation of energy of a cycle ([`Cycle::fluctuation`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fluctuation {
    /// ΔE = S_max − S_min, J.
    pub energy: f64,
    /// The largest accumulated work S_max, J.
    pub s_max: f64,
    /// Where S_max is reached, rad.
    pub q_s_max: f64,
    /// The smallest accumulated work S_min, J.
    pub s_min: f64,
    /// Where S_min is reached, rad.
    pub q_s_min: f64,
}

/// Both flywheels for one (ω_a, ε) ([`Cycle::flywheel`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Flywheel {
    /// Mean speed ω_a, rad/s.
    pub omega_mean: f64,
    /// Irregularity ε.
    pub irregularity: f64,
    /// Wittenbauer's exact inertia and its diagram.
    pub exact: Wittenbauer,
    /// The approximate inertia.
    pub approximate: Approximate,
}

/// One simulated cycle ([`Cycle::simulate`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CycleSimulation {
    /// ω_max, ω_min (located on the dense output), ω_a, ε reached.
    pub speeds: SpeedRange,
    /// Speed at the start q0, rad/s.
    pub omega_start: f64,
    /// Speed on return to q0 + λ, rad/s (= `omega_start` in steady state).
    pub omega_end: f64,
    /// Duration of the cycle, s.
    pub duration: f64,
    /// The integrator's work.
    pub stats: Stats,
}

impl<'a, M: OneDof> Cycle<'a, M> {
    /// The cycle [start, start + period] of `machine` (rad) with `loads(q)` and the driver
    /// action `driver(q)` (N·m on a revolute input, N on a prismatic one); `breakpoints`
    /// (rad, strictly inside the cycle) are where the actions are not smooth (a valve
    /// opening, the start of a cut): panels end there. Computes the table of S(q).
    /// Errors: non-finite or non-positive period, breakpoints outside the cycle, and the
    /// machine's, the loads' and the quadrature's errors over the cycle.
    pub fn new(
        machine: &'a M,
        start: f64,
        period: f64,
        breakpoints: &[f64],
        loads: impl Fn(f64) -> Result<M::Loads, MechError> + 'a,
        driver: impl Fn(f64) -> f64 + 'a,
    ) -> Result<Self, MechError> {
        crate::error::check_finite("cycle start and period", &[start, period])?;
        crate::error::check_finite("breakpoints", breakpoints)?;
        if !(period > 0.0) {
            return Err(MechError::InvalidInput(format!(
                "the cycle's period must be positive, got {period}"
            )));
        }
        let end = start + period;
        let mut cuts: Vec<f64> = breakpoints.to_vec();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        if let Some(b) = cuts.iter().find(|&&b| !(b > start && b < end)) {
            return Err(MechError::InvalidInput(format!(
                "breakpoint {b} is not inside the cycle ({start}, {end})"
            )));
        }
        let mut me = Cycle {
            machine,
            loads: Box::new(loads),
            driver: Box::new(driver),
            start,
            period,
            breakpoints: cuts,
            nodes: Vec::new(),
            atol_rate: 0.0,
            gross_work: 0.0,
        };
        me.tabulate()?;
        Ok(me)
    }

    /// The cycle with the defaults a designer expects: from q0 = 0 over `period` (2π,
    /// or 4π for a four-stroke engine), no breakpoints, no driver torque — only the loads,
    /// a function of q. Balance it with [`Cycle::balance`]; for a start, breakpoints or a
    /// driver use [`CycleBuilder`] ([`Cycle::builder`]) or [`Cycle::new`].
    pub fn of(
        machine: &'a M,
        period: f64,
        loads: impl Fn(f64) -> Result<M::Loads, MechError> + 'a,
    ) -> Result<Self, MechError> {
        Self::new(machine, 0.0, period, &[], loads, |_| 0.0)
    }

    /// A builder with those defaults: `Cycle::builder(&m, 4π, loads).start(q0)
    /// .breakpoints(&[..]).driver(|q| ..).build()`.
    pub fn builder<L>(machine: &'a M, period: f64, loads: L) -> CycleBuilder<'a, M, L>
    where
        L: Fn(f64) -> Result<M::Loads, MechError> + 'a,
    {
        CycleBuilder {
            machine,
            period,
            loads,
            start: 0.0,
            breakpoints: Vec::new(),
            driver: Box::new(|_| 0.0),
        }
    }

    /// The panel ends, their I*, then S by quadrature panel by panel.
    fn tabulate(&mut self) -> Result<(), MechError> {
        let width = self.period / PANELS_PER_CYCLE as f64;
        let mut edges = vec![self.start];
        let cuts: Vec<f64> = self
            .breakpoints
            .iter()
            .copied()
            .chain([self.start + self.period])
            .collect();
        for b in cuts {
            let a = *edges.last().unwrap();
            let n = ((b - a) / width).ceil().max(1.0) as usize;
            edges.extend((1..=n).map(|i| {
                if i == n {
                    b
                } else {
                    a + (b - a) * i as f64 / n as f64
                }
            }));
        }
        let mut scale = 0.0f64;
        self.nodes.clear();
        for &q in &edges {
            scale = scale.max(self.moment(q)?.abs());
            self.nodes.push(Node {
                q,
                work: 0.0,
                inertia: self.reduced(q)?.inertia,
            });
        }
        self.atol_rate = QUADRATURE_RTOL * scale.max(f64::MIN_POSITIVE);
        let (mut s, mut gross) = (0.0, 0.0);
        for k in 1..self.nodes.len() {
            let w = self.integral(self.nodes[k - 1].q, self.nodes[k].q)?;
            s += w;
            gross += w.abs();
            self.nodes[k].work = s;
        }
        self.gross_work = gross;
        Ok(())
    }

    /// ∫_a^b M* dq inside one panel, J.
    fn integral(&self, a: f64, b: f64) -> Result<f64, MechError> {
        gauss_kronrod(
            |q| self.moment(q),
            a,
            b,
            QUADRATURE_RTOL,
            self.atol_rate * (b - a).abs(),
        )
    }

    /// The machine.
    pub fn machine(&self) -> &'a M {
        self.machine
    }

    /// The start q0 of the cycle, rad.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// The period λ, rad.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// The breakpoints, rad, sorted.
    pub fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }

    /// The loads at q.
    pub fn loads(&self, q: f64) -> Result<M::Loads, MechError> {
        (self.loads)(q)
    }

    /// The driver action at q, N·m (N).
    pub fn driver(&self, q: f64) -> f64 {
        (self.driver)(q)
    }

    /// M*(q) = driver(q) + Σ F·g + Σ M g (loads and gravity), N·m: dS/dq.
    pub fn moment(&self, q: f64) -> Result<f64, MechError> {
        let driver = (self.driver)(q);
        crate::error::check_finite("driver action", &[driver])?;
        Ok(driver + self.machine.reduced_moment(q, &(self.loads)(q)?)?)
    }

    /// I*(q) and dI*/dq of the machine (no flywheel), kg·m², kg·m²/rad.
    pub fn reduced(&self, q: f64) -> Result<Reduced, MechError> {
        self.machine.reduced(q)
    }

    /// The accumulated work S(q) = ∫_{q0}^{q} M* dq, J, for any q (S(q + λ) = S(q) + W).
    pub fn work(&self, q: f64) -> Result<f64, MechError> {
        crate::error::check_finite("q", &[q])?;
        let turns = ((q - self.start) / self.period).floor();
        let r = q - turns * self.period;
        let n = self.nodes.len();
        // The panel [q_k, q_k+1] holding r (the last one if rounding put r at the end).
        let k = self
            .nodes
            .partition_point(|node| node.q <= r)
            .clamp(1, n - 1)
            - 1;
        let node = self.nodes[k];
        let inside = if r > node.q {
            self.integral(node.q, r)?
        } else {
            0.0
        };
        Ok(node.work + inside + turns * self.net_work())
    }

    /// The net work W = ∫ M* dq over the cycle, J.
    pub fn net_work(&self) -> f64 {
        self.nodes.last().map_or(0.0, |n| n.work)
    }

    /// Σ over the panels of |∫ M* dq|, J: the scale of [`PERIODIC_TOLERANCE`].
    pub fn gross_work(&self) -> f64 {
        self.gross_work
    }

    /// Ok when the net work is zero to [`PERIODIC_TOLERANCE`] × the gross work; otherwise
    /// [`MechError::NotPeriodic`] with W (J): the machine speeds up or slows down from
    /// cycle to cycle and has no steady state.
    pub fn check_periodic(&self) -> Result<(), MechError> {
        let w = self.net_work();
        if w.abs() <= PERIODIC_TOLERANCE * self.gross_work {
            Ok(())
        } else {
            Err(MechError::NotPeriodic { net_work: w })
        }
    }

    /// The constant torque on the input T = −W/λ (N·m; N for a prismatic input) whose work
    /// cancels the net work of the cycle: negative for an engine (a resisting torque),
    /// positive for a driven machine (the mean motor torque).
    pub fn balancing_torque(&self) -> f64 {
        -self.net_work() / self.period
    }

    /// Add [`Cycle::balancing_torque`] to the driver, in place: the cycle becomes
    /// periodic, S(q) becomes S(q) + T (q − q0). Returns T (N·m). Calling it again adds
    /// the (zero, up to rounding) torque that is left.
    pub fn balance(&mut self) -> f64 {
        let t = self.balancing_torque();
        let old = std::mem::replace(&mut self.driver, Box::new(|_| 0.0));
        self.driver = Box::new(move |q| old(q) + t);
        let mut gross = 0.0;
        let mut prev = self.nodes[0];
        for k in 1..self.nodes.len() {
            let here = self.nodes[k];
            gross += (here.work - prev.work + t * (here.q - prev.q)).abs();
            self.nodes[k].work = here.work + t * (here.q - self.start);
            prev = here;
        }
        // The last node is q0 + λ: its work is W + T λ = 0 up to rounding; make it exact.
        if let Some(last) = self.nodes.last_mut() {
            last.work = 0.0;
        }
        self.gross_work = gross;
        t
    }

    /// The same cycle with [`Cycle::balancing_torque`] added to the driver ([`Cycle::balance`]
    /// on a cycle given by value): the cycle and the torque T (N·m).
    pub fn balanced(mut self) -> (Self, f64) {
        let t = self.balance();
        (self, t)
    }

    /// The maximum fluctuation of energy over the cycle, ΔE = S_max − S_min (J), with
    /// where S reaches its extremes: the energy the flywheel must store and give back
    /// (`docs/theory.md` §7). Needs a periodic cycle ([`MechError::NotPeriodic`]).
    pub fn fluctuation(&self) -> Result<Fluctuation, MechError> {
        self.check_periodic()?;
        let hi = self.extreme(|s, _| s, true)?;
        let lo = self.extreme(|s, _| s, false)?;
        Ok(Fluctuation {
            energy: hi.value - lo.value,
            s_max: hi.value,
            q_s_max: hi.q,
            s_min: lo.value,
            q_s_min: lo.q,
        })
    }

    /// The coefficient of fluctuation of speed δ = (ω_max − ω_min)/ω_a that a flywheel of
    /// inertia I (kg·m², added on the input) gives at the mean speed ω_a (rad/s): the
    /// steady state of [`Cycle::steady_state`], exact (no I ≫ I* assumption). For a large
    /// flywheel δ → ΔE' / (I ω_a²), ΔE' the range of S(q) − ½ I*(q) ω_a² over the cycle:
    /// ΔE ([`Cycle::fluctuation`]) less the swing of the machine's own kinetic energy,
    /// which the approximate formula neglects and Wittenbauer's method keeps.
    pub fn speed_fluctuation(&self, omega_mean: f64, flywheel: f64) -> Result<f64, MechError> {
        Ok(self.steady_state(omega_mean, flywheel)?.speeds.irregularity)
    }

    /// n + 1 evenly spaced samples q0 + k λ / n, k = 0..=n, of M*, I*, dI*/dq and S.
    pub fn sample(&self, n: usize) -> Result<Vec<CyclePoint>, MechError> {
        if n == 0 {
            return Err(MechError::InvalidInput(
                "sample needs at least one interval".into(),
            ));
        }
        (0..=n)
            .map(|k| {
                let q = self.start + self.period * k as f64 / n as f64;
                let r = self.reduced(q)?;
                Ok(CyclePoint {
                    q,
                    moment: self.moment(q)?,
                    inertia: r.inertia,
                    inertia_derivative: r.inertia_derivative,
                    work: self.work(q)?,
                })
            })
            .collect()
    }

    /// The largest (`maximize`) or smallest value over the cycle of f(S(q), I*(q)):
    /// bracketed on the panel ends, refined by golden-section search.
    pub fn extreme(
        &self,
        f: impl Fn(f64, f64) -> f64,
        maximize: bool,
    ) -> Result<Extreme, MechError> {
        let sign = if maximize { 1.0 } else { -1.0 };
        let h = |q: f64| -> Result<f64, MechError> {
            Ok(sign * f(self.work(q)?, self.reduced(q)?.inertia))
        };
        // Panel ends without the last (it is the first again, one period on).
        let m = self.nodes.len() - 1;
        let vals: Vec<f64> = self.nodes[..m]
            .iter()
            .map(|n| sign * f(n.work, n.inertia))
            .collect();
        if let Some(k) = vals.iter().position(|v| !v.is_finite()) {
            return Err(MechError::InvalidInput(format!(
                "non-finite value at q = {}",
                self.nodes[k].q
            )));
        }
        let (lo, hi) = vals
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let margin = 0.05 * (hi - lo);
        let q_at = |i: isize| -> f64 {
            let (k, shift) = if i < 0 {
                ((i + m as isize) as usize, -self.period)
            } else {
                (i as usize, 0.0)
            };
            self.nodes[k].q + shift
        };
        let mut best: Option<(f64, f64)> = None;
        for k in 0..m {
            let (prev, next) = (vals[(k + m - 1) % m], vals[(k + 1) % m]);
            if vals[k] < prev || vals[k] < next || vals[k] < hi - margin {
                continue;
            }
            let (x, v) = golden_max(h, q_at(k as isize - 1), q_at(k as isize + 1))?;
            let (x, v) = if v >= vals[k] {
                (x, v)
            } else {
                (self.nodes[k].q, vals[k])
            };
            if best.is_none_or(|(_, b)| v > b) {
                best = Some((x, v));
            }
            if margin == 0.0 {
                break;
            }
        }
        let (mut q, _) =
            best.ok_or_else(|| MechError::InvalidInput("no extreme found over the cycle".into()))?;
        if q < self.start {
            q += self.period;
        }
        let (work, inertia) = (self.work(q)?, self.reduced(q)?.inertia);
        Ok(Extreme {
            q,
            work,
            inertia,
            value: f(work, inertia),
        })
    }

    /// The smallest I* over the cycle, kg·m².
    fn min_inertia(&self) -> Result<f64, MechError> {
        Ok(self.extreme(|_, i| i, false)?.value)
    }

    /// The approximate flywheel (`docs/theory.md` §7.5, I ≫ I*):
    /// I = (S_max − S_min)/(ε ω_a²), kg·m².
    /// Errors: ω_a ≤ 0, ε ∉ (0, 2), non-finite input, [`MechError::NotPeriodic`].
    pub fn approximate(
        &self,
        omega_mean: f64,
        irregularity: f64,
    ) -> Result<Approximate, MechError> {
        check_design(omega_mean, irregularity)?;
        let f = self.fluctuation()?;
        Ok(Approximate {
            inertia: f.energy / (irregularity * omega_mean * omega_mean),
            s_max: f.s_max,
            q_s_max: f.q_s_max,
            s_min: f.s_min,
            q_s_min: f.q_s_min,
        })
    }

    /// The exact flywheel by Wittenbauer's method (module documentation):
    /// I = (max(F − a I*) − min(F − b I*))/(a − b), a, b = (1 ± ε/2)², F = 2 S/ω_a², kg·m².
    /// Errors: ω_a ≤ 0, ε ∉ (0, 2), non-finite input, [`MechError::NotPeriodic`], and
    /// [`MechError::NonPositiveInertia`] (with min(I + I*)) when the result leaves
    /// I + I*(q) ≤ 0 somewhere: the machine alone is steadier than ε and no flywheel of
    /// this kind gives exactly ε.
    pub fn wittenbauer(
        &self,
        omega_mean: f64,
        irregularity: f64,
    ) -> Result<Wittenbauer, MechError> {
        check_design(omega_mean, irregularity)?;
        self.check_periodic()?;
        let k = 2.0 / (omega_mean * omega_mean);
        let tangent = |slope: f64, maximize: bool| -> Result<Tangent, MechError> {
            let e = self.extreme(|s, i| k * s - slope * i, maximize)?;
            Ok(Tangent {
                slope,
                intercept: e.value,
                q: e.q,
                reduced_inertia: e.inertia,
                f: k * e.work,
            })
        };
        let (a, b) = (
            (1.0 + 0.5 * irregularity).powi(2),
            (1.0 - 0.5 * irregularity).powi(2),
        );
        let upper = tangent(a, true)?;
        let lower = tangent(b, false)?;
        let inertia = (upper.intercept - lower.intercept) / (a - b);
        let c = a * inertia - upper.intercept;
        let total = inertia + self.min_inertia()?;
        if !(total > 0.0) {
            return Err(MechError::NonPositiveInertia(total));
        }
        let state = SteadyState {
            flywheel: inertia,
            energy: 0.5 * c * omega_mean * omega_mean,
            speeds: SpeedRange {
                omega_max: omega_mean * (1.0 + 0.5 * irregularity),
                q_max: upper.q,
                omega_min: omega_mean * (1.0 - 0.5 * irregularity),
                q_min: lower.q,
                omega_mean,
                irregularity,
            },
        };
        Ok(Wittenbauer {
            inertia,
            c,
            upper,
            lower,
            state,
        })
    }

    /// Both flywheels for the mean speed ω_a (rad/s) and the irregularity ε.
    pub fn flywheel(&self, omega_mean: f64, irregularity: f64) -> Result<Flywheel, MechError> {
        Ok(Flywheel {
            omega_mean,
            irregularity,
            exact: self.wittenbauer(omega_mean, irregularity)?,
            approximate: self.approximate(omega_mean, irregularity)?,
        })
    }

    /// The periodic motion with a flywheel of inertia I (kg·m², 0 for none) whose mean speed
    /// (ω_max + ω_min)/2 is ω_a (rad/s): the energy E (J) by safeguarded Newton iteration on
    /// ω_a(E), ω_max,min = max,min over q of √(2 (E + S)/(I + I*)). Errors: bad input,
    /// [`MechError::NotPeriodic`], [`MechError::NonPositiveInertia`] when I + I* ≤ 0
    /// somewhere, [`MechError::Stall`] (at the position of S_min) when even the slowest
    /// periodic motion (ω = 0 at S_min) has a mean speed above ω_a: the machine cannot turn
    /// that slowly with this flywheel, it stops.
    pub fn steady_state(&self, omega_mean: f64, flywheel: f64) -> Result<SteadyState, MechError> {
        crate::error::check_finite("flywheel", &[flywheel])?;
        check_speed(omega_mean)?;
        self.check_periodic()?;
        let total = flywheel + self.min_inertia()?;
        if !(total > 0.0) {
            return Err(MechError::NonPositiveInertia(total));
        }
        let s_min = self.extreme(|s, _| s, false)?;
        // (ω_mean(E) − ω_a, its derivative dω/dE = Σ 1/(2 ω (I + I*)), the state).
        let eval = |e: f64| -> Result<(f64, f64, SteadyState), MechError> {
            let hi = self.extreme(|s, i| (e + s) / (flywheel + i), true)?;
            let lo = self.extreme(|s, i| (e + s) / (flywheel + i), false)?;
            let (w_hi, w_lo) = ((2.0 * hi.value).sqrt(), (2.0 * lo.value.max(0.0)).sqrt());
            let d = 0.5 / (w_hi * (flywheel + hi.inertia))
                + if w_lo > 0.0 {
                    0.5 / (w_lo * (flywheel + lo.inertia))
                } else {
                    f64::INFINITY
                };
            let speeds = SpeedRange::new(w_hi, hi.q, w_lo, lo.q);
            Ok((
                speeds.omega_mean - omega_mean,
                d,
                SteadyState {
                    flywheel,
                    energy: e,
                    speeds,
                },
            ))
        };
        let mut lo = -s_min.value;
        let (g_lo, _, _) = eval(lo)?;
        if g_lo >= 0.0 {
            return Err(MechError::Stall { q: s_min.q });
        }
        // An upper bracket: at E = −S_min + ½ (I + max I*) ω_a², (E + S)/(I + I*) ≥ ω_a²/2
        // everywhere, so even the slowest point turns at ω_a or faster.
        let mut hi =
            lo + 0.5 * (flywheel + self.extreme(|_, i| i, true)?.value) * omega_mean * omega_mean;
        while eval(hi)?.0 < 0.0 {
            hi = lo + 2.0 * (hi - lo);
        }
        let mut e = hi;
        for _ in 0..200 {
            let (g, d, state) = eval(e)?;
            if g.abs() <= 4.0 * f64::EPSILON * omega_mean
                || hi - lo <= 4.0 * f64::EPSILON * hi.abs()
            {
                return Ok(state);
            }
            if g < 0.0 {
                lo = e;
            } else {
                hi = e;
            }
            let newton = e - g / d;
            e = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
        }
        Ok(eval(e)?.2)
    }

    /// ω(q) = √(2 (E + S(q)) / (I + I*(q))) in the steady state `state`, rad/s.
    /// Errors: [`MechError::Stall`] where E + S ≤ 0, [`MechError::NonPositiveInertia`].
    pub fn speed(&self, state: &SteadyState, q: f64) -> Result<f64, MechError> {
        speed_from_energy(
            state.energy,
            self.work(q)?,
            state.flywheel + self.reduced(q)?.inertia,
            q,
        )
    }

    /// The check by time integration: the machine with the flywheel (I + I*) q̈ + ½ dI*/dq q̇²
    /// = M*(q), from q0 at ω(q0) of `state`, integrated by DOP853 (relative tolerance `rtol`)
    /// until q = q0 + λ (an event); ω_max and ω_min are located on the dense output where
    /// q̈ changes sign. Errors: bad `rtol`, the machine's and the integrator's errors.
    pub fn simulate(&self, state: &SteadyState, rtol: f64) -> Result<CycleSimulation, MechError> {
        crate::error::check_finite("rtol", &[rtol])?;
        if !(rtol > 0.0) {
            return Err(MechError::InvalidInput(format!(
                "rtol must be positive, got {rtol}"
            )));
        }
        let (q0, q_end) = (self.start, self.start + self.period);
        let omega0 = self.speed(state, q0)?;
        let flywheel = state.flywheel;
        let mut rhs = |_t: f64, y: &[f64; 2]| -> Result<[f64; 2], MechError> {
            let r = self.reduced(y[0])?;
            let total = Reduced {
                inertia: flywheel + r.inertia,
                ..r
            };
            Ok([
                y[1],
                zhukovski::acceleration(total, self.moment(y[0])?, y[1], 0.0)?,
            ])
        };
        let acc0 = rhs(0.0, &[q0, omega0])?[1];
        // Extremes of q̇ over the steps, clipped to q ≤ q0 + λ (the event step overshoots).
        let mut best = Best {
            max: (omega0, q0),
            min: (omega0, q0),
        };
        let mut prev_acc = acc0;
        let mut failure: Option<MechError> = None;
        let mut observe = |d: &<Dop853 as ode::Method<2>>::Dense| {
            let (ta, mut tb) = (d.t_start(), d.t_end());
            if d.y_end()[0] > q_end {
                tb = bisect(|t| d.eval(t)[0] - q_end, ta, tb);
            }
            let yb = d.eval(tb);
            best.add(yb[1], yb[0]);
            let acc = d.dy_end()[1];
            if prev_acc * acc <= 0.0 && tb > ta {
                let s = if prev_acc > 0.0 || acc < 0.0 {
                    1.0
                } else {
                    -1.0
                };
                match golden_max(|t| Ok(s * d.eval(t)[1]), ta, tb) {
                    Ok((t, _)) => {
                        let y = d.eval(t);
                        best.add(y[1], y[0]);
                    }
                    Err(e) => failure = Some(e),
                }
            }
            prev_acc = acc;
        };
        let mut g = |_t: f64, y: &[f64; 2]| y[0] - q_end;
        let mut event = Event {
            g: &mut g,
            direction: 1,
            t_tol: 1e-15,
        };
        // Long enough to pass q0 + λ at the slowest speed the state allows.
        let t_end = 4.0 * self.period / state.speeds.omega_min.max(1e-3 * omega0);
        let mut method = Dop853::new(rtol, rtol * 1e-6);
        let out = ode::solve(
            &mut method,
            &mut rhs,
            0.0,
            [q0, omega0],
            t_end,
            Some(&mut event),
            Some(&mut observe),
        )?;
        if let Some(e) = failure {
            return Err(e);
        }
        if !out.event {
            return Err(MechError::Stall { q: out.y[0] });
        }
        let ((omega_max, q_max), (omega_min, q_min)) = (best.max, best.min);
        Ok(CycleSimulation {
            speeds: SpeedRange::new(omega_max, q_max, omega_min, q_min),
            omega_start: omega0,
            omega_end: out.y[1],
            duration: out.t,
            stats: out.stats,
        })
    }
}

/// A [`Cycle`] under construction ([`Cycle::builder`]): the table of S(q) is built once,
/// by [`CycleBuilder::build`], with every setting in place.
pub struct CycleBuilder<'a, M: OneDof, L> {
    machine: &'a M,
    period: f64,
    loads: L,
    start: f64,
    breakpoints: Vec<f64>,
    driver: Box<dyn Fn(f64) -> f64 + 'a>,
}

impl<'a, M: OneDof, L: Fn(f64) -> Result<M::Loads, MechError> + 'a> CycleBuilder<'a, M, L> {
    /// Where the cycle starts, q0 (rad; default 0).
    pub fn start(mut self, q0: f64) -> Self {
        self.start = q0;
        self
    }

    /// Input positions (rad, inside the cycle) where the loads are not smooth.
    pub fn breakpoints(mut self, at: &[f64]) -> Self {
        self.breakpoints = at.to_vec();
        self
    }

    /// The driver action as a function of q (N·m; default none).
    pub fn driver(mut self, driver: impl Fn(f64) -> f64 + 'a) -> Self {
        self.driver = Box::new(driver);
        self
    }

    /// The cycle and its table of S(q) ([`Cycle::new`]'s errors).
    pub fn build(self) -> Result<Cycle<'a, M>, MechError> {
        let driver = self.driver;
        Cycle::new(
            self.machine,
            self.start,
            self.period,
            &self.breakpoints,
            self.loads,
            driver,
        )
    }
}

/// The running extremes (value, position) of a simulation.
struct Best {
    max: (f64, f64),
    min: (f64, f64),
}

impl Best {
    fn add(&mut self, w: f64, q: f64) {
        if w > self.max.0 {
            self.max = (w, q);
        }
        if w < self.min.0 {
            self.min = (w, q);
        }
    }
}

/// A finite ω_a > 0.
fn check_speed(omega_mean: f64) -> Result<(), MechError> {
    crate::error::check_finite("mean speed", &[omega_mean])?;
    if omega_mean > 0.0 {
        Ok(())
    } else {
        Err(MechError::InvalidInput(format!(
            "the mean speed must be positive, got {omega_mean}"
        )))
    }
}

/// ω_a > 0 and 0 < ε < 2 (so that ω_min = ω_a (1 − ε/2) > 0), finite.
fn check_design(omega_mean: f64, irregularity: f64) -> Result<(), MechError> {
    check_speed(omega_mean)?;
    crate::error::check_finite("irregularity", &[irregularity])?;
    if !(irregularity > 0.0 && irregularity < 2.0) {
        return Err(MechError::InvalidInput(format!(
            "the irregularity must be in (0, 2), got {irregularity}"
        )));
    }
    Ok(())
}

/// The maximum of h on [a, b] (h unimodal there) by golden-section search to
/// |b − a| ≤ 1e-13 max(1, |x|): (x, h(x)).
fn golden_max(
    mut h: impl FnMut(f64) -> Result<f64, MechError>,
    mut a: f64,
    mut b: f64,
) -> Result<(f64, f64), MechError> {
    const R: f64 = 0.618_033_988_749_894_9; // (√5 − 1)/2
    let (mut x1, mut x2) = (b - R * (b - a), a + R * (b - a));
    let (mut h1, mut h2) = (h(x1)?, h(x2)?);
    while (b - a).abs() > 1e-13 * a.abs().max(b.abs()).max(1.0) {
        if h1 >= h2 {
            b = x2;
            (x2, h2) = (x1, h1);
            x1 = b - R * (b - a);
            h1 = h(x1)?;
        } else {
            a = x1;
            (x1, h1) = (x2, h2);
            x2 = a + R * (b - a);
            h2 = h(x2)?;
        }
        if x1 == x2 {
            break;
        }
    }
    Ok(if h1 >= h2 { (x1, h1) } else { (x2, h2) })
}

/// The zero of an increasing f on [a, b] with f(a) ≤ 0 ≤ f(b), by bisection to the last bit.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    loop {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            return b;
        }
        if f(m) > 0.0 {
            b = m;
        } else {
            a = m;
        }
    }
}
