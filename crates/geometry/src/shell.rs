//! The shell chart `Theta(x1, x2, x3) = sigma(x1, x2) + x3 N(x1, x2)` and its 3-D geometry.

use crate::ad::{self, SurfaceJet};
use crate::error::GeometryError;
use crate::scalar::{Real, Scalar};
use crate::surface::Surface;
use crate::surface::point3;
use crate::vector::{add, axpy, cross, dot, is_finite, scale};

/// The 3-D geometry of a shell chart at one point `(x1, x2, x3)`.
///
/// # Math
/// ```text
/// g_a = a_a + x3 d_a N,   g_3 = N                     covariant basis (a = 1, 2)
/// g_ij = g_i . g_j,   g^ij = (g_ij)^-1                metric and inverse
/// sqrt(g) = g_1 . (g_2 x g_3)                         volume element (> 0 off the focal surface)
/// g^1 = g_2 x g_3 / sqrt(g)  (and cyclic)             contravariant basis
/// Gamma^k_ij = g^k . d_i g_j                          Christoffel symbols of the second kind
/// d_b g_a = d_a d_b sigma + x3 d_a d_b N,  d_3 g_a = d_a g_3 = d_a N,  d_3 g_3 = 0
/// ```
/// With `x3 = 0` on the obstacle, `g_ab = a_ab - 2 x3 b_ab + x3^2 b_ac b^c_b`, `g_a3 = 0`, `g_33 = 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellPoint<F> {
    /// `Theta(x)` in E^3.
    pub position: [F; 3],
    /// `covariant_basis[i] = g_i`.
    pub covariant_basis: [[F; 3]; 3],
    /// `contravariant_basis[i] = g^i`.
    pub contravariant_basis: [[F; 3]; 3],
    /// `metric[i][j] = g_ij`.
    pub metric: [[F; 3]; 3],
    /// `inverse_metric[i][j] = g^ij`.
    pub inverse_metric: [[F; 3]; 3],
    /// `sqrt(g) = sqrt(det g_ij)`.
    pub sqrt_g: F,
    /// `christoffel[k][i][j] = Gamma^k_ij`.
    pub christoffel: [[[F; 3]; 3]; 3],
}

/// Derivatives of the unit normal: `(N, d_a N, d_a d_b N)`, from the jet of `sigma`.
///
/// # Math
/// ```text
/// n = a_1 x a_2,  r = |n|,  N = n / r
/// n_c  = d_1c sigma x a_2 + a_1 x d_2c sigma
/// n_cd = d_1cd sigma x a_2 + d_1c sigma x d_2d sigma + d_1d sigma x d_2c sigma + a_1 x d_2cd sigma
/// r_c  = n . n_c / r,   r_cd = (n_c . n_d + n . n_cd - r_c r_d) / r
/// N_c  = n_c / r - n r_c / r^2
/// N_cd = n_cd / r - (n_c r_d + n_d r_c + n r_cd) / r^2 + 2 n r_c r_d / r^3
/// ```
/// Written for any scalar `D` over `F`: on the jet of a dual point ([`ad::surface_jet_over`])
/// the results carry their derivatives too.
#[allow(clippy::type_complexity, clippy::needless_range_loop)] // (N, dN, ddN) and index loops mirror the math
pub fn normal_derivatives<F: Real, D: Scalar<F>>(
    jet: &SurfaceJet<D>,
) -> ([D; 3], [[D; 3]; 2], [[[D; 3]; 2]; 2]) {
    let (a1, a2) = (&jet.d1[0], &jet.d1[1]);
    let n = cross(a1, a2);
    let r = dot(&n, &n).sqrt();
    let nc: [[D; 3]; 2] = [0, 1].map(|c| add(&cross(&jet.d2[0][c], a2), &cross(a1, &jet.d2[1][c])));
    let z = D::zero();
    let mut ncd = [[[z; 3]; 2]; 2];
    for (c, row) in ncd.iter_mut().enumerate() {
        for (d, v) in row.iter_mut().enumerate() {
            let t1 = cross(&jet.d3[0][c][d], a2);
            let t2 = cross(&jet.d2[0][c], &jet.d2[1][d]);
            let t3 = cross(&jet.d2[0][d], &jet.d2[1][c]);
            let t4 = cross(a1, &jet.d3[1][c][d]);
            *v = add(&add(&t1, &t2), &add(&t3, &t4));
        }
    }
    let inv_r = D::one() / r;
    let rc = [0, 1].map(|c| dot(&n, &nc[c]) * inv_r);
    let mut rcd = [[z; 2]; 2];
    for c in 0..2 {
        for d in 0..2 {
            rcd[c][d] = (dot(&nc[c], &nc[d]) + dot(&n, &ncd[c][d]) - rc[c] * rc[d]) * inv_r;
        }
    }
    let normal = scale(inv_r, &n);
    let inv_r2 = inv_r * inv_r;
    let dn = [0, 1].map(|c| axpy(&scale(inv_r, &nc[c]), -rc[c] * inv_r2, &n));
    let mut ddn = [[[z; 3]; 2]; 2];
    let two = D::one() + D::one();
    for c in 0..2 {
        for d in c..2 {
            let mut v = scale(inv_r, &ncd[c][d]);
            v = axpy(&v, -rc[d] * inv_r2, &nc[c]);
            v = axpy(&v, -rc[c] * inv_r2, &nc[d]);
            v = axpy(
                &v,
                -rcd[c][d] * inv_r2 + two * rc[c] * rc[d] * inv_r2 * inv_r,
                &n,
            );
            ddn[c][d] = v;
            ddn[d][c] = v;
        }
    }
    (normal, dn, ddn)
}

