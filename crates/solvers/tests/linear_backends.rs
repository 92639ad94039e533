//! Public behaviour of the linear backends: one Poisson problem and one convection–diffusion
//! problem through every backend, refactorisation, many right-hand sides, and typed failures.

use capstan_solvers::samples::{ConvectionDiffusion2d, LinearSystem, Poisson2d};
use capstan_solvers::{
    GaussSeidel, IterativeParams, Jacobi, LinearBackend, LinearContext, LinearSettings,
    LinearSolver, SolverError, SparseCholesky, SparseLu, SparsityPattern, max_abs,
    max_abs_difference,
};

/// The registered backends that need nothing from the caller (`multigrid` needs a hierarchy).
const STANDALONE: [LinearBackend; 4] = [
    LinearBackend::LU,
    LinearBackend::CHOLESKY,
    LinearBackend::JACOBI,
    LinearBackend::GAUSS_SEIDEL,
];

/// Solves `system` with `backend`; returns the solution and the iterations reported.
fn solve(system: &LinearSystem, backend: LinearBackend) -> (Vec<f64>, Option<usize>) {
    let mut solver = backend.build(&LinearSettings::default(), &()).unwrap();
    solver.analyse(&system.pattern).unwrap();
    solver.factor(&system.values).unwrap();
    let mut x = system.rhs.clone();
    solver.solve_in_place(&mut x).unwrap();
    (x, solver.last_iterations())
}

