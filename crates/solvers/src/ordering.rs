//! Fill-reducing orderings for the direct backends: COLAMD (faer's default for LU), AMD on the
//! symmetrised pattern, and a geometric nested dissection for structured grids.

use crate::error::SolverError;
use crate::sparsity_pattern::SparsityPattern;

/// The shape of a structured grid, as metadata a discretisation passes to a solver. Knows no
/// physics: only how unknowns are numbered.
///
/// # Math
/// ```text
/// dof(i2, i3, c) = dofs_per_node * (i2 * n3 + i3) + c
///     0 <= i2 < n2,  0 <= i3 < n3,  0 <= c < dofs_per_node
/// periodic: node (n2 - 1, i3) neighbours node (0, i3)
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridShape {
    /// Nodes along the first (slow, possibly periodic) direction.
    pub n2: usize,
    /// Nodes along the second (fast) direction.
    pub n3: usize,
    /// Unknowns per node, numbered consecutively.
    pub dofs_per_node: usize,
    /// Whether the first direction wraps around.
    #[serde(default)]
    pub periodic: bool,
}

impl GridShape {
    /// Number of unknowns `n2 * n3 * dofs_per_node`.
    pub fn dof_count(&self) -> usize {
        self.n2 * self.n3 * self.dofs_per_node
    }
}

/// How a direct backend orders the columns before factorising.
///
/// The supernodal kernel of [`crate::SparseLu`] ([`crate::LuKind::Supernodal`]) builds its
/// static structure from `A^T A` (valid for any row pivoting), so a nested dissection for it
/// must cut the couplings of `A^T A`: twice the stencil reach of `A`. The multifrontal kernel
/// (the default) and [`crate::SparseCholesky`] use the structure of `A + A^T` (of `A`) and need
/// only the reach of `A`: on the Navier operator 1-line separators give it 12.1e6 stored values
/// at 500 x 81 against 17.4e6 with 2-line ones and 13.2e6 with AMD (`Auto`).
///
/// Which ordering wins depends on the stencil. Measured with the supernodal LU (bench
/// `bench_navier` of the elasticity crate: 2 unknowns per node, 9-point stencil with reach-2
/// one-sided boundary rows; 2 shared cores, timings within about 30%), nested dissection with
/// 2-line separators against COLAMD:
/// ```text
/// grid        unknowns   fill bound (1e6)   analyse s     factor s      VmHWM MiB
///                        colamd    nd       colamd  nd    colamd  nd    colamd   nd
/// 250 x 41      20,500     7.8      6.1      0.08  0.01    0.15  0.11     102     76
/// 500 x 81      81,000    43.2     32.3      0.44  0.05    0.89  0.58     496    355
/// 1000 x 161   322,000   215.1    163.3      1.89  0.21    4.84  3.72    2280   1677
/// 2000 x 321 1,284,000   975.0    797.7      5.68  1.05   30.6  25.1     9998   7881
/// ```
/// (fill bound: [`crate::SparseLu::structural_fill_bound`]; separators 3 and 4 lines wide
/// were worse, 1 line far worse: it leaves the halves coupled in `A^T A`). On the 5-point
/// Laplacian (1 unknown per node) COLAMD has the smaller bound, by about 25%. [`Amd`] on
/// `A + A^T` is poor for the supernodal LU (250 x 41 Navier: bound 6.8x COLAMD's, factor 45x
/// slower): it ignores the `A^T A` structure.
///
/// [`Amd`]: ColumnOrdering::Amd
///
/// # Example
/// ```
/// use capstan_solvers::{ColumnOrdering, DirectParams, GridShape, LinearSolver, SparseLu};
/// use capstan_solvers::samples::Poisson2d;
/// let system = Poisson2d::new(20).system(); // unknown k = i + 20 j: n2 = 20 (j), n3 = 20 (i)
/// let grid = GridShape { n2: 20, n3: 20, dofs_per_node: 1, periodic: false };
/// let params = DirectParams {
///     ordering: ColumnOrdering::NestedDissection { grid, separator_width: 2 },
///     ..Default::default()
/// };
/// let mut lu = SparseLu::new(params).unwrap();
/// lu.analyse(&system.pattern).unwrap();
/// lu.factor(&system.values).unwrap();
/// let mut x = system.rhs.clone();
/// lu.solve_in_place(&mut x).unwrap();
/// assert!(system.residual_norm(&x) < 1e-12);
/// ```
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum ColumnOrdering {
    /// The backend's own choice: AMD on `A + A^T` for the multifrontal LU, COLAMD for the
    /// supernodal LU, AMD for Cholesky.
    #[default]
    Auto,
    /// Approximate minimum degree on the pattern of `A + A^T` ([`amd_symmetrised`]).
    Amd,
    /// Geometric nested dissection of a structured grid ([`nested_dissection_grid`]).
    NestedDissection {
        /// How the unknowns are numbered.
        grid: GridShape,
        /// Grid lines per separator: at least the stencil reach of the factorised structure
        /// (`A^T A` for LU, `A` for Cholesky).
        separator_width: usize,
    },
    /// Nested dissection of a structured grid of finite elements, cut along element
    /// boundaries by single node lines ([`nested_dissection_elements`]): for the symmetric
    /// structure of `A` (Cholesky, the multifrontal LU), not for `A^T A`.
    ElementNestedDissection {
        /// How the unknowns are numbered.
        grid: GridShape,
        /// Grid intervals per element and direction (the Lagrange degree: 1 for Q1, 2 for Q2).
        degree: usize,
    },
}

