//! The two kernels of `SparseLu` (`LuKind`): the multifrontal kernel agrees with the supernodal
//! one and with a dense LU, pivots inside its fronts, falls back to the supernodal kernel when
//! a pivot from outside a front is needed, and reports singular matrices as typed errors.

use capstan_solvers::samples::{
    ConvectionDiffusion2d, LinearSystem, Poisson2d, RandomDiagonallyDominant, SplitMix64,
};
use faer::linalg::solvers::Solve;

use capstan_solvers::{
    ColumnOrdering, DirectParams, GridShape, LinearSolver, LuKind, SolverError, SparseLu,
};

fn lu(kind: LuKind, ordering: ColumnOrdering) -> SparseLu {
    SparseLu::new(DirectParams {
        lu_kind: kind,
        ordering,
        ..Default::default()
    })
    .unwrap()
}

fn solve(lu: &mut SparseLu, system: &LinearSystem) -> Result<Vec<f64>, SolverError> {
    lu.analyse(&system.pattern)?;
    lu.factor(&system.values)?;
    let mut x = system.rhs.clone();
    lu.solve_in_place(&mut x)?;
    Ok(x)
}

/// Dense LU with partial pivoting (faer) of the same system.
fn dense_solve(system: &LinearSystem) -> Vec<f64> {
    let n = system.dimension();
    let mut a = faer::Mat::<f64>::zeros(n, n);
    for ((i, j), v) in system.pattern.entries().zip(&system.values) {
        a[(i, j)] += v;
    }
    let b = faer::Mat::from_fn(n, 1, |i, _| system.rhs[i]);
    let x = a.partial_piv_lu().solve(&b);
    (0..n).map(|i| x[(i, 0)]).collect()
}

fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// A random sparse matrix that is not diagonally dominant: every diagonal entry is small
/// next to its row, so partial pivoting leaves the diagonal often.
fn random_general(n: usize, per_row: usize, seed: u64) -> LinearSystem {
    let mut rng = SplitMix64(seed);
    let mut t = Vec::new();
    for i in 0..n {
        t.push((i, i, 0.05 * rng.uniform()));
        for _ in 0..per_row {
            let j = (rng.next_u64() % n as u64) as usize;
            t.push((i, j, rng.uniform()));
        }
        t.push((i, (i + 1) % n, 1.0 + rng.uniform()));
    }
    let rhs = (0..n).map(|_| rng.uniform()).collect();
    LinearSystem::from_triplets(n, &t, rhs)
}

fn samples() -> Vec<(&'static str, LinearSystem)> {
    vec![
        ("poisson", Poisson2d::new(12).system()),
        (
            "convection-diffusion",
            ConvectionDiffusion2d::new(12, [30.0, -20.0]).system(),
        ),
        (
            "random dominant",
            RandomDiagonallyDominant {
                n: 300,
                off_diagonals: 4,
                seed: 7,
            }
            .system(),
        ),
        ("random general", random_general(300, 3, 11)),
    ]
}

#[test]
fn multifrontal_agrees_with_supernodal_and_dense_on_samples() {
    for (name, system) in samples() {
        let dense = dense_solve(&system);
        let mut multifrontal = lu(LuKind::Multifrontal, ColumnOrdering::Auto);
        let x = solve(&mut multifrontal, &system).unwrap();
        let mut supernodal = lu(LuKind::Supernodal, ColumnOrdering::Auto);
        let y = solve(&mut supernodal, &system).unwrap();
        assert_eq!(supernodal.last_kind(), Some(LuKind::Supernodal));
        // the samples are well conditioned (cond < 1e4): round-off only
        assert!(relative_difference(&x, &dense) < 1e-10, "{name}");
        assert!(relative_difference(&x, &y) < 1e-10, "{name}");
        assert!(system.residual_norm(&x) < 1e-10, "{name}");
    }
}

