//! External force fields `(0, g_r2, g_r3)` on the membrane (Theorem 1).

use capstan_geometry::SurfaceGeometry;

/// An external force per unit length of membrane, in the curvilinear components of Theorem 1.
///
/// # Math
/// For a Euclidean force `q` per unit length at the point with tangent `a_2` and normal `N`:
/// ```text
/// g_r2 = q . a_2      covariant tangential component (per unit x2, = sqrt(a_22) q . t)
/// g_r3 = q . N        normal component (per unit length)
/// ```
/// These enter the prism equilibrium (eq. PrismEqn02) as
/// `dT/dx2 = mu sqrt(a_22) (kappa (T - c) - g_r3) - g_r2`, `c = rho_l V^2`.
pub trait LoadField {
    /// `[g_r2, g_r3]` at `x2 = theta`, given the surface's geometry there.
    fn load(&self, theta: f64, geometry: &SurfaceGeometry<f64>) -> [f64; 2];
}

/// No external force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct NoLoad;

impl LoadField for NoLoad {
    fn load(&self, _theta: f64, _geometry: &SurfaceGeometry<f64>) -> [f64; 2] {
        [0.0, 0.0]
    }
}

/// Gravity `(0, 0, -g)`: a force `q = (0, 0, -w)` per unit length, `w = rho h l g`.
///
/// # Math
/// `g_r2 = -w (a_2)_z`, `g_r3 = -w N_z`; on the cylinder `(x1, a sin t, a cos t)` this is the
/// paper's `(0, a w sin t, -w cos t)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity {
    /// Weight per unit length `w`.
    pub weight_per_length: f64,
}

impl LoadField for Gravity {
    fn load(&self, _theta: f64, g: &SurfaceGeometry<f64>) -> [f64; 2] {
        let w = self.weight_per_length;
        [-w * g.tangents[1][2], -w * g.normal[2]]
    }
}

impl<G: Fn(f64, &SurfaceGeometry<f64>) -> [f64; 2]> LoadField for G {
    fn load(&self, theta: f64, geometry: &SurfaceGeometry<f64>) -> [f64; 2] {
        self(theta, geometry)
    }
}
