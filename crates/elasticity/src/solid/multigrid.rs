//! The geometric multigrid hierarchy of the structured box grid: coarser grids and the
//! trilinear prolongations between them, per displacement component, with constrained
//! (Dirichlet) dofs honoured.
//!
//! # Coarsenable grids
//! A direction of `c` cells (`n - 1` nodes apart; `n` when `x2` is periodic) is halved when
//! `c` is even and at least 4; the hierarchy stops when no direction can be halved or a level
//! has at most `coarsest_unknowns` unknowns. Grids with `2^k` (or `2^k m`) cells per direction
//! coarsen all the way (`n = 2^k + 1` nodes: 5, 9, 17, 33, 65, 129, 257, ...); a direction of
//! odd cell count is left as it is (semi-coarsening in the others).

use std::sync::Arc;

use capstan_solvers::CsrMatrix;

use super::grid::BoxGrid;
use super::operator::SolidNavier;

/// Unknowns per node.
const COMPONENTS: usize = 3;

/// The coarse node count along a direction of `n` nodes (`periodic`: `n` cells), or `None`
/// when it is not halved.
///
/// # Math
/// ```text
/// cells c = n - 1 (n periodic);  halved when c even and c >= 4 (6 periodic):  c' = c / 2
/// ```
pub fn coarser_count(n: usize, periodic: bool) -> Option<usize> {
    let cells = if periodic { n } else { n - 1 };
    (cells.is_multiple_of(2) && cells >= if periodic { 6 } else { 4 })
        .then(|| if periodic { cells / 2 } else { cells / 2 + 1 })
}

/// The 1-D interpolation from the coarse nodes to the `n` fine nodes of a direction: for each
/// fine node its `(coarse node, weight)` pairs.
///
/// # Math
/// ```text
/// fine 2I    <- coarse I              (weight 1)
/// fine 2I+1  <- coarse I, I + 1       (weights 1/2, 1/2; I + 1 taken mod n/2 when periodic)
/// ```
/// A direction that is not halved is the identity.
pub(super) fn interpolation_1d(n: usize, periodic: bool, halve: bool) -> Vec<Vec<(usize, f64)>> {
    if !halve {
        return (0..n).map(|i| vec![(i, 1.0)]).collect();
    }
    let coarse = if periodic { n / 2 } else { (n - 1) / 2 + 1 };
    (0..n)
        .map(|i| {
            if i % 2 == 0 {
                vec![(i / 2, 1.0)]
            } else {
                vec![(i / 2, 0.5), ((i / 2 + 1) % coarse, 0.5)]
            }
        })
        .collect()
}

/// The trilinear prolongation from the grid of `coarse` nodes to the grid of `fine` nodes
/// (numbering `3 ((i1 n2 + i2) n3 + i3) + c`, as [`SolidNavier`]), and the constrained mask of
/// the coarse dofs.
///
/// # Math
/// ```text
/// P[(i, c), (I, c)] = w1(i1, I1) w2(i2, I2) w3(i3, I3)      (1-D weights: interpolation_1d)
/// coarse dof (I, c) constrained  iff  the fine dof at the same node is
/// constrained fine dof:  the row is the injection from its coarse dof when its node is a
///                        coarse node, else empty (the correction never moves it)
/// free fine dof:         the weights of constrained coarse dofs are dropped
/// ```
/// so a constrained dof (an identity row of the Dirichlet elimination) stays decoupled on
/// every level, and `P^T A P` is the Galerkin operator of the constrained space.
fn prolongation(
    fine: [usize; 3],
    halve: [bool; 3],
    periodic: bool,
    constrained: &[bool],
) -> (CsrMatrix, [usize; 3], Vec<bool>) {
    let per = [false, periodic, false];
    let w: [Vec<Vec<(usize, f64)>>; 3] =
        core::array::from_fn(|d| interpolation_1d(fine[d], per[d], halve[d]));
    tensor_prolongation(fine, &w, constrained)
}

