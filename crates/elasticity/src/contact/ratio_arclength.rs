//! Pseudo-arclength continuation in the tension ratio on the full-system Newton: follows the
//! equilibrium path `R(v, r) = 0` past the points where the Jacobian `dR/dv` is singular, and
//! tells a limit point (fold: the path turns back to lower ratios, so no equilibrium lies
//! beyond it on the path) from a solver stall.

use capstan_friction::FrictionLaw;
use capstan_solvers::{BoxedLinearSolver, Jacobian, Residual, SolverError};

use crate::contact::error::ContactError;
use crate::contact::full_system::{FullSystemProblem, FullSystemSolver};
use crate::contact::load_continuation::LoadSteps;
use crate::contact::loads::EndLoads;
use crate::contact::operator::ContactOperator;
use crate::contact::solution::ContactSolution;

/// Arclength steps at most.
const MAX_STEPS: usize = 200;
/// Corrector iterations per step.
const CORRECTOR_ITERATIONS: usize = 25;
/// How far (in units of the ratio step `to - from`) the path must fall back below the largest
/// ratio it reached to count as folded: the contact set changes along the path, and each
/// change may turn the path back by a little (measured: 0.006 on the cone, `3 x 20 x 3`, near
/// 1.436) before it climbs on. The textbook test, the sign change of the tangent's ratio
/// component `t_r`, stops at those local folds: measured (release), it brackets the stop at
/// 1.395746 on `3 x 20 x 3` (this test: 1.439790) and 1.266972 on `6 x 40 x 5` (1.276532),
/// in 50 and 40 arclength steps of [`FullSystemSolver::run_off`] against 72 and 58.
const FOLD_RETURN: f64 = 0.5;
/// Smallest arclength step, relative to the first.
const MIN_STEP: f64 = 1e-6;

