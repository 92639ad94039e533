//! One body description for both dimensions: the dimension is data ([`Dimension`]), and
//! [`Body::operator`] / [`Body::model`] are the one place the library forks between the
//! plane-strain body ([`ThickBody`]) and the 3-D body ([`SolidBody`]).

use capstan_friction::FrictionLaw;
use capstan_geometry::{Obstacle, Surface};
use capstan_solvers::Observer;

use crate::contact::body::ThickBody;
use crate::contact::body_force::BodyForceField;
use crate::contact::error::ContactError;
use crate::contact::loads::EndLoads;
use crate::contact::matrix_free_newton::MatrixFreeSettings;
use crate::contact::model::ContactModel;
use crate::contact::operator::BodyOperator;
use crate::contact::solid_sequencing::MatrixFreeSequenced;
use crate::contact::unilateral::ContactKind;
use crate::error::ElasticityError;
use crate::finite_element::DiscretisationMethod;
use crate::material::Material;
use crate::registration::{DiscretisationScheme, DiscretisationSettings};
use crate::solid::{SideFaces, SolidBody};

/// The dimension of a [`Body`], with what only the 3-D body has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dimension {
    /// Plane strain on the `(x2, x3)` rectangle (`v^1 = 0`, `d_1 = 0`): a prism obstacle.
    Plane,
    /// The 3-D body on `[x1a, x1b] x [theta0, theta1] x [0, h]`, `n1` nodes across the
    /// width, with its side faces.
    Solid {
        /// `[x1a, x1b]`.
        x1: [f64; 2],
        /// Nodes along `x1`.
        n1: usize,
        /// The conditions on the faces `x1 = x1a`, `x1 = x1b`.
        sides: SideFaces,
    },
}

impl Dimension {
    /// `2` (plane strain) or `3`.
    pub fn count(&self) -> usize {
        match self {
            Self::Plane => 2,
            Self::Solid { .. } => 3,
        }
    }
}

