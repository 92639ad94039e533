//! An independent 3-D check of Theorem 2: a string along a geodesic of any surface.

use capstan_geometry::Surface;

use crate::error::FrictionError;
use crate::ode::Dop853;

/// The tension of a string (or a narrow strip) lying along a geodesic of a surface, at
/// limiting equilibrium, integrated with the surface's Christoffel symbols and second
/// fundamental form from the geometry layer.
///
/// # Math
/// A string along a geodesic has no tangential curvature, so only the normal reaction
/// `R = kappa_n T` acts and `dT/ds = mu R`:
/// ```text
/// x^k'' + Gamma^k_ij x^i' x^j' = 0                 geodesic (' = d/ds)
/// d ln T / ds = mu kappa_n,   kappa_n = -b_ij x^i' x^j' / a_ij x^i' x^j'
/// ```
/// integrated in `x2` as the independent variable (valid while `dx2/ds > 0`). On a cone
/// the membrane strip of Theorem 2 lies along such geodesics (straight lines of the
/// development), so this checks Theorem 2 without the development map.
#[derive(Debug, Clone, Copy)]
pub struct GeodesicStrip<'a, S: ?Sized> {
    surface: &'a S,
    mu: f64,
    ode: Dop853<f64>,
}

impl<'a, S: Surface<f64> + ?Sized> GeodesicStrip<'a, S> {
    /// A strip with friction coefficient `mu` on `surface`, integrated to `1e-13`.
    pub fn new(surface: &'a S, mu: f64) -> Self {
        Self {
            surface,
            mu,
            ode: Dop853 {
                rel_tol: 1e-13,
                abs_tol: 1e-13,
                ..Default::default()
            },
        }
    }

    /// The unit direction at `x` perpendicular to `a_1` with `dx2/ds > 0` (the development's
    /// straight line crossing the generator at right angles, on a cone).
    ///
    /// # Errors
    /// A geometry error at `x`.
    pub fn perpendicular_to_generator(&self, x: [f64; 2]) -> Result<[f64; 2], FrictionError> {
        let g = self.surface.geometry(x)?;
        let a = g.first_form;
        let p = [-a[0][1] / a[0][0], 1.0];
        let n =
            (a[0][0] * p[0] * p[0] + 2.0 * a[0][1] * p[0] * p[1] + a[1][1] * p[1] * p[1]).sqrt();
        Ok([p[0] / n, p[1] / n])
    }

    /// `ln T(x2 = theta_i) - ln T(start)` along the geodesic from `start` with contravariant
    /// unit direction `direction`, at each `thetas[i]` (either side of `start[1]`).
    ///
    /// # Errors
    /// Geometry errors; [`FrictionError::NonFinite`] if the geodesic turns back
    /// (`dx2/ds <= 0`); integrator errors.
    #[allow(clippy::needless_range_loop)] // mirrors Gamma^k_ij p^i p^j
    pub fn log_tension(
        &self,
        start: [f64; 2],
        direction: [f64; 2],
        thetas: &[f64],
    ) -> Result<Vec<f64>, FrictionError> {
        let rhs = |t: f64, y: &[f64; 4]| -> Result<[f64; 4], FrictionError> {
            let g = self.surface.geometry([y[0], t])?;
            let p = [y[1], y[2]];
            if p[1] <= 0.0 {
                return Err(FrictionError::NonFinite {
                    what: "geodesic (turns back: dx2/ds <= 0)",
                    angle: t,
                });
            }
            let quad = |m: &[[f64; 2]; 2]| {
                let mut s = 0.0;
                for i in 0..2 {
                    for j in 0..2 {
                        s += m[i][j] * p[i] * p[j];
                    }
                }
                s
            };
            let speed2 = quad(&g.first_form);
            let kappa_n = -quad(&g.second_form) / speed2;
            Ok([
                p[0] / p[1],
                -quad(&g.christoffel[0]) / p[1],
                -quad(&g.christoffel[1]) / p[1],
                self.mu * kappa_n * speed2.sqrt() / p[1],
            ])
        };
        let y0 = [start[0], direction[0], direction[1], 0.0];
        let lo = thetas.iter().copied().fold(start[1], f64::min);
        let hi = thetas.iter().copied().fold(start[1], f64::max);
        let up = self.ode.integrate(rhs, start[1], y0, hi)?;
        let down = self.ode.integrate(rhs, start[1], y0, lo)?;
        Ok(thetas
            .iter()
            .map(|&t| {
                if t >= start[1] {
                    up.eval(t)[3]
                } else {
                    down.eval(t)[3]
                }
            })
            .collect())
    }
}
