//! The dense Schur complement of a sparse matrix onto a few trailing unknowns, from one
//! partial multifrontal factorisation.

use crate::error::SolverError;
use crate::linear_solver::{check_square, check_values};
use crate::multifrontal_lu::{FrontFailure, FrontalStructure};
use crate::ordering::{amd_symmetrised, is_permutation};
use crate::sparsity_pattern::SparsityPattern;

/// The dense Schur complement of the sparse square `A` (`values` in `pattern` order) onto the
/// unknowns `trailing`: `S = A_TT - A_TI A_II^-1 A_IT`, `k x k` column-major, row and column
/// `i` being `trailing[i]`. The interior is eliminated in the order of `order` (a permutation
/// of all unknowns, `order[k]` eliminated `k`-th, the trailing ones skipped: e.g. a nested
/// dissection of the grid), or by AMD for `None`. `Ok(None)` when the interior needs row
/// pivoting across fronts (a pivot below 0.01 of its column inside every front): compute `S`
/// by solves instead.
///
/// # Math
/// ```text
/// Q = [order or AMD(A_II + A_II^T), T]   the interior first, the trailing unknowns last
/// Q^T A Q = [A_II A_IT; A_TI A_TT]    multifrontal LU of the interior fronts only
/// S = A_TT - A_TI A_II^-1 A_IT        the contribution blocks left for T, extend-added
/// ```
/// The cost is one factorisation of `A_II` (no solves): where `(A^-1)_TT` or `A^-1` applied
/// to right-hand sides supported on `T` is needed for all of `T`, `S` replaces `k` sparse
/// solves: `(A^-1)_TT = S^-1`, and for `b` supported on `T`,
/// `x_T = S^-1 b_T`, `x_I = -A_II^-1 A_IT x_T`.
///
/// # Errors
/// [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`] or
/// [`SolverError::NonFinite`] for bad input; [`SolverError::InvalidParameter`]
/// (`trailing`, `order`) for an index out of range or repeated; [`SolverError::Singular`] when `A_II`
/// is singular; [`SolverError::Backend`] when faer's analysis runs out of memory.
///
/// # Example
/// ```
/// use capstan_solvers::{SparsityPattern, schur_complement};
/// // A = [[4, 1, 0], [1, 4, 1], [0, 1, 4]], T = {1}: S = 4 - 1/4 - 1/4
/// let entries = [(0, 0), (1, 0), (0, 1), (1, 1), (2, 1), (1, 2), (2, 2)];
/// let (pattern, _) = SparsityPattern::from_entries(3, 3, &entries).unwrap();
/// let values = [4.0, 1.0, 1.0, 4.0, 1.0, 1.0, 4.0];
/// let s = schur_complement(&pattern, &values, &[1], None).unwrap().unwrap();
/// assert!((s[0] - 3.5).abs() < 1e-15);
/// ```
pub fn schur_complement(
    pattern: &SparsityPattern,
    values: &[f64],
    trailing: &[usize],
    order: Option<&[usize]>,
) -> Result<Option<Vec<f64>>, SolverError> {
    let n = check_square(pattern)?;
    check_values(pattern, values)?;
    let k = trailing.len();
    let mut interior_index = vec![usize::MAX - 1; n]; // MAX - 1: interior, unnumbered
    for &t in trailing {
        if t >= n || interior_index[t] == usize::MAX {
            return Err(SolverError::InvalidParameter {
                field: "trailing",
                value: t as f64,
                allowed: "distinct indices in [0, n)",
            });
        }
        interior_index[t] = usize::MAX;
    }
    let mut interior = Vec::with_capacity(n - k);
    for (j, index) in interior_index.iter_mut().enumerate() {
        if *index != usize::MAX {
            *index = interior.len();
            interior.push(j);
        }
    }
    let mut perm: Vec<usize> = match order {
        Some(order) => {
            if !is_permutation(order, n) {
                return Err(SolverError::InvalidParameter {
                    field: "order",
                    value: order.len() as f64,
                    allowed: "a permutation of 0..n",
                });
            }
            order
                .iter()
                .copied()
                .filter(|&j| interior_index[j] != usize::MAX)
                .collect()
        }
        None => {
            let entries: Vec<(usize, usize)> = pattern
                .entries()
                .filter(|&(i, j)| {
                    interior_index[i] != usize::MAX && interior_index[j] != usize::MAX
                })
                .map(|(i, j)| (interior_index[i], interior_index[j]))
                .collect();
            let (inner, _) = SparsityPattern::from_entries(n - k, n - k, &entries)?;
            amd_symmetrised(&inner)?
                .into_iter()
                .map(|p| interior[p])
                .collect()
        }
    };
    perm.extend_from_slice(trailing);
    let Some(structure) = FrontalStructure::analyse(pattern, Some(&perm))? else {
        return Ok(None);
    };
    debug_assert_eq!(structure.permutation(), perm.as_slice());
    match structure.schur_complement(pattern, values, n - k, faer::get_global_parallelism()) {
        Ok(s) => Ok(Some(s)),
        Err(FrontFailure::NeedsPivoting) => Ok(None),
        Err(FrontFailure::Singular(column)) => Err(SolverError::Singular {
            pivot: Some(column),
        }),
        Err(FrontFailure::NonFinite) => Err(SolverError::Singular { pivot: None }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;
    use faer::linalg::solvers::Solve;

    /// A 2-D convection-diffusion matrix on an `nx x ny` grid (unsymmetric values, symmetric
    /// structure), with a few extra long-range couplings.
    fn convection_diffusion(nx: usize, ny: usize) -> (SparsityPattern, Vec<f64>) {
        let n = nx * ny;
        let id = |i: usize, j: usize| i + nx * j;
        let mut terms = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let p = id(i, j);
                terms.push((p, p, 4.3 + 0.01 * (p % 7) as f64));
                if i > 0 {
                    terms.push((p, id(i - 1, j), -1.2));
                }
                if i + 1 < nx {
                    terms.push((p, id(i + 1, j), -0.8));
                }
                if j > 0 {
                    terms.push((p, id(i, j - 1), -1.1));
                }
                if j + 1 < ny {
                    terms.push((p, id(i, j + 1), -0.9));
                }
            }
        }
        let entries: Vec<(usize, usize)> = terms.iter().map(|&(i, j, _)| (i, j)).collect();
        let (pattern, slots) = SparsityPattern::from_entries(n, n, &entries).unwrap();
        let mut values = vec![0.0; pattern.nnz()];
        for (t, &slot) in terms.iter().zip(&slots) {
            values[slot] += t.2;
        }
        (pattern, values)
    }

    /// `A_TT - A_TI A_II^-1 A_IT` by dense LU.
    fn dense_schur(pattern: &SparsityPattern, values: &[f64], trailing: &[usize]) -> Mat<f64> {
        let n = pattern.nrows();
        let mut a = Mat::<f64>::zeros(n, n);
        for ((i, j), v) in pattern.entries().zip(values) {
            a[(i, j)] += v;
        }
        let interior: Vec<usize> = (0..n).filter(|j| !trailing.contains(j)).collect();
        let sub = |rows: &[usize], cols: &[usize]| {
            Mat::<f64>::from_fn(rows.len(), cols.len(), |i, j| a[(rows[i], cols[j])])
        };
        let a_ii = sub(&interior, &interior);
        let a_it = sub(&interior, trailing);
        let a_ti = sub(trailing, &interior);
        let a_tt = sub(trailing, trailing);
        let x = a_ii.partial_piv_lu().solve(&a_it);
        a_tt - a_ti * x
    }

    #[test]
    fn schur_complement_matches_dense_elimination() {
        let (pattern, values) = convection_diffusion(23, 9);
        // the bottom edge of the grid (a contact face) and a few scattered unknowns
        let mut trailing: Vec<usize> = (0..23).collect();
        trailing.extend([100, 57, 206]);
        let s = schur_complement(&pattern, &values, &trailing, None)
            .unwrap()
            .unwrap();
        let dense = dense_schur(&pattern, &values, &trailing);
        let k = trailing.len();
        let scale = (0..k).map(|i| dense[(i, i)].abs()).fold(0.0, f64::max);
        for j in 0..k {
            for i in 0..k {
                // round-off of two eliminations of a well-conditioned matrix
                assert!(
                    (s[i + k * j] - dense[(i, j)]).abs() < 1e-13 * scale,
                    "({i}, {j}): {} vs {}",
                    s[i + k * j],
                    dense[(i, j)]
                );
            }
        }
    }

    #[test]
    fn schur_complement_in_a_given_order_matches_dense_elimination() {
        let (pattern, values) = convection_diffusion(17, 6);
        let trailing: Vec<usize> = (0..17).collect();
        let order: Vec<usize> = (0..17 * 6).rev().collect(); // any permutation will do
        let s = schur_complement(&pattern, &values, &trailing, Some(&order))
            .unwrap()
            .unwrap();
        let dense = dense_schur(&pattern, &values, &trailing);
        for j in 0..17 {
            for i in 0..17 {
                // round-off of two eliminations of a well-conditioned matrix
                assert!((s[i + 17 * j] - dense[(i, j)]).abs() < 1e-13 * dense[(0, 0)].abs());
            }
        }
        assert!(matches!(
            schur_complement(&pattern, &values, &trailing, Some(&[0, 1])),
            Err(SolverError::InvalidParameter { field: "order", .. })
        ));
    }

    #[test]
    fn schur_complement_of_everything_and_of_nothing() {
        let (pattern, values) = convection_diffusion(4, 3);
        let all: Vec<usize> = (0..12).rev().collect();
        let s = schur_complement(&pattern, &values, &all, None)
            .unwrap()
            .unwrap();
        let dense = dense_schur(&pattern, &values, &all);
        for j in 0..12 {
            for i in 0..12 {
                assert_eq!(s[i + 12 * j], dense[(i, j)]); // no elimination: A_TT itself
            }
        }
        assert_eq!(
            schur_complement(&pattern, &values, &[], None).unwrap(),
            Some(vec![])
        );
    }

    #[test]
    fn schur_complement_rejects_bad_trailing_and_reports_pivoting() {
        let (pattern, values) = convection_diffusion(4, 3);
        for bad in [vec![12], vec![3, 3]] {
            assert!(matches!(
                schur_complement(&pattern, &values, &bad, None),
                Err(SolverError::InvalidParameter {
                    field: "trailing",
                    ..
                })
            ));
        }
        // A = [[0, 1], [1, 1]], T = {1}: the interior pivot 0 needs the trailing row
        let (p, _) =
            SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
        assert_eq!(
            schur_complement(&p, &[0.0, 1.0, 1.0, 1.0], &[1], None).unwrap(),
            None
        );
        // a singular interior
        let (p, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 1)]).unwrap();
        assert!(matches!(
            schur_complement(&p, &[0.0, 1.0], &[1], None),
            Err(SolverError::Singular { .. })
        ));
    }
}
