//! The direct dynamic problem (`docs/theory.md` §6), written once over the traits that every
//! generated mechanism implements ([`Machine`], [`OneDof`]).
//!
//! One DOF, coordinate q (rad for a revolute input, m for a prismatic one):
//! - Quinn's energy-contribution coefficients ε_j(q) = T_j / T ([`quinn_coefficients`]);
//! - the energy theorem W_ext(q0 → q) = T(q) − T(q0), T = ½ I*(q) q̇², for actions that
//!   depend on the position only, and the time t(q) = t0 + ∫ dq / ω(q), both by adaptive
//!   Gauss–Kronrod quadrature ([`EnergyMethod`]);
//! - the equation of motion I* q̈ + ½ dI*/dq q̇² = driver + M* as a first-order system
//!   y = (q, q̇) with actions that depend on (t, q, q̇) ([`equation_of_motion`]), for the
//!   integrators of [`crate::dynamics::ode`].
//!
//! Several DOF: the generalized mass matrix M(q), the velocity, gravity and load terms
//! b(q, q̇) from the generated virtual-power solver, and Lagrange's equations
//! M(q) q̈ + b(q, q̇) = τ ([`lagrange_equations`]).

// The published coefficients keep all their digits; `!(x > 0.0)` also rejects NaN; the
// kernels index several arrays in lockstep and pass the integrator's whole state.
#![allow(
    clippy::excessive_precision,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::needless_range_loop,
    clippy::too_many_arguments,
    clippy::type_complexity
)]

use crate::solvers::traits::{Machine, OneDof};
use crate::MechError;
use nalgebra::SMatrix;

// ---------------------------------------------------------------------------------------
// Energies

/// Links of a mechanism whose energies fit in the stack buffer; larger ones use the heap.
const STACK_LINKS: usize = 32;

/// Run `f` on a zeroed scratch slice of length `n` (on the stack when n ≤ 32).
fn with_scratch<R>(n: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    if n <= STACK_LINKS {
        let mut buf = [0.0; STACK_LINKS];
        f(&mut buf[..n])
    } else {
        f(&mut vec![0.0; n])
    }
}

/// Kinetic energy T = Σ_j (½ m_j |v_Gj|² + ½ I_Gj ω_j²) of a motion, J.
pub fn kinetic_energy<M: Machine>(machine: &M, motion: &M::Motion) -> f64 {
    with_scratch(machine.links(), |e| {
        machine.link_kinetic_energies(motion, e);
        e.iter().sum()
    })
}

/// Total mechanical energy T + V at (q, q̇), J: V = Σ −m_j g·r_Gj (gravity only; the
/// loads have no potential). `q`, `qd` have length G. `InvalidInput` when T or V
/// overflows f64 (a finite speed too large for this mechanism).
pub fn total_energy<M: Machine>(machine: &M, q: &[f64], qd: &[f64]) -> Result<f64, MechError> {
    if q.len() != machine.dof() || qd.len() != machine.dof() {
        return Err(MechError::InvalidInput(format!(
            "expected {} input values",
            machine.dof()
        )));
    }
    // The accelerations do not enter T or V: q̇ serves as any finite q̈ of the right length.
    let motion = machine.motion(q, qd, qd)?;
    let (t, v) = (
        kinetic_energy(machine, &motion),
        machine.potential_energy(&motion),
    );
    // Finite speeds can still square past f64 (m v² of a link at 1e160 m/s).
    crate::kernel::finite::finite_result("kinetic and potential energy", &[t, v, t + v])?;
    Ok(t + v)
}

