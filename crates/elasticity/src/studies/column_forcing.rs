//! The plane-strain manufactured forcing `f_j = -nabla_i T^i_j` along a column of points
//! `x2 = const` from one dual frame of the chart, and a per-thread cache of that frame.
//!
//! Differentiating the flux `sqrt(g) T^a_j` along `x2` and `x3` needs the shell geometry at
//! dual coordinates. Seeding `x2` in the inner part and `x3` in the outer part of a nested
//! dual number ([`Dual2`]) gives both derivatives from one evaluation per point, and since the
//! chart is affine in `x3` the dual jet of `sigma` (the expensive part: fourth derivatives of
//! `sigma`) depends on `x2` only: it is built once per column ([`ForcingColumn`]) and every
//! height above it costs the shell formulas and the stress only. The quadrature loops of the
//! discretisations visit the points column by column, so [`ColumnCache`] keeps the last
//! column of each thread.
//!
//! This is a leaf module: it names no manufactured field (the field's inputs come as a
//! closure), so `samples` can use it without a cycle.

use core::cell::RefCell;
use core::sync::atomic::{AtomicU64, Ordering};

use capstan_geometry::ad::{self, Dual1};
use capstan_geometry::{ShellChart, ShellFrame, ShellPoint, Surface};

use crate::continuum::kinematics::christoffel_contraction;
use crate::error::ElasticityError;
use crate::material::Material;

/// A nested dual number: `x2` derivatives in the inner part, `x3` derivatives in the outer
/// part (`((v, d_2 v), (d_3 v, d_2 d_3 v))`).
pub type Dual2 = Dual1<Dual1<f64>>;

/// `x + eps_2 d2 + eps_3 d3` as a [`Dual2`].
fn seed(x: f64, d2: f64, d3: f64) -> Dual2 {
    ad::seed(ad::seed(x, d2), ad::seed(d3, 0.0))
}

/// The value part of a [`Dual2`].
fn value(d: Dual2) -> f64 {
    ad::value_part(ad::value_part(d))
}

/// The `x2` derivative part of a [`Dual2`].
fn d2(d: Dual2) -> f64 {
    ad::derivative_part(ad::value_part(d))
}

/// The `x3` derivative part of a [`Dual2`].
fn d3(d: Dual2) -> f64 {
    ad::value_part(ad::derivative_part(d))
}

/// The dual frame of the chart over the surface point `(0, x2)`, `x2` seeded (the part of
/// the geometry every height of the column shares).
#[derive(Debug, Clone, Copy)]
pub struct ForcingColumn {
    x2: f64,
    frame: ShellFrame<Dual2>,
}

impl ForcingColumn {
    /// The column `x2 = const` of `chart`.
    ///
    /// # Errors
    /// Geometry failures at the real surface point.
    pub fn new<Surf: Surface<f64>>(
        chart: &ShellChart<Surf>,
        x2: f64,
    ) -> Result<Self, ElasticityError> {
        let frame = chart.frame_over([seed(0.0, 0.0, 0.0), seed(x2, 1.0, 0.0)])?;
        Ok(Self { x2, frame })
    }

    /// The forcing `[f_2, f_3]` at height `x3` of the column of a field whose six plane-strain
    /// inputs `[v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]` at dual `(x2, x3)` are
    /// `inputs(y)`.
    ///
    /// # Math
    /// ```text
    /// f_j = -( (1/sqrt(g)) (d_2 (sqrt(g) T^2_j) + d_3 (sqrt(g) T^3_j)) - Gamma^k_ij T^i_k )
    /// ```
    /// with `sqrt(g) T^a_j` evaluated once at `(x2 + eps_2, x3 + eps_3)` (nested dual numbers
    /// through the shell point and the field): `d_2` its inner, `d_3` its outer derivative
    /// part; `sqrt(g)`, `Gamma` and `T` its value parts.
    ///
    /// # Errors
    /// Geometry failures at the real point.
    pub fn forcing(
        &self,
        material: &Material,
        x3: f64,
        inputs: impl Fn([Dual2; 2]) -> [Dual2; 6],
    ) -> Result<[f64; 2], ElasticityError> {
        let y = [seed(self.x2, 1.0, 0.0), seed(x3, 0.0, 1.0)];
        let q = self.frame.point_over(y[1])?;
        let t = plane_strain_stress(&q, material, &inputs(y));
        let div: [f64; 3] =
            core::array::from_fn(|j| d2(q.sqrt_g * t[1][j]) + d3(q.sqrt_g * t[2][j]));
        let p = value_point(&q);
        let stress = t.map(|row| row.map(value));
        Ok([1, 2].map(|j| -(div[j] / p.sqrt_g - christoffel_contraction(&p, &stress, j))))
    }
}

