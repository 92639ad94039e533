//! Benchmark of the matrix-free 3-D operator against the assembled one: the finite-width
//! body on the elliptical prism `a = 2`, `b = 1.5` (width 1, `h = 1`, `E = 1e3`, `nu = 1/4`,
//! `x2 in [-pi/2, pi/2]`, end stresses 1 and 1.5) with the contact face clamped (`v = 0` on
//! `x3 = 0`: the bulk problem of the stuck start, symmetric positive definite), solved by CG
//! to `1e-8` with a multigrid V-cycle.
//!
//! Run one size and path per process so the peak memory (VmHWM) belongs to it:
//! ```text
//! cargo run --release -p capstan-elasticity --example bench_matrix_free -- 17 129 17 1 mf
//! cargo run --release -p capstan-elasticity --example bench_matrix_free -- 17 129 17 1 assembled
//! ```
//! Arguments: nodes `n1 n2 n3`, the order `p` (Qp hexahedra with GLL nodes; 1 and 2 are
//! Q1 and Q2), the path: `mf` (matrix-free operator, p-multigrid / semi-coarsening to an
//! assembled Q1 level, Galerkin below) or `assembled` (the assembled operator with the box's
//! Galerkin multigrid, as `solver.linear = "multigrid"`; `p <= 2`), or `compare` (both
//! operators in one process: their actions compared and their applications timed
//! alternately, see [`compare`]).
//! Prints one JSON line: unknowns, set-up seconds (operator and multigrid), seconds per
//! operator application (at least 20 applications and 2e7 unknowns' worth: wall and CPU; with `RAYON_NUM_THREADS=1` the CPU
//! time is the one to compare on a loaded machine), CG iterations and seconds, the relative residual,
//! max `|v^2|`, CPU seconds and VmHWM in MiB.

mod common;

use std::sync::Arc;
use std::time::Instant;

use capstan_elasticity::finite_element::VolumetricIntegration;
use capstan_elasticity::solid::{
    FaceComponent, FaceCondition, HexElement, SolidBody, SolidBoundary, SolidMatrixFree,
    SolidMultigridParams,
};
use capstan_elasticity::solvers::{
    CsrMatrix, KrylovMethod, KrylovParams, LinearOperator, Multigrid, MultigridParams,
    Preconditioner, SilentObserver, krylov_solve_operator,
};
use capstan_elasticity::verification::peak_memory_mib;
use capstan_geometry::{EllipticalPrism, ShellChart};
use common::{ExampleArgs, cpu_seconds};

fn main() {
    let args = ExampleArgs::from_env();
    let nodes = [
        args.positional(0, 17),
        args.positional(1, 129),
        args.positional(2, 17),
    ];
    let p: usize = args.positional(3, 1);
    let path = args.word(4).unwrap_or("mf").to_string();
    let mut body = SolidBody::new(EllipticalPrism::new(2.0, 1.5).unwrap(), [-0.5, 0.5], nodes);
    body.order = HexElement::Gll(p);
    let mut boundary = body.boundary(1.0, 1.5);
    boundary.faces[4] = FaceCondition([
        FaceComponent::fixed(),
        FaceComponent::fixed(),
        FaceComponent::fixed(),
    ]);
    if path == "compare" {
        compare(&body, &boundary, nodes, p);
        return;
    }
    let start = Instant::now();
    // the operator, its right-hand side and a preconditioner, behind one interface
    let (op, rhs, mut pc, levels): Path = match path.as_str() {
        "mf" => {
            let op = Arc::new(
                SolidMatrixFree::new(
                    ShellChart::new(body.surface),
                    body.material,
                    body.grid().unwrap(),
                    &boundary,
                    None,
                    body.order,
                    VolumetricIntegration::Full,
                )
                .unwrap(),
            );
            let mg = SolidMultigridParams::default()
                .build(&op, &boundary)
                .unwrap();
            let rhs = op.rhs().to_vec();
            let levels = mg.level_sizes();
            (Box::new(Shared(op)), rhs, Box::new(mg), levels)
        }
        _ => {
            let navier = capstan_elasticity::solid::SolidNavier::new(
                ShellChart::new(body.surface),
                body.material,
                body.grid().unwrap(),
                &boundary,
                None,
                body.order,
                VolumetricIntegration::Full,
            )
            .unwrap();
            let system = navier.system();
            let a = Arc::new(CsrMatrix::from_pattern(&system.pattern, &system.values).unwrap());
            let rhs = system.rhs.clone();
            let hierarchy = navier.multigrid_hierarchy(5_000);
            drop(navier);
            let mut mg =
                Multigrid::new(hierarchy.prolongations, MultigridParams::default()).unwrap();
            mg.setup(&a).unwrap();
            let levels = mg.level_sizes();
            (
                Box::new(Shared(Arc::clone(&a))),
                rhs,
                Box::new(Bound { a, mg }),
                levels,
            )
        }
    };
    let setup_seconds = start.elapsed().as_secs_f64();
    let n = rhs.len();
    let x0: Vec<f64> = (0..n).map(|i| ((i * 37) % 101) as f64 / 101.0).collect();
    let mut y = vec![0.0; n];
    // at least 20 applications and 2e7 unknowns' worth (CPU time is counted in 10 ms ticks)
    let reps = 20.max(20_000_000 / n);
    let (t, cpu) = (Instant::now(), cpu_seconds());
    for _ in 0..reps {
        op.apply(&x0, &mut y);
    }
    let apply_seconds = t.elapsed().as_secs_f64() / reps as f64;
    let apply_cpu_seconds = (cpu_seconds() - cpu) / reps as f64;
    let params = KrylovParams {
        method: KrylovMethod::Cg,
        tolerance: 1e-8,
        max_iterations: 500,
        ..Default::default()
    };
    let mut x = vec![0.0; n];
    let t = Instant::now();
    let report = krylov_solve_operator(
        op.as_ref(),
        &rhs,
        &mut x,
        pc.as_mut(),
        &params,
        &mut SilentObserver,
    )
    .unwrap();
    let solve_seconds = t.elapsed().as_secs_f64();
    let mut r = vec![0.0; n];
    op.residual(&x, &rhs, &mut r);
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let max_v2 = x
        .iter()
        .skip(1)
        .step_by(3)
        .fold(0.0f64, |m, v| m.max(v.abs()));
    println!(
        "{{\"nodes\":{nodes:?},\"order\":{p},\"path\":\"{path}\",\"unknowns\":{n},\"levels\":{levels:?},\"setup_seconds\":{setup_seconds:.3},\"apply_seconds\":{apply_seconds:.4},\"apply_cpu_seconds\":{apply_cpu_seconds:.4},\"unknowns_per_second\":{:.3e},\"cg_iterations\":{},\"solve_seconds\":{solve_seconds:.3},\"relative_residual\":{:.2e},\"max_v2\":{max_v2:.9e},\"cpu_seconds\":{:.1},\"vm_hwm_mib\":{:.0}}}",
        n as f64 / apply_seconds,
        report.iterations,
        norm(&r) / norm(&rhs),
        cpu_seconds(),
        peak_memory_mib(),
    );
}

