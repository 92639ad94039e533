//! `capstan export-system`: the contact problem's linear system in Matrix Market, for
//! comparison with PETSc, MUMPS or scipy.
//!
//! # Math
//! At a state `v` (zero, or the converged solution), with the full residual `R` and its
//! Jacobian `J = dR/dv` (see `FullSystemProblem`):
//! ```text
//! A = J(v),   b = J(v) v - R(v),   A x = b  <=>  x = v - J(v)^-1 R(v)   (one Newton step from v)
//! ```
//! At `v = 0` the friction traction vanishes, `A` is the bulk operator with the friction
//! entries of the extended pattern (zero or friction-tangent values) and `b` the load vector:
//! the first Newton step. At the converged solution `R(v) ~ 0`, so `x = v` to the solver's
//! tolerance. `x.mtx` holds our sparse LU's solution of `A x = b`.

use std::path::PathBuf;

use capstan_elasticity::Component;
use capstan_elasticity::contact::FullSystemProblem;
use capstan_elasticity::solvers::{Jacobian, LinearSolver, Residual, SparseLu};
use clap::{Args, ValueEnum};
use serde::Serialize;

use crate::commands::SceneArgs;
use crate::commands::contact;
use crate::error::CliError;
use crate::output::OutputDir;
use crate::output::{write_matrix_market_array, write_matrix_market_coordinate};

/// The state the system is linearised at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum State {
    /// `v = 0`: the first Newton step (bulk operator and load vector).
    Zero,
    /// The converged contact solution (the scene's solver): the Newton Jacobian there.
    #[default]
    Solution,
}

/// Arguments of `capstan export-system`.
#[derive(Debug, Args, Clone, Default)]
pub struct ExportSystemArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Write `A.mtx`, `b.mtx`, `x.mtx` and `system.json` into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Linearise at `zero` or at the converged `solution`.
    #[arg(long, value_enum, default_value_t = State::Solution)]
    pub state: State,
}

/// The unknowns of one component at the grid nodes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DofNumbering {
    /// How nodes are ordered in `x2_dofs`, `x3_dofs`.
    pub node_order: &'static str,
    /// `x2` coordinates of the node columns (`n2` values).
    pub x2: Vec<f64>,
    /// `x3` coordinates of the node rows (`n3` values).
    pub x3: Vec<f64>,
    /// 0-based unknown of `v^2` at node `(i2, i3)`, at position `i2 * n3 + i3`.
    pub x2_dofs: Vec<usize>,
    /// 0-based unknown of `v^3` at node `(i2, i3)`, at position `i2 * n3 + i3`.
    pub x3_dofs: Vec<usize>,
}

/// `system.json` (and `--json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SystemReport {
    /// `A x = b` with `A = J(v)`, `b = J(v) v - R(v)`.
    pub system: &'static str,
    /// The state `v`.
    pub state: State,
    /// Discretisation method (`fd`, `fem-q1`, ...).
    pub method: &'static str,
    /// `[n2, n3]`.
    pub grid: [usize; 2],
    /// Unknowns (rows and columns of `A`).
    pub unknowns: usize,
    /// Stored entries of `A` (the extended pattern, explicit zeros included).
    pub nonzeros: usize,
    /// `[tau0, tau_max]`.
    pub loads: [f64; 2],
    /// Files: matrix, right-hand side and (unless `A` is singular) our solution.
    pub files: Vec<&'static str>,
    /// 1-based indices in the `.mtx` files; the numbering below is 0-based.
    pub index_base_in_files: usize,
    /// Where each unknown sits.
    pub dofs: DofNumbering,
    /// `max|R(v)| / max(1, max|b|)` at the state.
    pub state_residual: f64,
    /// `max|A x - b| / max(1, max|b|)` for `x.mtx` (our sparse LU); `null` if singular.
    pub solution_residual: Option<f64>,
    /// `max|x - v| / max(1, max|v|)`: 0-ish at the converged state; `null` if singular.
    pub step_from_state: Option<f64>,
    /// Why there is no `x.mtx` (our LU found `A` singular), `null` otherwise.
    pub singular: Option<String>,
}