/// The prolongation of the tensor product of the 1-D interpolations `w` (per direction, for
/// each fine node line its `(coarse line, weight)` pairs, no zero weights; a fine line with a
/// single pair of weight 1 lies on a coarse line), with the constraints of [`prolongation`].
pub(super) fn tensor_prolongation(
    fine: [usize; 3],
    w: &[Vec<Vec<(usize, f64)>>; 3],
    constrained: &[bool],
) -> (CsrMatrix, [usize; 3], Vec<bool>) {
    let coarse: [usize; 3] =
        core::array::from_fn(|d| w[d].iter().flatten().map(|e| e.0 + 1).max().unwrap_or(0));
    let node = |n: [usize; 3], [i, j, k]: [usize; 3]| (i * n[1] + j) * n[2] + k;
    let mut coarse_constrained = vec![false; COMPONENTS * coarse.iter().product::<usize>()];
    let is_coarse_node =
        |i: [usize; 3]| (0..3).all(|d| w[d][i[d]].len() == 1 && w[d][i[d]][0].1 == 1.0);
    let to_coarse = |i: [usize; 3]| -> [usize; 3] { core::array::from_fn(|d| w[d][i[d]][0].0) };
    for i1 in 0..fine[0] {
        for i2 in 0..fine[1] {
            for i3 in 0..fine[2] {
                let i = [i1, i2, i3];
                if !is_coarse_node(i) {
                    continue;
                }
                let (f, c) = (node(fine, i), node(coarse, to_coarse(i)));
                for comp in 0..COMPONENTS {
                    coarse_constrained[COMPONENTS * c + comp] = constrained[COMPONENTS * f + comp];
                }
            }
        }
    }
    let rows = COMPONENTS * fine.iter().product::<usize>();
    let mut row_ptr = Vec::with_capacity(rows + 1);
    row_ptr.push(0);
    let mut cols: Vec<u32> = Vec::with_capacity(rows * 4);
    let mut values = Vec::with_capacity(rows * 4);
    let mut entries: Vec<(u32, f64)> = Vec::with_capacity(8);
    for i1 in 0..fine[0] {
        for i2 in 0..fine[1] {
            for i3 in 0..fine[2] {
                let i = [i1, i2, i3];
                let f = node(fine, i);
                for comp in 0..COMPONENTS {
                    entries.clear();
                    if constrained[COMPONENTS * f + comp] {
                        if is_coarse_node(i) {
                            let c = node(coarse, to_coarse(i));
                            entries.push(((COMPONENTS * c + comp) as u32, 1.0));
                        }
                    } else {
                        for &(a, wa) in &w[0][i1] {
                            for &(b, wb) in &w[1][i2] {
                                for &(e, we) in &w[2][i3] {
                                    let dof = COMPONENTS * node(coarse, [a, b, e]) + comp;
                                    if !coarse_constrained[dof] {
                                        entries.push((dof as u32, wa * wb * we));
                                    }
                                }
                            }
                        }
                    }
                    entries.sort_unstable_by_key(|e| e.0);
                    for &(c, v) in &entries {
                        cols.push(c);
                        values.push(v);
                    }
                    row_ptr.push(cols.len());
                }
            }
        }
    }
    let ncols = coarse_constrained.len();
    let p = CsrMatrix::new(rows, ncols, row_ptr, cols, values)
        .expect("the prolongation's rows are sorted and in range");
    (p, coarse, coarse_constrained)
}

/// The multigrid hierarchy of a box grid: node counts of every level (finest first) and the
/// prolongations between consecutive levels.
#[derive(Debug, Clone)]
pub struct BoxHierarchy {
    /// `[n1, n2, n3]` of every level, finest first.
    pub counts: Vec<[usize; 3]>,
    /// `P_l` from level `l + 1` to level `l`.
    pub prolongations: Arc<[CsrMatrix]>,
}

