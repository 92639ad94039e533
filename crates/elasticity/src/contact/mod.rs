//! Frictional contact of the thick body with a rough rigid prism: the paper's section 3
//! (Kikuchi–Oden regularised Coulomb friction in curvilinear coordinates), on any
//! [`crate::Discretisation`].
//!
//! # Math
//! Bilateral contact on `x3 = 0` (`v^3 = 0`) with a pointwise friction law for the tangential
//! traction (paper eq. CoulombOden3, derived again here):
//! ```text
//! A v - b(tau) - sum_k w_k e_row_k t_2,k(v) = 0
//! t_2 = sqrt(g_22) t(u, sigma_n),  u = sqrt(g_22) v^2,  sigma_n = n.T.n = T^3_3   (n = -g^3)
//! regularised Coulomb: t = mu sigma_n u / max(|u|, eps)   (opposes u when sigma_n < 0)
//! ```
//! Stick/slip per node: `+1` if `u >= eps`, `-1` if `u <= -eps`, else `0`; the paper's Slip is
//! their mean over the contact nodes.
//!
//! # Solvers
//! - [`BoundarySolver`]: the bulk is linear, so it is factorised once and the problem is
//!   condensed onto the `m` contact tractions (dense `m x m` Newton with line search and load
//!   continuation). One factorisation serves every tension ratio.
//! - [`FullSystemSolver`]: Newton on the whole residual with the friction Jacobian, LU
//!   refactorised each step, or the paper's Jacobi–Newton; the cross-check and the baseline.
//!
//! # Limiting equilibrium
//! On a circle the bilaterally constrained body can rotate rigidly; only friction holds it.
//! [`BoundarySolver`] detects the sliding mode (a singular frictionless condensed operator),
//! computes the limiting tension ratios from the solvability of the full-slip system, and
//! reports loads beyond them as [`ContactError::NoEquilibrium`] instead of iterating.
//!
//! # Bodies
//! Any [`ContactOperator`]: the plane-strain body of every [`crate::Discretisation`]
//! ([`ThickBody`]) and the 3-D body ([`crate::solid::SolidBody`]), whose contact nodes carry
//! two tangential entries (`v^1`, `v^2`) that the law sees as one 2-component physical slip in
//! the tangent plane (the condensed system is `2m x 2m` for `m` contact nodes).
//!
//! # Unilateral contact
//! [`ContactKind::Unilateral`] (Signorini, with a [`Gap`]) replaces `v^3 = 0` by the rows
//! `d_k min(v^3_k + g_k, lambda_k)` (`lambda_k` the contact reaction from the free normal
//! balance row; see [`ContactModel::into_unilateral`]); [`FullSystemSolver`] solves it as a
//! semismooth Newton method and reports each iterate's active set (stick, slip, separated);
//! [`BoundarySolver`] refuses it.
//!
//! # Load paths with memory
//! [`solve_path`] solves a sequence of load states quasi-statically, each from the previous
//! state, with friction acting on the slip increment of each step
//! ([`ContactModel::with_slip_reference`]): on the condensed solver, whose condensation serves
//! every step, or on the full-system Newton (exact friction, unilateral contact).
//!
//! # Limitations
//! One friction law with one parameter set for the whole contact surface; tensile normal
//! stress on the bilateral contact is not excluded (counted in
//! [`ContactSolution::tensile_contact_nodes`]; unilateral contact excludes it). The limiting ratios assume that at full slip
//! every contact point slides along the rigid mode (true in plane strain); on a 3-D body whose
//! full slip is not rigid (a band on a cone also slides towards the apex) the full-slip
//! balance has no positive ratio and the limits are reported unbounded. One rigid mode is
//! handled: a circular cylinder of finite width with free sides (rotation and axial
//! translation) is not supported yet.