/// Builds the system at the chosen state, writes the files and returns the report.
///
/// # Errors
/// Bad scene (exit 2), no equilibrium (3) or non-convergence (4) for `--state solution`;
/// a singular Jacobian; output errors.
pub fn run(args: &ExportSystemArgs) -> Result<SystemReport, CliError> {
    let scene = args.scene.load()?;
    let model = contact::model(&scene)?;
    let Some(disc) = model.discretisation().plane() else {
        return Err(CliError::Scene {
            origin: "body.dimension".into(),
            message: format!(
                "`body.dimension` = {}: export-system writes the plane-strain body only (allowed: 2)",
                scene.body.dimension
            ),
        });
    };
    let loads = contact::loads(&scene);
    let n = model.dof_count();
    let v = match args.state {
        State::Zero => vec![0.0; n],
        State::Solution => contact::solve(&scene)?.1.solution().displacement.clone(),
    };
    let problem = FullSystemProblem::new(&model, loads);
    let pattern = problem.pattern();
    let mut values = vec![0.0; pattern.nnz()];
    let mut r = vec![0.0; n];
    problem
        .jacobian(&v, &mut values)
        .and_then(|()| problem.residual(&v, &mut r))
        .map_err(capstan_elasticity::contact::ContactError::from)?;
    let mut b = vec![0.0; n];
    pattern.matvec(&values, &v, &mut b);
    for (bi, ri) in b.iter_mut().zip(&r) {
        *bi -= ri;
    }
    // Singular at `v = 0` on a circle: without pressure there is no friction, and the body
    // can rotate rigidly. The system is still exported, without `x`.
    let mut lu = SparseLu::default();
    let mut x = b.clone();
    let solved = lu
        .analyse(pattern)
        .and_then(|()| lu.factor(&values))
        .and_then(|()| lu.solve_in_place(&mut x));
    let max = |a: &[f64]| a.iter().fold(0.0f64, |m, y| m.max(y.abs()));
    let bmax = max(&b).max(1.0);
    let (x, solution_residual, step_from_state, singular) = match solved {
        Ok(()) => {
            let mut ax = vec![0.0; n];
            pattern.residual_into(&values, &x, &b, &mut ax);
            let step: Vec<f64> = x.iter().zip(&v).map(|(a, c)| a - c).collect();
            let step = max(&step) / max(&v).max(1.0);
            (Some(x), Some(max(&ax) / bmax), Some(step), None)
        }
        Err(e) => (
            None,
            None,
            None,
            Some(format!(
                "{e} (at v = 0 on a circular obstacle the body can slide rigidly)"
            )),
        ),
    };

    let grid = disc.grid();
    let mut dofs = DofNumbering {
        node_order: "i2 major: node (i2, i3) at position i2 * n3 + i3",
        x2: (0..grid.n2()).map(|i| grid.x2(i)).collect(),
        x3: (0..grid.n3()).map(|j| grid.x3(j)).collect(),
        x2_dofs: Vec::new(),
        x3_dofs: Vec::new(),
    };
    for i in 0..grid.n2() {
        for j in 0..grid.n3() {
            dofs.x2_dofs.push(disc.dof([i, j], Component::X2));
            dofs.x3_dofs.push(disc.dof([i, j], Component::X3));
        }
    }
    let report = SystemReport {
        system: "A x = b, A = J(v) (Newton Jacobian of the contact residual R), b = J(v) v - R(v)",
        state: args.state,
        method: disc.method(),
        grid: [grid.n2(), grid.n3()],
        unknowns: n,
        nonzeros: pattern.nnz(),
        loads: [loads.tau0, loads.tau_max],
        files: if x.is_some() {
            vec!["A.mtx", "b.mtx", "x.mtx"]
        } else {
            vec!["A.mtx", "b.mtx"]
        },
        index_base_in_files: 1,
        dofs,
        state_residual: max(&r) / bmax,
        solution_residual,
        step_from_state,
        singular,
    };
    let out = OutputDir::create(&args.out)?;
    let comment = format!(
        "capstan export-system: state {:?}, grid {} x {}, method {}",
        args.state,
        grid.n2(),
        grid.n3(),
        disc.method()
    );
    out.write("A.mtx", |w| {
        write_matrix_market_coordinate(w, pattern, &values, &[comment.as_str(), "A = J(v)"])
    })?;
    out.write("b.mtx", |w| {
        write_matrix_market_array(w, "b", &b, &[comment.as_str(), "b = J(v) v - R(v)"])
    })?;
    if let Some(x) = &x {
        out.write("x.mtx", |w| {
            write_matrix_market_array(
                w,
                "x",
                x,
                &[comment.as_str(), "x = A^-1 b (capstan sparse LU)"],
            )
        })?;
    }
    out.write_json("system.json", &report)?;
    Ok(report)
}

/// Plain text.
pub fn table(r: &SystemReport) -> String {
    let e = |x: Option<f64>| x.map_or("-".into(), |x| format!("{x:.2e}"));
    let mut s = format!(
        "export-system: {} unknowns, {} entries ({} grid {} x {}, state {:?})\n  |R(v)| {:.2e}, |A x - b| {}, |x - v| {} (relative max norms)\n",
        r.unknowns,
        r.nonzeros,
        r.method,
        r.grid[0],
        r.grid[1],
        r.state,
        r.state_residual,
        e(r.solution_residual),
        e(r.step_from_state)
    );
    if let Some(why) = &r.singular {
        s += &format!("  no x.mtx: {why}\n");
    }
    s
}