fn norm(a: &[f64]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[test]
fn poisson_is_solved_by_every_backend_and_they_agree() {
    let system = Poisson2d::new(16).system();
    let b = norm(&system.rhs);
    let (reference, _) = solve(&system, LinearBackend::LU);
    assert!(system.residual_norm(&reference) < 1e-14 * b.max(1.0)); // direct: round-off only
    for backend in STANDALONE {
        let (x, iterations) = solve(&system, backend);
        let residual = system.residual_norm(&x);
        if backend.is_direct() {
            assert!(residual <= 1e-13 * b, "{backend}: {residual:e}"); // round-off only
            assert_eq!(iterations, None);
        } else {
            // the iteration stops at relative residual 1e-10
            assert!(residual <= 1e-10 * b, "{backend}: {residual:e}");
        }
        // |x - x_lu| <= cond(A) |r| / |A| ~ (4 / (pi h)^2) * 1e-10 relative: 1e-7 is generous
        assert!(
            max_abs_difference(&x, &reference) <= 1e-7 * max_abs(&reference),
            "{backend}"
        );
    }
}

#[test]
fn iterative_counts_on_poisson_are_pinned() {
    // Deterministic: x_0 = 0, fixed ordering, default tolerance 1e-10.
    let system = Poisson2d::new(16).system();
    let (_, jacobi) = solve(&system, LinearBackend::JACOBI);
    let (_, gauss_seidel) = solve(&system, LinearBackend::GAUSS_SEIDEL);
    assert_eq!(jacobi, Some(1332));
    assert_eq!(gauss_seidel, Some(667)); // rho(GS) = rho(Jacobi)^2: half the sweeps
}

#[test]
fn convection_diffusion_is_solved_by_lu_jacobi_and_gauss_seidel() {
    let system = ConvectionDiffusion2d::new(16, [20.0, 10.0]).system();
    let b = norm(&system.rhs);
    let (reference, _) = solve(&system, LinearBackend::LU);
    assert!(system.residual_norm(&reference) <= 1e-13 * b); // direct: round-off only
    let mut counts = Vec::new();
    for backend in [LinearBackend::JACOBI, LinearBackend::GAUSS_SEIDEL] {
        let (x, iterations) = solve(&system, backend);
        assert!(system.residual_norm(&x) <= 1e-10 * b, "{backend}");
        assert!(
            max_abs_difference(&x, &reference) <= 1e-7 * max_abs(&reference),
            "{backend}"
        );
        counts.push(iterations.unwrap());
    }
    assert_eq!(counts, vec![207, 93]);
}

#[test]
fn cholesky_rejects_the_nonsymmetric_convection_operator() {
    let system = ConvectionDiffusion2d::new(4, [20.0, 0.0]).system();
    let mut chol = SparseCholesky::default();
    chol.analyse(&system.pattern).unwrap();
    assert!(matches!(
        chol.factor(&system.values),
        Err(SolverError::NotSymmetric { .. })
    ));
}

#[test]
fn refactor_with_new_values_on_the_same_pattern() {
    let system = Poisson2d::new(12).system();
    // A' = 2 A + I: same pattern, different values
    let diagonal = system.pattern.diagonal_slots();
    let mut shifted = system.values.iter().map(|v| 2.0 * v).collect::<Vec<_>>();
    for s in diagonal.into_iter().flatten() {
        shifted[s] += 1.0;
    }
    let new_system = LinearSystem {
        values: shifted,
        ..system.clone()
    };
    for backend in STANDALONE {
        let mut solver = backend.build(&LinearSettings::default(), &()).unwrap();
        solver.analyse(&system.pattern).unwrap();
        for s in [&system, &new_system, &system] {
            solver.factor(&s.values).unwrap();
            let mut x = s.rhs.clone();
            solver.solve_in_place(&mut x).unwrap();
            assert!(s.residual_norm(&x) <= 1e-10 * norm(&s.rhs), "{backend}");
        }
    }
    let mut lu = SparseLu::default();
    lu.analyse(&system.pattern).unwrap();
    lu.factor(&system.values).unwrap();
    lu.factor(&new_system.values).unwrap();
    assert_eq!(lu.factorisations(), 2);
}

#[test]
fn many_right_hand_sides_match_single_solves() {
    let system = ConvectionDiffusion2d::new(10, [5.0, -5.0]).system();
    let n = system.dimension();
    let ncols = 5;
    let rhs: Vec<f64> = (0..n * ncols)
        .map(|k| ((k * 7919) % 101) as f64 / 101.0 - 0.5)
        .collect();
    for backend in [
        LinearBackend::LU,
        LinearBackend::JACOBI,
        LinearBackend::GAUSS_SEIDEL,
    ] {
        let mut solver = backend.build(&LinearSettings::default(), &()).unwrap();
        solver.analyse(&system.pattern).unwrap();
        solver.factor(&system.values).unwrap();
        let mut blocked = rhs.clone();
        solver.solve_many_in_place(&mut blocked, ncols).unwrap();
        for c in 0..ncols {
            let mut single = rhs[c * n..(c + 1) * n].to_vec();
            let b = norm(&single);
            solver.solve_in_place(&mut single).unwrap();
            let x = &blocked[c * n..(c + 1) * n];
            let column_system = LinearSystem {
                rhs: rhs[c * n..(c + 1) * n].to_vec(),
                ..system.clone()
            };
            assert!(column_system.residual_norm(x) <= 1e-10 * b, "{backend}");
            // same method, same data: identical up to round-off of the blocked kernels
            assert!(
                max_abs_difference(x, &single) <= 1e-12 * max_abs(&single),
                "{backend}"
            );
        }
    }
}

/// A pattern with every entry of an `n x n` matrix given in row-major `dense`.
fn dense_system(n: usize, dense: &[f64]) -> (SparsityPattern, Vec<f64>) {
    let entries: Vec<(usize, usize)> = (0..n * n).map(|k| (k / n, k % n)).collect();
    let (pattern, slots) = SparsityPattern::from_entries(n, n, &entries).unwrap();
    let mut values = vec![0.0; pattern.nnz()];
    for (k, v) in dense.iter().enumerate() {
        values[slots[k]] += v;
    }
    (pattern, values)
}

fn direct_solvers() -> Vec<Box<dyn LinearSolver<f64> + Send>> {
    vec![
        Box::new(SparseLu::default()),
        Box::new(SparseCholesky::default()),
    ]
}

/// Every direct solver refuses `values` on `pattern` (or the solve of `x` with them) as
/// singular or not positive definite: a typed error, never NaN.
fn assert_every_direct_solver_refuses(pattern: &SparsityPattern, values: &[f64], rhs: &[f64]) {
    for mut solver in direct_solvers() {
        solver.analyse(pattern).unwrap();
        let mut x = rhs.to_vec();
        let result = solver
            .factor(values)
            .and_then(|()| solver.solve_in_place(&mut x));
        assert!(
            matches!(
                result,
                Err(SolverError::Singular { .. } | SolverError::NotPositiveDefinite { .. })
            ),
            "{result:?}"
        );
    }
}

#[test]
fn exactly_singular_matrix_is_a_typed_error_not_nan() {
    // [[1, 1], [1, 1]]: no empty line, an exact zero pivot after one elimination step
    let (pattern, values) = dense_system(2, &[1.0, 1.0, 1.0, 1.0]);
    assert_every_direct_solver_refuses(&pattern, &values, &[1.0, 2.0]);
}

#[test]
fn numerically_singular_matrix_is_a_typed_error() {
    // rank 2: row 2 = row 0 + row 1 in floating point inexact arithmetic
    let dense = [0.1, 0.3, 0.7, 0.2, 0.6, 0.3, 0.3, 0.9, 1.0];
    let (pattern, values) = dense_system(3, &dense);
    let mut lu = SparseLu::default();
    lu.analyse(&pattern).unwrap();
    lu.factor(&values).unwrap();
    let mut x = vec![1.0, 0.0, 0.0];
    assert!(matches!(
        lu.solve_in_place(&mut x),
        Err(SolverError::Singular { pivot: None })
    ));
}

#[test]
fn singular_graph_laplacian_is_a_typed_error_on_a_larger_grid() {
    // Poisson with the boundary terms removed: rows sum to zero, constants in the kernel.
    let system = Poisson2d::new(30).system();
    let mut values = system.values.clone();
    let n = system.dimension();
    let mut off = vec![0.0; n];
    for (s, (row, col)) in system.pattern.entries().enumerate() {
        if row != col {
            off[row] += values[s];
        }
    }
    for (i, s) in system.pattern.diagonal_slots().into_iter().enumerate() {
        values[s.unwrap()] = -off[i];
    }
    let mut rhs = vec![0.0; n];
    rhs[0] = 1.0; // not in the range
    for backend in STANDALONE {
        let mut solver = backend
            .build(
                &LinearSettings {
                    iterative: IterativeParams {
                        max_iterations: 500,
                        ..Default::default()
                    },
                    ..Default::default()
                },
                &(),
            )
            .unwrap();
        solver.analyse(&system.pattern).unwrap();
        let mut x = rhs.clone();
        let result = solver
            .factor(&values)
            .and_then(|()| solver.solve_in_place(&mut x));
        let expected = match backend.name() {
            "lu" => matches!(result, Err(SolverError::Singular { .. })),
            "cholesky" => matches!(
                result,
                Err(SolverError::NotPositiveDefinite { .. } | SolverError::Singular { .. })
            ),
            _ => matches!(result, Err(SolverError::NotConverged { .. })),
        };
        assert!(expected, "{backend}: {result:?}");
    }
}

#[test]
fn empty_column_is_singular_before_factorising() {
    let (pattern, mut values) = dense_system(3, &[2.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 1.0]);
    values[pattern.slot(2, 2).unwrap()] = 0.0; // row and column 2 are now zero
    for mut solver in direct_solvers() {
        solver.analyse(&pattern).unwrap();
        assert!(matches!(
            solver.factor(&values),
            Err(SolverError::Singular { pivot: Some(2) })
        ));
    }
    let mut jacobi = Jacobi::<f64>::default();
    jacobi.analyse(&pattern).unwrap();
    assert!(matches!(
        jacobi.factor(&values),
        Err(SolverError::Singular { pivot: Some(2) })
    ));
}

#[test]
fn indefinite_matrix_to_cholesky_is_not_positive_definite() {
    let system = Poisson2d::new(10).system();
    let mut values = system.values.clone();
    for s in system.pattern.diagonal_slots().into_iter().flatten() {
        values[s] -= 3.0; // eigenvalues of the 5-point stencil span (0, 8): now (-3, 5)
    }
    let mut chol = SparseCholesky::default();
    chol.analyse(&system.pattern).unwrap();
    let err = chol.factor(&values).unwrap_err();
    assert!(
        matches!(err, SolverError::NotPositiveDefinite { pivot } if pivot < 100),
        "{err:?}"
    );
    // the same matrix is fine for LU
    let mut lu = SparseLu::default();
    lu.analyse(&system.pattern).unwrap();
    lu.factor(&values).unwrap();
    let mut x = system.rhs.clone();
    lu.solve_in_place(&mut x).unwrap();
    assert!(system.pattern.residual_norm(&values, &x, &system.rhs) < 1e-12);
    // negative definite fails at the first pivot
    let negative: Vec<f64> = system.values.iter().map(|v| -v).collect();
    assert!(matches!(
        chol.factor(&negative),
        Err(SolverError::NotPositiveDefinite { .. })
    ));
}

#[test]
fn jacobi_and_gauss_seidel_report_not_converged_without_diagonal_dominance() {
    // [[1, 2], [2, 1]]: the Jacobi iteration matrix has spectral radius 2
    let (pattern, values) = dense_system(2, &[1.0, 2.0, 2.0, 1.0]);
    let params = IterativeParams {
        max_iterations: 200,
        ..Default::default()
    };
    let mut solvers: Vec<Box<dyn LinearSolver<f64>>> = vec![
        Box::new(Jacobi::new(params).unwrap()),
        Box::new(GaussSeidel::new(params).unwrap()),
    ];
    for solver in &mut solvers {
        solver.analyse(&pattern).unwrap();
        solver.factor(&values).unwrap();
        let mut x = vec![1.0, 0.0];
        let err = solver.solve_in_place(&mut x).unwrap_err();
        match err {
            SolverError::NotConverged {
                iterations,
                residual,
            } => {
                assert!(
                    iterations <= 200 && residual > 1.0,
                    "{iterations} {residual}"
                );
                assert_eq!(solver.last_iterations(), Some(iterations));
            }
            other => panic!("expected NotConverged, got {other:?}"),
        }
    }
    // with a tiny cap the count is exactly the cap
    let mut jacobi = Jacobi::new(IterativeParams {
        max_iterations: 3,
        ..Default::default()
    })
    .unwrap();
    jacobi.analyse(&pattern).unwrap();
    jacobi.factor(&values).unwrap();
    assert!(matches!(
        jacobi.solve_in_place(&mut [1.0, 0.0]),
        Err(SolverError::NotConverged { iterations: 3, .. })
    ));
}

#[test]
fn non_finite_inputs_are_rejected() {
    let system = Poisson2d::new(3).system();
    let mut bad = system.values.clone();
    bad[4] = f64::NAN;
    for backend in STANDALONE {
        let mut solver = backend.build(&LinearSettings::default(), &()).unwrap();
        solver.analyse(&system.pattern).unwrap();
        assert!(
            matches!(
                solver.factor(&bad),
                Err(SolverError::NonFinite {
                    quantity: "matrix value",
                    index: 4,
                    ..
                })
            ),
            "{backend}"
        );
        solver.factor(&system.values).unwrap();
        let mut rhs = system.rhs.clone();
        rhs[2] = f64::INFINITY;
        assert!(
            matches!(
                solver.solve_in_place(&mut rhs),
                Err(SolverError::NonFinite {
                    quantity: "right-hand side",
                    index: 2,
                    ..
                })
            ),
            "{backend}"
        );
    }
}

#[test]
fn zero_right_hand_side_gives_zero_solution() {
    let system = Poisson2d::new(5).system();
    for backend in STANDALONE {
        let mut solver = backend.build(&LinearSettings::default(), &()).unwrap();
        solver.analyse(&system.pattern).unwrap();
        solver.factor(&system.values).unwrap();
        let mut x = vec![0.0; system.dimension()];
        solver.solve_in_place(&mut x).unwrap();
        assert!(x.iter().all(|v| *v == 0.0), "{backend}");
    }
}

#[test]
fn jacobi_works_in_single_precision() {
    let system = Poisson2d::new(8).system();
    let values: Vec<f32> = system.values.iter().map(|&v| v as f32).collect();
    let mut x: Vec<f32> = system.rhs.iter().map(|&v| v as f32).collect();
    let mut jacobi = Jacobi::<f32>::new(IterativeParams {
        tolerance: 1e-5,
        ..Default::default()
    })
    .unwrap();
    jacobi.analyse(&system.pattern).unwrap();
    jacobi.factor(&values).unwrap();
    jacobi.solve_in_place(&mut x).unwrap();
    let (reference, _) = solve(&system, LinearBackend::LU);
    for (a, b) in x.iter().zip(&reference) {
        // 1e-5 relative residual times cond ~ 40 for n = 8
        assert!((f64::from(*a) - b).abs() <= 1e-3 * max_abs(&reference));
    }
}

#[test]
fn backend_names_parse() {
    for (name, backend) in [
        ("lu", LinearBackend::LU),
        ("cholesky", LinearBackend::CHOLESKY),
        ("jacobi", LinearBackend::JACOBI),
        ("gauss-seidel", LinearBackend::GAUSS_SEIDEL),
        ("multigrid", LinearBackend::MULTIGRID),
    ] {
        assert_eq!(name.parse::<LinearBackend>().unwrap(), backend);
    }
    let err = "Gauss-Seidel".parse::<LinearBackend>().unwrap_err();
    assert!(err.to_string().contains("gauss-seidel"));
}

#[test]
fn exact_zero_pivot_inside_a_large_matrix_is_singular_not_a_panic() {
    // Poisson(40) plus a decoupled [[1, 1], [1, 1]] block: large enough for faer's supernodal
    // path, with an exact zero pivot (faer issue 232 territory).
    let poisson = Poisson2d::new(40).system();
    let m = poisson.dimension();
    let mut entries = Vec::new();
    let mut contributions = Vec::new();
    for (s, entry) in poisson.pattern.entries().enumerate() {
        entries.push(entry);
        contributions.push(poisson.values[s]);
    }
    for (r, c) in [(m, m), (m + 1, m), (m, m + 1), (m + 1, m + 1)] {
        entries.push((r, c));
        contributions.push(1.0);
    }
    let (pattern, slots) = SparsityPattern::from_entries(m + 2, m + 2, &entries).unwrap();
    let mut values = vec![0.0; pattern.nnz()];
    for (k, v) in contributions.into_iter().enumerate() {
        values[slots[k]] += v;
    }
    assert_every_direct_solver_refuses(&pattern, &values, &vec![1.0; m + 2]);
}

#[test]
fn structurally_singular_matrix_without_empty_lines_is_singular() {
    // columns 0 and 1 live only in row 0: no perfect matching, though no row or column is empty
    let entries = [(0, 0), (0, 1), (1, 2), (2, 2), (1, 3), (2, 3), (3, 3)];
    let (pattern, slots) = SparsityPattern::from_entries(4, 4, &entries).unwrap();
    let mut values = vec![0.0; pattern.nnz()];
    for (k, v) in [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0].into_iter().enumerate() {
        values[slots[k]] += v;
    }
    let mut lu = SparseLu::default();
    lu.analyse(&pattern).unwrap();
    let mut x = vec![1.0; 4];
    let result = lu.factor(&values).and_then(|()| lu.solve_in_place(&mut x));
    assert!(
        matches!(result, Err(SolverError::Singular { .. })),
        "{result:?}"
    );
}

/// A one-level hierarchy: the V-cycle is the sparse LU of the matrix itself.
struct OneLevel;

impl LinearContext for OneLevel {
    fn prolongations(
        &self,
        _coarsest_unknowns: usize,
    ) -> Option<std::sync::Arc<[capstan_solvers::CsrMatrix]>> {
        Some(Vec::new().into())
    }
}

#[test]
fn multigrid_solves_with_the_callers_hierarchy_and_is_refused_without_one() {
    let system = ConvectionDiffusion2d::new(16, [20.0, 10.0]).system();
    let (reference, _) = solve(&system, LinearBackend::LU);
    let mut solver = LinearBackend::MULTIGRID
        .build(&LinearSettings::default(), &OneLevel)
        .unwrap();
    solver.analyse(&system.pattern).unwrap();
    solver.factor(&system.values).unwrap();
    let mut x = system.rhs.clone();
    solver.solve_in_place(&mut x).unwrap();
    // the preconditioner is the exact inverse: one GMRES iteration
    assert_eq!(solver.last_iterations(), Some(1));
    assert!(max_abs_difference(&x, &reference) < 1e-10 * max_abs(&reference));
    assert!(matches!(
        LinearBackend::MULTIGRID.build(&LinearSettings::default(), &()),
        Err(SolverError::InvalidParameter {
            field: "linear",
            ..
        })
    ));
}