/// The hierarchy of `grid` with the constrained dofs `constrained` (one per dof, numbering
/// `3 node + c`): halving every direction that can be halved ([`coarser_count`]) until none can
/// or a level has at most `coarsest_unknowns` unknowns.
///
/// # Panics
/// If `constrained` does not have `3 n1 n2 n3` entries.
#[track_caller]
pub fn box_hierarchy(
    grid: &BoxGrid,
    constrained: &[bool],
    coarsest_unknowns: usize,
) -> BoxHierarchy {
    assert_eq!(
        constrained.len(),
        COMPONENTS * grid.node_count(),
        "one constrained flag per dof"
    );
    coarsen(grid, constrained, coarsest_unknowns, None)
}

/// [`box_hierarchy`] with semi-coarsening for stretched cells: `cell` is the physical size of
/// a fine cell per direction (e.g. `dx_d sqrt(g_dd)` at the centre of the body); a level
/// halves only the directions whose cells are shorter than twice the shortest cell among
/// the directions that can be halved, so cells of aspect 4 are first made cubic.
///
/// # Math
/// ```text
/// halve d  iff  d can be halved (coarser_count)  and  h_d < 2 min_{d' halvable} h_d'
/// h_d <- 2 h_d for every halved d
/// ```
///
/// # Panics
/// If `constrained` does not have `3 n1 n2 n3` entries.
#[track_caller]
pub fn semicoarsening_hierarchy(
    grid: &BoxGrid,
    constrained: &[bool],
    coarsest_unknowns: usize,
    cell: [f64; 3],
) -> BoxHierarchy {
    assert_eq!(
        constrained.len(),
        COMPONENTS * grid.node_count(),
        "one constrained flag per dof"
    );
    coarsen(grid, constrained, coarsest_unknowns, Some(cell))
}

/// The coarsening loop of [`box_hierarchy`] (`cell = None`: every halvable direction) and
/// [`semicoarsening_hierarchy`].
fn coarsen(
    grid: &BoxGrid,
    constrained: &[bool],
    coarsest_unknowns: usize,
    mut cell: Option<[f64; 3]>,
) -> BoxHierarchy {
    let mut counts = vec![grid.counts()];
    let periodic = grid.is_periodic();
    let mut mask = constrained.to_vec();
    let mut prolongations = Vec::new();
    loop {
        let n = *counts.last().expect("the fine grid");
        if COMPONENTS * n.iter().product::<usize>() <= coarsest_unknowns {
            break;
        }
        let per = [false, periodic, false];
        let mut halve: [bool; 3] = core::array::from_fn(|d| coarser_count(n[d], per[d]).is_some());
        if !halve.iter().any(|&h| h) {
            break;
        }
        if let Some(h) = cell.as_mut() {
            let shortest = (0..3)
                .filter(|&d| halve[d])
                .map(|d| h[d])
                .fold(f64::INFINITY, f64::min);
            for d in 0..3 {
                halve[d] = halve[d] && h[d] < 2.0 * shortest;
                if halve[d] {
                    h[d] *= 2.0;
                }
            }
        }
        let (p, coarse, coarse_mask) = prolongation(n, halve, periodic, &mask);
        prolongations.push(p);
        counts.push(coarse);
        mask = coarse_mask;
    }
    BoxHierarchy {
        counts,
        prolongations: prolongations.into(),
    }
}

