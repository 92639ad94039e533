//! A multigrid V-cycle on a given hierarchy of prolongations: Galerkin coarse operators,
//! damped-Jacobi or Chebyshev–Jacobi smoothing, a sparse LU on the coarsest level.

use std::sync::Arc;

use crate::csr_matrix::CsrMatrix;
use crate::error::SolverError;
use crate::krylov::Preconditioner;
use crate::linear_operator::LinearOperator;
use crate::linear_solver::LinearSolver;
use crate::sparse_lu::SparseLu;
use crate::sparsity_pattern::SparsityPattern;

/// The smoother of a [`Multigrid`] level.
///
/// # Math
/// With `D = diag(A)` and `lambda` the largest eigenvalue of `D^-1 A` (estimated by power
/// iteration):
/// ```text
/// Jacobi:     x <- x + omega D^-1 (b - A x)                        (one sweep)
/// Chebyshev:  x <- x + p(D^-1 A) D^-1 (b - A x),  p of degree `degree` - 1, the Chebyshev
///             polynomial that is small on [lower lambda, 1.1 lambda]   (`degree` products)
/// ```
/// Both are symmetric in the sense that the V-cycle with the same smoother before and after
/// the coarse correction is a symmetric preconditioner for a symmetric `A` (usable in CG).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum Smoother {
    /// Damped Jacobi with weight `omega` in `(0, 1]`.
    Jacobi {
        /// The damping weight.
        omega: f64,
    },
    /// Chebyshev–Jacobi of `degree` matrix products on `[lower lambda, 1.1 lambda]`.
    Chebyshev {
        /// Matrix products per smoothing step, at least 1.
        degree: usize,
        /// The lower end of the smoothed interval as a fraction of `lambda`, in `(0, 1)`.
        lower: f64,
    },
}

impl Default for Smoother {
    fn default() -> Self {
        Self::Chebyshev {
            degree: 2,
            lower: 0.1,
        }
    }
}

/// Settings of [`Multigrid`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MultigridParams {
    /// The smoother of every level but the coarsest.
    pub smoother: Smoother,
    /// Smoothing steps before and after the coarse correction (at least 1).
    pub smoothing_steps: usize,
    /// Power iterations for `lambda` (the largest eigenvalue of `D^-1 A`), at least 1.
    pub power_iterations: usize,
    /// The hierarchy the caller builds stops coarsening at a level of at most this many
    /// unknowns (solved by a sparse LU), at least 1 ([`crate::LinearContext::prolongations`]).
    pub coarsest_unknowns: usize,
}

impl Default for MultigridParams {
    fn default() -> Self {
        Self {
            smoother: Smoother::default(),
            smoothing_steps: 1,
            power_iterations: 12,
            coarsest_unknowns: 5_000,
        }
    }
}

impl MultigridParams {
    /// Checks every field.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SolverError> {
        match self.smoother {
            Smoother::Jacobi { omega } if !(omega > 0.0 && omega <= 1.0) => {
                return Err(SolverError::invalid("smoother.omega", omega, "(0, 1]"));
            }
            Smoother::Chebyshev { degree: 0, .. } => {
                return Err(SolverError::invalid("smoother.degree", 0.0, "[1, inf)"));
            }
            Smoother::Chebyshev { lower, .. } if !(lower > 0.0 && lower < 1.0) => {
                return Err(SolverError::invalid("smoother.lower", lower, "(0, 1)"));
            }
            _ => {}
        }
        SolverError::check_count("smoothing_steps", self.smoothing_steps)?;
        SolverError::check_count("power_iterations", self.power_iterations)?;
        SolverError::check_count("coarsest_unknowns", self.coarsest_unknowns)?;
        Ok(())
    }
}

/// One level's smoother data and work vectors.
#[derive(Debug, Default)]
pub(crate) struct LevelData {
    inv_diag: Vec<f64>,
    lambda: f64,
    pub(crate) r: Vec<f64>,
    pub(crate) d: Vec<f64>,
    b: Vec<f64>,
    x: Vec<f64>,
}

impl LevelData {
    /// `lambda_max(D^-1 A)` as estimated.
    pub(crate) fn lambda(&self) -> f64 {
        self.lambda
    }

    /// The smoother data of a level of `n` unknowns: `D^-1` and `lambda_max(D^-1 A)`.
    pub(crate) fn new(n: usize, inv_diag: Vec<f64>, lambda: f64) -> Self {
        Self {
            inv_diag,
            lambda,
            r: vec![0.0; n],
            d: vec![0.0; n],
            b: Vec::new(),
            x: Vec::new(),
        }
    }
}

