//! Static condensation: factor a constant bulk block once, refactor only a small dense Schur
//! complement when the interface block changes.

use faer::linalg::lu::partial_pivoting::{factor::lu_in_place, solve::solve_in_place};
use faer::linalg::lu::partial_pivoting::{
    factor::lu_in_place_scratch, solve::solve_in_place_scratch,
};

use crate::direct_params::DirectParams;
use crate::direct_solve::check_and_refine;
use crate::error::{SolverError, scratch};
use crate::linear_solver::{LinearSolver, check_rhs, check_square, check_values};
use crate::sparse_lu::SparseLu;
use crate::sparsity_pattern::SparsityPattern;

/// Columns of `A_BI` solved together when the Schur complement is formed.
const BLOCK_COLUMNS: usize = 64;

/// Where a slot of the full pattern goes.
#[derive(Clone, Copy, Debug)]
enum BlockSlot {
    /// Slot in the `A_BB` pattern.
    Bb(usize),
    /// Slot in the `A_BI` pattern.
    Bi(usize),
    /// Slot in the `A_IB` pattern.
    Ib(usize),
    /// Column-major index `row + col * n_I` in the dense `A_II`.
    Ii(usize),
}

#[derive(Clone, Copy, Debug)]
enum Local {
    Bulk(usize),
    Interface(usize),
}

#[derive(Debug)]
struct Layout {
    pattern: SparsityPattern,
    bulk: Vec<usize>,
    local: Vec<Local>,
    bi: SparsityPattern,
    ib: SparsityPattern,
    slot_map: Vec<BlockSlot>,
    ii_slots: Vec<usize>,
}

/// Direct solver by static condensation onto a small set of interface unknowns.
///
/// The unknowns split into a large bulk set `B` and a small interface set `I` (up to a few
/// thousand). When only the `I-I` block changes between Newton steps (friction acting on
/// contact-boundary unknowns of an otherwise linear body), the bulk block is factorised once
/// with [`SparseLu`] and every step only refactorises the dense Schur complement.
///
/// # Math
/// ```text
/// [ A_BB  A_BI ] [ x_B ]   [ b_B ]
/// [ A_IB  A_II ] [ x_I ] = [ b_I ]
///
/// S_0 = - A_IB A_BB^-1 A_BI        dense n_I x n_I, formed once per bulk factorisation
///                                  (A_BI solved 64 columns at a time)
/// S   = A_II + S_0                 dense LU with partial pivoting, per interface update
/// S x_I = b_I - A_IB A_BB^-1 b_B
/// x_B   = A_BB^-1 (b_B - A_BI x_I)
/// ```
/// Cost: one sparse LU of `A_BB` and `n_I` sparse solves per bulk change; `O(n_I^3)` per
/// interface change; two sparse solves and one dense solve per right-hand side. Memory: the
/// sparse factors plus two dense `n_I x n_I` matrices. Requires `A_BB` nonsingular (the
/// complement `S` is then nonsingular exactly when `A` is). Every full solution is checked
/// as in [`DirectParams`].
///
/// [`LinearSolver::factor`] compares the bulk blocks (`A_BB`, `A_BI`, `A_IB`) with the last
/// factorised values and redoes the bulk work only when they changed, so the solver can sit
/// behind [`crate::Newton::with_linear_solver`];
/// [`CondensedSolver::refactor_interface`] skips even the comparison.
///
/// # Errors
/// [`SolverError::InvalidParameter`] (field `interface`) for an interface index out of range
/// or repeated; [`SolverError::Singular`] when `A_BB` or `S` is singular (pivot in the full
/// numbering); the common errors of [`LinearSolver`].
///
/// # Example
/// ```
/// use capstan_solvers::{CondensedSolver, LinearSolver, SparseLu, samples::Poisson2d};
/// let system = Poisson2d::new(8).system();
/// let mut condensed = CondensedSolver::new(&[0, 1, 2, 3]); // condense onto four unknowns
/// let mut lu = SparseLu::default();
/// let mut x = [system.rhs.clone(), system.rhs.clone()];
/// for (solver, x) in [&mut condensed as &mut dyn LinearSolver<f64>, &mut lu].into_iter().zip(&mut x) {
///     solver.analyse(&system.pattern).unwrap();
///     solver.factor(&system.values).unwrap();
///     solver.solve_in_place(x).unwrap();
/// }
/// assert!(x[0].iter().zip(&x[1]).all(|(a, b)| (a - b).abs() < 1e-12));
/// ```
#[derive(Debug)]
pub struct CondensedSolver {
    params: DirectParams,
    interface: Vec<usize>,
    layout: Option<Layout>,
    bulk_lu: SparseLu,
    bb_values: Vec<f64>,
    bi_values: Vec<f64>,
    ib_values: Vec<f64>,
    /// `S_0 = -A_IB A_BB^-1 A_BI`, column-major.
    schur_bulk: Vec<f64>,
    /// LU factors of `S`, column-major (unit `L` below, `U` on and above the diagonal).
    schur_lu: Vec<f64>,
    perm_fwd: Vec<usize>,
    perm_inv: Vec<usize>,
    values: Vec<f64>,
    bulk_factored: bool,
    interface_factored: bool,
    bulk_factorisations: usize,
    interface_factorisations: usize,
}