impl ColumnOrdering {
    /// Nested dissection for the supernodal LU of an operator whose stencil reaches `reach`
    /// grid lines: the separators are `2 * reach` lines wide, enough to cut every coupling of
    /// `A^T A` (the multifrontal kernel needs only `reach`).
    pub fn nested_dissection_for_lu(grid: GridShape, reach: usize) -> Self {
        Self::NestedDissection {
            grid,
            separator_width: 2 * reach.max(1),
        }
    }

    /// The explicit permutation (`perm[k]` = original index eliminated `k`-th), or `None` for
    /// [`ColumnOrdering::Auto`].
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] if a grid does not have `pattern.ncols()` unknowns;
    /// [`SolverError::InvalidParameter`] for a zero separator width;
    /// [`SolverError::Backend`] if AMD runs out of memory.
    pub fn permutation(
        &self,
        pattern: &SparsityPattern,
    ) -> Result<Option<Vec<usize>>, SolverError> {
        match *self {
            Self::Auto => Ok(None),
            Self::Amd => amd_symmetrised(pattern).map(Some),
            Self::NestedDissection {
                grid,
                separator_width,
            } => {
                check_grid(grid, pattern)?;
                if separator_width == 0 {
                    return Err(SolverError::invalid("separator_width", 0.0, ">= 1"));
                }
                Ok(Some(nested_dissection_grid(grid, separator_width)))
            }
            Self::ElementNestedDissection { grid, degree } => {
                check_grid(grid, pattern)?;
                if degree == 0 {
                    return Err(SolverError::invalid("degree", 0.0, ">= 1"));
                }
                Ok(Some(nested_dissection_elements(grid, degree)))
            }
        }
    }
}

/// [`SolverError::DimensionMismatch`] unless `grid` numbers `pattern.ncols()` unknowns.
fn check_grid(grid: GridShape, pattern: &SparsityPattern) -> Result<(), SolverError> {
    if grid.dof_count() != pattern.ncols() {
        return Err(SolverError::DimensionMismatch {
            quantity: "grid unknowns",
            expected: pattern.ncols(),
            found: grid.dof_count(),
        });
    }
    Ok(())
}

/// Regions with at most this many nodes are leaves of the dissection, numbered naturally.
///
/// Measured on the Navier operator (500 x 81 grid, LU, separators 2 lines wide): leaves of
/// 4-16 nodes peak at 355 MiB, 32 at 362, 64 at 382 (the leaves' own fill grows).
const LEAF_NODES: usize = 16;

