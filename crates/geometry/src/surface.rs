//! The `Surface` trait: a parametrised surface `sigma(x1, x2)` and everything derived from it.

use crate::ad::{self, Jet3, SurfaceJet};
use crate::error::GeometryError;
use crate::scalar::{Real, Scalar};
use crate::vector::{cross, dot, inverse2, is_finite, norm, scale};

/// Relative size of `|a_1 x a_2|` against `|a_1| |a_2|` below which the normal is undefined.
const DEGENERACY_TOLERANCE: f64 = 1e-12;

/// The differential geometry of a surface at one point, derived from its [`SurfaceJet`].
///
/// # Math
/// ```text
/// a_a   = d_a sigma                               tangent basis
/// N     = a_1 x a_2 / |a_1 x a_2|                 unit normal
/// a_ab  = a_a . a_b,   a^ab = (a_ab)^-1           first fundamental form and inverse
/// b_ab  = N . d_a d_b sigma                       second fundamental form
/// b^a_b = a^ac b_cb                               mixed (shape operator)
/// H     = -1/2 b^a_a                              mean curvature (paper's sign)
/// K     = det(b_ab) / det(a_ab)                   Gaussian curvature
/// Gamma^c_ab = a^cd a_d . d_a a_b                 surface Christoffel symbols
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceGeometry<F> {
    /// `sigma(x)`.
    pub point: [F; 3],
    /// `tangents[a] = a_a`.
    pub tangents: [[F; 3]; 2],
    /// Unit normal `N`.
    pub normal: [F; 3],
    /// `first_form[a][b] = a_ab`.
    pub first_form: [[F; 2]; 2],
    /// `first_form_inverse[a][b] = a^ab`.
    pub first_form_inverse: [[F; 2]; 2],
    /// `second_form[a][b] = b_ab`.
    pub second_form: [[F; 2]; 2],
    /// `mixed_second_form[a][b] = b^a_b`.
    pub mixed_second_form: [[F; 2]; 2],
    /// `H = -1/2 b^a_a`.
    pub mean_curvature: F,
    /// `K = det(b^a_b)`.
    pub gaussian_curvature: F,
    /// `christoffel[c][a][b] = Gamma^c_ab` of the surface.
    pub christoffel: [[[F; 2]; 2]; 2],
}

impl<F: Real> SurfaceGeometry<F> {
    /// Derives the geometry from the derivatives of `sigma` at `x`.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] if the jet is not finite; [`GeometryError::Degenerate`] if a
    /// tangent vanishes or the tangents are parallel (normal undefined).
    #[allow(clippy::needless_range_loop)] // index loops mirror Gamma^c_ab and b^a_b
    pub fn from_jet(jet: &SurfaceJet<F>, x: [F; 2]) -> Result<Self, GeometryError> {
        let at = point3(x, F::zero());
        let t = jet.d1;
        let ln = check_regular(jet, at)?;
        let n = cross(&t[0], &t[1]);
        let normal = scale(F::one() / ln, &n);
        let first_form = [
            [dot(&t[0], &t[0]), dot(&t[0], &t[1])],
            [dot(&t[1], &t[0]), dot(&t[1], &t[1])],
        ];
        let first_form_inverse = inverse2(&first_form).ok_or(GeometryError::Degenerate {
            what: "singular first fundamental form",
            at,
        })?;
        let second_form = [
            [dot(&normal, &jet.d2[0][0]), dot(&normal, &jet.d2[0][1])],
            [dot(&normal, &jet.d2[1][0]), dot(&normal, &jet.d2[1][1])],
        ];
        let mut mixed = [[F::zero(); 2]; 2];
        for a in 0..2 {
            for b in 0..2 {
                mixed[a][b] = first_form_inverse[a][0] * second_form[0][b]
                    + first_form_inverse[a][1] * second_form[1][b];
            }
        }
        let half = crate::scalar::real::<F>(0.5);
        let mean_curvature = -half * (mixed[0][0] + mixed[1][1]);
        let gaussian_curvature = mixed[0][0] * mixed[1][1] - mixed[0][1] * mixed[1][0];
        // Contravariant tangents a^c = a^cd a_d, then Gamma^c_ab = a^c . d_a d_b sigma.
        let contra = [
            [0, 1, 2]
                .map(|k| first_form_inverse[0][0] * t[0][k] + first_form_inverse[0][1] * t[1][k]),
            [0, 1, 2]
                .map(|k| first_form_inverse[1][0] * t[0][k] + first_form_inverse[1][1] * t[1][k]),
        ];
        let mut christoffel = [[[F::zero(); 2]; 2]; 2];
        for (c, gc) in christoffel.iter_mut().enumerate() {
            for a in 0..2 {
                for b in 0..2 {
                    gc[a][b] = dot(&contra[c], &jet.d2[a][b]);
                }
            }
        }
        let geometry = Self {
            point: jet.point,
            tangents: t,
            normal,
            first_form,
            first_form_inverse,
            second_form,
            mixed_second_form: mixed,
            mean_curvature,
            gaussian_curvature,
            christoffel,
        };
        if !(is_finite(&geometry.normal)
            && geometry.mean_curvature.is_finite()
            && geometry.gaussian_curvature.is_finite())
        {
            return Err(GeometryError::NonFinite {
                what: "curvature",
                at,
            });
        }
        Ok(geometry)
    }
}

