//! The paper's thick body on a prism, discretised by finite differences or finite elements
//! (`discretisation.method`): the convenience builder of contact models.

use capstan_friction::FrictionLaw;
use capstan_geometry::{Obstacle, ShellChart};

use crate::boundary::Component;
use crate::boundary::{BoundaryConditions, BoundaryFunction, SideCondition, X2Ends};
use crate::contact::error::ContactError;
use crate::contact::model::ContactModel;
use crate::discretisation::{ContactNode, Discretisation, LinearSystem};
use crate::error::ElasticityError;
use crate::fields::NodalFields;
use crate::finite_difference::FiniteDifferenceNavier;
use crate::finite_element::{
    DiscretisationMethod, FiniteElementNavier, Grading, HighOrderNavier, QpSettings,
    VolumetricIntegration,
};
use crate::grid::Grid;
use crate::material::Material;
use crate::plane_problem::PlaneProblem;

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
    /// The discretisation (`fd` by default; `fem-q2` needs odd `n2`, `n3`).
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
}

/// The discretisation [`ThickBody`] builds: finite differences or finite elements of the same
/// operator on the same nodes, behind [`Discretisation`].
#[derive(Debug)]
pub enum ThickBodyOperator {
    /// `discretisation.method = fd`.
    FiniteDifference(FiniteDifferenceNavier<ShellChart<Obstacle>>),
    /// `discretisation.method = fem-q1 | fem-q2`.
    FiniteElement(FiniteElementNavier<ShellChart<Obstacle>>),
    /// `discretisation.method = fem-qp`.
    HighOrder(Box<HighOrderNavier<ShellChart<Obstacle>>>),
}

/// Forwards a [`Discretisation`] call to the operator inside.
macro_rules! forward {
    ($self:ident, $op:ident => $call:expr) => {
        match $self {
            ThickBodyOperator::FiniteDifference($op) => $call,
            ThickBodyOperator::FiniteElement($op) => $call,
            ThickBodyOperator::HighOrder($op) => $call,
        }
    };
}

