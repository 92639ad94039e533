//! The intermediate levels of the p-multigrid of a high-order matrix-free operator: degree
//! `p -> p/2 -> ... ` on the same elements, each matrix-free, above the assembled Q1 level.

use std::sync::Arc;

use capstan_solvers::{CsrMatrix, LinearOperator};

use super::operator::SolidMatrixFree;
use crate::error::ElasticityError;
use crate::finite_element::VolumetricIntegration;
use crate::shell_geometry::ShellGeometry;
use crate::solid::boundary::SolidBoundary;
use crate::solid::element::HexElement;
use crate::solid::multigrid::tensor_prolongation;

/// The smallest degree that gets intermediate p-levels: `p >= 4` (Qp3 and below go straight
/// to Q1, as before).
pub(crate) const P_LEVELS_FROM_DEGREE: usize = 4;

/// Moves each pinned node of `boundary` to its node on a coarser level, given per direction
/// the interpolation rows `w[d][fine] = [(coarse, weight)]`: a pinned node must be a node of
/// the coarse level too (its row is the single entry `(c, 1)`), so the pinned set injects.
///
/// # Errors
/// [`ElasticityError::InconsistentBoundary`] naming `what` for a pinned node off the coarse
/// level's node lines.
pub(super) fn inject_pinned(
    boundary: &mut SolidBoundary,
    w: &[Vec<Vec<(usize, f64)>>; 3],
    what: &'static str,
) -> Result<(), ElasticityError> {
    for (node, _, _) in &mut boundary.pinned {
        for d in 0..3 {
            match w[d].get(node[d]).map(|v| &v[..]) {
                Some([(c, 1.0)]) => node[d] = *c,
                _ => return Err(ElasticityError::InconsistentBoundary { what }),
            }
        }
    }
    Ok(())
}

/// The degrees of the intermediate p-levels below a fine level of degree `p`, finest first:
/// `p / 2, p / 4, ...` while at least 2 (none below [`P_LEVELS_FROM_DEGREE`]).
///
/// # Math
/// ```text
/// p = 4: [2];  p = 5: [2];  p = 8: [4, 2];  p <= 3: []
/// ```
pub(crate) fn p_level_degrees(p: usize) -> Vec<usize> {
    let mut out = Vec::new();
    if p < P_LEVELS_FROM_DEGREE {
        return out;
    }
    let mut q = p / 2;
    while q >= 2 {
        out.push(q);
        q /= 2;
    }
    out
}

/// An intermediate matrix-free level of the p-multigrid: the operator of degree `degree` on the
/// fine grid's elements (GLL nodes) and the prolongation to the next finer level.
#[derive(Clone)]
pub struct PLevel {
    /// The element degree of this level.
    pub degree: usize,
    /// The operator of this level ([`SolidMatrixFree`] on the same chart, material, elements
    /// and Dirichlet dofs), by its action.
    pub operator: Arc<dyn LinearOperator + Send>,
    /// From this level to the next finer one (the fine level for the first p-level).
    pub prolongation: CsrMatrix,
    /// Bytes held by the operator.
    pub bytes: usize,
}

impl core::fmt::Debug for PLevel {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PLevel")
            .field("degree", &self.degree)
            .field("unknowns", &self.operator.dimension())
            .field("coarse_unknowns", &self.prolongation.ncols())
            .finish()
    }
}

/// The 1-D interpolation of a field of degree `q` (nodes `coarse_nodes` in each element) at
/// the node lines of degree `p` (nodes `fine_nodes`) on the same elements: for each of the `n`
/// fine lines its `(coarse line, weight)` pairs, zero weights dropped.
///
/// # Math
/// ```text
/// fine line i = p e + a (a = 0 .. p), xi_a = fine_nodes[a]:
///   coarse line q e + b  <-  L_b(xi_a),  L_b the Lagrange basis on coarse_nodes  (b = 0 .. q;
///                                         line q e + b taken mod q elements if periodic)
/// ```
/// A fine line at a coarse node (`xi_a = eta_b`) gets the single weight `L_b(eta_b) = 1`
/// exactly (the products of the basis are `(x - x) = 0` and `(x - y) / (x - y) = 1`).
fn p_to_p_interpolation(
    n: usize,
    p: usize,
    fine_nodes: &[f64],
    coarse: HexElement,
    periodic: bool,
) -> Vec<Vec<(usize, f64)>> {
    let q = coarse.degree();
    let elements = if periodic { n / p } else { (n - 1) / p };
    let lines = if periodic {
        q * elements
    } else {
        q * elements + 1
    };
    (0..n)
        .map(|i| {
            let e = (i / p).min(elements.saturating_sub(1));
            let (basis, _) = coarse.shape_1d(fine_nodes[i - p * e]);
            basis
                .into_iter()
                .enumerate()
                .filter(|&(_, w)| w != 0.0)
                .map(|(b, w)| ((q * e + b) % lines, w))
                .collect()
        })
        .collect()
}