impl<F: Real> ShellPoint<F> {
    /// The shell geometry at height `x3` above the surface point whose jet is given.
    ///
    /// Equal, bit for bit, to [`ShellFrame::point`] on the frame of the same jet.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] for a non-finite jet; [`GeometryError::Degenerate`] when the
    /// normal is undefined or `sqrt(g) <= 0` (`x3` at or past the focal surface, e.g.
    /// `x3 <= -R` under a cylinder of radius `R`).
    pub fn from_jet(jet: &SurfaceJet<F>, x: [F; 3]) -> Result<Self, GeometryError> {
        crate::surface::check_regular(jet, point3([x[0], x[1]], x[2]))?;
        ShellFrame::unchecked(jet, [x[0], x[1]]).point(x[2])
    }

    /// `max_kij |Gamma^k_ij|`, the scale of the Christoffel symbols (for relative
    /// tolerances on them).
    pub fn christoffel_scale(&self) -> F {
        self.christoffel
            .iter()
            .flatten()
            .flatten()
            .fold(F::zero(), |m, x| m.max(x.abs()))
    }
}

/// The part of the shell geometry that depends on the surface point `(x1, x2)` only: the jet
/// of `sigma` and the derivatives of the unit normal. Built once per surface point and reused
/// for every height `x3` above it (the chart is affine in `x3`), e.g. for all quadrature
/// points of a column of elements.
///
/// # Math
/// ```text
/// frame(x1, x2):  sigma, d_a sigma, d_a d_b sigma, N, d_a N, d_a d_b N     (once)
/// point(x3):      g_a = a_a + x3 d_a N,  d_b g_a = d_a d_b sigma + x3 d_a d_b N, ...
/// ```
///
/// # Example
/// ```
/// use capstan_geometry::{EllipticalPrism, ShellChart};
/// let chart = ShellChart::new(EllipticalPrism::new(2.0_f64, 1.0).unwrap());
/// let frame = chart.frame([0.0, 0.4]).unwrap();
/// for x3 in [0.0, 0.25, 0.5] {
///     assert_eq!(frame.point(x3).unwrap(), chart.point([0.0, 0.4, x3]).unwrap());
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellFrame<F> {
    jet: SurfaceJet<F>,
    at: [F; 2],
    normal: [F; 3],
    dn: [[F; 3]; 2],
    ddn: [[[F; 3]; 2]; 2],
}

impl<F: Real> ShellFrame<F> {
    /// The frame of the surface point `x = (x1, x2)` whose jet is given.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] for a non-finite jet; [`GeometryError::Degenerate`] when the
    /// normal is undefined.
    pub fn new(jet: &SurfaceJet<F>, x: [F; 2]) -> Result<Self, GeometryError> {
        crate::surface::check_regular(jet, point3(x, F::zero()))?;
        Ok(Self::unchecked(jet, x))
    }

