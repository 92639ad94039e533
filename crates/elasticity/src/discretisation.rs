//! The interface between a discretisation of the Navier operator and the solvers: dof
//! numbering, assembly into a fixed sparsity pattern, the contact boundary rows, output fields.

use capstan_solvers::{LinearSolver, SparsityPattern};

use crate::boundary::Component;
use crate::error::ElasticityError;
use crate::fields::NodalFields;

/// A sparse row `r`: the linear functional `v -> sum_k values[k] v[columns[k]]`.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct SparseRow {
    /// Column (dof) indices, increasing.
    pub columns: Vec<usize>,
    /// Coefficients.
    pub values: Vec<f64>,
}

impl SparseRow {
    /// Builds a row from `(column, value)` terms, summing duplicates and sorting the columns.
    pub fn from_terms(terms: &mut [(usize, f64)]) -> Self {
        terms.sort_unstable_by_key(|t| t.0);
        let mut row = Self::default();
        for &(c, v) in terms.iter() {
            if row.columns.last() == Some(&c) {
                *row.values.last_mut().expect("same length") += v;
            } else {
                row.columns.push(c);
                row.values.push(v);
            }
        }
        row
    }

    /// `sum_k values[k] v[columns[k]]`.
    ///
    /// # Panics
    /// If a column is out of range of `v`.
    #[track_caller]
    pub fn dot(&self, v: &[f64]) -> f64 {
        self.columns
            .iter()
            .zip(&self.values)
            .map(|(&c, &a)| a * v[c])
            .sum()
    }
}

/// One node of the contact surface `x3 = 0`, with everything a friction law needs to add its
/// terms (and their exact Jacobian) to the assembled system.
///
/// # Math
/// The assembled system is `A v = b`. If a tangential traction `t_2 = n_i T^i_2` (covariant,
/// unit outward normal `n = -g^3`, so `t_2 = -T^3_2`) acts on the contact face of this node,
/// ```text
/// residual[tangential_row] = (A v - b)[tangential_row] - traction_weight * t_2
/// ```
/// with `b` assembled for zero tangential traction on `x3 = 0`. The tangential physical
/// displacement is `sqrt_g22 * v^2` and the physical tangential traction is `t_2 / sqrt_g22`.
/// `normal_stress . v = T^3_3` and `shear_stress . v = T^3_2` at the node (the pressure is
/// `p = -T^3_3`); their columns are in the sparsity pattern of `tangential_row`, so a friction
/// Jacobian `d t_2/d v^2 e_{v^2} + d t_2/d T^3_3 normal_stress` fits the pattern.
///
/// # Several tangential directions (a 3-D body)
/// A contact node of a 3-D body carries two tangential unknowns `v^1`, `v^2`: it is listed
/// as two `ContactNode` entries (one per tangential balance row) with the same
/// [`ContactNode::site`]. The friction law sees the physical slip of the site,
/// ```text
/// u = sum_(entries e of the site) frame_e v[tangential_dof_e]      (2 components: e_1, e_2)
/// t_e = frame_e . t(u, sigma_n)                                   (covariant traction)
/// ```
/// with `frame_e = [e_1 . a_alpha, e_2 . a_alpha]` for the entry's direction `alpha`, in an
/// orthonormal frame `e_1 = a_1/|a_1|`, `e_2 = a^2/|a^2|` of the tangent plane (so that
/// `e_2 . a_1 = 0`); the plane-strain entry has `frame = [0, sqrt(g_22)]`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContactNode {
    /// `(i2, 0)`.
    pub node: [usize; 2],
    /// `i1` of the node of a 3-D body (0 in plane strain).
    pub i1: usize,
    /// The contact point this entry belongs to: entries with the same site share one slip
    /// vector and one normal stress (plane strain: one entry per site, `site = i2`).
    pub site: usize,
    /// `x1` of the node of a 3-D body (0 in plane strain).
    pub x1: f64,
    /// `x2` of the node.
    pub x2: f64,
    /// The displacement component of [`ContactNode::tangential_dof`]: 1 for `v^1`, 2 for `v^2`.
    pub component: usize,
    /// Physical slip components `[e_1, e_2]` per unit of the entry's `v^alpha` (see above).
    pub frame: [f64; 2],
    /// Row of the `j = 2` balance equation; `None` if `v^2` is prescribed at this node.
    pub tangential_row: Option<usize>,
    /// Dof of `v^2` at the node.
    pub tangential_dof: usize,
    /// Dof of `v^3` at the node.
    pub normal_dof: usize,
    /// Coefficient of the traction `t_2` in the right-hand side of `tangential_row`.
    pub traction_weight: f64,
    /// `sqrt(g_aa)` at the node for the entry's direction `a` (plane strain: `sqrt(g_22)`,
    /// physical tangential displacement `= sqrt_g22 v^2`).
    pub sqrt_g22: f64,
    /// `v -> T^3_3` at the node (second-order one-sided in `x3`).
    pub normal_stress: SparseRow,
    /// `v -> T^3_a` at the node (`a` the entry's component: `T^3_2` in plane strain).
    pub shear_stress: SparseRow,
}