impl CondensedSolver {
    /// A condensed solver for the given interface unknowns (indices into the full system; their
    /// order is the order of the Schur complement), with default [`DirectParams`].
    pub fn new(interface: &[usize]) -> Self {
        Self {
            params: DirectParams::default(),
            interface: interface.to_vec(),
            layout: None,
            bulk_lu: SparseLu::default(),
            bb_values: Vec::new(),
            bi_values: Vec::new(),
            ib_values: Vec::new(),
            schur_bulk: Vec::new(),
            schur_lu: Vec::new(),
            perm_fwd: Vec::new(),
            perm_inv: Vec::new(),
            values: Vec::new(),
            bulk_factored: false,
            interface_factored: false,
            bulk_factorisations: 0,
            interface_factorisations: 0,
        }
    }

    /// As [`CondensedSolver::new`] with explicit settings.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if `params` is out of range.
    pub fn with_params(interface: &[usize], params: DirectParams) -> Result<Self, SolverError> {
        params.validate()?;
        Ok(Self {
            params,
            bulk_lu: SparseLu::new(params)?,
            ..Self::new(interface)
        })
    }

    /// The interface unknowns, in Schur-complement order.
    pub fn interface(&self) -> &[usize] {
        &self.interface
    }

    /// Slots of the full pattern that belong to the `I-I` block (empty before `analyse`).
    pub fn interface_slots(&self) -> &[usize] {
        self.layout.as_ref().map_or(&[], |l| &l.ii_slots)
    }

    /// `(row, col)` in the full numbering of each `I-I` block entry, in the order of
    /// [`CondensedSolver::interface_slots`] (the order [`CondensedSolver::refactor_interface_block`]
    /// expects).
    pub fn interface_entries(&self) -> Vec<(usize, usize)> {
        let Some(layout) = self.layout.as_ref() else {
            return Vec::new();
        };
        let ni = self.interface.len();
        layout
            .ii_slots
            .iter()
            .map(|&s| match layout.slot_map[s] {
                BlockSlot::Ii(k) => (self.interface[k % ni], self.interface[k / ni]),
                _ => unreachable!("ii_slots holds I-I slots only"),
            })
            .collect()
    }

    /// Sparse LU factorisations of `A_BB` (each followed by forming `S_0`).
    pub fn bulk_factorisations(&self) -> usize {
        self.bulk_factorisations
    }

    /// Dense LU factorisations of the Schur complement `S`.
    pub fn interface_factorisations(&self) -> usize {
        self.interface_factorisations
    }

    /// Refactorises after a change of the `I-I` block only: reads `values` (full length, in
    /// pattern order) at [`CondensedSolver::interface_slots`] and ignores every other slot.
    ///
    /// # Errors
    /// [`SolverError::CallOrder`] before a full [`LinearSolver::factor`];
    /// [`SolverError::DimensionMismatch`], [`SolverError::NonFinite`],
    /// [`SolverError::Singular`] if `S` is singular.
    pub fn refactor_interface(&mut self, values: &[f64]) -> Result<(), SolverError> {
        let Some(layout) = self.layout.as_ref() else {
            return Err(SolverError::call_order("refactor_interface", "analyse"));
        };
        if !self.bulk_factored {
            return Err(SolverError::call_order("refactor_interface", "factor"));
        }
        layout.pattern.check_values_len(values.len())?;
        for &s in &layout.ii_slots {
            if !values[s].is_finite() {
                return Err(SolverError::NonFinite {
                    quantity: "matrix value",
                    index: s,
                    iteration: None,
                });
            }
        }
        for &s in &layout.ii_slots {
            self.values[s] = values[s];
        }
        self.factor_interface()
    }

