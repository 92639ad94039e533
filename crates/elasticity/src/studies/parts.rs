//! The parts of a reference problem that every plane-strain discretisation takes (a
//! [`PlaneProblem`] on the samples' chart), and the discretisations built from a problem.

use capstan_geometry::{Obstacle, ShellChart};

use crate::error::ElasticityError;
use crate::finite_difference::FiniteDifferenceNavier;
use crate::finite_element::{ElementOrder, HighOrderNavier, QpSettings, VolumetricIntegration};
use crate::plane_problem::PlaneProblem;
use crate::shell_geometry::ShellGeometry;

/// The chart of every sample problem: an obstacle from the geometry crate.
pub type SampleChart = ShellChart<Obstacle>;

/// Everything a discretisation constructor takes, for one reference problem on one grid: a
/// [`PlaneProblem`] on the samples' chart.
pub type ProblemParts = PlaneProblem<SampleChart>;

impl<G: ShellGeometry + Sync> PlaneProblem<G> {
    /// The finite-difference discretisation.
    ///
    /// # Errors
    /// See [`FiniteDifferenceNavier::new`].
    pub fn finite_difference(self) -> Result<FiniteDifferenceNavier<G>, ElasticityError> {
        FiniteDifferenceNavier::new(self)
    }

    /// The Q1 or Q2 elements of `order` with full integration (`fem-q1`, `fem-q2`: orders 1
    /// and 2 of [`HighOrderNavier`], [`HighOrderNavier::with_element`]).
    ///
    /// # Errors
    /// See [`HighOrderNavier::new`].
    pub fn finite_element(
        self,
        order: ElementOrder,
    ) -> Result<HighOrderNavier<G>, ElasticityError> {
        HighOrderNavier::with_element(self, order, VolumetricIntegration::Full)
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
    ) -> Result<HighOrderNavier<G>, ElasticityError> {
        HighOrderNavier::with_volumetric(self, p, volumetric)
    }

    /// The tensor-product elements with `settings` (order, volumetric integration, grading of
    /// the element boundaries: [`HighOrderNavier::with_settings`]).
    ///
    /// # Errors
    /// See [`HighOrderNavier::new`].
    pub fn high_order_with(
        self,
        settings: QpSettings,
    ) -> Result<HighOrderNavier<G>, ElasticityError> {
        HighOrderNavier::with_settings(self, settings)
    }
}