/// The dof of `component` at `node` in the plane-strain numbering `2 node + c` of every
/// [`Discretisation`] on a [`crate::Grid`].
///
/// # Panics
/// If `node` is outside the grid.
#[track_caller]
pub(crate) fn plane_strain_dof(
    grid: &crate::grid::Grid,
    node: [usize; 2],
    component: Component,
) -> usize {
    assert!(
        node[0] < grid.n2() && node[1] < grid.n3(),
        "node {node:?} outside the grid"
    );
    2 * grid.node_index(node) + component.index()
}

impl ContactNode {
    /// The contact node `(i, 0)` of a plane-strain discretisation `d` (the grid's `x2`, the
    /// dofs of `d`); `dirichlet` holds the prescribed value of every dof (its tangential row is
    /// free where it has none); `rows` are `[shear_stress, normal_stress]`.
    pub fn at<D: Discretisation + ?Sized>(
        d: &D,
        i: usize,
        dirichlet: &[Option<f64>],
        traction_weight: f64,
        sqrt_g22: f64,
        [shear_stress, normal_stress]: [SparseRow; 2],
    ) -> Self {
        let node = [i, 0];
        let tangential_dof = d.dof(node, Component::X2);
        Self {
            node,
            i1: 0,
            site: i,
            x1: 0.0,
            x2: d.grid().x2(i),
            component: 2,
            frame: [0.0, sqrt_g22],
            tangential_row: dirichlet[tangential_dof]
                .is_none()
                .then_some(tangential_dof),
            tangential_dof,
            normal_dof: d.dof(node, Component::X3),
            traction_weight,
            sqrt_g22,
            normal_stress,
            shear_stress,
        }
    }
}

/// Consecutive rows of a matrix for [`LinearSystem::from_row_blocks`]: row `i` of the block
/// holds the columns `cols[ends[i - 1]..ends[i]]` (distinct; `ends[-1] = 0`) with
/// the values at the same places.
#[derive(Debug, Clone, Default)]
pub struct RowBlock {
    /// Column of every entry, row after row.
    pub cols: Vec<usize>,
    /// Value of every entry, in the order of `cols`.
    pub values: Vec<f64>,
    /// End (exclusive) in `cols` of every row.
    pub ends: Vec<usize>,
}

/// An assembled linear system `A v = b` on a sparsity pattern built once.
#[derive(Debug, Clone)]
pub struct LinearSystem {
    /// The pattern of `A` (fixed for the life of the discretisation).
    pub pattern: SparsityPattern,
    /// The values of `A` in `pattern` order.
    pub values: Vec<f64>,
    /// The right-hand side `b`.
    pub rhs: Vec<f64>,
    /// Slot of each structural entry; `None`: entry `k` is slot `k` (no duplicates).
    slots: Option<Vec<u32>>,
}

