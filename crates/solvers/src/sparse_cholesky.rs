//! faer sparse Cholesky (`L L^T`) for symmetric positive definite systems.

use faer::linalg::cholesky::llt::factor::{LltError as DenseLltError, LltRegularization};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering, factorize_symbolic_cholesky,
};

use crate::direct_params::DirectParams;
use crate::direct_solve::{
    analysed_values, check_no_empty_line, checked_solve, direct_solves, finite_rhs,
};
use crate::error::{SolverError, scratch};
use crate::linear_registration::{BackendKind, Parameter, RegisteredLinearSolver};
use crate::linear_solver::{LinearSolver, check_square};
use crate::ordering::ColumnOrdering;
use crate::scalar::max_abs;
use crate::sparsity_pattern::SparsityPattern;

/// Sparse Cholesky factorisation (faer) for symmetric positive definite (SPD) matrices.
///
/// `analyse` computes an approximate-minimum-degree ordering (or the nested dissection of
/// [`DirectParams::ordering`]) and the symbolic factor once;
/// `factor` refills the numeric factor. Only the lower triangle is factorised, so `factor`
/// first checks that the values are symmetric (the pattern may hold both triangles or just
/// the lower one; a missing transpose counts as zero). On SPD systems (FEM stiffness with
/// enough Dirichlet conditions) this is far cheaper than LU, whose structure comes from
/// `A^T A`.
///
/// # Math
/// ```text
/// P A P^T = L L^T        P: AMD ordering (symbolic, once)
/// x = P^T L^-T L^-1 P b
/// symmetric iff |a_ij - a_ji| <= symmetry_tolerance * max |a|
/// ```
///
/// # Errors
/// [`SolverError::NotSymmetric`] for asymmetric values, [`SolverError::NotPositiveDefinite`]
/// when a pivot is not positive, [`SolverError::Singular`] for an empty row or column or a
/// solution that fails the check of [`DirectParams`]; the common errors of [`LinearSolver`].
///
/// # Example
/// ```
/// use capstan_solvers::{LinearSolver, SolverError, SparseCholesky, SparsityPattern};
/// let (pattern, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
/// let mut chol = SparseCholesky::default();
/// chol.analyse(&pattern).unwrap();
/// chol.factor(&[2.0, 1.0, 1.0, 2.0]).unwrap(); // SPD
/// let mut x = vec![3.0, 3.0];
/// chol.solve_in_place(&mut x).unwrap();
/// assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14);
/// // symmetric but indefinite: eigenvalues 3 and -1
/// let err = chol.factor(&[1.0, 2.0, 2.0, 1.0]).unwrap_err();
/// assert!(matches!(err, SolverError::NotPositiveDefinite { .. }));
/// ```
#[derive(Debug, Default)]
pub struct SparseCholesky {
    params: DirectParams,
    pattern: Option<SparsityPattern>,
    symbolic: Option<SymbolicCholesky<usize>>,
    transpose_slot: Vec<Option<usize>>,
    /// The lower triangle (diagonal included) that faer factorises, and the slot in `pattern`
    /// of each of its entries.
    lower: Option<SparsityPattern>,
    lower_slot: Vec<usize>,
    lower_values: Vec<f64>,
    l_values: Vec<f64>,
    values: Vec<f64>,
    factored: bool,
    factorisations: usize,
}

impl SparseCholesky {
    /// A solver with the given settings (`symmetry_tolerance` and the solution check).
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if `params` is out of range.
    pub fn new(params: DirectParams) -> Result<Self, SolverError> {
        params.validate()?;
        Ok(Self {
            params,
            ..Default::default()
        })
    }

    /// Numeric factorisations done since construction.
    pub fn factorisations(&self) -> usize {
        self.factorisations
    }

    /// Values stored for the factor `L` by the last `analyse` (the fill of the ordering,
    /// supernodal padding included), 0 before it.
    pub fn factor_values(&self) -> usize {
        self.l_values.len()
    }

    fn check_symmetry(&self, pattern: &SparsityPattern, values: &[f64]) -> Result<(), SolverError> {
        let bound = self.params.symmetry_tolerance * max_abs(values);
        let col_ptr = pattern.col_ptr();
        let row_idx = pattern.row_idx();
        for j in 0..pattern.ncols() {
            for s in col_ptr[j]..col_ptr[j + 1] {
                let i = row_idx[s];
                let mirror = self.transpose_slot[s].map_or(0.0, |t| values[t]);
                if (values[s] - mirror).abs() > bound {
                    return Err(SolverError::NotSymmetric { row: i, col: j });
                }
            }
        }
        Ok(())
    }

