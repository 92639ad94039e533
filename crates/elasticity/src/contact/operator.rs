//! What the contact model needs of a discretised body: the assembled bulk operator, the
//! contact rows and the largest displacements. Every plane-strain [`Discretisation`] provides
//! it; a 3-D body ([`crate::solid::SolidNavier`]) implements it directly.

use std::sync::Arc;

use capstan_solvers::row_distribution::RowDistribution;
use capstan_solvers::{
    ColumnOrdering, CsrMatrix, LinearOperator, NearNullSpace, OperatorMultigrid,
};

use crate::boundary::Component;
use crate::discretisation::{ContactNode, Discretisation, LinearSystem};
use crate::error::ElasticityError;

/// A signed extreme value and where it occurs.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Extremum {
    /// The value of largest magnitude (signed).
    pub value: f64,
    /// `x1` of the node (a 3-D body only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x1: Option<f64>,
    /// `x2` of the node.
    pub x2: f64,
    /// `x3` of the node.
    pub x3: f64,
}

/// A discretised body the frictional contact solvers work on (2-D or 3-D).
///
/// # Math
/// The assembled system `A v = b` with zero tangential traction on the contact face, and the
/// contact entries ([`ContactNode`]: one per tangential balance row, grouped in sites) through
/// which a friction law adds `- w_k t_k(v)` to the rows.
pub trait ContactOperator {
    /// Short name of the method (`"fd"`, `"fem-q2"`, `"solid-q1"`).
    fn method(&self) -> &'static str;

    /// Number of unknowns.
    fn dof_count(&self) -> usize;

    /// The fill-reducing ordering for a sparse LU of the operator and of the contact
    /// Jacobians on its pattern (default: the backend's own).
    fn lu_ordering(&self) -> ColumnOrdering {
        ColumnOrdering::Auto
    }

    /// The prolongations `P_0, P_1, ...` of a geometric multigrid hierarchy on the unknowns
    /// (finest first, `P_l` from level `l + 1` to level `l`), coarsening to at most
    /// `coarsest_unknowns`; `None` (the default) for a discretisation without one, which then
    /// needs a direct linear backend.
    fn multigrid_prolongations(&self, coarsest_unknowns: usize) -> Option<Arc<[CsrMatrix]>> {
        let _ = coarsest_unknowns;
        None
    }

    /// The rigid motions of the body in its unknowns and the unknowns per node, for an
    /// algebraic multigrid (PETSc's GAMG: `MatSetNearNullSpace`, `MatSetBlockSize`); `None`
    /// (the default) when the discretisation does not give them.
    fn near_null_space(&self) -> Option<NearNullSpace> {
        None
    }

    /// The process's share of a distributed solve when [`ContactOperator::contact_system`]
    /// holds only its rows ([`RowDistribution::owned`] for `block` unknowns a node; the
    /// right-hand side whole): `(distribution, block)`. `None` (the default): the whole
    /// system.
    fn row_distribution(&self) -> Option<(Arc<dyn RowDistribution>, usize)> {
        None
    }

    /// The assembled system `A v = b`.
    ///
    /// # Errors
    /// Assembly failures.
    fn contact_system(&self) -> Result<LinearSystem, ElasticityError>;

    /// The contact entries, sites in increasing `(x1, x2)`.
    ///
    /// # Errors
    /// Geometry failures.
    fn contact_entries(&self) -> Result<Vec<ContactNode>, ElasticityError>;

    /// The largest `|v^2|` and `|v^3|` over the body, where they are.
    ///
    /// # Panics
    /// If `v` has the wrong length.
    fn extremes(&self, v: &[f64]) -> [Extremum; 2];

    /// The plane-strain discretisation behind the operator (its grid, nodal fields and
    /// numbering, for outputs), `None` (the default) for a 3-D body.
    fn plane(&self) -> Option<&dyn Discretisation> {
        None
    }

    /// The 3-D body behind the operator (its box grid and nodal fields, for outputs), `None`
    /// (the default) for a plane-strain operator.
    fn solid(&self) -> Option<&dyn crate::solid::SolidOutput> {
        None
    }

    /// The plane-strain mesh discretisation behind the operator (its nodes and cells, for
    /// outputs), `None` (the default) for an operator on a grid.
    fn mesh(&self) -> Option<&dyn crate::mesh_discretisation::MeshDiscretisation> {
        None
    }

    /// The bulk operator known by its action when the discretisation is matrix-free: then
    /// [`ContactOperator::contact_system`] has an empty pattern (only its right-hand side
    /// counts) and the model adds `A v` to its residual. `None` (the default): `A` is the
    /// assembled matrix of `contact_system`.
    fn matrix_free(&self) -> Option<Arc<dyn MatrixFreeBulk + Send + Sync>> {
        None
    }
}

