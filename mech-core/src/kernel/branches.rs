//! The assembly branches of a mechanism with redundant constraints.
//!
//! Each closed-form group keeps the branch sign of the drawing. With redundant
//! constraints those signs may be the wrong ones past a change point (a parallelogram
//! folding): the redundant group then finds its equations inconsistent and reports
//! [`MechError::NoAssembly`]. [`search`] then tries the other combinations of signs.

use crate::MechError;

/// At most the first `MAX_FLIPPED` groups have their branch flipped by [`search`]
/// (2^8 = 256 combinations at most).
pub const MAX_FLIPPED: usize = 8;

/// `solve` on the drawing's branch signs `drawing`; while it reports `NoAssembly`, on
/// the next combination of flipped signs: combination c (1, 2, … < 2^min(G, 8)) negates
/// the sign of group k when bit k of c is set. The first answer that is not `NoAssembly`
/// is returned, else the last `NoAssembly`.
#[inline(always)]
pub fn search<B: AsRef<[f64]> + AsMut<[f64]> + Clone, T>(
    drawing: &B,
    mut solve: impl FnMut(&B) -> Result<T, MechError>,
) -> Result<T, MechError> {
    let mut result = solve(drawing);
    let g = drawing.as_ref().len();
    let combinations = 1u32 << g.min(MAX_FLIPPED);
    let mut flips = 1u32;
    while matches!(result, Err(MechError::NoAssembly)) && flips < combinations {
        let mut b = drawing.clone();
        for (k, x) in b.as_mut().iter_mut().enumerate().take(MAX_FLIPPED) {
            if flips & (1 << k) != 0 {
                *x = -*x;
            }
        }
        result = solve(&b);
        flips += 1;
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tries_every_combination_until_one_assembles() {
        let mut tried = Vec::new();
        let r = search(&[1.0, 1.0, -1.0], |b| {
            tried.push(*b);
            if *b == [-1.0, -1.0, -1.0] {
                Ok(7)
            } else {
                Err(MechError::NoAssembly)
            }
        });
        assert_eq!(r, Ok(7));
        assert_eq!(
            tried,
            vec![
                [1.0, 1.0, -1.0],
                [-1.0, 1.0, -1.0],
                [1.0, -1.0, -1.0],
                [-1.0, -1.0, -1.0]
            ]
        );
    }

    #[test]
    fn other_errors_stop_the_search() {
        let mut n = 0;
        let r: Result<(), _> = search(&[1.0, 1.0], |_| {
            n += 1;
            Err(MechError::Singular { condition: 1e17 })
        });
        assert!(matches!(r, Err(MechError::Singular { .. })));
        assert_eq!(n, 1);
        let r: Result<(), _> = search(&[1.0, 1.0], |_| Err(MechError::NoAssembly));
        assert_eq!(r, Err(MechError::NoAssembly));
    }
}
