//! When the KSP of a Newton step may stop early (Eisenstat–Walker forcing) and when GAMG's
//! hierarchy may be kept from an earlier Jacobian (preconditioner lagging): the bookkeeping of
//! [`crate::PetscSolver`], free of PETSc so that it is tested without it.

use capstan_solvers::{EisenstatWalker, SolverError};

/// The PETSc option switching the Eisenstat–Walker forcing on or off
/// (`solver.petsc_options = "-capstan_forcing true"`; default false).
pub const FORCING_OPTION: &str = "-capstan_forcing";

/// The PETSc option of the loosest forcing term `eta_max` in `(0, 1)` (default 0.9, also the
/// first step's): a hard first Newton step may need it tighter.
pub const FORCING_ETA_MAX_OPTION: &str = "-capstan_forcing_eta_max";

/// The PETSc option of the preconditioner lagging: `g >= 1` keeps GAMG's hierarchy across
/// Jacobians until a solve needs more than `g` times the Krylov iterations per decade of the
/// solve that built it; `0` rebuilds it at every Jacobian (PETSc's own behaviour).
pub const PC_LAG_OPTION: &str = "-capstan_pc_lag_growth";

/// The forcing and lagging state of one solver, across the Newton steps it serves.
///
/// # Math
/// Forcing (the first solve after each new matrix: the Newton direction `J_k d = -r_k`, whose
/// right-hand side norm is the Newton residual `|r_k|_2`):
/// ```text
/// eta_k = EisenstatWalker { gamma 0.9, alpha 2, eta_max (0.9), eta_min rtol }.next(|r_k|, ...)
/// KSP relative tolerance of step k = max(eta_k, rtol)   (rtol: -ksp_rtol, the floor)
/// ```
/// every further solve with the same matrix (the stuck start's unit loads) uses `rtol`.
/// Lagging (growth `g`): a solve of `m` iterations that reduced the residual from `r_0` to
/// `r_m` costs `c = m / log10(r_0 / r_m)` iterations a decade; the solve right after a
/// rebuild sets `c_0`; a later matrix keeps the hierarchy while the last solve had
/// `c <= g c_0`, and the next matrix rebuilds it otherwise (or when a solve failed).
#[derive(Debug, Clone, PartialEq)]
pub struct StepPolicy {
    forcing: Option<EisenstatWalker>,
    lag_growth: f64,
    /// `(|r_{k-1}|, eta_{k-1})` of the previous Newton direction.
    history: Option<(f64, f64)>,
    /// Iterations a decade of the solve with a freshly built preconditioner.
    fresh_rate: Option<f64>,
    /// Whether the preconditioner of the current matrix was built for it.
    fresh: bool,
    rebuild: bool,
    solves_since_factor: usize,
}

impl StepPolicy {
    /// A policy: forcing with the loosest term `eta_max` (`None`: off), lagging with growth
    /// `lag_growth` (0: off).
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming `solver.petsc_options -capstan_pc_lag_growth`
    /// unless `lag_growth` is 0 or in `[1, inf)`, or `-capstan_forcing_eta_max` unless
    /// `eta_max` is in `(0, 1)`.
    pub fn new(forcing: Option<f64>, lag_growth: f64) -> Result<Self, SolverError> {
        if let Some(eta_max) = forcing
            && !(eta_max > 0.0 && eta_max < 1.0)
        {
            return Err(SolverError::InvalidParameter {
                field: "solver.petsc_options -capstan_forcing_eta_max",
                value: eta_max,
                allowed: "(0, 1)",
            });
        }
        if !(lag_growth == 0.0 || (lag_growth >= 1.0 && lag_growth.is_finite())) {
            return Err(SolverError::InvalidParameter {
                field: "solver.petsc_options -capstan_pc_lag_growth",
                value: lag_growth,
                allowed: "0 (off) or [1, inf)",
            });
        }
        Ok(Self {
            forcing: forcing.map(|eta_max| EisenstatWalker {
                eta_max,
                ..EisenstatWalker::default()
            }),
            lag_growth,
            ..Self::off()
        })
    }

