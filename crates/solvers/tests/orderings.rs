//! Column orderings of the direct backends: every ordering solves the same systems to the same
//! residual as the default, the grid nested dissection is a permutation for any grid shape,
//! and failures stay typed.

use capstan_solvers::samples::{
    ConvectionDiffusion2d, LinearSystem, Poisson2d, RandomDiagonallyDominant,
};
use capstan_solvers::{
    ColumnOrdering, DirectParams, GridShape, LinearSolver, SolverError, SparseCholesky, SparseLu,
    SparsityPattern, is_permutation, max_abs_difference, nested_dissection_grid,
};
use proptest::prelude::*;

fn lu_with(ordering: ColumnOrdering) -> SparseLu {
    SparseLu::new(DirectParams {
        ordering,
        ..Default::default()
    })
    .unwrap()
}

fn solve(solver: &mut impl LinearSolver<f64>, system: &LinearSystem) -> Vec<f64> {
    solver.analyse(&system.pattern).unwrap();
    solver.factor(&system.values).unwrap();
    let mut x = system.rhs.clone();
    solver.solve_in_place(&mut x).unwrap();
    x
}

fn norm(a: &[f64]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The unknown `k = i + n j` of the samples' `n x n` grids: `n2 = n` (j), `n3 = n` (i).
fn square_grid(n: usize) -> GridShape {
    GridShape {
        n2: n,
        n3: n,
        dofs_per_node: 1,
        periodic: false,
    }
}

fn orderings(grid: GridShape) -> [ColumnOrdering; 4] {
    [
        ColumnOrdering::Auto,
        ColumnOrdering::Amd,
        ColumnOrdering::NestedDissection {
            grid,
            separator_width: 2,
        },
        ColumnOrdering::nested_dissection_for_lu(grid, 2),
    ]
}

#[test]
fn every_ordering_solves_poisson_and_convection_diffusion_like_colamd() {
    let n = 24;
    let systems = [
        Poisson2d::new(n).system(),
        ConvectionDiffusion2d::new(n, [30.0, -20.0]).system(),
    ];
    for system in &systems {
        let reference = solve(&mut SparseLu::default(), system);
        let b = norm(&system.rhs);
        for ordering in orderings(square_grid(n)) {
            let x = solve(&mut lu_with(ordering), system);
            let residual = system.residual_norm(&x);
            assert!(residual <= 1e-13 * b, "{ordering:?}: {residual:e}"); // round-off only
            // cond(A) ~ 4 / (pi h)^2 ~ 250: round-off differences of the factors only
            assert!(max_abs_difference(&x, &reference) <= 1e-11, "{ordering:?}");
        }
    }
}

#[test]
fn every_ordering_solves_random_diagonally_dominant_systems() {
    let system = RandomDiagonallyDominant {
        n: 300,
        off_diagonals: 4,
        seed: 7,
    }
    .system();
    let reference = solve(&mut SparseLu::default(), &system);
    let b = norm(&system.rhs);
    // not a grid: a 300 x 1 "grid" gives a one-dimensional dissection, still a valid order
    let line = GridShape {
        n2: 300,
        n3: 1,
        dofs_per_node: 1,
        periodic: false,
    };
    let reversed: Vec<usize> = (0..300).rev().collect();
    let mut solvers: Vec<SparseLu> = orderings(line).into_iter().map(lu_with).collect();
    solvers.push(SparseLu::default().with_column_permutation(reversed));
    for mut lu in solvers {
        let x = solve(&mut lu, &system);
        assert!(system.residual_norm(&x) <= 1e-13 * b); // strictly dominant: round-off only
        assert!(max_abs_difference(&x, &reference) <= 1e-12);
    }
}

#[test]
fn nested_dissection_ordering_equals_the_same_permutation_given_explicitly() {
    // On the 5-point stencil COLAMD has the smaller bound (60 x 60: 345,104 vs 436,776 for
    // separators 2 lines wide); the dissection wins on wider stencils with several unknowns
    // per node (see `ColumnOrdering`). Here: the analysis uses exactly the given order.
    let n = 60;
    let system = Poisson2d::new(n).system();
    let mut nd = lu_with(ColumnOrdering::nested_dissection_for_lu(square_grid(n), 1));
    nd.analyse(&system.pattern).unwrap();
    let perm = nested_dissection_grid(square_grid(n), 2);
    assert_eq!(nd.column_permutation().unwrap(), perm.as_slice());
    let mut explicit = SparseLu::default().with_column_permutation(perm);
    explicit.analyse(&system.pattern).unwrap();
    assert_eq!(nd.structural_fill_bound(), explicit.structural_fill_bound());
    assert_eq!(nd.structural_fill_bound(), Some(436_776));
    assert!(nd.structural_fill_bound().unwrap() >= system.pattern.nnz());
}

#[test]
fn cholesky_with_nested_dissection_solves_poisson() {
    let n = 24;
    let system = Poisson2d::new(n).system();
    let reference = solve(&mut SparseCholesky::default(), &system);
    let mut chol = SparseCholesky::new(DirectParams {
        ordering: ColumnOrdering::NestedDissection {
            grid: square_grid(n),
            separator_width: 1,
        },
        ..Default::default()
    })
    .unwrap();
    let x = solve(&mut chol, &system);
    assert!(system.residual_norm(&x) <= 1e-13 * norm(&system.rhs)); // round-off only
    assert!(max_abs_difference(&x, &reference) <= 1e-12);
}

#[test]
fn singular_matrix_with_nested_dissection_is_a_typed_error() {
    // Graph Laplacian of the 6 x 6 grid (Neumann everywhere): constants are in the kernel.
    let n = 6;
    let mut triplets = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let k = i + n * j;
            let neighbours = [
                (i + 1 < n).then(|| k + 1),
                (i > 0).then(|| k - 1),
                (j + 1 < n).then(|| k + n),
                (j > 0).then(|| k - n),
            ];
            let mut degree = 0.0;
            for m in neighbours.into_iter().flatten() {
                triplets.push((k, m, -1.0));
                degree += 1.0;
            }
            triplets.push((k, k, degree));
        }
    }
    let rhs = (0..n * n).map(|k| k as f64).collect();
    let system = LinearSystem::from_triplets(n * n, &triplets, rhs);
    let mut lu = lu_with(ColumnOrdering::nested_dissection_for_lu(square_grid(n), 1));
    lu.analyse(&system.pattern).unwrap();
    let mut x = system.rhs.clone();
    let result = lu
        .factor(&system.values)
        .and_then(|()| lu.solve_in_place(&mut x));
    assert!(
        matches!(result, Err(SolverError::Singular { .. })),
        "{result:?}"
    );
}

