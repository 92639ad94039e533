//! The paper's thick body on a prism, discretised by any registered discretisation
//! (`discretisation.method`): the convenience builder of plane-strain contact models.

use std::sync::Arc;

use capstan_friction::FrictionLaw;
use capstan_geometry::{Obstacle, ShellChart, Surface};

use crate::boundary::{BoundaryConditions, BoundaryFunction, SideCondition, X2Ends};
use crate::contact::body_force::BodyForceField;
use crate::contact::error::ContactError;
use crate::contact::loads::{BODY_FORCE, END_LOADS};
use crate::contact::model::ContactModel;
use crate::error::ElasticityError;
use crate::finite_element::{DiscretisationMethod, Grading, VolumetricIntegration};
use crate::grid::Grid;
use crate::material::Material;
use crate::plane_problem::PlaneProblem;
use crate::registration::{DiscretisationScheme, DiscretisationSettings, PlaneOperator};
use crate::shell_geometry::SharedChart;

/// A plane-strain body of thickness `h` on `x2 in [theta0, theta1]` of a prism surface `S`
/// (the closed [`Obstacle`] by default, any [`Surface`] that is `x1`-invariant),
/// bilateral contact on `x3 = 0` (`v^3 = 0`, including the corners), free outer surface, end
/// tensions `T^2_2 = tau0` at `theta0` and `tau_max` at `theta1` with zero end shear.
///
/// # Example
/// ```
/// use capstan_elasticity::contact::ThickBody;
/// use capstan_elasticity::Discretisation;
/// let body = ThickBody::paper(20, 5).unwrap();
/// let op = body.discretisation(1.0, 2.0).unwrap();
/// assert_eq!(op.dof_count(), 2 * 20 * 5);
/// ```
///
/// A user surface reaches 2-D contact the same way as 3-D ([`crate::solid::SolidBody::new`]):
/// ```
/// use capstan_elasticity::contact::ThickBody;
/// use capstan_elasticity::Discretisation;
/// use capstan_geometry::{Scalar, Surface};
/// /// A circular prism of radius 2, written once as sigma(x1, x2).
/// #[derive(Debug, Clone)]
/// struct Round;
/// impl Surface<f64> for Round {
///     fn sigma<S: Scalar<f64>>(&self, x: [S; 2]) -> [S; 3] {
///         [x[0], x[1].cos() * 2.0, x[1].sin() * 2.0]
///     }
/// }
/// let op = ThickBody::on(Round, 21, 5).unwrap().discretisation(1.0, 2.0).unwrap();
/// assert_eq!(op.dof_count(), 2 * 21 * 5);
/// ```
#[derive(Debug, Clone)]
pub struct ThickBody<S = Obstacle> {
    /// The obstacle surface (a prism).
    pub obstacle: S,
    /// `[theta0, theta1]`.
    pub theta: [f64; 2],
    /// Thickness `h`.
    pub thickness: f64,
    /// The material.
    pub material: Material,
    /// Nodes along `x2`.
    pub n2: usize,
    /// Nodes through the thickness.
    pub n3: usize,
    /// The discretisation (`fd` by default; `fem-q2` needs odd `n2`, `n3`), any registered
    /// one ([`crate::registry`]).
    pub method: DiscretisationMethod,
    /// How the finite elements integrate the volumetric part (`Full` for `fd`).
    pub volumetric: VolumetricIntegration,
    /// The order `p` of `fem-qp` (`n2 - 1`, `n3 - 1` multiples of it); ignored by the other
    /// methods.
    pub order: usize,
    /// The spacing of the `fem-qp` element boundaries (`discretisation.grading`,
    /// `discretisation.layers`): [`Grading::UNIFORM`] (the default of [`ThickBody::paper`]) or
    /// geometric layers toward both ends of `x2` and `x3` ([`Grading::geometric`]). The other
    /// methods accept only the uniform one.
    pub grading: Grading,
    /// A body force (`loads.body_force`), `None` for none: a load of the contact model beside
    /// the end tractions, always at its full value ([`ContactModel::with_fixed_loads`]).
    pub body_force: Option<BodyForceField>,
}

/// The operator [`ThickBody`] builds: any registered discretisation, boxed (the name is kept
/// for callers that spelled the type).
pub type ThickBodyOperator = PlaneOperator;

