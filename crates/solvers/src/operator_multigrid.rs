//! A multigrid V-cycle whose fine levels are operators known only by their action
//! (matrix-free), above an assembled coarse level with its own Galerkin [`Multigrid`].

use std::sync::Arc;

use crate::csr_matrix::CsrMatrix;
use crate::error::SolverError;
use crate::krylov::Preconditioner;
use crate::linear_operator::LinearOperator;
use crate::linear_registration::{BackendKind, Parameter, RegisteredLinearSolver};
use crate::multigrid::{LevelData, Multigrid, MultigridParams, power_estimate, smooth};

/// The factor on the power-iteration estimate of `lambda_max(D^-1 A)` of a matrix-free level,
/// so that the Chebyshev smoother's interval `[lower lambda, 1.1 lambda]` lies above the whole
/// spectrum.
///
/// # Math
/// ```text
/// lambda = 1.15 lambda_k,   lambda_k the Rayleigh quotient / |D^-1 A v| after k power
///                           iterations (k = power_iterations, 12 by default): lambda_k <= lambda_max
/// ```
/// Power iteration approaches `lambda_max` from below, slowly when the start has little of
/// the top eigenvectors (the fixed start is mostly smooth; the top modes of `D^-1 A` are the
/// most oscillatory). With the old `1.1 lambda_k` alone the interval ended below
/// `lambda_max` on some grids and the Chebyshev polynomial, which grows fast outside its
/// interval, amplified those modes: the V-cycle of the 3-D contact Jacobian contracted GMRES's
/// residual by about 0.9 per iteration on the 25 x 301 x 25 grid (estimate 3.29; 314 Krylov
/// iterations in 7 fine Newton steps) against 0.3 on its neighbours (estimates 3.5-3.7). With
/// the margin the same grid takes 6 steps and 20 iterations (issue 30). The assembled
/// [`Multigrid`] keeps its own estimate (its results are unchanged).
pub const MATRIX_FREE_ESTIMATE_MARGIN: f64 = 1.15;

/// A matrix-free level of an [`OperatorMultigrid`]: its operator and the prolongation from
/// the next coarser level (the next matrix-free level, or the assembled coarse matrix).
#[derive(Clone)]
pub struct OperatorLevel {
    /// `A_l`, known by its action and diagonal.
    pub operator: Arc<dyn LinearOperator + Send>,
    /// `P_l` from level `l + 1` to level `l` (`A_l.dimension()` rows).
    pub prolongation: CsrMatrix,
}

impl core::fmt::Debug for OperatorLevel {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("OperatorLevel")
            .field("unknowns", &self.operator.dimension())
            .field("coarse_unknowns", &self.prolongation.ncols())
            .finish()
    }
}

/// One matrix-free level with its restriction and smoother data.
#[derive(Debug)]
struct Level {
    level: OperatorLevel,
    restriction: CsrMatrix,
    data: LevelData,
}

/// A V-cycle over matrix-free fine levels and an assembled coarse level.
///
/// # Math
/// ```text
/// levels 0 .. m-1:  A_l given by its action (e.g. a sum-factorised finite-element operator,
///                   p-multigrid or a rediscretised coarser grid), P_l to level l + 1
/// level m:          A_m assembled (a CsrMatrix), preconditioned by one V-cycle of its own
///                   Galerkin Multigrid (A_{k+1} = Q_k^T A_k Q_k, sparse LU at the bottom)
/// V(l, b):  x = S_l(0, b)                              (Chebyshev or Jacobi on D_l^-1 A_l,
///                                                       D_l the diagonal computed matrix-free)
///           x = x + P_l V(l + 1, P_l^T (b - A_l x))
///           x = S_l(x, b)
/// ```
/// With symmetric `A_l`, the same smoother before and after, and a symmetric coarse cycle,
/// the V-cycle is symmetric (usable in CG). The coarse operators are not the Galerkin
/// products of the matrix-free ones (which would need them assembled): rediscretisations
/// on the coarser spaces, which keep the multigrid property for elliptic operators.
#[derive(Debug)]
pub struct OperatorMultigrid {
    params: MultigridParams,
    levels: Vec<Level>,
    coarse: CsrMatrix,
    inner: Multigrid,
}

impl OperatorMultigrid {
    /// Builds the cycle: the smoothers of the matrix-free `levels` (finest first; their
    /// diagonals and the largest eigenvalue of `D^-1 A` by power iteration), and the
    /// Galerkin hierarchy of the assembled `coarse` matrix on `coarse_prolongations`.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] for bad settings or no matrix-free level;
    /// [`SolverError::DimensionMismatch`] when the levels do not chain;
    /// [`SolverError::Singular`] for a zero or non-finite diagonal or a singular coarsest
    /// operator.
    pub fn new(
        levels: Vec<OperatorLevel>,
        coarse: CsrMatrix,
        coarse_prolongations: Arc<[CsrMatrix]>,
        params: MultigridParams,
    ) -> Result<Self, SolverError> {
        Self::with_estimates(levels, coarse, coarse_prolongations, params, None)
    }

