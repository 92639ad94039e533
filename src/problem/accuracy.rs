//! What an error estimate of a [`Problem`] needs: the problem one grid level coarser and the
//! converging quantities of a solution ([`ContactQuantities`]).

use std::collections::BTreeMap;

use capstan_elasticity::contact::{ContactQuantities, Dimension};
use capstan_geometry::Surface;

use super::builder::Problem;
use super::solve::{ProblemError, Solved, SolvedModel};

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// The problem one grid level coarser: `n2`, `n3` (and a 3-D body's `n1` where its method
    /// has a coarser level there) by the method's grid sequencing
    /// ([`capstan_elasticity::registration::DiscretisationScheme::coarser_nodes`]:
    /// `n -> (n + 1) / 2`, whole elements kept); `None` when the method has no coarser level
    /// (a graded `fem-qp` mesh, or a grid already at the coarsest level).
    ///
    /// # Errors
    /// The discretisation's settings errors ([`ProblemError::Elasticity`]).
    pub fn coarser(&self) -> Result<Option<Self>, ProblemError> {
        let scheme = self.body.scheme()?;
        let (Some(n2), Some(n3)) = (
            scheme.coarser_nodes(self.body.n2),
            scheme.coarser_nodes(self.body.n3),
        ) else {
            return Ok(None);
        };
        let mut coarse = self.clone();
        coarse.body.n2 = n2;
        coarse.body.n3 = n3;
        if let Dimension::Solid { n1, .. } = &mut coarse.body.dimension {
            *n1 = scheme.coarser_nodes(*n1).unwrap_or(*n1);
        }
        Ok(Some(coarse))
    }

    /// The grid as estimates report it: `[n2, n3]`, or `[n1, n2, n3]` for a 3-D body.
    pub fn grid(&self) -> Vec<usize> {
        match self.body.dimension {
            Dimension::Plane => vec![self.body.n2, self.body.n3],
            Dimension::Solid { n1, .. } => vec![n1, self.body.n2, self.body.n3],
        }
    }
}

impl SolvedModel {
    /// The converging quantities of `solution` (a solution of this model), with `sigma_n`
    /// at `probes` ([`ContactQuantities::new`]).
    ///
    /// # Errors
    /// A probe outside the contact face ([`ProblemError::Elasticity`]).
    pub fn quantities(
        &self,
        solution: &capstan_elasticity::contact::ContactSolution,
        probes: &[f64],
    ) -> Result<ContactQuantities, ProblemError> {
        Ok(match self {
            Self::Body(m) => ContactQuantities::new(m, solution, probes)?,
            Self::Sequenced(m) => ContactQuantities::new(m, solution, probes)?,
        })
    }
}

impl Solved {
    /// The converging quantities of the solution, with `sigma_n` at `probes`.
    ///
    /// # Errors
    /// See [`SolvedModel::quantities`].
    pub fn quantities(&self, probes: &[f64]) -> Result<ContactQuantities, ProblemError> {
        self.model.quantities(&self.solution, probes)
    }

    /// Every converging scalar by name ([`ContactQuantities::scalars`]).
    ///
    /// # Errors
    /// See [`SolvedModel::quantities`].
    pub fn scalars(&self, probes: &[f64]) -> Result<BTreeMap<String, f64>, ProblemError> {
        Ok(self.quantities(probes)?.scalars(&self.solution))
    }
}