#[test]
fn orderings_that_do_not_fit_the_pattern_are_rejected() {
    let system = Poisson2d::new(5).system();
    // nested dissection of a square grid of `n` nodes a side, separators `width` lines wide
    let analyse = |n: usize, width: usize| {
        lu_with(ColumnOrdering::NestedDissection {
            grid: square_grid(n),
            separator_width: width,
        })
        .analyse(&system.pattern)
    };
    let wrong_grid = analyse(4, 2);
    assert!(matches!(
        wrong_grid,
        Err(SolverError::DimensionMismatch {
            expected: 25,
            found: 16,
            ..
        })
    ));
    let zero_width = analyse(5, 0);
    assert!(matches!(
        zero_width,
        Err(SolverError::InvalidParameter {
            field: "separator_width",
            ..
        })
    ));
    let mut repeated: Vec<usize> = (0..25).collect();
    repeated[3] = 4;
    let not_a_permutation = SparseLu::default()
        .with_column_permutation(repeated)
        .analyse(&system.pattern);
    assert!(matches!(
        not_a_permutation,
        Err(SolverError::InvalidParameter {
            field: "column permutation",
            ..
        })
    ));
    let too_short = SparseLu::default()
        .with_column_permutation((0..24).collect())
        .analyse(&system.pattern);
    assert!(matches!(
        too_short,
        Err(SolverError::DimensionMismatch { .. })
    ));
}

#[test]
fn ordering_round_trips_through_serde_and_defaults_to_auto() {
    let params: DirectParams = serde_json::from_str("{}").unwrap();
    assert_eq!(params.ordering, ColumnOrdering::Auto);
    let params = DirectParams {
        ordering: ColumnOrdering::NestedDissection {
            grid: GridShape {
                n2: 2000,
                n3: 321,
                dofs_per_node: 2,
                periodic: false,
            },
            separator_width: 2,
        },
        ..Default::default()
    };
    let json = serde_json::to_string(&params).unwrap();
    assert!(json.contains("\"nested-dissection\""), "{json}");
    assert_eq!(serde_json::from_str::<DirectParams>(&json).unwrap(), params);
    let amd: ColumnOrdering = serde_json::from_str("\"amd\"").unwrap();
    assert_eq!(amd, ColumnOrdering::Amd);
}

#[test]
fn empty_pattern_with_every_ordering_is_trivial() {
    let (pattern, _) = SparsityPattern::from_entries(0, 0, &[]).unwrap();
    let empty = GridShape {
        n2: 0,
        n3: 0,
        dofs_per_node: 2,
        periodic: false,
    };
    for ordering in orderings(empty) {
        let mut lu = lu_with(ordering);
        lu.analyse(&pattern).unwrap();
        lu.factor(&[]).unwrap();
        lu.solve_in_place(&mut []).unwrap();
    }
}

proptest! {
    #[test]
    fn nested_dissection_is_a_permutation_for_any_grid(
        n2 in 0usize..70,
        n3 in 0usize..70,
        dofs_per_node in 1usize..4,
        separator_width in 1usize..5,
        periodic in any::<bool>(),
    ) {
        let grid = GridShape { n2, n3, dofs_per_node, periodic };
        let perm = nested_dissection_grid(grid, separator_width);
        prop_assert!(is_permutation(&perm, grid.dof_count()));
        // a node's unknowns stay together, in order
        for chunk in perm.chunks_exact(dofs_per_node) {
            prop_assert_eq!(chunk[0] % dofs_per_node, 0);
            for (c, &p) in chunk.iter().enumerate() {
                prop_assert_eq!(p, chunk[0] + c);
            }
        }
    }
}
