//! A manufactured Signorini (unilateral contact) problem with a known contact/separation
//! split: the exact solution is the smooth manufactured field of [`PrismMms`], the data
//! (a normal load on the contact face and the initial gap) make it the solution of a
//! Signorini problem that touches the obstacle on `x2 < c` and has lifted off on `x2 > c`.

use std::sync::Arc;

use capstan_friction::{FrictionLaw, Frictionless};

use super::samples::{
    ManufacturedField, MmsBoundaries, PrismMms, TrigonometricExact, displacement_error,
};
use crate::boundary::{
    BoundaryConditions, BoundaryFunction, Component, ComponentCondition, Side, SideCondition,
    X2Ends,
};
use crate::contact::{ContactError, ContactModel, EndLoads, Gap};
use crate::discretisation::Discretisation;
use crate::error::ElasticityError;
use crate::finite_element::DiscretisationMethod;
use crate::plane_problem::BodyForce;
use crate::registration::PlaneOperator;
use crate::verification::GridLevel;

/// A manufactured Signorini problem on a prism (frictionless), with the split at `x2 = c`.
///
/// # Math
/// `U` is the manufactured field of [`PrismMms`] (the trigonometric field, `U^3 = 0` on
/// `x3 = 0`), `f = -nabla . T(U)` its forcing, Dirichlet data from `U` at both `x2` ends, the
/// traction of `U` on `x3 = h` and the tangential traction of `U` on `x3 = 0`. On the contact
/// face the data are
/// ```text
/// applied normal traction   t_3 = n_i T^i_3(U) - p(x2),   p(x2) = P max(c - x2, 0)^2
/// initial gap               g(x2) = -U^3(x2, 0) + d(x2),  d(x2) = D max(x2 - c, 0)^2
/// ```
/// so that `U` balances the applied loads plus the contact pressure `p >= 0` (on the body,
/// `t_3 = +p` pushes it off the obstacle). Signorini holds for `U`: on `x2 < c` the opening
/// `U^3 + g = d = 0` and the reaction is `p > 0` (contact); on `x2 > c` the opening is
/// `d > 0` and the reaction `p = 0` (separated). `p` and `d` are `C^1` at the split, so the
/// discrete solution converges at the element's order, the active set being wrong at most in
/// a band of a few nodes around `c` where both `p` and `d` are `O(h^2)`.
#[derive(Debug, Clone)]
pub struct SignoriniMms {
    /// The prism, field, material and domain (its boundaries are replaced as above).
    pub mms: PrismMms,
    /// `c`: contact on `x2 < c`, separated on `x2 > c`.
    pub split: f64,
    /// `P` (traction per squared length).
    pub pressure: f64,
    /// `D` (per length).
    pub opening: f64,
}

impl Default for SignoriniMms {
    /// The ellipse `a = 1`, `b = 1/2` of the convergence studies (`x2 in [-1.2, 1]`, `h = 1/2`,
    /// `E = 10`, `nu = 0.3`) with the split at `c = 0.1`, `P = 2`, `D = 0.05`.
    fn default() -> Self {
        Self {
            mms: PrismMms::ellipse(0.5, MmsBoundaries::TractionContact),
            split: 0.1,
            pressure: 2.0,
            opening: 0.05,
        }
    }
}

/// The errors of one [`SignoriniMms`] solve.
#[derive(Debug, Clone, PartialEq)]
pub struct SignoriniPoint {
    /// The grid.
    pub level: GridLevel,
    /// `dx2`.
    pub h: f64,
    /// Max over the nodes of the Cartesian displacement error.
    pub max_error: f64,
    /// Max over the nodes with `|x2 - c| >= away` ([`SignoriniMms::run`]).
    pub max_error_away: f64,
    /// `x2` of the last contact node and of the first separated one on `x3 = 0` (the
    /// discrete split, bracketing `c`), `None` when the face is not split in two.
    pub split: Option<[f64; 2]>,
    /// Newton iterations.
    pub newton_iterations: usize,
}

impl SignoriniMms {
    /// `p(x2)`, the contact pressure of the exact solution.
    pub fn contact_pressure(&self, x2: f64) -> f64 {
        self.pressure * (self.split - x2).max(0.0).powi(2)
    }

    /// `d(x2)`, the opening of the exact solution.
    pub fn exact_opening(&self, x2: f64) -> f64 {
        self.opening * (x2 - self.split).max(0.0).powi(2)
    }

    /// The initial gap `g(x2) = -U^3(x2, 0) + d(x2)`.
    pub fn gap(&self, exact: &Arc<TrigonometricExact>) -> Gap {
        let (ex, this) = (Arc::clone(exact), self.clone());
        Gap::new(move |x: [f64; 2]| {
            this.exact_opening(x[1]) - ex.field.displacement([x[1], 0.0]).value[1]
        })
    }

    /// The frictionless unilateral contact model of `method` on `level`, with its exact
    /// solution: all data in the first load (`tau0`, solve with `EndLoads::new(1.0, 0.0)`),
    /// the second load zero.
    ///
    /// # Errors
    /// Grid, geometry and discretisation errors; those of
    /// [`ContactModel::into_unilateral`].
    pub fn model(
        &self,
        method: DiscretisationMethod,
        level: GridLevel,
    ) -> Result<
        (
            ContactModel<PlaneOperator, Frictionless>,
            Arc<TrigonometricExact>,
        ),
        ContactError,
    > {
        self.model_with(method, level, Frictionless, (), 1.0)
    }

