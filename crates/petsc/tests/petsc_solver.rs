//! The PETSc backend against capstan's sparse LU on a non-symmetric model system, its Krylov
//! events, its typed errors. One test function: PETSc starts once per process. The binary
//! also runs under `mpirun -n K` (every rank runs the same calls; rows are split).
#![cfg(feature = "petsc")]

use capstan_petsc::{MUMPS_OPTIONS, PetscDistribution, PetscError, PetscSolver, Session};
use capstan_solvers::row_distribution::RowDistribution;
use capstan_solvers::samples::ConvectionDiffusion2d;
use capstan_solvers::{
    LinearBackend, LinearSolver, NearNullSpace, Progress, SolveStage, SolverError,
    max_abs_difference,
};
use std::sync::Arc;

fn solve(system: &capstan_solvers::samples::LinearSystem) -> (Vec<f64>, Vec<Progress<f64>>, usize) {
    let mut solver = PetscSolver::new().unwrap();
    solver.analyse(&system.pattern).unwrap();
    solver.factor(&system.values).unwrap();
    let mut x = system.rhs.clone();
    let mut events = Vec::new();
    let mut observer = |p: &Progress<f64>| events.push(*p);
    solver
        .solve_in_place_observed(&mut x, &mut observer)
        .unwrap();
    (x, events, solver.last_iterations().unwrap())
}

#[test]
fn petsc_solver_matches_lu_reports_krylov_and_spends_budget_typed() {
    let session = Session::start("-ksp_type gmres -pc_type gamg -ksp_rtol 1e-12").unwrap();
    let system = ConvectionDiffusion2d::new(40, [20.0, -10.0]).system();
    let mut lu = LinearBackend::LU.build(&Default::default(), &()).unwrap();
    lu.analyse(&system.pattern).unwrap();
    lu.factor(&system.values).unwrap();
    let mut exact = system.rhs.clone();
    lu.solve_in_place(&mut exact).unwrap();
    let scale = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));

    // GMRES + GAMG to rtol 1e-12: the LU answer to ~1e-10 relative (cond(A) ~ 1e3).
    let (x, events, iterations) = solve(&system);
    assert!(max_abs_difference(&x, &exact) < 1e-9 * scale);
    assert!(
        system.residual_norm(&x) < 1e-10 * system.rhs.iter().map(|b| b * b).sum::<f64>().sqrt()
    );
    assert!(iterations > 1 && iterations < 100, "{iterations}");
    // one Krylov event per iteration, relative residuals ending below the tolerance
    assert_eq!(events.len(), iterations);
    assert!(events.iter().all(|p| p.stage == SolveStage::Krylov));
    assert!(events.last().unwrap().residual_norm < 1e-12);

    // MUMPS (the direct option): one "iteration" of preonly, the LU answer to round-off.
    session.insert_options(MUMPS_OPTIONS).unwrap();
    let (x, _, _) = solve(&system);
    assert!(max_abs_difference(&x, &exact) < 1e-12 * scale);

    // A near-null space reaches GAMG (the constants; a dependent second vector is dropped by
    // the orthonormalisation), the same answer; a block size that does not divide the
    // unknowns is a typed error at analyse.
    session
        .insert_options("-ksp_type gmres -pc_type gamg -ksp_rtol 1e-12")
        .unwrap();
    let n = system.pattern.nrows();
    let constants = NearNullSpace {
        block_size: 1,
        vectors: vec![vec![1.0; n], vec![2.0; n]],
    };
    let mut solver = PetscSolver::new()
        .unwrap()
        .with_near_null_space(Arc::new(constants));
    solver.analyse(&system.pattern).unwrap();
    solver.factor(&system.values).unwrap();
    let mut x = system.rhs.clone();
    solver.solve_in_place(&mut x).unwrap();
    assert!(max_abs_difference(&x, &exact) < 1e-9 * scale);
    let odd = NearNullSpace {
        block_size: n + 1,
        vectors: Vec::new(),
    };
    let mut solver = PetscSolver::new()
        .unwrap()
        .with_near_null_space(Arc::new(odd));
    assert!(matches!(
        solver.analyse(&system.pattern),
        Err(SolverError::DimensionMismatch {
            quantity: "block size",
            ..
        })
    ));

    // A spent budget is a typed error naming the option.
    session
        .insert_options("-ksp_type gmres -pc_type jacobi -ksp_max_it 3 -ksp_rtol 1e-14")
        .unwrap();
    let mut solver = PetscSolver::new().unwrap();
    solver.analyse(&system.pattern).unwrap();
    solver.factor(&system.values).unwrap();
    let mut x = system.rhs.clone();
    match solver.solve_in_place(&mut x) {
        Err(SolverError::BudgetSpent {
            field, iterations, ..
        }) => {
            assert_eq!(field, "solver.petsc_options -ksp_max_it");
            assert_eq!(iterations, 3);
        }
        other => panic!("expected BudgetSpent, got {other:?}"),
    }
    // call order, lengths and non-finite input are refused before PETSc sees them
    let mut fresh = PetscSolver::new().unwrap();
    assert!(matches!(
        fresh.solve_in_place(&mut x),
        Err(SolverError::CallOrder { .. })
    ));
    fresh.analyse(&system.pattern).unwrap();
    let mut bad = system.values.clone();
    bad[0] = f64::NAN;
    assert!(matches!(
        fresh.factor(&bad),
        Err(SolverError::NonFinite { .. })
    ));
    assert!(matches!(
        Session::start(""),
        Err(PetscError::AlreadyStarted)
    ));

    // The row distribution's gather: every rank's rows to every rank (its own rows hold the
    // same values on every rank here, so the vector comes back unchanged).
    let distribution = PetscDistribution::new(&session).unwrap();
    let whole: Vec<f64> = (0..12).map(f64::from).collect();
    let mut v = whole.clone();
    distribution.gather(&mut v, 3).unwrap();
    assert_eq!(v, whole);
    // PETSc calls come from the session's thread: from another, a gather or a new solver is a
    // typed error before any MPI message (two threads' collectives would interleave
    // differently on different ranks: MPI_ERR_TRUNCATE, or a hang)
    std::thread::scope(|scope| {
        scope.spawn(|| {
            let mut w = whole.clone();
            match distribution.gather(&mut w, 3) {
                Err(SolverError::External {
                    backend: "petsc",
                    source,
                }) => assert!(source.to_string().contains("thread"), "{source}"),
                other => panic!("expected a typed wrong-thread error, got {other:?}"),
            }
            assert!(matches!(
                PetscSolver::new(),
                Err(PetscError::WrongThread { .. })
            ));
        });
    });
    distribution.gather(&mut v, 3).unwrap();
    assert_eq!(v, whole);
    drop(distribution);
    drop(solver);
    drop(fresh);
    drop(session);
    assert!(matches!(PetscSolver::new(), Err(PetscError::NotStarted)));
}
