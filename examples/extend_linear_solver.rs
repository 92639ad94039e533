//! Extending capstan with a new linear backend, without editing capstan: dense LU.
//!
//! Problem: a host code has its own linear solver (here nalgebra's dense LU with partial
//! pivoting, `P A = L U`, the right tool for the small systems of a parameter study on coarse
//! grids) and wants capstan's contact solvers to use it. It implements capstan's
//! `LinearSolver` (`analyse` a sparsity pattern once, `factor` its values, `solve_in_place`)
//! and registers it once under a name with `linear_registry::register`. From then on:
//! - a scene names it (`solver.linear = "dense-lu"`), validated like the built-ins;
//! - **both** contact solvers use it: the boundary-only Newton (`solver.nonlinear =
//!   "newton"`) for its condensation of the bulk, the full-system Newton (`"full-newton"`)
//!   for its stuck start and every Newton step;
//! - on the 2-D (plane strain) and the 3-D body alike.
//!
//! Run: `cargo run --release --example extend_linear_solver`
//! Look at: every solve through `dense-lu` gives the displacement of the built-in sparse LU
//! to ~1e-12 relative (two exact factorisations of the same matrices), and the counter shows
//! the backend did the work.

use std::sync::atomic::{AtomicUsize, Ordering};

use capstan::geometry::nalgebra::{self, DMatrix, DVector};
use capstan::solvers::{
    BackendKind, LinearSolver, RegisteredLinearSolver, SolverError, SparsityPattern,
    linear_registry,
};
use capstan::{CliError, Scene};

/// Numeric factorisations done by `dense-lu` (to show that the solvers called it).
static FACTORISATIONS: AtomicUsize = AtomicUsize::new(0);

/// Dense LU of a sparse matrix: the pattern's `(row, column)` slots scattered into an
/// `n x n` matrix, factorised by Gaussian elimination with partial pivoting (`O(n^3)`).
#[derive(Debug, Default)]
struct DenseLu {
    /// `(row, column)` of each slot of the analysed pattern, in slot order.
    slots: Vec<(usize, usize)>,
    /// The order `n`.
    n: usize,
    /// The factors of the last `factor`.
    lu: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
}

impl LinearSolver<f64> for DenseLu {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        if !pattern.is_square() {
            return Err(SolverError::NotSquare {
                nrows: pattern.nrows(),
                ncols: pattern.ncols(),
            });
        }
        self.n = pattern.nrows();
        self.slots = pattern.entries().collect();
        self.lu = None;
        Ok(())
    }

    fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
        if values.len() != self.slots.len() {
            return Err(SolverError::DimensionMismatch {
                quantity: "values",
                expected: self.slots.len(),
                found: values.len(),
            });
        }
        let mut a = DMatrix::zeros(self.n, self.n);
        for (&(i, j), &v) in self.slots.iter().zip(values) {
            a[(i, j)] += v;
        }
        let lu = a.lu();
        if !lu.is_invertible() {
            return Err(SolverError::Singular { pivot: None });
        }
        self.lu = Some(lu);
        FACTORISATIONS.fetch_add(1, Ordering::SeqCst);
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
        let lu = self.lu.as_ref().ok_or(SolverError::CallOrder {
            called: "solve_in_place",
            requires: "factor",
        })?;
        let mut b = DVector::from_column_slice(rhs);
        if !lu.solve_mut(&mut b) {
            return Err(SolverError::Singular { pivot: None });
        }
        rhs.copy_from_slice(b.as_slice());
        Ok(())
    }

    fn last_iterations(&self) -> Option<usize> {
        None // a direct method
    }
}

/// The registration: a name, a summary, the settings it reads (none) and a builder.
const DENSE_LU: RegisteredLinearSolver = RegisteredLinearSolver {
    name: "dense-lu",
    summary: "dense LU with partial pivoting (nalgebra): small systems only, O(n^3)",
    parameters: &[],
    kind: BackendKind::Direct,
    build: |_settings, _context| Ok(Box::new(DenseLu::default())),
};