/// Quinn's energy-contribution coefficients (`docs/theory.md` §6.5) at position q:
/// ε_j(q) = T_j / T = (m_j g_Gj² + I_Gj g_j²) / I*(q), independent of q̇; written into
/// `out` (length N = `machine.links()`, the ground's entry 0). They sum to 1.
/// Errors: `out` of the wrong length, a configuration error, and
/// [`MechError::NonPositiveInertia`] when T = 0 (a massless chain).
pub fn quinn_coefficients<M: OneDof>(
    machine: &M,
    q: f64,
    out: &mut [f64],
) -> Result<(), MechError> {
    if out.len() != machine.links() {
        return Err(MechError::InvalidInput(format!(
            "Quinn coefficients need a slice of {} links, got {}",
            machine.links(),
            out.len()
        )));
    }
    crate::error::check_finite("q", &[q])?;
    let motion = machine.motion(&[q], &[1.0], &[0.0])?;
    machine.link_kinetic_energies(&motion, out);
    let total: f64 = out.iter().sum();
    if !(total > 0.0) {
        return Err(MechError::NonPositiveInertia(2.0 * total));
    }
    for e in out.iter_mut() {
        *e /= total;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Quadrature

/// Kronrod nodes of the 15-point rule on [−1, 1] (the positive half, descending; 0 last).
const XGK: [f64; 8] = [
    0.991455371120812639206854697526329,
    0.949107912342758524526189684047851,
    0.864864423359769072789712788640926,
    0.741531185599394439863864773280788,
    0.586087235467691130294144845693013,
    0.405845151377397166906606412076961,
    0.207784955007898467600689403773245,
    0.0,
];
/// Kronrod weights for [`XGK`].
const WGK: [f64; 8] = [
    0.022935322010529224963732008058970,
    0.063092092629978553290700663189204,
    0.104790010322250183839876322541518,
    0.140653259715525918745189590510238,
    0.169004726639267902826583426598550,
    0.190350578064785409913256402421014,
    0.204432940075298892414161999234649,
    0.209482141084727828012999174891714,
];
/// Gauss 7-point weights for the nodes XGK[1], XGK[3], XGK[5], XGK[7].
const WG: [f64; 4] = [
    0.129484966168869693270611432679082,
    0.279705391489276667901467771423780,
    0.381830050505118944950369775488975,
    0.417959183673469387755102040816327,
];

/// Deepest bisection of the adaptive quadratures.
const MAX_DEPTH: u32 = 48;

/// The most intervals one adaptive quadrature evaluates ([`gauss_kronrod`]; a tenth of it
/// for one leg of [`EnergyMethod`]'s time integral, whose intervals cost 15 quadratures
/// each). A point singularity costs two per level of
/// [`MAX_DEPTH`]; an integrand noisy above the tolerance over a stretch (the rounding of an
/// ill-conditioned configuration) never converges there, and its bisection tree, 2^48
/// intervals deep, would never end.
const MAX_INTERVALS: usize = 10_000;

/// The error of an adaptive quadrature past [`MAX_INTERVALS`] on [a, b].
#[cold]
fn not_converged(what: &str, a: f64, b: f64, rtol: f64) -> MechError {
    MechError::InvalidInput(format!(
        "{what} did not reach its tolerance (rtol {rtol:e}) in {MAX_INTERVALS} intervals, the last over [{a}, {b}]: the integrand is not smooth to that tolerance there (the rounding noise of a configuration near a dead point, or a singularity); keep the machine away from its dead points or loosen the tolerance"
    ))
}

/// The 15 abscissae of the Gauss–Kronrod rule on [a, b], in the order of [`gk15_sums`].
fn gk15_nodes(a: f64, b: f64) -> [f64; 15] {
    let (c, hl) = (0.5 * (a + b), 0.5 * (b - a));
    let mut x = [c; 15];
    for i in 0..7 {
        x[2 * i] = c - hl * XGK[i];
        x[2 * i + 1] = c + hl * XGK[i];
    }
    x
}

/// (Kronrod 15-point, Gauss 7-point) estimates of ∫_a^b from the values at [`gk15_nodes`].
fn gk15_sums(a: f64, b: f64, fx: &[f64; 15]) -> (f64, f64) {
    let hl = 0.5 * (b - a);
    let mut k = WGK[7] * fx[14];
    let mut g = WG[3] * fx[14];
    for i in 0..7 {
        let pair = fx[2 * i] + fx[2 * i + 1];
        k += WGK[i] * pair;
        if i % 2 == 1 {
            g += WG[i / 2] * pair;
        }
    }
    (hl * k, hl * g)
}

/// ∫_a^b f(x) dx by adaptive Gauss–Kronrod (G7–K15, bisection): an interval is accepted
/// when |K15 − G7| ≤ max(rtol·|K15|, atol·|interval| / |b − a|), so the result is within
/// about max(rtol·Σ|K|, atol) (the K15 value is far more accurate than that bound for
/// smooth f). Errors: those of f, non-finite values of f, [`MechError::StepUnderflow`]
/// (with `t` = the abscissa) when an interval can no longer be halved, `InvalidInput`
/// past 10 000 intervals (an integrand noisy above the tolerance).
pub fn gauss_kronrod<F>(mut f: F, a: f64, b: f64, rtol: f64, atol: f64) -> Result<f64, MechError>
where
    F: FnMut(f64) -> Result<f64, MechError>,
{
    crate::error::check_finite("integration limits", &[a, b])?;
    if !(rtol >= 0.0 && atol >= 0.0) || (rtol == 0.0 && atol == 0.0) {
        return Err(MechError::InvalidInput(format!(
            "quadrature tolerances rtol = {rtol}, atol = {atol}"
        )));
    }
    if a == b {
        return Ok(0.0);
    }
    let span = (b - a).abs();
    fn rec<F: FnMut(f64) -> Result<f64, MechError>>(
        f: &mut F,
        a: f64,
        b: f64,
        rtol: f64,
        atol_per: f64,
        depth: u32,
        budget: &mut usize,
    ) -> Result<f64, MechError> {
        if *budget == 0 {
            return Err(not_converged("the quadrature", a, b, rtol));
        }
        *budget -= 1;
        let x = gk15_nodes(a, b);
        let mut fx = [0.0; 15];
        for (v, xi) in fx.iter_mut().zip(x) {
            *v = f(xi)?;
            if !v.is_finite() {
                return Err(MechError::InvalidInput(format!(
                    "integrand non-finite at {xi}"
                )));
            }
        }
        let (k, g) = gk15_sums(a, b, &fx);
        if (k - g).abs() <= (rtol * k.abs()).max(atol_per * (b - a).abs()) {
            return Ok(k);
        }
        let m = 0.5 * (a + b);
        if depth >= MAX_DEPTH || m == a || m == b {
            return Err(MechError::StepUnderflow { t: m });
        }
        Ok(rec(f, a, m, rtol, atol_per, depth + 1, budget)?
            + rec(f, m, b, rtol, atol_per, depth + 1, budget)?)
    }
    rec(&mut f, a, b, rtol, atol / span, 0, &mut { MAX_INTERVALS })
}

// ---------------------------------------------------------------------------------------
// Energy theorem

/// The speed from the energy theorem, rad/s (m/s): with T0 = ½ I*(q0) ω0² and the work
/// W = W_ext(q0 → q) (J) of every action, ω(q) = ±√(2 (T0 + W) / I*(q)).
/// Errors: [`MechError::NonPositiveInertia`] for I* ≤ 0, [`MechError::Stall`] (at `q`)
/// when T0 + W ≤ 0: the machine cannot reach q.
pub fn speed_from_energy(kinetic0: f64, work: f64, inertia: f64, q: f64) -> Result<f64, MechError> {
    if !(inertia > 0.0) {
        return Err(MechError::NonPositiveInertia(inertia));
    }
    let t = kinetic0 + work;
    if !(t > 0.0) {
        return Err(MechError::Stall { q });
    }
    Ok((2.0 * t / inertia).sqrt())
}

/// A point of the motion found by the energy method.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EnergyPoint {
    /// Position q, rad (m).
    pub q: f64,
    /// Speed q̇ = ω(q), rad/s (m/s).
    pub omega: f64,
    /// Time t(q) = t0 + ∫ dq / ω, s.
    pub t: f64,
    /// Work of every action since the start, W_ext(q0 → q), J.
    pub work: f64,
}

/// The energy method for actions that depend on the position only (`docs/theory.md` §6.6, §6.7):
/// ω(q) from W_ext(q0 → q) = T(q) − T(q0) with W_ext = ∫ (driver(q) + M*(q)) dq, and
/// t(q) = t0 + ∫ dq / ω(q).
///
/// Both integrals are adaptive Gauss–Kronrod quadratures (G7–K15) to the relative tolerance
/// `rtol`; the time integral is refined left to right, and the work at each of its nodes is
/// the work at the node's interval start plus a Gauss–Kronrod integral over the rest, so
/// the cost stays local. A start from rest (ω0 = 0) moves in the direction of the initial
/// moment and integrates t with the substitution q = a + (b − a) s², which removes the
/// 1/√(q − q0) singularity. The method runs in the direction of motion: call
/// [`EnergyMethod::advance_to`] with successive positions to trace ω(q), t(q).
pub struct EnergyMethod<'a, M: OneDof, A> {
    machine: &'a M,
    actions: A,
    rtol: f64,
    kinetic0: f64,
    sign: f64,
    here: EnergyPoint,
    /// Positions per initial leg of the time integral, rad (m).
    leg: f64,
}

