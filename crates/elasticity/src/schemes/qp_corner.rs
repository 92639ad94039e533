//! `fem-qp-corner` in the registry: the Qp elements on the mesh refined toward the four corners
//! only ([`CornerRefinedNavier`]), a mesh discretisation
//! ([`crate::mesh_discretisation::MeshDiscretisation`]) of the contact solvers.

use std::sync::Arc;

use crate::error::ElasticityError;
use crate::finite_element::high_order::{
    CornerRefinedNavier, CornerSettings, TransitionGrading, check_order,
};
use crate::mesh_discretisation::MeshOperator;
use crate::plane_problem::PlaneProblem;
use crate::registration::{
    DiscretisationScheme, DiscretisationSettings, PlaneOperator, RegisteredDiscretisation,
    SchemeParameter, check_element_nodes, nearest_element_nodes,
};
use crate::shell_geometry::SharedChart;
use crate::solid::HexElement;

/// `fem-qp-corner`: Qp elements of order `p` on the grid's `e2 x e3` element cells
/// (`n = p e + 1` nodes, `e >= 2`), each corner cell cut into `layers` geometric trapezoid
/// layers of ratio `ratio` ([`CornerSettings`]); `layers = 0` is the uniform `fem-qp` mesh.
///
/// A plain function of `(order, grid, corner settings)`: [`FemQpCorner::settings_for`] gives
/// the [`CornerSettings`] of a grid, [`CornerRefinedNavier::new`] builds the operator.
#[derive(Debug, Clone, PartialEq)]
pub struct FemQpCorner {
    /// The order `p`.
    pub order: usize,
    /// Geometric layers per corner (`0 ..= 16`).
    pub layers: usize,
    /// Ratio of successive layers (`0.05 ..= 0.95`).
    pub ratio: f64,
    /// Layers toward interior `x2` points of the face ([`TransitionGrading`]; default none).
    pub transitions: TransitionGrading,
}

impl FemQpCorner {
    /// Validates the settings, naming the scene keys.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `discretisation.order`,
    /// `discretisation.corner_layers` or `discretisation.corner_ratio`.
    pub fn new(order: usize, layers: usize, ratio: f64) -> Result<Self, ElasticityError> {
        check_order(order)?;
        if !CornerSettings::LAYERS.contains(&layers) {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.corner_layers",
                value: layers as f64,
                allowed: "0..=16",
            });
        }
        if !(0.05..=0.95).contains(&ratio) {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.corner_ratio",
                value: ratio,
                allowed: "0.05 <= corner_ratio <= 0.95",
            });
        }
        Ok(Self {
            order,
            layers,
            ratio,
            transitions: TransitionGrading::NONE,
        })
    }

    /// The corner mesh of an `n2 x n3` grid: cells `[(n2 - 1) / p, (n3 - 1) / p]`.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `grid.n2` or `grid.n3` when `n - 1` is
    /// not `p e` with `e >= 2`.
    pub fn settings_for(&self, n2: usize, n3: usize) -> Result<CornerSettings, ElasticityError> {
        self.check_nodes("grid.n2", n2)?;
        self.check_nodes("grid.n3", n3)?;
        let p = self.order;
        Ok(CornerSettings {
            order: p,
            cells: [(n2 - 1) / p, (n3 - 1) / p],
            layers: self.layers,
            ratio: self.ratio,
        })
    }
}