    /// [`SignoriniMms::model`] with the friction law `law` on the contact part (stick/slip
    /// threshold `slip_threshold`) on top of the manufactured tangential traction: a
    /// frictional Signorini problem held at both ends (no rigid mode), whose solution is no
    /// longer `U`.
    ///
    /// # Errors
    /// See [`SignoriniMms::model`].
    pub fn model_with<L: FrictionLaw<f64>>(
        &self,
        method: DiscretisationMethod,
        level: GridLevel,
        law: L,
        params: L::Params,
        slip_threshold: f64,
    ) -> Result<(ContactModel<PlaneOperator, L>, Arc<TrigonometricExact>), ContactError> {
        let (parts, exact) = self.mms.parts(level)?;
        let base = parts.boundary.clone();
        let force = parts.body_force.clone();
        let grid = parts.grid;
        let build = |m: &[f64]| -> Result<PlaneOperator, ElasticityError> {
            let s = m[0];
            let mut problem = parts.clone();
            problem.boundary = self.scaled_boundary(&base, &exact, &grid, s);
            problem.body_force = force
                .clone()
                .map(|f| -> BodyForce { Arc::new(move |x| f(x).map(|y| s * y)) });
            method.build(problem)
        };
        let model = ContactModel::with_loads(
            build,
            &["mms.data", "mms.zero"],
            law,
            params,
            slip_threshold,
        )?;
        let model = model.into_unilateral(&self.gap(&exact))?;
        Ok((model, exact))
    }

    /// The boundary of [`SignoriniMms`] times `s`.
    fn scaled_boundary(
        &self,
        base: &BoundaryConditions,
        exact: &Arc<TrigonometricExact>,
        grid: &crate::grid::Grid,
        s: f64,
    ) -> BoundaryConditions {
        let scale = |c: &ComponentCondition| -> ComponentCondition {
            let f = match c {
                ComponentCondition::Displacement(f)
                | ComponentCondition::Traction(f)
                | ComponentCondition::Stress(f) => f.clone(),
            };
            let g = BoundaryFunction::new(move |x| s * f.eval(x));
            match c {
                ComponentCondition::Displacement(_) => ComponentCondition::Displacement(g),
                ComponentCondition::Traction(_) => ComponentCondition::Traction(g),
                ComponentCondition::Stress(_) => ComponentCondition::Stress(g),
            }
        };
        let side = |c: &SideCondition| SideCondition([scale(&c.0[0]), scale(&c.0[1])]);
        let x2 = match &base.x2 {
            X2Ends::Sides { min, max } => X2Ends::Sides {
                min: side(min),
                max: side(max),
            },
            X2Ends::Periodic => X2Ends::Periodic,
        };
        let (ex, this, grid) = (Arc::clone(exact), self.clone(), *grid);
        let normal = BoundaryFunction::new(move |x2: f64| {
            let point = Side::X3Min.point(&grid, x2);
            let t = ex
                .traction(Side::X3Min, point)
                .map_or(f64::NAN, |t| t[Component::X3.index()]);
            s * (t - this.contact_pressure(point[0]))
        });
        BoundaryConditions {
            x2,
            x3_min: SideCondition([
                scale(base.x3_min.component(Component::X2)),
                ComponentCondition::Traction(normal),
            ]),
            x3_max: side(&base.x3_max),
            pinned: base.pinned.clone(),
        }
    }

    /// Solves on `level` with the full-system (semismooth) Newton and measures the errors;
    /// `away` is the distance from the split beyond which `max_error_away` is taken.
    ///
    /// # Errors
    /// See [`SignoriniMms::model`]; solver failures.
    pub fn run(
        &self,
        method: DiscretisationMethod,
        level: GridLevel,
        away: f64,
    ) -> Result<SignoriniPoint, ContactError> {
        use crate::contact::{FullSystemSettings, FullSystemSolver, SEPARATED};
        let (model, exact) = self.model(method, level)?;
        let solution = FullSystemSolver::new(&model, FullSystemSettings::default())?
            .solve(EndLoads::new(1.0, 0.0))?;
        let disc = model.discretisation();
        let v = &solution.displacement;
        let [max_error, _] = displacement_error(disc, v, &exact.field)?;
        let grid = *disc.grid();
        let fields = disc.fields(v)?;
        let mut max_error_away = 0.0f64;
        for k in 0..grid.node_count() {
            let node = grid.node(k);
            let x = grid.coordinates(node);
            if (x[0] - self.split).abs() < away {
                continue;
            }
            let u = exact.field.displacement(x).value;
            let (d, sc) = (fields.displacement[k], fields.scale[k]);
            let e = ((sc[1] * (d[0] - u[0])).powi(2) + (sc[2] * (d[1] - u[1])).powi(2)).sqrt();
            max_error_away = max_error_away.max(e);
        }
        let p = &solution.contact;
        let separated: Vec<bool> = p
            .separated
            .clone()
            .unwrap_or_else(|| p.state.iter().map(|&s| s == SEPARATED).collect());
        let switches = separated.windows(2).filter(|w| w[0] != w[1]).count();
        let split = match separated.iter().position(|&s| s) {
            Some(i) if i > 0 && switches == 1 => Some([p.x2[i - 1], p.x2[i]]),
            _ => None,
        };
        Ok(SignoriniPoint {
            level,
            h: grid.dx2(),
            max_error,
            max_error_away,
            split,
            newton_iterations: solution.stats.newton_iterations,
        })
    }
}