/// Registers `dense-lu` once per process (a second registration would be refused).
fn register_dense_lu() {
    // `Once`, not find-then-register: the tests run on several threads and both would
    // see the name missing before either registered it.
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        linear_registry::register(DENSE_LU).expect("first registration of `dense-lu`");
    });
}

/// A small scene of either dimension with `solver.nonlinear = nonlinear` and
/// `solver.linear = linear`.
fn scene(dimension: usize, nonlinear: &str, linear: &str) -> Result<Scene, CliError> {
    register_dense_lu();
    let sets: &[(&str, String)] = &[
        ("body.dimension", dimension.to_string()),
        ("grid.n1", "3".into()),
        ("grid.n2", if dimension == 2 { "41" } else { "21" }.into()),
        ("grid.n3", "5".into()),
        ("body.width", "0.5".into()),
        ("loads.tau_max", "1.5".into()),
        ("solver.nonlinear", format!("\"{nonlinear}\"")),
        ("solver.linear", format!("\"{linear}\"")),
    ];
    let mut scene = Scene::default();
    for (key, value) in sets {
        scene = scene.with_raw(key, value, "example")?;
    }
    Ok(scene)
}

/// The displacement of the scene's solve, and the factorisations `dense-lu` did for it.
fn displacement(
    dimension: usize,
    nonlinear: &str,
    linear: &str,
) -> Result<(Vec<f64>, usize), CliError> {
    let problem = scene(dimension, nonlinear, linear)?.build()?;
    let before = FACTORISATIONS.load(Ordering::SeqCst);
    let solved = problem.solve().map_err(CliError::from)?;
    let count = FACTORISATIONS.load(Ordering::SeqCst) - before;
    Ok((solved.solution.displacement, count))
}

/// `max |a - b| / max |b|`.
fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    capstan::solvers::max_abs_difference(a, b) / capstan::solvers::max_abs(b)
}

/// For each body and contact solver: the relative difference of `dense-lu` from `lu` and
/// the factorisations `dense-lu` did.
fn compare() -> Result<Vec<(usize, &'static str, f64, usize)>, CliError> {
    let mut rows = Vec::new();
    for dimension in [2, 3] {
        for nonlinear in ["newton", "full-newton"] {
            let (dense, count) = displacement(dimension, nonlinear, "dense-lu")?;
            let (sparse, none) = displacement(dimension, nonlinear, "lu")?;
            assert_eq!(none, 0, "`lu` does not call the user's backend");
            rows.push((
                dimension,
                nonlinear,
                relative_difference(&dense, &sparse),
                count,
            ));
        }
    }
    Ok(rows)
}

fn main() -> Result<(), CliError> {
    println!("registered linear backends: {}", {
        register_dense_lu();
        linear_registry::names()
    });
    for (dimension, nonlinear, difference, count) in compare()? {
        println!(
            "{dimension}-D, solver.nonlinear = {nonlinear:11}: dense-lu vs lu {difference:.2e} relative, {count} dense factorisations"
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_user_backend_drives_both_contact_solvers_in_2d_and_3d() {
        for (dimension, nonlinear, difference, count) in compare().unwrap() {
            // two exact factorisations of the same well-conditioned matrices
            assert!(
                difference < 1e-10,
                "{dimension}-D {nonlinear}: {difference:e}"
            );
            assert!(
                count >= 1,
                "{dimension}-D {nonlinear}: dense-lu was not called"
            );
        }
    }

    #[test]
    fn a_scene_naming_an_unregistered_backend_is_refused_listing_the_registered_ones() {
        register_dense_lu();
        let err = scene(2, "newton", "superlu").unwrap_err().to_string();
        assert!(
            err.contains("solver.linear") && err.contains("superlu") && err.contains("dense-lu"),
            "{err}"
        );
    }
}