/// The mixed stress `T^i_j` of a plane-strain displacement with inputs
/// `u = [v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]` at `p`: the same tensor as
/// [`crate::continuum::mixed_stress_of`] with [`crate::continuum::PLANE_STRAIN`], contracted
/// in the order gradient first (one strain instead of one per input: a fifth of the
/// products), for any scalar.
///
/// # Math
/// ```text
/// nabla_i v^n = d_i v^n + Gamma^n_im v^m          (v^1 = 0, d_1 = 0)
/// E_il = (nabla_i v^n g_nl + nabla_l v^n g_ni) / 2,   M^i_l = g^ij E_jl
/// T^i_j = lambda delta^i_j tr M + 2 mu M^i_j
/// ```
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
pub(crate) fn plane_strain_stress<S: capstan_geometry::Scalar<f64>>(
    p: &ShellPoint<S>,
    material: &Material,
    u: &[S; 6],
) -> [[S; 3]; 3] {
    let (g, gi, gamma) = (&p.metric, &p.inverse_metric, &p.christoffel);
    let z = S::zero();
    // nabla_i v^n
    let mut grad = [[z; 3]; 3];
    for i in 0..3 {
        for n in 0..3 {
            grad[i][n] = gamma[n][i][1] * u[0] + gamma[n][i][2] * u[1];
        }
    }
    for (i, d) in [(1, [u[2], u[3]]), (2, [u[4], u[5]])] {
        grad[i][1] += d[0];
        grad[i][2] += d[1];
    }
    let mut h = [[z; 3]; 3];
    for i in 0..3 {
        for l in 0..3 {
            h[i][l] = grad[i][0] * g[0][l] + grad[i][1] * g[1][l] + grad[i][2] * g[2][l];
        }
    }
    let mut e = [[z; 3]; 3];
    for i in 0..3 {
        for l in 0..3 {
            e[i][l] = (h[i][l] + h[l][i]) * 0.5;
        }
    }
    let mut m = [[z; 3]; 3];
    for i in 0..3 {
        for l in 0..3 {
            m[i][l] = gi[i][0] * e[0][l] + gi[i][1] * e[1][l] + gi[i][2] * e[2][l];
        }
    }
    let trace = m[0][0] + m[1][1] + m[2][2];
    let (lambda, two_mu) = (material.lambda(), 2.0 * material.mu());
    core::array::from_fn(|i| {
        core::array::from_fn(|j| {
            let delta = if i == j { trace * lambda } else { z };
            delta + m[i][j] * two_mu
        })
    })
}

/// The value parts of a dual shell point.
fn value_point(q: &ShellPoint<Dual2>) -> ShellPoint<f64> {
    let v3 = |a: &[Dual2; 3]| a.map(value);
    let m3 = |m: &[[Dual2; 3]; 3]| m.map(|r| r.map(value));
    ShellPoint {
        position: v3(&q.position),
        covariant_basis: m3(&q.covariant_basis),
        contravariant_basis: m3(&q.contravariant_basis),
        metric: m3(&q.metric),
        inverse_metric: m3(&q.inverse_metric),
        sqrt_g: value(q.sqrt_g),
        christoffel: q.christoffel.map(|m| m.map(|r| r.map(value))),
    }
}

/// Ids of the caches, so that a thread's slot never serves another forcing's column.
static NEXT_CACHE: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// The last column of this thread: `(cache id, x2 bits, column)`.
    static LAST_COLUMN: RefCell<Option<(u64, u64, ForcingColumn)>> = const { RefCell::new(None) };
}

/// The last [`ForcingColumn`] of each thread, for one forcing (one chart): a column is built
/// again only when `x2` changes (or another forcing used the thread meanwhile). The column
/// is a pure function of the chart and `x2`, so the cache changes no result.
#[derive(Debug)]
pub struct ColumnCache {
    id: u64,
}

impl Default for ColumnCache {
    fn default() -> Self {
        Self {
            id: NEXT_CACHE.fetch_add(1, Ordering::Relaxed),
        }
    }
}

impl ColumnCache {
    /// `visit(column)` with the column of `chart` at `x2`, built by [`ForcingColumn::new`]
    /// unless it is this thread's last column of this cache.
    ///
    /// # Errors
    /// Those of [`ForcingColumn::new`] and of `visit`.
    pub fn with<Surf: Surface<f64>, R>(
        &self,
        chart: &ShellChart<Surf>,
        x2: f64,
        visit: impl FnOnce(&ForcingColumn) -> Result<R, ElasticityError>,
    ) -> Result<R, ElasticityError> {
        let key = (self.id, x2.to_bits());
        LAST_COLUMN.with(|cell| {
            // a hit is visited in place (no copy of the frame); a nested call that finds the
            // slot borrowed computes without the cache
            if let Ok(slot) = cell.try_borrow()
                && let Some((id, bits, column)) = &*slot
                && (*id, *bits) == key
            {
                return visit(column);
            }
            let column = ForcingColumn::new(chart, x2)?;
            let out = visit(&column);
            if let Ok(mut slot) = cell.try_borrow_mut() {
                *slot = Some((key.0, key.1, column));
            }
            out
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuum::{PLANE_STRAIN, mixed_stress_of};
    use capstan_geometry::EllipticalPrism;

    /// The gradient-first stress equals the per-input contraction of `mixed_stress_of` to
    /// round-off, on a curved chart off the obstacle, at arbitrary inputs.
    #[test]
    fn plane_strain_stress_is_the_mixed_stress() {
        let chart = ShellChart::new(EllipticalPrism::new(1.0, 2.0).unwrap());
        let material = Material::new(10.0, 0.3).unwrap();
        for (x, u) in [
            ([0.0, 0.4, 0.3], [0.1, -0.2, 0.3, 0.05, -0.7, 0.2]),
            ([0.0, -1.1, 0.05], [-0.3, 0.8, -0.1, 0.6, 0.25, -0.4]),
        ] {
            let p: ShellPoint<f64> = chart.point(x).unwrap();
            let u: [f64; 6] = u;
            let a = plane_strain_stress(&p, &material, &u);
            let b = mixed_stress_of(&p, &PLANE_STRAIN, &material, &u);
            let scale = b
                .iter()
                .flatten()
                .fold(0.0f64, |m: f64, t: &f64| m.max(t.abs()));
            for (ra, rb) in a.iter().zip(&b) {
                for (ta, tb) in ra.iter().zip(rb) {
                    assert!((ta - tb).abs() <= 1e-14 * scale, "{ta} against {tb}");
                }
            }
        }
    }
}