    /// The frame of a jet that passed `check_regular`.
    fn unchecked(jet: &SurfaceJet<F>, x: [F; 2]) -> Self {
        let (normal, dn, ddn) = normal_derivatives::<F, F>(jet);
        Self {
            jet: *jet,
            at: x,
            normal,
            dn,
            ddn,
        }
    }

    /// The jet of `sigma` at the frame's surface point.
    pub fn jet(&self) -> &SurfaceJet<F> {
        &self.jet
    }

    /// The shell geometry at height `x3` above the frame's surface point.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] for non-finite geometry; [`GeometryError::Degenerate`] when
    /// `sqrt(g) <= 0` (`x3` at or past the focal surface).
    pub fn point(&self, x3: F) -> Result<ShellPoint<F>, GeometryError> {
        let at = point3(self.at, x3);
        let point = shell_point_of::<F, F>(&self.jet, self.normal, &self.dn, &self.ddn, x3);
        if !point.sqrt_g.is_finite() {
            return Err(GeometryError::NonFinite {
                what: "sqrt(g)",
                at,
            });
        }
        if point.sqrt_g <= F::zero() {
            return Err(GeometryError::Degenerate {
                what: "sqrt(g) <= 0: x3 at or past the focal surface",
                at,
            });
        }
        let finite = is_finite(&point.position)
            && point.christoffel.iter().flatten().all(is_finite)
            && point.inverse_metric.iter().all(is_finite);
        if !finite {
            return Err(GeometryError::NonFinite {
                what: "shell geometry",
                at,
            });
        }
        Ok(point)
    }
}

impl<D: Copy> ShellFrame<D> {
    /// The shell geometry at height `x3` above the frame of a dual surface point
    /// ([`ShellChart::frame_over`]), at a height of the same scalar `D`: with `x2` seeded in
    /// the frame and `x3` seeded here (e.g. nested dual numbers, one direction each), every
    /// field of the point carries its exact `x2` and `x3` derivatives from one evaluation.
    /// Equal, bit for bit, to [`ShellChart::point_over`] at the same dual coordinates.
    ///
    /// # Math
    /// ```text
    /// g_a = a_a + x3 d_a N,  g_3 = N,  g_ij, g^ij, sqrt(g), Gamma^k_ij   as in ShellPoint,
    /// over the scalar D (value and derivative parts)
    /// ```
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] for non-finite geometry at the real point;
    /// [`GeometryError::Degenerate`] when `sqrt(g) <= 0` there (`x3` at or past the focal
    /// surface).
    pub fn point_over<F: Real>(&self, x3: D) -> Result<ShellPoint<D>, GeometryError>
    where
        D: Scalar<F>,
    {
        let real = |d: D| ad::real_part::<F, D>(d);
        let at = point3(self.at.map(real), real(x3));
        let point = shell_point_of::<F, D>(&self.jet, self.normal, &self.dn, &self.ddn, x3);
        let sqrt_g = real(point.sqrt_g);
        if !sqrt_g.is_finite() {
            return Err(GeometryError::NonFinite {
                what: "sqrt(g)",
                at,
            });
        }
        if sqrt_g <= F::zero() {
            return Err(GeometryError::Degenerate {
                what: "sqrt(g) <= 0: x3 at or past the focal surface",
                at,
            });
        }
        let finite = point
            .position
            .iter()
            .chain(point.christoffel.iter().flatten().flatten())
            .chain(point.inverse_metric.iter().flatten())
            .all(|&d| real(d).is_finite());
        if !finite {
            return Err(GeometryError::NonFinite {
                what: "shell geometry",
                at,
            });
        }
        Ok(point)
    }
}

