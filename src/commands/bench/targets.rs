//! Time to reach a target error: per series, and the headline comparison of the fastest
//! capstan series with the fastest peer series at each target.

use serde::Serialize;

use super::peers::is_peer_method;
use super::run::{Run, SeriesKey};

/// The target relative errors of the comparison.
pub const TARGETS: [f64; 4] = [1e-4, 1e-6, 1e-8, 1e-10];

/// The time one series (method, backend, threads) needs for each of [`TARGETS`].
#[derive(Debug, Clone, Serialize)]
pub struct SeriesTimes {
    /// Problem.
    pub problem: &'static str,
    /// Method (`fem-q2`, `ngsolve-p4`, ...).
    pub method: String,
    /// Linear backend.
    pub backend: String,
    /// Threads.
    pub threads: usize,
    /// Seconds to reach each of [`TARGETS`] (the contact series: each of
    /// [`super::contact::CONTACT_TARGETS`]); `None` where the series never gets there.
    pub seconds: Vec<Option<f64>>,
}

/// The fastest capstan series with one thread count against the fastest peer series at one
/// target error.
#[derive(Debug, Clone, Serialize)]
pub struct Headline {
    /// Problem.
    pub problem: &'static str,
    /// Target relative error.
    pub target_error: f64,
    /// Threads of the capstan series (peers run with one).
    pub threads: usize,
    /// Fastest capstan series at the target, `method/backend`; `None` if none gets there.
    pub capstan: Option<String>,
    /// Its time, seconds.
    pub capstan_seconds: Option<f64>,
    /// Fastest peer series at the target.
    pub peer: Option<String>,
    /// Its time, seconds.
    pub peer_seconds: Option<f64>,
    /// `peer_seconds / capstan_seconds`: above 1, capstan is faster.
    pub ratio: Option<f64>,
}

/// Time to reach `target` along one series: log-log interpolation between the runs that
/// bracket it (in order of decreasing error); `None` if the series never gets there.
///
/// # Math
/// ```text
/// s = (ln target - ln e0) / (ln e1 - ln e0),   t = exp(ln t0 + s (ln t1 - ln t0))
/// ```
/// exact for a power law `e = C t^-k` between the two runs.
pub fn time_to_error(runs: &[&Run], target: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = runs.iter().map(|r| (r.error, r.seconds)).collect();
    pts.sort_by(|a, b| b.0.total_cmp(&a.0)); // decreasing error
    pts.windows(2).find_map(|w| {
        let ((e0, t0), (e1, t1)) = (w[0], w[1]);
        (e0 >= target && e1 <= target).then(|| {
            if e0 == e1 {
                return t0.min(t1);
            }
            let s = (target.ln() - e0.ln()) / (e1.ln() - e0.ln());
            (t0.ln() + s * (t1.ln() - t0.ln())).exp()
        })
    })
}

/// The series of `problem` in the order of their first run.
pub fn series_names(runs: &[Run], problem: &str) -> Vec<SeriesKey> {
    let mut names = vec![];
    for r in runs.iter().filter(|r| r.problem == problem) {
        let key = r.series();
        if !names.contains(&key) {
            names.push(key);
        }
    }
    names
}

/// The runs of one series.
pub fn series_runs<'a>(runs: &'a [Run], problem: &str, key: &SeriesKey) -> Vec<&'a Run> {
    runs.iter()
        .filter(|r| r.problem == problem && &r.series() == key)
        .collect()
}

