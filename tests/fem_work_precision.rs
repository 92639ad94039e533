//! `capstan bench work-precision`: argument parsing, a smoke run of the benchmark on its
//! quick grids (ignored in CI: several seconds), and very small smoke tests of the peer
//! scripts (scikit-fem, NGSolve) when `.venv/bin/python` has the library (skipped with a note
//! otherwise; CI installs neither).

mod common;

use std::path::Path;
use std::process::Command;

use capstan::cli::{Cli, Command as Sub};
use capstan::commands::bench::{BenchCommand, Problem, WorkPrecisionArgs, report};
use clap::Parser;

/// `capstan bench work-precision ARGS`, parsed.
fn parse(args: &[&str]) -> Result<WorkPrecisionArgs, clap::Error> {
    let all = ["capstan", "bench", "work-precision"].iter().chain(args);
    let Some(Sub::Bench(b)) = Cli::try_parse_from(all)?.command else {
        panic!("not bench")
    };
    let BenchCommand::WorkPrecision(a) = b.what;
    Ok(a)
}

#[test]
fn work_precision_arguments_parse() {
    let a = parse(&["--quick", "--json", "--out", "x"]).unwrap();
    assert!(a.quick && a.json && !a.no_peer);
    assert!(a.threads.is_empty()); // all cores
    assert_eq!(a.out.as_deref(), Some(std::path::Path::new("x")));
    let a = parse(&["--threads", "1,2"]).unwrap();
    assert_eq!(a.threads, [1, 2]);
    assert!(a.problems.is_empty()); // all four
    let a = parse(&[
        "--problems",
        "contact",
        "--methods",
        "fem-qp-hp,fem-qp-corner",
    ])
    .unwrap();
    assert_eq!(a.problems, [Problem::Contact]);
    let a = parse(&["--problems", "paper,lame"]).unwrap();
    assert_eq!(a.problems, [Problem::Paper, Problem::Lame]);
    assert!(parse(&["--problems", "x"]).is_err());
}

