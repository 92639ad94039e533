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

use capstan_elasticity::contact::{Dimension, slip_transitions};
use capstan_elasticity::finite_element::{DiscretisationMethod, TransitionGrading};
use capstan_elasticity::registration::DiscretisationSettings;
use capstan_geometry::Surface;

use super::builder::Problem;
use super::solve::{ProblemError, Solved, SolvedModel};

/// The grading of the second pass by default: 4 layers of ratio `0.3` on each side of a
/// transition (elements `H 0.3^4 ~ 8e-3 H` at it, `H` the coarse cell).
pub const DEFAULT_TRANSITION_GRADING: (usize, f64) = (4, 0.3);

/// The first pass of the transition-graded ladder ([`Problem::transition_step`]): order 2 on
/// `12 x 2` cells of `fem-qp-corner` (833 nodes). It only locates the stick/slip transitions:
/// on the default scene within 0.02 of the converged ones, its slip measure `3.8e-3` of `pi`
/// off.
pub const TRANSITION_FIRST_PASS: (usize, [usize; 2]) = (2, [12, 2]);

/// The cells of the transition-graded ladder's order steps (`p = 2 ... 10`); past `p = 10`
/// its `h` steps double them in both directions.
pub const TRANSITION_LADDER_CELLS: [usize; 2] = [24, 8];

/// The highest order of the transition-graded ladder (the highest Qp order).
const TRANSITION_MAX_ORDER: usize = 10;

/// The rows toward the contact face of the stop's twin ([`Problem::transition_twin`]): 3 of
/// the transition ratio `0.3`, h28-ref's reference mesh (4 rows stall Newton at `p >= 8`).
pub const TWIN_FACE_LAYERS: usize = 3;

