//! What a discretisation registers: its name, its scene parameters and how to build it from
//! the scene's values ([`RegisteredDiscretisation`]), the values ([`DiscretisationSettings`])
//! and the built variant with its data ([`DiscretisationScheme`]). The registry itself is
//! [`crate::registry`].

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::discretisation::Discretisation;
use crate::error::ElasticityError;
use crate::finite_element::{Grading, TransitionGrading, VolumetricIntegration};
use crate::mesh_discretisation::MeshOperator;
use crate::plane_problem::PlaneProblem;
use crate::shell_geometry::SharedChart;
use crate::solid::HexElement;

/// A plane-strain operator of any registered discretisation, over any chart.
pub type PlaneOperator = Box<dyn Discretisation + Send + Sync>;

/// The values of a scene's `[discretisation]` table a discretisation draws its data from.
///
/// The keys of the built-in discretisations are fields; any other numeric key of the table (a
/// parameter of a discretisation registered outside this crate) is in `extra`.
#[derive(Debug, Clone, PartialEq)]
pub struct DiscretisationSettings {
    /// `discretisation.order`: the order `p` of `fem-qp` (default
    /// [`crate::finite_element::DiscretisationMethod::DEFAULT_ORDER`]).
    pub order: usize,
    /// `discretisation.volumetric`: full or selective reduced integration of the volumetric
    /// part (finite elements).
    pub volumetric: VolumetricIntegration,
    /// `discretisation.grading`, `discretisation.layers`: the spacing of the element boundaries.
    pub grading: Grading,
    /// `discretisation.corner_layers`: geometric layers per corner of `fem-qp-corner`
    /// (default [`DiscretisationSettings::DEFAULT_CORNER_LAYERS`]; `0`: the uniform mesh).
    pub corner_layers: usize,
    /// `discretisation.corner_ratio`: the ratio of successive corner layers of
    /// `fem-qp-corner` (default [`DiscretisationSettings::DEFAULT_CORNER_RATIO`]).
    pub corner_ratio: f64,
    /// `fem-qp-corner`'s `x2` layers toward interior points of the contact face (the stick/slip
    /// transitions of a first solve: the two-pass solve of the root crate sets them; no scene
    /// key). Default [`TransitionGrading::NONE`].
    pub transitions: TransitionGrading,
    /// Every other key of `[discretisation]` (parameters of discretisations registered
    /// elsewhere).
    pub extra: BTreeMap<String, f64>,
}

impl Default for DiscretisationSettings {
    fn default() -> Self {
        Self {
            order: crate::finite_element::DiscretisationMethod::DEFAULT_ORDER,
            volumetric: VolumetricIntegration::Full,
            grading: Grading::UNIFORM,
            corner_layers: Self::DEFAULT_CORNER_LAYERS,
            corner_ratio: Self::DEFAULT_CORNER_RATIO,
            transitions: TransitionGrading::NONE,
            extra: BTreeMap::new(),
        }
    }
}

impl DiscretisationSettings {
    /// Corner layers of `fem-qp-corner` by default: five layers of `0.3` (the smallest element
    /// `2.4e-3` of a cell; beyond five the paper problem's error does not move,
    /// docs/high-order.md).
    pub const DEFAULT_CORNER_LAYERS: usize = 5;

    /// The ratio of successive corner layers by default.
    pub const DEFAULT_CORNER_RATIO: f64 = 0.3;

    /// Checks the settings of a method with neither a volumetric rule to reduce nor element
    /// boundaries to grade: `volumetric` must be full and `grading` uniform; the errors say
    /// `volumetric_allowed`, `grading_allowed`.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `discretisation.volumetric` or
    /// `discretisation.grading`.
    pub fn require_full_uniform(
        &self,
        volumetric_allowed: &'static str,
        grading_allowed: &'static str,
    ) -> Result<(), ElasticityError> {
        if self.volumetric != VolumetricIntegration::Full {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.volumetric",
                value: f64::NAN,
                allowed: volumetric_allowed,
            });
        }
        if !self.grading.is_uniform() {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.grading",
                value: self.grading.ratio(),
                allowed: grading_allowed,
            });
        }
        Ok(())
    }
}

/// One scene parameter of a discretisation: its key under `[discretisation]`, its default and
/// its allowed values, as text for help and error messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SchemeParameter {
    /// The key without the `discretisation.` prefix (`order`).
    pub key: &'static str,
    /// The default (`4`).
    pub default: &'static str,
    /// The allowed values (`1..=10`).
    pub allowed: &'static str,
}

/// A discretisation that scenes can name (`discretisation.method`): registered once, in the
/// file of the discretisation, and listed in [`crate::registry`].
#[derive(Debug, Clone, Copy)]
pub struct RegisteredDiscretisation {
    /// The scene name (`fd`, `fem-qp`).
    pub name: &'static str,
    /// One line for help texts.
    pub summary: &'static str,
    /// The keys of `[discretisation]` it reads, with defaults and ranges.
    pub parameters: &'static [SchemeParameter],
    /// Builds the variant from the settings, validating them (the constructor's errors name
    /// the scene key).
    pub build:
        fn(&DiscretisationSettings) -> Result<Arc<dyn DiscretisationScheme>, ElasticityError>,
}

/// A discretisation variant with its data (`FemQp { order, .. }`): what a body needs to build
/// its operator, coarsen its grid and size its solve. Methods with defaults have correct
/// defaults for a nodal method on the grid's own nodes.
///
/// # Math
/// The plane-strain Navier operator (see [`Discretisation`]) on the nodes of an `n2 x n3`
/// [`crate::Grid`]; `n` below is a node count along one direction.
pub trait DiscretisationScheme: core::fmt::Debug + Send + Sync {
    /// The scene name (`discretisation.method`).
    fn name(&self) -> &'static str;