/// The formulas of [`ShellPoint`] at height `x3` over a surface point, from the jet of `sigma`
/// and the derivatives of the normal, for any scalar `D` (no checks: the callers check the
/// real point).
#[inline]
#[allow(clippy::needless_range_loop)] // index loops mirror g_ij and Gamma^k_ij
fn shell_point_of<F: Real, D: Scalar<F>>(
    jet: &SurfaceJet<D>,
    normal: [D; 3],
    dn: &[[D; 3]; 2],
    ddn: &[[[D; 3]; 2]; 2],
    x3: D,
) -> ShellPoint<D> {
    let g = [
        axpy(&jet.d1[0], x3, &dn[0]),
        axpy(&jet.d1[1], x3, &dn[1]),
        normal,
    ];
    let sqrt_g = dot(&g[0], &cross(&g[1], &g[2]));
    let inv = D::one() / sqrt_g;
    let contra = [
        scale(inv, &cross(&g[1], &g[2])),
        scale(inv, &cross(&g[2], &g[0])),
        scale(inv, &cross(&g[0], &g[1])),
    ];
    let z = D::zero();
    let mut metric = [[z; 3]; 3];
    let mut inverse_metric = [[z; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            metric[i][j] = dot(&g[i], &g[j]);
            inverse_metric[i][j] = dot(&contra[i], &contra[j]);
        }
    }
    // dg[i][j] = d_i g_j (symmetric in i, j).
    let mut dg = [[[z; 3]; 3]; 3];
    for a in 0..2 {
        for b in 0..2 {
            dg[a][b] = axpy(&jet.d2[a][b], x3, &ddn[a][b]);
        }
        dg[2][a] = dn[a];
        dg[a][2] = dn[a];
    }
    let mut christoffel = [[[z; 3]; 3]; 3];
    for (k, gk) in christoffel.iter_mut().enumerate() {
        for i in 0..3 {
            for j in i..3 {
                // symmetric by construction: computed once, mirrored exactly
                gk[i][j] = dot(&contra[k], &dg[i][j]);
                gk[j][i] = gk[i][j];
            }
        }
    }
    ShellPoint {
        position: axpy(&jet.point, x3, &normal),
        covariant_basis: g,
        contravariant_basis: contra,
        metric,
        inverse_metric,
        sqrt_g,
        christoffel,
    }
}

/// The shell chart `Theta = sigma + x3 N` over a surface.
///
/// # Example
/// ```
/// use capstan_geometry::{CircularCylinder, ShellChart};
/// let chart = ShellChart::new(CircularCylinder::new(2.0_f64).unwrap());
/// let p = chart.point([0.0_f64, 0.3, 0.5]).unwrap();
/// // polar coordinates with r = 2 + x3: g_22 = r^2, Gamma^3_22 = -r, Gamma^2_23 = 1/r
/// assert!((p.metric[1][1] - 6.25).abs() < 1e-13);
/// assert!((p.christoffel[2][1][1] + 2.5).abs() < 1e-13);
/// assert!((p.christoffel[1][1][2] - 0.4).abs() < 1e-13);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ShellChart<S> {
    surface: S,
}

impl<S> ShellChart<S> {
    /// The shell chart over `surface`.
    pub fn new(surface: S) -> Self {
        Self { surface }
    }

    /// The underlying surface.
    pub fn surface(&self) -> &S {
        &self.surface
    }
}

impl<S> ShellChart<S> {
    /// The shell geometry at `x = (x1, x2, x3)`.
    ///
    /// # Errors
    /// See [`ShellPoint::from_jet`].
    pub fn point<F: Real>(&self, x: [F; 3]) -> Result<ShellPoint<F>, GeometryError>
    where
        S: Surface<F>,
    {
        ShellPoint::from_jet(&self.surface.jet([x[0], x[1]]), x)
    }

    /// The frame of the surface point `x = (x1, x2)`: everything [`ShellChart::point`] needs
    /// that does not depend on `x3`, so that many heights above one surface point cost one
    /// jet of `sigma` ([`ShellFrame::point`] equals [`ShellChart::point`] bit for bit).
    ///
    /// # Errors
    /// See [`ShellFrame::new`].
    pub fn frame<F: Real>(&self, x: [F; 2]) -> Result<ShellFrame<F>, GeometryError>
    where
        S: Surface<F>,
    {
        ShellFrame::new(&self.surface.jet(x), x)
    }