    /// [`OperatorMultigrid::new`] with the largest eigenvalues of `D^-1 A` of the matrix-free
    /// levels given (`Some`, one per level: e.g. [`OperatorMultigrid::estimates`] of an
    /// earlier cycle of a nearby operator, such as the Jacobian of the previous Newton step)
    /// instead of estimated by power iteration (`None`): saves `power_iterations` operator
    /// applications per level.
    ///
    /// # Errors
    /// As [`OperatorMultigrid::new`]; [`SolverError::DimensionMismatch`] for a wrong number
    /// of estimates.
    pub fn with_estimates(
        levels: Vec<OperatorLevel>,
        coarse: CsrMatrix,
        coarse_prolongations: Arc<[CsrMatrix]>,
        params: MultigridParams,
        estimates: Option<&[f64]>,
    ) -> Result<Self, SolverError> {
        params.validate()?;
        if let Some(e) = estimates
            && e.len() != levels.len()
        {
            return Err(SolverError::DimensionMismatch {
                quantity: "eigenvalue estimates",
                expected: levels.len(),
                found: e.len(),
            });
        }
        if levels.is_empty() {
            return Err(SolverError::invalid(
                "operator multigrid levels",
                0.0,
                "[1, inf)",
            ));
        }
        for (l, level) in levels.iter().enumerate() {
            let next = levels
                .get(l + 1)
                .map_or(coarse.nrows(), |n| n.operator.dimension());
            let p = &level.prolongation;
            if p.nrows() != level.operator.dimension() || p.ncols() != next {
                return Err(SolverError::DimensionMismatch {
                    quantity: "prolongation shape",
                    expected: next,
                    found: p.ncols(),
                });
            }
        }
        let mut inner = Multigrid::new(coarse_prolongations, params)?;
        inner.setup(&coarse)?;
        let levels = levels
            .into_iter()
            .enumerate()
            .map(|(l, level)| -> Result<Level, SolverError> {
                let op = level.operator.as_ref();
                let n = op.dimension();
                let inv_diag = op
                    .diagonal()
                    .iter()
                    .enumerate()
                    .map(|(i, &v)| {
                        if v == 0.0 || !v.is_finite() {
                            Err(SolverError::Singular { pivot: Some(i) })
                        } else {
                            Ok(1.0 / v)
                        }
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                let lambda = match estimates {
                    Some(e) => e[l],
                    None => {
                        MATRIX_FREE_ESTIMATE_MARGIN
                            * power_estimate(op, &inv_diag, params.power_iterations)
                    }
                };
                let restriction = level.prolongation.transpose();
                Ok(Level {
                    level,
                    restriction,
                    data: LevelData::new(n, inv_diag, lambda),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            params,
            levels,
            coarse,
            inner,
        })
    }

    /// Unknowns of every level, finest first (the matrix-free levels, then the assembled
    /// coarse hierarchy).
    pub fn level_sizes(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self
            .levels
            .iter()
            .map(|l| l.level.operator.dimension())
            .collect();
        out.extend(self.inner.level_sizes());
        out
    }

    /// Bytes held by the transfers, the assembled coarse hierarchy and the work vectors (not
    /// the matrix-free operators themselves).
    pub fn bytes(&self) -> usize {
        self.levels
            .iter()
            .map(|l| l.level.prolongation.bytes() + l.restriction.bytes() + 8 * 7 * l.data.r.len())
            .sum::<usize>()
            + self.coarse.bytes()
            + self.inner.bytes()
    }

    /// The upper bound of the spectrum of `D^-1 A` of every matrix-free level (as given, or
    /// [`MATRIX_FREE_ESTIMATE_MARGIN`] times the power-iteration estimate).
    pub fn estimates(&self) -> Vec<f64> {
        self.levels.iter().map(|l| l.data.lambda()).collect()
    }

    /// The finest operator `A_0`.
    pub fn operator(&self) -> &dyn LinearOperator {
        self.levels[0].level.operator.as_ref()
    }

    fn cycle(&mut self, level: usize, b: &[f64], x: &mut [f64]) {
        if level == self.levels.len() {
            self.inner.with(&self.coarse).apply(b, x);
            return;
        }
        let params = self.params;
        let (this, _) = self.levels[level..].split_first_mut().expect("a level");
        let op = Arc::clone(&this.level.operator);
        x.fill(0.0);
        for step in 0..params.smoothing_steps {
            smooth(op.as_ref(), &mut this.data, &params, b, x, step == 0);
        }
        op.residual(x, b, &mut this.data.r);
        let nc = this.level.prolongation.ncols();
        let mut cb = vec![0.0; nc];
        let mut cx = vec![0.0; nc];
        this.restriction.mul_vec(&this.data.r, &mut cb);
        self.cycle(level + 1, &cb, &mut cx);
        let this = &mut self.levels[level];
        this.level.prolongation.mul_vec(&cx, &mut this.data.d);
        x.iter_mut()
            .zip(&this.data.d)
            .for_each(|(xi, di)| *xi += di);
        for _ in 0..params.smoothing_steps {
            smooth(op.as_ref(), &mut this.data, &params, b, x, false);
        }
    }
}

impl Preconditioner for OperatorMultigrid {
    fn apply(&mut self, r: &[f64], z: &mut [f64]) {
        self.cycle(0, r, z);
    }
}

/// The `matrix-free-mg` entry of [`crate::linear_registry`]: the Newton steps of a caller
/// that never assembles its matrix (the 3-D contact body's matrix-free full-system Newton,
/// `capstan_elasticity::contact::MatrixFreeNewton`), GMRES preconditioned by an
/// [`OperatorMultigrid`] whose fine level is the operator's action. It has no assembled
/// matrix to work on, so building it as a [`crate::LinearSolver`] is refused: the caller
/// dispatches on the name ([`BackendKind::MatrixFree`]).
pub(crate) const MATRIX_FREE_REGISTRATION: RegisteredLinearSolver = RegisteredLinearSolver {
    name: "matrix-free-mg",
    summary: "matrix-free Newton-Krylov (3-D body): GMRES on the operator's action with a p-multigrid/semi-coarsening V-cycle, Eisenstat-Walker forcing",
    parameters: &[
        Parameter {
            key: "krylov.max_iterations",
            default: "500",
            allowed: "[1, inf)",
        },
        Parameter {
            key: "krylov.restart",
            default: "100",
            allowed: "[1, inf)",
        },
        Parameter {
            key: "multigrid.smoothing_steps",
            default: "1",
            allowed: "[1, inf)",
        },
        Parameter {
            key: "multigrid.coarsest_unknowns",
            default: "5000",
            allowed: "[1, inf)",
        },
    ],
    kind: BackendKind::MatrixFree,
    build: |_, _| {
        Err(SolverError::InvalidParameter {
            field: "linear",
            value: f64::NAN,
            allowed: "`matrix-free-mg` only for the full-system Newton of the 3-D body (body.dimension = 3), which never assembles its matrix",
        })
    },
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::krylov::{KrylovMethod, KrylovParams, krylov_solve_operator};
    use crate::observer::SilentObserver;

    /// The 1-D Laplacian `tridiag(-1, 2, -1) / h` on `n` interior points, matrix-free.
    struct Laplacian1d {
        n: usize,
    }

    impl LinearOperator for Laplacian1d {
        fn dimension(&self) -> usize {
            self.n
        }
        fn apply(&self, x: &[f64], y: &mut [f64]) {
            let h = 1.0 / (self.n + 1) as f64;
            for i in 0..self.n {
                let left = if i > 0 { x[i - 1] } else { 0.0 };
                let right = if i + 1 < self.n { x[i + 1] } else { 0.0 };
                y[i] = (2.0 * x[i] - left - right) / h;
            }
        }
        fn diagonal(&self) -> Vec<f64> {
            vec![2.0 * (self.n + 1) as f64; self.n]
        }
    }

    /// Linear interpolation from `(n - 1) / 2` coarse interior points to `n` fine ones.
    fn interpolation(n: usize) -> CsrMatrix {
        let nc = (n - 1) / 2;
        let (mut ptr, mut cols, mut vals) = (vec![0], vec![], vec![]);
        for i in 0..n {
            if i % 2 == 1 {
                cols.push((i / 2) as u32);
                vals.push(1.0);
            } else {
                if i >= 2 {
                    cols.push((i / 2 - 1) as u32);
                    vals.push(0.5);
                }
                if i / 2 < nc {
                    cols.push((i / 2) as u32);
                    vals.push(0.5);
                }
            }
            ptr.push(cols.len());
        }
        CsrMatrix::new(n, nc, ptr, cols, vals).unwrap()
    }

    /// The assembled Laplacian on `n` points.
    fn assembled(n: usize) -> CsrMatrix {
        let op = Laplacian1d { n };
        let (mut ptr, mut cols, mut vals) = (vec![0], vec![], vec![]);
        let mut e = vec![0.0; n];
        let mut col = vec![0.0; n];
        let mut dense = vec![vec![0.0; n]; n];
        for j in 0..n {
            e.fill(0.0);
            e[j] = 1.0;
            op.apply(&e, &mut col);
            for i in 0..n {
                dense[i][j] = col[i];
            }
        }
        for row in &dense {
            for (j, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    cols.push(j as u32);
                    vals.push(v);
                }
            }
            ptr.push(cols.len());
        }
        CsrMatrix::new(n, n, ptr, cols, vals).unwrap()
    }

    /// CG iterations to 1e-10 with two matrix-free levels over an assembled third one.
    fn cg_iterations(n: usize) -> usize {
        let n1 = (n - 1) / 2;
        let n2 = (n1 - 1) / 2;
        let levels = vec![
            OperatorLevel {
                operator: Arc::new(Laplacian1d { n }),
                prolongation: interpolation(n),
            },
            OperatorLevel {
                operator: Arc::new(Laplacian1d { n: n1 }),
                prolongation: interpolation(n1),
            },
        ];
        let mut mg = OperatorMultigrid::new(
            levels,
            assembled(n2),
            vec![].into(),
            MultigridParams::default(),
        )
        .unwrap();
        assert_eq!(mg.level_sizes(), vec![n, n1, n2]);
        let b: Vec<f64> = (0..n).map(|i| ((i * 7) % 11) as f64 - 5.0).collect();
        let mut x = vec![0.0; n];
        let params = KrylovParams {
            method: KrylovMethod::Cg,
            tolerance: 1e-10,
            ..Default::default()
        };
        let op = Laplacian1d { n };
        let report =
            krylov_solve_operator(&op, &b, &mut x, &mut mg, &params, &mut SilentObserver).unwrap();
        let mut r = vec![0.0; n];
        op.residual(&x, &b, &mut r);
        let rn = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(rn <= 1e-10 * bn, "{}", rn / bn);
        report.iterations
    }

    #[test]
    fn matrix_free_levels_keep_cg_counts_bounded() {
        // 8x the unknowns: the two-matrix-free-level V-cycle keeps CG within a few iterations
        let counts: Vec<usize> = [63, 255, 511].map(cg_iterations).to_vec();
        assert!(counts[2] <= counts[0] + 3, "{counts:?}");
        assert!(counts.iter().all(|&c| c <= 12), "{counts:?}");
    }

    #[test]
    fn the_smoothing_interval_of_a_matrix_free_level_lies_above_its_spectrum() {
        // D^-1 A of the 1-D Laplacian: I - T/2, lambda_max = 1 + cos(pi / (n + 1)). Twelve
        // power iterations from the fixed (mostly smooth) start reach 0.94 of it; the bound
        // kept by the level must lie above lambda_max (the 0.94 alone did not), and not so far
        // above that the smoother loses its lower modes (at most 1.25 lambda_max).
        for n in [63, 255, 511] {
            let mg = OperatorMultigrid::new(
                vec![OperatorLevel {
                    operator: Arc::new(Laplacian1d { n }),
                    prolongation: interpolation(n),
                }],
                assembled((n - 1) / 2),
                vec![].into(),
                MultigridParams::default(),
            )
            .unwrap();
            let exact = 1.0 + (core::f64::consts::PI / (n + 1) as f64).cos();
            let bound = mg.estimates()[0];
            assert!(bound >= exact, "n = {n}: {bound} < {exact}");
            assert!(bound <= 1.25 * exact, "n = {n}: {bound} > 1.25 x {exact}");
            let raw = power_estimate(&Laplacian1d { n }, &vec![0.5 / (n + 1) as f64; n], 12);
            assert!(
                raw < exact,
                "n = {n}: the plain estimate {raw} is below lambda_max"
            );
            assert!((bound - MATRIX_FREE_ESTIMATE_MARGIN * raw).abs() <= 1e-12 * bound);
        }
    }

    #[test]
    fn levels_that_do_not_chain_are_refused() {
        let levels = vec![OperatorLevel {
            operator: Arc::new(Laplacian1d { n: 15 }),
            prolongation: interpolation(15),
        }];
        let r = OperatorMultigrid::new(levels, assembled(5), vec![].into(), Default::default());
        assert!(matches!(r, Err(SolverError::DimensionMismatch { .. })));
        let r = OperatorMultigrid::new(vec![], assembled(5), vec![].into(), Default::default());
        assert!(matches!(r, Err(SolverError::InvalidParameter { .. })));
    }
}