/// A geometric (or any given-hierarchy) multigrid V-cycle.
///
/// The hierarchy is given as prolongations `P_0, P_1, ...` (`P_l` maps level `l + 1` to the
/// finer level `l`); [`Multigrid::setup`] builds the Galerkin operators for a fine matrix
/// `A_0` and the smoothers; [`Multigrid::with`] is then a [`Preconditioner`] for `A_0`.
///
/// # Math
/// ```text
/// A_{l+1} = P_l^T A_l P_l                                  (Galerkin)
/// V(l, b):  x = S_l(0, b)                                  (pre-smoothing)
///           x = x + P_l V(l + 1, P_l^T (b - A_l x))        (coarse correction)
///           x = S_l(x, b)                                  (post-smoothing)
/// V(L, b) = A_L^-1 b                                       (sparse LU)
/// ```
/// For a symmetric positive definite `A_0` and full-rank prolongations the V-cycle is a
/// symmetric positive definite preconditioner; its contraction is independent of the grid
/// size for elliptic problems on nested grids (the multigrid property).
#[derive(Debug)]
pub struct Multigrid {
    params: MultigridParams,
    prolongations: Arc<[CsrMatrix]>,
    restrictions: Vec<CsrMatrix>,
    /// `A_1 .. A_L`.
    coarse: Vec<CsrMatrix>,
    data: Vec<LevelData>,
    lu: SparseLu,
    lu_pattern: Option<SparsityPattern>,
    ready: bool,
}

impl Multigrid {
    /// The V-cycle over `prolongations` (finest first; none: the LU of `A_0` itself).
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] for bad settings;
    /// [`SolverError::DimensionMismatch`] if consecutive prolongations do not chain
    /// (`P_l` has as many columns as `P_{l+1}` has rows).
    pub fn new(
        prolongations: Arc<[CsrMatrix]>,
        params: MultigridParams,
    ) -> Result<Self, SolverError> {
        params.validate()?;
        for w in prolongations.windows(2) {
            if w[0].ncols() != w[1].nrows() {
                return Err(SolverError::DimensionMismatch {
                    quantity: "prolongation rows",
                    expected: w[0].ncols(),
                    found: w[1].nrows(),
                });
            }
        }
        let restrictions = prolongations.iter().map(CsrMatrix::transpose).collect();
        Ok(Self {
            params,
            prolongations,
            restrictions,
            coarse: Vec::new(),
            data: Vec::new(),
            lu: SparseLu::default(),
            lu_pattern: None,
            ready: false,
        })
    }

    /// Number of levels (prolongations + 1).
    pub fn levels(&self) -> usize {
        self.prolongations.len() + 1
    }

    /// Unknowns of every level, finest first (after [`Multigrid::setup`]).
    pub fn level_sizes(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self.prolongations.iter().map(CsrMatrix::nrows).collect();
        out.push(
            self.prolongations
                .last()
                .map_or(self.data.first().map_or(0, |d| d.r.len()), CsrMatrix::ncols),
        );
        out
    }

    /// Bytes held by the coarse operators, transfer operators and work vectors.
    pub fn bytes(&self) -> usize {
        let m: usize = self.coarse.iter().map(CsrMatrix::bytes).sum::<usize>()
            + self
                .prolongations
                .iter()
                .map(CsrMatrix::bytes)
                .sum::<usize>()
            + self
                .restrictions
                .iter()
                .map(CsrMatrix::bytes)
                .sum::<usize>();
        m + self.data.iter().map(|d| 8 * 6 * d.r.len()).sum::<usize>()
    }

    /// Builds the Galerkin operators, the smoothers and the coarsest LU for the fine matrix
    /// `a`.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] if `a` does not fit the finest prolongation;
    /// [`SolverError::Singular`] for a zero diagonal on a smoothed level or a singular
    /// coarsest operator.
    pub fn setup(&mut self, a: &CsrMatrix) -> Result<(), SolverError> {
        self.ready = false;
        if let Some(p) = self.prolongations.first()
            && p.nrows() != a.nrows()
        {
            return Err(SolverError::DimensionMismatch {
                quantity: "matrix rows",
                expected: p.nrows(),
                found: a.nrows(),
            });
        }
        self.coarse.clear();
        for (l, (p, r)) in self
            .prolongations
            .iter()
            .zip(&self.restrictions)
            .enumerate()
        {
            let fine = if l == 0 { a } else { &self.coarse[l - 1] };
            let c = fine.galerkin(p, r);
            self.coarse.push(c);
        }
        let levels = self.levels();
        self.data.resize_with(levels, LevelData::default);
        for l in 0..levels {
            let op = if l == 0 { a } else { &self.coarse[l - 1] };
            let n = op.nrows();
            let d = &mut self.data[l];
            for v in [&mut d.r, &mut d.d, &mut d.b, &mut d.x] {
                v.resize(n, 0.0);
            }
            if l + 1 == levels {
                break;
            }
            d.inv_diag = op
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
                .collect::<Result<_, _>>()?;
            d.lambda = power_estimate(op, &d.inv_diag, self.params.power_iterations);
        }
        let coarsest = if levels == 1 {
            a
        } else {
            &self.coarse[levels - 2]
        };
        let (pattern, values) = coarsest.to_pattern();
        if self.lu_pattern.as_ref() != Some(&pattern) {
            self.lu.analyse(&pattern)?;
            self.lu_pattern = Some(pattern);
        }
        self.lu.factor(&values)?;
        self.ready = true;
        Ok(())
    }

    /// The V-cycle as a preconditioner for `a`, the matrix of the last
    /// [`Multigrid::setup`].
    ///
    /// # Panics
    /// Before a successful [`Multigrid::setup`] (a programmer error).
    #[track_caller]
    pub fn with<'a>(&'a mut self, a: &'a CsrMatrix) -> MultigridPreconditioner<'a> {
        assert!(self.ready, "Multigrid::with before a successful setup");
        MultigridPreconditioner { fine: a, mg: self }
    }

    fn cycle(&mut self, fine: &CsrMatrix, level: usize, b: &[f64], x: &mut [f64]) {
        let levels = self.levels();
        if level + 1 == levels {
            x.copy_from_slice(b);
            // a failed coarse solve leaves the smoothed iterate without correction
            if self.lu.solve_in_place(x).is_err() {
                x.fill(0.0);
            }
            return;
        }
        let params = self.params;
        let Self {
            coarse,
            data,
            prolongations,
            restrictions,
            ..
        } = self;
        let op = if level == 0 { fine } else { &coarse[level - 1] };
        let (this, rest) = data[level..].split_first_mut().expect("a level");
        x.fill(0.0);
        for step in 0..params.smoothing_steps {
            smooth(op, this, &params, b, x, step == 0);
        }
        op.residual(x, b, &mut this.r);
        let next = &mut rest[0];
        restrictions[level].mul_vec(&this.r, &mut next.b);
        let (mut cb, mut cx) = (std::mem::take(&mut next.b), std::mem::take(&mut next.x));
        let p = Arc::clone(prolongations);
        self.cycle(fine, level + 1, &cb, &mut cx);
        let this = &mut self.data[level];
        p[level].mul_vec(&cx, &mut this.d);
        x.iter_mut().zip(&this.d).for_each(|(xi, di)| *xi += di);
        let next = &mut self.data[level + 1];
        core::mem::swap(&mut next.b, &mut cb);
        core::mem::swap(&mut next.x, &mut cx);
        let op = if level == 0 {
            fine
        } else {
            &self.coarse[level - 1]
        };
        for _ in 0..params.smoothing_steps {
            smooth(op, &mut self.data[level], &params, b, x, false);
        }
    }
}