impl<D: ContactOperator, L: FrictionLaw<f64>> FullSystemSolver<'_, D, L> {
    /// Continues the equilibrium `v_start` at `tau_max / tau0 = from` (converged, e.g. by
    /// [`FullSystemSolver::solve_from`]) to the ratio `to` by pseudo-arclength continuation in
    /// `(v, r)`, and solves there; or reports the fold of the path before `to` as
    /// [`ContactError::NoEquilibrium`]: with `upper` the largest ratio the path reached when
    /// it climbs (`to > from`), with `lower` the smallest when it goes down (`to < from`).
    ///
    /// # Math
    /// ```text
    /// R(v, r) = R(v; tau0, r tau0) = 0,    x = (v, r),    |t| = 1,  t = (t_v, t_r)
    /// d = sign(to - from): the first tangent has d t_r > 0
    /// tangent:    J t_v + R_r t_r = 0      (J = dR/dv, R_r = dR/dr)
    /// predictor:  x_p = x + ds t
    /// corrector:  [J    R_r] [dv]     [R          ]
    ///             [t_v  t_r] [dr] = - [t . (x-x_p)]
    /// by bordering with two solves of one factorisation of J (Keller):
    ///   a = -J^{-1} R,  b = -J^{-1} R_r,  dr = -(t.(x-x_p) + t_v . a) / (t_v . b + t_r),
    ///   dv = a + dr b
    /// ```
    /// `R` is affine in `r` (the end loads), so `R_r = R(v, r + 1) - R(v, r)` at fixed `v` and
    /// contact set. Where `d dr/ds = d t_r` changes sign from positive to negative the path
    /// has a limit point `r* = max d r` (a fold: `J` singular along the sliding mode there,
    /// the net load along the mode no longer balanced by friction); a load-controlled path has
    /// no equilibrium nearby past it. The path is only piecewise smooth (the contact and slip
    /// sets change along it), so a fold is reported once the path has fallen back by half the
    /// ratio step `|to - from| / 2` from the furthest ratio it reached along `d`, not at the
    /// first sign change of `d t_r`. Steps grow by 1.5 after a converged corrector and halve
    /// after a failed one. The fold found is one of this path; another branch (a different
    /// contact set) is not searched.
    ///
    /// # Errors
    /// [`ContactError::NoEquilibrium`] when the path turns back before `to` (climbing:
    /// `lower` = `-inf`, `upper` = the fold's ratio; going down: `lower` = the fold's ratio,
    /// `upper` = `+inf`); [`ContactError::NotConverged`] when the steps fall
    /// below their minimum or run out; linear solver failures; invalid loads.
    pub fn continue_ratio(
        &self,
        tau0: f64,
        from: f64,
        v_start: &[f64],
        to: f64,
    ) -> Result<ContactSolution, ContactError> {
        self.continue_ratio_counted(tau0, from, v_start, to, &mut ArclengthBudget::unlimited())
    }

    /// [`FullSystemSolver::continue_ratio`] with every arclength step (converged or not)
    /// counted against `budget`.
    ///
    /// # Errors
    /// As [`FullSystemSolver::continue_ratio`];
    /// [`ContactError::ContinuationBudgetSpent`] when `budget` runs out first.
    pub(crate) fn continue_ratio_counted(
        &self,
        tau0: f64,
        from: f64,
        v_start: &[f64],
        to: f64,
        budget: &mut ArclengthBudget,
    ) -> Result<ContactSolution, ContactError> {
        EndLoads::new(tau0, tau0 * to).check()?;
        let model = self.model();
        let n = model.dof_count();
        let problem = |r: f64| FullSystemProblem::new(model, EndLoads::new(tau0, tau0 * r));
        let residual = |v: &[f64], r: f64| -> Result<Vec<f64>, SolverError> {
            let mut out = vec![0.0; n];
            problem(r).residual(v, &mut out)?;
            Ok(out)
        };
        let mut lu = self.linear_backend()?;
        let pattern = problem(from).pattern().clone();
        lu.analyse(&pattern)?;
        let mut values = vec![0.0; pattern.nnz()];
        // J factorised at (v, r); R_r there
        let factor = |lu: &mut BoxedLinearSolver,
                      values: &mut [f64],
                      v: &[f64],
                      r: f64|
         -> Result<Vec<f64>, ContactError> {
            problem(r).jacobian(v, values)?;
            lu.factor(values)?;
            let (a, b) = (residual(v, r + 1.0)?, residual(v, r)?);
            Ok(a.iter().zip(&b).map(|(x, y)| x - y).collect())
        };
        let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
        let b_norm = dot(&residual(&vec![0.0; n], to)?, &residual(&vec![0.0; n], to)?)
            .sqrt()
            .max(1.0);
        let tolerance = self.settings().continuation.tolerance * b_norm;
        let (mut v, mut r) = (v_start.to_vec(), from);
        // d = +1 climbing, -1 going down
        let d = if to >= from { 1.0 } else { -1.0 };
        // the first tangent: t_v = -J^{-1} R_r t_r, d t_r > 0
        let rr = factor(&mut lu, &mut values, &v, r)?;
        let mut tv: Vec<f64> = rr.iter().map(|x| -d * x).collect();
        lu.solve_in_place(&mut tv)?;
        let mut tr = d;
        let size = (dot(&tv, &tv) + 1.0).sqrt();
        tv.iter_mut().for_each(|x| *x /= size);
        tr /= size;
        // first step: a ratio step of (to - from) / 4 (ds > 0: to - from and t_r share d)
        let first = 0.25 * (to - from) / tr;
        let mut ds = first;
        // the furthest ratio along d the path reached
        let mut furthest = r;
        let mut iterations = 0;
        for _ in 0..MAX_STEPS {
            budget.spend(r, to)?;
            let xp: Vec<f64> = v.iter().zip(&tv).map(|(x, t)| x + ds * t).collect();
            let rp = r + ds * tr;
            let (mut x, mut xr) = (xp.clone(), rp);
            let mut converged = false;
            for _ in 0..CORRECTOR_ITERATIONS {
                let res = residual(&x, xr)?;
                let g = dot(
                    &tv,
                    &x.iter().zip(&xp).map(|(a, b)| a - b).collect::<Vec<_>>(),
                ) + tr * (xr - rp);
                if dot(&res, &res).sqrt() <= tolerance && g.abs() <= tolerance {
                    converged = true;
                    break;
                }
                iterations += 1;
                let rr = factor(&mut lu, &mut values, &x, xr)?;
                let mut a: Vec<f64> = res.iter().map(|y| -y).collect();
                lu.solve_in_place(&mut a)?;
                let mut b: Vec<f64> = rr.iter().map(|y| -y).collect();
                lu.solve_in_place(&mut b)?;
                let dr = -(g + dot(&tv, &a)) / (dot(&tv, &b) + tr);
                if !dr.is_finite() {
                    break;
                }
                x.iter_mut()
                    .zip(a.iter().zip(&b))
                    .for_each(|(xi, (ai, bi))| *xi += ai + dr * bi);
                xr += dr;
            }
            if !converged {
                ds *= 0.5;
                if ds.abs() < MIN_STEP * first.abs() {
                    break;
                }
                continue;
            }
            // the new tangent: [J R_r; t_old] t = e_{n+1}, oriented along the old one
            let rr = factor(&mut lu, &mut values, &x, xr)?;
            let mut b: Vec<f64> = rr.iter().map(|y| -y).collect();
            lu.solve_in_place(&mut b)?;
            // t = (b, 1) scaled so that t_old . t = 1
            let scale = dot(&tv, &b) + tr;
            let (mut nv, mut nr): (Vec<f64>, f64) = if scale.abs() > 1e-300 {
                (b.iter().map(|y| y / scale).collect(), 1.0 / scale)
            } else {
                (tv.clone(), tr)
            };
            let size = (dot(&nv, &nv) + nr * nr).sqrt();
            nv.iter_mut().for_each(|y| *y /= size);
            nr /= size;
            if d * (xr - to) >= 0.0 {
                // past the target: Newton there from the point interpolated on the chord
                let s = (to - r) / (xr - r);
                let start: Vec<f64> = v.iter().zip(&x).map(|(a, b)| a + s * (b - a)).collect();
                let mut sol = self.solve_from(EndLoads::new(tau0, tau0 * to), &start)?;
                sol.stats.newton_iterations += iterations;
                return Ok(sol);
            }
            if d * xr > d * furthest {
                furthest = xr;
            }
            (v, r, tv, tr) = (x, xr, nv, nr);
            if d * r < d * furthest - FOLD_RETURN * (to - from).abs() {
                // a limit point: the path has turned back well before its furthest ratio
                let (lower, upper) = if d > 0.0 {
                    (f64::NEG_INFINITY, furthest)
                } else {
                    (furthest, f64::INFINITY)
                };
                return Err(ContactError::NoEquilibrium {
                    ratio: to,
                    lower,
                    upper,
                });
            }
            ds *= 1.5;
        }
        Err(ContactError::NotConverged {
            iterations,
            residual: f64::NAN,
            load_factor: (r - from) / (to - from),
        })
    }
}

/// The arclength steps a sequence of continuations may take in total (the work budget of
/// [`FullSystemSolver::run_off`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ArclengthBudget {
    /// Steps taken.
    pub spent: usize,
    /// Steps allowed.
    pub max: usize,
}

impl ArclengthBudget {
    /// No limit but the per-continuation one ([`MAX_STEPS`]).
    pub fn unlimited() -> Self {
        Self {
            spent: 0,
            max: usize::MAX,
        }
    }

    /// Takes one step at ratio `reached` on the way to `target`.
    ///
    /// # Errors
    /// [`ContactError::ContinuationBudgetSpent`] when every step is spent.
    pub fn spend(&mut self, reached: f64, target: f64) -> Result<(), ContactError> {
        if self.spent >= self.max {
            return Err(ContactError::ContinuationBudgetSpent {
                steps: self.max,
                reached,
                ratio: target,
            });
        }
        self.spent += 1;
        Ok(())
    }
}
