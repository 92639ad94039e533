//! Preconditioned Krylov methods: conjugate gradients for symmetric positive definite
//! matrices, restarted right-preconditioned GMRES for general ones.

use crate::csr_matrix::CsrMatrix;
use crate::error::SolverError;
use crate::linear_operator::LinearOperator;
use crate::observer::{Observer, Progress, SolveStage};

/// The field a spent Krylov budget names ([`SolverError::BudgetSpent`]).
pub const KRYLOV_BUDGET_FIELD: &str = "krylov.max_iterations";

/// The Krylov method of a [`crate::KrylovSolver`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum KrylovMethod {
    /// Preconditioned conjugate gradients: `A` and the preconditioner symmetric positive
    /// definite.
    Cg,
    /// Restarted GMRES(`restart`), right-preconditioned: any nonsingular `A`.
    #[default]
    Gmres,
}

/// Settings of the Krylov methods.
///
/// # Math
/// ```text
/// stop when |b - A x_k|_2 <= tolerance |b|_2          (x_0 = 0)
/// CG:     minimises |x - x*|_A over x_0 + K_k(M^-1 A, M^-1 b)
/// GMRES:  x_k = M^-1 y_k,  y_k minimises |b - A M^-1 y|_2 over K_k(A M^-1, b),
///         restarted every `restart` iterations
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct KrylovParams {
    /// CG or GMRES.
    pub method: KrylovMethod,
    /// Relative residual at which to stop, in `(0, 1)`.
    pub tolerance: f64,
    /// Work budget: iterations (preconditioner applications) per solve, at least 1; spending
    /// it is [`SolverError::BudgetSpent`] naming [`KRYLOV_BUDGET_FIELD`].
    pub max_iterations: usize,
    /// GMRES restart length `m` (Krylov vectors kept), at least 1; default 100: the contact
    /// Jacobians have a few outlying eigenvalues under the multigrid preconditioner, which a
    /// restart after 40 vectors forgets (a 9 x 33 x 9 body stalled at 1e-3 with `m = 40` and
    /// needs 20 iterations per Newton step with `m = 100`).
    pub restart: usize,
}

impl Default for KrylovParams {
    fn default() -> Self {
        Self {
            method: KrylovMethod::Gmres,
            tolerance: 1e-8,
            max_iterations: 500,
            restart: 100,
        }
    }
}

impl KrylovParams {
    /// Checks every field.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SolverError> {
        SolverError::check_fraction("krylov.tolerance", self.tolerance)?;
        SolverError::check_count(KRYLOV_BUDGET_FIELD, self.max_iterations)?;
        SolverError::check_count("krylov.restart", self.restart)?;
        Ok(())
    }
}

/// An approximate inverse `z = M^-1 r` applied inside a Krylov method.
pub trait Preconditioner {
    /// Overwrites `z` with `M^-1 r`.
    fn apply(&mut self, r: &[f64], z: &mut [f64]);
}

/// No preconditioning: `M = I`.
#[derive(Clone, Copy, Debug, Default)]
pub struct IdentityPreconditioner;

impl Preconditioner for IdentityPreconditioner {
    fn apply(&mut self, r: &[f64], z: &mut [f64]) {
        z.copy_from_slice(r);
    }
}

/// What a converged Krylov solve did.
#[derive(Clone, Debug, PartialEq)]
pub struct KrylovReport {
    /// Iterations (preconditioner applications).
    pub iterations: usize,
    /// The relative residual `|b - A x| / |b|` after each iteration (GMRES: the
    /// least-squares estimate, the true residual at restarts and at the end).
    pub residuals: Vec<f64>,
}

impl KrylovReport {
    /// Records iteration `iterations + 1` with relative residual `relative` and step `step`,
    /// and reports it to `observer`.
    ///
    /// # Errors
    /// [`SolverError::Interrupted`] when the observer asks to stop.
    fn record(
        &mut self,
        relative: f64,
        step: f64,
        observer: &mut dyn Observer<f64>,
    ) -> Result<(), SolverError> {
        self.iterations += 1;
        self.residuals.push(relative);
        observer.iteration(&Progress::new(
            SolveStage::Krylov,
            self.iterations,
            relative,
            step,
        ));
        if observer.interrupted() {
            return Err(SolverError::Interrupted {
                iteration: self.iterations,
            });
        }
        Ok(())
    }
}

/// One Krylov solve from `x = 0` with `b != 0`: the inputs, `|b|_2` and the report so far.
struct Run<'s> {
    a: &'s dyn LinearOperator,
    b: &'s [f64],
    preconditioner: &'s mut dyn Preconditioner,
    params: &'s KrylovParams,
    observer: &'s mut dyn Observer<f64>,
    bn: f64,
}