/// One smoothing step on `x` for `A x = b` (`zero`: `x` is known to be 0).
pub(crate) fn smooth(
    a: &dyn LinearOperator,
    d: &mut LevelData,
    params: &MultigridParams,
    b: &[f64],
    x: &mut [f64],
    zero: bool,
) {
    let LevelData {
        inv_diag,
        lambda,
        r,
        d: dir,
        ..
    } = d;
    let residual = |x: &[f64], r: &mut Vec<f64>| {
        if zero {
            r.copy_from_slice(b);
        } else {
            a.residual(x, b, r);
        }
        r.iter_mut()
            .zip(inv_diag.iter())
            .for_each(|(ri, di)| *ri *= di);
    };
    match params.smoother {
        Smoother::Jacobi { omega } => {
            residual(x, r);
            x.iter_mut()
                .zip(r.iter())
                .for_each(|(xi, ri)| *xi += omega * ri);
        }
        Smoother::Chebyshev { degree, lower } => {
            let (alpha, beta) = (lower * *lambda, 1.1 * *lambda);
            let theta = 0.5 * (beta + alpha);
            let delta = 0.5 * (beta - alpha);
            let sigma = theta / delta;
            let mut rho = 1.0 / sigma;
            residual(x, r);
            dir.iter_mut()
                .zip(r.iter())
                .for_each(|(di, ri)| *di = ri / theta);
            for k in 1..=degree {
                x.iter_mut().zip(dir.iter()).for_each(|(xi, di)| *xi += di);
                if k == degree {
                    break;
                }
                a.residual(x, b, r);
                r.iter_mut()
                    .zip(inv_diag.iter())
                    .for_each(|(ri, di)| *ri *= di);
                let rho_next = 1.0 / (2.0 * sigma - rho);
                let (c1, c2) = (rho_next * rho, 2.0 * rho_next / delta);
                dir.iter_mut()
                    .zip(r.iter())
                    .for_each(|(di, ri)| *di = c1 * *di + c2 * ri);
                rho = rho_next;
            }
        }
    }
}

