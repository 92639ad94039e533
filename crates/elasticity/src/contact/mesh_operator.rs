//! A mesh discretisation ([`MeshDiscretisation`], e.g. `fem-qp-corner`) as a contact
//! operator: its assembled system and contact nodes, extremes over its nodes.

use capstan_solvers::NearNullSpace;

use crate::contact::operator::{ContactOperator, Extremum, extremum};
use crate::discretisation::{ContactNode, LinearSystem};
use crate::error::ElasticityError;
use crate::mesh_discretisation::{MeshDiscretisation, MeshOperator};

/// A [`MeshOperator`] the contact solvers work on (what [`crate::contact::Body::operator`]
/// builds for a method with [`crate::registration::DiscretisationScheme::is_mesh`]).
#[derive(Debug)]
pub struct MeshContactOperator(pub MeshOperator);

impl ContactOperator for MeshContactOperator {
    fn method(&self) -> &'static str {
        self.0.method()
    }

    fn dof_count(&self) -> usize {
        self.0.dof_count()
    }

    /// Block size 2 (`dof = 2 m + c`), no vectors (as the grid discretisations).
    fn near_null_space(&self) -> Option<NearNullSpace> {
        Some(NearNullSpace {
            block_size: 2,
            vectors: Vec::new(),
        })
    }

    fn contact_system(&self) -> Result<LinearSystem, ElasticityError> {
        self.0.system()
    }

    fn contact_entries(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        self.0.contact_nodes()
    }

    fn extremes(&self, v: &[f64]) -> [Extremum; 2] {
        [0, 1].map(|c| {
            extremum(
                self.0.node_count(),
                |m| v[2 * m + c],
                |m| {
                    let [x2, x3] = self.0.node_position(m);
                    (None, x2, x3)
                },
            )
        })
    }

    fn mesh(&self) -> Option<&dyn MeshDiscretisation> {
        Some(&*self.0)
    }
}
