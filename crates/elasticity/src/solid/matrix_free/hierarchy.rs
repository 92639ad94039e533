//! The multigrid of the matrix-free 3-D operator: p-multigrid to Q1 (or one geometric
//! halving of Q1) onto an assembled Q1 operator, then the box's Galerkin hierarchy with
//! semi-coarsening for stretched cells.

use std::sync::Arc;

use capstan_solvers::{CsrMatrix, MultigridParams, OperatorLevel, OperatorMultigrid};

use super::operator::SolidMatrixFree;
use super::p_levels::{PLevel, inject_pinned, p_levels};
use crate::error::ElasticityError;
use crate::finite_element::{ElementOrder, VolumetricIntegration};
use crate::shell_geometry::ShellGeometry;
use crate::solid::boundary::SolidBoundary;
use crate::solid::element::HexElement;
use crate::solid::grid::BoxGrid;
use crate::solid::multigrid::{
    coarser_count, interpolation_1d, semicoarsening_hierarchy, tensor_prolongation,
};
use crate::solid::operator::SolidNavier;

/// Settings of the multigrid of a [`SolidMatrixFree`] operator ([`SolidMultigridParams::build`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidMultigridParams {
    /// Smoother (Chebyshev–Jacobi by default, its diagonal computed matrix-free on the fine
    /// level), smoothing steps and power iterations of every level.
    pub multigrid: MultigridParams,
    /// The assembled hierarchy below the matrix-free level coarsens until a level has at most
    /// this many unknowns (solved by a sparse LU).
    pub coarsest_unknowns: usize,
    /// Intermediate matrix-free p-levels for elements of degree `p >= 4` (`p -> p/2 -> ... ->
    /// 2`, then Q1; default `true`); `false` goes from the fine level straight to Q1.
    pub p_levels: bool,
}

/// The pieces of the V-cycle of a [`SolidMatrixFree`] operator
/// ([`SolidMultigridParams::parts`]).
#[derive(Debug, Clone)]
pub struct MultigridParts {
    /// `P_0` from the assembled Q1 level to the matrix-free fine level (the field on the
    /// element vertices for `p > 1`; with p-levels the product of their transfers, kept for
    /// grid sequencing).
    pub prolongation: CsrMatrix,
    /// The assembled Q1 operator of the coarse level (rediscretised).
    pub coarse: CsrMatrix,
    /// The box's (semi-coarsening) prolongations below the coarse level, finest first.
    pub below: Arc<[CsrMatrix]>,
    /// The intermediate matrix-free p-levels between the fine level and the Q1 level, finest
    /// first (empty for `p <= 3` or without [`SolidMultigridParams::p_levels`]).
    pub p_levels: Vec<PLevel>,
    /// With p-levels: the transfer from the assembled Q1 level to the last p-level.
    pub p_coarse: Option<CsrMatrix>,
}

impl MultigridParts {
    /// The prolongation of each matrix-free level of the V-cycle from the level below it,
    /// finest first: `prolongation` alone without p-levels; else the fine level's from the
    /// first p-level, each p-level's from the next, the last one's from Q1 (`p_coarse`).
    pub fn transfers(&self) -> Vec<&CsrMatrix> {
        match &self.p_coarse {
            None => vec![&self.prolongation],
            Some(last) => self
                .p_levels
                .iter()
                .map(|l| &l.prolongation)
                .chain([last])
                .collect(),
        }
    }
}

impl Default for SolidMultigridParams {
    fn default() -> Self {
        Self {
            multigrid: MultigridParams::default(),
            coarsest_unknowns: 5_000,
            p_levels: true,
        }
    }
}

/// The 1-D interpolation of the Q1 field on the element boundaries (`elements + 1` lines,
/// `elements` when `periodic`) at the node lines of elements of degree `k` with reference
/// nodes `nodes`: for each fine line its `(coarse line, weight)` pairs, zero weights dropped.
///
/// # Math
/// ```text
/// fine line i = k e + a  (a = 0 .. k),  xi_a the reference node:
///   coarse e <- (1 - xi_a) / 2,   coarse e + 1 <- (1 + xi_a) / 2     (mod elements if periodic)
/// ```
fn p_interpolation(n: usize, k: usize, nodes: &[f64], periodic: bool) -> Vec<Vec<(usize, f64)>> {
    let elements = if periodic { n / k } else { (n - 1) / k };
    (0..n)
        .map(|i| {
            let e = (i / k).min(elements.saturating_sub(1));
            let xi = nodes[i - k * e];
            let right = if periodic { (e + 1) % elements } else { e + 1 };
            [(e, 0.5 * (1.0 - xi)), (right, 0.5 * (1.0 + xi))]
                .into_iter()
                .filter(|&(_, w)| w != 0.0)
                .collect()
        })
        .collect()
}

