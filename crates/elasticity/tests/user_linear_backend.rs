//! A linear backend written outside capstan, registered once, drives both contact solvers:
//! the boundary-only solver (its condensation of the bulk) and the full-system Newton (its
//! stuck start and every Newton step). Sparse LU behind a counter: the numbers must equal the
//! built-in `lu` ones bit for bit, and the counter must move.

use std::sync::atomic::{AtomicUsize, Ordering};

use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, EndLoads, FullSystemSettings, FullSystemSolver, ThickBody,
};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solvers::{
    BackendKind, LinearBackend, LinearSolver, RegisteredLinearSolver, SolverError, SparseLu,
    SparsityPattern, linear_registry, max_abs, max_abs_difference,
};

static FACTORISATIONS: AtomicUsize = AtomicUsize::new(0);

/// Sparse LU that counts its numeric factorisations.
#[derive(Debug)]
struct CountingLu(SparseLu);

impl LinearSolver<f64> for CountingLu {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        self.0.analyse(pattern)
    }
    fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
        FACTORISATIONS.fetch_add(1, Ordering::SeqCst);
        self.0.factor(values)
    }
    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
        self.0.solve_in_place(rhs)
    }
    fn last_iterations(&self) -> Option<usize> {
        None
    }
    fn solve_many_in_place(&mut self, rhs: &mut [f64], ncols: usize) -> Result<(), SolverError> {
        self.0.solve_many_in_place(rhs, ncols)
    }
}

/// The registration: one value, nothing else in capstan changes.
const COUNTING_LU: RegisteredLinearSolver = RegisteredLinearSolver {
    name: "counting-lu",
    summary: "sparse LU that counts its factorisations",
    parameters: &[],
    kind: BackendKind::Direct,
    build: |settings, _| Ok(Box::new(CountingLu(SparseLu::new(settings.direct)?))),
};

#[test]
fn a_registered_user_backend_drives_both_contact_solvers_to_the_lu_numbers() {
    linear_registry::register(COUNTING_LU).unwrap();
    let backend: LinearBackend = "counting-lu".parse().unwrap(); // as a scene names it
    assert!(linear_registry::names().ends_with("counting-lu"));

    // the default scene's problem: the paper's body on its 250 x 41 grid, mu = 0.5,
    // eps = 1e-5, tau0 = 1, tau_max = 2
    let eps = 1e-5;
    let body = ThickBody::paper(250, 41).unwrap();
    let params = RegularisedCoulombParams::new(0.5, eps).unwrap();
    let model = body.model(RegularisedCoulomb, params, eps).unwrap();
    let loads = EndLoads::new(1.0, 2.0);

    // boundary-only solver
    let lu = BoundarySolver::new(&model, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let before = FACTORISATIONS.load(Ordering::SeqCst);
    let settings = ContactSettings {
        linear: backend,
        ..Default::default()
    };
    let user = BoundarySolver::new(&model, settings)
        .unwrap()
        .solve(loads)
        .unwrap();
    let condensed = FACTORISATIONS.load(Ordering::SeqCst) - before;
    assert!(condensed >= 1, "the condensation factorised the bulk");
    // the default condenses from the Schur complement, the user's backend by solves with the
    // same LU: the same numbers up to round-off
    let scale = max_abs(&lu.displacement);
    assert!(max_abs_difference(&user.displacement, &lu.displacement) < 1e-12 * scale);
    assert_eq!(user.stats.newton_iterations, lu.stats.newton_iterations);
    assert_eq!(lu.stats.newton_iterations, 10); // pinned: `capstan contact --json`

    // full-system Newton
    let full_lu = FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let mut settings = FullSystemSettings::default();
    settings.newton.linear = backend;
    let before = FACTORISATIONS.load(Ordering::SeqCst);
    let full_user = FullSystemSolver::new(&model, settings)
        .unwrap()
        .solve(loads)
        .unwrap();
    let full = FACTORISATIONS.load(Ordering::SeqCst) - before;
    // the stuck start and one factorisation per Newton step, all by the user's backend
    assert!(full > 1);
    assert_eq!(full, full_user.stats.factorisations);
    assert_eq!(full_user.displacement, full_lu.displacement);
    assert_eq!(
        full_user.stats.newton_iterations,
        full_lu.stats.newton_iterations
    );
    // both solvers solve the same problem: agreement to the solver tolerance
    let scale = lu.displacement.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = lu
        .displacement
        .iter()
        .zip(&full_user.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff < 1e-7 * scale, "{:e}", diff / scale);
}
