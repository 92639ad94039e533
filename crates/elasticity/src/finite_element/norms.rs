//! Error norms of a discrete displacement against an exact one, element by element for any
//! tensor-product Lagrange discretisation ([`super::HighOrderNavier::displacement_errors`], [`super::CornerRefinedNavier::displacement_errors`]).

use capstan_geometry::ShellPoint;
use rayon::prelude::*;

use crate::error::ElasticityError;
use crate::plane_problem::PlaneProblem;
use crate::shell_geometry::ShellGeometry;

/// Errors of a discrete displacement against an exact one.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DisplacementErrors {
    /// Max over the nodes of `|U_h - U|` (Cartesian displacement error).
    pub max: f64,
    /// RMS over the parameter rectangle, `sqrt(int |U_h - U|^2 dx2 dx3 / area)` (the
    /// verification norm of the finite differences, integrated exactly instead of by the
    /// nodal trapezoid rule).
    pub rms: f64,
    /// Physical L2 norm `sqrt(int |U_h - U|^2 dA)` (per unit `x1`, `dA = sqrt(g) dx2 dx3`).
    pub l2: f64,
    /// `sqrt(int |U|^2 dA)`, for relative errors.
    pub l2_exact: f64,
}

/// The map of one element from the reference square `[-1, 1]^2`: `(xi, eta) -> ((x2, x3),
/// det J)`, the parameters and the Jacobian determinant there.
pub(crate) type ElementMap<'a> = Box<dyn Fn([f64; 2]) -> ([f64; 2], f64) + 'a>;

/// A tensor-product Lagrange discretisation element by element (`np x np` nodes per element
/// on any element map: rectangles of the tensor grid, quadrilaterals of the corner mesh), for
/// [`displacement_errors`].
pub(crate) struct LagrangeElements<'a> {
    /// Number of elements.
    pub count: usize,
    /// Gauss points and weights on `[-1, 1]`.
    pub rule: (&'a [f64], &'a [f64]),
    /// The 1-D shape functions at Gauss point `i`: `basis[i][a]`, `a < np`.
    pub basis: &'a [Vec<f64>],
    /// The `np x np` node numbers (index `a2 np + a3`) and the map of element `e`.
    #[allow(clippy::type_complexity)] // one closure type, read in one place
    pub element: &'a (dyn Fn(usize) -> (Vec<usize>, ElementMap<'a>) + Sync),
}

/// The error norms of the discrete displacement `v = [v^2, v^3]` (per node `k <
/// node_count`, at `position(k)` in `problem`'s chart) against `exact`: the max over the
/// nodes of `|U_h - U|`, and by the Gauss rule of `elements` over every element
/// ```text
/// rms^2 = int |U_h - U|^2 dx2 dx3 / area,  l2^2 = int |U_h - U|^2 sqrt(g) dx2 dx3,
/// l2_exact^2 = int |U|^2 sqrt(g) dx2 dx3,  |e|^2 = g_22 e2 e2 + 2 g_23 e2 e3 + g_33 e3 e3
/// ```
/// (`dx2 dx3 = det J dxi deta` on each element), summed in element order (reproducible under
/// parallelism); `area` is the parameter rectangle of `problem`'s grid.
///
/// # Errors
/// [`ElasticityError::DimensionMismatch`] unless `v` has two values per node; geometry
/// failures of the chart.
pub(crate) fn displacement_errors<G: ShellGeometry + Sync>(
    problem: &PlaneProblem<G>,
    elements: &LagrangeElements<'_>,
    node_count: usize,
    position: &(dyn Fn(usize) -> [f64; 2] + Sync),
    v: &[f64],
    exact: &(dyn Fn([f64; 2]) -> [f64; 2] + Sync),
) -> Result<DisplacementErrors, ElasticityError> {
    let (chart, grid) = (&problem.chart, &problem.grid);
    ElasticityError::check_length("displacement", 2 * node_count, v.len())?;
    let norm2 = |p: &ShellPoint<f64>, e: [f64; 2]| {
        let g = &p.metric;
        g[1][1] * e[0] * e[0] + 2.0 * g[1][2] * e[0] * e[1] + g[2][2] * e[1] * e[1]
    };
    let max = (0..node_count)
        .into_par_iter()
        .map(|k| -> Result<f64, ElasticityError> {
            let [x2, x3] = position(k);
            let p = chart.shell_point([0.0, x2, x3])?;
            let u = exact([x2, x3]);
            Ok(norm2(&p, [v[2 * k] - u[0], v[2 * k + 1] - u[1]]).sqrt())
        })
        .try_reduce(|| 0.0, |a, b| Ok(a.max(b)))?;
    let (gp, gw) = elements.rule;
    let basis = elements.basis;
    let sums = (0..elements.count)
        .into_par_iter()
        .map(|e| -> Result<[f64; 3], ElasticityError> {
            let (nodes, map) = (elements.element)(e);
            let np = basis.first().map_or(0, Vec::len);
            let mut s = [0.0; 3];
            for (i, &xi) in gp.iter().enumerate() {
                for (j, &eta) in gp.iter().enumerate() {
                    let (x, det) = map([xi, eta]);
                    let mut uh = [0.0; 2];
                    for a2 in 0..np {
                        for a3 in 0..np {
                            let node = nodes[a2 * np + a3];
                            let n = basis[i][a2] * basis[j][a3];
                            uh[0] += n * v[2 * node];
                            uh[1] += n * v[2 * node + 1];
                        }
                    }
                    let p = chart.shell_point([0.0, x[0], x[1]])?;
                    let u = exact(x);
                    let w = gw[i] * gw[j] * det;
                    let err2 = norm2(&p, [uh[0] - u[0], uh[1] - u[1]]);
                    s[0] += w * err2;
                    s[1] += w * p.sqrt_g * err2;
                    s[2] += w * p.sqrt_g * norm2(&p, u);
                }
            }
            Ok(s)
        })
        .collect::<Result<Vec<_>, _>>()?;
    // sequential sum in element order: reproducible
    let s = sums.iter().fold([0.0; 3], |acc, x| {
        [acc[0] + x[0], acc[1] + x[1], acc[2] + x[2]]
    });
    let [t0, t1] = grid.theta();
    let area = (t1 - t0) * grid.thickness();
    Ok(DisplacementErrors {
        max,
        rms: (s[0] / area).sqrt(),
        l2: s[1].sqrt(),
        l2_exact: s[2].sqrt(),
    })
}