impl DiscretisationScheme for FemQpCorner {
    fn name(&self) -> &'static str {
        "fem-qp-corner"
    }

    /// Refused: the corner mesh's nodes are not the grid's ([`Self::build_mesh`]).
    fn build(&self, problem: PlaneProblem<SharedChart>) -> Result<PlaneOperator, ElasticityError> {
        let _ = problem;
        Err(ElasticityError::InvalidParameter {
            field: "discretisation.method",
            value: f64::NAN,
            allowed: "a method on the grid's nodes here (fd, fem-q1, fem-q2, fem-qp): fem-qp-corner is a mesh, built by Body::operator",
        })
    }

    fn is_mesh(&self) -> bool {
        true
    }

    fn build_mesh(
        &self,
        problem: PlaneProblem<SharedChart>,
    ) -> Result<MeshOperator, ElasticityError> {
        let settings = self.settings_for(problem.grid.n2(), problem.grid.n3())?;
        Ok(Box::new(CornerRefinedNavier::with_transitions(
            problem,
            settings,
            &self.transitions,
        )?))
    }

    fn is_symmetric(&self) -> bool {
        true
    }

    /// `n = p e + 1` with `e >= 2` cells (each corner its own cell).
    fn check_nodes(&self, field: &'static str, n: usize) -> Result<(), ElasticityError> {
        check_element_nodes(
            field,
            n,
            self.order,
            2,
            "p e + 1 nodes, e >= 2 cells of order p = discretisation.order, with fem-qp-corner",
        )
    }

    fn admissible_nodes(&self, n: usize) -> usize {
        nearest_element_nodes(n, self.order).max(2 * self.order + 1)
    }

    /// None: grid sequencing interpolates on the grid's nodes, which the mesh does not have.
    fn coarser_nodes(&self, n: usize) -> Option<usize> {
        let _ = n;
        None
    }

    /// As `fem-qp`.
    fn memory_width(&self) -> f64 {
        4.0
    }

    /// Qp hexahedra (GLL nodes), placed on the extruded corner layout
    /// ([`DiscretisationScheme::solid_layout`]), not on the box grid's nodes.
    fn solid_element(&self) -> Result<HexElement, ElasticityError> {
        HexElement::gll(self.order)
    }

    /// The corner layout of the grid ([`FemQpCorner::settings_for`]), extruded along `x1` by
    /// [`crate::solid::SolidCornerNavier`].
    fn solid_layout(
        &self,
        n2: usize,
        n3: usize,
    ) -> Result<Option<CornerSettings>, ElasticityError> {
        self.settings_for(n2, n3).map(Some)
    }
}

/// `fem-qp-corner` in the registry.
pub(crate) const REGISTRATION: RegisteredDiscretisation = RegisteredDiscretisation {
    name: "fem-qp-corner",
    summary: "Qp elements on the grid's p e + 1 cells with geometric layers toward the four corners only (plane strain; in 3-D extruded along x1)",
    parameters: &[
        super::qp::ORDER_PARAMETER,
        SchemeParameter {
            key: "corner_layers",
            default: "5",
            allowed: "0..=16 (0: uniform)",
        },
        SchemeParameter {
            key: "corner_ratio",
            default: "0.3",
            allowed: "0.05..=0.95",
        },
    ],
    build: |s: &DiscretisationSettings| {
        s.require_full_uniform(
            "full (fem-qp-corner integrates fully)",
            "1 (fem-qp-corner refines the corners with discretisation.corner_layers)",
        )?;
        Ok(Arc::new(FemQpCorner {
            transitions: s.transitions.clone(),
            ..FemQpCorner::new(s.order, s.corner_layers, s.corner_ratio)?
        }))
    },
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_keys_outside_their_ranges_name_the_key() {
        let build = |s: DiscretisationSettings| (REGISTRATION.build)(&s).map(|_| ());
        let field = |r: Result<(), ElasticityError>| match r {
            Err(ElasticityError::InvalidParameter { field, .. }) => field,
            other => panic!("{other:?}"),
        };
        let d = DiscretisationSettings::default;
        assert!(build(d()).is_ok());
        let cases = [
            (
                DiscretisationSettings {
                    corner_layers: 17,
                    ..d()
                },
                "discretisation.corner_layers",
            ),
            (
                DiscretisationSettings {
                    corner_ratio: 1.0,
                    ..d()
                },
                "discretisation.corner_ratio",
            ),
            (
                DiscretisationSettings {
                    corner_ratio: f64::NAN,
                    ..d()
                },
                "discretisation.corner_ratio",
            ),
            (
                DiscretisationSettings { order: 0, ..d() },
                "discretisation.order",
            ),
        ];
        for (s, key) in cases {
            assert_eq!(field(build(s)), key);
        }
        let scheme = (REGISTRATION.build)(&d()).unwrap();
        assert!(scheme.is_mesh());
        assert!(scheme.check_nodes("grid.n2", 9).is_ok()); // p = 4, 2 cells
        assert!(scheme.check_nodes("grid.n2", 5).is_err()); // 1 cell
        assert!(scheme.check_nodes("grid.n3", 10).is_err());
        assert_eq!(scheme.coarser_nodes(17), None);
        assert_eq!(scheme.admissible_nodes(3), 9);
        // the 3-D body: GLL hexahedra on the layout of the grid's cells
        assert_eq!(scheme.solid_element().unwrap(), HexElement::Gll(4));
        let layout = scheme.solid_layout(9, 13).unwrap().unwrap();
        assert_eq!(
            (layout.cells, layout.layers, layout.ratio),
            ([2, 3], 5, 0.3)
        );
        assert!(scheme.solid_layout(5, 13).is_err());
        let qp = crate::finite_element::DiscretisationMethod::FemQp
            .scheme(&d())
            .unwrap();
        assert_eq!(qp.solid_layout(9, 13).unwrap(), None);
    }
}
