//! `fd` in the registry: the finite-difference operator with no data of its own.

use crate::error::ElasticityError;
use crate::finite_difference::FiniteDifferenceNavier;
use crate::plane_problem::PlaneProblem;
use crate::registration::{DiscretisationScheme, PlaneOperator, RegisteredDiscretisation};
use crate::shell_geometry::SharedChart;

/// `fd` in the registry: [`FiniteDifferenceNavier`] on the grid's nodes; no quadrature to
/// reduce and uniform grids only.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FiniteDifferences;

impl DiscretisationScheme for FiniteDifferences {
    fn name(&self) -> &'static str {
        "fd"
    }

    fn build(&self, problem: PlaneProblem<SharedChart>) -> Result<PlaneOperator, ElasticityError> {
        Ok(Box::new(FiniteDifferenceNavier::new(problem)?))
    }
}

/// `fd` in the registry.
pub(crate) const REGISTRATION: RegisteredDiscretisation = RegisteredDiscretisation {
    name: "fd",
    summary: "second-order finite differences (vertex-centred finite volumes), plane strain only",
    parameters: &[],
    build: |s| {
        s.require_full_uniform(
            "full with finite differences (reduced needs fem-q1 or fem-q2)",
            "1 (uniform) unless discretisation.method = fem-qp",
        )?;
        Ok(std::sync::Arc::new(FiniteDifferences))
    },
};