/// The intermediate p-levels below `fine` ([`p_level_degrees`] of its degree), finest first,
/// with the node counts and constrained dofs of the last one (`None` when there is none).
///
/// Each level is [`SolidMatrixFree`] on the fine chart, material and elements, with the
/// boundary's pinned nodes injected (they must lie on the level's node lines) and the
/// Dirichlet dofs of the fine grid at its nodes; its prolongation interpolates its field at
/// the finer level's nodes ([`p_to_p_interpolation`] in each direction, constraints as the
/// box hierarchy's).
///
/// # Errors
/// [`ElasticityError::InconsistentBoundary`] for a pinned node off a level's lines or
/// Dirichlet dofs that differ from the finer level's at its nodes; the operator's errors.
#[allow(clippy::type_complexity)]
pub(crate) fn p_levels<G: ShellGeometry + Clone + Send + Sync + 'static>(
    fine: &SolidMatrixFree<G>,
    boundary: &SolidBoundary,
) -> Result<(Vec<PLevel>, Option<([usize; 3], Vec<bool>, HexElement)>), ElasticityError> {
    let grid = fine.grid();
    let periodic = grid.is_periodic();
    let per = [false, periodic, false];
    let mut counts = grid.counts();
    let mut element = fine.element();
    let mut constrained = fine.constrained().to_vec();
    let mut levels: Vec<PLevel> = Vec::new();
    let mut pinned = boundary.clone();
    for q in p_level_degrees(element.degree()) {
        let coarse = HexElement::Gll(q);
        let nodes = element.reference_nodes();
        let p = element.degree();
        let w: [Vec<Vec<(usize, f64)>>; 3] =
            core::array::from_fn(|d| p_to_p_interpolation(counts[d], p, &nodes, coarse, per[d]));
        let (prolongation, coarse_counts, coarse_mask) =
            tensor_prolongation(counts, &w, &constrained);
        inject_pinned(
            &mut pinned,
            &w,
            "a pinned node is off the lines of a p-level of the multigrid",
        )?;
        let level_grid = grid.with_counts(coarse_counts)?;
        let operator = SolidMatrixFree::new(
            fine.setup.chart.clone(),
            fine.material(),
            level_grid,
            &pinned,
            None,
            coarse,
            VolumetricIntegration::Full,
        )?;
        if operator.constrained() != coarse_mask.as_slice() {
            return Err(ElasticityError::InconsistentBoundary {
                what: "a p-level's Dirichlet dofs differ from the finer level's at its nodes",
            });
        }
        let bytes = operator.bytes();
        levels.push(PLevel {
            degree: q,
            operator: Arc::new(operator),
            prolongation,
            bytes,
        });
        counts = coarse_counts;
        constrained = coarse_mask;
        element = coarse;
    }
    let last = (!levels.is_empty()).then_some((counts, constrained, element));
    Ok((levels, last))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn p_level_degrees_halve_down_to_two() {
        assert_eq!(p_level_degrees(1), Vec::<usize>::new());
        assert_eq!(p_level_degrees(3), Vec::<usize>::new());
        assert_eq!(p_level_degrees(4), vec![2]);
        assert_eq!(p_level_degrees(5), vec![2]);
        assert_eq!(p_level_degrees(8), vec![4, 2]);
    }

    #[test]
    fn p_to_p_interpolation_reproduces_quadratics_at_the_fine_nodes() {
        // a quadratic of x is of degree 2 in every element: interpolated exactly at the GLL(4)
        // nodes (x = e + (xi + 1) / 2 in element e; the coarse GLL(2) lines at x = c / 2)
        let fine = HexElement::Gll(4);
        let nodes = fine.reference_nodes();
        let f = |x: f64| 1.3 * x * x - 0.7 * x + 0.3;
        let elements = 3;
        for periodic in [false, true] {
            let n = if periodic {
                4 * elements
            } else {
                4 * elements + 1
            };
            let w = p_to_p_interpolation(n, 4, &nodes, HexElement::Gll(2), periodic);
            let lines = if periodic {
                2 * elements
            } else {
                2 * elements + 1
            };
            let coarse: Vec<f64> = (0..lines).map(|c| f(0.5 * c as f64)).collect();
            // periodic: the last element's field wraps to line 0 (not this quadratic)
            let checked = if periodic { n - 4 } else { n };
            for (i, pairs) in w.iter().enumerate().take(checked) {
                let e = (i / 4).min(elements - 1);
                let x = e as f64 + 0.5 * (nodes[i - 4 * e] + 1.0);
                let value: f64 = pairs.iter().map(|&(c, wt)| wt * coarse[c]).sum();
                // round-off of the basis products only
                assert!(
                    (value - f(x)).abs() < 1e-13,
                    "line {i}: {value} against {}",
                    f(x)
                );
                if i % 2 == 0 {
                    // lines at coarse nodes are injections (exact weight 1)
                    assert_eq!(pairs, &vec![(i / 2 % lines, 1.0)], "line {i}");
                }
            }
            assert_eq!(
                w[n - 1].iter().map(|p| p.0).max(),
                Some(if periodic { 5 } else { 6 })
            );
        }
    }
}