impl LinearSystem {
    /// The system for the structural `entries` (duplicates allowed), values zero.
    ///
    /// # Errors
    /// [`ElasticityError::Solver`] for out-of-range entries; `InvalidParameter` if the pattern
    /// has more than `u32::MAX` nonzeros.
    pub fn from_entries(n: usize, entries: &[(usize, usize)]) -> Result<Self, ElasticityError> {
        let (pattern, slots) = SparsityPattern::from_entries(n, n, entries)?;
        if pattern.nnz() > u32::MAX as usize {
            return Err(ElasticityError::InvalidParameter {
                field: "pattern nonzeros",
                value: pattern.nnz() as f64,
                allowed: "[0, 2^32)",
            });
        }
        let slots = Some(slots.into_iter().map(|s| s as u32).collect());
        Ok(Self {
            values: vec![0.0; pattern.nnz()],
            rhs: vec![0.0; n],
            pattern,
            slots,
        })
    }

    /// The system with an assembled square `pattern`, its `values` (in slot order) and `rhs`:
    /// the structural entries are the slots of `pattern` in order (`entries()` =
    /// `pattern.entries()`, entry `k` is slot `k`), as [`LinearSystem::from_entries`] builds
    /// for distinct entries listed column by column. No sort: `O(1)`.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] if `pattern` is not `n x n` with
    /// `n = rhs.len()`, or `values` does not have `pattern.nnz()` entries;
    /// `InvalidParameter` if the pattern has more than `u32::MAX` nonzeros.
    pub fn from_parts(
        pattern: SparsityPattern,
        values: Vec<f64>,
        rhs: Vec<f64>,
    ) -> Result<Self, ElasticityError> {
        let n = rhs.len();
        for (quantity, expected, found) in [
            ("pattern rows", n, pattern.nrows()),
            ("pattern columns", n, pattern.ncols()),
            ("values", pattern.nnz(), values.len()),
        ] {
            if expected != found {
                return Err(ElasticityError::DimensionMismatch {
                    quantity,
                    expected,
                    found,
                });
            }
        }
        if pattern.nnz() > u32::MAX as usize {
            return Err(ElasticityError::InvalidParameter {
                field: "pattern nonzeros",
                value: pattern.nnz() as f64,
                allowed: "[0, 2^32)",
            });
        }
        Ok(Self {
            pattern,
            values,
            rhs,
            slots: None,
        })
    }

    /// The system of rows listed in row order, no column twice in a row: the
    /// same pattern, entry slots and values, bit for bit, as [`LinearSystem::from_entries`] on
    /// the entries `(row, column)` in that order followed by `add_entry(k, value_k)`, built by
    /// one counting pass over the columns instead of the general sort (no entry list, no
    /// permutation: about half the memory touched).
    ///
    /// # Math
    /// With `count_c` the entries of column `c`, `col_ptr[c + 1] = col_ptr[c] + count_c`; entry
    /// `k = (r, c)` takes the next free slot of column `c`, so rows increase within a column
    /// because rows come in order, and `values[slot_k] = 0 + value_k`.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] when the blocks hold other than `rhs.len()` rows
    /// or a block's columns and values differ in length; [`ElasticityError::Solver`] for a
    /// column out of range or a column repeated in a row;
    /// `InvalidParameter` if the pattern has more than `u32::MAX` nonzeros.
    pub fn from_row_blocks(blocks: &[RowBlock], rhs: Vec<f64>) -> Result<Self, ElasticityError> {
        let n = rhs.len();
        let rows: usize = blocks.iter().map(|b| b.ends.len()).sum();
        ElasticityError::check_length("rows of the row blocks", n, rows)?;
        let mut col_ptr = vec![0usize; n + 1];
        let mut row = 0;
        for block in blocks {
            ElasticityError::check_length(
                "values of a row block",
                block.cols.len(),
                block.values.len(),
            )?;
            if block.ends.last().copied().unwrap_or(0) != block.cols.len()
                || block.ends.windows(2).any(|w| w[0] > w[1])
            {
                return Err(ElasticityError::InvalidParameter {
                    field: "row block ends",
                    value: block.cols.len() as f64,
                    allowed: "non-decreasing row ends, the last equal to the block's entries",
                });
            }
            let mut start = 0;
            for &end in &block.ends {
                for &c in &block.cols[start..end] {
                    if c >= n {
                        return Err(capstan_solvers::SolverError::EntryOutOfBounds {
                            row,
                            col: c,
                            nrows: n,
                            ncols: n,
                        }
                        .into());
                    }
                    col_ptr[c + 1] += 1;
                }
                start = end;
                row += 1;
            }
        }
        for c in 0..n {
            col_ptr[c + 1] += col_ptr[c];
        }
        let nnz = col_ptr[n];
        if nnz > u32::MAX as usize {
            return Err(ElasticityError::InvalidParameter {
                field: "pattern nonzeros",
                value: nnz as f64,
                allowed: "[0, 2^32)",
            });
        }
        let mut next = col_ptr[..n].to_vec();
        let mut row_idx = vec![0usize; nnz];
        let mut values = vec![0.0; nnz];
        let mut slots = Vec::with_capacity(nnz);
        let mut row = 0;
        for block in blocks {
            let mut start = 0;
            for &end in &block.ends {
                for (&c, &v) in block.cols[start..end].iter().zip(&block.values[start..end]) {
                    let slot = next[c];
                    next[c] += 1;
                    row_idx[slot] = row;
                    values[slot] += v;
                    slots.push(slot as u32);
                }
                start = end;
                row += 1;
            }
        }
        // rows strictly increasing within every column holds iff no row repeats a column
        let pattern = SparsityPattern::from_compressed_columns(n, n, col_ptr, row_idx)?;
        Ok(Self {
            pattern,
            values,
            rhs,
            slots: Some(slots),
        })
    }

