//! Naming a discretisation (`discretisation.method` in scene files; the lookups by name are in
//! [`crate::registry`]), and the Q1/Q2 elements' registrations.

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
    /// `fem-qp-corner`: [`super::high_order::CornerRefinedNavier`], the Qp elements on the
    /// grid's element cells with geometric layers toward the four corners only: a mesh
    /// discretisation ([`crate::mesh_discretisation::MeshDiscretisation`]), not in [`Self::ALL`].
    pub const FemQpCorner: Self = Self("fem-qp-corner");

    /// The built-in methods on the grid's nodes (what [`Self::build`] builds), in registry
    /// order.
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::registration::DiscretisationSettings;

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