/// Substitution of a time-integral leg: q(u) = a + u (linear) or q(u) = a + L u² (from rest).
#[derive(Clone, Copy)]
enum Map {
    Linear,
    FromRest { a: f64, len: f64 },
}

impl Map {
    #[inline]
    fn q(self, u: f64) -> f64 {
        match self {
            Map::Linear => u,
            Map::FromRest { a, len } => a + len * u * u,
        }
    }
    #[inline]
    fn dq_du(self, u: f64) -> f64 {
        match self {
            Map::Linear => 1.0,
            Map::FromRest { len, .. } => 2.0 * len * u,
        }
    }
}

impl<'a, M, A> EnergyMethod<'a, M, A>
where
    M: OneDof,
    A: FnMut(f64) -> (f64, M::Loads),
{
    /// Start at time `t0` (s), position `q0`, speed `omega0`; `actions(q)` returns the
    /// driver action (N·m or N) and the loads at q. `rtol` (> 0) is the relative tolerance
    /// of both quadratures. Errors: non-finite input, `rtol` ≤ 0, I*(q0) ≤ 0, and a start
    /// from rest where the moment is zero (the machine stays: [`MechError::Stall`]).
    pub fn new(
        machine: &'a M,
        t0: f64,
        q0: f64,
        omega0: f64,
        actions: A,
        rtol: f64,
    ) -> Result<Self, MechError> {
        crate::error::check_finite("t0, q0, omega0, rtol", &[t0, q0, omega0, rtol])?;
        if !(rtol > 0.0) {
            return Err(MechError::InvalidInput(format!(
                "rtol must be positive, got {rtol}"
            )));
        }
        let inertia = machine.reduced(q0)?.inertia;
        if !(inertia > 0.0) {
            return Err(MechError::NonPositiveInertia(inertia));
        }
        let mut me = EnergyMethod {
            machine,
            actions,
            rtol,
            kinetic0: 0.5 * inertia * omega0 * omega0,
            sign: omega0.signum(),
            here: EnergyPoint {
                q: q0,
                omega: omega0,
                t: t0,
                work: 0.0,
            },
            leg: 0.25,
        };
        if omega0 == 0.0 {
            let p = me.moment(q0)?;
            if p == 0.0 {
                return Err(MechError::Stall { q: q0 });
            }
            me.sign = p.signum();
        }
        Ok(me)
    }

    /// The generalized moment of every action, driver(q) + M*(q) (N·m or N): dW/dq.
    pub fn moment(&mut self, q: f64) -> Result<f64, MechError> {
        let (driver, loads) = (self.actions)(q);
        crate::error::check_finite("driver", &[driver])?;
        Ok(driver + self.machine.reduced_moment(q, &loads)?)
    }

    /// The last point reached (the start until the first advance).
    pub fn current(&self) -> EnergyPoint {
        self.here
    }

    /// W_ext(a → b) = ∫_a^b (driver + M*) dq, to `rtol` relative to the kinetic-energy
    /// scale `scale` (J).
    fn work(&mut self, a: f64, b: f64, scale: f64) -> Result<f64, MechError> {
        let rtol = self.rtol;
        gauss_kronrod(
            |q| self.moment(q),
            a,
            b,
            rtol,
            rtol * scale.max(f64::MIN_POSITIVE),
        )
    }

    /// The kinetic-energy scale of the tolerance on the work: T0 + |W| at `w`.
    fn energy_scale(&self, w: f64) -> f64 {
        self.kinetic0 + w.abs()
    }

    /// ω at q, given the work from the start to q; on a stall, the stall position found by
    /// bisection on T0 + W between `a` (where T0 + W(a) = T0 + w_a > 0) and q.
    fn speed(&mut self, q: f64, w: f64, a: f64, w_a: f64) -> Result<f64, MechError> {
        let inertia = self.machine.reduced(q)?.inertia;
        match speed_from_energy(self.kinetic0, w, inertia, q) {
            Err(MechError::Stall { .. }) => Err(MechError::Stall {
                q: self.stall_between(a, w_a, q)?,
            }),
            r => r.map(|s| self.sign * s),
        }
    }

    fn stall_between(&mut self, a: f64, w_a: f64, b: f64) -> Result<f64, MechError> {
        let (mut lo, mut hi) = (a, b);
        let scale = self.energy_scale(w_a);
        for _ in 0..200 {
            let m = 0.5 * (lo + hi);
            if m == lo || m == hi || (hi - lo).abs() <= 1e-12 * (1.0 + a.abs()) {
                break;
            }
            let e = self.kinetic0 + w_a + self.work(a, m, scale)?;
            if e > 0.0 {
                lo = m;
            } else {
                hi = m;
            }
        }
        Ok(0.5 * (lo + hi))
    }

    /// One interval [ua, ub] of the time integral in the variable u of `map`, whose start
    /// q(ua) has work `w_a`: returns (Δt, W at q(ub)). At most `budget` intervals (each
    /// 15 quadratures of the work) are evaluated.
    fn time_leg(
        &mut self,
        map: Map,
        ua: f64,
        ub: f64,
        w_a: f64,
        depth: u32,
        budget: &mut usize,
    ) -> Result<(f64, f64), MechError> {
        if *budget == 0 {
            return Err(not_converged(
                "the time integral of the energy method",
                map.q(ua),
                map.q(ub),
                self.rtol,
            ));
        }
        *budget -= 1;
        let qa = map.q(ua);
        let scale = self.energy_scale(w_a);
        let us = gk15_nodes(ua, ub);
        let mut fx = [0.0; 15];
        for (i, u) in us.iter().enumerate() {
            let q = map.q(*u);
            let w = w_a + self.work(qa, q, scale)?;
            let omega = self.speed(q, w, qa, w_a)?;
            fx[i] = map.dq_du(*u) / omega;
        }
        let (k, g) = gk15_sums(ua, ub, &fx);
        if (k - g).abs() <= self.rtol * k.abs() {
            let w_b = w_a + self.work(qa, map.q(ub), scale)?;
            return Ok((k, w_b));
        }
        let um = 0.5 * (ua + ub);
        if depth >= MAX_DEPTH || um == ua || um == ub {
            return Err(MechError::StepUnderflow { t: self.here.t });
        }
        let (t1, w_m) = self.time_leg(map, ua, um, w_a, depth + 1, budget)?;
        let (t2, w_b) = self.time_leg(map, um, ub, w_m, depth + 1, budget)?;
        Ok((t1 + t2, w_b))
    }

    /// Advance along the motion to position `q` (in the direction of motion from the
    /// current point): ω(q) and t(q) by the energy theorem, to `rtol`.
    /// Errors: `q` behind the current point, [`MechError::Stall`] where the speed reaches
    /// zero first (the machine turns back there), [`MechError::NonPositiveInertia`], the
    /// machine's configuration errors, [`MechError::StepUnderflow`] if a quadrature
    /// cannot converge.
    pub fn advance_to(&mut self, q: f64) -> Result<EnergyPoint, MechError> {
        crate::error::check_finite("q", &[q])?;
        let dq = q - self.here.q;
        if dq == 0.0 {
            return Ok(self.here);
        }
        if dq.signum() != self.sign {
            return Err(MechError::InvalidInput(format!(
                "the energy method runs in the direction of motion: q = {q} is behind q = {}",
                self.here.q
            )));
        }
        let legs = (dq.abs() / self.leg).ceil().max(1.0) as usize;
        let mut here = self.here;
        for i in 0..legs {
            let (a, b) = (
                here.q,
                if i + 1 == legs {
                    q
                } else {
                    self.here.q + dq * (i + 1) as f64 / legs as f64
                },
            );
            let (dt, w_b) = if here.omega == 0.0 {
                self.time_leg(
                    Map::FromRest { a, len: b - a },
                    0.0,
                    1.0,
                    here.work,
                    0,
                    &mut (MAX_INTERVALS / 10),
                )?
            } else {
                self.time_leg(Map::Linear, a, b, here.work, 0, &mut (MAX_INTERVALS / 10))?
            };
            let inertia = self.machine.reduced(b)?.inertia;
            let omega = self.sign * speed_from_energy(self.kinetic0, w_b, inertia, b)?;
            here = EnergyPoint {
                q: b,
                omega,
                t: here.t + dt,
                work: w_b,
            };
        }
        self.here = here;
        Ok(here)
    }
}

