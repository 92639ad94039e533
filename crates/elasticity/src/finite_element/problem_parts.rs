//! The parts of a reference problem that every plane-strain discretisation takes: chart,
//! material, grid, boundary conditions and body force, and the discretisations built from them.

use capstan_geometry::{Obstacle, ShellChart};

use super::element::ElementOrder;
use super::high_order::HighOrderNavier;
use super::navier::FiniteElementNavier;
use super::volumetric::VolumetricIntegration;
use crate::boundary::BoundaryConditions;
use crate::error::ElasticityError;
use crate::finite_difference::{BodyForce, FiniteDifferenceNavier};
use crate::grid::Grid;
use crate::material::Material;

/// The chart of every sample problem: an obstacle from the geometry crate.
pub type SampleChart = ShellChart<Obstacle>;

/// Everything a discretisation constructor takes, for one reference problem on one grid.
#[derive(Clone)]
pub struct ProblemParts {
    /// The chart.
    pub chart: SampleChart,
    /// The material.
    pub material: Material,
    /// The grid.
    pub grid: Grid,
    /// The boundary conditions.
    pub boundary: BoundaryConditions,
    /// The body force.
    pub body_force: Option<BodyForce>,
}

impl core::fmt::Debug for ProblemParts {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ProblemParts")
            .field("grid", &self.grid)
            .field("boundary", &self.boundary)
            .finish_non_exhaustive()
    }
}

impl ProblemParts {
    /// The finite-difference discretisation.
    ///
    /// # Errors
    /// See [`FiniteDifferenceNavier::new`].
    pub fn finite_difference(self) -> Result<FiniteDifferenceNavier<SampleChart>, ElasticityError> {
        FiniteDifferenceNavier::new(
            self.chart,
            self.material,
            self.grid,
            self.boundary,
            self.body_force,
        )
    }

    /// The finite-element discretisation of `order`.
    ///
    /// # Errors
    /// See [`FiniteElementNavier::new`].
    pub fn finite_element(
        self,
        order: ElementOrder,
    ) -> Result<FiniteElementNavier<SampleChart>, ElasticityError> {
        self.finite_element_with(order, VolumetricIntegration::Full)
    }

    /// The finite-element discretisation of `order` with the volumetric part integrated as
    /// `volumetric` says.
    ///
    /// # Errors
    /// See [`FiniteElementNavier::new`].
    pub fn finite_element_with(
        self,
        order: ElementOrder,
        volumetric: VolumetricIntegration,
    ) -> Result<FiniteElementNavier<SampleChart>, ElasticityError> {
        FiniteElementNavier::with_volumetric(
            self.chart,
            self.material,
            self.grid,
            self.boundary,
            self.body_force,
            order,
            volumetric,
        )
    }

    /// The tensor-product elements of order `p` ([`HighOrderNavier`]; the grid's `n - 1`
    /// a multiple of `p`) with the volumetric part integrated as `volumetric` says.
    ///
    /// # Errors
    /// See [`HighOrderNavier::new`].
    pub fn high_order(
        self,
        p: usize,
        volumetric: VolumetricIntegration,
    ) -> Result<HighOrderNavier<SampleChart>, ElasticityError> {
        HighOrderNavier::with_volumetric(
            self.chart,
            self.material,
            self.grid,
            self.boundary,
            self.body_force,
            p,
            volumetric,
        )
    }

    /// The tensor-product elements with `settings` (order, volumetric integration, grading of
    /// the element boundaries: [`HighOrderNavier::with_settings`]).
    ///
    /// # Errors
    /// See [`HighOrderNavier::new`].
    pub fn high_order_with(
        self,
        settings: crate::finite_element::high_order::QpSettings,
    ) -> Result<HighOrderNavier<SampleChart>, ElasticityError> {
        HighOrderNavier::with_settings(
            self.chart,
            self.material,
            self.grid,
            self.boundary,
            self.body_force,
            settings,
        )
    }
}