    /// The plane-strain operator of `problem`.
    ///
    /// # Errors
    /// The constructor's errors (grid, geometry, boundary).
    fn build(&self, problem: PlaneProblem<SharedChart>) -> Result<PlaneOperator, ElasticityError>;

    /// Whether the assembled matrix is symmetric (a Cholesky backend applies). Default `false`
    /// (a general LU, always correct).
    fn is_symmetric(&self) -> bool {
        false
    }

    /// Whether `n` nodes along a (non-periodic) direction fit the method; the error names
    /// `field`. Default: any `n >= 3`.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `field` with the allowed values.
    fn check_nodes(&self, field: &'static str, n: usize) -> Result<(), ElasticityError> {
        if n < 3 {
            return Err(ElasticityError::InvalidParameter {
                field,
                value: n as f64,
                allowed: "at least 3 nodes",
            });
        }
        Ok(())
    }

    /// The node count nearest `n` (ties down) that [`DiscretisationScheme::check_nodes`]
    /// accepts: a default grid that follows the method. Default `n`.
    fn admissible_nodes(&self, n: usize) -> usize {
        n.max(3)
    }

    /// The node count of the next coarser grid of grid sequencing, `None` when the method has
    /// no coarser level. Default: every other node, `n -> (n + 1) / 2`, at least 5 nodes.
    fn coarser_nodes(&self, n: usize) -> Option<usize> {
        let c = n.div_ceil(2);
        (c >= 5 && c < n).then_some(c)
    }

    /// How much wider than the five-point finite differences the sparse couplings are (the
    /// factor of the `N log2 N` memory estimate of a 2-D solve). Default `1`.
    fn memory_width(&self) -> f64 {
        1.0
    }

    /// Whether the method's nodes are a mesh's rather than the grid's
    /// ([`DiscretisationScheme::build_mesh`] builds it; [`DiscretisationScheme::build`]
    /// refuses). Default `false`.
    fn is_mesh(&self) -> bool {
        false
    }

    /// The operator on a mesh whose nodes are not the grid's tensor product (the grid gives
    /// the rectangle and the element counts): what the contact solvers and the outputs use for
    /// a method with [`DiscretisationScheme::is_mesh`].
    ///
    /// # Errors
    /// Default: [`ElasticityError::InvalidParameter`] naming `discretisation.method` (a
    /// method on the grid's nodes: [`DiscretisationScheme::build`]); the constructor's errors.
    fn build_mesh(
        &self,
        problem: PlaneProblem<SharedChart>,
    ) -> Result<MeshOperator, ElasticityError> {
        let _ = problem;
        Err(ElasticityError::InvalidParameter {
            field: "discretisation.method",
            value: f64::NAN,
            allowed: "a method on a mesh (fem-qp-corner): this one is on the grid's nodes",
        })
    }

    /// The hexahedra of the 3-D body of this method.
    ///
    /// # Errors
    /// Default: [`ElasticityError::InvalidParameter`] naming `discretisation.method` (a
    /// plane-strain-only method).
    fn solid_element(&self) -> Result<HexElement, ElasticityError> {
        Err(ElasticityError::InvalidParameter {
            field: "discretisation.method",
            value: f64::NAN,
            allowed: "a finite-element method (fem-q1, fem-q2, fem-qp, fem-qp-corner) with body.dimension = 3: this one is plane strain only",
        })
    }

    /// The 2-D layout of the `(x2, x3)` rectangle whose extrusion along `x1` carries the 3-D
    /// body's hexahedra ([`DiscretisationScheme::solid_element`]) for a method on a mesh
    /// (`fem-qp-corner`: the corner layout of an `n2 x n3` grid, built by
    /// [`crate::solid::SolidCornerNavier`]); `None` (the default) for a method whose 3-D body
    /// is on the box grid's nodes.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `grid.n2` or `grid.n3` when the grid does
    /// not fit the layout.
    fn solid_layout(
        &self,
        n2: usize,
        n3: usize,
    ) -> Result<Option<crate::finite_element::high_order::CornerSettings>, ElasticityError> {
        let _ = (n2, n3);
        Ok(None)
    }
}

/// The nodes `p e + 1` nearest `n` (ties down), at least one element: the grids elements of
/// `p` nodes a side accept.
pub(crate) fn nearest_element_nodes(n: usize, p: usize) -> usize {
    let p = p.max(1);
    let e = ((n.max(2) - 1) + (p - 1) / 2) / p;
    p * e.max(1) + 1
}

/// Checks that `n` nodes (at `field`) are `p e + 1` with `e >= min_elements` elements of order
/// `p`; `allowed` is the error's description of the range.
///
/// # Errors
/// [`ElasticityError::InvalidParameter`] naming `field` otherwise.
pub(crate) fn check_element_nodes(
    field: &'static str,
    n: usize,
    p: usize,
    min_elements: usize,
    allowed: &'static str,
) -> Result<(), ElasticityError> {
    if n < min_elements * p + 1 || n < 2 || !(n - 1).is_multiple_of(p) {
        return Err(ElasticityError::InvalidParameter {
            field,
            value: n as f64,
            allowed,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_element_nodes_rounds_to_whole_elements() {
        assert_eq!(nearest_element_nodes(250, 1), 250);
        assert_eq!(nearest_element_nodes(250, 2), 249);
        assert_eq!(nearest_element_nodes(41, 2), 41);
        assert_eq!(nearest_element_nodes(250, 4), 249);
        assert_eq!(nearest_element_nodes(41, 4), 41);
        assert_eq!(nearest_element_nodes(250, 3), 250);
        assert_eq!(nearest_element_nodes(2, 5), 6);
    }
}
