//! A plane-strain discretisation whose nodes are not the tensor product of a grid (an
//! unstructured quadrilateral mesh, e.g. the corner-refined Qp mesh): what the contact
//! solvers and the outputs need of it, without the grid numbering of [`Discretisation`].
//!
//! [`Discretisation`]: crate::Discretisation

use crate::discretisation::{ContactNode, LinearSystem};
use crate::error::ElasticityError;

/// The plane-strain Navier operator on the nodes of a mesh: `2` unknowns per node
/// (`dof = 2 m + c`, `c = 0` for `v^2`, `1` for `v^3`), the assembled system, the contact
/// face `x3 = 0` as [`ContactNode`] entries in increasing `x2`, and the mesh for the outputs.
///
/// # Math
/// As [`crate::Discretisation`]: `A v = b` with zero tangential traction on `x3 = 0`; a
/// friction law adds `- w_k t_k(v)` to the tangential row of contact node `k`
/// (`w_k` = [`ContactNode::traction_weight`]).
pub trait MeshDiscretisation {
    /// Short name of the method (`"fem-qp-corner"`).
    fn method(&self) -> &'static str;

    /// Number of nodes.
    fn node_count(&self) -> usize;

    /// Number of unknowns, `2` per node (prescribed ones included).
    fn dof_count(&self) -> usize {
        2 * self.node_count()
    }

    /// `[x2, x3]` of node `m`.
    ///
    /// # Panics
    /// For `m` outside the nodes.
    fn node_position(&self, m: usize) -> [f64; 2];

    /// The assembled system `A v = b` on every node.
    ///
    /// # Errors
    /// Assembly failures.
    fn system(&self) -> Result<LinearSystem, ElasticityError>;

    /// The nodes of the contact face `x3 = 0` in increasing `x2` (entry `k` has
    /// `node = [k, 0]`, `site = k`).
    ///
    /// # Errors
    /// Geometry failures.
    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError>;

    /// The mesh as bilinear quadrilaterals on the nodes for a plot (`[m00, m10, m11, m01]`,
    /// counter-clockwise): a Qp element of order `p` as its `p x p` sub-quadrilaterals
    /// between GLL nodes.
    fn output_cells(&self) -> Vec<[usize; 4]>;
}

/// A mesh discretisation of any registered method, boxed (what
/// [`crate::registration::DiscretisationScheme::build_mesh`] builds).
pub type MeshOperator = Box<dyn MeshDiscretisation + Send + Sync>;

impl core::fmt::Debug for dyn MeshDiscretisation + Send + Sync {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MeshDiscretisation")
            .field("method", &self.method())
            .field("nodes", &self.node_count())
            .finish_non_exhaustive()
    }
}
