//! `fem-q1`, `fem-q2` in the registry: orders 1 and 2 of the Qp family with their data
//! (order, volumetric integration) and the nodal-difference recovery.

use std::sync::Arc;

use crate::error::ElasticityError;
use crate::finite_element::{ElementOrder, HighOrderNavier, VolumetricIntegration};
use crate::plane_problem::PlaneProblem;
use crate::registration::{
    DiscretisationScheme, DiscretisationSettings, PlaneOperator, RegisteredDiscretisation,
    SchemeParameter, nearest_element_nodes,
};
use crate::shell_geometry::SharedChart;
use crate::solid::HexElement;

/// `fem-q1`, `fem-q2`: [`HighOrderNavier`] of order 1 or 2 on the grid's uniform elements,
/// the volumetric part integrated as `volumetric` says, contact rows and fields by nodal
/// differences ([`HighOrderNavier::with_element`], [`crate::finite_element::NodalRecovery`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FemQk {
    /// Q1 or Q2.
    pub order: ElementOrder,
    /// `discretisation.volumetric`.
    pub volumetric: VolumetricIntegration,
}

impl FemQk {
    fn from_settings(
        order: ElementOrder,
        s: &DiscretisationSettings,
    ) -> Result<Arc<dyn DiscretisationScheme>, ElasticityError> {
        if !s.grading.is_uniform() {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.grading",
                value: s.grading.ratio(),
                allowed: "1 (uniform) unless discretisation.method = fem-qp",
            });
        }
        Ok(Arc::new(Self {
            order,
            volumetric: s.volumetric,
        }))
    }
}

impl DiscretisationScheme for FemQk {
    fn name(&self) -> &'static str {
        match self.order {
            ElementOrder::Q1 => "fem-q1",
            ElementOrder::Q2 => "fem-q2",
        }
    }

    fn build(&self, problem: PlaneProblem<SharedChart>) -> Result<PlaneOperator, ElasticityError> {
        Ok(Box::new(HighOrderNavier::with_element(
            problem,
            self.order,
            self.volumetric,
        )?))
    }

    fn is_symmetric(&self) -> bool {
        true
    }

    fn check_nodes(&self, field: &'static str, n: usize) -> Result<(), ElasticityError> {
        self.order.check_nodes(field, n, false)
    }

    fn admissible_nodes(&self, n: usize) -> usize {
        nearest_element_nodes(n, self.order.degree()).max(3)
    }

    /// Every other node, kept odd for Q2 (whole elements); at least 5 nodes (9 for Q2).
    fn coarser_nodes(&self, n: usize) -> Option<usize> {
        let q2 = self.order == ElementOrder::Q2;
        let c = n.div_ceil(2);
        let c = if q2 && c.is_multiple_of(2) { c + 1 } else { c };
        (c >= if q2 { 9 } else { 5 } && c < n).then_some(c)
    }

    fn memory_width(&self) -> f64 {
        self.order.degree() as f64
    }

    fn solid_element(&self) -> Result<HexElement, ElasticityError> {
        Ok(HexElement::Uniform(self.order))
    }
}

const VOLUMETRIC: SchemeParameter = SchemeParameter {
    key: "volumetric",
    default: "full",
    allowed: "full, reduced",
};

/// `fem-q1` in the registry.
pub(crate) const Q1_REGISTRATION: RegisteredDiscretisation = RegisteredDiscretisation {
    name: "fem-q1",
    summary: "bilinear (Q1) finite elements on the grid's nodes",
    parameters: &[VOLUMETRIC],
    build: |s| FemQk::from_settings(ElementOrder::Q1, s),
};

/// `fem-q2` in the registry.
pub(crate) const Q2_REGISTRATION: RegisteredDiscretisation = RegisteredDiscretisation {
    name: "fem-q2",
    summary: "biquadratic (Q2) finite elements on the grid's nodes (odd n2, n3)",
    parameters: &[VOLUMETRIC],
    build: |s| FemQk::from_settings(ElementOrder::Q2, s),
};
