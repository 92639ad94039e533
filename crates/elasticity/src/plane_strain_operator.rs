//! What the finite-difference and finite-element plane-strain operators share word for word:
//! the accessors of their setup and the numbering of their unknowns.

/// `grid`, `dof_count` and `dof` of a [`Discretisation`](crate::Discretisation) with the
/// plane-strain numbering of its `self.problem.grid` (two unknowns a node, `plane_strain_dof`).
macro_rules! plane_strain_numbering {
    () => {
        fn grid(&self) -> &$crate::grid::Grid {
            &self.problem.grid
        }

        fn dof_count(&self) -> usize {
            2 * self.problem.grid.node_count()
        }

        #[track_caller]
        fn dof(&self, node: [usize; 2], component: $crate::boundary::Component) -> usize {
            $crate::discretisation::plane_strain_dof(&self.problem.grid, node, component)
        }
    };
}
pub(crate) use plane_strain_numbering;

/// `material`, `boundary` and `chart`: the accessors of the pieces of an operator's
/// `self.problem` (a [`PlaneProblem`](crate::PlaneProblem) of the chart type `G`).
macro_rules! setup_accessors {
    () => {
        /// The material.
        pub fn material(&self) -> &$crate::material::Material {
            &self.problem.material
        }

        /// The boundary conditions.
        pub fn boundary(&self) -> &$crate::boundary::BoundaryConditions {
            &self.problem.boundary
        }

        /// The chart.
        pub fn chart(&self) -> &G {
            &self.problem.chart
        }
    };
}
pub(crate) use setup_accessors;
