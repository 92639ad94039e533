//! A 3-D thick body on any obstacle under end tensions, with the frictional contact face
//! `x3 = 0`: the convenience builder of 3-D contact models (the counterpart of
//! [`crate::contact::ThickBody`]).

use capstan_geometry::{ShellChart, Surface};

use super::boundary::{FaceComponent, FaceCondition, FaceFunction, SolidBoundary};
use super::element::HexElement;
use super::grid::BoxGrid;
use super::operator::SolidNavier;
use crate::error::ElasticityError;
use crate::finite_element::{ElementOrder, VolumetricIntegration};
use crate::material::Material;

/// The conditions on the side faces `x1 = x1a`, `x1 = x1b` of a 3-D body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SideFaces {
    /// Traction-free: a body of finite width.
    Free,
    /// `v^1 = 0`, the other components free: the plane-strain body extruded (on a prism it
    /// reproduces the 2-D solution).
    PlaneStrain,
}

/// A 3-D body of thickness `h` on the parametric box `[x1a, x1b] x [theta0, theta1] x [0, h]`
/// of the shell chart of `surface`, bilateral contact on `x3 = 0` (`v^3 = 0`, tangential
/// traction from the friction law), free outer surface, end tensions `T^2_2 = tau0` at
/// `theta0` and `tau_max` at `theta1` (zero `T^2_1`, `T^2_3`), and [`SideFaces`] on the
/// `x1` faces.
///
/// # Example
/// ```
/// use capstan_elasticity::solid::{SideFaces, SolidBody};
/// use capstan_elasticity::contact::ContactOperator;
/// use capstan_geometry::EllipticalPrism;
/// let body = SolidBody::new(EllipticalPrism::new(2.0, 1.5).unwrap(), [-0.5, 0.5], [3, 9, 3]);
/// let op = body.operator(1.0, 2.0).unwrap();
/// assert_eq!(op.dof_count(), 3 * 3 * 9 * 3);
/// ```
#[derive(Debug, Clone)]
pub struct SolidBody<S> {
    /// The obstacle surface `sigma(x1, x2)`.
    pub surface: S,
    /// `[x1a, x1b]` (the width: `body.width`).
    pub x1: [f64; 2],
    /// `[theta0, theta1]`.
    pub theta: [f64; 2],
    /// Thickness `h`.
    pub thickness: f64,
    /// The material.
    pub material: Material,
    /// Nodes `[n1, n2, n3]`.
    pub nodes: [usize; 3],
    /// Q1, Q2 or Qp hexahedra.
    pub order: HexElement,
    /// Full or selective reduced integration of the volumetric part.
    pub volumetric: VolumetricIntegration,
    /// The side faces.
    pub sides: SideFaces,
}

impl<S: Surface<f64> + Clone + Send + Sync> SolidBody<S> {
    /// The paper's section-3 body (`h = 1`, `E = 1e3`, `nu = 1/4`, `x2 in [-pi/2, pi/2]`) on
    /// `surface` over `x1 in x1`, Q1 elements, free sides.
    ///
    /// # Panics
    /// Never: the paper's material is valid.
    pub fn new(surface: S, x1: [f64; 2], nodes: [usize; 3]) -> Self {
        let half = core::f64::consts::FRAC_PI_2;
        Self {
            surface,
            x1,
            theta: [-half, half],
            thickness: 1.0,
            material: Material::new(1e3, 0.25).expect("the paper's material"),
            nodes,
            order: HexElement::Uniform(ElementOrder::Q1),
            volumetric: VolumetricIntegration::Full,
            sides: SideFaces::Free,
        }
    }

    /// The boundary conditions for the end loads.
    pub fn boundary(&self, tau0: f64, tau_max: f64) -> SolidBoundary {
        let end = |tau: f64| {
            FaceCondition([
                FaceComponent::Stress(FaceFunction::constant(0.0)),
                FaceComponent::Stress(FaceFunction::constant(tau)),
                FaceComponent::Stress(FaceFunction::constant(0.0)),
            ])
        };
        let side = match self.sides {
            SideFaces::Free => FaceCondition::free(),
            SideFaces::PlaneStrain => FaceCondition::plane_strain(),
        };
        let contact = FaceCondition([
            FaceComponent::free(),
            FaceComponent::free(),
            FaceComponent::fixed(),
        ]);
        SolidBoundary {
            faces: [
                side.clone(),
                side,
                end(tau0),
                end(tau_max),
                contact,
                FaceCondition::free(),
            ],
            periodic_x2: false,
            pinned: vec![],
        }
    }

    /// [`SolidBody::boundary`] with a traction-free contact face (all three components):
    /// the body of unilateral contact.
    pub fn boundary_free_face(&self, tau0: f64, tau_max: f64) -> SolidBoundary {
        let mut b = self.boundary(tau0, tau_max);
        b.faces[4] = FaceCondition::free();
        b
    }

    /// The assembled operator with end loads `tau0`, `tau_max` and a traction-free contact
    /// face ([`SolidBody::boundary_free_face`]).
    ///
    /// # Errors
    /// See [`SolidBody::operator`].
    pub fn operator_free_face(
        &self,
        tau0: f64,
        tau_max: f64,
    ) -> Result<SolidNavier<ShellChart<S>>, ElasticityError> {
        self.operator_with(&self.boundary_free_face(tau0, tau_max))
    }

    /// The grid of the body.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `body.width`, `grid.n1`, ... (see
    /// [`BoxGrid::new`]).
    pub fn grid(&self) -> Result<BoxGrid, ElasticityError> {
        BoxGrid::new(self.x1, self.theta, self.thickness, self.nodes, false)
    }

    /// The assembled operator with end loads `tau0`, `tau_max`.
    ///
    /// # Errors
    /// Grid, geometry (a degenerate chart anywhere in the body) or boundary errors.
    pub fn operator(
        &self,
        tau0: f64,
        tau_max: f64,
    ) -> Result<SolidNavier<ShellChart<S>>, ElasticityError> {
        self.operator_with(&self.boundary(tau0, tau_max))
    }

    /// The assembled operator of the body with the face conditions `boundary`.
    fn operator_with(
        &self,
        boundary: &SolidBoundary,
    ) -> Result<SolidNavier<ShellChart<S>>, ElasticityError> {
        SolidNavier::new(
            ShellChart::new(self.surface.clone()),
            self.material,
            self.grid()?,
            boundary,
            None,
            self.order,
            self.volumetric,
        )
    }
}