    /// Neither forcing nor lagging (every solve to `-ksp_rtol`, every matrix its own
    /// preconditioner).
    pub fn off() -> Self {
        Self {
            forcing: None,
            lag_growth: 0.0,
            history: None,
            fresh_rate: None,
            fresh: false,
            rebuild: true,
            solves_since_factor: 0,
        }
    }

    /// Forgets every earlier step (a new pattern: the next matrix builds its preconditioner).
    pub fn reset(&mut self) {
        self.history = None;
        self.fresh_rate = None;
        self.fresh = false;
        self.rebuild = true;
        self.solves_since_factor = 0;
    }

    /// A new matrix: whether its solves keep the preconditioner built for an earlier one.
    pub fn reuse_for_new_matrix(&mut self) -> bool {
        self.solves_since_factor = 0;
        let reuse = self.lag_growth > 0.0 && !self.rebuild && self.fresh_rate.is_some();
        self.fresh = !reuse;
        self.rebuild = false;
        reuse
    }

    /// Whether the current matrix's preconditioner was built for it.
    pub fn fresh(&self) -> bool {
        self.fresh
    }

    /// The preconditioner is rebuilt for the current matrix (after a failed solve with a kept
    /// one).
    pub fn rebuilt(&mut self) {
        self.fresh = true;
    }

    /// The relative tolerance of the next solve, whose right-hand side has norm `rhs_norm`,
    /// for the floor `rtol` (`-ksp_rtol`).
    pub fn tolerance(&mut self, rhs_norm: f64, rtol: f64) -> f64 {
        self.solves_since_factor += 1;
        let Some(ew) = self.forcing else {
            return rtol;
        };
        if self.solves_since_factor > 1 || !(rhs_norm > 0.0 && rhs_norm.is_finite()) {
            return rtol;
        }
        let ew = EisenstatWalker {
            eta_min: rtol.min(ew.eta_max),
            ..ew
        };
        let eta = ew.next(rhs_norm, self.history, 0.0).max(rtol);
        self.history = Some((rhs_norm, eta));
        eta
    }