/// Checks that the jet is finite and the tangents span a plane; returns `|a_1 x a_2|`.
pub(crate) fn check_regular<F: Real>(
    jet: &SurfaceJet<F>,
    at: [f64; 3],
) -> Result<F, GeometryError> {
    if !jet.is_finite() {
        return Err(GeometryError::NonFinite {
            what: "sigma or its derivatives",
            at,
        });
    }
    let t = &jet.d1;
    let (l0, l1, ln) = (norm(&t[0]), norm(&t[1]), norm(&cross(&t[0], &t[1])));
    if l0 == F::zero() || l1 == F::zero() {
        return Err(GeometryError::Degenerate {
            what: "zero tangent vector",
            at,
        });
    }
    if ln <= crate::scalar::real::<F>(DEGENERACY_TOLERANCE) * l0 * l1 {
        return Err(GeometryError::Degenerate {
            what: "parallel tangents: normal undefined",
            at,
        });
    }
    Ok(ln)
}

pub(crate) fn point3<F: Real>(x: [F; 2], x3: F) -> [f64; 3] {
    [x[0], x[1], x3].map(|v| v.to_f64().unwrap_or(f64::NAN))
}

/// A parametrised surface `sigma(x1, x2)` in Euclidean space E^3.
///
/// Implement only [`Surface::sigma`], generically over the scalar: every other quantity is
/// derived from it with exact derivatives by forward-mode automatic differentiation. An
/// implementation may override [`Surface::jet`] with closed-form derivatives (a fast path);
/// such an override must be tested equal to the default.
///
/// # Example
/// A new obstacle, a paraboloidal trough `(x1, x2, -x2^2/2)`:
/// ```
/// use capstan_geometry::{Real, Scalar, Surface};
/// struct Trough;
/// impl Surface<f64> for Trough {
///     fn sigma<S: Scalar<f64>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
///         [x1, x2, x2 * x2 * (-0.5)]
///     }
/// }
/// // N = (0, x2, 1)/sqrt(1 + x2^2); at x2 = 0 the curvature is 1, so H = 1/2 with the paper's sign.
/// let g = Trough.geometry([0.0, 0.0]).unwrap();
/// assert!((g.mean_curvature - 0.5).abs() < 1e-15);
/// assert!(g.gaussian_curvature.abs() < 1e-15);
/// ```
pub trait Surface<F: Real> {
    /// `sigma(x1, x2)`, the surface in E^3, written once for every scalar type.
    fn sigma<S: Scalar<F>>(&self, x: [S; 2]) -> [S; 3];

    /// `sigma` and its exact partial derivatives up to third order, by forward-mode AD
    /// through [`Surface::sigma`]. Override only with closed forms tested equal to this.
    fn jet(&self, x: [F; 2]) -> SurfaceJet<F> {
        ad::surface_jet(|y: [Jet3<F>; 2]| self.sigma(y), x)
    }

    /// Every first- and second-order quantity of the surface at `x`.
    ///
    /// # Errors
    /// See [`SurfaceGeometry::from_jet`].
    fn geometry(&self, x: [F; 2]) -> Result<SurfaceGeometry<F>, GeometryError> {
        SurfaceGeometry::from_jet(&self.jet(x), x)
    }

    /// Tangent basis `a_a = d_a sigma`.
    ///
    /// # Errors
    /// See [`SurfaceGeometry::from_jet`].
    fn tangents(&self, x: [F; 2]) -> Result<[[F; 3]; 2], GeometryError> {
        Ok(self.geometry(x)?.tangents)
    }

    /// Unit normal `N = a_1 x a_2 / |a_1 x a_2|`.
    ///
    /// # Errors
    /// See [`SurfaceGeometry::from_jet`].
    fn normal(&self, x: [F; 2]) -> Result<[F; 3], GeometryError> {
        Ok(self.geometry(x)?.normal)
    }

    /// First fundamental form `a_ab`.
    ///
    /// # Errors
    /// See [`SurfaceGeometry::from_jet`].
    fn first_fundamental_form(&self, x: [F; 2]) -> Result<[[F; 2]; 2], GeometryError> {
        Ok(self.geometry(x)?.first_form)
    }

    /// Second fundamental form `b_ab = N . d_a d_b sigma`.
    ///
    /// # Errors
    /// See [`SurfaceGeometry::from_jet`].
    fn second_fundamental_form(&self, x: [F; 2]) -> Result<[[F; 2]; 2], GeometryError> {
        Ok(self.geometry(x)?.second_form)
    }

    /// Mean curvature `H = -1/2 b^a_a` (positive on a convex obstacle with outward normal).
    ///
    /// # Errors
    /// See [`SurfaceGeometry::from_jet`].
    fn mean_curvature(&self, x: [F; 2]) -> Result<F, GeometryError> {
        Ok(self.geometry(x)?.mean_curvature)
    }

    /// Gaussian curvature `K = det(b^a_b)`.
    ///
    /// # Errors
    /// See [`SurfaceGeometry::from_jet`].
    fn gaussian_curvature(&self, x: [F; 2]) -> Result<F, GeometryError> {
        Ok(self.geometry(x)?.gaussian_curvature)
    }

    /// Surface Christoffel symbols `Gamma^c_ab`, indexed `[c][a][b]`.
    ///
    /// # Errors
    /// See [`SurfaceGeometry::from_jet`].
    fn christoffel(&self, x: [F; 2]) -> Result<[[[F; 2]; 2]; 2], GeometryError> {
        Ok(self.geometry(x)?.christoffel)
    }
}

impl<F: Real, T: Surface<F> + ?Sized> Surface<F> for &T {
    fn sigma<S: Scalar<F>>(&self, x: [S; 2]) -> [S; 3] {
        (**self).sigma(x)
    }
    fn jet(&self, x: [F; 2]) -> SurfaceJet<F> {
        (**self).jet(x)
    }
}
