//! The cycle: [`Cycle`], a one-DOF machine with its actions over one period, its table
//! of the work S(q) on the panels, the net work and its balancing torque, and its
//! [`CycleBuilder`].

use crate::dynamics::gauss_kronrod;
use crate::solvers::traits::OneDof;
use crate::solvers::zhukovski::Reduced;
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
pub(super) struct Node {
    pub(super) q: f64,
    pub(super) work: f64,
    pub(super) inertia: f64,
}

/// A one-DOF machine with its actions over one cycle of its steady state (see the module
/// documentation), and the table of the work S(q) on the cycle's panels.
pub struct Cycle<'a, M: OneDof> {
    machine: &'a M,
    loads: LoadsFn<'a, M>,
    driver: Box<dyn Fn(f64) -> f64 + 'a>,
    pub(super) start: f64,
    pub(super) period: f64,
    breakpoints: Vec<f64>,
    pub(super) nodes: Vec<Node>,
    /// Absolute tolerance of the quadratures per unit of q, N·m.
    atol_rate: f64,
    /// Σ over the panels of |∫ M* dq|, J.
    gross_work: f64,
    /// Relative tolerance of the quadratures ([`QUADRATURE_RTOL`] unless the builder's
    /// [`CycleBuilder::tolerance`] says).
    rtol: f64,
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
        Self::with_tolerance(
            machine,
            start,
            period,
            breakpoints,
            loads,
            driver,
            QUADRATURE_RTOL,
        )
    }

    /// [`Cycle::new`] with the quadratures' relative tolerance `rtol`.
    fn with_tolerance(
        machine: &'a M,
        start: f64,
        period: f64,
        breakpoints: &[f64],
        loads: impl Fn(f64) -> Result<M::Loads, MechError> + 'a,
        driver: impl Fn(f64) -> f64 + 'a,
        rtol: f64,
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
            rtol,
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
            rtol: QUADRATURE_RTOL,
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
        // I* at every panel end in one batched call (lanes of four configurations).
        let (mut inertia, mut slope) = (vec![0.0; edges.len()], vec![0.0; edges.len()]);
        let failed = self.machine.reduced_many(&edges, &mut inertia, &mut slope);
        if let Some(e) = failed.refusal().or(failed.iter().next().map(|(_, e)| e)) {
            return Err(e.clone());
        }
        let mut scale = 0.0f64;
        self.nodes.clear();
        for (&q, &inertia) in edges.iter().zip(&inertia) {
            scale = scale.max(self.moment(q)?.abs());
            self.nodes.push(Node {
                q,
                work: 0.0,
                inertia,
            });
        }
        self.atol_rate = self.rtol * scale.max(f64::MIN_POSITIVE);
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
            self.rtol,
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
    rtol: f64,
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

    /// The quadratures' relative tolerance (default [`QUADRATURE_RTOL`], 1e-13): a looser
    /// one, 1e-8 say, tabulates a cycle whose loads come from a table with a kink at every
    /// row (a gas-pressure table) many times faster, for a search that compares designs
    /// (`design::optimize`'s `flywheel`). From 1e-15 to 1e-3.
    pub fn tolerance(mut self, rtol: f64) -> Self {
        self.rtol = rtol;
        self
    }

    /// The cycle and its table of S(q) ([`Cycle::new`]'s errors; a tolerance outside
    /// [1e-15, 1e-3]).
    pub fn build(self) -> Result<Cycle<'a, M>, MechError> {
        if !(1e-15..=1e-3).contains(&self.rtol) {
            return Err(MechError::InvalidInput(format!(
                "the cycle's quadrature tolerance {} is outside [1e-15, 1e-3]",
                self.rtol
            )));
        }
        let driver = self.driver;
        Cycle::with_tolerance(
            self.machine,
            self.start,
            self.period,
            &self.breakpoints,
            self.loads,
            driver,
            self.rtol,
        )
    }
}
