//! One timed solve of `capstan bench work-precision` (capstan's or a peer's) and the rule by
//! which every run is repeated.

use serde::Serialize;

/// One timed solve.
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    /// `lame`, `mms`, `paper`.
    pub problem: &'static str,
    /// `fd`, `fem-q1`, `fem-q2`, `fem-qp2` ... `fem-qp10`; peers: `skfem-q1`, `skfem-q2`,
    /// `ngsolve-p1` ... `ngsolve-p8`.
    pub method: String,
    /// `lu`, `cholesky`, `gauss-seidel`, ...; peers: `scipy-superlu`, `sparsecholesky`,
    /// `umfpack`.
    pub backend: String,
    /// Threads of the run: capstan's rayon pool (element loops and faer); 1 for the peers.
    pub threads: usize,
    /// Nodes in `x2` (scikit-fem: cells around; NGSolve: triangles; `fem-qpP-corner`: elements).
    pub n2: usize,
    /// Nodes in `x3` (scikit-fem: nodes through; NGSolve: 0; `fem-qpP-corner`: layers per corner).
    pub n3: usize,
    /// Unknowns (NGSolve: all dofs of the space, element bubbles included).
    pub dofs: usize,
    /// Discretisation build (geometry, data, pattern), seconds.
    pub setup_seconds: f64,
    /// Assembly, seconds.
    pub assemble_seconds: f64,
    /// Analyse + factor + solve (or iterate), seconds.
    pub solve_seconds: f64,
    /// Data to solution, seconds.
    pub seconds: f64,
    /// Relative L2 displacement error.
    pub error: f64,
    /// Peak memory of the run, MiB.
    pub peak_mib: f64,
}

/// A series: method, backend, threads.
pub type SeriesKey = (String, String, usize);

impl Run {
    /// The series the run belongs to.
    pub fn series(&self) -> SeriesKey {
        (self.method.clone(), self.backend.clone(), self.threads)
    }
}

/// How often each run of the benchmark (capstan's and the peers' alike) is repeated: at least
/// `min` times, then until `budget_seconds` of run time have been spent or `max` runs made; the
/// fastest run (total time) is kept, with its stage split. The minimum is the least perturbed
/// estimate of the work on a shared machine: noise only ever adds time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RepeatRule {
    /// Runs at least this many times.
    pub min: usize,
    /// Runs at most this many times.
    pub max: usize,
    /// Stops repeating (after `min` runs) once the runs have taken this long in total.
    pub budget_seconds: f64,
}

/// The rule of `capstan bench work-precision`: 2 to 5 runs, about 1 s per grid.
pub const REPEAT_RULE: RepeatRule = RepeatRule {
    min: 2,
    max: 5,
    budget_seconds: 1.0,
};

impl RepeatRule {
    /// Whether another run is due after `runs` runs that took `spent` seconds in total.
    pub fn again(&self, runs: usize, spent: f64) -> bool {
        runs < self.min || (runs < self.max && spent < self.budget_seconds)
    }

    /// The fastest (least `seconds`) of the runs of `once` this rule asks for.
    ///
    /// # Errors
    /// The first error of `once`.
    pub fn fastest<E>(&self, mut once: impl FnMut() -> Result<Run, E>) -> Result<Run, E> {
        let mut best = once()?;
        let (mut runs, mut spent) = (1, best.seconds);
        while self.again(runs, spent) {
            let run = once()?;
            runs += 1;
            spent += run.seconds;
            if run.seconds < best.seconds {
                best = run;
            }
        }
        Ok(best)
    }

    /// The peer scripts' command-line arguments for the same rule.
    pub fn peer_args(&self) -> [String; 6] {
        [
            "--repeat-min".to_owned(),
            self.min.to_string(),
            "--repeat-max".to_owned(),
            self.max.to_string(),
            "--repeat-budget".to_owned(),
            self.budget_seconds.to_string(),
        ]
    }
}

/// Resets the peak resident set (Linux `clear_refs` 5); false if unavailable.
pub(super) fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// A field of `/proc/self/status` in KiB (e.g. `VmHWM:`); `None` if unavailable.
pub(super) fn status_kib(field: &str) -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    s.lines()
        .find(|l| l.starts_with(field))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse().ok())
}

/// A time cell of the tables: seconds to 4 decimals, `-` when the target was not reached.
pub(super) fn seconds_cell(t: Option<f64>) -> String {
    t.map_or_else(|| "-".to_owned(), |t| format!("{t:.4}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeat_rule_runs_twice_at_least_and_stops_at_the_budget_or_five() {
        let runs = |seconds: f64| {
            let mut n = 0;
            while REPEAT_RULE.again(n, n as f64 * seconds) {
                n += 1;
            }
            n
        };
        assert_eq!(runs(0.001), 5);
        assert_eq!(runs(0.3), 4); // 0.9 s after three runs: one more
        assert_eq!(runs(0.6), 2);
        assert_eq!(runs(3.0), 2);
    }
}