    /// Zeroes values and right-hand side; returns an adder `add(entry_index, value)` target.
    pub fn clear(&mut self) {
        self.values.iter_mut().for_each(|v| *v = 0.0);
        self.rhs.iter_mut().for_each(|v| *v = 0.0);
    }

    /// Adds `value` to the slot of structural entry number `k` (in `entries` order).
    #[track_caller]
    pub fn add_entry(&mut self, k: usize, value: f64) {
        let slot = self.slots.as_ref().map_or(k, |s| s[k] as usize);
        self.values[slot] += value;
    }

    /// Dimension `n`.
    pub fn dimension(&self) -> usize {
        self.rhs.len()
    }

    /// `r = A v - b`.
    ///
    /// # Panics
    /// If `v` or `r` have the wrong length.
    #[track_caller]
    pub fn residual_into(&self, v: &[f64], r: &mut [f64]) {
        self.pattern.matvec(&self.values, v, r);
        for (ri, bi) in r.iter_mut().zip(&self.rhs) {
            *ri -= bi;
        }
    }

    /// `max_i |A v - b|_i / max(1, max_i |b_i|)`.
    pub fn relative_residual(&self, v: &[f64]) -> f64 {
        let mut r = vec![0.0; self.dimension()];
        self.residual_into(v, &mut r);
        let b = self.rhs.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1.0);
        r.iter().fold(0.0f64, |m, x| m.max(x.abs())) / b
    }

    /// Solves `A v = b` with `solver` (analyse, factor, solve).
    ///
    /// # Errors
    /// The solver's typed error.
    pub fn solve(&self, solver: &mut dyn LinearSolver<f64>) -> Result<Vec<f64>, ElasticityError> {
        solver.analyse(&self.pattern)?;
        solver.factor(&self.values)?;
        let mut v = self.rhs.clone();
        solver.solve_in_place(&mut v)?;
        Ok(v)
    }
}

/// A discretisation of the plane-strain curvilinear Navier operator on the `(x2, x3)`
/// rectangle, with nodal unknowns `v^2, v^3` on an `n2 x n3` structured grid (finite
/// differences today; a finite-element discretisation on the same nodes fits behind it).
///
/// The structural nonzeros are listed once by [`Discretisation::entries`]; [`Discretisation::fill`]
/// produces the values in exactly that order, so the sparsity pattern (and a direct solver's
/// symbolic analysis) is built once and refilled.
pub trait Discretisation {
    /// Short name of the method (`"fd"`).
    fn method(&self) -> &'static str;

