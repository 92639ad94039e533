//! The plane-strain numbering shared by the finite-difference and finite-element operators.

/// `grid`, `dof_count` and `dof` of a [`Discretisation`](crate::Discretisation) with the
/// plane-strain numbering of its `self.grid` (two unknowns a node, `plane_strain_dof`).
macro_rules! plane_strain_numbering {
    () => {
        fn grid(&self) -> &$crate::grid::Grid {
            &self.grid
        }

        fn dof_count(&self) -> usize {
            2 * self.grid.node_count()
        }

        #[track_caller]
        fn dof(&self, node: [usize; 2], component: $crate::boundary::Component) -> usize {
            $crate::discretisation::plane_strain_dof(&self.grid, node, component)
        }
    };
}
pub(crate) use plane_strain_numbering;