    /// Records a finished solve: `iterations` Krylov iterations reduced the monitored residual
    /// by the factor `reduction` (final over initial); `failed` when KSP did not converge.
    pub fn solved(&mut self, iterations: usize, reduction: f64, failed: bool) {
        if failed {
            self.rebuild = true;
            return;
        }
        let decades = if reduction > 0.0 && reduction < 1.0 {
            -reduction.log10()
        } else {
            0.0
        };
        if decades < 1e-3 {
            return; // nothing to learn from (a zero right-hand side, no iteration)
        }
        let rate = iterations as f64 / decades;
        if self.fresh {
            self.fresh_rate = Some(rate);
        } else if let Some(c0) = self.fresh_rate
            && rate > self.lag_growth * c0.max(1.0)
        {
            self.rebuild = true;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_growth_is_refused_naming_the_option() {
        for g in [-1.0, 0.5, f64::NAN, f64::INFINITY] {
            let e = StepPolicy::new(Some(0.9), g).unwrap_err().to_string();
            assert!(e.contains("-capstan_pc_lag_growth"), "{e}");
        }
        assert!(StepPolicy::new(Some(0.9), 0.0).is_ok());
        for eta in [0.0, 1.0, -0.1, f64::NAN] {
            let e = StepPolicy::new(Some(eta), 0.0).unwrap_err().to_string();
            assert!(e.contains("-capstan_forcing_eta_max"), "{e}");
        }
        let mut tight = StepPolicy::new(Some(0.1), 0.0).unwrap();
        tight.reuse_for_new_matrix();
        assert_eq!(tight.tolerance(1.0, 1e-8), 0.1);
        assert!(StepPolicy::new(None, 1.0).is_ok());
    }

    #[test]
    fn forcing_follows_eisenstat_walker_with_rtol_as_floor() {
        let mut p = StepPolicy::new(Some(0.9), 0.0).unwrap();
        assert!(!p.reuse_for_new_matrix());
        assert_eq!(p.tolerance(1.0, 1e-8), 0.9); // eta_0 = eta_max
        // a second solve with the same matrix is not a Newton direction: the floor
        assert_eq!(p.tolerance(0.5, 1e-8), 1e-8);
        p.reuse_for_new_matrix();
        // |r| fell 10x: gamma (0.1)^2 = 9e-3, but safeguard 1 (0.9 * 0.9^2 = 0.729 > 0.1)
        let eta = p.tolerance(0.1, 1e-8);
        assert!((eta - 0.9 * 0.81).abs() < 1e-15, "{eta}");
        p.reuse_for_new_matrix();
        // |r| fell 1e3 more: 0.9e-6, safeguard 0.9 eta^2 = 0.478 > 0.1 still
        let eta2 = p.tolerance(1e-4, 1e-8);
        assert!((eta2 - 0.9 * eta * eta).abs() < 1e-15, "{eta2}");
        p.reuse_for_new_matrix();
        let eta3 = p.tolerance(1e-12, 1e-8);
        // 0.9 (1e-8)^2 below the floor; safeguard 0.9 * 0.478^2 = 0.206 > 0.1 keeps it
        assert!((eta3 - 0.9 * eta2 * eta2).abs() < 1e-15, "{eta3}");
        p.reuse_for_new_matrix();
        let eta4 = p.tolerance(1e-20, 1e-8);
        // safeguard 0.9 * 0.206^2 = 0.038 < 0.1: choice 2 alone, floored at rtol
        assert_eq!(eta4, 1e-8);
        // without forcing: always rtol
        let mut q = StepPolicy::new(None, 0.0).unwrap();
        q.reuse_for_new_matrix();
        assert_eq!(q.tolerance(1.0, 1e-6), 1e-6);
    }

    #[test]
    fn lagging_keeps_the_hierarchy_until_the_rate_per_decade_grows() {
        let mut p = StepPolicy::new(None, 2.0).unwrap();
        // first matrix: built
        assert!(!p.reuse_for_new_matrix());
        assert!(p.fresh());
        p.tolerance(1.0, 1e-8);
        p.solved(40, 1e-8, false); // 5 a decade
        // next matrices: kept while <= 10 a decade
        assert!(p.reuse_for_new_matrix());
        assert!(!p.fresh());
        p.solved(80, 1e-8, false); // 10 a decade: still kept
        assert!(p.reuse_for_new_matrix());
        p.solved(81, 1e-8, false); // 10.1 a decade: rebuild at the next matrix
        assert!(!p.reuse_for_new_matrix());
        assert!(p.fresh());
        p.solved(48, 1e-8, false); // the new baseline: 6 a decade
        assert!(p.reuse_for_new_matrix());
        p.solved(100, 1e-8, false); // 12.5 <= 12? no: rebuild
        assert!(!p.reuse_for_new_matrix());
        // a failed solve always rebuilds
        p.solved(5, 1e-8, false);
        assert!(p.reuse_for_new_matrix());
        p.solved(2000, 0.5, true);
        assert!(!p.reuse_for_new_matrix());
        // a solve that reduced nothing teaches nothing
        p.solved(0, 1.0, false);
        assert!(p.reuse_for_new_matrix());
        // lagging off: never kept; reset: rebuilt
        let mut off = StepPolicy::new(Some(0.9), 0.0).unwrap();
        off.reuse_for_new_matrix();
        off.solved(10, 1e-8, false);
        assert!(!off.reuse_for_new_matrix());
        p.reset();
        assert!(!p.reuse_for_new_matrix());
    }
}
