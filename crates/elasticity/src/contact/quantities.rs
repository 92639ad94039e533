//! Converging quantities of a contact solution: numbers that tend to a limit as the grid is
//! refined (unlike the node fraction [`ContactSolution::slip_fraction`], which moves in steps
//! of one node), each named, so that an error estimate can be attached to every one.

use std::collections::BTreeMap;

use capstan_friction::FrictionLaw;

use crate::contact::model::ContactModel;
use crate::contact::operator::ContactOperator;
use crate::contact::solution::ContactSolution;
use crate::error::ElasticityError;

/// The normal stress `sigma_n = T^3_3` at a chosen `x2` of the contact face.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct NormalStressProbe {
    /// Where (`x2`; on a 3-D body along the middle `x1` line of the contact face).
    pub x2: f64,
    /// `sigma_n` there, linearly interpolated between the two nearest contact nodes.
    pub value: f64,
}

/// The converging quantities of one [`ContactSolution`] (JSON keys are a public contract).
///
/// # Math
/// Stick/slip is decided as in [`ContactSolution`]: a point slips where `|u| >= eps` (`u` the
/// physical slip, `eps` the law's threshold `friction.eps`). Between nodes the decision is
/// made on the piecewise-linear interpolant, so the slipping set has a measure that is not a
/// multiple of the node spacing:
/// ```text
/// plane strain:  S = { x2 : |u_h(x2)| >= eps },  u_h piecewise linear in x2 (signed, as
///                [`crate::contact::StateInterval`] interpolates the stick-zone ends)
///                slip_measure = |S| (x2-length),  slip_physical_measure = int_S sqrt(g_22) dx2
/// 3-D body:      S = { (x1, x2) : |u_h| >= eps },  u_h (both components) linear on the
///                two triangles of each grid cell of the contact face
///                slip_measure = area of S in the (x1, x2) plane,
///                slip_physical_measure = int_S sqrt(det a_ab) dx1 dx2
/// ```
/// `sqrt(g_22)` and `sqrt(det a_ab)` are interpolated linearly too (exact integrals of the
/// interpolant). `contact_measure` is the same measure of the whole contact face.
///
/// In plane strain the measure is exact for the interpolant. On a 3-D triangle `|u_h|` is
/// convex: a triangle whose vertices all stick sticks, one whose smallest `|u_h|` (the distance
/// from the origin to the image triangle of its vertex slips) is `>= eps` slips, and the rest
/// (the few along a transition) are split into `4^6` sub-triangles on which `|u_h| - eps` is
/// interpolated linearly: the transition's place is then within `(h / 64)^2` of the
/// interpolant's, so an extruded plane-strain solution gives the 2-D measure times the width.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContactQuantities {
    /// Parameter-plane measure of the slipping set: `x2`-length (2-D), `(x1, x2)` area (3-D).
    pub slip_measure: f64,
    /// Physical length (2-D, per unit `x1`) or area (3-D) of the slipping set on the
    /// obstacle surface.
    pub slip_physical_measure: f64,
    /// The parameter-plane measure of the whole contact face (`slip_measure <= contact_measure`).
    pub contact_measure: f64,
    /// `sigma_n` at the probe points.
    pub normal_stress_probes: Vec<NormalStressProbe>,
}

