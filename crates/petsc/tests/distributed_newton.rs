//! `DistributedNewton` over `PetscDistribution` and `PetscSolver` on 1, 2 and 4 ranks: a
//! nonlinear two-point problem held as each rank's rows (its two ghosts fetched per residual
//! and Jacobian), solved to the serial sparse-LU Newton's answer; a non-finite residual on one
//! rank only stops every rank with the same typed error and global index (at the start, and
//! in a line search). The test re-runs its own binary under `mpirun -n K` (skipped with a
//! note when `mpirun` is not installed); each rank checks its answers and exits non-zero on a
//! mismatch.
#![cfg(feature = "petsc")]

use std::cell::Cell;
use std::ops::Range;
use std::process::Command;

use capstan_petsc::{PetscDistribution, PetscSolver, Session};
use capstan_solvers::row_distribution::{RowDistribution, owned_blocks};
use capstan_solvers::{
    DistributedNewton, Jacobian, LinearBackend, Newton, NewtonParams, NonlinearSolver,
    OwnedRowsProblem, Residual, SilentObserver, SolverError, SparsityPattern,
};

const CHILD: &str = "CAPSTAN_PETSC_DISTRIBUTED_NEWTON_CHILD";
const TEST: &str = "distributed_newton_gives_the_serial_answer_on_1_2_4_ranks";
const N: usize = 203;

/// `R_i(u) = (2 u_i - u_{i-1} - u_{i+1}) / h^2 + u_i^3 - f_i` (zero ends), `f` from the
/// root `u_i = sin(pi x_i) + x_i`; a NaN at global row `nan_row` from the `nan_from`-th
/// residual evaluation on (counted per rank; every rank evaluates in step).
struct TwoPoint<'d> {
    d: Option<&'d PetscDistribution>,
    rows: Range<usize>,
    pattern: SparsityPattern,
    f: Vec<f64>,
    nan_row: Option<usize>,
    nan_from: usize,
    evaluations: Cell<usize>,
}

fn h() -> f64 {
    1.0 / (N + 1) as f64
}

fn exact(i: usize) -> f64 {
    let x = (i + 1) as f64 * h();
    (std::f64::consts::PI * x).sin() + x
}

impl<'d> TwoPoint<'d> {
    fn new(d: Option<&'d PetscDistribution>) -> Self {
        let rows = d.map_or(0..N, |d| owned_blocks(N, 1, d.rank(), d.size()));
        let mut entries = Vec::new();
        for i in rows.clone() {
            for j in i.saturating_sub(1)..(i + 2).min(N) {
                entries.push((i, j));
            }
        }
        let (pattern, _) = SparsityPattern::from_entries(N, N, &entries).unwrap();
        let at = |i: Option<usize>| i.filter(|&i| i < N).map_or(0.0, exact);
        let f = rows
            .clone()
            .map(|i| {
                let lap = (2.0 * exact(i) - at(i.checked_sub(1)) - at(Some(i + 1))) / (h() * h());
                lap + exact(i).powi(3)
            })
            .collect();
        Self {
            d,
            rows,
            pattern,
            f,
            nan_row: None,
            nan_from: 0,
            evaluations: Cell::new(0),
        }
    }

    /// `u` at this rank's rows and its two neighbours (fetched from their owners).
    fn with_ghosts(&self, u: &[f64]) -> Result<(f64, f64), SolverError> {
        let (first, end) = (self.rows.start, self.rows.end);
        let want: Vec<usize> = [first.checked_sub(1), Some(end).filter(|&e| e < N)]
            .into_iter()
            .flatten()
            .filter(|_| !self.rows.is_empty())
            .collect();
        let mut got = vec![0.0; want.len()];
        if let Some(d) = self.d {
            d.fetch(u, N, 1, &want, &mut got)?;
        }
        let left = want
            .iter()
            .position(|&i| i + 1 == first)
            .map_or(0.0, |k| got[k]);
        let right = want.iter().position(|&i| i == end).map_or(0.0, |k| got[k]);
        Ok((left, right))
    }
}

impl Residual<f64> for TwoPoint<'_> {
    type Error = SolverError;
    fn residual(&self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
        self.residual_owned(u, r)
    }
}

impl Jacobian<f64> for TwoPoint<'_> {
    fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
    fn jacobian(&self, u: &[f64], values: &mut [f64]) -> Result<(), SolverError> {
        self.jacobian_owned(u, values)
    }
}

