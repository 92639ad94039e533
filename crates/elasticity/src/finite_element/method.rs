//! Naming a discretisation (`discretisation.method` in scene files; the lookups by name are in
//! [`crate::registry`]), and the Q1/Q2 elements' registrations.

use std::sync::Arc;

use super::element::ElementOrder;
use super::navier::FiniteElementNavier;
use super::volumetric::VolumetricIntegration;
use crate::error::ElasticityError;
use crate::plane_problem::PlaneProblem;
use crate::registration::{
    DiscretisationScheme, DiscretisationSettings, PlaneOperator, RegisteredDiscretisation,
    SchemeParameter, nearest_element_nodes,
};
use crate::shell_geometry::SharedChart;
use crate::solid::HexElement;

/// A discretisation of the Navier operator, by its registered name: `fd`, `fem-q1`,
/// `fem-q2`, `fem-qp` (with its order `p`, scene key `discretisation.order`, given
/// separately), or any discretisation added with [`crate::registry::register`].
///
/// The same spelling is used by serde and [`core::fmt::Display`]; reading an unregistered
/// name fails, listing the registered ones. The variant with its data is built by
/// [`DiscretisationMethod::scheme`].
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct DiscretisationMethod(&'static str);

// The lookups (`from_name`, `scheme`, `build`, `FromStr`, serde) live in `crate::registry`,
// which imports this module: an inherent impl there keeps the imports one way.

#[allow(non_upper_case_globals)] // spelled as the variants they were, so call sites read the same
impl DiscretisationMethod {
    /// `fd`: [`crate::FiniteDifferenceNavier`], second-order finite differences (finite volumes).
    pub const Fd: Self = Self("fd");
    /// `fem-q1`: bilinear (Q1) elements.
    pub const FemQ1: Self = Self("fem-q1");
    /// `fem-q2`: biquadratic (Q2) elements (odd `n2`, `n3`).
    pub const FemQ2: Self = Self("fem-q2");
    /// `fem-qp`: [`super::HighOrderNavier`], tensor-product elements of order `p` with GLL
    /// nodes (`n - 1` a multiple of `p`), statically condensed.
    pub const FemQp: Self = Self("fem-qp");

    /// The built-in methods, in registry order.
    pub const ALL: [Self; 4] = [Self::Fd, Self::FemQ1, Self::FemQ2, Self::FemQp];

    /// The order of `fem-qp` when none is given (`discretisation.order`).
    pub const DEFAULT_ORDER: usize = 4;

    /// The name as used in files.
    pub fn name(self) -> &'static str {
        self.0
    }

    /// The method of a registered name (the registry's own `&'static` spelling).
    pub(crate) const fn registered(name: &'static str) -> Self {
        Self(name)
    }
}

impl Default for DiscretisationMethod {
    fn default() -> Self {
        Self::Fd
    }
}

impl core::fmt::Display for DiscretisationMethod {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.0)
    }
}

/// `fem-q1`, `fem-q2`: [`FiniteElementNavier`] of `order` with the volumetric part integrated
/// as `volumetric` says, on the grid's uniform nodes.
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
        Ok(Box::new(FiniteElementNavier::with_volumetric(
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_through_serde_and_unknown_names_list_the_registry() {
        use serde::Deserialize;
        use serde::de::value::{Error, StrDeserializer};
        let read =
            |name: &str| DiscretisationMethod::deserialize(StrDeserializer::<Error>::new(name));
        for m in DiscretisationMethod::ALL {
            assert_eq!(read(m.name()).unwrap(), m);
            assert_eq!(m.to_string(), m.name());
        }
        let err = read("fem-q3").unwrap_err();
        assert!(err.to_string().contains("fem-q1"), "{err}");
    }

    #[test]
    fn q2_coarsens_to_odd_counts_and_checks_odd_nodes() {
        let s = DiscretisationSettings::default();
        let q2 = DiscretisationMethod::FemQ2.scheme(&s).unwrap();
        assert_eq!(q2.coarser_nodes(257), Some(129));
        assert_eq!(q2.coarser_nodes(35), Some(19)); // 18 -> 19
        assert_eq!(q2.coarser_nodes(13), None); // 7 nodes: under 9
        assert!(q2.check_nodes("grid.n2", 250).is_err());
        assert_eq!(q2.admissible_nodes(250), 249);
        let q1 = DiscretisationMethod::FemQ1.scheme(&s).unwrap();
        assert_eq!(q1.coarser_nodes(250), Some(125));
        assert_eq!(q1.coarser_nodes(8), None);
        assert_eq!(q1.admissible_nodes(250), 250);
    }
}
