//! Refinement toward the stick/slip transitions: a two-pass solve on the corner mesh
//! (`fem-qp-corner`), the first locating the transitions, the second with its `x2` element
//! lines graded toward them ([`TransitionGrading`]).
//!
//! # Why
//! Where the slip `|u|` crosses the regularisation width `eps` the friction traction has a kink
//! (`|t_T|` reaches `mu |sigma_n|`), so the displacement is not smooth there and Qp elements
//! spanning a transition converge only algebraically; the slip measure (the length of the
//! slipping set) inherits that rate. With an element line at each transition and geometric
//! layers toward it, every element sees a smooth field again (the hp mesh of a point
//! singularity: Schwab, *p- and hp-FEM*, section 4.4).

use capstan_elasticity::contact::slip_transitions;
use capstan_elasticity::finite_element::{DiscretisationMethod, TransitionGrading};
use capstan_geometry::Surface;

use super::builder::Problem;
use super::solve::{ProblemError, Solved, SolvedModel};

/// The grading of the second pass by default: 4 layers of ratio `0.3` on each side of a
/// transition (elements `H 0.3^4 ~ 8e-3 H` at it, `H` the coarse cell).
pub const DEFAULT_TRANSITION_GRADING: (usize, f64) = (4, 0.3);

/// The two passes of [`Problem::solve_transition_graded`].
#[derive(Debug)]
pub struct TwoPass {
    /// The first solve (the problem as given).
    pub first: Solved,
    /// The transitions it located (`x2`, increasing).
    pub transitions: Vec<f64>,
    /// The second solve, graded toward `transitions`.
    pub second: Solved,
}

impl SolvedModel {
    /// The stick/slip transitions of `solution` (a plane-strain solution of this model):
    /// [`slip_transitions`]; empty in 3-D.
    pub fn transitions(&self, solution: &capstan_elasticity::contact::ContactSolution) -> Vec<f64> {
        match self {
            Self::Body(m) => slip_transitions(m, solution),
            Self::Sequenced(m) => slip_transitions(m, solution),
        }
    }
}

impl Solved {
    /// The stick/slip transitions of the solution (`x2`, increasing; empty in 3-D or without
    /// a transition).
    pub fn transitions(&self) -> Vec<f64> {
        self.model.transitions(&self.solution)
    }
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// The problem with `fem-qp-corner`'s `x2` lines graded toward `points` with `layers`
    /// layers of ratio `ratio` on each side ([`TransitionGrading`]).
    ///
    /// # Errors
    /// [`ProblemError::Elasticity`] (`InvalidParameter`) naming `discretisation.method` when
    /// the method is not `fem-qp-corner` (the only mesh that grades toward interior points),
    /// or the grading's out-of-range field ([`TransitionGrading::check`]).
    pub fn graded_toward(
        &self,
        points: Vec<f64>,
        layers: usize,
        ratio: f64,
    ) -> Result<Self, ProblemError> {
        if self.body.method != DiscretisationMethod::FemQpCorner {
            return Err(capstan_elasticity::ElasticityError::InvalidParameter {
                field: "discretisation.method",
                value: f64::NAN,
                allowed: "fem-qp-corner (the mesh graded toward the stick/slip transitions)",
            }
            .into());
        }
        let grading = TransitionGrading {
            points,
            layers,
            ratio,
        };
        grading.check()?;
        let mut p = self.clone();
        p.body.settings.transitions = grading;
        Ok(p)
    }

    /// Two passes: solves the problem, locates its stick/slip transitions
    /// ([`Solved::transitions`]) and solves again on the mesh graded toward them with `layers`
    /// layers of ratio `ratio` ([`Self::graded_toward`]). Without a transition the second pass
    /// is the first problem again.
    ///
    /// # Errors
    /// The solves' errors; [`Self::graded_toward`]'s.
    pub fn solve_transition_graded(
        &self,
        layers: usize,
        ratio: f64,
    ) -> Result<TwoPass, ProblemError> {
        self.solve_graded_after(self, layers, ratio)
    }

    /// Two passes with a first pass of its own: solves `first` (e.g. a coarser, lower-order
    /// mesh of the same body: it only has to locate the transitions), then this problem graded
    /// toward `first`'s transitions ([`Self::graded_toward`]). On the default scene a first
    /// pass of order 2 on `12 x 2` cells (833 nodes) places the two transitions within 0.02 of
    /// the converged ones, and order 4 on `24 x 8` cells graded toward them has the slip
    /// measure within `4e-5` of `pi` of the reference (docs/verification.md).
    ///
    /// # Errors
    /// The solves' errors; [`Self::graded_toward`]'s.
    pub fn solve_graded_after(
        &self,
        first: &Self,
        layers: usize,
        ratio: f64,
    ) -> Result<TwoPass, ProblemError> {
        let first = first.solve()?;
        let transitions = first.transitions();
        let second = self
            .graded_toward(transitions.clone(), layers, ratio)?
            .solve()?;
        Ok(TwoPass {
            first,
            transitions,
            second,
        })
    }
}