#[test]
fn multifrontal_keeps_its_pivots_inside_the_fronts_on_the_samples() {
    // not "random general": its diagonal is small next to its rows, and some column's pivot
    // lies outside its front (that sample is solved through the fallback)
    for (name, system) in samples().into_iter().take(3) {
        let mut lu = lu(LuKind::Auto, ColumnOrdering::Auto);
        solve(&mut lu, &system).unwrap();
        assert_eq!(lu.last_kind(), Some(LuKind::Multifrontal), "{name}");
        let stored = lu.multifrontal_factor_entries().unwrap();
        assert!(stored >= system.pattern.nnz() / 2, "{name}: {stored}");
    }
}

#[test]
fn multifrontal_stores_less_than_the_supernodal_bound_on_a_grid() {
    // the point of the kernel: the structure of A + A^T instead of A^T A
    let system = ConvectionDiffusion2d::new(40, [10.0, 5.0]).system();
    let grid = GridShape {
        n2: 40,
        n3: 40,
        dofs_per_node: 1,
        periodic: false,
    };
    let nd = ColumnOrdering::NestedDissection {
        grid,
        separator_width: 1,
    };
    let mut multifrontal = lu(LuKind::Multifrontal, nd);
    let x = solve(&mut multifrontal, &system).unwrap();
    let mut supernodal = lu(LuKind::Supernodal, ColumnOrdering::Auto);
    let y = solve(&mut supernodal, &system).unwrap();
    assert!(relative_difference(&x, &y) < 1e-10);
    let stored = multifrontal.multifrontal_factor_entries().unwrap();
    let bound = supernodal.structural_fill_bound().unwrap();
    // 5-point stencil: 84,628 against 124,972 (the Navier operator's 9-point, 2-unknown
    // stencil gains more, see `LuKind`)
    assert!(stored < bound, "stored {stored}, supernodal bound {bound}");
    assert_eq!(supernodal.multifrontal_factor_entries(), None);
}

#[test]
fn pivoting_inside_a_front_solves_a_zero_diagonal() {
    // [[0, 2], [1, 0]]: both columns form one front, the pivots are its off-diagonal entries
    let system = LinearSystem::from_triplets(2, &[(0, 1, 2.0), (1, 0, 1.0)], vec![4.0, 3.0]);
    let mut lu = lu(LuKind::Multifrontal, ColumnOrdering::Auto);
    let x = solve(&mut lu, &system).unwrap();
    assert_eq!(lu.last_kind(), Some(LuKind::Multifrontal));
    assert_eq!(x, vec![3.0, 2.0]); // one division by a power of two per unknown: exact
}

/// `n x n` identity except rows and columns `0` and `n - 1`, which hold
/// `[[d, 1], [1, d]]`; the identity order keeps column 0 alone in its front.
fn swapped_ends(n: usize, d: f64) -> LinearSystem {
    let mut t: Vec<_> = (1..n - 1).map(|i| (i, i, 2.0)).collect();
    t.extend([
        (0, 0, d),
        (0, n - 1, 1.0),
        (n - 1, 0, 1.0),
        (n - 1, n - 1, d),
    ]);
    let rhs = (0..n).map(|i| 1.0 + i as f64).collect();
    LinearSystem::from_triplets(n, &t, rhs)
}

#[test]
fn front_without_acceptable_pivot_falls_back_to_supernodal() {
    let n = 50;
    let needs_pivot = swapped_ends(n, 0.0);
    let identity: Vec<usize> = (0..n).collect();
    let mut lu = SparseLu::new(DirectParams {
        lu_kind: LuKind::Multifrontal,
        ..Default::default()
    })
    .unwrap()
    .with_column_permutation(identity);
    let x = solve(&mut lu, &needs_pivot).unwrap();
    assert_eq!(lu.last_kind(), Some(LuKind::Supernodal));
    assert!(relative_difference(&x, &dense_solve(&needs_pivot)) < 1e-14); // permutation: exact
    // the structure is kept: new values with a usable diagonal go back to the fronts
    let fine = swapped_ends(n, 4.0);
    lu.factor(&fine.values).unwrap();
    assert_eq!(lu.last_kind(), Some(LuKind::Multifrontal));
    let mut x = fine.rhs.clone();
    lu.solve_in_place(&mut x).unwrap();
    assert!(relative_difference(&x, &dense_solve(&fine)) < 1e-14);
    assert_eq!(lu.factorisations(), 2);
}