/// The p-multigrid transfer of `grid` (node lines of elements of `element`) to the Q1 grid
/// of the element vertices: the prolongation, the vertex grid's node counts and its
/// constrained dofs (see [`p_interpolation`] and [`tensor_prolongation`]).
pub(crate) fn p_prolongation(
    grid: &BoxGrid,
    element: HexElement,
    constrained: &[bool],
) -> (CsrMatrix, [usize; 3], Vec<bool>) {
    let n = grid.counts();
    let per = [false, grid.is_periodic(), false];
    let nodes = element.reference_nodes();
    let k = element.degree();
    let w: [Vec<Vec<(usize, f64)>>; 3] =
        core::array::from_fn(|d| p_interpolation(n[d], k, &nodes, per[d]));
    tensor_prolongation(n, &w, constrained)
}

/// The physical cell sizes `dx_d sqrt(g_dd)` of `grid` at its centre (mid-thickness), which
/// decide the semi-coarsening of the matrix-free V-cycle ([`coarse_level_nodes`]).
///
/// # Errors
/// The chart's at the centre ([`ElasticityError::Geometry`]).
pub fn cell_sizes<G: ShellGeometry>(
    chart: &G,
    grid: &BoxGrid,
) -> Result<[f64; 3], ElasticityError> {
    let [a, b] = grid.x1_range();
    let [c, d] = grid.x2_range();
    let p = chart.shell_point([0.5 * (a + b), 0.5 * (c + d), 0.5 * grid.thickness()])?;
    let h = grid.spacing();
    Ok(core::array::from_fn(|k| h[k] * p.metric[k][k].sqrt()))
}

/// The node counts of the assembled Q1 level of the matrix-free V-cycle below a grid of
/// `nodes` (non-periodic) of elements of `degree` with cell sizes `cell` ([`cell_sizes`]):
/// what [`SolidMultigridParams::parts`] builds, for memory estimates before any assembly.
///
/// # Math
/// ```text
/// p > 1:  (n_d - 1) / p + 1          (the element vertices: p-multigrid straight to Q1)
/// p = 1:  the first semi-coarsening step: each halvable direction (coarser_count) whose cell
///         is shorter than twice the shortest halvable one, n_d -> (n_d - 1) / 2 + 1; the
///         other directions keep n_d
/// ```
pub fn coarse_level_nodes(nodes: [usize; 3], degree: usize, cell: [f64; 3]) -> [usize; 3] {
    if degree > 1 {
        return nodes.map(|n| (n - 1) / degree + 1);
    }
    let coarser = nodes.map(|n| coarser_count(n, false));
    let shortest = (0..3)
        .filter(|&d| coarser[d].is_some())
        .map(|d| cell[d])
        .fold(f64::INFINITY, f64::min);
    core::array::from_fn(|d| match coarser[d] {
        Some(c) if cell[d] < 2.0 * shortest => c,
        _ => nodes[d],
    })
}