// ---------------------------------------------------------------------------------------
// Time integration, one DOF

/// The equation of motion of a one-DOF machine as the first-order system y = (q, q̇):
/// y' = (q̇, q̈), q̈ = (driver + M*(q) − ½ dI*/dq q̇²) / I*(q) ([`OneDof::acceleration`]).
/// `actions(t, q, q̇)` returns the driver action (N·m or N) and the loads. The closure is
/// the right-hand side for [`crate::dynamics::ode::solve`]; it allocates nothing.
pub fn equation_of_motion<'a, M, A>(
    machine: &'a M,
    mut actions: A,
) -> impl FnMut(f64, &[f64; 2]) -> Result<[f64; 2], MechError> + 'a
where
    M: OneDof,
    A: FnMut(f64, f64, f64) -> (f64, M::Loads) + 'a,
{
    move |t, y| {
        let (driver, loads) = actions(t, y[0], y[1]);
        Ok([y[1], machine.acceleration(y[0], y[1], driver, &loads)?])
    }
}

// ---------------------------------------------------------------------------------------
// Several DOF: Lagrange's equations

fn check_dof<M: Machine>(machine: &M, g: usize) -> Result<(), MechError> {
    if g == machine.dof() {
        Ok(())
    } else {
        Err(MechError::InvalidInput(format!(
            "the machine has {} inputs, {g} given",
            machine.dof()
        )))
    }
}