    /// The shell geometry at a point whose coordinates are any scalar `D` over `F`: with dual
    /// numbers seeded along a direction ([`ad::seed`]), every field of the point carries its
    /// exact derivative along it (`d_a g_ij`, `d_a Gamma^k_ij`: fourth derivatives of `sigma`,
    /// by nested forward-mode AD through [`Surface::sigma`]).
    ///
    /// # Errors
    /// Those of [`ShellChart::point`] at the real point (checked there).
    ///
    /// # Example
    /// ```
    /// use capstan_geometry::{ad, CircularCylinder, ShellChart};
    /// let chart = ShellChart::new(CircularCylinder::new(2.0_f64).unwrap());
    /// // along x3: g_22 = r^2 with r = 2 + x3, so d_3 g_22 = 2 r = 5 at x3 = 0.5
    /// let x = [ad::seed(0.0_f64, 0.0), ad::seed(0.3, 0.0), ad::seed(0.5, 1.0)];
    /// let p = chart.point_over(x).unwrap();
    /// assert!((ad::derivative_part(p.metric[1][1]) - 5.0).abs() < 1e-13);
    /// ```
    pub fn point_over<F: Real, D: Scalar<F>>(
        &self,
        x: [D; 3],
    ) -> Result<ShellPoint<D>, GeometryError>
    where
        S: Surface<F>,
    {
        self.point(x.map(ad::real_part::<F, D>))?;
        let jet = ad::surface_jet_over(|y| self.surface.sigma(y), [x[0], x[1]]);
        let (normal, dn, ddn) = normal_derivatives::<F, D>(&jet);
        Ok(shell_point_of::<F, D>(&jet, normal, &dn, &ddn, x[2]))
    }