/// A thick body of either dimension on the surface `S`: thickness `h` over
/// `x2 in [theta0, theta1]`, bilateral frictional contact on `x3 = 0`, end tensions `tau0`,
/// `tau_max` on the `x2` ends, free outer face; discretised by any registered method
/// ([`crate::registry`]) with its settings.
///
/// # Math
/// The curvilinear Navier operator `nabla_i T^i_j = 0` with
/// `A^ijkl = lambda g^ij g^kl + mu (g^ik g^jl + g^il g^jk)` from the shell chart
/// `Theta = sigma + x3 N` of the surface; plane strain is the case `v^1 = 0`, `d_1 = 0`
/// (see [`ThickBody`], [`SolidBody`]).
///
/// # Example
/// The same description in 2-D and 3-D, one call to the contact model:
/// ```
/// use capstan_elasticity::contact::{Body, BoundarySolver, ContactSettings, Dimension, EndLoads};
/// use capstan_elasticity::finite_element::DiscretisationMethod;
/// use capstan_elasticity::solid::SideFaces;
/// use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
/// use capstan_geometry::{EllipticalPrism, Obstacle};
/// let circle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 2.0).unwrap());
/// let mut body = Body::new(circle, 21, 5);
/// body.method = DiscretisationMethod::FemQ1;
/// let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
/// let plane = body.model(RegularisedCoulomb, params, 1e-5).unwrap();
/// body.dimension = Dimension::Solid { x1: [-0.5, 0.5], n1: 3, sides: SideFaces::PlaneStrain };
/// let solid = body.model(RegularisedCoulomb, params, 1e-5).unwrap();
/// let slip = |model| {
///     let solver = BoundarySolver::new(model, ContactSettings::default()).unwrap();
///     solver.solve(EndLoads::new(1.0, 1.5)).unwrap().slip_fraction
/// };
/// // the extruded plane-strain body reproduces the 2-D one
/// assert!((slip(&plane) - slip(&solid)).abs() < 1e-9);
/// ```
#[derive(Debug, Clone)]
pub struct Body<S = Obstacle> {
    /// The obstacle surface `sigma(x1, x2)` (a prism in plane strain).
    pub surface: S,
    /// Plane strain or 3-D.
    pub dimension: Dimension,
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
    /// The discretisation, any registered one.
    pub method: DiscretisationMethod,
    /// Its settings (order, volumetric integration, grading, extra keys).
    pub settings: DiscretisationSettings,
    /// A body force (`loads.body_force`), `None` for none: held at its full value while the
    /// solvers drive the end loads ([`ContactModel::with_fixed_loads`]).
    pub body_force: Option<BodyForceField>,
    /// Bilateral (default) or unilateral contact on `x3 = 0` (`contact.kind`, `contact.gap`).
    pub contact: ContactKind,
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Body<S> {
    /// The paper's section-3 body (`h = 1`, `E = 1e3`, `nu = 1/4`, `x2 in [-pi/2, pi/2]`) in
    /// plane strain on `surface`, finite differences on an `n2 x n3` grid.
    ///
    /// # Panics
    /// Never: the paper's material is valid.
    pub fn new(surface: S, n2: usize, n3: usize) -> Self {
        let half = core::f64::consts::FRAC_PI_2;
        Self {
            surface,
            dimension: Dimension::Plane,
            theta: [-half, half],
            thickness: 1.0,
            material: Material::new(1e3, 0.25).expect("the paper's material"),
            n2,
            n3,
            method: DiscretisationMethod::Fd,
            settings: DiscretisationSettings::default(),
            body_force: None,
            contact: ContactKind::Bilateral,
        }
    }

    /// The discretisation variant with its data, from the registry.
    ///
    /// # Errors
    /// The registered builder's errors, naming the scene key.
    pub fn scheme(&self) -> Result<std::sync::Arc<dyn DiscretisationScheme>, ElasticityError> {
        self.method.scheme(&self.settings)
    }

    /// The plane-strain body (whatever [`Body::dimension`] says: its `x1` data is dropped).
    pub fn plane(&self) -> ThickBody<S> {
        ThickBody {
            obstacle: self.surface.clone(),
            theta: self.theta,
            thickness: self.thickness,
            material: self.material,
            n2: self.n2,
            n3: self.n3,
            method: self.method,
            volumetric: self.settings.volumetric,
            order: self.settings.order,
            grading: self.settings.grading,
            body_force: self.body_force.clone(),
        }
    }

    /// The 3-D body, `None` in plane strain.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `discretisation.method` for a method
    /// without hexahedra ([`DiscretisationScheme::solid_element`]), or
    /// `discretisation.grading` for a graded mesh (3-D elements are uniform).
    pub fn solid(&self) -> Result<Option<SolidBody<S>>, ElasticityError> {
        let Dimension::Solid { x1, n1, sides } = self.dimension else {
            return Ok(None);
        };
        if !self.settings.grading.is_uniform() {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.grading",
                value: self.settings.grading.ratio(),
                allowed: "1 (uniform) with body.dimension = 3",
            });
        }
        Ok(Some(SolidBody {
            surface: self.surface.clone(),
            x1,
            theta: self.theta,
            thickness: self.thickness,
            material: self.material,
            nodes: [n1, self.n2, self.n3],
            order: self.scheme()?.solid_element()?,
            volumetric: self.settings.volumetric,
            sides,
        }))
    }

    /// The 2-D layout whose extrusion along `x1` carries the 3-D body's hexahedra
    /// ([`DiscretisationScheme::solid_layout`]: `fem-qp-corner`), `None` in plane strain and
    /// for a method on the box grid's nodes.
    ///
    /// # Errors
    /// The registered builder's errors; [`ElasticityError::InvalidParameter`] naming `grid.n2`
    /// or `grid.n3` when the grid does not fit the layout.
    pub fn solid_layout(
        &self,
    ) -> Result<Option<crate::finite_element::high_order::CornerSettings>, ElasticityError> {
        match self.dimension {
            Dimension::Plane => Ok(None),
            Dimension::Solid { .. } => self.scheme()?.solid_layout(self.n2, self.n3),
        }
    }

    /// The assembled contact operator with end loads `tau0`, `tau_max`, of either dimension.
    ///
    /// # Errors
    /// Those of [`Body::solid`], [`ThickBody::discretisation`] and
    /// [`SolidBody::operator`].
    pub fn operator(&self, tau0: f64, tau_max: f64) -> Result<BodyOperator, ElasticityError> {
        self.loaded_operator(&[tau0, tau_max, 1.0])
    }

    /// The assembled operator with the loads of [`ThickBody::loads`] at `magnitudes`
    /// (`[tau0, tau_max]`, then the body force's scale; a missing scale is 0).
    ///
    /// # Errors
    /// As [`Body::operator`].
    pub fn loaded_operator(&self, magnitudes: &[f64]) -> Result<BodyOperator, ElasticityError> {
        let force_scale = magnitudes.get(2).copied().unwrap_or(0.0);
        let force = match &self.body_force {
            Some(f) if force_scale != 0.0 => Some(f.scaled(force_scale)),
            _ => None,
        };
        Ok(match self.solid()? {
            Some(solid) => match self.solid_layout()? {
                Some(layout) => Box::new(solid.corner_operator(
                    layout,
                    &solid.boundary(magnitudes[0], magnitudes[1]),
                    force.as_ref(),
                )?),
                None => Box::new(solid.operator_with_force(
                    magnitudes[0],
                    magnitudes[1],
                    force.as_ref(),
                )?),
            },
            None => {
                let plane = self.plane();
                match self.mesh_operator(|| {
                    plane.problem_scaled(magnitudes[0], magnitudes[1], force_scale)
                })? {
                    Some(mesh) => mesh,
                    None => Box::new(plane.loaded_discretisation(magnitudes)?),
                }
            }
        })
    }

    /// The contact operator of a method on a mesh ([`DiscretisationScheme::is_mesh`]:
    /// `fem-qp-corner`) over the plane problem `problem()`, with the body's own settings (the
    /// corner keys included); `None` for a method on the grid's nodes.
    fn mesh_operator(
        &self,
        problem: impl FnOnce() -> Result<
            crate::plane_problem::PlaneProblem<crate::shell_geometry::SharedChart>,
            ElasticityError,
        >,
    ) -> Result<Option<BodyOperator>, ElasticityError> {
        let scheme = self.scheme()?;
        if !scheme.is_mesh() {
            return Ok(None);
        }
        let mesh = scheme.build_mesh(problem()?)?;
        Ok(Some(Box::new(crate::contact::MeshContactOperator(mesh))))
    }

    /// The assembled contact operator with end loads `tau0`, `tau_max` and a traction-free
    /// contact face (the body of unilateral contact), of either dimension.
    ///
    /// # Errors
    /// See [`Body::operator`].
    pub fn operator_free_face(
        &self,
        tau0: f64,
        tau_max: f64,
    ) -> Result<BodyOperator, ElasticityError> {
        Ok(match self.solid()? {
            Some(solid) => match self.solid_layout()? {
                Some(layout) => Box::new(solid.corner_operator(
                    layout,
                    &solid.boundary_free_face(tau0, tau_max),
                    None,
                )?),
                None => Box::new(solid.operator_free_face(tau0, tau_max)?),
            },
            None => {
                let plane = self.plane();
                let free = || {
                    let mut problem = plane.problem(tau0, tau_max)?;
                    problem.boundary = ThickBody::boundary_free_face(tau0, tau_max);
                    Ok(problem)
                };
                match self.mesh_operator(free)? {
                    Some(mesh) => mesh,
                    None => Box::new(plane.discretisation_free_face(tau0, tau_max)?),
                }
            }
        })
    }

    /// The contact model with the friction law `law` (stick/slip threshold `slip_threshold`),
    /// of either dimension and either [`ContactKind`]: every contact solver takes a bilateral
    /// one, the full-system solvers a unilateral one ([`ContactModel::into_unilateral`]).
    ///
    /// # Errors
    /// See [`Body::operator`], [`ContactModel::new`] and [`ContactModel::into_unilateral`].
    pub fn model<L: FrictionLaw<f64>>(
        &self,
        law: L,
        params: L::Params,
        slip_threshold: f64,
    ) -> Result<ContactModel<BodyOperator, L>, ContactError> {
        self.solid()?; // the 3-D body's own errors before any assembly
        match &self.contact {
            ContactKind::Bilateral if self.body_force.is_none() => ContactModel::new(
                |tau0, tau_max| self.operator(tau0, tau_max),
                law,
                params,
                slip_threshold,
            ),
            ContactKind::Bilateral => Ok(ContactModel::with_loads(
                |m: &[f64]| self.loaded_operator(m),
                &self.plane().loads(),
                law,
                params,
                slip_threshold,
            )?
            .with_fixed_loads(&[1.0])),
            ContactKind::Unilateral { .. } if self.body_force.is_some() => {
                Err(ContactError::Unsupported {
                    field: "loads.body_force",
                    message: "a body force with unilateral contact (contact.kind = \"unilateral\") is not supported yet; remove the body force or use bilateral contact",
                })
            }
            ContactKind::Unilateral { gap } => ContactModel::new(
                |tau0, tau_max| self.operator_free_face(tau0, tau_max),
                law,
                params,
                slip_threshold,
            )?
            .into_unilateral(gap),
        }
    }
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Body<S> {
    /// The contact model with the bulk operator matrix-free (the 3-D body only,
    /// [`SolidBody::matrix_free_loads`]), solved by [`crate::contact::MatrixFreeNewton`].
    ///
    /// # Errors
    /// [`ContactError::Unsupported`] naming `solver.linear` for a plane-strain body, naming
    /// `contact.kind` for unilateral contact, naming `loads.body_force` with a body force; the
    /// body's and the model's errors.
    pub fn matrix_free_model<L: FrictionLaw<f64>>(
        &self,
        law: L,
        params: L::Params,
        slip_threshold: f64,
        multigrid: crate::solid::SolidMultigridParams,
    ) -> Result<ContactModel<BodyOperator, L>, ContactError> {
        boxed_matrix_free_model(
            &self.matrix_free_solid()?,
            law,
            params,
            slip_threshold,
            multigrid,
        )
    }

    /// The 3-D body that [`Body::matrix_free_model`] discretises.
    ///
    /// # Errors
    /// See [`Body::matrix_free_model`].
    fn matrix_free_solid(&self) -> Result<SolidBody<S>, ContactError> {
        let Some(solid) = self.solid()? else {
            return Err(ContactError::Unsupported {
                field: "solver.linear",
                message: "`matrix-free-mg` is the 3-D body's (body.dimension = 3); in plane strain use \"lu\"",
            });
        };
        if self.solid_layout()?.is_some() {
            return Err(ContactError::Unsupported {
                field: "solver.linear",
                message: "the corner-refined 3-D body (discretisation.method = \"fem-qp-corner\") is assembled, not matrix-free: use solver.linear = \"lu\" or \"cholesky\"",
            });
        }
        if self.contact.is_unilateral() {
            return Err(ContactError::Unsupported {
                field: "contact.kind",
                message: "unilateral contact is not solved matrix-free yet; use solver.linear = \"lu\" or \"multigrid\"",
            });
        }
        if self.body_force.is_some() {
            return Err(ContactError::Unsupported {
                field: "loads.body_force",
                message: "a body force is not applied matrix-free yet; use solver.linear = \"lu\" or \"multigrid\"",
            });
        }
        Ok(solid)
    }

    /// The matrix-free Newton of the 3-D body with grid sequencing
    /// ([`SolidBody::solve_matrix_free_sequenced`]), every level's model as
    /// [`Body::matrix_free_model`] builds it.
    ///
    /// # Errors
    /// [`Body::matrix_free_model`]'s refusals; the solve's errors.
    #[allow(clippy::too_many_arguments)]
    pub fn solve_matrix_free_sequenced<L: FrictionLaw<f64> + Clone>(
        &self,
        law: L,
        params: L::Params,
        slip_threshold: f64,
        multigrid: crate::solid::SolidMultigridParams,
        settings: MatrixFreeSettings,
        coarsest_unknowns: usize,
        loads: EndLoads,
        observer: &mut dyn Observer<f64>,
    ) -> Result<MatrixFreeSequenced<BodyOperator, L>, ContactError>
    where
        L::Params: Clone,
    {
        self.matrix_free_solid()?.solve_sequenced_with(
            |body: &SolidBody<S>| {
                boxed_matrix_free_model(
                    body,
                    law.clone(),
                    params.clone(),
                    slip_threshold,
                    multigrid,
                )
            },
            settings,
            coarsest_unknowns,
            loads,
            observer,
        )
    }
}