/// The motor actions D(q, q̇, q̈, loads) of virtual power (N·m or N per input), as an array.
fn actions_at<M: Machine, const G: usize>(
    machine: &M,
    q: &[f64; G],
    qd: &[f64; G],
    qdd: &[f64; G],
    loads: &M::Loads,
) -> Result<[f64; G], MechError> {
    let motion = machine.motion(q, qd, qdd)?;
    let mut out = [0.0; G];
    machine.driver_actions(&motion, loads, &mut out)?;
    Ok(out)
}

/// The generalized mass matrix M(q) (kg·m², kg·m or kg by input type), column k:
/// M e_k = D(q, 0, e_k, no loads) − D(q, 0, 0, no loads), D the motor actions of virtual
/// power (the gravity terms cancel). For one DOF, M = (I*), the 1 × 1 matrix.
pub fn mass_matrix<M: Machine, const G: usize>(
    machine: &M,
    q: &[f64; G],
) -> Result<[[f64; G]; G], MechError> {
    check_dof(machine, G)?;
    let none = M::Loads::default();
    let zero = [0.0; G];
    let base = actions_at(machine, q, &zero, &zero, &none)?;
    let mut m = [[0.0; G]; G];
    for k in 0..G {
        let mut e = [0.0; G];
        e[k] = 1.0;
        let col = actions_at(machine, q, &zero, &e, &none)?;
        for i in 0..G {
            m[i][k] = col[i] - base[i];
        }
    }
    // Two finite motor actions can differ by more than f64 holds.
    crate::kernel::finite::finite_result("mass matrix", m.as_flattened())?;
    Ok(m)
}