    /// The grid.
    fn grid(&self) -> &crate::grid::Grid;

    /// Number of unknowns.
    fn dof_count(&self) -> usize;

    /// The fill-reducing ordering for a sparse LU (multifrontal kernel, structure of
    /// `A + A^T`) of this operator and of the contact Jacobians on its pattern: the
    /// operators on structured grids give a nested dissection. Default: the backend's own
    /// ([`capstan_solvers::ColumnOrdering::Auto`], AMD).
    fn lu_ordering(&self) -> capstan_solvers::ColumnOrdering {
        capstan_solvers::ColumnOrdering::Auto
    }

    /// The parameters `(x2, x3)` of node `(i2, i3)`: the grid's uniform positions by default;
    /// the high-order elements place the nodes inside an element at its Gauss–Lobatto points.
    fn node_position(&self, node: [usize; 2]) -> [f64; 2] {
        self.grid().coordinates(node)
    }

    /// The unknown of `component` at node `(i2, i3)`.
    ///
    /// # Panics
    /// If the node is outside the grid.
    fn dof(&self, node: [usize; 2], component: Component) -> usize;

    /// The structural nonzeros `(row, column)` of `A`, duplicates allowed, in fill order. They
    /// include, in each contact tangential row, the columns of [`ContactNode::normal_stress`]
    /// and [`ContactNode::shear_stress`].
    ///
    /// # Errors
    /// Non-finite boundary data.
    fn entries(&self) -> Result<Vec<(usize, usize)>, ElasticityError>;

    /// Calls `add(k, value)` for every structural entry `k` in the order of
    /// [`Discretisation::entries`] and writes the right-hand side into `rhs`, after checking
    /// that `rhs` has [`Discretisation::dof_count`] entries ([`Discretisation::fill_values`]
    /// does the rest).
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for `rhs` of the wrong length; those of
    /// [`Discretisation::fill_values`].
    fn fill(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
        ElasticityError::check_length("rhs", self.dof_count(), rhs.len())?;
        self.fill_values(add, rhs)
    }

    /// [`Discretisation::fill`] once `rhs` is known to have [`Discretisation::dof_count`]
    /// entries: calls `add(k, value)` for every structural entry `k` in the order of
    /// [`Discretisation::entries`] and writes the right-hand side into `rhs`.
    ///
    /// # Errors
    /// Non-finite boundary or forcing data.
    fn fill_values(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError>;

    /// The nodes of the contact surface `x3 = 0`, in increasing `i2`.
    ///
    /// # Errors
    /// Geometry failures.
    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError>;

    /// Displacement, strain and stress at the nodes for the solution `v`.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    fn fields(&self, v: &[f64]) -> Result<NodalFields, ElasticityError>;

    /// Builds the pattern and fills it.
    ///
    /// # Errors
    /// See [`Discretisation::entries`] and [`Discretisation::fill`].
    fn system(&self) -> Result<LinearSystem, ElasticityError> {
        let entries = self.entries()?;
        let mut system = LinearSystem::from_entries(self.dof_count(), &entries)?;
        drop(entries);
        self.refill(&mut system)?;
        Ok(system)
    }

    /// Refills the values and right-hand side of a system built by [`Discretisation::system`].
    ///
    /// # Errors
    /// See [`Discretisation::fill`].
    fn refill(&self, system: &mut LinearSystem) -> Result<(), ElasticityError> {
        system.clear();
        let mut rhs = core::mem::take(&mut system.rhs);
        let result = self.fill(&mut |k, v| system.add_entry(k, v), &mut rhs);
        system.rhs = rhs;
        result
    }

    /// Assembles and solves with `solver`.
    ///
    /// # Errors
    /// Assembly or solver errors.
    fn solve(&self, solver: &mut dyn LinearSolver<f64>) -> Result<Vec<f64>, ElasticityError> {
        self.system()?.solve(solver)
    }
}

impl core::fmt::Debug for dyn Discretisation + Send + Sync {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Discretisation")
            .field("method", &self.method())
            .field("grid", self.grid())
            .finish_non_exhaustive()
    }
}