/// The corner layers of the transition-graded ladder's order-`p` step: `p + 3` (of ratio
/// `0.3`: the smallest corner element `0.3^(p+3)` of the cell, `2e-3` at `p = 2`, `1.6e-6` at
/// `p = 8`). hp theory asks for layers growing linearly with `p` (Schwab, section 4.4); with
/// the default 5 layers the order-6 step's max `|v2|` is `1e-5` off and does not settle when
/// the cells are refined (measured: `3.58785e-3` at 5 layers against `3.587884e-3` at 11,
/// where orders 7 ... 10 agree to `1e-8` relative).
pub fn transition_corner_layers(order: usize) -> usize {
    order + 3
}

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
            face_layers: self.body.settings.transitions.face_layers,
        };
        grading.check()?;
        let mut p = self.clone();
        p.body.settings.transitions = grading;
        Ok(p)
    }

    /// The problem with `face_layers` geometric rows toward the contact face (and the opposite
    /// face and the ends, so the corner cells stay square: [`TransitionGrading`]'s
    /// `face_layers`), of the transition grading's ratio; the transition points and layers kept.
    ///
    /// # Math
    /// ```text
    /// rows  x3 = H3 sigma^k, h - H3 sigma^k;  columns  x2 = a + H2 sigma^k, b - H2 sigma^k
    /// k = 1 ... face_layers,  H2, H3 the coarse cell,  sigma the transition ratio (0.3)
    /// ```
    /// The stick zone of the default scene is `0.03` long and the rows `0.125` high on
    /// `24 x 8` cells: its ends are located only to `2.3e-5` by order 6 while the grading
    /// toward them (its points, its layers) moves them by `1e-8`; rows toward the face
    /// resolve it (docs/verification.md, "The contact reference to 1e-7").
    ///
    /// # Errors
    /// As [`Self::graded_toward`]: not `fem-qp-corner`, or `face_layers` over 16.
    pub fn face_graded(&self, face_layers: usize) -> Result<Self, ProblemError> {
        if self.body.method != DiscretisationMethod::FemQpCorner {
            return Err(capstan_elasticity::ElasticityError::InvalidParameter {
                field: "discretisation.method",
                value: f64::NAN,
                allowed: "fem-qp-corner (the mesh graded toward the contact face)",
            }
            .into());
        }
        let mut p = self.clone();
        p.body.settings.transitions.face_layers = face_layers;
        p.body.settings.transitions.check()?;
        Ok(p)
    }

    /// This problem's body on the `fem-qp-corner` mesh of order `order` on `cells` element
    /// cells (`n = p e + 1` nodes per direction), with the default corner layers
    /// ([`DiscretisationSettings::DEFAULT_CORNER_LAYERS`] of
    /// [`DiscretisationSettings::DEFAULT_CORNER_RATIO`]) and no transition grading.
    pub fn corner_mesh(&self, order: usize, cells: [usize; 2]) -> Self {
        let mut q = self.clone();
        q.body.method = DiscretisationMethod::FemQpCorner;
        q.body.settings.order = order;
        q.body.settings.corner_layers = DiscretisationSettings::DEFAULT_CORNER_LAYERS;
        q.body.settings.corner_ratio = DiscretisationSettings::DEFAULT_CORNER_RATIO;
        q.body.settings.transitions = TransitionGrading::NONE;
        q.body.n2 = cells[0] * order + 1;
        q.body.n3 = cells[1] * order + 1;
        q
    }

    /// The first pass of the transition-graded ladder ([`TRANSITION_FIRST_PASS`]).
    pub fn transition_first_pass(&self) -> Self {
        let (order, cells) = TRANSITION_FIRST_PASS;
        self.corner_mesh(order, cells)
    }

    /// Step `k` of the transition-graded ladder of the contact quantities: `fem-qp-corner`
    /// with its `x2` lines graded toward `transitions` by [`DEFAULT_TRANSITION_GRADING`]
    /// (the accuracy target passes the first pass's transitions at `k = 0`, and the ones step
    /// `k - 1` located after that: `capstan::commands::accuracy::contact_to`).
    ///
    /// # Math
    /// ```text
    /// k = 0 ... 8:   order p = 2 + k on 24 x 8 cells, p + 3 corner layers of 0.3
    /// k = 9, 10, ...: p = 10 on (24 x 8) 2^(k-8) cells, 13 corner layers
    /// ```
    /// Every step has an element line at each transition with 4 geometric layers of ratio
    /// `0.3` on both sides, so the kink of the friction traction at `|u| = eps` lies on (within
    /// the previous step's location error of) an element line, and the slip measure and the
    /// stick-zone ends converge geometrically in `p` where the uniform interior of the hp
    /// ladder ([`Self::accuracy_step`]) stalls: the stick zone (~0.03 long) is under half an
    /// element there. The corner layers grow with `p`
    /// ([`transition_corner_layers`]) for the end corners' singular stresses.
    ///
    /// # Errors
    /// [`ProblemError::Elasticity`] naming `body.dimension` for a 3-D body (the ladder is
    /// plane strain), or [`Self::graded_toward`]'s (a non-finite transition).
    pub fn transition_step(&self, k: usize, transitions: &[f64]) -> Result<Self, ProblemError> {
        self.transition_step_on(k, transitions, TRANSITION_LADDER_CELLS)
    }

    /// [`Self::transition_step`] with the order steps on `cells` instead of
    /// [`TRANSITION_LADDER_CELLS`] (a cheaper ladder for tests and quick studies).
    ///
    /// # Errors
    /// As [`Self::transition_step`].
    pub fn transition_step_on(
        &self,
        k: usize,
        transitions: &[f64],
        cells: [usize; 2],
    ) -> Result<Self, ProblemError> {
        if self.body.dimension != Dimension::Plane {
            return Err(capstan_elasticity::ElasticityError::InvalidParameter {
                field: "body.dimension",
                value: 3.0,
                allowed: "2 (the transition-graded ladder is plane strain)",
            }
            .into());
        }
        let order = (2 + k).min(TRANSITION_MAX_ORDER);
        let h = k.saturating_sub(TRANSITION_MAX_ORDER - 2);
        let mut q = self.corner_mesh(order, cells.map(|c| c << h));
        q.body.settings.corner_layers = transition_corner_layers(order);
        let (layers, ratio) = DEFAULT_TRANSITION_GRADING;
        q.graded_toward(transitions.to_vec(), layers, ratio)
    }

    /// The twin of a step of the transition-graded ladder ([`Self::transition_step`]): the same
    /// order, cells, corner layers and transition grading with [`TWIN_FACE_LAYERS`] rows toward
    /// the contact face ([`Self::face_graded`]). The accuracy target solves it at the stop and
    /// takes `SAFETY |Q_k - Q'_k|` as every quantity's estimate (`capstan::problem::estimate`,
    /// "The twin at the stop").
    ///
    /// # Math
    /// The rows refine the stop's mesh where its error lives: the band at the contact face,
    /// where the `0.03`-long stick zone sits in rows `0.125` high on `24 x 8` cells, and the
    /// corner cells (squares of side `H 0.3^3` with the corner layers inside). On the default
    /// scene the twin of the order-4 step has the stick ends 160x ... 200x closer and the
    /// smooth quantities (displacements, probe stresses) at 0.12 ... 0.55 times the step's errors,
    /// max `|v3|` aside (3.7 times: the step landed `1.3e-7` from its limit); its unknowns are
    /// 1.8x the step's (docs/verification.md, "The transition-graded ladder").
    ///
    /// # Errors
    /// As [`Self::face_graded`] (not `fem-qp-corner`).
    pub fn transition_twin(&self) -> Result<Self, ProblemError> {
        self.face_graded(TWIN_FACE_LAYERS)
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