/// A bulk operator `A` that is never assembled, with the preconditioner of the contact
/// problem's Newton steps ([`crate::contact::MatrixFreeNewton`]).
///
/// # Math
/// A Newton step solves `(A + F) d = -R` with `F` the friction Jacobian of the contact face (a
/// sparse matrix with entries only in the tangential rows of contact nodes):
/// ```text
/// step_operator(F):    x -> A x + F x,  diagonal diag(A) + diag(F)
/// preconditioner(F):   a V-cycle whose fine level is step_operator(F) and whose assembled
///                      coarse level is A_c + P^T F P
/// ```
pub trait MatrixFreeBulk: Sync {
    /// `A`.
    fn bulk(&self) -> &dyn LinearOperator;
    /// `A + F`, owned (the fine level of the preconditioner and the Krylov operator).
    fn step_operator(&self, face: CsrMatrix) -> Arc<dyn LinearOperator + Send>;
    /// The V-cycle for `step = step_operator(face)`, with the smoothers' eigenvalue
    /// estimates given (`Some`: e.g. the previous Newton step's,
    /// [`OperatorMultigrid::estimates`]) or by power iteration (`None`).
    ///
    /// # Errors
    /// A singular diagonal or coarsest operator.
    fn preconditioner(
        &self,
        step: Arc<dyn LinearOperator + Send>,
        face: &CsrMatrix,
        estimates: Option<&[f64]>,
    ) -> Result<OperatorMultigrid, ElasticityError>;
    /// Bytes held (operator data, transfers, the assembled coarse level).
    fn bytes(&self) -> usize;
    /// `P`, the prolongation from the V-cycle's first coarse level (the Q1 grid below, in its
    /// own dof numbering) to this operator's dofs: also the interpolation of a coarser
    /// body's solution in grid sequencing.
    fn prolongation(&self) -> &CsrMatrix;
}

/// A contact operator of either dimension, as [`crate::contact::Body::operator`] builds it.
pub type BodyOperator = Box<dyn ContactOperator + Send + Sync>;

impl core::fmt::Debug for dyn ContactOperator + Send + Sync {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ContactOperator")
            .field("method", &self.method())
            .field("dofs", &self.dof_count())
            .finish_non_exhaustive()
    }
}

impl ContactOperator for BodyOperator {
    fn method(&self) -> &'static str {
        (**self).method()
    }

    fn dof_count(&self) -> usize {
        (**self).dof_count()
    }

    fn lu_ordering(&self) -> ColumnOrdering {
        (**self).lu_ordering()
    }

    fn multigrid_prolongations(&self, coarsest_unknowns: usize) -> Option<Arc<[CsrMatrix]>> {
        (**self).multigrid_prolongations(coarsest_unknowns)
    }

    fn near_null_space(&self) -> Option<NearNullSpace> {
        (**self).near_null_space()
    }

    fn row_distribution(&self) -> Option<(Arc<dyn RowDistribution>, usize)> {
        (**self).row_distribution()
    }

    fn contact_system(&self) -> Result<LinearSystem, ElasticityError> {
        (**self).contact_system()
    }

    fn contact_entries(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        (**self).contact_entries()
    }

    fn extremes(&self, v: &[f64]) -> [Extremum; 2] {
        (**self).extremes(v)
    }

    fn plane(&self) -> Option<&dyn Discretisation> {
        (**self).plane()
    }

    fn solid(&self) -> Option<&dyn crate::solid::SolidOutput> {
        (**self).solid()
    }

    fn mesh(&self) -> Option<&dyn crate::mesh_discretisation::MeshDiscretisation> {
        (**self).mesh()
    }

    fn matrix_free(&self) -> Option<Arc<dyn MatrixFreeBulk + Send + Sync>> {
        (**self).matrix_free()
    }
}

/// The signed value of largest magnitude of `value(node)` over the nodes, with the node's
/// coordinates `at(node)` (`[x1, x2, x3]`, `x1 = None` in plane strain).
pub(crate) fn extremum(
    nodes: usize,
    value: impl Fn(usize) -> f64,
    at: impl Fn(usize) -> (Option<f64>, f64, f64),
) -> Extremum {
    let (x1, x2, x3) = at(0);
    let mut best = Extremum {
        value: 0.0,
        x1,
        x2,
        x3,
    };
    let mut best_node = None;
    for k in 0..nodes {
        let x = value(k);
        if x.abs() > best.value.abs() {
            best.value = x;
            best_node = Some(k);
        }
    }
    if let Some(k) = best_node {
        (best.x1, best.x2, best.x3) = at(k);
    }
    best
}

impl<D: Discretisation> ContactOperator for D {
    fn method(&self) -> &'static str {
        Discretisation::method(self)
    }

    fn dof_count(&self) -> usize {
        Discretisation::dof_count(self)
    }

    fn lu_ordering(&self) -> ColumnOrdering {
        Discretisation::lu_ordering(self)
    }

    /// The block size 2 of the numbering `2 node + c` and no vectors: the plane
    /// discretisations do not carry their chart, so an algebraic multigrid falls back to its
    /// own near-null space for blocks of 2 (PETSc's GAMG: one constant per component).
    fn near_null_space(&self) -> Option<NearNullSpace> {
        Some(NearNullSpace {
            block_size: 2,
            vectors: Vec::new(),
        })
    }

    fn contact_system(&self) -> Result<LinearSystem, ElasticityError> {
        self.system()
    }

    fn contact_entries(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        self.contact_nodes()
    }

    fn plane(&self) -> Option<&dyn Discretisation> {
        Some(self)
    }

    fn extremes(&self, v: &[f64]) -> [Extremum; 2] {
        let grid = self.grid();
        let n3 = grid.n3();
        [Component::X2, Component::X3].map(|c| {
            extremum(
                grid.n2() * n3,
                |k| v[self.dof([k / n3, k % n3], c)],
                |k| {
                    let [x2, x3] = self.node_position([k / n3, k % n3]);
                    (None, x2, x3)
                },
            )
        })
    }
}