/// A boxed discretisation is one ([`crate::PlaneOperator`], what the registry builds).
impl<T: Discretisation + ?Sized> Discretisation for Box<T> {
    fn method(&self) -> &'static str {
        (**self).method()
    }

    fn grid(&self) -> &crate::grid::Grid {
        (**self).grid()
    }

    fn dof_count(&self) -> usize {
        (**self).dof_count()
    }

    fn lu_ordering(&self) -> capstan_solvers::ColumnOrdering {
        (**self).lu_ordering()
    }

    fn node_position(&self, node: [usize; 2]) -> [f64; 2] {
        (**self).node_position(node)
    }

    #[track_caller]
    fn dof(&self, node: [usize; 2], component: Component) -> usize {
        (**self).dof(node, component)
    }

    fn entries(&self) -> Result<Vec<(usize, usize)>, ElasticityError> {
        (**self).entries()
    }

    fn fill(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
        (**self).fill(add, rhs)
    }

    fn fill_values(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
        (**self).fill_values(add, rhs)
    }

    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        (**self).contact_nodes()
    }

    fn fields(&self, v: &[f64]) -> Result<NodalFields, ElasticityError> {
        (**self).fields(v)
    }

    fn system(&self) -> Result<LinearSystem, ElasticityError> {
        (**self).system()
    }

    fn refill(&self, system: &mut LinearSystem) -> Result<(), ElasticityError> {
        (**self).refill(system)
    }

    fn solve(&self, solver: &mut dyn LinearSolver<f64>) -> Result<Vec<f64>, ElasticityError> {
        (**self).solve(solver)
    }
}