/// Geometric nested dissection of a structured grid: `perm[k]` is the unknown eliminated
/// `k`-th.
///
/// The region is cut across its longer side by a strip of `separator_width` grid lines; the two
/// halves are ordered recursively, then the strip. A periodic first direction is first cut by
/// two strips half a period apart. Regions of at most 16 nodes (or too thin to cut) are
/// numbered naturally, the longer side outermost. A node's unknowns stay consecutive.
///
/// # Math
/// ```text
/// region R = [a2, b2) x [a3, b3), cut across the longer side at its middle m:
/// order(R) = order(left), order(right), strip [m, m + separator_width)
/// ```
/// The halves are uncoupled in a matrix whose stencil reaches fewer than `separator_width + 1`
/// lines: for LU (structure of `A^T A`) that is `separator_width >= 2 * reach(A)`.
///
/// # Panics
/// If `separator_width` is zero.
///
/// # Example
/// ```
/// use capstan_solvers::{GridShape, nested_dissection_grid};
/// let grid = GridShape { n2: 30, n3: 10, dofs_per_node: 2, periodic: false };
/// let perm = nested_dissection_grid(grid, 2);
/// let mut seen = vec![false; 600];
/// perm.iter().for_each(|&p| seen[p] = true);
/// assert!(seen.iter().all(|&s| s));
/// // the first cut is across the longer side, at its middle: lines 14 and 15, numbered last
/// assert_eq!(perm[560..].iter().map(|&p| p / 2 / 10).min(), Some(14));
/// ```
#[track_caller]
pub fn nested_dissection_grid(grid: GridShape, separator_width: usize) -> Vec<usize> {
    assert!(separator_width > 0, "separator_width must be positive");
    let mut perm = Vec::with_capacity(grid.dof_count());
    let w = separator_width;
    let cut = separator_cut(w);
    if grid.periodic && grid.n2 >= 2 * w + 4 {
        // two strips half a period apart split the ring into two open pieces
        let half = w + (grid.n2 - 2 * w) / 2;
        dissect_by(grid, (w, half), (0, grid.n3), &mut perm, &cut);
        dissect_by(grid, (half + w, grid.n2), (0, grid.n3), &mut perm, &cut);
        push_block(grid, (0, w), (0, grid.n3), &mut perm);
        push_block(grid, (half, half + w), (0, grid.n3), &mut perm);
    } else {
        // a periodic grid too short to cut twice is simply numbered naturally
        dissect_by(grid, (0, grid.n2), (0, grid.n3), &mut perm, &cut);
    }
    debug_assert_eq!(perm.len(), grid.dof_count());
    perm
}

/// The separators of [`nested_dissection_grid`]: `w` lines across the middle of the longer
/// side; none for a region of at most [`LEAF_NODES`] nodes or too short to cut.
fn separator_cut(w: usize) -> impl Fn((usize, usize), (usize, usize)) -> Option<Cut> {
    move |r2, r3| {
        let (l2, l3) = (r2.1 - r2.0, r3.1 - r3.0);
        if l2 * l3 <= LEAF_NODES || l2.max(l3) < w + 2 {
            None
        } else if l2 >= l3 {
            Some(Cut::X2(r2.0 + (l2 - w) / 2, w))
        } else {
            Some(Cut::X3(r3.0 + (l3 - w) / 2, w))
        }
    }
}

/// A separator of a region: the grid lines `m..m + width` across `x2` or across `x3`.
enum Cut {
    X2(usize, usize),
    X3(usize, usize),
}

/// Orders the region `[r2.0, r2.1) x [r3.0, r3.1)` (not periodic) into `perm`: the two sides
/// of the separator `cut(r2, r3)` recursively, then the separator; a region without one
/// naturally ([`push_block`]).
fn dissect_by(
    grid: GridShape,
    r2: (usize, usize),
    r3: (usize, usize),
    perm: &mut Vec<usize>,
    cut: &dyn Fn((usize, usize), (usize, usize)) -> Option<Cut>,
) {
    match cut(r2, r3) {
        None => push_block(grid, r2, r3, perm),
        Some(Cut::X2(m, width)) => {
            dissect_by(grid, (r2.0, m), r3, perm, cut);
            dissect_by(grid, (m + width, r2.1), r3, perm, cut);
            push_block(grid, (m, m + width), r3, perm);
        }
        Some(Cut::X3(m, width)) => {
            dissect_by(grid, r2, (r3.0, m), perm, cut);
            dissect_by(grid, r2, (m + width, r3.1), perm, cut);
            push_block(grid, r2, (m, m + width), perm);
        }
    }
}