/// A report of no iterations.
const NO_ITERATIONS: KrylovReport = KrylovReport {
    iterations: 0,
    residuals: Vec::new(),
};

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

fn spent(params: &KrylovParams, iterations: usize, residual: f64) -> SolverError {
    SolverError::BudgetSpent {
        field: KRYLOV_BUDGET_FIELD,
        iterations,
        residual,
        tolerance: params.tolerance,
    }
}

fn breakdown(iteration: usize) -> SolverError {
    SolverError::NonFinite {
        quantity: "krylov residual",
        index: 0,
        iteration: Some(iteration),
    }
}

/// Solves `A x = b` from `x = 0` by the method of `params`: preconditioned conjugate
/// gradients ([`KrylovMethod::Cg`]) or restarted right-preconditioned GMRES
/// ([`KrylovMethod::Gmres`]); `x` is overwritten. `b = 0` gives `x = 0` with no iterations.
///
/// # Math
/// Conjugate gradients (`A` and `M` symmetric positive definite):
/// ```text
/// r_0 = b, z_0 = M^-1 r_0, p_0 = z_0
/// alpha_k = (r_k, z_k) / (p_k, A p_k),  x_{k+1} = x_k + alpha_k p_k,  r_{k+1} = r_k - alpha_k A p_k
/// beta_k  = (r_{k+1}, z_{k+1}) / (r_k, z_k),  p_{k+1} = z_{k+1} + beta_k p_k
/// ```
/// convergence confirmed on the true residual `b - A x` (the recurrence drifts).
///
/// GMRES(`m`), modified Gram–Schmidt and Givens rotations:
/// ```text
/// r = b - A x,  v_1 = r / |r|
/// for j = 1..m:  w = A M^-1 v_j,  h_ij = (w, v_i) (i <= j),  v_{j+1} = (w - sum h_ij v_i) / h_{j+1,j}
/// y minimises | |r| e_1 - H_j y |_2  (Givens: the residual estimate is |g_{j+1}|)
/// x <- x + M^-1 V_j y  at the restart or on convergence
/// ```
/// The estimate is the true residual in exact arithmetic (right preconditioning); each
/// restart and the final answer recompute `b - A x`.
///
/// Each iteration reports [`SolveStage::Krylov`] with its relative residual.
///
/// # Errors
/// [`SolverError::BudgetSpent`] when `params.max_iterations` is spent;
/// [`SolverError::NotPositiveDefinite`] when CG meets `(p, A p) <= 0` (the matrix or the
/// preconditioner is not SPD); [`SolverError::Interrupted`] when the observer asks to stop; a
/// non-finite quantity; invalid settings or lengths.
pub fn krylov_solve(
    a: &CsrMatrix,
    b: &[f64],
    x: &mut [f64],
    preconditioner: &mut dyn Preconditioner,
    params: &KrylovParams,
    observer: &mut dyn Observer<f64>,
) -> Result<KrylovReport, SolverError> {
    if a.nrows() != a.ncols() {
        return Err(SolverError::NotSquare {
            nrows: a.nrows(),
            ncols: a.ncols(),
        });
    }
    krylov_solve_operator(a, b, x, preconditioner, params, observer)
}

/// [`krylov_solve`] for an operator known only by its action ([`LinearOperator`]: a
/// matrix-free finite-element operator, or a [`CsrMatrix`]).
///
/// # Errors
/// See [`krylov_solve`].
pub fn krylov_solve_operator(
    a: &dyn LinearOperator,
    b: &[f64],
    x: &mut [f64],
    preconditioner: &mut dyn Preconditioner,
    params: &KrylovParams,
    observer: &mut dyn Observer<f64>,
) -> Result<KrylovReport, SolverError> {
    check(a, b, x, params)?;
    x.fill(0.0);
    let bn = norm(b);
    if bn == 0.0 {
        return Ok(NO_ITERATIONS);
    }
    let run = Run {
        a,
        b,
        preconditioner,
        params,
        observer,
        bn,
    };
    match params.method {
        KrylovMethod::Cg => run.conjugate_gradient(x),
        KrylovMethod::Gmres => run.gmres(x),
    }
}

fn check(
    a: &dyn LinearOperator,
    b: &[f64],
    x: &[f64],
    params: &KrylovParams,
) -> Result<(), SolverError> {
    params.validate()?;
    for (quantity, len) in [("rhs", b.len()), ("x", x.len())] {
        if len != a.dimension() {
            return Err(SolverError::DimensionMismatch {
                quantity,
                expected: a.dimension(),
                found: len,
            });
        }
    }
    crate::scalar::check_finite("right-hand side", b)
}

