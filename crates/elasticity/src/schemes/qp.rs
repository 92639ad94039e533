//! `fem-qp` in the registry: the Qp variant with its data (order, volumetric integration,
//! grading).

use std::sync::Arc;

use crate::error::ElasticityError;
use crate::finite_element::high_order::{Grading, HighOrderNavier, QpSettings, check_order};
use crate::plane_problem::PlaneProblem;
use crate::registration::{
    DiscretisationScheme, PlaneOperator, RegisteredDiscretisation, SchemeParameter,
    check_element_nodes, nearest_element_nodes,
};
use crate::shell_geometry::SharedChart;
use crate::solid::HexElement;

/// `fem-qp`: [`HighOrderNavier`] with its settings (order `p`, volumetric integration,
/// grading).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FemQp {
    /// The settings, order checked.
    pub settings: QpSettings,
}

impl DiscretisationScheme for FemQp {
    fn name(&self) -> &'static str {
        "fem-qp"
    }

    fn build(&self, problem: PlaneProblem<SharedChart>) -> Result<PlaneOperator, ElasticityError> {
        Ok(Box::new(HighOrderNavier::with_settings(
            problem,
            self.settings,
        )?))
    }

    fn is_symmetric(&self) -> bool {
        true
    }

    /// `n = p e + 1` (`e >= 1` elements of order `p`).
    fn check_nodes(&self, field: &'static str, n: usize) -> Result<(), ElasticityError> {
        check_element_nodes(
            field,
            n,
            self.settings.order,
            1,
            "p e + 1 nodes (e elements of order p = discretisation.order) with fem-qp",
        )
    }

    fn admissible_nodes(&self, n: usize) -> usize {
        nearest_element_nodes(n, self.settings.order)
    }

    /// Half the elements (`n = p e + 1 -> p e / 2 + 1`, `e` even, at least 2 elements left);
    /// none for a graded mesh: halving the elements of a geometric mesh keeps the layers but
    /// moves every middle boundary, and the level-to-level transfer
    /// ([`crate::interpolate_nodal`]) interpolates on the uniform grid lines, not the graded
    /// node positions.
    fn coarser_nodes(&self, n: usize) -> Option<usize> {
        if !self.settings.grading.is_uniform() {
            return None;
        }
        let p = self.settings.order.max(1);
        let e = (n - 1) / p;
        (e.is_multiple_of(2) && e >= 4 && (n - 1).is_multiple_of(p)).then_some(p * e / 2 + 1)
    }

    /// Wider element couplings; the fill of the element nested dissection grows ~ `p`.
    fn memory_width(&self) -> f64 {
        4.0
    }

    fn solid_element(&self) -> Result<HexElement, ElasticityError> {
        HexElement::gll(self.settings.order)
    }
}

/// `discretisation.order` of the Qp family: `1..=10`, default 4 (shared by `fem-qp-corner`).
pub(crate) const ORDER_PARAMETER: SchemeParameter = SchemeParameter {
    key: "order",
    default: "4",
    allowed: "1..=10",
};

/// `fem-qp` in the registry.
pub(crate) const REGISTRATION: RegisteredDiscretisation = RegisteredDiscretisation {
    name: "fem-qp",
    summary: "tensor-product elements of order p with GLL nodes, statically condensed (n = p e + 1)",
    parameters: &[
        ORDER_PARAMETER,
        SchemeParameter {
            key: "volumetric",
            default: "full",
            allowed: "full, reduced",
        },
        SchemeParameter {
            key: "grading",
            default: "1 (uniform)",
            allowed: Grading::ALLOWED,
        },
        SchemeParameter {
            key: "layers",
            default: "none",
            allowed: "1..=12 (with a grading)",
        },
    ],
    build: |s| {
        check_order(s.order)?;
        Ok(Arc::new(FemQp {
            settings: QpSettings {
                volumetric: s.volumetric,
                grading: s.grading,
                ..QpSettings::order(s.order)
            },
        }))
    },
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::registration::DiscretisationSettings;

    #[test]
    fn qp_nodes_coarsening_and_defaults_follow_the_order() {
        let s = DiscretisationSettings::default(); // p = 4
        let qp = (REGISTRATION.build)(&s).unwrap();
        assert!(qp.check_nodes("grid.n2", 249).is_ok());
        assert!(qp.check_nodes("grid.n2", 250).is_err());
        assert_eq!(qp.admissible_nodes(250), 249);
        assert_eq!(qp.coarser_nodes(161), Some(81));
        assert_eq!(qp.coarser_nodes(25), Some(13)); // 6 elements -> 3
        assert_eq!(qp.coarser_nodes(21), None); // 5 elements: odd
        let bad = DiscretisationSettings { order: 11, ..s };
        assert!((REGISTRATION.build)(&bad).is_err());
        let graded = DiscretisationSettings {
            grading: Grading::geometric(0.15, 2).unwrap(),
            ..DiscretisationSettings::default()
        };
        assert_eq!(
            (REGISTRATION.build)(&graded).unwrap().coarser_nodes(161),
            None
        );
    }
}