impl SolidMultigridParams {
    /// The V-cycle of `fine` with the boundary conditions it was built with (only which dofs
    /// are prescribed matters: the coarse operators are rediscretised on them).
    ///
    /// # Math
    /// ```text
    /// level 0:  A_0 = fine (matrix-free), Chebyshev on D^-1 A_0 (D computed matrix-free)
    /// p >= 4:   p-levels of degree p/2, p/4, ... >= 2 on the same elements (GLL nodes),
    ///           matrix-free, each with its Chebyshev smoother; the transfer between two of
    ///           them interpolates the coarser degree's field at the finer level's nodes
    /// P_0:      p > 1: the Q1 field on the element vertices interpolated at the GLL (or
    ///           uniform) nodes ((n - 1)/p + 1 nodes per direction; from the last p-level
    ///           when there are p-levels, else straight from the fine level)
    ///           p = 1: trilinear from the grid with every halvable direction halved (semi-
    ///           coarsening of stretched cells); the same grid if none can be halved
    /// level 1:  A_1 = the Q1 operator rediscretised on the coarse grid (assembled)
    /// below:    Galerkin P^T A P on the box's semi-coarsening hierarchy, sparse LU at
    ///           `coarsest_unknowns`
    /// ```
    /// Prolongations honour the Dirichlet dofs as the box hierarchy does (injection at coarse
    /// nodes, dropped weights of constrained coarse dofs).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] for bad multigrid settings (naming the setting);
    /// [`ElasticityError::InconsistentBoundary`] for a pinned node off the coarse grid; the
    /// coarse operator's errors; a singular coarsest operator.
    pub fn build<G: ShellGeometry + Clone + Send + Sync + 'static>(
        &self,
        fine: &Arc<SolidMatrixFree<G>>,
        boundary: &SolidBoundary,
    ) -> Result<OperatorMultigrid, ElasticityError> {
        let parts = self.parts(fine, boundary)?;
        let operators =
            core::iter::once(Arc::clone(fine) as Arc<dyn capstan_solvers::LinearOperator + Send>)
                .chain(parts.p_levels.iter().map(|l| Arc::clone(&l.operator)));
        let levels = operators
            .zip(parts.transfers())
            .map(|(operator, p)| OperatorLevel {
                operator,
                prolongation: p.clone(),
            })
            .collect();
        Ok(OperatorMultigrid::new(
            levels,
            parts.coarse,
            parts.below,
            self.multigrid,
        )?)
    }

    /// What [`SolidMultigridParams::build`] builds the V-cycle from (the transfers and the
    /// assembled coarse level), for callers that put another operator on the fine level
    /// (the Jacobian of the contact problem: the bulk plus a face term).
    ///
    /// # Errors
    /// See [`SolidMultigridParams::build`].
    pub fn parts<G: ShellGeometry + Clone + Send + Sync + 'static>(
        &self,
        fine: &SolidMatrixFree<G>,
        boundary: &SolidBoundary,
    ) -> Result<MultigridParts, ElasticityError> {
        self.multigrid.validate()?;
        let grid = fine.grid();
        let n = grid.counts();
        let periodic = grid.is_periodic();
        let per = [false, periodic, false];
        let element = fine.element();
        let k = element.degree();
        let chart = fine.setup.chart.clone();
        let w: [Vec<Vec<(usize, f64)>>; 3] = if k > 1 {
            let nodes = element.reference_nodes();
            core::array::from_fn(|d| p_interpolation(n[d], k, &nodes, per[d]))
        } else {
            // one semi-coarsening step of the box (or none: the same grid, assembled)
            let h =
                semicoarsening_hierarchy(grid, fine.constrained(), 0, cell_sizes(&chart, grid)?);
            let halve: [bool; 3] = match h.counts.get(1) {
                Some(c) => core::array::from_fn(|d| c[d] != n[d]),
                None => [false; 3],
            };
            debug_assert!((0..3).all(|d| !halve[d] || coarser_count(n[d], per[d]).is_some()));
            core::array::from_fn(|d| interpolation_1d(n[d], per[d], halve[d]))
        };
        let (prolongation, coarse_counts, coarse_mask) =
            tensor_prolongation(n, &w, fine.constrained());
        let (p_levels, last) = if self.p_levels && k > 1 {
            p_levels(fine, boundary)?
        } else {
            (Vec::new(), None)
        };
        let p_coarse = last.map(|(counts, constrained, element)| {
            let nodes = element.reference_nodes();
            let q = element.degree();
            let w: [Vec<Vec<(usize, f64)>>; 3] =
                core::array::from_fn(|d| p_interpolation(counts[d], q, &nodes, per[d]));
            let (p, c, mask) = tensor_prolongation(counts, &w, &constrained);
            debug_assert!(c == coarse_counts && mask == coarse_mask, "one Q1 level");
            p
        });
        debug_assert!(
            periodic || coarse_counts == coarse_level_nodes(n, k, cell_sizes(&chart, grid)?),
            "the memory estimate's coarse level is the one built"
        );
        let coarse_grid = grid.with_counts(coarse_counts)?;
        let mut coarse_boundary = boundary.clone();
        inject_pinned(
            &mut coarse_boundary,
            &w,
            "a pinned node is off the coarse grid of the multigrid",
        )?;
        let coarse = SolidNavier::new(
            chart.clone(),
            fine.material(),
            coarse_grid,
            &coarse_boundary,
            None,
            HexElement::Uniform(ElementOrder::Q1),
            VolumetricIntegration::Full,
        )?;
        let coarse_constrained: Vec<bool> =
            coarse.setup.dirichlet.iter().map(Option::is_some).collect();
        if coarse_constrained != coarse_mask {
            return Err(ElasticityError::InconsistentBoundary {
                what: "the coarse grid's Dirichlet dofs differ from the fine grid's at its nodes",
            });
        }
        let system = coarse.system();
        let matrix = CsrMatrix::from_pattern(&system.pattern, &system.values)?;
        let below = semicoarsening_hierarchy(
            coarse.grid(),
            &coarse_constrained,
            self.coarsest_unknowns,
            cell_sizes(&chart, coarse.grid())?,
        );
        drop(coarse);
        Ok(MultigridParts {
            prolongation,
            coarse: matrix,
            below: below.prolongations,
            p_levels,
            p_coarse,
        })
    }
}