/// The nodal field `v` of `from` interpolated onto the nodes of `to` (both on grids of the same
/// parameter rectangle): bilinear in `(x2, x3)` on `from`'s grid, each component apart.
///
/// # Math
/// ```text
/// t2 = (x2 - theta0) / dx2,  i = floor(t2) (clamped to the last cell),  a = t2 - i
/// t3 = x3 / dx3,             j = floor(t3) (likewise),                  b = t3 - j
/// v(x2, x3) = (1-a)(1-b) v_ij + a(1-b) v_i+1,j + (1-a) b v_i,j+1 + a b v_i+1,j+1
/// ```
/// (`i + 1` wraps on a periodic grid). Exact for fields bilinear in `(x2, x3)`; the error of a
/// smooth field is `O(dx^2)`: a starting guess on a finer grid ([`crate::contact::solve_sequenced`]).
///
/// # Panics
/// If `v.len() != from.dof_count()`.
pub fn interpolate_nodal<A, B>(from: &A, v: &[f64], to: &B) -> Vec<f64>
where
    A: Discretisation + ?Sized,
    B: Discretisation + ?Sized,
{
    assert_eq!(v.len(), from.dof_count(), "one value per unknown of `from`");
    let (src, dst) = (from.grid(), to.grid());
    let [theta0, _] = src.theta();
    let (n2, n3) = (src.n2(), src.n3());
    let (dx2, dx3) = (src.dx2(), src.dx3());
    let cell = |t: f64, n: usize, periodic: bool| -> (usize, usize, f64) {
        if periodic {
            let k = t.floor();
            let i = (k.rem_euclid(n as f64)) as usize % n;
            (i, (i + 1) % n, t - k)
        } else {
            let i = (t.floor().max(0.0) as usize).min(n - 2);
            (i, i + 1, t - i as f64)
        }
    };
    let mut out = vec![0.0; to.dof_count()];
    for k in 0..dst.node_count() {
        let node = dst.node(k);
        let [x2, x3] = dst.coordinates(node);
        let (i0, i1, a) = cell((x2 - theta0) / dx2, n2, src.is_periodic());
        let (j0, j1, b) = cell(x3 / dx3, n3, false);
        for c in Component::ALL {
            let at = |i: usize, j: usize| v[from.dof([i, j], c)];
            out[to.dof(node, c)] = (1.0 - a) * (1.0 - b) * at(i0, j0)
                + a * (1.0 - b) * at(i1, j0)
                + (1.0 - a) * b * at(i0, j1)
                + a * b * at(i1, j1);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows of a 7 x 7 matrix with scattered columns, split into blocks of `sizes` rows.
    fn rows() -> Vec<Vec<(usize, f64)>> {
        (0..7)
            .map(|r| {
                let mut row: Vec<(usize, f64)> = (0..7)
                    .filter(|c| (r * 3 + c * 5) % 4 != 0)
                    .map(|c| (c, 1.0 / (1.0 + (r * 7 + c) as f64) - 0.1))
                    .collect();
                row.push((r, -0.0)); // a signed zero, placed as `0 + v` like `add_entry`
                row.sort_by_key(|t| t.0);
                row.dedup_by_key(|t| t.0);
                row
            })
            .collect()
    }

    fn blocks(rows: &[Vec<(usize, f64)>], sizes: &[usize]) -> Vec<RowBlock> {
        let mut out = Vec::new();
        let mut next = 0;
        for &size in sizes {
            let mut block = RowBlock::default();
            for row in &rows[next..next + size] {
                block.cols.extend(row.iter().map(|t| t.0));
                block.values.extend(row.iter().map(|t| t.1));
                block.ends.push(block.cols.len());
            }
            out.push(block);
            next += size;
        }
        out
    }

    #[test]
    fn from_row_blocks_matches_from_entries_bit_for_bit() {
        let rows = rows();
        let entries: Vec<(usize, usize)> = rows
            .iter()
            .enumerate()
            .flat_map(|(r, row)| row.iter().map(move |t| (r, t.0)))
            .collect();
        let mut filled = LinearSystem::from_entries(7, &entries).unwrap();
        let values: Vec<f64> = rows.iter().flatten().map(|t| t.1).collect();
        for (k, &v) in values.iter().enumerate() {
            filled.add_entry(k, v);
        }
        let rhs: Vec<f64> = (0..7).map(|r| r as f64).collect();
        for sizes in [&[7][..], &[3, 0, 4], &[1, 1, 1, 1, 1, 1, 1]] {
            let mut reference = filled.clone();
            let mut system =
                LinearSystem::from_row_blocks(&blocks(&rows, sizes), rhs.clone()).unwrap();
            assert_eq!(system.pattern, reference.pattern);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&system.values), bits(&reference.values));
            assert_eq!(system.rhs, rhs);
            // entry k lands in the same slot: a refill by entry number agrees too
            system.clear();
            reference.clear();
            for (k, &v) in values.iter().enumerate() {
                system.add_entry(k, 2.0 * v);
                reference.add_entry(k, 2.0 * v);
            }
            assert_eq!(bits(&system.values), bits(&reference.values));
        }
    }

    #[test]
    fn from_row_blocks_rejects_bad_rows() {
        let block = |cols: Vec<usize>, ends: Vec<usize>| RowBlock {
            values: vec![1.0; cols.len()],
            cols,
            ends,
        };
        let rhs = vec![0.0; 2];
        // a repeated column, a column out of range, too few rows, decreasing ends
        for (blocks, what) in [
            (vec![block(vec![0, 0], vec![2, 2])], "repeated column"),
            (vec![block(vec![0, 2], vec![1, 2])], "column out of range"),
            (vec![block(vec![0], vec![1])], "one row of two"),
            (vec![block(vec![0, 1], vec![2, 1])], "decreasing ends"),
        ] {
            assert!(
                LinearSystem::from_row_blocks(&blocks, rhs.clone()).is_err(),
                "{what} accepted"
            );
        }
        let mismatched = RowBlock {
            cols: vec![0, 1],
            values: vec![1.0],
            ends: vec![1, 2],
        };
        assert!(matches!(
            LinearSystem::from_row_blocks(&[mismatched], rhs),
            Err(ElasticityError::DimensionMismatch { .. })
        ));
    }
}