/// The velocity, gravity and load terms b(q, q̇) = D(q, q̇, 0, loads) of Lagrange's
/// equations M q̈ + b = τ (N·m or N per input): Coriolis and centrifugal terms minus the
/// generalized forces of gravity and the loads. For one DOF, b = ½ dI*/dq q̇² − M*.
pub fn velocity_terms<M: Machine, const G: usize>(
    machine: &M,
    q: &[f64; G],
    qd: &[f64; G],
    loads: &M::Loads,
) -> Result<[f64; G], MechError> {
    check_dof(machine, G)?;
    actions_at(machine, q, qd, &[0.0; G], loads)
}

/// q̈ = M(q)⁻¹ (τ − b(q, q̇)) (rad/s² or m/s² per input) for motor actions τ, by Cholesky.
/// Errors: [`MechError::NonPositiveInertia`] (carrying the smallest diagonal entry of M)
/// when M is not positive definite, and those of the kinematics.
pub fn lagrange_acceleration<M: Machine, const G: usize>(
    machine: &M,
    q: &[f64; G],
    qd: &[f64; G],
    tau: &[f64; G],
    loads: &M::Loads,
) -> Result<[f64; G], MechError> {
    crate::error::check_finite("q", q)?;
    crate::error::check_finite("qd", qd)?;
    crate::error::check_finite("tau", tau)?;
    let m = mass_matrix(machine, q)?;
    let b = velocity_terms(machine, q, qd, loads)?;
    let mm = SMatrix::<f64, G, G>::from_fn(|i, j| 0.5 * (m[i][j] + m[j][i]));
    let rhs = nalgebra::SVector::<f64, G>::from_fn(|i, _| tau[i] - b[i]);
    match mm.cholesky() {
        Some(c) => {
            let x = c.solve(&rhs);
            let qdd = core::array::from_fn(|i| x[i]);
            // τ − b of finite terms, divided by a small M, can overflow.
            crate::kernel::finite::finite_result("accelerations q̈ (M⁻¹ (τ − b))", &qdd)?;
            Ok(qdd)
        }
        None => Err(MechError::NonPositiveInertia(
            (0..G).map(|i| m[i][i]).fold(f64::INFINITY, f64::min),
        )),
    }
}