    /// Refactorises with new values of the `I-I` block alone: `block_values[k]` is the value
    /// of entry [`CondensedSolver::interface_entries`]`()[k]` (full slot
    /// [`CondensedSolver::interface_slots`]`()[k]`).
    ///
    /// # Errors
    /// As [`CondensedSolver::refactor_interface`], with
    /// [`SolverError::DimensionMismatch`] if `block_values` has the wrong length.
    pub fn refactor_interface_block(&mut self, block_values: &[f64]) -> Result<(), SolverError> {
        let Some(layout) = self.layout.as_ref() else {
            return Err(SolverError::call_order(
                "refactor_interface_block",
                "analyse",
            ));
        };
        if !self.bulk_factored {
            return Err(SolverError::call_order(
                "refactor_interface_block",
                "factor",
            ));
        }
        if block_values.len() != layout.ii_slots.len() {
            return Err(SolverError::DimensionMismatch {
                quantity: "block_values",
                expected: layout.ii_slots.len(),
                found: block_values.len(),
            });
        }
        if let Some(index) = crate::scalar::first_non_finite(block_values) {
            return Err(SolverError::NonFinite {
                quantity: "matrix value",
                index: layout.ii_slots[index],
                iteration: None,
            });
        }
        for (&s, &v) in layout.ii_slots.iter().zip(block_values) {
            self.values[s] = v;
        }
        self.factor_interface()
    }

    fn factor_interface(&mut self) -> Result<(), SolverError> {
        self.interface_factored = false;
        let layout = self.layout.as_ref().expect("analysed");
        let ni = self.interface.len();
        self.schur_lu.copy_from_slice(&self.schur_bulk);
        for &s in &layout.ii_slots {
            if let BlockSlot::Ii(k) = layout.slot_map[s] {
                self.schur_lu[k] += self.values[s];
            }
        }
        if ni > 0 {
            let par = faer::get_global_parallelism();
            let mut mem = scratch(lu_in_place_scratch::<usize, f64>(
                ni,
                ni,
                par,
                Default::default(),
            ))?;
            let stack = faer::dyn_stack::MemStack::new(&mut mem);
            let a = faer::MatMut::from_column_major_slice_mut(&mut self.schur_lu, ni, ni);
            lu_in_place(
                a,
                &mut self.perm_fwd,
                &mut self.perm_inv,
                par,
                stack,
                Default::default(),
            );
            // Partial pivoting takes columns in order: a zero (or non-finite) U_kk means
            // column k of S has no usable pivot.
            for k in 0..ni {
                let d = self.schur_lu[k + k * ni];
                if d == 0.0 || !d.is_finite() {
                    return Err(SolverError::Singular {
                        pivot: Some(self.interface[k]),
                    });
                }
            }
        }
        self.interface_factored = true;
        self.interface_factorisations += 1;
        Ok(())
    }