/// The largest eigenvalue of `D^-1 A` by `iterations` power iterations from a fixed
/// pseudo-random start (an estimate from below; the smoothers add 10 %).
pub(crate) fn power_estimate(a: &dyn LinearOperator, inv_diag: &[f64], iterations: usize) -> f64 {
    let n = a.dimension();
    let mut v: Vec<f64> = (0..n)
        .map(|i| {
            let h = (i as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
            0.5 + (h >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect();
    let mut w = vec![0.0; n];
    let mut lambda = 1.0;
    for _ in 0..iterations {
        let vn = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(vn > 0.0 && vn.is_finite()) {
            break;
        }
        v.iter_mut().for_each(|x| *x /= vn);
        a.apply(&v, &mut w);
        w.iter_mut().zip(inv_diag).for_each(|(wi, di)| *wi *= di);
        lambda = v.iter().zip(&w).map(|(x, y)| x * y).sum::<f64>().abs();
        let wn = w.iter().map(|x| x * x).sum::<f64>().sqrt();
        lambda = lambda.max(wn);
        core::mem::swap(&mut v, &mut w);
    }
    if lambda > 0.0 && lambda.is_finite() {
        lambda
    } else {
        1.0
    }
}

/// A [`Multigrid`] V-cycle bound to its fine matrix: a [`Preconditioner`].
#[derive(Debug)]
pub struct MultigridPreconditioner<'a> {
    fine: &'a CsrMatrix,
    mg: &'a mut Multigrid,
}

impl Preconditioner for MultigridPreconditioner<'_> {
    fn apply(&mut self, r: &[f64], z: &mut [f64]) {
        self.mg.cycle(self.fine, 0, r, z);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::krylov::{KrylovMethod, KrylovParams, krylov_solve};
    use crate::observer::SilentObserver;

    /// The 1-D Laplacian on `n` interior nodes and linear interpolation from `(n - 1) / 2`.
    fn laplacian(n: usize) -> CsrMatrix {
        let mut row_ptr = vec![0];
        let (mut c, mut v) = (Vec::new(), Vec::new());
        for i in 0..n {
            for (j, a) in [(i.wrapping_sub(1), -1.0), (i, 2.0), (i + 1, -1.0)] {
                if j < n {
                    c.push(j as u32);
                    v.push(a);
                }
            }
            row_ptr.push(c.len());
        }
        CsrMatrix::new(n, n, row_ptr, c, v).unwrap()
    }

    fn interpolation(n: usize) -> CsrMatrix {
        let m = (n - 1) / 2;
        let mut row_ptr = vec![0];
        let (mut c, mut v) = (Vec::new(), Vec::new());
        for i in 0..n {
            // fine i (1-based i + 1) sits at coarse (i + 1) / 2
            if i % 2 == 1 {
                c.push((i / 2) as u32);
                v.push(1.0);
            } else {
                for j in [i / 2, i / 2 + 1] {
                    if j >= 1 && j <= m {
                        c.push((j - 1) as u32);
                        v.push(0.5);
                    }
                }
            }
            row_ptr.push(c.len());
        }
        CsrMatrix::new(n, m, row_ptr, c, v).unwrap()
    }

    #[test]
    fn v_cycle_cg_iterations_do_not_grow_with_the_grid() {
        let mut counts = Vec::new();
        for k in [6, 8, 10] {
            let n = (1 << k) - 1;
            let mut ps = Vec::new();
            let mut m = n;
            while m > 7 {
                ps.push(interpolation(m));
                m = (m - 1) / 2;
            }
            let a = laplacian(n);
            for smoother in [Smoother::default(), Smoother::Jacobi { omega: 2.0 / 3.0 }] {
                let params = MultigridParams {
                    smoother,
                    ..Default::default()
                };
                let mut mg = Multigrid::new(ps.clone().into(), params).unwrap();
                mg.setup(&a).unwrap();
                assert_eq!(mg.level_sizes()[0], n);
                let b: Vec<f64> = (0..n).map(|i| ((i * 7) % 5) as f64 - 2.0).collect();
                let mut x = vec![0.0; n];
                let kp = KrylovParams {
                    method: KrylovMethod::Cg,
                    tolerance: 1e-10,
                    ..Default::default()
                };
                let rep = krylov_solve(&a, &b, &mut x, &mut mg.with(&a), &kp, &mut SilentObserver)
                    .unwrap();
                counts.push(rep.iterations);
            }
        }
        // unpreconditioned CG would need ~n iterations (1023 at the finest)
        assert!(counts.iter().all(|&c| c <= 20), "{counts:?}");
    }
}