mod any_body;
mod body;
mod body_force;
mod boundary_solver;
mod bulk_multigrid;
mod error;
mod exact_friction;
mod full_system;
mod load_continuation;
mod loads;
mod matrix_free_newton;
mod mesh_operator;
mod model;
mod operator;
mod owned_rows;
mod path;
mod pattern;
mod quantities;
mod ratio_arclength;
mod run_off;
mod solid_body;
mod solid_corner;
mod solid_matrix_free;
mod solid_operator;
mod solid_sequencing;
mod solution;
mod threshold;
mod unilateral;
mod unilateral_limits;

pub use any_body::{Body, Dimension};
pub use body::{ThickBody, ThickBodyOperator};
pub use body_force::BodyForceField;
pub use boundary_solver::exact_start::{
    EXACT_START_TOLERANCE, EXACT_START_TOLERANCE_SLIDING, StartedExactFace,
};
pub use boundary_solver::semismooth::ExactFaceSolution;
pub use boundary_solver::{
    BoundarySolver, CONDENSED_SEMISMOOTH, ContactSettings, SetupStats, SlidingMode,
};
pub use error::{ContactError, ContactErrorKind};
pub use full_system::{
    FullSystemProblem, FullSystemSettings, FullSystemSolver, SEQUENCING_COARSEST_NODES, Sequenced,
    solve_sequenced,
};
pub use loads::{BODY_FORCE, END_LOADS, EndLoads};
pub use matrix_free_newton::{MatrixFreeNewton, MatrixFreeSettings};
pub use mesh_operator::MeshContactOperator;
pub use model::{ContactModel, ExactRows, SiteTraction};
pub use operator::{BodyOperator, ContactOperator, Extremum, MatrixFreeBulk};
pub use path::{PathSolver, PathStep, solve_path, solve_path_silent};
pub use quantities::{
    ContactQuantities, NormalStressProbe, default_probes, interpolate, slip_transitions,
};
pub use run_off::{RunOff, RunOffEnd, RunOffSettings, RunOffTrial};
pub use solid_matrix_free::{MatrixFreeLoads, SolidMatrixFreeBody};
pub use solid_sequencing::{MatrixFreeSequenced, SEQUENCE_COARSEST_UNKNOWNS};
pub use solution::{
    ContactProfile, ContactSolution, SEPARATED, SolidContactProfile, SolveStats, StateInterval,
    classify, state_intervals,
};
pub use threshold::{ThresholdResult, ThresholdSettings, solve_below_threshold, threshold_ratio};
pub use unilateral::{ContactKind, Gap};
pub use unilateral_limits::{
    FULL_SLIP_NEWTON_ITERATIONS, FullSlip, FullSlipEnd, LimitingRange, RIGID_MODE_DEFECT,
};

/// Makes faer's dense and sparse kernels sequential (`Par::Seq`), for callers that run many
/// contact solves in parallel themselves (rayon sweeps): avoids oversubscription.
pub fn sequential_linear_algebra() {
    faer::set_global_parallelism(faer::Par::Seq);
}

/// faer's global parallelism before [`sequential_linear_algebra_scope`], set back when this
/// guard is dropped.
#[must_use = "the previous parallelism is restored when the guard is dropped"]
#[derive(Debug)]
pub struct LinearAlgebraParallelism(faer::Par);

impl Drop for LinearAlgebraParallelism {
    fn drop(&mut self) {
        faer::set_global_parallelism(self.0);
    }
}

/// As [`sequential_linear_algebra`] for the lifetime of the returned guard only: a sweep in a
/// long-lived process (the Python package) leaves later solves with the parallelism they had
/// before. Parallel and sequential kernels sum in different orders, so without the guard a
/// solve after a sweep could differ from the same solve in a fresh process in the last digits.
pub fn sequential_linear_algebra_scope() -> LinearAlgebraParallelism {
    let previous = faer::get_global_parallelism();
    faer::set_global_parallelism(faer::Par::Seq);
    LinearAlgebraParallelism(previous)
}