/// The time to each of [`TARGETS`] of every series of every problem.
pub fn series_times(runs: &[Run], problems: &[&'static str]) -> Vec<SeriesTimes> {
    series_times_at(runs, problems, &TARGETS)
}

/// The time to each of `targets` of every series of every problem (`seconds` in the order of
/// `targets`).
pub fn series_times_at(
    runs: &[Run],
    problems: &[&'static str],
    targets: &[f64],
) -> Vec<SeriesTimes> {
    let mut out = vec![];
    for &problem in problems {
        for key in series_names(runs, problem) {
            let series = series_runs(runs, problem, &key);
            let (method, backend, threads) = key;
            out.push(SeriesTimes {
                problem,
                method,
                backend,
                threads,
                seconds: targets.iter().map(|&t| time_to_error(&series, t)).collect(),
            });
        }
    }
    out
}

/// For each problem, target and capstan thread count: the fastest capstan series and the
/// fastest peer series; a row wherever either reaches the target.
pub fn headlines(times: &[SeriesTimes]) -> Vec<Headline> {
    let mut out = vec![];
    let mut problems: Vec<&'static str> = times.iter().map(|s| s.problem).collect();
    problems.dedup();
    let mut threads: Vec<usize> = times
        .iter()
        .filter(|s| !is_peer_method(&s.method))
        .map(|s| s.threads)
        .collect();
    threads.sort_unstable();
    threads.dedup();
    let fastest = |problem: &str, k: usize, keep: &dyn Fn(&SeriesTimes) -> bool| {
        times
            .iter()
            .filter(|s| s.problem == problem && keep(s))
            .filter_map(|s| s.seconds[k].map(|t| (format!("{}/{}", s.method, s.backend), t)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    };
    for problem in problems {
        for (k, &target) in TARGETS.iter().enumerate() {
            let peer = fastest(problem, k, &|s| is_peer_method(&s.method));
            for &n in &threads {
                let capstan = fastest(problem, k, &|s| {
                    !is_peer_method(&s.method) && s.threads == n
                });
                if capstan.is_none() && peer.is_none() {
                    continue;
                }
                out.push(Headline {
                    problem,
                    target_error: target,
                    threads: n,
                    ratio: capstan.as_ref().zip(peer.as_ref()).map(|(c, p)| p.1 / c.1),
                    capstan_seconds: capstan.as_ref().map(|c| c.1),
                    capstan: capstan.map(|c| c.0),
                    peer_seconds: peer.as_ref().map(|p| p.1),
                    peer: peer.clone().map(|p| p.0),
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(method: &str, threads: usize, error: f64, seconds: f64) -> Run {
        Run {
            problem: "lame",
            method: method.into(),
            backend: "cholesky".into(),
            threads,
            n2: 0,
            n3: 0,
            dofs: 0,
            setup_seconds: 0.0,
            assemble_seconds: 0.0,
            solve_seconds: 0.0,
            seconds,
            error,
            peak_mib: 0.0,
        }
    }

    /// One-thread runs of `method` at `times` whose errors follow `error = c t^-k`.
    fn power_law_runs(method: &str, (c, k): (f64, f64), times: &[f64]) -> Vec<Run> {
        times
            .iter()
            .map(|&t| run(method, 1, c * t.powf(-k), t))
            .collect()
    }

    #[test]
    fn time_to_error_interpolates_log_log_and_refuses_to_extrapolate() {
        // error = 1e-7 t^-2: 1e-3, 1e-5, 1e-7 at 0.01, 0.1, 1 s; 1e-6 lies half way (in
        // logs) between 0.1 s and 1 s
        let runs = power_law_runs("fem-q2", (1e-7, 2.0), &[0.01, 0.1, 1.0]);
        let refs: Vec<&Run> = runs.iter().collect();
        let t = time_to_error(&refs, 1e-6).unwrap();
        assert!((t - 10f64.powf(-0.5)).abs() < 1e-12);
        assert!(time_to_error(&refs, 1e-8).is_none());
        assert!(time_to_error(&refs, 1e-2).is_none());
    }

    #[test]
    fn time_to_error_is_exact_on_a_power_law_at_every_target() {
        // error = C t^-k with C = 1e-6, k = 1.7 (0.13 at 1 ms, 7.9e-12 at 1000 s), runs at
        // irregular times, given out of order
        let (c, k) = (1e-6, 1.7);
        let times = [0.001, 0.02, 0.0071, 0.4, 13.0, 90.0, 1000.0, 0.09];
        let runs = power_law_runs("ngsolve-p4", (c, k), &times);
        let refs: Vec<&Run> = runs.iter().collect();
        for target in TARGETS {
            let expected = (c / target).powf(1.0 / k); // t = (C / e)^(1/k)
            let t = time_to_error(&refs, target).unwrap();
            // logs and exponentials of O(10) numbers: round-off only
            assert!(
                (t / expected - 1.0).abs() < 1e-12,
                "{target}: {t} vs {expected}"
            );
        }
    }

    #[test]
    fn headlines_pair_each_thread_count_with_the_fastest_peer() {
        let runs = [
            run("fem-q2", 1, 1e-3, 0.02),
            run("fem-q2", 1, 1e-7, 2.0),
            run("fem-q2", 2, 1e-3, 0.01),
            run("fem-q2", 2, 1e-7, 1.0),
            run("ngsolve-p4", 1, 1e-3, 0.1),
            run("ngsolve-p4", 1, 1e-11, 1.0),
            run("skfem-q2", 1, 1e-3, 0.5),
            run("skfem-q2", 1, 1e-5, 5.0),
        ];
        let times = series_times(&runs, &["lame"]);
        assert_eq!(times.len(), 4);
        let h = headlines(&times);
        // 1e-4 and 1e-6 for both thread counts; 1e-8 and 1e-10 reached by the peer only
        assert_eq!(h.len(), 8);
        let at = |target: f64, threads: usize| {
            h.iter()
                .find(|x| x.target_error == target && x.threads == threads)
                .unwrap()
        };
        let one = at(1e-4, 1);
        assert_eq!(one.peer.as_deref(), Some("ngsolve-p4/cholesky"));
        // capstan 1 thread: 0.02 * 100^(1/4); ngsolve: 0.1 * 10^(1/8)
        let expected = 0.1 * 10f64.powf(0.125) / (0.02 * 100f64.powf(0.25));
        assert!((one.ratio.unwrap() - expected).abs() < 1e-12);
        assert!((at(1e-4, 2).ratio.unwrap() - 2.0 * expected).abs() < 1e-12);
        assert!(at(1e-8, 2).capstan.is_none() && at(1e-8, 2).ratio.is_none());
        assert!(at(1e-10, 1).peer_seconds.is_some());
    }
}
