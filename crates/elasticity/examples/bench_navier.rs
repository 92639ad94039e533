//! Benchmark of the finite-difference Navier operator on the paper's ellipse (section 3:
//! `a = b = 2`, `h = 1`, end tractions 1 and 2, free outer surface, `v^2 = v^3 = 0` on
//! `x3 = 0` as a linear stand-in for the contact).
//!
//! Run one size per process so the peak memory (VmHWM) belongs to that size:
//! ```text
//! cargo run --release -p capstan-elasticity --example bench_navier -- 2000 321
//! cargo run --release -p capstan-elasticity --example bench_navier -- 2000 321 --ordering nd
//! cargo run --release -p capstan-elasticity --example bench_navier -- 1000 161 --lu-kind supernodal
//! cargo run --release -p capstan-elasticity --example bench_navier -- 250 41 --iterative
//! cargo run --release -p capstan-elasticity --example bench_navier -- 250 41 --rhs 252
//! ```
//! Prints one JSON line: grid, unknowns, nonzeros, LU kernel and ordering, seconds for
//! geometry+operator, pattern, fill, LU analyse, factor, solve, the static fill bound of the
//! ordering (`2 nnz(R) - n`, `R^T R = A^T A` permuted), the values stored by the multifrontal
//! kernel, relative residual, VmHWM in MiB; with `--iterative` also damped Jacobi (relaxation
//! 1/2) and Gauss-Seidel to a relative residual of 1e-8; with `--compare` the largest difference
//! to the other LU kernel's solution (default ordering), relative to the largest unknown; with
//! `--rhs K` the seconds for `K` right-hand sides (unit vectors `e_i`, `i = 7919 c mod n`, as
//! in the contact condensation) solved one `solve_in_place` at a time against one blocked
//! `solve_many_in_place`, their ratio, and the largest difference of the two, relative to the
//! largest entry.
//!
//! `--lu-kind auto` (default: multifrontal), `multifrontal` or `supernodal` (faer's, on the
//! structure of `A^T A`). `--ordering auto` (default: AMD on `A + A^T` for the multifrontal
//! kernel, COLAMD for the supernodal one), `colamd` (supernodal only), `nd` (nested dissection
//! of the grid, with separators `--separator-width W` lines wide, default 1 for the multifrontal
//! kernel and 2 for the supernodal one) or `amd` (AMD on `A + A^T`).

mod common;

use std::time::Instant;

use capstan_elasticity::samples::PaperEllipse;
use capstan_elasticity::solvers::{
    ColumnOrdering, DirectParams, GridShape, IterativeParams, LinearBackend, LinearSolver, LuKind,
    SparseLu, max_abs, max_abs_difference,
};
use capstan_elasticity::verification::{GridLevel, peak_memory_mib};
use capstan_elasticity::{Discretisation, LinearSystem};
use common::ExampleArgs;

fn iterative(
    system: &LinearSystem,
    backend: LinearBackend,
    relaxation: f64,
    reference: &[f64],
) -> String {
    let params = IterativeParams {
        tolerance: 1e-8,
        max_iterations: 2_000_000,
        relaxation,
    };
    let mut solver = backend
        .build(
            &capstan_elasticity::solvers::LinearSettings {
                iterative: params,
                ..Default::default()
            },
            &(),
        )
        .expect("valid parameters");
    let t = Instant::now();
    let result = system.solve(&mut *solver);
    let seconds = t.elapsed().as_secs_f64();
    let diff = result
        .as_ref()
        .map_or(f64::NAN, |v| max_abs_difference(v, reference));
    format!(
        "{{\"backend\":\"{backend}\",\"relaxation\":{relaxation},\"ok\":{},\"iterations\":{:?},\"seconds\":{seconds:.3},\"max_diff_to_lu\":{diff:.3e}}}",
        result.is_ok(),
        solver.last_iterations()
    )
}

