//! The run-time error of every solver (`docs/conventions.md#errors`).

/// Why a computation could not give a trustworthy answer.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MechError {
    /// The input value has no real configuration (e.g. a four-bar driven past its limit).
    #[error("no assembly: the mechanism cannot be assembled at this input value")]
    NoAssembly,
    /// A dead point or toggle position: a linear system is singular to working accuracy.
    #[error("singular configuration (dead point): condition estimate {condition:.3e}")]
    Singular {
        /// Estimate of the condition number of the offending system (dimensionless).
        condition: f64,
    },
    /// A NaN or infinite input, or a parameter out of its domain.
    #[error("invalid input: {0}")]
    InvalidInput(String),
    /// Redundant constraints: reactions are indeterminate, or the drawing is redundant.
    #[error("redundant constraints: {0}")]
    Redundant(String),
    /// Friction locks the mechanism: the driver cannot move it.
    #[error("self-locking: {0}")]
    SelfLocking(String),
    /// Flywheel: the net work over one cycle is not zero (J).
    #[error("not periodic: net work over the cycle is {net_work:.6e} J; balance it with a constant resisting torque")]
    NotPeriodic {
        /// Net work of M* over one cycle, J.
        net_work: f64,
    },
    /// Non-positive reduced inertia I* (kg·m²).
    #[error("non-positive reduced inertia I* = {0:.6e} kg·m²")]
    NonPositiveInertia(f64),
    /// The energy method reached ω = 0: the machine stalls before the requested position.
    #[error("stall: the speed reaches zero at q = {q:.6} rad")]
    Stall {
        /// Where the speed vanished, rad.
        q: f64,
    },
    /// An adaptive integrator needed a step smaller than it can represent.
    #[error("step size underflow at t = {t:.6e} s")]
    StepUnderflow {
        /// Time reached, s.
        t: f64,
    },
    /// A mechanism description was rejected (run-time loader); the messages of every check.
    #[error("invalid mechanism:\n{0}")]
    Invalid(String),
    /// A defect of mech, not of the input: a panic caught where the loader runs the front
    /// end on a thread of its own. Tests and the fuzzer count it as a panic.
    #[error("internal error (a defect of mech; please report it with the input): {0}")]
    Internal(String),
}

/// True when `v` is an infinity or a NaN: !(|v| < ∞), one compare. Checks OR these
/// flags over their values rather than summing the values: an OR is exact and
/// associative, so the compiler may join the flags in any order (a float sum is a chain
/// it may not reorder), and it never overflows, so it raises no false alarm and needs no
/// second look. Measured against the sums, the generated solvers gained up to a tenth of
/// their time (`docs/performance.md`, "the finiteness checks").
#[inline(always)]
pub fn non_finite(v: f64) -> bool {
    !(v.abs() < f64::INFINITY)
}

/// True when every value is finite ([`non_finite`] over the values, joined by OR).
#[inline(always)]
pub fn all_finite(values: &[f64]) -> bool {
    !values.iter().fold(false, |bad, &v| bad | non_finite(v))
}

/// True when every value is finite, tested as Σ v·0 = 0: v·0 is ±0 for a finite v and NaN
/// for an infinity or a NaN, and a sum of zeros is a zero (exact: no overflow, no false
/// alarm). Two operations per value (a multiplication and an addition, both on two values
/// at once in vector registers) where [`all_finite`] takes a mask, a compare and a branch:
/// for values known at a solver's entry (its inputs), whose check only gates the result,
/// so that the chain of additions waits on nothing the solve computes. The values are
/// summed in two interleaved chains, each half as long as one would be.
#[inline(always)]
fn all_finite_inputs(values: &[f64]) -> bool {
    let (mut even, mut odd) = (0.0, 0.0);
    let mut pairs = values.chunks_exact(2);
    for p in &mut pairs {
        even += p[0] * 0.0;
        odd += p[1] * 0.0;
    }
    if let [v] = pairs.remainder() {
        even += v * 0.0;
    }
    even + odd == 0.0
}