/// Lagrange's equations as the first-order system y = (q₁…q_G, q̇₁…q̇_G) of length N = 2G:
/// y' = (q̇, M(q)⁻¹ (τ − b(q, q̇))). `actions(t, q, q̇)` returns the motor actions τ and the
/// loads. The closure is the right-hand side for [`crate::dynamics::ode::solve`]; it allocates nothing.
/// Errors (per call): N ≠ 2G or G ≠ the machine's DOF, and those of
/// [`lagrange_acceleration`].
pub fn lagrange_equations<'a, M, A, const G: usize, const N: usize>(
    machine: &'a M,
    mut actions: A,
) -> impl FnMut(f64, &[f64; N]) -> Result<[f64; N], MechError> + 'a
where
    M: Machine,
    A: FnMut(f64, &[f64; G], &[f64; G]) -> ([f64; G], M::Loads) + 'a,
{
    move |t, y| {
        if N != 2 * G {
            return Err(MechError::InvalidInput(format!(
                "a state of {N} values for {G} inputs: need {}",
                2 * G
            )));
        }
        let q: [f64; G] = core::array::from_fn(|i| y[i]);
        let qd: [f64; G] = core::array::from_fn(|i| y[G + i]);
        let (tau, loads) = actions(t, &q, &qd);
        let qdd = lagrange_acceleration(machine, &q, &qd, &tau, &loads)?;
        Ok(core::array::from_fn(
            |i| if i < G { qd[i] } else { qdd[i - G] },
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::measure::within;

    #[test]
    fn gauss_kronrod_rules_are_exact_for_polynomials() {
        // K15 integrates degree 22 exactly, G7 degree 13.
        let x = gk15_nodes(-1.0, 1.0);
        for d in 0..=22u32 {
            let fx: [f64; 15] = core::array::from_fn(|i| x[i].powi(d as i32));
            let (k, g) = gk15_sums(-1.0, 1.0, &fx);
            let exact = if d % 2 == 1 {
                0.0
            } else {
                2.0 / (d as f64 + 1.0)
            };
            // measured worst 1.1e-16 (be05608); 100×
            assert!(
                within((k - exact).abs(), 1e-15),
                "K15, degree {d}: {k} vs {exact}"
            );
            if d <= 13 {
                // measured worst 1.1e-16 (be05608); 100×
                assert!(
                    within((g - exact).abs(), 1e-15),
                    "G7, degree {d}: {g} vs {exact}"
                );
            }
        }
    }

    #[test]
    fn adaptive_quadrature() {
        // measured worst 0 (be05608); exact; a few ulps
        let v = gauss_kronrod(|x| Ok(x.sin()), 0.0, 20.0, 1e-13, 0.0).unwrap();
        assert!(within((v - (1.0 - 20f64.cos())).abs(), 1e-15));
        // A sharp peak: ∫ dx / (1e-4 + x²) over [−1, 1] = 200 atan(100).
        let v = gauss_kronrod(|x| Ok(1.0 / (1e-4 + x * x)), -1.0, 1.0, 1e-12, 0.0).unwrap();
        // measured worst 1.1e-13 (be05608); 100×
        assert!(within((v - 200.0 * 100f64.atan()).abs(), 1e-11), "{v}");
        let v = gauss_kronrod(|x| Ok(x.exp()), 2.0, 0.0, 1e-14, 0.0).unwrap();
        // measured worst 1.8e-15 (be05608); 100×
        assert!(within((v - (1.0 - 2f64.exp())).abs(), 1e-13));
        assert!(matches!(
            gauss_kronrod(Ok, 0.0, f64::NAN, 1e-9, 0.0),
            Err(MechError::InvalidInput(_))
        ));
        assert!(gauss_kronrod(|x| Ok(1.0 / x), -1.0, 1.0, 1e-9, 0.0).is_err());
    }

    /// An integrand that converges only on intervals far below its span (sin(10⁷ x)
    /// over [0, 1]: some 2^24 intervals) made a bisection tree of millions of intervals
    /// (`mech-fuzz` found a flywheel cycle through a near-toggle, whose M* is rounding
    /// noise there, still integrating after 20 s). It ends after its budget of intervals
    /// with an error that says why; a tolerance the rule meets sooner is unaffected.
    #[test]
    fn a_quadrature_that_cannot_converge_ends_in_an_error_not_a_hang() {
        let mut calls = 0usize;
        let r = gauss_kronrod(
            |x: f64| {
                calls += 1;
                Ok((1e7 * x).sin())
            },
            0.0,
            1.0,
            1e-13,
            0.0,
        );
        match r {
            Err(MechError::InvalidInput(m)) => {
                assert!(m.contains("did not reach its tolerance"), "{m}")
            }
            other => panic!("expected the budget's error, got {other:?}"),
        }
        assert!(calls <= 15 * MAX_INTERVALS, "{calls} evaluations");
        let v = gauss_kronrod(|x: f64| Ok((1e3 * x).sin()), 0.0, 1.0, 1e-12, 0.0).unwrap();
        assert!((v - (1.0 - 1e3f64.cos()) / 1e3).abs() < 1e-14, "{v}");
    }

    #[test]
    fn speed_from_energy_formula() {
        // T0 = 2 J, W = 6 J, I* = 4 kg·m²: ω = √(2·8/4) = 2.
        assert_eq!(speed_from_energy(2.0, 6.0, 4.0, 0.0).unwrap(), 2.0);
        assert_eq!(
            speed_from_energy(2.0, -2.0, 4.0, 1.5),
            Err(MechError::Stall { q: 1.5 })
        );
        assert_eq!(
            speed_from_energy(2.0, 1.0, 0.0, 1.5),
            Err(MechError::NonPositiveInertia(0.0))
        );
    }
}