/// The matrix-free contact model of `solid` with its operator boxed ([`BodyOperator`]).
fn boxed_matrix_free_model<S: Surface<f64> + Clone + Send + Sync + 'static, L: FrictionLaw<f64>>(
    solid: &SolidBody<S>,
    law: L,
    params: L::Params,
    slip_threshold: f64,
    multigrid: crate::solid::SolidMultigridParams,
) -> Result<ContactModel<BodyOperator, L>, ContactError> {
    let loads = solid.matrix_free_loads(multigrid)?;
    ContactModel::new(
        |tau0, tau_max| Ok(Box::new(loads.at(tau0, tau_max)) as BodyOperator),
        law,
        params,
        slip_threshold,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::operator::ContactOperator;
    use capstan_geometry::EllipticalPrism;

    #[test]
    fn finite_differences_have_no_3d_body_and_say_so() {
        let mut body = Body::new(EllipticalPrism::new(2.0, 1.5).unwrap(), 9, 3);
        body.dimension = Dimension::Solid {
            x1: [-0.5, 0.5],
            n1: 3,
            sides: SideFaces::Free,
        };
        let Err(err) = body.operator(1.0, 2.0) else {
            panic!("fd has no hexahedra")
        };
        assert!(
            matches!(
                err,
                ElasticityError::InvalidParameter {
                    field: "discretisation.method",
                    ..
                }
            ),
            "{err}"
        );
        body.method = DiscretisationMethod::FemQ1;
        let op = body.operator(1.0, 2.0).unwrap();
        assert_eq!(op.dof_count(), 3 * 3 * 9 * 3);
        assert!(op.plane().is_none());
        body.dimension = Dimension::Plane;
        let op = body.operator(1.0, 2.0).unwrap();
        assert_eq!(op.dof_count(), 2 * 9 * 3);
        assert_eq!(op.plane().unwrap().grid().n2(), 9);
        assert_eq!(body.dimension.count(), 2);
    }
}