/// Nested dissection of a structured grid of elements `degree` grid intervals wide in each
/// direction (Lagrange `Q_degree` on the grid nodes), cut along element boundaries: `perm[k]`
/// is the unknown eliminated `k`-th.
///
/// The nodes of one element are coupled only within it, so a single node line on an element
/// boundary (index a multiple of `degree`) separates the two sides, whatever the degree. The
/// region is cut across its longer side by the element-boundary line nearest its middle (the
/// other side if the longer one has no interior boundary line); the two halves are ordered
/// recursively, then the line. A periodic first direction is first cut by the lines `0` and
/// (about) `n2 / 2`. Regions of at most 16 nodes (or without an interior boundary line) are
/// numbered naturally, the longer side outermost. A node's unknowns stay consecutive.
///
/// # Math
/// ```text
/// element e covers node lines [degree e, degree (e + 1)] in each direction
/// region R = [a2, b2) x [a3, b3), cut line m: a < m < b - 1, m = 0 mod degree, nearest (a + b) / 2
/// order(R) = order(R ∩ {i < m}), order(R ∩ {i > m}), line m
/// ```
/// On a 2-D grid this gives `O(n log n)` fill and `O(n^1.5)` factor work. With `degree = 1`
/// it is [`nested_dissection_grid`] with 1-line separators up to where the cuts fall.
///
/// # Panics
/// If `degree` is zero.
///
/// # Example
/// ```
/// use capstan_solvers::{GridShape, is_permutation, nested_dissection_elements};
/// // Q2 on 4 x 2 elements: 9 x 5 nodes
/// let grid = GridShape { n2: 9, n3: 5, dofs_per_node: 2, periodic: false };
/// let perm = nested_dissection_elements(grid, 2);
/// assert!(is_permutation(&perm, 90));
/// // the first cut is the element boundary x2 line 4, numbered last
/// assert!(perm[80..].iter().all(|&p| p / 2 / 5 == 4));
/// ```
#[track_caller]
pub fn nested_dissection_elements(grid: GridShape, degree: usize) -> Vec<usize> {
    assert!(degree > 0, "degree must be positive");
    let cut = element_cut(degree);
    let mut perm = Vec::with_capacity(grid.dof_count());
    // on the ring, line 0 comes again after line n2 - 1: the second cut is half way round
    let half = aligned_cut(0, grid.n2 + 1, degree).filter(|&h| h > 1 && h + 1 < grid.n2);
    match half {
        Some(half) if grid.periodic => {
            // lines 0 and `half` split the ring into two open pieces
            dissect_by(grid, (1, half), (0, grid.n3), &mut perm, &cut);
            dissect_by(grid, (half + 1, grid.n2), (0, grid.n3), &mut perm, &cut);
            push_block(grid, (0, 1), (0, grid.n3), &mut perm);
            push_block(grid, (half, half + 1), (0, grid.n3), &mut perm);
        }
        _ => dissect_by(grid, (0, grid.n2), (0, grid.n3), &mut perm, &cut),
    }
    debug_assert_eq!(perm.len(), grid.dof_count());
    perm
}

/// The element-boundary line (a multiple of `degree`) strictly inside `[a, b)` with a line on
/// each side (`a < m < b - 1`), nearest the middle `(a + b - 1) / 2`.
fn aligned_cut(a: usize, b: usize, degree: usize) -> Option<usize> {
    if b < a + 3 {
        return None;
    }
    let mid = (a + b - 1) / 2;
    let below = mid - mid % degree;
    let above = below + degree;
    let ok = |m: usize| a < m && m + 1 < b;
    match (ok(below), ok(above)) {
        (true, true) if above - mid < mid - below => Some(above),
        (true, _) => Some(below),
        (false, true) => Some(above),
        (false, false) => None,
    }
}