#[test]
fn singular_matrices_are_typed_errors_never_nan() {
    // exactly singular: all ones
    let ones = LinearSystem::from_triplets(
        2,
        &[(0, 0, 1.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 1.0)],
        vec![1.0, 2.0],
    );
    let equal_rows = poisson_with_equal_rows();
    for system in [ones, equal_rows] {
        for kind in [LuKind::Multifrontal, LuKind::Supernodal] {
            let mut lu = lu(kind, ColumnOrdering::Auto);
            let result = solve(&mut lu, &system);
            assert!(
                matches!(result, Err(SolverError::Singular { .. })),
                "{kind:?}: {result:?}"
            );
        }
    }
}

#[test]
fn lu_kind_is_kebab_case_and_defaults_to_auto() {
    let params: DirectParams = serde_json::from_str("{}").unwrap();
    assert_eq!(params.lu_kind, LuKind::Auto);
    assert_eq!(LuKind::Auto.resolved(), LuKind::Multifrontal);
    assert_eq!(LuKind::Supernodal.resolved(), LuKind::Supernodal);
    let params: DirectParams = serde_json::from_str(r#"{"lu_kind": "supernodal"}"#).unwrap();
    assert_eq!(params.lu_kind, LuKind::Supernodal);
    assert_eq!(
        serde_json::to_string(&LuKind::Multifrontal).unwrap(),
        "\"multifrontal\""
    );
}

#[test]
fn multifrontal_matches_dense_lu_on_random_general_matrices() {
    // small diagonals (pivots inside and outside the fronts, fallbacks) and large ones, with
    // AMD and the identity order; both kinds of result are checked against a dense LU
    let mut kinds_seen = [false; 2];
    for seed in 0..40u64 {
        let n = 5 + (seed as usize * 7) % 70;
        let system = random_general(n, 1 + seed as usize % 3, 100 + seed);
        let dense = dense_solve(&system);
        let order = if seed % 2 == 0 {
            None
        } else {
            Some((0..n).collect::<Vec<_>>())
        };
        let mut lu = lu(LuKind::Multifrontal, ColumnOrdering::Auto);
        if let Some(order) = order {
            lu = lu.with_column_permutation(order);
        }
        let x = solve(&mut lu, &system).unwrap();
        kinds_seen[usize::from(lu.last_kind() == Some(LuKind::Multifrontal))] = true;
        // measured at most 2.8e-14 (12 of the 40 stay in the fronts): round-off only
        let diff = relative_difference(&x, &dense);
        assert!(diff < 1e-12, "seed {seed}, n {n}: {diff:e}");
    }
    assert_eq!(
        kinds_seen,
        [true, true],
        "both the fronts and the fallback are exercised"
    );
}

/// `k` right-hand sides (column-major): dense pseudo-random columns.
fn random_block(n: usize, k: usize, seed: u64) -> Vec<f64> {
    let mut rng = SplitMix64(seed);
    (0..n * k).map(|_| rng.uniform()).collect()
}

#[test]
fn multifrontal_block_solve_equals_single_solves() {
    // samples, and random matrices with row swaps inside the fronts (the diagonal 5x the
    // other entries keeps most pivots in the fronts) or falling back to the supernodal kernel
    let mut systems = samples();
    systems.extend((0..6).map(|seed| {
        let mut system = random_general(60 + 40 * seed as usize, 3, 11 + seed);
        let mut rng = SplitMix64(seed);
        for ((i, j), v) in system.pattern.entries().zip(system.values.iter_mut()) {
            if i == j {
                *v += 5.0 * rng.uniform();
            }
        }
        ("random general, larger diagonal", system)
    }));
    let mut kinds_seen = [false; 2];
    for (name, system) in systems {
        let n = system.dimension();
        let mut lu = lu(LuKind::Auto, ColumnOrdering::Auto);
        lu.analyse(&system.pattern).unwrap();
        lu.factor(&system.values).unwrap();
        kinds_seen[usize::from(lu.last_kind() == Some(LuKind::Multifrontal))] = true;
        // one column, a few, one internal block (64), and widths that are no multiple of it
        for k in [1, 3, 64, 67, 130] {
            let rhs = random_block(n, k, k as u64);
            let mut blocked = rhs.clone();
            lu.solve_many_in_place(&mut blocked, k).unwrap();
            let mut single = rhs.clone();
            for column in single.chunks_exact_mut(n) {
                lu.solve_in_place(column).unwrap();
            }
            for c in 0..k {
                let column = c * n..(c + 1) * n;
                let diff = relative_difference(&blocked[column.clone()], &single[column]);
                // same factors, sums in another order: measured at most 2.3e-13 (random
                // matrices, some ill conditioned), 1e-15 on the samples
                assert!(diff < 1e-12, "{name}, k {k}, column {c}: {diff:e}");
            }
        }
    }
    assert!(kinds_seen[1], "the multifrontal kernel is exercised");
}

#[test]
fn block_check_rejects_a_column_that_fails_the_residual_test() {
    // a residual tolerance of 1e-300 accepts only exact solutions: the zero columns (x = 0,
    // residual 0) pass, one random column cannot, whatever the refinement
    let system = Poisson2d::new(9).system();
    let n = system.dimension();
    for kind in [LuKind::Multifrontal, LuKind::Supernodal] {
        let mut lu = SparseLu::new(DirectParams {
            lu_kind: kind,
            residual_tolerance: 1e-300,
            refinement_steps: 2,
            ..Default::default()
        })
        .unwrap();
        lu.analyse(&system.pattern).unwrap();
        lu.factor(&system.values).unwrap();
        for k in [2, 3, 70] {
            let mut rhs = vec![0.0; n * k];
            lu.solve_many_in_place(&mut rhs, k).unwrap();
            assert!(rhs.iter().all(|&v| v == 0.0), "{kind:?}");
            let failing = k / 2;
            rhs[failing * n..(failing + 1) * n].copy_from_slice(&random_block(n, 1, 5));
            let result = lu.solve_many_in_place(&mut rhs, k);
            assert!(
                matches!(result, Err(SolverError::Singular { pivot: None })),
                "{kind:?}, k {k}: {result:?}"
            );
        }
    }
}

#[test]
fn block_solve_of_an_exactly_singular_matrix_is_a_typed_error() {
    // two equal rows: the factorisation or the checked block solve reports it, never NaN
    let system = poisson_with_equal_rows();
    let mut lu = lu(LuKind::Multifrontal, ColumnOrdering::Auto);
    lu.analyse(&system.pattern).unwrap();
    let mut rhs = random_block(100, 5, 1);
    let result = lu
        .factor(&system.values)
        .and_then(|()| lu.solve_many_in_place(&mut rhs, 5));
    assert!(
        matches!(result, Err(SolverError::Singular { .. })),
        "{result:?}"
    );
}

/// A 10 x 10 Poisson matrix with row 37 replaced by row 36: exactly singular.
fn poisson_with_equal_rows() -> LinearSystem {
    let poisson = Poisson2d::new(10).system();
    let mut t: Vec<(usize, usize, f64)> = poisson
        .pattern
        .entries()
        .zip(&poisson.values)
        .filter(|((i, _), _)| *i != 37)
        .map(|((i, j), &v)| (i, j, v))
        .collect();
    let copied: Vec<_> = t
        .iter()
        .filter(|(i, _, _)| *i == 36)
        .map(|&(_, j, v)| (37, j, v))
        .collect();
    t.extend(copied);
    LinearSystem::from_triplets(100, &t, vec![1.0; 100])
}