    fn raw_solve(
        symbolic: &SymbolicCholesky<usize>,
        l_values: &[f64],
        rhs: &mut [f64],
        n: usize,
        ncols: usize,
    ) -> Result<(), SolverError> {
        let par = faer::get_global_parallelism();
        let mut mem = scratch(symbolic.solve_in_place_scratch::<f64>(ncols, par))?;
        let stack = faer::dyn_stack::MemStack::new(&mut mem);
        let mat = faer::MatMut::from_column_major_slice_mut(rhs, n, ncols);
        LltRef::new(symbolic, l_values).solve_in_place_with_conj(faer::Conj::No, mat, par, stack);
        Ok(())
    }

    fn checked_solve(&self, rhs: &mut [f64], ncols: usize) -> Result<(), SolverError> {
        let (Some(pattern), Some(symbolic), true) =
            (self.pattern.as_ref(), self.symbolic.as_ref(), self.factored)
        else {
            return Err(SolverError::call_order("solve_in_place", "factor"));
        };
        let n = pattern.nrows();
        if !finite_rhs(rhs, n)? {
            return Ok(());
        }
        checked_solve(&self.params, pattern, &self.values, rhs, ncols, |r, k| {
            Self::raw_solve(symbolic, &self.l_values, r, n, k)
        })
    }
}

/// The `cholesky` entry of [`crate::linear_registry`].
pub(crate) const REGISTRATION: RegisteredLinearSolver = RegisteredLinearSolver {
    name: "cholesky",
    summary: "sparse Cholesky (faer): symmetric positive definite matrices",
    parameters: &[
        Parameter {
            key: "direct.ordering",
            default: "auto",
            allowed: "auto, colamd, amd, nested-dissection",
        },
        Parameter {
            key: "direct.residual_tolerance",
            default: "1e-8",
            allowed: "(0, 1)",
        },
        Parameter {
            key: "direct.refinement_steps",
            default: "2",
            allowed: "[0, inf)",
        },
        Parameter {
            key: "direct.symmetry_tolerance",
            default: "1e-10",
            allowed: "[0, 1)",
        },
    ],
    kind: BackendKind::Direct,
    build: |s, _| Ok(Box::new(SparseCholesky::new(s.direct)?)),
};