/// The separators of [`nested_dissection_elements`]: the element-boundary line nearest the
/// middle of the longer side (the other side if the longer one has none); none for a region
/// of at most [`LEAF_NODES`] nodes or without an interior boundary line.
fn element_cut(degree: usize) -> impl Fn((usize, usize), (usize, usize)) -> Option<Cut> {
    move |r2, r3| {
        let (l2, l3) = (r2.1 - r2.0, r3.1 - r3.0);
        if l2 * l3 <= LEAF_NODES {
            return None;
        }
        let cut2 = aligned_cut(r2.0, r2.1, degree);
        let cut3 = aligned_cut(r3.0, r3.1, degree);
        match (cut2, cut3) {
            (Some(m), _) if l2 >= l3 || cut3.is_none() => Some(Cut::X2(m, 1)),
            (_, Some(m)) => Some(Cut::X3(m, 1)),
            _ => None,
        }
    }
}

/// Appends the unknowns of a block, the longer side outermost (smaller bandwidth).
fn push_block(grid: GridShape, r2: (usize, usize), r3: (usize, usize), perm: &mut Vec<usize>) {
    let d = grid.dofs_per_node;
    let mut node = |i2: usize, i3: usize| {
        let first = d * (i2 * grid.n3 + i3);
        perm.extend(first..first + d);
    };
    if r2.1 - r2.0 >= r3.1 - r3.0 {
        for i2 in r2.0..r2.1 {
            for i3 in r3.0..r3.1 {
                node(i2, i3);
            }
        }
    } else {
        for i3 in r3.0..r3.1 {
            for i2 in r2.0..r2.1 {
                node(i2, i3);
            }
        }
    }
}

/// Approximate minimum degree (faer) on the pattern of `A + A^T`: `perm[k]` is the unknown
/// eliminated `k`-th. Applied to the columns of LU it ignores that LU's structure comes from
/// `A^T A`; it suits matrices whose pivots stay near the diagonal.
///
/// # Errors
/// [`SolverError::NotSquare`] for a rectangular pattern; [`SolverError::Backend`] if faer runs
/// out of memory or indices overflow.
pub fn amd_symmetrised(pattern: &SparsityPattern) -> Result<Vec<usize>, SolverError> {
    let n = crate::linear_solver::check_square(pattern)?;
    let mut fwd = vec![0usize; n];
    let mut inv = vec![0usize; n];
    if n == 0 {
        return Ok(fwd);
    }
    let mut mem = crate::error::scratch(faer::sparse::linalg::amd::order_scratch::<usize>(
        n,
        pattern.nnz(),
    ))?;
    let stack = faer::dyn_stack::MemStack::new(&mut mem);
    faer::sparse::linalg::amd::order(
        &mut fwd,
        &mut inv,
        pattern.as_faer_symbolic(),
        Default::default(),
        stack,
    )?;
    Ok(fwd)
}