impl ThickBody {
    /// The paper's body: ellipse `a = b = 2` (a circle), `h = 1`, `E = 1e3`, `nu = 1/4`,
    /// `x2 in [-pi/2, pi/2]`, on an `n2 x n3` grid.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn paper(n2: usize, n3: usize) -> Result<Self, ElasticityError> {
        let circle = Obstacle::Ellipse(capstan_geometry::EllipticalPrism::new(2.0, 2.0)?);
        ThickBody::on(circle, n2, n3)
    }

    /// The boundary conditions for the end loads with a traction-free contact face (both
    /// components; the body of unilateral contact, whose normal rows are then its free rows).
    pub fn boundary_free_face(tau0: f64, tau_max: f64) -> BoundaryConditions {
        BoundaryConditions {
            x3_min: SideCondition::free(),
            ..ThickBody::boundary(tau0, tau_max)
        }
    }

    /// The boundary conditions for the end loads.
    pub fn boundary(tau0: f64, tau_max: f64) -> BoundaryConditions {
        BoundaryConditions {
            x2: X2Ends::Sides {
                min: SideCondition::end_tension(tau0),
                max: SideCondition::end_tension(tau_max),
            },
            x3_min: SideCondition::bilateral(BoundaryFunction::zero()),
            x3_max: SideCondition::free(),
            pinned: vec![],
        }
    }
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> ThickBody<S> {
    /// The paper's section-3 body (`h = 1`, `E = 1e3`, `nu = 1/4`, `x2 in [-pi/2, pi/2]`)
    /// on the prism `surface`, finite differences on an `n2 x n3` grid.
    ///
    /// # Errors
    /// Never for the paper's material; kept fallible like [`ThickBody::paper`].
    pub fn on(surface: S, n2: usize, n3: usize) -> Result<Self, ElasticityError> {
        let half = core::f64::consts::FRAC_PI_2;
        Ok(Self {
            obstacle: surface,
            theta: [-half, half],
            thickness: 1.0,
            material: Material::new(1e3, 0.25)?,
            n2,
            n3,
            method: DiscretisationMethod::Fd,
            volumetric: VolumetricIntegration::Full,
            order: DiscretisationMethod::DEFAULT_ORDER,
            grading: Grading::UNIFORM,
            body_force: None,
        })
    }

    /// The settings the discretisation is built from (`order`, `volumetric`, `grading`).
    pub fn settings(&self) -> DiscretisationSettings {
        DiscretisationSettings {
            order: self.order,
            volumetric: self.volumetric,
            grading: self.grading,
            ..Default::default()
        }
    }

    /// The discretisation variant with its data, from the registry.
    ///
    /// # Errors
    /// The registered builder's errors (naming `discretisation.volumetric`,
    /// `discretisation.grading`, `discretisation.order`).
    pub fn scheme(&self) -> Result<Arc<dyn DiscretisationScheme>, ElasticityError> {
        self.method.scheme(&self.settings())
    }

    /// The problem of the body with end loads `tau0`, `tau_max` (and its body force, if any),
    /// over the shared chart.
    ///
    /// # Errors
    /// Grid errors.
    pub fn problem(
        &self,
        tau0: f64,
        tau_max: f64,
    ) -> Result<PlaneProblem<SharedChart>, ElasticityError> {
        self.problem_scaled(tau0, tau_max, 1.0)
    }

    /// [`ThickBody::problem`] with the body force times `force_scale` (`0`: none).
    ///
    /// # Errors
    /// Grid errors.
    pub fn problem_scaled(
        &self,
        tau0: f64,
        tau_max: f64,
        force_scale: f64,
    ) -> Result<PlaneProblem<SharedChart>, ElasticityError> {
        let chart: SharedChart = Arc::new(ShellChart::new(self.obstacle.clone()));
        let body_force = match &self.body_force {
            Some(f) if force_scale != 0.0 => Some(f.scaled(force_scale).plane(chart.clone())),
            _ => None,
        };
        Ok(PlaneProblem {
            chart,
            material: self.material,
            grid: Grid::new(self.theta, self.thickness, self.n2, self.n3, false)?,
            boundary: ThickBody::boundary(tau0, tau_max),
            body_force,
        })
    }

    /// The operator of [`ThickBody::method`] with end loads `tau0`, `tau_max` and a
    /// traction-free contact face ([`ThickBody::boundary_free_face`]): what unilateral
    /// contact is built from.
    ///
    /// # Errors
    /// See [`ThickBody::discretisation`].
    pub fn discretisation_free_face(
        &self,
        tau0: f64,
        tau_max: f64,
    ) -> Result<PlaneOperator, ElasticityError> {
        let scheme = self.scheme()?;
        let mut problem = self.problem(tau0, tau_max)?;
        problem.boundary = ThickBody::boundary_free_face(tau0, tau_max);
        scheme.build(problem)
    }

    /// The operator of [`ThickBody::method`] with end loads `tau0`, `tau_max`.
    ///
    /// # Errors
    /// Grid, geometry or boundary errors; the registered builder's errors
    /// ([`ElasticityError::InvalidParameter`] for a reduced volumetric integration with finite
    /// differences, or naming `discretisation.grading` for a graded body of another method
    /// than `fem-qp`).
    pub fn discretisation(
        &self,
        tau0: f64,
        tau_max: f64,
    ) -> Result<PlaneOperator, ElasticityError> {
        let scheme = self.scheme()?;
        scheme.build(self.problem(tau0, tau_max)?)
    }

    /// The operator with the loads of [`ThickBody::loads`] at `magnitudes` (`[tau0, tau_max]`,
    /// then the body force's scale when there is one).
    ///
    /// # Errors
    /// As [`ThickBody::discretisation`].
    pub fn loaded_discretisation(
        &self,
        magnitudes: &[f64],
    ) -> Result<PlaneOperator, ElasticityError> {
        let force_scale = magnitudes.get(2).copied().unwrap_or(0.0);
        self.scheme()?
            .build(self.problem_scaled(magnitudes[0], magnitudes[1], force_scale)?)
    }

    /// The loads of the body's contact model, by scene key: [`END_LOADS`], then
    /// [`BODY_FORCE`] when the body has one.
    pub fn loads(&self) -> Vec<&'static str> {
        let mut loads = END_LOADS.to_vec();
        if self.body_force.is_some() {
            loads.push(BODY_FORCE);
        }
        loads
    }

    /// The body on the next coarser grid of grid sequencing
    /// ([`DiscretisationScheme::coarser_nodes`] in both directions): `n -> (n + 1) / 2` nodes
    /// per direction (every other node of an odd `n`), kept odd for `fem-q2`; `None` when a
    /// direction would fall below 5 nodes (9 for `fem-q2`). `fem-qp`: half the elements
    /// (`n = p e + 1 -> p e / 2 + 1`, `e` even, at least 2 elements left).
    ///
    /// A graded body ([`ThickBody::grading`] not uniform) has no coarser level, so grid
    /// sequencing solves it on its own grid directly: halving the elements of a geometric mesh
    /// keeps the layers but moves every middle boundary, and the level-to-level transfer
    /// ([`crate::discretisation::interpolate_nodal`]) interpolates on the uniform grid lines,
    /// not the graded node positions, so the start would be the coarse field at the wrong
    /// places.
    pub fn coarser(&self) -> Option<Self> {
        let scheme = self.scheme().ok()?;
        Some(ThickBody {
            n2: scheme.coarser_nodes(self.n2)?,
            n3: scheme.coarser_nodes(self.n3)?,
            ..self.clone()
        })
    }

    /// The contact model with the friction law `law` (stick/slip threshold `slip_threshold`).
    ///
    /// # Errors
    /// See [`ContactModel::new`].
    pub fn model<L: FrictionLaw<f64>>(
        &self,
        law: L,
        params: L::Params,
        slip_threshold: f64,
    ) -> Result<ContactModel<PlaneOperator, L>, ContactError> {
        if self.body_force.is_none() {
            return ContactModel::new(
                |tau0, tau_max| self.discretisation(tau0, tau_max),
                law,
                params,
                slip_threshold,
            );
        }
        Ok(ContactModel::with_loads(
            |m: &[f64]| self.loaded_discretisation(m),
            &self.loads(),
            law,
            params,
            slip_threshold,
        )?
        .with_fixed_loads(&[1.0]))
    }
}