fn main() {
    let args = ExampleArgs::from_env();
    let n2 = args.positional(0, 250);
    let n3 = args.positional(1, 41);
    let with_iterative = args.flag("--iterative");
    let with_compare = args.flag("--compare");
    let ordering_name = args.option("--ordering").unwrap_or("auto");
    let lu_kind = match args.option("--lu-kind").unwrap_or("auto") {
        "auto" => LuKind::Auto,
        "multifrontal" => LuKind::Multifrontal,
        "supernodal" => LuKind::Supernodal,
        other => panic!("unknown LU kind `{other}`: expected auto, multifrontal or supernodal"),
    };
    // the supernodal structure (A^T A) reaches twice as far as A + A^T
    let default_width = if lu_kind == LuKind::Supernodal { 2 } else { 1 };
    let separator_width: usize = args
        .option("--separator-width")
        .map_or(default_width, |w| w.parse().expect("width"));
    // dof = 2 (i2 n3 + i3) + c, the numbering GridShape describes
    let grid = GridShape {
        n2,
        n3,
        dofs_per_node: 2,
        periodic: false,
    };
    let ordering = match ordering_name {
        "auto" => ColumnOrdering::Auto,
        "colamd" if lu_kind == LuKind::Supernodal => ColumnOrdering::Auto,
        "amd" => ColumnOrdering::Amd,
        "nd" => ColumnOrdering::NestedDissection {
            grid,
            separator_width,
        },
        other => {
            panic!("unknown ordering `{other}`: expected auto, colamd (supernodal only), nd or amd")
        }
    };
    let problem = PaperEllipse::default();

    let t = Instant::now();
    let op = problem.operator(GridLevel { n2, n3 }).expect("operator");
    let t_operator = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let entries = op.entries().expect("entries");
    let mut system = LinearSystem::from_entries(op.dof_count(), &entries).expect("pattern");
    drop(entries);
    let t_pattern = t.elapsed().as_secs_f64();
    let t = Instant::now();
    op.refill(&mut system).expect("fill");
    let t_fill = t.elapsed().as_secs_f64();
    assert_eq!(op.dof_count(), grid.dof_count());
    assert_eq!(
        op.dof([n2 - 1, 1], capstan_elasticity::Component::X2),
        2 * ((n2 - 1) * n3 + 1)
    );

    let mut lu = SparseLu::new(DirectParams {
        ordering,
        lu_kind,
        ..Default::default()
    })
    .expect("valid parameters");
    let t = Instant::now();
    lu.analyse(&system.pattern).expect("analyse");
    let t_analyse = t.elapsed().as_secs_f64();
    let fill_bound = lu.structural_fill_bound().unwrap_or(0);
    let t = Instant::now();
    lu.factor(&system.values).expect("factor");
    let t_factor = t.elapsed().as_secs_f64();
    let kind_used = lu
        .last_kind()
        .map_or("none".into(), |k| format!("{k:?}").to_lowercase());
    let factor_entries = lu.multifrontal_factor_entries().unwrap_or(0);
    let mut v = system.rhs.clone();
    let t = Instant::now();
    lu.solve_in_place(&mut v).expect("solve");
    let t_solve = t.elapsed().as_secs_f64();
    let residual = system.relative_residual(&v);
    let hwm = peak_memory_mib();
    let max_v2 = (0..n2)
        .map(|i| v[op.dof([i, n3 - 1], capstan_elasticity::Component::X2)].abs())
        .fold(0.0, f64::max);

    let mut extra = String::new();
    if with_compare {
        // the other kernel with its default ordering, as an independent reference
        let other = if lu.last_kind() == Some(LuKind::Supernodal) {
            LuKind::Multifrontal
        } else {
            LuKind::Supernodal
        };
        let mut reference = SparseLu::new(DirectParams {
            lu_kind: other,
            ..Default::default()
        })
        .expect("valid parameters");
        let w = system.solve(&mut reference).expect("reference solve");
        extra = format!(
            ",\"compare\":{{\"lu_kind\":\"{}\",\"max_relative_diff\":{:.2e}}}",
            format!("{other:?}").to_lowercase(),
            max_abs_difference(&v, &w) / max_abs(&w)
        );
    }
    if let Some(k) = args.option("--rhs") {
        let k: usize = k.parse().expect("number of right-hand sides");
        let n = op.dof_count();
        let mut block = vec![0.0; n * k];
        for (c, col) in block.chunks_exact_mut(n).enumerate() {
            col[(7919 * c) % n] = 1.0;
        }
        let mut looped = block.clone();
        let t = Instant::now();
        for col in looped.chunks_exact_mut(n) {
            lu.solve_in_place(col).expect("single solve");
        }
        let t_loop = t.elapsed().as_secs_f64();
        let t = Instant::now();
        lu.solve_many_in_place(&mut block, k)
            .expect("blocked solve");
        let t_blocked = t.elapsed().as_secs_f64();
        extra += &format!(
            ",\"rhs\":{{\"k\":{k},\"loop_s\":{t_loop:.3},\"blocked_s\":{t_blocked:.3},\"speedup\":{:.1},\"max_relative_diff\":{:.2e}}}",
            t_loop / t_blocked,
            max_abs_difference(&block, &looped) / max_abs(&looped)
        );
    }
    if with_iterative {
        extra += &format!(
            ",\"iterative\":[{},{}]",
            iterative(&system, LinearBackend::JACOBI, 0.5, &v),
            iterative(&system, LinearBackend::GAUSS_SEIDEL, 1.0, &v)
        );
    }
    println!(
        "{{\"n2\":{n2},\"n3\":{n3},\"unknowns\":{},\"nnz\":{},\"lu_kind\":\"{kind_used}\",\"ordering\":\"{ordering_name}\",\"separator_width\":{separator_width},\"operator_s\":{t_operator:.3},\"pattern_s\":{t_pattern:.3},\"fill_s\":{t_fill:.3},\"lu_analyse_s\":{t_analyse:.3},\"lu_factor_s\":{t_factor:.3},\"lu_solve_s\":{t_solve:.3},\"lu_total_s\":{:.3},\"lu_fill_bound\":{fill_bound},\"multifrontal_factor_entries\":{factor_entries},\"relative_residual\":{residual:.2e},\"max_outer_v2\":{max_v2:.4e},\"vm_hwm_mib\":{hwm:.1}{extra}}}",
        op.dof_count(),
        system.pattern.nnz(),
        t_operator + t_pattern + t_fill + t_analyse + t_factor + t_solve,
    );
}