impl OwnedRowsProblem for TwoPoint<'_> {
    fn distribution(&self) -> &dyn RowDistribution {
        self.d.expect("a distributed problem")
    }
    fn rows(&self) -> Range<usize> {
        self.rows.clone()
    }
    fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
    fn residual_owned(&self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
        let (left, right) = self.with_ghosts(u)?;
        let h2 = h() * h();
        let m = u.len();
        for k in 0..m {
            let l = if k > 0 { u[k - 1] } else { left };
            let rr = if k + 1 < m { u[k + 1] } else { right };
            r[k] = (2.0 * u[k] - l - rr) / h2 + u[k].powi(3) - self.f[k];
        }
        let count = self.evaluations.get() + 1;
        self.evaluations.set(count);
        if let Some(row) = self.nan_row
            && count >= self.nan_from
            && self.rows.contains(&row)
        {
            r[row - self.rows.start] = f64::NAN;
        }
        Ok(())
    }
    fn jacobian_owned(&self, u: &[f64], values: &mut [f64]) -> Result<(), SolverError> {
        let h2 = h() * h();
        for ((i, j), slot) in self.pattern.entries().zip(0..) {
            values[slot] = if i == j {
                2.0 / h2 + 3.0 * u[i - self.rows.start].powi(2)
            } else {
                -1.0 / h2
            };
        }
        Ok(())
    }
}

fn params() -> NewtonParams {
    NewtonParams {
        absolute_tolerance: 1e-9,
        relative_tolerance: 0.0,
        ..NewtonParams::default()
    }
}

/// What one rank checks (every rank runs the same collective calls in the same order).
fn rank_checks() {
    let session =
        Session::start("-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps").unwrap();
    let d = PetscDistribution::new(&session).unwrap();
    let (rank, size) = (d.rank(), d.size());

    // the serial answer: sparse LU on the whole problem (no communication)
    let serial_problem = TwoPoint::new(None);
    let lu = LinearBackend::LU.build(&Default::default(), &()).unwrap();
    let mut serial = vec![0.0; N];
    Newton::with_linear_solver(params(), lu)
        .unwrap()
        .solve(&serial_problem, &mut serial, &mut SilentObserver)
        .unwrap();

    let problem = TwoPoint::new(Some(&d));
    let rows = problem.rows();
    let mut u = vec![0.0; rows.len()];
    let report = DistributedNewton::new(params(), Box::new(PetscSolver::new().unwrap()))
        .unwrap()
        .solve(&problem, &mut u, &mut SilentObserver)
        .unwrap();
    let scale = serial.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (k, i) in rows.clone().enumerate() {
        assert!(
            (u[k] - serial[i]).abs() <= 1e-10 * scale,
            "row {i} on rank {rank} of {size}: {} against {}",
            u[k],
            serial[i]
        );
    }
    // the discrete solution is within O(h^2) of the root it was made from
    assert!((serial[N / 2] - exact(N / 2)).abs() < 1e-3);
    // every rank took the same decisions: the same iterations and residuals
    let first = report.residuals[0];
    assert_eq!(
        d.max(report.iterations as f64).unwrap(),
        report.iterations as f64
    );
    assert_eq!(d.max(first).unwrap(), first);
    assert!(report.iterations >= 2 && report.residuals.last().unwrap() <= &1e-9);

    // a NaN on the last rank's first row only: the same typed error on every rank
    let bad_row = owned_blocks(N, 1, size - 1, size).start;
    // (from the first evaluation: at the start; from the third: in a line search)
    for from in [1, 3] {
        let mut problem = TwoPoint::new(Some(&d));
        problem.nan_row = Some(bad_row);
        problem.nan_from = from;
        let mut u = vec![0.0; rows.len()];
        let e = DistributedNewton::new(params(), Box::new(PetscSolver::new().unwrap()))
            .unwrap()
            .solve(&problem, &mut u, &mut SilentObserver)
            .unwrap_err();
        let SolverError::NonFinite {
            quantity: "residual",
            index,
            iteration: Some(iteration),
        } = e
        else {
            panic!("NaN from evaluation {from} on rank {rank} of {size}: {e:?}");
        };
        assert_eq!(index, bad_row, "rank {rank} of {size}");
        assert_eq!(
            iteration == 0,
            from == 1,
            "rank {rank} of {size}: {iteration}"
        );
        assert_eq!(d.max(iteration as f64).unwrap(), iteration as f64);
        assert_eq!(d.max(-(iteration as f64)).unwrap(), -(iteration as f64));
    }
    drop(d);
    drop(session);
}

#[test]
fn distributed_newton_gives_the_serial_answer_on_1_2_4_ranks() {
    if std::env::var_os(CHILD).is_some() {
        rank_checks();
        return;
    }
    if Command::new("mpirun").arg("--version").output().is_err() {
        eprintln!("SKIP: mpirun not installed");
        return;
    }
    let me = std::env::current_exe().unwrap();
    for ranks in [1, 2, 4] {
        let out = Command::new("mpirun")
            .args([
                "--allow-run-as-root",
                "--oversubscribe",
                "-n",
                &ranks.to_string(),
            ])
            .arg(&me)
            .args(["--exact", TEST, "--nocapture", "--test-threads", "1"])
            .env(CHILD, "1")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{ranks} ranks: {}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            String::from_utf8_lossy(&out.stdout).contains("1 passed"),
            "{ranks} ranks"
        );
    }
}