/// Approximate minimum degree (faer) on the graph of a structurally symmetric pattern,
/// computed on its quotient by runs of consecutive indistinguishable unknowns: columns
/// `j, j + 1, ...` with identical row sets (the closed neighbourhoods of a symmetric pattern)
/// become one vertex, e.g. the 2 unknowns of a node in a vector-valued discretisation.
/// `perm[k]` is the unknown eliminated `k`-th; a run stays consecutive, in increasing order.
///
/// # Math
/// ```text
/// run r = [s_r, s_{r+1}):  rows(j) = rows(s_r) for s_r <= j < s_{r+1}
/// quotient graph:          r -- t  iff  some row of column s_r lies in run t
/// perm = expand(AMD(quotient))
/// ```
/// Indistinguishable unknowns are eliminated together by any minimum-degree ordering, so the
/// quotient loses nothing and AMD works on a graph with `nnz / b^2` entries (`b` unknowns per
/// run). The caller guarantees structural symmetry (with the diagonal, the row set of a column
/// is its closed neighbourhood); on an unsymmetric pattern the result is still a permutation
/// but the runs may not be indistinguishable.
///
/// # Errors
/// [`SolverError::NotSquare`] for a rectangular pattern; [`SolverError::Backend`] if faer runs
/// out of memory or indices overflow.
///
/// # Example
/// ```
/// use capstan_solvers::{SparsityPattern, amd_compressed, is_permutation};
/// // two nodes with two coupled unknowns each, the nodes coupled: one dense 4 x 4 block
/// let entries: Vec<(usize, usize)> = (0..4).flat_map(|i| (0..4).map(move |j| (i, j))).collect();
/// let (pattern, _) = SparsityPattern::from_entries(4, 4, &entries).unwrap();
/// let perm = amd_compressed(&pattern).unwrap();
/// assert!(is_permutation(&perm, 4));
/// ```
pub fn amd_compressed(pattern: &SparsityPattern) -> Result<Vec<usize>, SolverError> {
    let n = crate::linear_solver::check_square(pattern)?;
    if n == 0 {
        return Ok(vec![]);
    }
    let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
    let rows = |j: usize| &row_idx[col_ptr[j]..col_ptr[j + 1]];
    // run starts and the run of every unknown
    let mut starts = vec![0usize];
    let mut run_of = vec![0usize; n];
    for (j, run) in run_of.iter_mut().enumerate().skip(1) {
        if rows(j) != rows(j - 1) {
            starts.push(j);
        }
        *run = starts.len() - 1;
    }
    let runs = starts.len();
    starts.push(n);
    // quotient graph from each run's first column: rows map monotonically to runs, so the
    // mapped list is sorted and duplicates are neighbours
    let mut q_col_ptr = Vec::with_capacity(runs + 1);
    let mut q_row_idx = Vec::with_capacity(pattern.nnz() / (n / runs).max(1).pow(2) + runs);
    q_col_ptr.push(0);
    for &s in &starts[..runs] {
        for &i in rows(s) {
            let r = run_of[i];
            if q_row_idx.len() == *q_col_ptr.last().expect("starts at 0")
                || q_row_idx.last() != Some(&r)
            {
                q_row_idx.push(r);
            }
        }
        q_col_ptr.push(q_row_idx.len());
    }
    let quotient = faer::sparse::SymbolicSparseColMatRef::new_checked(
        runs, runs, &q_col_ptr, None, &q_row_idx,
    );
    let mut fwd = vec![0usize; runs];
    let mut inv = vec![0usize; runs];
    let mut mem = crate::error::scratch(faer::sparse::linalg::amd::order_scratch::<usize>(
        runs,
        q_row_idx.len(),
    ))?;
    let stack = faer::dyn_stack::MemStack::new(&mut mem);
    faer::sparse::linalg::amd::order(&mut fwd, &mut inv, quotient, Default::default(), stack)?;
    let mut perm = Vec::with_capacity(n);
    for r in fwd {
        perm.extend(starts[r]..starts[r + 1]);
    }
    Ok(perm)
}

