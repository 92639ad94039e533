//! Convergence studies: grids, errors, observed orders, and the list of registered studies; the
//! peak memory the benchmarks report.

use crate::error::ElasticityError;

/// Grid size of one refinement level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct GridLevel {
    /// Nodes in `x2`.
    pub n2: usize,
    /// Nodes in `x3`.
    pub n3: usize,
}

/// The errors on one grid.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StudyPoint {
    /// The grid.
    pub level: GridLevel,
    /// Mesh size used for the order (`dx3`; `dx2` is refined in proportion).
    pub h: f64,
    /// Max-norm error.
    pub max_error: f64,
    /// L2-norm (RMS) error.
    pub l2_error: f64,
}

/// The default [`Study::order_tolerance`]: an observed L2 order at least `expected - 0.3`.
pub const DEFAULT_ORDER_TOLERANCE: f64 = 0.3;

/// A convergence study: a problem with a known solution, solved on a sequence of grids.
pub trait Study {
    /// Name of the study.
    fn name(&self) -> String;
    /// Geometry description.
    fn geometry(&self) -> String;
    /// The discretisation (`"fd"`, `"fem-q1"`, `"fem-q2"`).
    fn discretisation(&self) -> &'static str;
    /// The grids, coarsest first.
    fn levels(&self) -> Vec<GridLevel>;
    /// The order of convergence of the L2 error the method must show on this problem:
    /// `p + 1` for elements of order `p` (Q1: 2, Q2: 3), 2 for the second-order finite
    /// differences. [`Study::run`] compares the observed order with it.
    fn expected_order(&self) -> f64;
    /// How far the observed L2 order may fall below [`Study::expected_order`] before the study
    /// counts as missed (pre-asymptotic coarse grids, round-off on the finest):
    /// [`DEFAULT_ORDER_TOLERANCE`] unless a study says otherwise. Superconvergence (an order
    /// above the expected one) is never a miss.
    fn order_tolerance(&self) -> f64 {
        DEFAULT_ORDER_TOLERANCE
    }
    /// Solves on one grid and measures the errors.
    ///
    /// # Errors
    /// Any error of building or solving the problem.
    fn run_level(&self, level: GridLevel) -> Result<StudyPoint, ElasticityError>;

    /// Runs all levels (the three coarsest with `quick`) and computes the observed orders.
    ///
    /// # Errors
    /// See [`Study::run_level`].
    fn run(&self, quick: bool) -> Result<StudyReport, ElasticityError> {
        let mut levels = self.levels();
        if quick {
            levels.truncate(3);
        }
        let points = levels
            .into_iter()
            .map(|l| self.run_level(l))
            .collect::<Result<Vec<_>, _>>()?;
        let order = |f: fn(&StudyPoint) -> f64| {
            observed_order(&points.iter().map(|p| (p.h, f(p))).collect::<Vec<_>>())
        };
        let order_l2 = order(|p| p.l2_error);
        let (expected_order, order_tolerance) = (self.expected_order(), self.order_tolerance());
        Ok(StudyReport {
            name: self.name(),
            discretisation: self.discretisation(),
            geometry: self.geometry(),
            order_max: order(|p| p.max_error),
            order_l2,
            expected_order,
            order_tolerance,
            meets_expected_order: order_l2 >= expected_order - order_tolerance,
            points,
        })
    }
}

/// The result of a study.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StudyReport {
    /// Study name.
    pub name: String,
    /// Discretisation.
    pub discretisation: &'static str,
    /// Geometry.
    pub geometry: String,
    /// Errors per grid.
    pub points: Vec<StudyPoint>,
    /// Observed order in the max norm.
    pub order_max: f64,
    /// Observed order in the L2 norm.
    pub order_l2: f64,
    /// The L2 order the method must show ([`Study::expected_order`]).
    pub expected_order: f64,
    /// How far below `expected_order` the observed L2 order may fall ([`Study::order_tolerance`]).
    pub order_tolerance: f64,
    /// `order_l2 >= expected_order - order_tolerance` (false also when the order is NaN).
    pub meets_expected_order: bool,
}

impl StudyReport {
    /// A plain-text table.
    pub fn table(&self) -> String {
        let mut s = format!(
            "{} [{}] on {}\n{:>6} {:>6} {:>10} {:>12} {:>12}\n",
            self.name, self.discretisation, self.geometry, "n2", "n3", "h", "max error", "L2 error"
        );
        for p in &self.points {
            s += &format!(
                "{:>6} {:>6} {:>10.4e} {:>12.4e} {:>12.4e}\n",
                p.level.n2, p.level.n3, p.h, p.max_error, p.l2_error
            );
        }
        s += &format!(
            "observed order: max {:.3}, L2 {:.3} (expected L2 {} - {}: {})\n",
            self.order_max,
            self.order_l2,
            self.expected_order,
            self.order_tolerance,
            if self.meets_expected_order {
                "ok"
            } else {
                "MISSED"
            }
        );
        s
    }
}

/// The process's peak resident set (Linux `VmHWM`) in MiB; NaN where `/proc/self/status` does
/// not tell.
pub fn peak_memory_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|k| k.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kib| kib / 1024.0)
}

/// Least-squares slope of `ln(error)` against `ln(h)`.
///
/// # Example
/// ```
/// use capstan_elasticity::verification::observed_order;
/// let p = observed_order(&[(0.1, 3e-2), (0.05, 7.5e-3), (0.025, 1.875e-3)]);
/// assert!((p - 2.0).abs() < 1e-12);
/// ```
pub fn observed_order(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let xs: Vec<f64> = points.iter().map(|p| p.0.ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}