/// The `compare` path: the matrix-free operator and the assembled matrix of the same grid
/// in one process, their actions on one vector compared (`max |A_mf x - A x| / max |A x|`),
/// then ten rounds of five applications of each, alternating, timed in CPU seconds (run it
/// with `RAYON_NUM_THREADS=1` on a loaded machine: the ratio is the number to read).
fn compare(
    body: &SolidBody<EllipticalPrism<f64>>,
    boundary: &SolidBoundary,
    nodes: [usize; 3],
    p: usize,
) {
    let build = || {
        SolidMatrixFree::new(
            ShellChart::new(body.surface),
            body.material,
            body.grid().unwrap(),
            boundary,
            None,
            body.order,
            VolumetricIntegration::Full,
        )
        .unwrap()
    };
    let mf = build();
    let navier = capstan_elasticity::solid::SolidNavier::new(
        ShellChart::new(body.surface),
        body.material,
        body.grid().unwrap(),
        boundary,
        None,
        body.order,
        VolumetricIntegration::Full,
    )
    .unwrap();
    let system = navier.system();
    let a = CsrMatrix::from_pattern(&system.pattern, &system.values).unwrap();
    drop(navier);
    let n = a.nrows();
    let x: Vec<f64> = (0..n)
        .map(|i| ((i * 37) % 101) as f64 / 101.0 - 0.5)
        .collect();
    let (mut y, mut z) = (vec![0.0; n], vec![0.0; n]);
    mf.apply(&x, &mut y);
    a.mul_vec(&x, &mut z);
    let max = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |m, t| m.max(t.abs()));
    let difference = max(&mut y.iter().zip(&z).map(|(a, b)| a - b)) / max(&mut z.iter().copied());
    let reps = 5.max(4_000_000 / n);
    let (mut t_mf, mut t_csr) = (0.0, 0.0);
    for _ in 0..10 {
        let c = cpu_seconds();
        for _ in 0..reps {
            mf.apply(&x, &mut y);
        }
        let m = cpu_seconds();
        for _ in 0..reps {
            a.mul_vec(&x, &mut z);
        }
        t_mf += m - c;
        t_csr += cpu_seconds() - m;
    }
    let count = (10 * reps) as f64;
    println!(
        "{{\"nodes\":{nodes:?},\"order\":{p},\"path\":\"compare\",\"unknowns\":{n},\"threads\":{},\"difference\":{difference:.2e},\"mf_apply_cpu_seconds\":{:.3e},\"csr_apply_cpu_seconds\":{:.3e},\"mf_over_csr\":{:.3},\"mf_bytes\":{},\"csr_bytes\":{}}}",
        rayon::current_num_threads(),
        t_mf / count,
        t_csr / count,
        t_mf / t_csr,
        mf.bytes(),
        a.bytes(),
    );
}

/// A path: the operator, its right-hand side, its preconditioner and the level sizes.
type Path = (
    Box<dyn LinearOperator>,
    Vec<f64>,
    Box<dyn Preconditioner>,
    Vec<usize>,
);

/// An operator shared with its preconditioner.
struct Shared<T>(Arc<T>);

impl<T: LinearOperator + Send> LinearOperator for Shared<T> {
    fn dimension(&self) -> usize {
        self.0.dimension()
    }
    fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.0.apply(x, y);
    }
    fn diagonal(&self) -> Vec<f64> {
        self.0.diagonal()
    }
}

/// The assembled path's V-cycle bound to its matrix.
struct Bound {
    a: Arc<CsrMatrix>,
    mg: Multigrid,
}

impl Preconditioner for Bound {
    fn apply(&mut self, r: &[f64], z: &mut [f64]) {
        self.mg.with(&self.a).apply(r, z);
    }
}