    /// Factorises `A_BB` and forms `S_0 = -A_IB A_BB^-1 A_BI`.
    fn factor_bulk(&mut self) -> Result<(), SolverError> {
        self.bulk_factored = false;
        self.interface_factored = false;
        let layout = self.layout.as_ref().expect("analysed");
        let nb = layout.bulk.len();
        let ni = self.interface.len();
        self.schur_bulk.iter_mut().for_each(|v| *v = 0.0);
        if nb > 0 {
            self.bulk_lu
                .factor(&self.bb_values)
                .map_err(|e| to_global(e, &layout.bulk))?;
            let bi_ptr = layout.bi.col_ptr();
            let bi_rows = layout.bi.row_idx();
            let ib_ptr = layout.ib.col_ptr();
            let ib_rows = layout.ib.row_idx();
            let mut block = Vec::with_capacity(nb * BLOCK_COLUMNS.min(ni));
            for c0 in (0..ni).step_by(BLOCK_COLUMNS) {
                let k = BLOCK_COLUMNS.min(ni - c0);
                // columns of A_BI with at least one nonzero; the others give zero columns of S_0
                let cols: Vec<usize> = (c0..c0 + k)
                    .filter(|&c| bi_ptr[c] < bi_ptr[c + 1])
                    .collect();
                if cols.is_empty() {
                    continue;
                }
                block.clear();
                block.resize(nb * cols.len(), 0.0);
                for (jj, &c) in cols.iter().enumerate() {
                    for s in bi_ptr[c]..bi_ptr[c + 1] {
                        block[jj * nb + bi_rows[s]] = self.bi_values[s];
                    }
                }
                self.bulk_lu
                    .checked_solve(&mut block, cols.len())
                    .map_err(|e| to_global(e, &layout.bulk))?;
                for (jj, &c) in cols.iter().enumerate() {
                    let x = &block[jj * nb..(jj + 1) * nb];
                    let column = &mut self.schur_bulk[c * ni..(c + 1) * ni];
                    for (b, &xb) in x.iter().enumerate() {
                        if xb != 0.0 {
                            for s in ib_ptr[b]..ib_ptr[b + 1] {
                                column[ib_rows[s]] -= self.ib_values[s] * xb;
                            }
                        }
                    }
                }
            }
        }
        self.bulk_factored = true;
        self.bulk_factorisations += 1;
        Ok(())
    }

    /// The condensed solve without the final check.
    fn raw_solve(&self, rhs: &mut [f64]) -> Result<(), SolverError> {
        let layout = self.layout.as_ref().expect("factored");
        let nb = layout.bulk.len();
        let ni = self.interface.len();
        let mut b_bulk: Vec<f64> = layout.bulk.iter().map(|&g| rhs[g]).collect();
        let mut x_int: Vec<f64> = self.interface.iter().map(|&g| rhs[g]).collect();
        let bulk_err = |e| to_global(e, &layout.bulk);
        // y_B = A_BB^-1 b_B ;  c_I = b_I - A_IB y_B
        let mut y = b_bulk.clone();
        if nb > 0 && y.iter().any(|v| *v != 0.0) {
            self.bulk_lu.checked_solve(&mut y, 1).map_err(bulk_err)?;
            let (ptr, rows) = (layout.ib.col_ptr(), layout.ib.row_idx());
            for (b, &yb) in y.iter().enumerate() {
                for s in ptr[b]..ptr[b + 1] {
                    x_int[rows[s]] -= self.ib_values[s] * yb;
                }
            }
        }
        // x_I = S^-1 c_I
        if ni > 0 {
            let par = faer::get_global_parallelism();
            let mut mem = scratch(solve_in_place_scratch::<usize, f64>(ni, 1, par))?;
            let stack = faer::dyn_stack::MemStack::new(&mut mem);
            let lu = faer::MatRef::from_column_major_slice(&self.schur_lu, ni, ni);
            let perm = faer::perm::PermRef::new_checked(&self.perm_fwd, &self.perm_inv, ni);
            let x = faer::MatMut::from_column_major_slice_mut(&mut x_int, ni, 1);
            solve_in_place(lu, lu, perm, x, par, stack);
        }
        // x_B = A_BB^-1 (b_B - A_BI x_I)
        if nb > 0 {
            let (ptr, rows) = (layout.bi.col_ptr(), layout.bi.row_idx());
            for (c, &xc) in x_int.iter().enumerate() {
                for s in ptr[c]..ptr[c + 1] {
                    b_bulk[rows[s]] -= self.bi_values[s] * xc;
                }
            }
            if b_bulk.iter().any(|v| *v != 0.0) {
                self.bulk_lu
                    .checked_solve(&mut b_bulk, 1)
                    .map_err(bulk_err)?;
            }
        }
        for (&g, &v) in layout.bulk.iter().zip(&b_bulk) {
            rhs[g] = v;
        }
        for (&g, &v) in self.interface.iter().zip(&x_int) {
            rhs[g] = v;
        }
        Ok(())
    }
}

/// Maps a pivot in the bulk numbering back to the full numbering.
fn to_global(e: SolverError, bulk: &[usize]) -> SolverError {
    match e {
        SolverError::Singular { pivot } => SolverError::Singular {
            pivot: pivot.map(|p| bulk[p]),
        },
        other => other,
    }
}

