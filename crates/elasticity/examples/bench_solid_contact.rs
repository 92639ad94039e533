//! Benchmark of the 3-D contact problem: a body of finite width (free sides) on the elliptical
//! prism `a = 2`, `b = 1.5` (the paper's body otherwise: `h = 1`, `E = 1e3`, `nu = 1/4`,
//! `x2 in [-pi/2, pi/2]`, width 1), regularised Coulomb `mu = 0.5`, `eps = 1e-5`, tension
//! ratio 1.5, Q1 hexahedra.
//!
//! Run one size per process so the peak memory (VmHWM) belongs to that size:
//! ```text
//! cargo run --release -p capstan-elasticity --example bench_solid_contact -- 11 201 15 full
//! cargo run --release -p capstan-elasticity --example bench_solid_contact -- 5 41 5 condensed --sweep
//! cargo run --release -p capstan-elasticity --example bench_solid_contact -- 9 257 17 multigrid
//! ```
//! `mf` is the matrix-free full-system Newton (`solver.linear = "matrix-free-mg"`:
//! inexact Newton-Krylov on the sum-factorised operator, p-multigrid/semi-coarsening V-cycle),
//! any element by `--order q1|q2|qpP`, `--width w` the body's width (aspect of the cells),
//! `--forcing eta` every Newton step solved to the same relative tolerance `eta` (Eisenstat-
//! Walker off: `eta_min = eta_max = eta`), so iterations per step compare across sizes at
//! matched forcing; `--sequence` grid sequencing (the body solved on the V-cycle's coarse
//! grids first, each solution prolonged as the next grid's start,
//! `SolidBody::solve_matrix_free_sequenced`; `levels` then lists each grid's nodes, Newton
//! steps and Krylov iterations, and the counts are the fine grid's); `--no-p-levels` takes the
//! V-cycle of `p >= 4` straight from the fine level to Q1 (no intermediate p-levels: the
//! V-cycle before issue 30's p-levels, for comparison).
//! `multigrid` is the full-system Newton with GMRES and the geometric multigrid of the box
//! (`--krylov-tol 1e-8` the relative tolerance of each linear solve, `--smoother jacobi` damped
//! Jacobi instead of Chebyshev, `--power 12` power iterations of its eigenvalue estimate, `--restart m` of GMRES). `--save FILE` (any path) writes the
//! displacement (raw little-endian f64), `--reference FILE` reports the relative max-norm
//! difference `max |v - v_ref| / max |v_ref|` to a saved one (work-precision); `--progress`
//! prints every Newton iterate (seconds since the solve began) to stderr.
//! Prints one JSON line: grid, unknowns, contact unknowns, solver, seconds of the model
//! (assembly), the solver set-up, the solve (and a 26-point ratio sweep from 1.0 to 2.0 with
//! `--sweep`, warm-started), Newton and Krylov iterations, residuals, max `|v^2|`, CPU seconds,
//! VmHWM in MiB.

mod common;

use std::time::Instant;

use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, EndLoads, FullSystemSettings, FullSystemSolver,
};
use capstan_elasticity::contact::{
    MatrixFreeNewton, MatrixFreeSettings, SEQUENCE_COARSEST_UNKNOWNS,
};
use capstan_elasticity::finite_element::ElementOrder;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{HexElement, SolidBody, SolidMultigridParams};
use capstan_elasticity::solvers::{
    KrylovParams, LinearBackend, MultigridParams, Progress, Smoother, SolveStage, max_abs,
    max_abs_difference,
};
use capstan_elasticity::verification::peak_memory_mib;
use capstan_geometry::{EllipticalPrism, Obstacle};
use common::{ExampleArgs, cpu_seconds};