    /// The frame of a surface point whose coordinates are any scalar `D` over `F`
    /// ([`ShellChart::frame`] over dual numbers): one jet of `sigma` at the dual point, reused
    /// by [`ShellFrame::point_over`] for every height above it. With `x2` seeded here, a column
    /// of points costs one dual jet of `sigma` instead of one per point.
    ///
    /// # Errors
    /// Those of [`ShellChart::frame`] at the real point.
    ///
    /// # Example
    /// ```
    /// use capstan_geometry::{ad, CircularCylinder, ShellChart};
    /// let chart = ShellChart::new(CircularCylinder::new(2.0_f64).unwrap());
    /// // x2 along the inner direction, x3 along the outer: g_22 = r^2, r = 2 + x3
    /// let d = |x: f64, inner: f64, outer: f64| ad::seed(ad::seed(x, inner), ad::seed(outer, 0.0));
    /// let frame = chart.frame_over([d(0.0, 0.0, 0.0), d(0.3, 1.0, 0.0)]).unwrap();
    /// let p = frame.point_over(d(0.5, 0.0, 1.0)).unwrap();
    /// let g22 = p.metric[1][1];
    /// let (d2, d3): (f64, f64) = (
    ///     ad::derivative_part(ad::value_part(g22)),
    ///     ad::value_part(ad::derivative_part(g22)),
    /// );
    /// assert!((d3 - 5.0).abs() < 1e-13); // d_3 g_22 = 2 r
    /// assert!(d2.abs() < 1e-13); // d_2 g_22 = 0
    /// ```
    pub fn frame_over<F: Real, D: Scalar<F>>(
        &self,
        x: [D; 2],
    ) -> Result<ShellFrame<D>, GeometryError>
    where
        S: Surface<F>,
    {
        self.frame(x.map(ad::real_part::<F, D>))?;
        let jet = ad::surface_jet_over(|y| self.surface.sigma(y), x);
        let (normal, dn, ddn) = normal_derivatives::<F, D>(&jet);
        Ok(ShellFrame {
            jet,
            at: x,
            normal,
            dn,
            ddn,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elliptical_prism::{CircularCylinder, EllipticalPrism};
    use crate::expression_profile::ExpressionProfile;
    use crate::prism::GeneralPrism;

    #[test]
    fn christoffel_scale_of_a_cylinder_is_the_largest_symbol() {
        // radius r + x3 = 2.5: Gamma^3_22 = -2.5, Gamma^2_23 = Gamma^2_32 = 1/2.5, the rest 0
        let p = ShellChart::new(CircularCylinder::new(2.0).unwrap())
            .point([0.3, 0.7, 0.5])
            .unwrap();
        assert!((p.christoffel_scale() - 2.5_f64).abs() < 1e-14); // closed form: round-off only
    }

    /// `frame(x1, x2).point(x3)` is the same computation as `point([x1, x2, x3])`: equal bit
    /// for bit, errors included.
    fn frame_equals_point<S: Surface<f64>>(chart: &ShellChart<S>, heights: &[f64]) {
        for x2 in [-1.2, -0.3, 0.0, 0.45, 1.1, 2.9] {
            let frame = chart.frame([0.7, x2]).unwrap();
            for &x3 in heights {
                let direct = chart.point([0.7, x2, x3]);
                let framed = frame.point(x3);
                match (direct, framed) {
                    (Ok(a), Ok(b)) => assert_eq!(a, b, "x2 {x2} x3 {x3}"),
                    (Err(a), Err(b)) => assert_eq!(a, b, "x2 {x2} x3 {x3}"),
                    (a, b) => panic!("x2 {x2} x3 {x3}: {a:?} against {b:?}"),
                }
            }
        }
    }

    #[test]
    fn frame_points_equal_chart_points_on_ellipse_and_expression_prism() {
        let heights = [0.0, 0.1, 0.37, 1.0, 2.5];
        frame_equals_point(
            &ShellChart::new(EllipticalPrism::new(2.0, 0.5).unwrap()),
            &heights,
        );
        let profile =
            ExpressionProfile::parse("2 * sin(t) + 0.3 * sin(2 * t)", "cos(t) + 0.1 * t^2")
                .unwrap();
        frame_equals_point(&ShellChart::new(GeneralPrism::new(profile)), &heights);
        // past the focal surface of a unit cylinder: the same error both ways
        frame_equals_point(
            &ShellChart::new(CircularCylinder::new(1.0).unwrap()),
            &[-0.5, -1.0, -1.5],
        );
    }

    /// `point_over` on dual coordinates: real parts equal `point` bit for bit, derivative
    /// parts equal central differences of `point` (h = 1e-5: truncation ~1e-10).
    fn dual_point_matches_differences<S: Surface<f64>>(chart: &ShellChart<S>) {
        let h = 1e-5;
        for x in [[0.3, -0.4, 0.1], [0.0, 0.9, 0.35], [0.5, 0.2, 0.0]] {
            for axis in 1..3 {
                let y = core::array::from_fn(|i| ad::seed(x[i], if i == axis { 1.0 } else { 0.0 }));
                let dual = chart.point_over(y).unwrap();
                let (mut xp, mut xm) = (x, x);
                xp[axis] += h;
                xm[axis] -= h;
                let (p, pp, pm) = (
                    chart.point(x).unwrap(),
                    chart.point(xp).unwrap(),
                    chart.point(xm).unwrap(),
                );
                let fields = |q: &ShellPoint<f64>| {
                    let mut v = vec![q.sqrt_g];
                    v.extend(q.metric.iter().flatten());
                    v.extend(q.inverse_metric.iter().flatten());
                    v.extend(q.christoffel.iter().flatten().flatten());
                    v
                };
                let mut duals = vec![dual.sqrt_g];
                duals.extend(dual.metric.iter().flatten());
                duals.extend(dual.inverse_metric.iter().flatten());
                duals.extend(dual.christoffel.iter().flatten().flatten());
                let (f, fp, fm) = (fields(&p), fields(&pp), fields(&pm));
                for (k, d) in duals.iter().enumerate() {
                    assert_eq!(ad::value_part(*d), f[k], "{x:?} field {k}");
                    let fd = (fp[k] - fm[k]) / (2.0 * h);
                    let exact = ad::derivative_part(*d);
                    assert!(
                        (exact - fd).abs() < 1e-8 * (1.0 + fd.abs()),
                        "{x:?} axis {axis} field {k}: {exact} against {fd}"
                    );
                }
            }
        }
    }

    #[test]
    fn dual_points_carry_exact_derivatives_on_ellipse_and_expression_prism() {
        dual_point_matches_differences(&ShellChart::new(EllipticalPrism::new(2.0, 0.5).unwrap()));
        let profile =
            ExpressionProfile::parse("2 * sin(t) + 0.3 * sin(2 * t)", "cos(t) + 0.1 * t^2")
                .unwrap();
        dual_point_matches_differences(&ShellChart::new(GeneralPrism::new(profile)));
    }

    /// `frame_over(x1, x2).point_over(x3)` on nested dual numbers (`x2` seeded in the inner
    /// part, `x3` in the outer) is the same computation as `point_over` at the same
    /// coordinates: equal bit for bit in every part; and both directions agree with the
    /// single-direction duals of `point_over`.
    #[test]
    fn dual_frame_points_equal_dual_chart_points() {
        type D2 = ad::Dual1<ad::Dual1<f64>>;
        let d = |x: f64, inner: f64, outer: f64| -> D2 {
            ad::seed(ad::seed(x, inner), ad::seed(outer, 0.0))
        };
        let parts = |q: &ShellPoint<D2>| {
            let mut v = vec![q.sqrt_g];
            v.extend(q.position);
            v.extend(q.metric.iter().flatten());
            v.extend(q.inverse_metric.iter().flatten());
            v.extend(q.christoffel.iter().flatten().flatten());
            v
        };
        let profile =
            ExpressionProfile::parse("2 * sin(t) + 0.3 * sin(2 * t)", "cos(t) + 0.1 * t^2")
                .unwrap();
        let prism = ShellChart::new(GeneralPrism::new(profile));
        let ellipse = ShellChart::new(EllipticalPrism::new(2.0, 0.5).unwrap());
        for x2 in [-0.4, 0.0, 0.9] {
            let frames = [
                ellipse
                    .frame_over([d(0.0, 0.0, 0.0), d(x2, 1.0, 0.0)])
                    .unwrap(),
                prism
                    .frame_over([d(0.0, 0.0, 0.0), d(x2, 1.0, 0.0)])
                    .unwrap(),
            ];
            for x3 in [0.0, 0.1, 0.35] {
                let x = [d(0.0, 0.0, 0.0), d(x2, 1.0, 0.0), d(x3, 0.0, 1.0)];
                for (frame, direct) in frames
                    .iter()
                    .zip([ellipse.point_over(x), prism.point_over(x)])
                {
                    let (a, b) = (
                        parts(&frame.point_over(x[2]).unwrap()),
                        parts(&direct.unwrap()),
                    );
                    assert_eq!(a, b, "x2 {x2} x3 {x3}");
                }
                // the two directions against single-direction duals
                let framed = parts(&frames[0].point_over(x[2]).unwrap());
                for axis in 1..3 {
                    let y = core::array::from_fn(|i| {
                        ad::seed([0.0, x2, x3][i], if i == axis { 1.0 } else { 0.0 })
                    });
                    let single = ellipse.point_over(y).unwrap();
                    let mut v = vec![single.sqrt_g];
                    v.extend(single.position);
                    v.extend(single.metric.iter().flatten());
                    v.extend(single.inverse_metric.iter().flatten());
                    v.extend(single.christoffel.iter().flatten().flatten());
                    for (k, (n, s)) in framed.iter().zip(&v).enumerate() {
                        let nested = if axis == 1 {
                            ad::derivative_part(ad::value_part(*n))
                        } else {
                            ad::value_part(ad::derivative_part(*n))
                        };
                        let e = ad::derivative_part(*s);
                        assert!(
                            (nested - e).abs() <= 1e-13 * (1.0 + e.abs()),
                            "axis {axis} field {k}"
                        );
                        assert!(
                            (ad::value_part(ad::value_part(*n)) - ad::value_part(*s)).abs()
                                <= 1e-14 * (1.0 + e.abs())
                        );
                    }
                }
            }
        }
        // past the focal surface of a unit cylinder: a typed error, as for the real point
        let cylinder = ShellChart::new(CircularCylinder::new(1.0).unwrap());
        let frame = cylinder
            .frame_over([d(0.0, 0.0, 0.0), d(0.3, 1.0, 0.0)])
            .unwrap();
        assert!(matches!(
            frame.point_over(d(-1.5, 0.0, 1.0)),
            Err(GeometryError::Degenerate { .. })
        ));
    }

    #[test]
    fn frame_rejects_a_degenerate_surface_point() {
        // (x1, 0, 0): a_2 = 0, no normal
        let chart = ShellChart::new(GeneralPrism::new(
            ExpressionProfile::parse("0 * t", "0 * t").unwrap(),
        ));
        assert!(matches!(
            chart.frame([0.0, 0.3]),
            Err(GeometryError::Degenerate { .. })
        ));
        assert!(matches!(
            chart.point([0.0, 0.3, 0.1]),
            Err(GeometryError::Degenerate { .. })
        ));
    }
}
