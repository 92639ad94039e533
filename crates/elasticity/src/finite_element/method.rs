//! Choosing a discretisation by name (`discretisation.method` in scene files).

use super::element::ElementOrder;
use super::high_order::HighOrderNavier;
use super::navier::FiniteElementNavier;
use crate::discretisation::Discretisation;
use crate::error::ElasticityError;
use crate::finite_difference::FiniteDifferenceNavier;
use crate::plane_problem::PlaneProblem;
use crate::shell_geometry::ShellGeometry;

/// The discretisations of the Navier operator, by name: `fd`, `fem-q1`, `fem-q2`, `fem-qp`
/// (with its order `p`, scene key `discretisation.order`, given separately).
///
/// The same spelling is used by serde and [`core::fmt::Display`].
///
/// # Example
/// ```
/// use capstan_elasticity::{BoundaryConditions, Discretisation, Grid, Material, PlaneProblem};
/// use capstan_elasticity::finite_element::DiscretisationMethod;
/// use capstan_geometry::{EllipticalPrism, ShellChart};
/// let problem = PlaneProblem {
///     chart: ShellChart::new(EllipticalPrism::new(2.0, 2.0).unwrap()),
///     material: Material::new(1e3, 0.25).unwrap(),
///     grid: Grid::new([-1.5707963, 1.5707963], 1.0, 25, 5, false).unwrap(),
///     boundary: BoundaryConditions::paper_clamped(1.0, 2.0),
///     body_force: None,
/// };
/// for method in DiscretisationMethod::ALL {
///     assert_eq!(DiscretisationMethod::from_name(method.name()), Some(method));
///     let op = method.build(problem.clone()).unwrap();
///     assert_eq!(op.method(), method.name());
/// }
/// ```
#[derive(
    Debug, Clone, Copy, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum DiscretisationMethod {
    /// [`FiniteDifferenceNavier`]: second-order finite differences (finite volumes).
    #[default]
    Fd,
    /// [`FiniteElementNavier`] with bilinear (Q1) elements.
    FemQ1,
    /// [`FiniteElementNavier`] with biquadratic (Q2) elements (odd `n2`, `n3`).
    FemQ2,
    /// [`HighOrderNavier`]: tensor-product elements of order `p` with GLL nodes (`n - 1` a
    /// multiple of `p`), statically condensed.
    FemQp,
}

capstan_solvers::named_variants!(DiscretisationMethod {
    Fd => "fd",
    FemQ1 => "fem-q1",
    FemQ2 => "fem-q2",
    FemQp => "fem-qp",
});

impl DiscretisationMethod {
    /// The order of `fem-qp` when none is given (`discretisation.order`).
    pub const DEFAULT_ORDER: usize = 4;

    /// The element order of a Q1/Q2 finite-element method (`None` for `fd` and `fem-qp`).
    pub fn element_order(self) -> Option<ElementOrder> {
        match self {
            Self::Fd | Self::FemQp => None,
            Self::FemQ1 => Some(ElementOrder::Q1),
            Self::FemQ2 => Some(ElementOrder::Q2),
        }
    }

    /// Whether the assembled matrix is symmetric (and, with enough Dirichlet conditions,
    /// positive definite): the Cholesky backend applies.
    pub fn is_symmetric(self) -> bool {
        self != Self::Fd
    }

    /// Builds the discretisation (`fem-qp` of order [`Self::DEFAULT_ORDER`]).
    ///
    /// # Errors
    /// The constructor's errors ([`FiniteDifferenceNavier::new`], [`FiniteElementNavier::new`],
    /// [`HighOrderNavier::new`]).
    pub fn build<G: ShellGeometry + Send + Sync + 'static>(
        self,
        problem: PlaneProblem<G>,
    ) -> Result<Box<dyn Discretisation + Send + Sync>, ElasticityError> {
        self.build_with_order(problem, Self::DEFAULT_ORDER)
    }

    /// Builds the discretisation; `order` is the `p` of `fem-qp` (ignored by the others).
    ///
    /// # Errors
    /// See [`Self::build`].
    pub fn build_with_order<G: ShellGeometry + Send + Sync + 'static>(
        self,
        problem: PlaneProblem<G>,
        order: usize,
    ) -> Result<Box<dyn Discretisation + Send + Sync>, ElasticityError> {
        if self == Self::FemQp {
            return Ok(Box::new(HighOrderNavier::new(problem, order)?));
        }
        Ok(match self.element_order() {
            None => Box::new(FiniteDifferenceNavier::new(problem)?),
            Some(order) => Box::new(FiniteElementNavier::new(problem, order)?),
        })
    }
}