impl LinearSolver<f64> for CondensedSolver {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        let n = check_square(pattern)?;
        self.layout = None;
        self.bulk_factored = false;
        self.interface_factored = false;
        let ni = self.interface.len();
        let mut local: Vec<Option<Local>> = vec![None; n];
        for (k, &g) in self.interface.iter().enumerate() {
            if g >= n || local[g].is_some() {
                return Err(SolverError::invalid(
                    "interface",
                    g as f64,
                    "distinct unknown indices below the matrix dimension",
                ));
            }
            local[g] = Some(Local::Interface(k));
        }
        let mut bulk = Vec::with_capacity(n - ni);
        let local: Vec<Local> = local
            .into_iter()
            .enumerate()
            .map(|(g, l)| {
                l.unwrap_or_else(|| {
                    bulk.push(g);
                    Local::Bulk(bulk.len() - 1)
                })
            })
            .collect();
        let nb = bulk.len();
        // Split the entries into the four blocks.
        let (mut bb, mut bi, mut ib) = (Vec::new(), Vec::new(), Vec::new());
        let mut which = Vec::with_capacity(pattern.nnz());
        let mut ii_slots = Vec::new();
        for j in 0..n {
            for s in pattern.col_ptr()[j]..pattern.col_ptr()[j + 1] {
                let i = pattern.row_idx()[s];
                which.push(match (local[i], local[j]) {
                    (Local::Bulk(r), Local::Bulk(c)) => {
                        bb.push((r, c));
                        BlockSlot::Bb(bb.len() - 1)
                    }
                    (Local::Bulk(r), Local::Interface(c)) => {
                        bi.push((r, c));
                        BlockSlot::Bi(bi.len() - 1)
                    }
                    (Local::Interface(r), Local::Bulk(c)) => {
                        ib.push((r, c));
                        BlockSlot::Ib(ib.len() - 1)
                    }
                    (Local::Interface(r), Local::Interface(c)) => {
                        ii_slots.push(s);
                        BlockSlot::Ii(r + c * ni)
                    }
                });
            }
        }
        let (bb_pattern, bb_slots) = SparsityPattern::from_entries(nb, nb, &bb)?;
        let (bi_pattern, bi_slots) = SparsityPattern::from_entries(nb, ni, &bi)?;
        let (ib_pattern, ib_slots) = SparsityPattern::from_entries(ni, nb, &ib)?;
        let slot_map = which
            .into_iter()
            .map(|w| match w {
                BlockSlot::Bb(k) => BlockSlot::Bb(bb_slots[k]),
                BlockSlot::Bi(k) => BlockSlot::Bi(bi_slots[k]),
                BlockSlot::Ib(k) => BlockSlot::Ib(ib_slots[k]),
                ii => ii,
            })
            .collect();
        if nb > 0 {
            self.bulk_lu.analyse(&bb_pattern)?;
        }
        self.bb_values = vec![0.0; bb_pattern.nnz()];
        self.bi_values = vec![0.0; bi_pattern.nnz()];
        self.ib_values = vec![0.0; ib_pattern.nnz()];
        self.schur_bulk = vec![0.0; ni * ni];
        self.schur_lu = vec![0.0; ni * ni];
        self.perm_fwd = vec![0; ni];
        self.perm_inv = vec![0; ni];
        self.values = vec![0.0; pattern.nnz()];
        self.layout = Some(Layout {
            pattern: pattern.clone(),
            bulk,
            local,
            bi: bi_pattern,
            ib: ib_pattern,
            slot_map,
            ii_slots,
        });
        Ok(())
    }

    fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
        let Some(layout) = self.layout.as_ref() else {
            return Err(SolverError::call_order("factor", "analyse"));
        };
        check_values(&layout.pattern, values)?;
        let mut bulk_changed = !self.bulk_factored;
        for (s, w) in layout.slot_map.iter().enumerate() {
            let (store, k) = match *w {
                BlockSlot::Bb(k) => (&mut self.bb_values, k),
                BlockSlot::Bi(k) => (&mut self.bi_values, k),
                BlockSlot::Ib(k) => (&mut self.ib_values, k),
                BlockSlot::Ii(_) => continue,
            };
            if store[k] != values[s] {
                store[k] = values[s];
                bulk_changed = true;
            }
        }
        self.values.copy_from_slice(values);
        if bulk_changed {
            self.factor_bulk()?;
        }
        self.factor_interface()
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
        let n = self.layout.as_ref().map_or(0, |l| l.local.len());
        check_rhs(rhs, n)?;
        if !self.interface_factored {
            return Err(SolverError::call_order("solve_in_place", "factor"));
        }
        let layout = self.layout.as_ref().expect("factored");
        let b = rhs.to_vec();
        self.raw_solve(rhs)?;
        let mut work = vec![0.0; n];
        let mut failure = None;
        check_and_refine(
            &self.params,
            &layout.pattern,
            &self.values,
            &b,
            rhs,
            &mut work,
            |r| {
                if let Err(e) = self.raw_solve(r) {
                    failure = Some(e);
                }
            },
        )?;
        failure.map_or(Ok(()), Err)
    }

    fn last_iterations(&self) -> Option<usize> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interface_must_be_distinct_and_in_range() {
        let (p, _) = SparsityPattern::from_entries(3, 3, &[(0, 0), (1, 1), (2, 2)]).unwrap();
        for bad in [&[0, 0][..], &[5]] {
            let err = CondensedSolver::new(bad).analyse(&p).unwrap_err();
            assert!(matches!(
                err,
                SolverError::InvalidParameter {
                    field: "interface",
                    ..
                }
            ));
        }
    }

    #[test]
    fn all_interface_and_no_interface_work() {
        // [[2, 1, 0], [1, 3, 0], [0, 0, 4]]
        let entries = [(0, 0), (1, 0), (0, 1), (1, 1), (2, 2)];
        let (p, slots) = SparsityPattern::from_entries(3, 3, &entries).unwrap();
        let mut values = vec![0.0; p.nnz()];
        for (k, v) in [2.0, 1.0, 1.0, 3.0, 4.0].into_iter().enumerate() {
            values[slots[k]] = v;
        }
        for interface in [&[][..], &[2, 0, 1]] {
            let mut s = CondensedSolver::new(interface);
            s.analyse(&p).unwrap();
            s.factor(&values).unwrap();
            let mut x = vec![3.0, 4.0, 8.0];
            s.solve_in_place(&mut x).unwrap();
            for (a, b) in x.iter().zip([1.0, 1.0, 2.0]) {
                assert!((a - b).abs() < 1e-14); // 3 x 3: round-off only
            }
        }
    }

    /// A dense 2 x 2 pattern analysed with unknown 1 as the interface.
    fn analysed_two_by_two() -> CondensedSolver {
        let entries = [(0, 0), (1, 0), (0, 1), (1, 1)];
        let (p, _) = SparsityPattern::from_entries(2, 2, &entries).unwrap();
        let mut s = CondensedSolver::new(&[1]);
        s.analyse(&p).unwrap();
        s
    }

    #[test]
    fn singular_interface_block_names_the_pivot() {
        // A_BB = [1], A_II = [1], A_IB = A_BI = [1]: S = 1 - 1 = 0
        let mut s = analysed_two_by_two();
        let err = s.factor(&[1.0, 1.0, 1.0, 1.0]).unwrap_err();
        assert!(matches!(err, SolverError::Singular { pivot: Some(1) }));
    }

    #[test]
    fn bulk_is_not_refactored_when_only_the_interface_changes() {
        let mut s = analysed_two_by_two();
        s.factor(&[2.0, 1.0, 1.0, 2.0]).unwrap();
        s.factor(&[2.0, 1.0, 1.0, 5.0]).unwrap();
        assert_eq!(
            (s.bulk_factorisations(), s.interface_factorisations()),
            (1, 2)
        );
        s.factor(&[3.0, 1.0, 1.0, 5.0]).unwrap();
        assert_eq!(s.bulk_factorisations(), 2);
        s.refactor_interface(&[99.0, 99.0, 99.0, 4.0]).unwrap(); // only slot 3 is read
        let mut x = vec![4.0, 5.0]; // [[3, 1], [1, 4]] [1, 1] = [4, 5]
        s.solve_in_place(&mut x).unwrap();
        assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14);
        assert_eq!(s.interface_slots(), &[3]);
    }
}