fn main() {
    let args = ExampleArgs::from_env();
    let nodes = [
        args.positional(0, 5),
        args.positional(1, 41),
        args.positional(2, 5),
    ];
    let solver = args.word(3).unwrap_or("full");
    let sweep = args.flag("--sweep");
    let progress = args.flag("--progress");
    let krylov_tol: f64 = args
        .option("--krylov-tol")
        .map_or(1e-8, |t| t.parse().expect("a number"));
    let smoother = match args.option("--smoother") {
        Some("jacobi") => Smoother::Jacobi { omega: 0.6 },
        _ => Smoother::default(),
    };
    let restart: usize = args
        .option("--restart")
        .map_or(KrylovParams::default().restart, |t| {
            t.parse().expect("a count")
        });
    let power_iterations: usize = args
        .option("--power")
        .map_or(12, |t| t.parse().expect("a count"));
    let obstacle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 1.5).expect("valid"));
    let width: f64 = args
        .option("--width")
        .map_or(1.0, |t| t.parse().expect("a number"));
    let mut body = SolidBody::new(obstacle, [-0.5 * width, 0.5 * width], nodes);
    body.order = match args.option("--order").unwrap_or("q1") {
        "q1" => HexElement::Uniform(ElementOrder::Q1),
        "q2" => HexElement::Uniform(ElementOrder::Q2),
        qp => HexElement::Gll(qp.trim_start_matches("qp").parse().expect("q1, q2 or qpP")),
    };
    let eps = 1e-5;
    let params = RegularisedCoulombParams::new(0.5, eps).expect("valid");
    if solver == "mf" {
        let forcing: Option<f64> = args
            .option("--forcing")
            .map(|s| s.parse().expect("--forcing eta in (0, 1)"));
        let sequence = args.flag("--sequence");
        let multigrid = SolidMultigridParams {
            p_levels: !args.flag("--no-p-levels"),
            ..Default::default()
        };
        matrix_free(
            &body,
            multigrid,
            params,
            eps,
            progress,
            [args.option("--save"), args.option("--reference")],
            forcing,
            sequence,
        );
        return;
    }
    let t = Instant::now();
    let model = body
        .model(RegularisedCoulomb, params, eps)
        .expect("a valid model");
    let model_seconds = t.elapsed().as_secs_f64();
    let ratios: Vec<f64> = if sweep {
        (0..26).map(|i| 1.0 + i as f64 / 25.0).collect()
    } else {
        vec![1.5]
    };
    let t = Instant::now();
    let (setup_seconds, results) = match solver {
        "condensed" => {
            let s = BoundarySolver::new(&model, ContactSettings::default()).expect("set-up");
            let setup = t.elapsed().as_secs_f64();
            let mut warm: Option<Vec<f64>> = None;
            let out: Vec<_> = ratios
                .iter()
                .map(|&r| {
                    let sol = s
                        .solve_from(EndLoads::ratio(r), warm.as_deref())
                        .expect("a solution");
                    warm = Some(sol.unknowns.clone());
                    sol
                })
                .collect();
            (setup, out)
        }
        _ => {
            let mut settings = FullSystemSettings::default();
            if solver == "multigrid" {
                settings.newton.linear = LinearBackend::MULTIGRID;
                settings.newton.krylov = KrylovParams {
                    tolerance: krylov_tol,
                    restart,
                    ..Default::default()
                };
                settings.newton.multigrid = MultigridParams {
                    smoother,
                    power_iterations,
                    ..Default::default()
                };
            }
            let s = FullSystemSolver::new(&model, settings).expect("set-up");
            let setup = t.elapsed().as_secs_f64();
            let out: Vec<_> = ratios
                .iter()
                .map(|&r| {
                    let start = Instant::now();
                    let mut log = |p: &Progress<f64>| {
                        if progress {
                            eprintln!(
                                "{:8.1} s  {} {:3}  residual {:.3e}  step {:.3}",
                                start.elapsed().as_secs_f64(),
                                p.stage,
                                p.iteration,
                                p.residual_norm,
                                p.step_length
                            );
                        }
                    };
                    s.solve_observed(EndLoads::ratio(r), &mut log)
                        .expect("a solution")
                })
                .collect();
            (setup, out)
        }
    };
    let total = t.elapsed().as_secs_f64();
    let last = results.last().expect("one solve at least");
    let iterations: usize = results.iter().map(|s| s.stats.newton_iterations).sum();
    let krylov: usize = results.iter().map(|s| s.stats.linear_iterations).sum();
    let v = &last.displacement;
    if let Some(path) = args.option("--save") {
        let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        std::fs::write(path, bytes).expect("writable --save file");
    }
    let difference = args.option("--reference").map(|path| {
        let bytes = std::fs::read(path).expect("a readable --reference file");
        let reference: Vec<f64> = bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect();
        assert_eq!(reference.len(), v.len(), "the reference is of this grid");
        max_abs_difference(&reference, v) / max_abs(&reference)
    });
    let loads = EndLoads::ratio(*ratios.last().expect("a ratio"));
    println!(
        "{{\"nodes\":{nodes:?},\"unknowns\":{},\"contact_unknowns\":{},\"solver\":\"{solver}\",\"krylov_tolerance\":{krylov_tol:.0e},\"solves\":{},\"model_seconds\":{model_seconds:.3},\"setup_seconds\":{setup_seconds:.3},\"solve_seconds\":{:.3},\"newton_iterations\":{iterations},\"krylov_iterations\":{krylov},\"krylov_per_newton\":{:.1},\"residual\":{:.2e},\"relative_residual\":{:.2e},\"difference_to_reference\":{},\"max_v2\":{:.9e},\"cpu_seconds\":{:.1},\"vm_hwm_mib\":{:.0}}}",
        model.dof_count(),
        model.active().len(),
        results.len(),
        total - setup_seconds,
        krylov as f64 / iterations.max(1) as f64,
        last.stats.residual,
        model.relative_residual(loads, v).expect("a residual"),
        difference.map_or("null".to_owned(), |d| format!("{d:.2e}")),
        last.max_azimuthal_displacement.value,
        cpu_seconds(),
        peak_memory_mib()
    );
}