/// `InvalidInput` unless every value is finite (`all_finite_inputs`).
#[inline]
pub fn check_finite(what: &str, values: &[f64]) -> Result<(), MechError> {
    if all_finite_inputs(values) {
        Ok(())
    } else {
        Err(not_finite(what, values))
    }
}

/// [`check_finite`] on the values of an array: the same test, with the values kept in
/// registers on the success path (they are stored for the message on the error path only,
/// where a slice's values are stored before the test because its error path reads them).
#[inline(always)]
pub fn check_inputs<const N: usize>(what: &str, values: [f64; N]) -> Result<(), MechError> {
    if all_finite_inputs(&values) {
        Ok(())
    } else {
        Err(inputs_not_finite(what, values))
    }
}

/// The error of [`check_inputs`], out of line, the values passed by value.
#[cold]
#[inline(never)]
fn inputs_not_finite<const N: usize>(what: &str, values: [f64; N]) -> MechError {
    not_finite(what, &values)
}

/// The error to report for a solve that failed with `e`, whose inputs are `values`
/// (named `what`): `InvalidInput` "… must be finite" when one of them is not finite, else
/// `e` itself. A NaN or an infinity among the inputs reaches every result it touches (IEEE
/// arithmetic: even ∞·0 is a NaN), so a solve given one fails, at its closed form or at its
/// results' finiteness check; the inputs are then looked at here, on the error path only,
/// and the common path checks nothing before it computes.
#[cold]
#[inline(never)]
pub fn blame(what: &str, values: &[f64], e: MechError) -> MechError {
    if all_finite(values) {
        e
    } else {
        not_finite(what, values)
    }
}

/// The error of [`check_finite`], out of line (the success path builds no message).
#[cold]
#[inline(never)]
fn not_finite(what: &str, values: &[f64]) -> MechError {
    MechError::InvalidInput(format!("{what} must be finite, got {values:?}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_flags_exactly_the_infinities_and_nans() {
        for v in [
            0.0,
            -0.0,
            1.0,
            -f64::MAX,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            assert!(!non_finite(v), "{v}");
        }
        for v in [f64::NAN, -f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(non_finite(v), "{v}");
        }
        // Values whose sum overflows are still finite (a sum-based test would need a
        // second look; the flags do not).
        assert!(all_finite(&[f64::MAX, f64::MAX, f64::MAX]));
        assert!(all_finite(&[]));
        assert!(!all_finite(&[1.0, 2.0, 3.0, 4.0, 5.0, f64::NAN]));
        // The inputs' test by Σ v·0 agrees, at the extremes too.
        for v in [0.0, -0.0, 1.0, -f64::MAX, f64::MAX, 5e-324] {
            assert!(all_finite_inputs(&[v, f64::MAX, -f64::MAX]), "{v}");
        }
        // A bad value anywhere, in either chain or the odd one left over, of 1 to 6 values.
        for v in [f64::NAN, -f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for n in 1..=6 {
                for at in 0..n {
                    let mut x = [-f64::MAX; 6];
                    x[at] = v;
                    assert!(!all_finite_inputs(&x[..n]), "{v} at {at} of {n}");
                }
            }
        }
        assert!(all_finite_inputs(&[]));
    }

    #[test]
    fn blame_names_non_finite_inputs_and_passes_other_errors_on() {
        let e = blame("q, qd", &[1.0, f64::INFINITY], MechError::NoAssembly);
        assert!(
            matches!(&e, MechError::InvalidInput(m) if m.starts_with("q, qd must be finite")),
            "{e:?}"
        );
        let e = blame("q, qd", &[1.0, 2.0], MechError::NoAssembly);
        assert!(matches!(e, MechError::NoAssembly), "{e:?}");
    }
}
