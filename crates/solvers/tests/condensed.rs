//! Static condensation against plain sparse LU.

use capstan_solvers::samples::{LinearSystem, Poisson2d, RandomDiagonallyDominant, SplitMix64};
use capstan_solvers::{CondensedSolver, LinearSolver, SolverError, SparseLu};

fn lu_solution(system: &LinearSystem, rhs: &[f64]) -> Vec<f64> {
    let mut lu = SparseLu::default();
    lu.analyse(&system.pattern).unwrap();
    lu.factor(&system.values).unwrap();
    let mut x = rhs.to_vec();
    lu.solve_in_place(&mut x).unwrap();
    x
}

fn assert_close(a: &[f64], b: &[f64], tolerance: f64) {
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tolerance * scale,
            "entry {i}: {x} vs {y} (scale {scale})"
        );
    }
}

#[test]
fn condensed_matches_lu_on_a_random_diagonally_dominant_system() {
    let mut system = RandomDiagonallyDominant {
        n: 600,
        off_diagonals: 6,
        seed: 20,
    }
    .system();
    // 90 interface unknowns, scattered, in a shuffled order
    let mut interface: Vec<usize> = (0..600)
        .filter(|i| i % 7 == 3 || i % 11 == 5)
        .take(90)
        .collect();
    interface.reverse();
    let mut solver = CondensedSolver::new(&interface);
    solver.analyse(&system.pattern).unwrap();
    solver.factor(&system.values).unwrap();
    let mut x = system.rhs.clone();
    solver.solve_in_place(&mut x).unwrap();
    // well conditioned (strictly dominant): both solutions are accurate to round-off
    assert_close(&x, &lu_solution(&system, &system.rhs), 1e-12);
    assert!(system.residual_norm(&x) < 1e-12);

    // change only the interface block, twice, through both entry points
    let mut rng = SplitMix64(3);
    for round in 0..2 {
        for &s in solver.interface_slots() {
            system.values[s] += 0.5 * rng.uniform();
        }
        if round == 0 {
            solver.factor(&system.values).unwrap();
        } else {
            solver.refactor_interface(&system.values).unwrap();
        }
        let mut x = system.rhs.clone();
        solver.solve_in_place(&mut x).unwrap();
        assert_close(&x, &lu_solution(&system, &system.rhs), 1e-12);
    }
    assert_eq!(solver.bulk_factorisations(), 1);
    assert_eq!(solver.interface_factorisations(), 3);
}

#[test]
fn condensed_matches_lu_on_a_laplacian_with_a_changing_boundary_block() {
    // 5-point Laplacian on 24 x 24; the interface is the bottom grid row (j = 0), the "contact
    // boundary" whose block changes between Newton steps like a friction tangent would.
    let n = 24;
    let mut system = Poisson2d::new(n).system();
    let interface: Vec<usize> = (0..n).collect();
    let mut solver = CondensedSolver::new(&interface);
    solver.analyse(&system.pattern).unwrap();
    // the II block of the bottom row is its tridiagonal part: 3n - 2 slots
    assert_eq!(solver.interface_slots().len(), 3 * n - 2);
    let entries = solver.interface_entries();
    assert!(
        entries
            .iter()
            .all(|&(r, c)| r < n && c < n && r.abs_diff(c) <= 1)
    );
    let rhs2: Vec<f64> = (0..n * n).map(|k| ((k % 13) as f64 - 6.0) / 13.0).collect();
    for step in 0..4 {
        // a Robin-like diagonal term and a nonsymmetric tangential coupling on the boundary
        for &s in solver.interface_slots() {
            let (row, col) = slot_position(&system, s);
            if row == col {
                system.values[s] = 4.0 + 0.7 * step as f64;
            } else if row < col {
                system.values[s] = -1.0 + 0.2 * step as f64;
            }
        }
        if step % 2 == 0 {
            solver.factor(&system.values).unwrap();
        } else {
            // the same update through the block-only entry point
            let block: Vec<f64> = solver
                .interface_slots()
                .iter()
                .map(|&s| system.values[s])
                .collect();
            solver.refactor_interface_block(&block).unwrap();
        }
        for rhs in [&system.rhs, &rhs2] {
            let mut x = rhs.clone();
            solver.solve_in_place(&mut x).unwrap();
            // cond ~ 300 on this grid: agreement to a few hundred ulps of the solution
            assert_close(&x, &lu_solution(&system, rhs), 1e-12);
        }
    }
    assert_eq!(solver.bulk_factorisations(), 1);
    assert_eq!(solver.interface_factorisations(), 4);

    // a change outside the interface block is detected and refactorises the bulk
    let bulk_slot = system.pattern.slot(n * n - 1, n * n - 1).unwrap();
    system.values[bulk_slot] += 1.0;
    solver.factor(&system.values).unwrap();
    assert_eq!(solver.bulk_factorisations(), 2);
    let mut x = system.rhs.clone();
    solver.solve_in_place(&mut x).unwrap();
    assert_close(&x, &lu_solution(&system, &system.rhs), 1e-12);
}

fn slot_position(system: &LinearSystem, slot: usize) -> (usize, usize) {
    system.pattern.entries().nth(slot).unwrap()
}

#[test]
fn block_update_rejects_wrong_length() {
    let system = Poisson2d::new(4).system();
    let mut solver = CondensedSolver::new(&[0, 1]);
    solver.analyse(&system.pattern).unwrap();
    solver.factor(&system.values).unwrap();
    assert!(matches!(
        solver.refactor_interface_block(&[1.0]),
        Err(SolverError::DimensionMismatch {
            expected: 4,
            found: 1,
            ..
        })
    ));
}

#[test]
fn condensed_reports_a_singular_bulk_block_in_full_numbering() {
    let mut system = Poisson2d::new(6).system();
    // zero the bulk unknown 20 entirely (row and column): A_BB singular
    for (v, (row, col)) in system.values.iter_mut().zip(system.pattern.entries()) {
        if row == 20 || col == 20 {
            *v = 0.0;
        }
    }
    let mut solver = CondensedSolver::new(&[0, 1, 2]);
    solver.analyse(&system.pattern).unwrap();
    let err = solver.factor(&system.values).unwrap_err();
    assert!(
        matches!(err, SolverError::Singular { pivot: Some(20) }),
        "{err:?}"
    );
}

#[test]
fn condensed_enforces_call_order() {
    let system = Poisson2d::new(3).system();
    let mut solver = CondensedSolver::new(&[4]);
    assert!(matches!(
        solver.refactor_interface(&system.values),
        Err(SolverError::CallOrder { .. })
    ));
    solver.analyse(&system.pattern).unwrap();
    assert!(matches!(
        solver.refactor_interface(&system.values),
        Err(SolverError::CallOrder { .. })
    ));
    let mut x = system.rhs.clone();
    assert!(matches!(
        solver.solve_in_place(&mut x),
        Err(SolverError::CallOrder { .. })
    ));
}