impl LinearSolver<f64> for SparseCholesky {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        let n = check_square(pattern)?;
        self.factored = false;
        self.pattern = None;
        self.symbolic = None;
        self.transpose_slot = transpose_slots(pattern);
        let (lower, lower_slot) = lower_triangle(pattern);
        let symmetric = self.transpose_slot.iter().all(Option::is_some);
        // AMD unless a nested dissection is asked for (`Auto` and `Amd` are the same here); on
        // a structurally symmetric pattern AMD runs on the quotient by indistinguishable
        // unknowns (the unknowns of a node), a quarter of the work for 2 unknowns per node
        let perm = match self.params.ordering {
            ColumnOrdering::Auto | ColumnOrdering::Amd if symmetric => {
                Some(crate::ordering::amd_compressed(pattern)?)
            }
            ColumnOrdering::Auto | ColumnOrdering::Amd => None,
            ordering @ (ColumnOrdering::NestedDissection { .. }
            | ColumnOrdering::ElementNestedDissection { .. }) => ordering.permutation(pattern)?,
        };
        let inverse = perm.as_ref().map(|p| {
            let mut inv = vec![0usize; n];
            for (k, &j) in p.iter().enumerate() {
                inv[j] = k;
            }
            inv
        });
        let ordering = match (&perm, &inverse) {
            (Some(p), Some(inv)) => SymmetricOrdering::Custom(PermRef::new_checked(p, inv, n)),
            _ => SymmetricOrdering::Amd,
        };
        let symbolic = factorize_symbolic_cholesky(
            lower.as_faer_symbolic(),
            faer::Side::Lower,
            ordering,
            Default::default(),
        )?;
        self.l_values = vec![0.0; symbolic.len_val()];
        self.symbolic = Some(symbolic);
        self.lower_values = vec![0.0; lower.nnz()];
        self.lower = Some(lower);
        self.lower_slot = lower_slot;
        self.pattern = Some(pattern.clone());
        self.values = vec![0.0; pattern.nnz()];
        Ok(())
    }

    fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
        self.factored = false;
        let pattern = analysed_values(self.pattern.as_ref(), values)?;
        self.check_symmetry(pattern, values)?;
        check_no_empty_line(pattern, values)?;
        self.values.copy_from_slice(values);
        for (x, &slot) in self.lower_values.iter_mut().zip(&self.lower_slot) {
            *x = values[slot];
        }
        let lower = self.lower.as_ref().expect("set together with pattern");
        let symbolic = self.symbolic.as_ref().expect("set together with pattern");
        let n = pattern.nrows();
        if n > 0 {
            let par = faer::get_global_parallelism();
            let mut mem =
                scratch(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()))?;
            let stack = faer::dyn_stack::MemStack::new(&mut mem);
            symbolic
                .factorize_numeric_llt(
                    &mut self.l_values,
                    lower.as_faer(&self.lower_values),
                    faer::Side::Lower,
                    LltRegularization::default(),
                    par,
                    stack,
                    Default::default(),
                )
                .map_err(|e| match e {
                    DenseLltError::NonPositivePivot { index } => {
                        // faer 0.24 counts the failing column from 1 in the simplicial
                        // kernel and from 0 in the supernodal one, in the AMD-permuted order.
                        let index = match symbolic.raw() {
                            SymbolicCholeskyRaw::Simplicial(_) => index.saturating_sub(1),
                            SymbolicCholeskyRaw::Supernodal(_) => index,
                        }
                        .min(n - 1);
                        let pivot = symbolic.perm().map_or(index, |p| p.arrays().0[index]);
                        SolverError::NotPositiveDefinite { pivot }
                    }
                })?;
        }
        self.factored = true;
        self.factorisations += 1;
        Ok(())
    }

    direct_solves!();
}

/// The slot of the transpose `(j, i)` of every entry `(i, j)`, `None` where it is not in the
/// pattern. One sweep: for a fixed column `i` the queries `(j, i)` come in increasing `j`, so a
/// cursor per column only moves forward (rows are sorted within a column).
fn transpose_slots(pattern: &SparsityPattern) -> Vec<Option<usize>> {
    let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
    let mut cursor: Vec<usize> = col_ptr[..pattern.ncols()].to_vec();
    let mut out = vec![None; pattern.nnz()];
    for j in 0..pattern.ncols() {
        for s in col_ptr[j]..col_ptr[j + 1] {
            let i = row_idx[s];
            if i >= pattern.ncols() {
                continue; // rectangular: no transpose column
            }
            let end = col_ptr[i + 1];
            let mut c = cursor[i];
            while c < end && row_idx[c] < j {
                c += 1;
            }
            cursor[i] = c;
            if c < end && row_idx[c] == j {
                out[s] = Some(c);
            }
        }
    }
    out
}

