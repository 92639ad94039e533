//! The skeleton of the element partition: the nodes on element edges, which carry the
//! unknowns of the statically condensed system, with their numbering and pattern.

use crate::error::ElasticityError;
use crate::finite_element::ElementAssembly;

/// The skeleton numbering and the pattern of the condensed system.
///
/// # Math
/// A grid node `(i2, i3)` is on the skeleton iff `i2 = 0 mod p` or `i3 = 0 mod p` (on an
/// element edge); skeleton node `s` has the dofs `2 s + c`. Each element contributes the
/// `4p` nodes of its edges, local boundary node `r` being the `r`-th local node
/// `a = a2 (p + 1) + a3` with `a2 in {0, p}` or `a3 in {0, p}`, in increasing `a`.
#[derive(Debug, Clone)]
pub struct Skeleton {
    /// Pattern and scatter of the condensed element matrices.
    pub assembly: ElementAssembly,
    /// Grid node of each skeleton node.
    pub nodes: Vec<usize>,
    /// Local nodes on the element's edges.
    pub boundary_local: Vec<usize>,
    /// Local nodes inside the element.
    pub interior_local: Vec<usize>,
    /// Prescribed value of each skeleton dof.
    pub dirichlet: Vec<Option<f64>>,
}

impl Skeleton {
    /// The skeleton of `elements` elements of order `p` on an `n2 x n3` grid (`x3`
    /// fastest), `element_nodes(e)` the grid nodes of element `e`, `dirichlet` the
    /// prescribed value of every grid dof.
    ///
    /// # Errors
    /// [`ElasticityError::InconsistentBoundary`] if an element-interior dof is prescribed
    /// (static condensation needs the prescribed dofs on element edges); assembly errors.
    pub fn new(
        p: usize,
        [n2, n3]: [usize; 2],
        elements: usize,
        element_nodes: impl Fn(usize) -> Vec<usize>,
        dirichlet: &[Option<f64>],
    ) -> Result<Self, ElasticityError> {
        let np = p + 1;
        let on_edge = |a2: usize, a3: usize| a2 == 0 || a2 == p || a3 == 0 || a3 == p;
        let (mut boundary_local, mut interior_local) = (vec![], vec![]);
        for a2 in 0..np {
            for a3 in 0..np {
                if on_edge(a2, a3) {
                    boundary_local.push(a2 * np + a3);
                } else {
                    interior_local.push(a2 * np + a3);
                }
            }
        }
        let mut index = vec![usize::MAX; n2 * n3];
        let mut nodes = vec![];
        for i2 in 0..n2 {
            for i3 in 0..n3 {
                if i2 % p == 0 || i3 % p == 0 {
                    index[i2 * n3 + i3] = nodes.len();
                    nodes.push(i2 * n3 + i3);
                }
            }
        }
        let mut connectivity = Vec::with_capacity(elements * boundary_local.len());
        for e in 0..elements {
            let en = element_nodes(e);
            for &a in &interior_local {
                if dirichlet[2 * en[a]].is_some() || dirichlet[2 * en[a] + 1].is_some() {
                    return Err(ElasticityError::InconsistentBoundary {
                        what: "a prescribed dof inside an element (static condensation needs them on element edges)",
                    });
                }
            }
            connectivity.extend(boundary_local.iter().map(|&a| index[en[a]]));
        }
        let dirichlet: Vec<Option<f64>> = nodes
            .iter()
            .flat_map(|&m| [dirichlet[2 * m], dirichlet[2 * m + 1]])
            .collect();
        let assembly = ElementAssembly::new(
            nodes.len(),
            2,
            boundary_local.len(),
            connectivity,
            &dirichlet,
        )?;
        Ok(Self {
            assembly,
            nodes,
            boundary_local,
            interior_local,
            dirichlet,
        })
    }
}