impl ContactQuantities {
    /// The quantities of `solution`, a solution of `model`, with `sigma_n` at `probes` (`x2`).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `output.probe_x2` for a probe outside the
    /// contact face or not finite.
    pub fn new<D: ContactOperator, L: FrictionLaw<f64>>(
        model: &ContactModel<D, L>,
        solution: &ContactSolution,
        probes: &[f64],
    ) -> Result<Self, ElasticityError> {
        let eps = model.slip_threshold();
        let c = &solution.contact;
        // the area (2-D: length) element of each site, from the frames of its entries:
        // |det [frame of v^1; frame of v^2]| = |a_1| / |a^2| = sqrt(det a) (3-D), sqrt(g_22) (2-D)
        let mut metric: Vec<f64> = Vec::with_capacity(c.x2.len());
        let mut rows: Vec<usize> = Vec::with_capacity(c.x2.len());
        let nodes = model.contact_nodes();
        let mut k = 0;
        while k < nodes.len() {
            let mut end = k + 1;
            while end < nodes.len() && nodes[end].site == nodes[k].site {
                end += 1;
            }
            let entries = &nodes[k..end];
            metric.push(match entries {
                [one] => one.sqrt_g22,
                [a, b, ..] => (a.frame[0] * b.frame[1] - a.frame[1] * b.frame[0]).abs(),
                [] => unreachable!("a run has at least one entry"),
            });
            rows.push(entries[0].i1);
            k = end;
        }
        let (slip_measure, slip_physical_measure, contact_measure, line) = match &c.solid {
            None => {
                let (s, p, t) = measure_line(&c.x2, &c.slip, &metric, eps);
                (s, p, t, (0..c.x2.len()).collect::<Vec<_>>())
            }
            Some(solid) => {
                let slip: Vec<[f64; 2]> = c
                    .slip
                    .iter()
                    .zip(&solid.slip_1)
                    .map(|(u2, u1)| [*u1, *u2])
                    .collect();
                let mut ids = rows.clone();
                ids.sort_unstable();
                ids.dedup();
                // sites row by row (x1 rows, x2 along each row, increasing)
                let mut grid: Vec<Vec<usize>> = vec![Vec::new(); ids.len()];
                for (site, r) in rows.iter().enumerate() {
                    let row = ids.binary_search(r).unwrap_or(0);
                    grid[row].push(site);
                }
                for row in &mut grid {
                    row.sort_by(|&a, &b| c.x2[a].total_cmp(&c.x2[b]));
                }
                let middle = grid[grid.len() / 2].clone();
                let (s, p, t) = measure_surface(&grid, &solid.x1, &c.x2, &slip, &metric, eps);
                (s, p, t, middle)
            }
        };
        let x2: Vec<f64> = line.iter().map(|&k| c.x2[k]).collect();
        let sn: Vec<f64> = line.iter().map(|&k| c.normal_stress[k]).collect();
        let normal_stress_probes = probes
            .iter()
            .map(|&p| {
                interpolate(&x2, &sn, p)
                    .map(|value| NormalStressProbe { x2: p, value })
                    .ok_or(ElasticityError::InvalidParameter {
                        field: "output.probe_x2",
                        value: p,
                        allowed: "inside the contact interval [membrane.theta0, membrane.theta_max]",
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            slip_measure,
            slip_physical_measure,
            contact_measure,
            normal_stress_probes,
        })
    }

    /// Every converging scalar of a solution by name: these quantities, the stick-zone ends
    /// (`stick_from`, `stick_to`, when something sticks) and `max_abs_v2`, `max_abs_v3` (the
    /// magnitudes of [`ContactSolution::max_azimuthal_displacement`],
    /// [`ContactSolution::max_radial_displacement`]). Probes are `normal_stress_probe_<i>`.
    pub fn scalars(&self, solution: &ContactSolution) -> BTreeMap<String, f64> {
        let mut out = BTreeMap::new();
        out.insert("slip_measure".to_owned(), self.slip_measure);
        out.insert(
            "slip_physical_measure".to_owned(),
            self.slip_physical_measure,
        );
        if let Some(stick) = solution.stick_interval {
            out.insert("stick_from".to_owned(), stick.from);
            out.insert("stick_to".to_owned(), stick.to);
        }
        out.insert(
            "max_abs_v2".to_owned(),
            solution.max_azimuthal_displacement.value.abs(),
        );
        out.insert(
            "max_abs_v3".to_owned(),
            solution.max_radial_displacement.value.abs(),
        );
        for (i, p) in self.normal_stress_probes.iter().enumerate() {
            out.insert(format!("normal_stress_probe_{i}"), p.value);
        }
        out
    }
}

/// The stick/slip transitions along the contact face of a plane-strain solution of `model`:
/// the `x2` where the nodal slip `|u|` crosses the regularisation width `eps`, located as in
/// the slip measure (the root of the cubic Lagrange interpolant of `u` on the four nodes
/// around the interval: `O(h^4)` for a smooth slip), in increasing `x2`. Empty for a 3-D body
/// (its transitions are curves) and for a face wholly stuck or wholly slipping.
pub fn slip_transitions<D: ContactOperator, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    solution: &ContactSolution,
) -> Vec<f64> {
    let c = &solution.contact;
    if c.solid.is_some() {
        return Vec::new();
    }
    line_transitions(&c.x2, &c.slip, model.slip_threshold())
}

/// The `x` where `|u| - eps` changes sign along one line (see [`slip_transitions`]).
fn line_transitions(x: &[f64], u: &[f64], eps: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for k in 1..x.len() {
        for sign in [1.0, -1.0] {
            let (fa, fb) = (sign * u[k - 1] - eps, sign * u[k] - eps);
            if (fa >= 0.0) != (fb >= 0.0) {
                let s = cubic_crossing(x, u, k, sign * eps).unwrap_or(fa / (fa - fb));
                out.push(x[k - 1] + s * (x[k] - x[k - 1]));
            }
        }
    }
    out
}

/// The default probe points: the quarter points of `[theta0, theta1]`.
pub fn default_probes(theta: [f64; 2]) -> Vec<f64> {
    [0.25, 0.5, 0.75]
        .iter()
        .map(|s| theta[0] + s * (theta[1] - theta[0]))
        .collect()
}

/// Linear interpolation of `(x, y)` (increasing `x`) at `at`; `None` outside `[x0, xn]`.
pub fn interpolate(x: &[f64], y: &[f64], at: f64) -> Option<f64> {
    let (first, last) = (*x.first()?, *x.last()?);
    // a probe at the end of the interval, given to the digits printed, is the end node
    let slack = 1e-12 * (last - first).abs().max(1.0);
    if !at.is_finite() || at < first - slack || at > last + slack {
        return None;
    }
    let k = x.partition_point(|&v| v <= at).clamp(1, x.len().max(2) - 1);
    if x.len() == 1 {
        return Some(y[0]);
    }
    let (a, b) = (k - 1, k);
    let s = ((at - x[a]) / (x[b] - x[a])).clamp(0.0, 1.0);
    Some(y[a] + s * (y[b] - y[a]))
}

/// `(slip, physical slip, total)` measures along one line: `S = {|u_h| >= eps}`, `m_h`
/// piecewise linear.
///
/// # Math
/// Where `|u| - eps` changes sign between two nodes, the transition is the root of
/// `P(x) = +-eps` in that interval, with `P` the cubic Lagrange interpolant of `u` on the four
/// nodes around it (`x_{k-2} ... x_{k+1}`, shifted inward at the ends): for a smooth slip the
/// transition is then located to `O(h^4)` instead of the `O(h^2)` of the linear interpolant
/// (the slip `u` is a displacement trace, smooth across the transition where the traction ratio
/// has its kink). The root is bracketed by the nodal values (`P(x_j) = u_j`) and found by
/// bisection to round-off (64 halvings, a fixed budget); lines of fewer than four nodes use the
/// linear interpolant. Intervals without a sign change are wholly in or out, as before.
fn measure_line(x: &[f64], u: &[f64], m: &[f64], eps: f64) -> (f64, f64, f64) {
    let (mut slip, mut physical, mut total) = (0.0, 0.0, 0.0);
    for k in 1..x.len() {
        let len = x[k] - x[k - 1];
        total += len;
        let (ua, ub) = (u[k - 1], u[k]);
        let (ma, mb) = (m[k - 1], m[k]);
        // the parts of s in [0, 1] where u >= eps and where -u >= eps
        for (sign, fa, fb) in [(1.0, ua - eps, ub - eps), (-1.0, -ua - eps, -ub - eps)] {
            if let Some([s0, s1]) = nonnegative_part(fa, fb) {
                let [s0, s1] = if (fa >= 0.0) == (fb >= 0.0) {
                    [s0, s1]
                } else {
                    let s = cubic_crossing(x, u, k, sign * eps).unwrap_or(fa / (fa - fb));
                    if fa >= 0.0 { [0.0, s] } else { [s, 1.0] }
                };
                slip += len * (s1 - s0);
                let mean = ma + 0.5 * (s0 + s1) * (mb - ma);
                physical += len * (s1 - s0) * mean;
            }
        }
    }
    (slip, physical, total)
}

/// The root `s in [0, 1]` of `P(x_{k-1} + s (x_k - x_{k-1})) = level`, `P` the cubic Lagrange
/// interpolant of `(x, u)` on the four nodes around the interval `[x_{k-1}, x_k]`, when
/// `u_{k-1} - level` and `u_k - level` differ in sign; `None` on a line of fewer than four
/// nodes. Bisection on the bracket (64 halvings: the interval to round-off).
fn cubic_crossing(x: &[f64], u: &[f64], k: usize, level: f64) -> Option<f64> {
    if x.len() < 4 {
        return None;
    }
    let j0 = (k.saturating_sub(2)).min(x.len() - 4);
    let (xs, us) = (&x[j0..j0 + 4], &u[j0..j0 + 4]);
    let p = |t: f64| -> f64 {
        let mut sum = 0.0;
        for i in 0..4 {
            let mut l = 1.0;
            for j in 0..4 {
                if j != i {
                    l *= (t - xs[j]) / (xs[i] - xs[j]);
                }
            }
            sum += us[i] * l;
        }
        sum - level
    };
    let (mut a, mut b) = (x[k - 1], x[k]);
    let fa = u[k - 1] - level;
    if (fa >= 0.0) == (u[k] - level >= 0.0) {
        return None;
    }
    for _ in 0..64 {
        let c = 0.5 * (a + b);
        if (p(c) >= 0.0) == (fa >= 0.0) {
            a = c;
        } else {
            b = c;
        }
    }
    Some(((0.5 * (a + b) - x[k - 1]) / (x[k] - x[k - 1])).clamp(0.0, 1.0))
}

/// The sub-interval of `[0, 1]` where `fa + s (fb - fa) >= 0`, if not empty.
fn nonnegative_part(fa: f64, fb: f64) -> Option<[f64; 2]> {
    match (fa >= 0.0, fb >= 0.0) {
        (true, true) => Some([0.0, 1.0]),
        (false, false) => None,
        (true, false) => Some([0.0, fa / (fa - fb)]),
        (false, true) => Some([fa / (fa - fb), 1.0]),
    }
}

/// `(slip, physical slip, total)` measures on a structured face: `grid[r]` the sites of row
/// `r` in increasing `x2`, every row of one length; each cell split along its diagonal into
/// two triangles with `u`, `m` linear on each; `S = {|u_h| >= eps}`.
fn measure_surface(
    grid: &[Vec<usize>],
    x1: &[f64],
    x2: &[f64],
    u: &[[f64; 2]],
    m: &[f64],
    eps: f64,
) -> (f64, f64, f64) {
    let (mut slip, mut physical, mut total) = (0.0, 0.0, 0.0);
    for r in 1..grid.len() {
        let (lo, hi) = (&grid[r - 1], &grid[r]);
        for k in 1..lo.len().min(hi.len()) {
            let corners = [lo[k - 1], lo[k], hi[k], hi[k - 1]];
            for tri in [[0, 1, 2], [0, 2, 3]] {
                let ids = tri.map(|t| corners[t]);
                let pts = ids.map(|i| [x1[i], x2[i]]);
                let (area, integral) =
                    slip_in_triangle(pts, ids.map(|i| u[i]), ids.map(|i| m[i]), eps, 6);
                slip += area;
                physical += integral;
                total += triangle_area(pts[0], pts[1], pts[2]);
            }
        }
    }
    (slip, physical, total)
}

/// Area and `int m` of the part of triangle `p` where `|u_h| >= eps` (`u`, `m` linear), by
/// the convexity of `|u_h|` and `depth` levels of 4-way splitting along the transition.
fn slip_in_triangle(
    p: [[f64; 2]; 3],
    u: [[f64; 2]; 3],
    m: [f64; 3],
    eps: f64,
    depth: u32,
) -> (f64, f64) {
    let norm = u.map(|v| v[0].hypot(v[1]));
    let area = triangle_area(p[0], p[1], p[2]);
    if norm.iter().all(|&n| n < eps) {
        return (0.0, 0.0); // |u_h| convex: below eps at the vertices, below inside
    }
    if smallest_norm(u) >= eps {
        return (area, area * (m[0] + m[1] + m[2]) / 3.0);
    }
    if depth == 0 {
        let (a, i, _) = clip_triangle(p, norm.map(|n| n - eps), m);
        return (a, i);
    }
    let mid = |a: usize, b: usize| {
        (
            [0.5 * (p[a][0] + p[b][0]), 0.5 * (p[a][1] + p[b][1])],
            [0.5 * (u[a][0] + u[b][0]), 0.5 * (u[a][1] + u[b][1])],
            0.5 * (m[a] + m[b]),
        )
    };
    let (m01, m12, m20) = (mid(0, 1), mid(1, 2), mid(2, 0));
    let corner = |k: usize| (p[k], u[k], m[k]);
    let parts = [
        [corner(0), m01, m20],
        [m01, corner(1), m12],
        [m20, m12, corner(2)],
        [m01, m12, m20],
    ];
    let (mut a, mut i) = (0.0, 0.0);
    for t in parts {
        let (da, di) = slip_in_triangle(
            t.map(|v| v.0),
            t.map(|v| v.1),
            t.map(|v| v.2),
            eps,
            depth - 1,
        );
        a += da;
        i += di;
    }
    (a, i)
}

/// `min |u_h|` over a triangle with vertex values `u` (2-vectors): 0 when the origin lies in
/// the image triangle, else the distance from the origin to its nearest edge.
fn smallest_norm(u: [[f64; 2]; 3]) -> f64 {
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let side = [0, 1, 2].map(|k| cross(u[k], u[(k + 1) % 3]));
    if side.iter().all(|&s| s >= 0.0) || side.iter().all(|&s| s <= 0.0) {
        return 0.0;
    }
    (0..3)
        .map(|k| {
            let (a, b) = (u[k], u[(k + 1) % 3]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let len2 = d[0] * d[0] + d[1] * d[1];
            let s = if len2 > 0.0 {
                (-(a[0] * d[0] + a[1] * d[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (a[0] + s * d[0]).hypot(a[1] + s * d[1])
        })
        .fold(f64::INFINITY, f64::min)
}

/// Area and `int m` of the part of triangle `p` where the linear `f >= 0`, and its whole area.
fn clip_triangle(p: [[f64; 2]; 3], f: [f64; 3], m: [f64; 3]) -> (f64, f64, f64) {
    // vertices as (x1, x2, m); clip the polygon by f >= 0 (Sutherland–Hodgman, one edge)
    let mut poly: Vec<([f64; 2], f64)> = Vec::with_capacity(4);
    for i in 0..3 {
        let j = (i + 1) % 3;
        let (fi, fj) = (f[i], f[j]);
        if fi >= 0.0 {
            poly.push((p[i], m[i]));
        }
        if (fi >= 0.0) != (fj >= 0.0) {
            let s = fi / (fi - fj);
            let at = [
                p[i][0] + s * (p[j][0] - p[i][0]),
                p[i][1] + s * (p[j][1] - p[i][1]),
            ];
            poly.push((at, m[i] + s * (m[j] - m[i])));
        }
    }
    let whole = triangle_area(p[0], p[1], p[2]);
    let (mut area, mut integral) = (0.0, 0.0);
    // fan triangulation; the integral of a linear m over a triangle is area x mean of vertices
    for k in 2..poly.len() {
        let a = triangle_area(poly[0].0, poly[k - 1].0, poly[k].0);
        area += a;
        integral += a * (poly[0].1 + poly[k - 1].1 + poly[k].1) / 3.0;
    }
    (area, integral, whole)
}

fn triangle_area(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_measure_of_a_linear_slip_is_exact() {
        // u = x on [-2, 2], eps = 0.5: slipping set [-2, -0.5] u [0.5, 2], length 3
        let x = [-2.0, -1.0, 0.0, 1.0, 2.0];
        let m = [2.0; 5];
        let (s, p, t) = measure_line(&x, &x, &m, 0.5);
        assert!((s - 3.0).abs() < 1e-14); // exact: u is linear
        assert!((p - 6.0).abs() < 1e-14);
        assert!((t - 4.0).abs() < 1e-14);
    }

    /// The slipping length of `u = sin(3 x) + 0.2 x` on `[0, 2]` at `eps = 0.5` from `n`
    /// uniform nodes, and the exact length (roots of `|u| = eps` by bisection on `u`).
    fn sine_measure(n: usize) -> (f64, f64) {
        let u = |x: f64| (3.0 * x).sin() + 0.2 * x;
        let x: Vec<f64> = (0..n).map(|i| 2.0 * i as f64 / (n - 1) as f64).collect();
        let uh: Vec<f64> = x.iter().map(|&t| u(t)).collect();
        let (s, _, _) = measure_line(&x, &uh, &vec![1.0; n], 0.5);
        // exact: sample finely, bisect every sign change of |u| - eps
        let f = |t: f64| u(t).abs() - 0.5;
        let fine = 20_000;
        let mut exact = 0.0;
        let mut start = if f(0.0) >= 0.0 { Some(0.0) } else { None };
        for i in 1..=fine {
            let (a0, b0) = (
                2.0 * (i - 1) as f64 / fine as f64,
                2.0 * i as f64 / fine as f64,
            );
            if (f(a0) >= 0.0) != (f(b0) >= 0.0) {
                let (mut a, mut b) = (a0, b0);
                for _ in 0..80 {
                    let c = 0.5 * (a + b);
                    if (f(c) >= 0.0) == (f(a) >= 0.0) {
                        a = c
                    } else {
                        b = c
                    }
                }
                let r = 0.5 * (a + b);
                match start.take() {
                    Some(s0) => exact += r - s0,
                    None => start = Some(r),
                }
            }
        }
        if let Some(s0) = start {
            exact += 2.0 - s0;
        }
        (s, exact)
    }

    #[test]
    fn line_measure_locates_smooth_transitions_to_fourth_order() {
        // the cubic locator: error falls 16x per halving (the linear one: 4x)
        let errors: Vec<f64> = [41, 81, 161, 321]
            .iter()
            .map(|&n| {
                let (s, exact) = sine_measure(n);
                (s - exact).abs()
            })
            .collect();
        let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        // measured: orders 3.35, 4.42, 4.04 (errors 7.6e-6 ... 2.1e-9); the linear locator
        // gives 1.4, 2.4, 2.0 (errors 1.8e-3 ... 3.3e-5)
        for o in &orders {
            assert!(
                (3.2..4.8).contains(o),
                "orders {orders:?} errors {errors:?}"
            );
        }
        assert!(orders[2] > 3.7, "orders {orders:?}");
        assert!(errors[3] < 1e-8, "{errors:?}");
    }

    #[test]
    fn line_transitions_are_the_ends_of_the_measured_slip_set() {
        // u = sin(3 x) + 0.2 x on [0, 2], eps = 0.5: the transitions bound the slip measure
        let n = 161;
        let x: Vec<f64> = (0..n).map(|i| 2.0 * i as f64 / (n - 1) as f64).collect();
        let u: Vec<f64> = x.iter().map(|&t| (3.0 * t).sin() + 0.2 * t).collect();
        let t = line_transitions(&x, &u, 0.5);
        let (s, _, _) = measure_line(&x, &u, &vec![1.0; n], 0.5);
        // |u| < eps at 0: the slip set is [t0, t1] u [t2, t3] u ...
        let mut from_ends = 0.0;
        for pair in t.chunks(2) {
            from_ends += pair.get(1).copied().unwrap_or(2.0) - pair[0];
        }
        assert!(t.windows(2).all(|w| w[0] < w[1]), "{t:?}");
        assert!((from_ends - s).abs() < 1e-13, "{from_ends} {s}");
        for &r in &t {
            let ur = (3.0 * r).sin() + 0.2 * r;
            assert!((ur.abs() - 0.5).abs() < 1e-6, "{r}: {ur}");
        }
    }

    #[test]
    fn surface_measure_of_a_planar_level_set_is_exact() {
        // f = x2 - 0.3 on [0, 1]^2 (3 x 4 nodes): slipping area 0.7, metric 1 + x1
        let (x1s, x2s) = ([0.0, 0.5, 1.0], [0.0, 0.25, 0.5, 1.0]);
        let (mut x1, mut x2, mut grid) = (vec![], vec![], vec![]);
        for &a in &x1s {
            let mut row = vec![];
            for &b in &x2s {
                row.push(x1.len());
                x1.push(a);
                x2.push(b);
            }
            grid.push(row);
        }
        // u = (0, x2 + 0.2) slips (|u| >= 0.5) for x2 >= 0.3 (linear, positive)
        let eps = 0.5;
        let u: Vec<[f64; 2]> = x2.iter().map(|b| [0.0, b + 0.2]).collect();
        let m: Vec<f64> = x1.iter().map(|a| 1.0 + a).collect();
        let (s, p, t) = measure_surface(&grid, &x1, &x2, &u, &m, eps);
        assert!((s - 0.7).abs() < 1e-14); // exact: |u_h| linear where it crosses eps
        assert!((p - 0.7 * 1.5).abs() < 1e-14); // int (1 + x1) over [0,1] x [0.3,1]
        assert!((t - 1.0).abs() < 1e-14);
    }

    #[test]
    fn smallest_norm_is_zero_around_the_origin_and_the_edge_distance_outside() {
        assert_eq!(smallest_norm([[1.0, 0.0], [-1.0, 1.0], [-1.0, -1.0]]), 0.0);
        let d = smallest_norm([[1.0, 1.0], [1.0, -1.0], [3.0, 0.0]]);
        assert!((d - 1.0).abs() < 1e-15); // the edge x = 1
    }

    #[test]
    fn a_slip_turning_inside_a_triangle_leaves_the_disk_out() {
        // u = (x, y) on the triangle (-1,-1), (1,-1), (0, 1) minus the disk |u| < 0.2
        let p = [[-1.0, -1.0], [1.0, -1.0], [0.0, 1.0]];
        let (a, i) = slip_in_triangle(p, p, [1.0; 3], 0.2, 8);
        let exact = 2.0 - core::f64::consts::PI * 0.04;
        // the disk as a polygon of sub-triangles h / 256: area error 2.7e-5 (2e-4 of the disk)
        assert!((a - exact).abs() < 5e-5, "{a} {exact}");
        assert!((i - a).abs() < 1e-12);
    }

    #[test]
    fn interpolate_is_linear_and_refuses_outside_points() {
        let (x, y) = ([0.0, 1.0, 3.0], [0.0, 2.0, 6.0]);
        assert_eq!(interpolate(&x, &y, 2.0), Some(4.0));
        assert_eq!(interpolate(&x, &y, 3.0), Some(6.0));
        assert_eq!(interpolate(&x, &y, 0.0), Some(0.0));
        assert_eq!(interpolate(&x, &y, 3.1), None);
        assert_eq!(interpolate(&x, &y, f64::NAN), None);
    }
}