/// Whether `perm` is a permutation of `0..n`.
pub fn is_permutation(perm: &[usize], n: usize) -> bool {
    if perm.len() != n {
        return false;
    }
    let mut seen = vec![false; n];
    perm.iter()
        .all(|&p| p < n && !std::mem::replace(&mut seen[p], true))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid_shape(n2: usize, n3: usize, dofs_per_node: usize, periodic: bool) -> GridShape {
        GridShape {
            n2,
            n3,
            dofs_per_node,
            periodic,
        }
    }

    /// [`nested_dissection_grid`] of `grid`, checked to be a permutation of its unknowns.
    #[track_caller]
    fn dissected(grid: GridShape, separator_width: usize) -> Vec<usize> {
        let perm = nested_dissection_grid(grid, separator_width);
        assert!(is_permutation(&perm, grid.dof_count()));
        perm
    }

    /// The grid line (`unknown / per_line`) of each unknown in `perm[from..]`.
    fn lines_of(perm: &[usize], from: usize, per_line: usize) -> Vec<usize> {
        perm[from..].iter().map(|&p| p / per_line).collect()
    }

    #[test]
    fn small_grid_is_natural_order() {
        let grid = grid_shape(4, 3, 2, false);
        assert_eq!(nested_dissection_grid(grid, 2), (0..24).collect::<Vec<_>>());
    }

    #[test]
    fn separator_splits_halves_numbered_first() {
        let perm = dissected(grid_shape(40, 4, 1, false), 3);
        assert_eq!(perm.len(), 160);
        // first cut: (40 - 3) / 2 = 18, strip = lines 18, 19, 20, last 12 unknowns
        let strip = lines_of(&perm, 148, 4);
        assert!(strip.iter().all(|&i2| (18..21).contains(&i2)), "{strip:?}");
        // everything left of the strip comes before everything right of it
        let first_right = perm.iter().position(|&p| p / 4 > 20).unwrap();
        assert!(perm[..first_right].iter().all(|&p| p / 4 < 18));
    }

    #[test]
    fn periodic_grid_is_cut_twice() {
        let perm = dissected(grid_shape(20, 2, 1, true), 1);
        assert_eq!(perm.len(), 40);
        assert_eq!(lines_of(&perm, 36, 2), vec![0, 0, 10, 10]);
    }

    /// The symmetric pattern of a 5-point stencil on an `m x m` grid with `b` coupled unknowns
    /// per node, some nodes with a single unknown coupled to itself only (as a pinned dof).
    fn vector_laplacian(m: usize, b: usize, pinned: &[usize]) -> SparsityPattern {
        let node = |i: usize, j: usize| i * m + j;
        let mut entries = vec![];
        for i in 0..m {
            for j in 0..m {
                let mut neighbours = vec![node(i, j)];
                if i > 0 {
                    neighbours.push(node(i - 1, j));
                }
                if i + 1 < m {
                    neighbours.push(node(i + 1, j));
                }
                if j > 0 {
                    neighbours.push(node(i, j - 1));
                }
                if j + 1 < m {
                    neighbours.push(node(i, j + 1));
                }
                for c in 0..b {
                    let r = b * node(i, j) + c;
                    if pinned.contains(&r) {
                        entries.push((r, r));
                        continue;
                    }
                    for &nb in &neighbours {
                        for d in 0..b {
                            let col = b * nb + d;
                            if !pinned.contains(&col) {
                                entries.push((r, col));
                            }
                        }
                    }
                }
            }
        }
        SparsityPattern::from_entries(b * m * m, b * m * m, &entries)
            .unwrap()
            .0
    }

    /// Fill of the Cholesky factor of a symmetric pattern in the order `perm` (symbolic
    /// elimination on dense boolean rows: small test matrices only).
    fn cholesky_fill(pattern: &SparsityPattern, perm: &[usize]) -> usize {
        let n = pattern.ncols();
        let mut position = vec![0; n];
        for (k, &p) in perm.iter().enumerate() {
            position[p] = k;
        }
        let mut adj = vec![vec![false; n]; n];
        for (i, j) in pattern.entries() {
            adj[position[i]][position[j]] = true;
            adj[position[j]][position[i]] = true;
        }
        let mut fill = 0;
        for k in 0..n {
            let later: Vec<usize> = (k + 1..n).filter(|&i| adj[k][i]).collect();
            fill += later.len();
            for &a in &later {
                for &b in &later {
                    adj[a][b] = true;
                }
            }
        }
        fill
    }

    #[test]
    fn compressed_amd_keeps_runs_together_and_fills_no_more_than_amd() {
        let pinned = [0, 7, 13];
        let pattern = vector_laplacian(9, 2, &pinned);
        let perm = amd_compressed(&pattern).unwrap();
        assert!(is_permutation(&perm, 162));
        // the two unknowns of an unpinned node are eliminated one after the other
        for w in perm.windows(2) {
            if w[0] % 2 == 0 && !pinned.contains(&w[0]) && !pinned.contains(&(w[0] + 1)) {
                assert_eq!(w[1], w[0] + 1, "{perm:?}");
            }
        }
        let compressed = cholesky_fill(&pattern, &perm);
        let plain = cholesky_fill(&pattern, &amd_symmetrised(&pattern).unwrap());
        let natural = cholesky_fill(&pattern, &(0..162).collect::<Vec<_>>());
        assert!(compressed < natural, "{compressed} vs natural {natural}");
        // on this pattern both orderings are minimum-degree orderings of the same graph
        assert!(
            compressed as f64 <= 1.1 * plain as f64,
            "{compressed} vs {plain}"
        );
    }

    #[test]
    fn compressed_amd_of_scalar_and_empty_patterns() {
        let pattern = vector_laplacian(6, 1, &[]);
        assert!(is_permutation(&amd_compressed(&pattern).unwrap(), 36));
        let (empty, _) = SparsityPattern::from_entries(0, 0, &[]).unwrap();
        assert!(amd_compressed(&empty).unwrap().is_empty());
    }

    /// The symmetric pattern of `Q_degree` elements on a grid (every node coupled to every
    /// node of the elements it belongs to), `b` unknowns per node.
    fn element_pattern(grid: GridShape, degree: usize) -> SparsityPattern {
        let (n2, n3, b) = (grid.n2, grid.n3, grid.dofs_per_node);
        let e2 = if grid.periodic {
            n2 / degree
        } else {
            (n2 - 1) / degree
        };
        let e3 = (n3 - 1) / degree;
        let mut entries = vec![];
        for i in 0..e2 {
            for j in 0..e3 {
                let nodes: Vec<usize> = (0..=degree)
                    .flat_map(|a| {
                        (0..=degree).map(move |c| ((degree * i + a) % n2) * n3 + degree * j + c)
                    })
                    .collect();
                for &p in &nodes {
                    for &q in &nodes {
                        for c in 0..b {
                            for d in 0..b {
                                entries.push((b * p + c, b * q + d));
                            }
                        }
                    }
                }
            }
        }
        SparsityPattern::from_entries(grid.dof_count(), grid.dof_count(), &entries)
            .unwrap()
            .0
    }

    #[test]
    fn element_dissection_cuts_on_element_boundaries_and_fills_less_than_natural() {
        for (periodic, n2) in [(false, 17), (true, 16)] {
            let grid = grid_shape(n2, 9, 2, periodic);
            let perm = nested_dissection_elements(grid, 2);
            assert!(is_permutation(&perm, grid.dof_count()));
            // the last line eliminated is a single element-boundary line
            let last = lines_of(&perm, perm.len() - 18, 18);
            assert!(
                last.iter().all(|&i2| i2 == last[0] && i2 % 2 == 0),
                "{last:?}"
            );
            let pattern = element_pattern(grid, 2);
            let nd = cholesky_fill(&pattern, &perm);
            let natural = cholesky_fill(&pattern, &(0..grid.dof_count()).collect::<Vec<_>>());
            assert!(nd < natural, "{nd} vs natural {natural}");
        }
    }

    #[test]
    fn aligned_cut_is_on_a_boundary_with_lines_on_both_sides() {
        assert_eq!(aligned_cut(0, 9, 2), Some(4));
        assert_eq!(aligned_cut(1, 8, 2), Some(4));
        assert_eq!(aligned_cut(0, 3, 2), None); // only lines 0, 1, 2: no interior boundary
        assert_eq!(aligned_cut(0, 5, 2), Some(2));
        assert_eq!(aligned_cut(5, 9, 1), Some(6));
        assert_eq!(aligned_cut(3, 6, 2), Some(4));
    }

    #[test]
    fn is_permutation_rejects_repeats_and_out_of_range() {
        assert!(is_permutation(&[2, 0, 1], 3));
        assert!(!is_permutation(&[0, 0, 1], 3));
        assert!(!is_permutation(&[0, 1, 3], 3));
        assert!(!is_permutation(&[0, 1], 3));
    }
}