/// The lower triangle `i >= j` of a pattern, and the slot in `pattern` of each of its entries.
fn lower_triangle(pattern: &SparsityPattern) -> (SparsityPattern, Vec<usize>) {
    let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
    let mut lower_ptr = Vec::with_capacity(pattern.ncols() + 1);
    let mut lower_rows = Vec::with_capacity(pattern.nnz() / 2 + pattern.ncols());
    let mut slots = Vec::with_capacity(lower_rows.capacity());
    lower_ptr.push(0);
    for j in 0..pattern.ncols() {
        for (s, &i) in row_idx
            .iter()
            .enumerate()
            .take(col_ptr[j + 1])
            .skip(col_ptr[j])
        {
            if i >= j {
                lower_rows.push(i);
                slots.push(s);
            }
        }
        lower_ptr.push(lower_rows.len());
    }
    let lower = SparsityPattern::from_compressed_columns(
        pattern.nrows(),
        pattern.ncols(),
        lower_ptr,
        lower_rows,
    )
    .expect("a subset of a valid pattern");
    (lower, slots)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn full_2x2() -> SparsityPattern {
        SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)])
            .unwrap()
            .0
    }

    #[test]
    fn transpose_slots_equal_binary_search() {
        // an unsymmetric 7 x 7 pattern: some transposes missing, empty columns
        let entries: Vec<(usize, usize)> = (0..7)
            .flat_map(|i| (0..7).map(move |j| (i, j)))
            .filter(|&(i, j)| (3 * i + 5 * j) % 4 != 1 && j != 4)
            .collect();
        let (p, _) = SparsityPattern::from_entries(7, 7, &entries).unwrap();
        let expected: Vec<Option<usize>> = p.entries().map(|(i, j)| p.slot(j, i)).collect();
        assert!(expected.iter().any(Option::is_none) && expected.iter().any(Option::is_some));
        assert_eq!(transpose_slots(&p), expected);
    }

    #[test]
    fn lower_triangle_keeps_the_entries_on_and_below_the_diagonal() {
        let (p, _) =
            SparsityPattern::from_entries(3, 3, &[(0, 0), (2, 0), (0, 1), (1, 1), (0, 2), (2, 2)])
                .unwrap();
        let (lower, slots) = lower_triangle(&p);
        assert_eq!(
            lower.entries().collect::<Vec<_>>(),
            vec![(0, 0), (2, 0), (1, 1), (2, 2)]
        );
        assert_eq!(slots, vec![0, 1, 3, 5]);
    }

    #[test]
    fn compressed_ordering_solves_a_two_unknowns_per_node_system() {
        // 1-D chain of 6 nodes, 2 coupled unknowns per node: SPD block tridiagonal
        let n: usize = 12;
        let mut entries = vec![];
        let mut values = vec![];
        for i in 0..n {
            for j in 0..n {
                let (a, b) = (i / 2, j / 2);
                if a.abs_diff(b) <= 1 {
                    entries.push((i, j));
                    values.push(if i == j {
                        4.0
                    } else if a == b {
                        1.0
                    } else {
                        -1.0
                    });
                }
            }
        }
        let (p, slots) = SparsityPattern::from_entries(n, n, &entries).unwrap();
        let mut v = vec![0.0; p.nnz()];
        for (s, x) in slots.iter().zip(values) {
            v[*s] += x;
        }
        let x_true: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut b = vec![0.0; n];
        p.matvec(&v, &x_true, &mut b);
        let mut chol = SparseCholesky::default();
        chol.analyse(&p).unwrap();
        chol.factor(&v).unwrap();
        chol.solve_in_place(&mut b).unwrap();
        for (x, t) in b.iter().zip(&x_true) {
            assert!((x - t).abs() < 1e-13); // well-conditioned: round-off only
        }
    }

    #[test]
    fn asymmetric_values_are_rejected() {
        let mut chol = SparseCholesky::default();
        chol.analyse(&full_2x2()).unwrap();
        let err = chol.factor(&[2.0, 1.0, 0.5, 2.0]).unwrap_err();
        assert!(matches!(err, SolverError::NotSymmetric { row: 1, col: 0 }));
    }

    #[test]
    fn lower_triangle_only_pattern_is_treated_as_asymmetric_unless_diagonal() {
        let (p, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (1, 1)]).unwrap();
        let mut chol = SparseCholesky::default();
        chol.analyse(&p).unwrap();
        assert!(matches!(
            chol.factor(&[2.0, 1.0, 2.0]),
            Err(SolverError::NotSymmetric { .. })
        ));
        chol.factor(&[2.0, 0.0, 2.0]).unwrap();
        let mut x = vec![2.0, 4.0];
        chol.solve_in_place(&mut x).unwrap();
        for (a, b) in x.iter().zip([1.0, 2.0]) {
            assert!((a - b).abs() < 1e-15); // diagonal 2 x 2: round-off only
        }
    }

    #[test]
    fn solve_many_equals_default_column_loop() {
        let mut chol = SparseCholesky::default();
        chol.analyse(&full_2x2()).unwrap();
        chol.factor(&[4.0, 1.0, 1.0, 3.0]).unwrap();
        let mut blocked = vec![1.0, 2.0, -3.0, 0.5];
        chol.solve_many_in_place(&mut blocked, 2).unwrap();
        let mut a = vec![1.0, 2.0];
        let mut b = vec![-3.0, 0.5];
        chol.solve_in_place(&mut a).unwrap();
        chol.solve_in_place(&mut b).unwrap();
        for (x, y) in blocked.iter().zip(a.iter().chain(&b)) {
            assert!((x - y).abs() <= 1e-15); // same factors: round-off only
        }
    }
}