impl<G> SolidNavier<G> {
    /// The geometric multigrid hierarchy of the operator's grid ([`box_hierarchy`]) with its
    /// Dirichlet dofs constrained.
    pub fn multigrid_hierarchy(&self, coarsest_unknowns: usize) -> BoxHierarchy {
        let constrained: Vec<bool> = self.setup.dirichlet.iter().map(Option::is_some).collect();
        box_hierarchy(&self.setup.grid, &constrained, coarsest_unknowns)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarser_counts_halve_even_cell_counts_only() {
        assert_eq!(coarser_count(9, false), Some(5));
        assert_eq!(coarser_count(5, false), Some(3));
        assert_eq!(coarser_count(3, false), None); // 2 cells: the coarsest
        assert_eq!(coarser_count(11, false), Some(6));
        assert_eq!(coarser_count(6, false), None); // 5 cells
        assert_eq!(coarser_count(8, true), Some(4));
        assert_eq!(coarser_count(6, true), Some(3));
        assert_eq!(coarser_count(4, true), None); // 2 periodic cells would alias
    }

    #[test]
    fn prolongation_reproduces_trilinear_fields_and_honours_constraints() {
        let grid = BoxGrid::new([0.0, 1.0], [0.0, 2.0], 1.0, [5, 9, 5], false).unwrap();
        let n = grid.node_count();
        let mut constrained = vec![false; 3 * n];
        // v^3 = 0 on x3 = 0 (as the contact face)
        for m in 0..n {
            if grid.node(m)[2] == 0 {
                constrained[3 * m + 2] = true;
            }
        }
        assert_eq!(
            box_hierarchy(&grid, &constrained, 0).counts,
            vec![[5, 9, 5], [3, 5, 3], [3, 3, 3]]
        );
        // stops at a level of at most `coarsest_unknowns` (3 x 3 x 5 x 3 = 135)
        let h = box_hierarchy(&grid, &constrained, 135);
        assert_eq!(h.counts, vec![[5, 9, 5], [3, 5, 3]]);
        let p = &h.prolongations[0];
        let coarse = BoxGrid::new([0.0, 1.0], [0.0, 2.0], 1.0, [3, 5, 3], false).unwrap();
        // a trilinear field per component is interpolated exactly (v^3 vanishing on x3 = 0)
        let field = |x: [f64; 3], c: usize| match c {
            0 => 1.0 + 2.0 * x[0] - x[1] + 0.5 * x[2] + x[0] * x[1] * x[2],
            1 => x[1] * x[2] - 3.0,
            _ => x[2] * (1.0 + x[0] - x[1]),
        };
        let xc: Vec<f64> = (0..3 * coarse.node_count())
            .map(|d| field(coarse.coordinates(coarse.node(d / 3)), d % 3))
            .collect();
        let mut xf = vec![0.0; 3 * n];
        p.mul_vec(&xc, &mut xf);
        for (d, v) in xf.iter().enumerate() {
            let exact = field(grid.coordinates(grid.node(d / 3)), d % 3);
            assert!((v - exact).abs() < 1e-13, "dof {d}: {v} vs {exact}");
        }
        // constrained rows: injection at coarse nodes, empty elsewhere
        for m in 0..n {
            let node = grid.node(m);
            if node[2] == 0 {
                let (cols, vals) = p.row(3 * m + 2);
                if node[0].is_multiple_of(2) && node[1].is_multiple_of(2) {
                    assert_eq!(vals, &[1.0]);
                    assert_eq!(cols.len(), 1);
                } else {
                    assert!(cols.is_empty());
                }
            }
        }
    }

    #[test]
    fn periodic_direction_wraps_and_semi_coarsening_stops() {
        let grid = BoxGrid::new([0.0, 1.0], [0.0, 6.0], 1.0, [6, 8, 5], true).unwrap();
        let h = box_hierarchy(&grid, &vec![false; 3 * grid.node_count()], 0);
        // x1: 5 cells (kept); x2: 8 -> 4 periodic cells; x3: 4 -> 2 cells
        assert_eq!(h.counts, vec![[6, 8, 5], [6, 4, 3]]);
        let p = &h.prolongations[0];
        // the last fine x2 node (j = 7) averages coarse j = 3 and j = 0 (wrapped)
        let grid_c = [6, 4, 3];
        let dof = 3 * ((2 * 8 + 7) * 5 + 2);
        let (cols, vals) = p.row(dof);
        let expect: Vec<u32> = [0usize, 3]
            .iter()
            .map(|&j| (3 * ((2 * grid_c[1] + j) * grid_c[2] + 1)) as u32)
            .collect();
        assert_eq!(cols, &expect[..]);
        assert_eq!(vals, &[0.5, 0.5]);
    }
}