/// The matrix-free path: model (operator, V-cycle transfers and coarse level), solve; one
/// JSON line as the assembled paths print (`vm_hwm_mib` the whole process).
#[allow(clippy::too_many_arguments)] // the example's flags, passed as they are parsed
fn matrix_free(
    body: &SolidBody<Obstacle>,
    multigrid: SolidMultigridParams,
    params: RegularisedCoulombParams<f64>,
    eps: f64,
    progress: bool,
    [save, reference]: [Option<&str>; 2],
    forcing: Option<f64>,
    sequence: bool,
) {
    let mut settings = MatrixFreeSettings::default();
    if let Some(eta) = forcing {
        settings.forcing.eta_max = eta;
        settings.forcing.eta_min = eta;
    }
    let mut newton_steps: Vec<(usize, usize)> = Vec::new();
    let mut level_steps: Vec<(usize, usize)> = Vec::new();
    let mut krylov_in_step = 0;
    let start = Instant::now();
    let mut start_seconds: Option<f64> = None;
    let mut log = |p: &Progress<f64>| {
        match p.stage {
            SolveStage::Krylov => {
                krylov_in_step += 1;
                // a long Krylov solve shows its residual every 100 iterations
                if progress && krylov_in_step % 100 == 0 {
                    eprintln!(
                        "{:8.1} s    krylov {:5}  residual {:.3e}",
                        start.elapsed().as_secs_f64(),
                        krylov_in_step,
                        p.residual_norm
                    );
                }
            }
            SolveStage::Newton => {
                if progress && p.iteration > 0 {
                    eprintln!(
                        "           (step {}: {krylov_in_step} Krylov iterations)",
                        p.iteration
                    );
                }
                if start_seconds.is_none() {
                    start_seconds = Some(start.elapsed().as_secs_f64());
                }
                newton_steps.push((p.iteration, krylov_in_step));
                krylov_in_step = 0;
            }
            // a grid level of the sequence is done: its steps (the last level's are reported)
            SolveStage::GridLevel => level_steps = std::mem::take(&mut newton_steps),
            _ => {}
        }
        if progress && p.stage != SolveStage::Krylov {
            eprintln!(
                "{:8.1} s  {} {:3}  residual {:.3e}  step {:.3}",
                start.elapsed().as_secs_f64(),
                p.stage,
                p.iteration,
                p.residual_norm,
                p.step_length
            );
        }
    };
    let loads = EndLoads::ratio(1.5);
    let t = Instant::now();
    // sequenced: the models of every level are built inside (their time is solve time)
    let (model, sol, levels, model_seconds) = if sequence {
        let s = body
            .solve_matrix_free_sequenced(
                RegularisedCoulomb,
                params,
                eps,
                multigrid,
                settings,
                SEQUENCE_COARSEST_UNKNOWNS,
                loads,
                &mut log,
            )
            .expect("a solution");
        (s.model, s.solution, s.levels, 0.0)
    } else {
        let model = body
            .matrix_free_model(RegularisedCoulomb, params, eps, multigrid)
            .expect("a valid model");
        let model_seconds = t.elapsed().as_secs_f64();
        let solver = MatrixFreeNewton::new(&model, settings).expect("settings");
        let sol = solver.solve_observed(loads, &mut log).expect("a solution");
        (model, sol, Vec::new(), model_seconds)
    };
    let solve_seconds = t.elapsed().as_secs_f64() - model_seconds;
    let v = &sol.displacement;
    if let Some(path) = save {
        let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        std::fs::write(path, bytes).expect("writable --save file");
    }
    let difference = reference.map(|path| {
        let bytes = std::fs::read(path).expect("a readable --reference file");
        let reference: Vec<f64> = bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect();
        assert_eq!(reference.len(), v.len(), "the reference is of this grid");
        max_abs_difference(&reference, v) / max_abs(&reference)
    });
    // Krylov iterations of each Newton step (the first event of a solve is its start)
    let steps = if sequence { level_steps } else { newton_steps };
    let per_step: Vec<usize> = steps.iter().filter(|s| s.0 > 0).map(|s| s.1).collect();
    // the start's Krylov iterations: those of the solve not inside a Newton step
    let start_iterations = sol.stats.linear_iterations - per_step.iter().sum::<usize>();
    // every grid level's [nodes, Newton steps, Krylov iterations], coarsest first
    let levels: Vec<String> = levels
        .iter()
        .map(|(n, s, k)| format!("[{n:?},{s},{k}]"))
        .collect();
    let levels = levels.join(",");
    println!(
        "{{\"nodes\":{:?},\"order\":\"{:?}\",\"unknowns\":{},\"contact_unknowns\":{},\"solver\":\"mf\",\"model_seconds\":{model_seconds:.3},\"solve_seconds\":{solve_seconds:.3},\"newton_iterations\":{},\"krylov_iterations\":{},\"krylov_per_newton_step\":{per_step:?},\"start_krylov_iterations\":{start_iterations},\"levels\":[{levels}],\"start_seconds\":{:.3},\"relative_residual\":{:.2e},\"difference_to_reference\":{},\"max_v2\":{:.9e},\"cpu_seconds\":{:.1},\"vm_hwm_mib\":{:.0}}}",
        body.nodes,
        body.order,
        model.dof_count(),
        model.active().len(),
        sol.stats.newton_iterations,
        sol.stats.linear_iterations,
        start_seconds.unwrap_or(f64::NAN),
        model.relative_residual(loads, v).expect("a residual"),
        difference.map_or("null".to_owned(), |d| format!("{d:.2e}")),
        sol.max_azimuthal_displacement.value,
        cpu_seconds(),
        peak_memory_mib()
    );
}