impl Run<'_> {
    /// Preconditioned conjugate gradients (see [`krylov_solve`]).
    fn conjugate_gradient(self, x: &mut [f64]) -> Result<KrylovReport, SolverError> {
        let n = self.b.len();
        let mut report = NO_ITERATIONS;
        let mut r = self.b.to_vec();
        let mut z = vec![0.0; n];
        let mut ap = vec![0.0; n];
        self.preconditioner.apply(&r, &mut z);
        let mut p = z.clone();
        let mut rz = dot(&r, &z);
        let target = self.params.tolerance * self.bn;
        loop {
            let k = report.iterations;
            if k == self.params.max_iterations {
                let mut true_r = vec![0.0; n];
                self.a.residual(x, self.b, &mut true_r);
                return Err(spent(self.params, k, norm(&true_r) / self.bn));
            }
            self.a.apply(&p, &mut ap);
            let pap = dot(&p, &ap);
            if pap.is_nan() || pap <= 0.0 {
                return Err(if pap.is_finite() {
                    SolverError::NotPositiveDefinite { pivot: k }
                } else {
                    breakdown(k + 1)
                });
            }
            let alpha = rz / pap;
            for i in 0..n {
                x[i] += alpha * p[i];
                r[i] -= alpha * ap[i];
            }
            let rn = norm(&r);
            report.record(rn / self.bn, alpha, self.observer)?;
            if !rn.is_finite() {
                return Err(breakdown(k + 1));
            }
            if rn <= target {
                // the recurrence drifts from b - A x: confirm on the true residual
                self.a.residual(x, self.b, &mut r);
                let true_rn = norm(&r);
                if true_rn <= target {
                    *report.residuals.last_mut().expect("one iteration") = true_rn / self.bn;
                    return Ok(report);
                }
            }
            self.preconditioner.apply(&r, &mut z);
            let rz_next = dot(&r, &z);
            let beta = rz_next / rz;
            rz = rz_next;
            for i in 0..n {
                p[i] = z[i] + beta * p[i];
            }
        }
    }

    /// Restarted right-preconditioned GMRES(`m`) (see [`krylov_solve`]).
    fn gmres(self, x: &mut [f64]) -> Result<KrylovReport, SolverError> {
        let n = self.b.len();
        let m = self
            .params
            .restart
            .min(self.params.max_iterations)
            .min(n.max(1));
        let mut report = NO_ITERATIONS;
        let target = self.params.tolerance * self.bn;
        let mut r = self.b.to_vec();
        let mut rn = self.bn;
        let mut basis: Vec<Vec<f64>> = Vec::with_capacity(m + 1);
        let mut z = vec![0.0; n];
        let mut w = vec![0.0; n];
        // h[j] is column j of the Hessenberg matrix (j + 2 entries)
        let mut h: Vec<Vec<f64>> = Vec::with_capacity(m);
        let mut rotations: Vec<(f64, f64)> = Vec::with_capacity(m);
        loop {
            basis.clear();
            h.clear();
            rotations.clear();
            basis.push(r.iter().map(|v| v / rn).collect());
            let mut g = vec![0.0; m + 1];
            g[0] = rn;
            let mut j = 0;
            while j < m && report.iterations < self.params.max_iterations {
                self.preconditioner.apply(&basis[j], &mut z);
                self.a.apply(&z, &mut w);
                let mut col = vec![0.0; j + 2];
                for (i, v) in basis.iter().enumerate() {
                    let hij = dot(&w, v);
                    col[i] = hij;
                    w.iter_mut().zip(v).for_each(|(wk, vk)| *wk -= hij * vk);
                }
                let wn = norm(&w);
                col[j + 1] = wn;
                for (i, &(c, s)) in rotations.iter().enumerate() {
                    let (hi, hk) = (col[i], col[i + 1]);
                    col[i] = c * hi + s * hk;
                    col[i + 1] = -s * hi + c * hk;
                }
                let (p, q) = (col[j], col[j + 1]);
                let d = p.hypot(q);
                let (c, s) = if d == 0.0 { (1.0, 0.0) } else { (p / d, q / d) };
                col[j] = d;
                col[j + 1] = 0.0;
                rotations.push((c, s));
                g[j + 1] = -s * g[j];
                g[j] *= c;
                h.push(col);
                let estimate = g[j + 1].abs();
                j += 1;
                report.record(estimate / self.bn, 1.0, self.observer)?;
                if !estimate.is_finite() || !wn.is_finite() {
                    return Err(breakdown(report.iterations));
                }
                if estimate <= target || wn <= f64::MIN_POSITIVE {
                    break;
                }
                basis.push(w.iter().map(|v| v / wn).collect());
            }
            // back substitution H y = g, then x += M^-1 V y
            let mut y = vec![0.0; j];
            for i in (0..j).rev() {
                let s: f64 = (i + 1..j).map(|k| h[k][i] * y[k]).sum();
                y[i] = if h[i][i] == 0.0 {
                    0.0
                } else {
                    (g[i] - s) / h[i][i]
                };
            }
            w.fill(0.0);
            for (v, yi) in basis.iter().zip(&y) {
                w.iter_mut().zip(v).for_each(|(wk, vk)| *wk += yi * vk);
            }
            self.preconditioner.apply(&w, &mut z);
            x.iter_mut().zip(&z).for_each(|(xi, zi)| *xi += zi);
            self.a.residual(x, self.b, &mut r);
            rn = norm(&r);
            if !rn.is_finite() {
                return Err(breakdown(report.iterations));
            }
            if let Some(last) = report.residuals.last_mut() {
                *last = rn / self.bn;
            }
            if rn <= target {
                return Ok(report);
            }
            if report.iterations >= self.params.max_iterations {
                return Err(spent(self.params, report.iterations, rn / self.bn));
            }
            // a restart (or an estimate that converged while the true residual did not: loss of
            // orthogonality) continues from the true residual
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::observer::SilentObserver;

    /// The 1-D Laplacian `tridiag(-1, 2 + shift, -1)` plus `skew` on the upper diagonal.
    fn tridiagonal(n: usize, shift: f64, skew: f64) -> CsrMatrix {
        let mut row_ptr = vec![0];
        let (mut c, mut v) = (Vec::new(), Vec::new());
        for i in 0..n {
            if i > 0 {
                c.push((i - 1) as u32);
                v.push(-1.0);
            }
            c.push(i as u32);
            v.push(2.0 + shift);
            if i + 1 < n {
                c.push((i + 1) as u32);
                v.push(-1.0 + skew);
            }
            row_ptr.push(c.len());
        }
        CsrMatrix::new(n, n, row_ptr, c, v).unwrap()
    }

    /// [`krylov_solve`] without a preconditioner or an observer.
    fn solve(
        a: &CsrMatrix,
        b: &[f64],
        x: &mut [f64],
        params: &KrylovParams,
    ) -> Result<KrylovReport, SolverError> {
        krylov_solve(
            a,
            b,
            x,
            &mut IdentityPreconditioner,
            params,
            &mut SilentObserver,
        )
    }

    fn relative_residual(a: &CsrMatrix, x: &[f64], b: &[f64]) -> f64 {
        let mut r = vec![0.0; b.len()];
        a.residual(x, b, &mut r);
        norm(&r) / norm(b)
    }

    #[test]
    fn cg_and_gmres_reach_the_tolerance() {
        let n = 50;
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin() + 1.0).collect();
        let spd = tridiagonal(n, 0.1, 0.0);
        let params = KrylovParams {
            tolerance: 1e-10,
            ..Default::default()
        };
        let mut x = vec![0.0; n];
        for method in [KrylovMethod::Cg, KrylovMethod::Gmres] {
            let p = KrylovParams { method, ..params };
            let rep = solve(&spd, &b, &mut x, &p).unwrap();
            assert!(relative_residual(&spd, &x, &b) <= 1e-10, "{method:?}");
            assert_eq!(rep.iterations, rep.residuals.len());
        }
        // nonsymmetric, restarted
        let a = tridiagonal(n, 0.5, 0.4);
        let p = KrylovParams {
            method: KrylovMethod::Gmres,
            restart: 5,
            ..params
        };
        solve(&a, &b, &mut x, &p).unwrap();
        assert!(relative_residual(&a, &x, &b) <= 1e-10);
    }

    #[test]
    fn a_spent_budget_names_the_field() {
        let n = 200;
        let a = tridiagonal(n, 0.0, 0.0);
        let b = vec![1.0; n];
        let mut x = vec![0.0; n];
        for method in [KrylovMethod::Cg, KrylovMethod::Gmres] {
            let p = KrylovParams {
                method,
                max_iterations: 3,
                ..Default::default()
            };
            match solve(&a, &b, &mut x, &p) {
                Err(SolverError::BudgetSpent {
                    field,
                    iterations,
                    residual,
                    ..
                }) => {
                    assert_eq!(field, KRYLOV_BUDGET_FIELD);
                    assert_eq!(iterations, 3);
                    assert!(residual > 1e-8 && residual.is_finite());
                }
                other => panic!("{method:?}: {other:?}"),
            }
        }
    }

    #[test]
    fn cg_detects_an_indefinite_matrix() {
        let a = tridiagonal(10, -3.0, 0.0);
        let mut x = vec![0.0; 10];
        let p = KrylovParams {
            method: KrylovMethod::Cg,
            ..Default::default()
        };
        let r = solve(&a, &[1.0; 10], &mut x, &p);
        assert!(matches!(r, Err(SolverError::NotPositiveDefinite { .. })));
    }
}