#[test]
fn work_precision_runs_can_be_restricted() {
    let a = parse(&[
        "--problems",
        "lame",
        "--methods",
        "fem-qp7,fem-qp8",
        "--peers",
        "ngsolve",
        "--peer-orders",
        "6,8",
    ])
    .unwrap();
    assert_eq!(a.problems, [Problem::Lame]);
    assert_eq!(a.methods, ["fem-qp7", "fem-qp8"]);
    assert_eq!(a.peers, ["ngsolve"]);
    assert_eq!(a.peer_orders, [6, 8]);
    for bad in [
        ["--problems", "circle"],
        ["--methods", "fem-qp11"],
        ["--peers", "fenics"],
        ["--peer-orders", "9"],
    ] {
        let msg = parse(&bad).expect_err("rejected").to_string();
        assert!(msg.contains(bad[0]), "{msg}"); // names the option
    }
    // one problem, one method: only those runs, and only that problem's plots
    let dir = common::scratch_dir("wp-restricted");
    let r = report(&WorkPrecisionArgs {
        quick: true,
        out: Some(dir.clone()),
        no_peer: true,
        problems: vec![Problem::Lame],
        methods: vec!["fem-qp2".to_owned()],
        ..Default::default()
    })
    .unwrap();
    assert!(!r.runs.is_empty());
    assert!(
        r.runs
            .iter()
            .all(|x| x.problem == "lame" && x.method == "fem-qp2")
    );
    assert!(dir.join("work-precision-lame.svg").exists());
    assert!(!dir.join("work-precision-mms.svg").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn contact_series_measure_three_quantities_against_a_cached_reference() {
    // the contact problem at its quick size: the first two hp-ladder steps (p = 2, 3), both
    // solvers, against the quick reference (p = 4, 4 layers, 32 x 8 elements)
    let dir = common::scratch_dir("wp-contact");
    let args = |method: &str| WorkPrecisionArgs {
        quick: true,
        out: Some(dir.clone()),
        no_peer: true,
        problems: vec![Problem::Contact],
        methods: vec![method.to_owned()],
        ..Default::default()
    };
    let r = report(&args("fem-qp-hp")).unwrap();
    let c = r.contact.as_ref().expect("contact ran");
    assert!(!c.reference.cached);
    assert!(r.runs.iter().all(|x| x.method == "fem-qp-hp"));
    for (quantity, solvers) in [
        ("contact-slip", 2),
        ("contact-threshold", 1),
        ("contact-v2", 2),
    ] {
        let rows: Vec<_> = r.runs.iter().filter(|x| x.problem == quantity).collect();
        assert_eq!(rows.len(), 2 * solvers, "{quantity}: {rows:?}");
        assert!(rows.iter().all(|x| x.error.is_finite() && x.seconds > 0.0));
    }
    // the threshold converges along the ladder: 3.3471 -> 3.3435 against ~3.3430 (1e-3
    // -> 1e-4 relative)
    let threshold: Vec<_> = r
        .runs
        .iter()
        .filter(|x| x.problem == "contact-threshold")
        .collect();
    assert!(
        threshold[1].error < 0.5 * threshold[0].error,
        "{threshold:?}"
    );
    assert!(threshold[0].error > 1e-4 && threshold[0].error < 3e-3);
    // both solvers give the same quantities (same discretisation, Newton to 1e-10)
    let slip: Vec<_> = r
        .runs
        .iter()
        .filter(|x| x.problem == "contact-slip")
        .collect();
    assert!((slip[0].error - slip[2].error).abs() < 1e-6, "{slip:?}");
    assert_eq!(c.series.len(), 5); // slip, v2: 2 solvers; threshold: 1
    assert_eq!(c.fastest.len(), 9);
    assert!(dir.join("work-precision-contact-threshold.svg").exists());
    // the reference is read back from the output directory
    let again = report(&args("fd")).unwrap();
    let c2 = again.contact.unwrap();
    assert!(c2.reference.cached);
    assert_eq!(c2.reference.values, c.reference.values);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn transition_series_runs_both_passes_on_the_graded_mesh() {
    // `fem-qp-transition` (quick: p = 2, 3 on 24 x 8 cells, graded toward the transitions of a
    // p = 2 first pass on 12 x 2 cells); its accuracy is tests/transition_grading.rs'
    let dir = common::scratch_dir("wp-transition");
    let r = report(&WorkPrecisionArgs {
        quick: true,
        out: Some(dir.clone()),
        no_peer: true,
        problems: vec![Problem::Contact],
        methods: vec!["fem-qp-transition".to_owned()],
        ..Default::default()
    })
    .unwrap();
    for quantity in ["contact-slip", "contact-v2"] {
        let rows: Vec<_> = r
            .runs
            .iter()
            .filter(|x| x.problem == quantity && x.backend == "newton")
            .collect();
        assert_eq!(rows.len(), 2, "{:?}", r.runs);
        for (run, order) in rows.iter().zip([2, 3]) {
            // the grid of the cells, and the graded mesh's own unknowns: more x2 lines
            assert_eq!([run.n2, run.n3], [24 * order + 1, 8 * order + 1]);
            assert!(run.dofs > 2 * run.n2 * run.n3, "{run:?}");
            assert!(run.error.is_finite() && run.seconds > 0.0, "{run:?}");
        }
    }
    let threshold = r
        .runs
        .iter()
        .filter(|x| x.problem == "contact-threshold")
        .count();
    assert_eq!(threshold, 2);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn paper_corner_series_converges_with_the_layers() {
    // fem-qp6 on `paper` (quick): the corner-refined rows, 1, 2, 3 layers of 0.3 on 12 x 2
    // cells, beside the uniform and graded ones
    let dir = common::scratch_dir("wp-corner");
    let r = report(&WorkPrecisionArgs {
        quick: true,
        out: Some(dir.clone()),
        no_peer: true,
        problems: vec![Problem::Paper],
        methods: vec!["fem-qp6".to_owned()],
        ..Default::default()
    })
    .unwrap();
    let corner: Vec<_> = r
        .runs
        .iter()
        .filter(|x| x.method == "fem-qp6-corner")
        .collect();
    assert_eq!(corner.len(), 3, "{:?}", r.runs);
    assert!(corner.iter().map(|x| x.n3).eq([1, 2, 3])); // layers
    assert!(
        corner
            .windows(2)
            .all(|w| w[1].error < w[0].error && w[1].dofs > w[0].dofs),
        "{corner:?}"
    );
    // 3 layers: 5.4e-6 against the p = 10 reference (docs/high-order.md), here the quick p = 8
    assert!(corner[2].error < 2e-5, "{corner:?}");
    assert!(r.series.iter().any(|s| s.method == "fem-qp6-corner"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn mms_x2_series_refines_where_the_error_is() {
    // fem-qp6 on `mms` (quick): the uniform rows `2k x k` (k = 1, 2, 4) and the `fem-qp6-x2`
    // rows `e2 x 1` (e2 = 2, 3, 4)
    let dir = common::scratch_dir("wp-mms-x2");
    let r = report(&WorkPrecisionArgs {
        quick: true,
        out: Some(dir.clone()),
        no_peer: true,
        problems: vec![Problem::Mms],
        methods: vec!["fem-qp6".to_owned()],
        ..Default::default()
    })
    .unwrap();
    let rows = |method: &str| -> Vec<_> { r.runs.iter().filter(|x| x.method == method).collect() };
    let (uniform, x2) = (rows("fem-qp6"), rows("fem-qp6-x2"));
    assert_eq!(x2.len(), 3, "{:?}", r.runs);
    assert!(x2.iter().map(|x| x.n2).eq([13, 19, 25]), "{x2:?}"); // 6 e2 + 1 nodes
    assert!(x2.iter().all(|x| x.n3 == 7), "{x2:?}"); // one element through the thickness
    // the first rung is the uniform series' first grid (2 x 1 elements): the same solve
    assert_eq!(x2[0].error, uniform[0].error);
    assert!(
        x2.windows(2)
            .all(|w| w[1].error < w[0].error && w[1].dofs > w[0].dofs),
        "{x2:?}"
    );
    // why the series exists: the uniform k = 2 run (4 x 2 elements) has the error of the
    // 4 x 1 one, so its second layer through the thickness buys nothing (5.48e-7 both)
    assert_eq!((uniform[1].n2, uniform[1].n3), (25, 13));
    let ratio = uniform[1].error / x2[2].error;
    assert!((ratio - 1.0).abs() < 1e-3, "{ratio}: {uniform:?} {x2:?}");
    // ... at 350 unknowns instead of 650
    assert!(x2[2].error < 1e-6 && 1.8 * (x2[2].dofs as f64) < uniform[1].dofs as f64);
    assert!(r.series.iter().any(|s| s.method == "fem-qp6-x2"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[ignore = "runs every method on three grids per problem: several seconds"]
fn quick_work_precision_writes_csv_and_plots() {
    let dir = common::scratch_dir("wp");
    let r = report(&WorkPrecisionArgs {
        quick: true,
        out: Some(dir.clone()),
        no_peer: true,
        ..Default::default()
    })
    .unwrap();
    // 3 problems x (fd lu, q1 lu+chol, q2 lu+chol) x 3 grids, plus Gauss-Seidel on the
    // smallest grid where it converges
    assert!(r.runs.len() >= 45, "{}", r.runs.len());
    for run in &r.runs {
        assert!(run.error > 0.0 && run.error < 0.2, "{run:?}");
    }
    // refining the grid reduces the error of every direct series
    let q2: Vec<_> = r
        .runs
        .iter()
        .filter(|x| x.problem == "lame" && x.method == "fem-q2" && x.backend == "cholesky")
        .collect();
    assert!(q2.windows(2).all(|w| w[1].error < w[0].error / 4.0));
    for f in [
        "work-precision.csv",
        "work-precision-lame.svg",
        "work-precision-lame.png",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `python ARGS` in the repository root, which must succeed: its stdout, one JSON object a line.
fn peer_lines(python: &Path, args: &[&str]) -> Vec<serde_json::Value> {
    let out = common::succeed(
        Command::new(python)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(args),
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn peer_script_smoke_when_scikit_fem_is_installed() {
    let Some(python) = common::venv_python_with("skfem") else {
        return;
    };
    let lines = peer_lines(
        &python,
        &[
            "bench/peers/skfem_lame.py",
            "--order",
            "2",
            "--levels",
            "2,4",
        ],
    );
    assert_eq!(lines.len(), 2);
    let e: Vec<f64> = lines.iter().map(|l| l["error"].as_f64().unwrap()).collect();
    // Q2 on the exact annulus: third order, so halving h divides the error by about 8
    assert!(e[1] < e[0] / 5.0 && e[1] < 1e-2, "{e:?}");
}

#[test]
fn ngsolve_peer_script_smoke_when_ngsolve_is_installed() {
    let Some(python) = common::venv_python_with("ngsolve") else {
        eprintln!("skipped: the NGSolve peer smoke test (.venv/bin/pip install ngsolve)");
        return;
    };
    let run = |inverse: &str| {
        peer_lines(
            &python,
            &[
                "bench/peers/ngsolve_lame.py",
                "--order",
                "3",
                "--levels",
                "2,4",
                "--inverse",
                inverse,
                "--repeat-min",
                "1",
                "--repeat-max",
                "1",
            ],
        )
    };
    let cholesky = run("sparsecholesky");
    assert_eq!(cholesky.len(), 2);
    assert_eq!(cholesky[0]["method"], "ngsolve-p3");
    assert_eq!(cholesky[0]["backend"], "sparsecholesky");
    let e: Vec<f64> = cholesky
        .iter()
        .map(|l| l["error"].as_f64().unwrap())
        .collect();
    // p = 3 on curved triangles: order 4 in L2, so halving maxh divides the error by about 16
    // (the coarse netgen meshes are not exactly nested: at least 8 here)
    assert!(e[1] < e[0] / 8.0 && e[1] < 1e-3, "{e:?}");
    // the other factorisation solves the same system: the same error up to round-off
    let umfpack = run("umfpack");
    assert_eq!(umfpack[1]["backend"], "umfpack");
    let e_umfpack = umfpack[1]["error"].as_f64().unwrap();
    assert!(
        (e_umfpack / e[1] - 1.0).abs() < 1e-6,
        "{e_umfpack} vs {}",
        e[1]
    );
}

#[test]
fn ngsolve_mms_peer_converges_at_order_p_plus_one_when_ngsolve_is_installed() {
    let (Some(python), Some(_)) = (
        common::venv_python_with("ngsolve"),
        common::venv_python_with("sympy"),
    ) else {
        eprintln!("skipped: the NGSolve mms peer test (.venv/bin/pip install ngsolve sympy)");
        return;
    };
    let lines = peer_lines(
        &python,
        &[
            "bench/peers/ngsolve_mms.py",
            "--order",
            "2",
            "--levels",
            "2,4,8",
            "--repeat-min",
            "1",
            "--repeat-max",
            "1",
        ],
    );
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[0]["method"], "ngsolve-p2");
    let e: Vec<f64> = lines.iter().map(|l| l["error"].as_f64().unwrap()).collect();
    // p = 2 against the exact manufactured solution: order 3 in L2 (the curved geometry is
    // exact to order 2 too), so halving maxh divides the error by about 8 (netgen's meshes are
    // not nested: at least 6); a wrong load or geometry would stall the error instead
    let orders: Vec<f64> = e.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    assert!(orders.iter().all(|&k| k > 2.6), "{e:?} {orders:?}");
    assert!(e[2] < 1e-4, "{e:?}");
}

#[test]
fn ngsolve_paper_peer_points_match_capstan_graded_solution_when_ngsolve_is_installed() {
    use capstan::commands::bench::{Rectangle, points_error_of};
    use capstan_elasticity::Discretisation;
    use capstan_elasticity::finite_element::{Grading, QpSettings};
    use capstan_elasticity::samples::PaperEllipse;
    use capstan_elasticity::solvers::SparseCholesky;
    use capstan_elasticity::studies::paper_parts;
    use capstan_elasticity::verification::GridLevel;

    let Some(python) = common::venv_python_with("ngsolve") else {
        eprintln!("skipped: the NGSolve paper peer test (.venv/bin/pip install ngsolve)");
        return;
    };
    let dir = std::env::temp_dir().join(format!("capstan-paper-points-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let lines = peer_lines(
        &python,
        &[
            "bench/peers/ngsolve_paper.py",
            "--order",
            "4",
            "--levels",
            "1,4",
            "--repeat-min",
            "1",
            "--repeat-max",
            "1",
            "--error-points",
            dir.to_str().unwrap(),
        ],
    );
    assert_eq!(lines.len(), 2);
    assert!(lines[0]["error"].is_null());
    // capstan's graded p = 4 solve, 4 layers per end, as the reference
    let (p, n) = (4, 4);
    let level = GridLevel {
        n2: (2 * n + 6) * p + 1,
        n3: (2 * n + 1) * p + 1,
    };
    let parts = paper_parts(&PaperEllipse::default(), level).unwrap();
    let rect = Rectangle {
        theta: parts.grid.theta(),
        thickness: parts.grid.thickness(),
    };
    let chart = parts.chart.clone();
    let op = parts
        .high_order_with(QpSettings {
            grading: Grading::geometric(0.4, n).unwrap(),
            ..QpSettings::order(p)
        })
        .unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    let reference = |x: [f64; 2]| op.displacement_at(&v, x);
    let mut errors = vec![];
    for line in &lines {
        let file = Path::new(line["error_points"].as_str().unwrap());
        let bytes = std::fs::read(file).unwrap();
        // the weights add up to the area of the half annulus 2 <= r <= 3 (the curved mesh's
        // geometry error is far below 1e-6)
        let w: f64 = bytes
            .chunks_exact(40)
            .map(|r| f64::from_le_bytes(r[16..24].try_into().unwrap()))
            .sum();
        let area = 2.5 * std::f64::consts::PI;
        assert!((w / area - 1.0).abs() < 1e-6, "{w} vs {area}");
        errors.push(points_error_of(&bytes, &chart, rect, &reference).unwrap());
    }
    std::fs::remove_dir_all(&dir).unwrap();
    // two discretisations of the same problem (clamped face, tensions 1 and 2 pulling along
    // -y at the ends): they agree to a few 1e-4 and more so with more corner layers; a sign
    // or a side mixed up would give an O(1) difference
    assert!(errors[1] < errors[0] && errors[1] < 3e-3, "{errors:?}");
}