impl Discretisation for ThickBodyOperator {
    fn method(&self) -> &'static str {
        forward!(self, op => op.method())
    }

    fn grid(&self) -> &Grid {
        forward!(self, op => op.grid())
    }

    fn dof_count(&self) -> usize {
        forward!(self, op => op.dof_count())
    }

    fn lu_ordering(&self) -> capstan_solvers::ColumnOrdering {
        forward!(self, op => op.lu_ordering())
    }

    #[track_caller]
    fn dof(&self, node: [usize; 2], component: Component) -> usize {
        forward!(self, op => op.dof(node, component))
    }

    fn node_position(&self, node: [usize; 2]) -> [f64; 2] {
        forward!(self, op => op.node_position(node))
    }

    fn entries(&self) -> Result<Vec<(usize, usize)>, ElasticityError> {
        forward!(self, op => op.entries())
    }

    fn fill_values(
        &self,
        add: &mut dyn FnMut(usize, f64),
        rhs: &mut [f64],
    ) -> Result<(), ElasticityError> {
        forward!(self, op => op.fill_values(add, rhs))
    }

    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        forward!(self, op => op.contact_nodes())
    }

    fn fields(&self, v: &[f64]) -> Result<NodalFields, ElasticityError> {
        forward!(self, op => op.fields(v))
    }

    fn system(&self) -> Result<LinearSystem, ElasticityError> {
        forward!(self, op => op.system())
    }

    fn refill(&self, system: &mut LinearSystem) -> Result<(), ElasticityError> {
        forward!(self, op => op.refill(system))
    }

    fn solve(
        &self,
        solver: &mut dyn capstan_solvers::LinearSolver<f64>,
    ) -> Result<Vec<f64>, ElasticityError> {
        forward!(self, op => op.solve(solver))
    }
}

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
            method: DiscretisationMethod::Fd,
            volumetric: VolumetricIntegration::Full,
            order: DiscretisationMethod::DEFAULT_ORDER,
            grading: Grading::UNIFORM,
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

    /// The operator of [`ThickBody::method`] with end loads `tau0`, `tau_max`.
    ///
    /// # Errors
    /// Grid, geometry or boundary errors; [`ElasticityError::InvalidParameter`] for a reduced
    /// volumetric integration with finite differences, or naming `discretisation.grading` for a
    /// graded body of another method than `fem-qp`.
    pub fn discretisation(
        &self,
        tau0: f64,
        tau_max: f64,
    ) -> Result<ThickBodyOperator, ElasticityError> {
        let problem = PlaneProblem {
            chart: ShellChart::new(self.obstacle.clone()),
            material: self.material,
            grid: Grid::new(self.theta, self.thickness, self.n2, self.n3, false)?,
            boundary: Self::boundary(tau0, tau_max),
            body_force: None,
        };
        if self.method == DiscretisationMethod::FemQp {
            let settings = QpSettings {
                order: self.order,
                volumetric: self.volumetric,
                grading: self.grading,
            };
            return Ok(ThickBodyOperator::HighOrder(Box::new(
                HighOrderNavier::with_settings(problem, settings)?,
            )));
        }
        if !self.grading.is_uniform() {
            return Err(ElasticityError::InvalidParameter {
                field: "discretisation.grading",
                value: self.grading.ratio(),
                allowed: "1 (uniform) unless discretisation.method = fem-qp",
            });
        }
        Ok(match self.method.element_order() {
            None if self.volumetric != VolumetricIntegration::Full => {
                return Err(ElasticityError::InvalidParameter {
                    field: "discretisation.volumetric",
                    value: f64::NAN,
                    allowed: "full with finite differences (reduced needs fem-q1 or fem-q2)",
                });
            }
            None => ThickBodyOperator::FiniteDifference(FiniteDifferenceNavier::new(problem)?),
            Some(order) => ThickBodyOperator::FiniteElement(FiniteElementNavier::with_volumetric(
                problem,
                order,
                self.volumetric,
            )?),
        })
    }

    /// The body on the next coarser grid of grid sequencing: `n -> (n + 1) / 2` nodes per
    /// direction (every other node of an odd `n`), kept odd for `fem-q2`; `None` when a
    /// direction would fall below 5 nodes (9 for `fem-q2`). `fem-qp`: half the elements
    /// (`n = p e + 1 -> p e / 2 + 1`, `e` even, at least 2 elements left).
    ///
    /// A graded body ([`ThickBody::grading`] not uniform) has no coarser level, so grid
    /// sequencing solves it on its own grid directly: halving the elements of a geometric mesh
    /// keeps the layers but moves every middle boundary, and the level-to-level transfer
    /// ([`crate::discretisation::interpolate_nodal`]) interpolates on the uniform grid lines,
    /// not the graded node positions, so the start would be the coarse field at the wrong
    /// places.
    pub fn coarser(&self) -> Option<ThickBody> {
        if !self.grading.is_uniform() {
            return None;
        }
        if self.method == DiscretisationMethod::FemQp {
            let p = self.order.max(1);
            let halve = |n: usize| {
                let e = (n - 1) / p;
                (e.is_multiple_of(2) && e >= 4 && (n - 1).is_multiple_of(p))
                    .then_some(p * e / 2 + 1)
            };
            return Some(ThickBody {
                n2: halve(self.n2)?,
                n3: halve(self.n3)?,
                ..self.clone()
            });
        }
        let q2 = self.method == DiscretisationMethod::FemQ2;
        let halve = |n: usize| {
            let c = n.div_ceil(2);
            let c = if q2 && c.is_multiple_of(2) { c + 1 } else { c };
            (c >= if q2 { 9 } else { 5 } && c < n).then_some(c)
        };
        Some(ThickBody {
            n2: halve(self.n2)?,
            n3: halve(self.n3)?,
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
    ) -> Result<ContactModel<ThickBodyOperator, L>, ContactError> {
        ContactModel::new(
            |tau0, tau_max| self.discretisation(tau0, tau_max),
            law,
            params,
            slip_threshold,
        )
    }
}
