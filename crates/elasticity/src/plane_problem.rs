//! The plane-strain problem every 2-D discretisation of the Navier operator is built from:
//! chart, material, grid, boundary conditions and body force.

use core::fmt;
use std::sync::Arc;

use capstan_geometry::ShellPoint;

use crate::boundary::{BoundaryConditions, Component};
use crate::continuum::check_plane_strain;
use crate::error::ElasticityError;
use crate::grid::Grid;
use crate::material::Material;
use crate::shell_geometry::{SharedChart, ShellGeometry};

/// A body force density: covariant components `[f_2, f_3]` at `(x2, x3)`.
pub type BodyForce = Arc<dyn Fn([f64; 2]) -> [f64; 2] + Send + Sync>;

/// The load of the body force `f` at one quadrature point `x` of weight `w`:
/// `[f_2(x) sqrt(g) w, f_3(x) sqrt(g) w]`, zero without a body force.
///
/// # Errors
/// [`ElasticityError::NonFinite`] where `f(x)` is not finite.
pub(crate) fn body_force_load(
    f: Option<&BodyForce>,
    x: [f64; 2],
    sqrt_g: f64,
    w: f64,
) -> Result<[f64; 2], ElasticityError> {
    let Some(f) = f else {
        return Ok([0.0; 2]);
    };
    let fx = f(x);
    if !(fx[0].is_finite() && fx[1].is_finite()) {
        return Err(ElasticityError::NonFinite {
            what: "body force",
            at: x,
        });
    }
    Ok([fx[0] * sqrt_g * w, fx[1] * sqrt_g * w])
}

/// A plane-strain elasticity problem on the parameter rectangle of a shell chart `G`: what
/// [`crate::FiniteDifferenceNavier`] and [`crate::finite_element::HighOrderNavier`] (Q1, Q2
/// and Qp) are built from.
///
/// # Math
/// ```text
/// nabla_i T^i_j + f_j = 0   on   [theta0, theta1] x [0, h]       (j = 2, 3; d_1 = 0, v^1 = 0)
/// T^ij = A^ijkl E_kl,   A^ijkl = lambda g^ij g^kl + mu (g^ik g^jl + g^il g^jk)
/// ```
/// with the metric of `chart` (a prism: `x1`-invariant), the Lamé constants of `material`, the
/// rectangle and nodes of `grid`, the side conditions and pinned dofs of `boundary`, and the
/// covariant body force `f_j` of `body_force` (`None`: `f = 0`).
///
/// # Example
/// ```
/// use capstan_elasticity::finite_element::{ElementOrder, HighOrderNavier, VolumetricIntegration};
/// use capstan_elasticity::{BoundaryConditions, Discretisation, FiniteDifferenceNavier, Grid};
/// use capstan_elasticity::{Material, PlaneProblem};
/// use capstan_geometry::{EllipticalPrism, ShellChart};
/// let problem = PlaneProblem {
///     chart: ShellChart::new(EllipticalPrism::new(2.0, 2.0).unwrap()),
///     material: Material::new(1e3, 0.25).unwrap(),
///     grid: Grid::new([-1.5707963, 1.5707963], 1.0, 25, 5, false).unwrap(),
///     boundary: BoundaryConditions::paper_clamped(1.0, 1.0),
///     body_force: None,
/// };
/// // one problem, three discretisations on the same nodes
/// let fd = FiniteDifferenceNavier::new(problem.clone()).unwrap();
/// let full = VolumetricIntegration::Full;
/// let q2 = HighOrderNavier::with_element(problem.clone(), ElementOrder::Q2, full).unwrap();
/// let qp = HighOrderNavier::new(problem, 4).unwrap();
/// assert_eq!(fd.dof_count(), 2 * 25 * 5);
/// assert!(fd.dof_count() == q2.dof_count() && q2.dof_count() == qp.dof_count());
/// ```
#[derive(Clone)]
pub struct PlaneProblem<G> {
    /// The shell chart of the body (`x1`-invariant).
    pub chart: G,
    /// The material.
    pub material: Material,
    /// The grid on the parameter rectangle.
    pub grid: Grid,
    /// The boundary conditions.
    pub boundary: BoundaryConditions,
    /// The body force, `None` for none.
    pub body_force: Option<BodyForce>,
}

impl<G> PlaneProblem<G> {
    /// The displacement prescribed at every unknown of the plane-strain numbering
    /// (`2 node_index + c`), `None` for a balance row, with node `(i2, i3)` at
    /// `position(node)` (the grid's uniform positions; the Gauss–Lobatto points of the
    /// high-order elements): [`BoundaryConditions::dirichlet_value_at`], pinned dofs first.
    ///
    /// # Errors
    /// [`ElasticityError::NonFinite`] where a prescribed function is not finite.
    pub(crate) fn dirichlet_values(
        &self,
        position: impl Fn([usize; 2]) -> [f64; 2],
    ) -> Result<Vec<Option<f64>>, ElasticityError> {
        (0..2 * self.grid.node_count())
            .map(|d| {
                let node = self.grid.node(d / 2);
                let c = Component::ALL[d % 2];
                self.boundary
                    .dirichlet_value_at(&self.grid, node, position(node), c)
            })
            .collect()
    }

    /// Writes `name { order, material, grid, boundary, .. }`: the `Debug` of the problem and of
    /// every operator built from it (`order`: the field naming the operator's element order,
    /// `None` for none). Chart and body force stay out (`..`): neither need be `Debug`.
    pub(crate) fn debug_fields(
        &self,
        f: &mut fmt::Formatter<'_>,
        name: &str,
        order: Option<(&str, &dyn fmt::Debug)>,
    ) -> fmt::Result {
        let mut s = f.debug_struct(name);
        if let Some((field, value)) = order {
            s.field(field, value);
        }
        s.field("material", &self.material)
            .field("grid", &self.grid)
            .field("boundary", &self.boundary)
            .finish_non_exhaustive()
    }
}

impl<G: ShellGeometry + Send + Sync + 'static> PlaneProblem<G> {
    /// The same problem over the chart shared as a [`SharedChart`] (what the registry's
    /// discretisations are built over).
    pub fn share_chart(self) -> PlaneProblem<SharedChart> {
        let chart: SharedChart = std::sync::Arc::new(self.chart);
        PlaneProblem {
            chart,
            material: self.material,
            grid: self.grid,
            boundary: self.boundary,
            body_force: self.body_force,
        }
    }
}

impl<G: ShellGeometry> PlaneProblem<G> {
    /// The chart's column of points above `(x1, x2) = (0, x2)` at `heights`
    /// ([`ShellGeometry::shell_column`], into `points`, cleared first), each checked for the
    /// plane-strain reduction and then handed to `visit(index, point, x3)`, in order.
    ///
    /// # Errors
    /// The chart's, then the first of [`ElasticityError::NotPlaneStrain`] and `visit`'s error
    /// in height order.
    pub(crate) fn visit_column(
        &self,
        x2: f64,
        heights: &[f64],
        points: &mut Vec<ShellPoint<f64>>,
        mut visit: impl FnMut(usize, &ShellPoint<f64>, f64) -> Result<(), ElasticityError>,
    ) -> Result<(), ElasticityError> {
        points.clear();
        self.chart.shell_column([0.0, x2], heights, points)?;
        for (index, (p, &x3)) in points.iter().zip(heights).enumerate() {
            check_plane_strain(p, [0.0, x2, x3])?;
            visit(index, p, x3)?;
        }
        Ok(())
    }
}

impl<G> fmt::Debug for PlaneProblem<G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.debug_fields(f, "PlaneProblem", None)
    }
}
