//! The paper's thick body on a prism, discretised by finite differences: the convenience
//! builder of contact models.

use capstan_friction::FrictionLaw;
use capstan_geometry::{Obstacle, ShellChart};

use crate::boundary::{BoundaryConditions, BoundaryFunction, SideCondition, X2Ends};
use crate::contact::error::ContactError;
use crate::contact::model::ContactModel;
use crate::error::ElasticityError;
use crate::finite_difference::FiniteDifferenceNavier;
use crate::grid::Grid;
use crate::material::Material;

/// A plane-strain body of thickness `h` on `x2 in [theta0, theta1]` of a prism obstacle,
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
#[derive(Debug, Clone)]
pub struct ThickBody {
    /// The obstacle (a prism).
    pub obstacle: Obstacle,
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
}

/// The discretisation [`ThickBody`] builds.
pub type ThickBodyOperator = FiniteDifferenceNavier<ShellChart<Obstacle>>;

impl ThickBody {
    /// The paper's body: ellipse `a = b = 2` (a circle), `h = 1`, `E = 1e3`, `nu = 1/4`,
    /// `x2 in [-pi/2, pi/2]`, on an `n2 x n3` grid.
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn paper(n2: usize, n3: usize) -> Result<Self, ElasticityError> {
        let half = core::f64::consts::FRAC_PI_2;
        Ok(Self {
            obstacle: Obstacle::Ellipse(capstan_geometry::EllipticalPrism::new(2.0, 2.0)?),
            theta: [-half, half],
            thickness: 1.0,
            material: Material::new(1e3, 0.25)?,
            n2,
            n3,
        })
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

    /// The finite-difference operator with end loads `tau0`, `tau_max`.
    ///
    /// # Errors
    /// Grid, geometry or boundary errors.
    pub fn discretisation(
        &self,
        tau0: f64,
        tau_max: f64,
    ) -> Result<ThickBodyOperator, ElasticityError> {
        let grid = Grid::new(self.theta, self.thickness, self.n2, self.n3, false)?;
        FiniteDifferenceNavier::new(
            ShellChart::new(self.obstacle.clone()),
            self.material,
            grid,
            Self::boundary(tau0, tau_max),
            None,
        )
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
    ) -> Result<ContactModel<ThickBodyOperator, L>, ContactError> {
        ContactModel::new(
            |tau0, tau_max| self.discretisation(tau0, tau_max),
            law,
            params,
            slip_threshold,
        )
    }
}
