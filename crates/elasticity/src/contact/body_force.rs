//! A body force on the thick body of either dimension, in physical components along the
//! body's coordinate lines (scene key `loads.body_force`).

use core::fmt;
use std::sync::Arc;

use crate::plane_problem::BodyForce;
use crate::shell_geometry::ShellGeometry;
use crate::solid::SolidForce;

/// The physical components `[f<1>, f<2>, f<3>]` at the curvilinear point `(x1, x2, x3)`.
type Components = Arc<dyn Fn([f64; 3]) -> [f64; 3] + Send + Sync>;

/// A body force density (force per unit volume) on the thick body, given by its physical
/// components along the unit covariant base vectors of the shell chart
/// `Theta = sigma(x1, x2) + x3 N`.
///
/// # Math
/// With `g_i = d Theta / d x^i`, `g_ij = g_i . g_j` and the physical components `f<j>`:
/// ```text
/// F   = sum_j f<j> g_j / |g_j|                   the force vector (per unit volume)
/// f_i = F . g_i = sum_j f<j> g_ij / sqrt(g_jj)   its covariant components
/// ```
/// The Navier equations `nabla_i T^i_j + f_j = 0` take the covariant `f_j`. On an orthogonal
/// chart (every prism, and the circular cone) `f_i = sqrt(g_ii) f<i>`: `f<2>` pulls along the
/// belt (toward `theta_max`), `f<3>` outward through the thickness, `f<1>` along the generators.
///
/// Physical components are what a load on a belt is stated in: their unit is force per volume
/// whatever the parametrisation (`x2` is an angle on a circle, so the covariant `f_2` would
/// carry a length, and it changes with the radius of the layer `x3`), and a constant `f<2>`
/// is a uniform drag along the belt on any obstacle. Plane strain uses `f<2>`, `f<3>` on the
/// plane `x1 = 0` of the prism (where `g_12 = g_13 = 0`, so `f<1>` plays no part).
///
/// # Example
/// ```
/// use capstan_elasticity::contact::BodyForceField;
/// let drag = BodyForceField::physical(|x| [0.0, 0.5 * x[2], 0.0]);
/// assert_eq!(drag.components([0.0, 0.1, 2.0]), [0.0, 1.0, 0.0]);
/// // on a metric diag(1, 4, 1) (a circle of radius 2 at x3 = 0) f_2 = 2 f<2>
/// let metric = [[1.0, 0.0, 0.0], [0.0, 4.0, 0.0], [0.0, 0.0, 1.0]];
/// assert_eq!(drag.covariant([0.0, 0.1, 2.0], &metric), [0.0, 2.0, 0.0]);
/// ```
#[derive(Clone)]
pub struct BodyForceField {
    components: Components,
}

impl fmt::Debug for BodyForceField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BodyForceField").finish_non_exhaustive()
    }
}

impl BodyForceField {
    /// The force with physical components `components(x) = [f<1>, f<2>, f<3>]` at
    /// `x = (x1, x2, x3)`.
    pub fn physical(components: impl Fn([f64; 3]) -> [f64; 3] + Send + Sync + 'static) -> Self {
        Self {
            components: Arc::new(components),
        }
    }

    /// `[f<1>, f<2>, f<3>]` at `x`.
    pub fn components(&self, x: [f64; 3]) -> [f64; 3] {
        (self.components)(x)
    }

    /// The same force times `s` (a load magnitude).
    pub fn scaled(&self, s: f64) -> Self {
        let inner = Arc::clone(&self.components);
        Self::physical(move |x| inner(x).map(|f| s * f))
    }

    /// The covariant components `f_i = sum_j f<j> g_ij / sqrt(g_jj)` at `x`, for the metric
    /// `g_ij` there.
    pub fn covariant(&self, x: [f64; 3], metric: &[[f64; 3]; 3]) -> [f64; 3] {
        let f = self.components(x);
        let mut out = [0.0; 3];
        for (i, o) in out.iter_mut().enumerate() {
            for j in 0..3 {
                if f[j] != 0.0 {
                    *o += f[j] * metric[i][j] / metric[j][j].sqrt();
                }
            }
        }
        out
    }

    /// The covariant body force `[f_2, f_3]` at `(x2, x3)` of a plane-strain body on
    /// `chart` (at `x1 = 0`), as the plane discretisations take it. A point where the chart
    /// is degenerate gives NaN, which the discretisations report as
    /// [`crate::ElasticityError::NonFinite`].
    pub fn plane<G: ShellGeometry + Send + Sync + 'static>(&self, chart: G) -> BodyForce {
        let force = self.clone();
        Arc::new(move |x: [f64; 2]| {
            let at = [0.0, x[0], x[1]];
            match chart.shell_point(at) {
                Ok(p) => {
                    let f = force.covariant(at, &p.metric);
                    [f[1], f[2]]
                }
                Err(_) => [f64::NAN; 2],
            }
        })
    }

    /// The covariant body force `[f_1, f_2, f_3]` at `(x1, x2, x3)` of a 3-D body on `chart`,
    /// as [`crate::solid::SolidNavier`] takes it (NaN where the chart is degenerate).
    pub fn solid<G: ShellGeometry + Send + Sync + 'static>(&self, chart: G) -> SolidForce {
        let force = self.clone();
        Arc::new(move |x: [f64; 3]| match chart.shell_point(x) {
            Ok(p) => force.covariant(x, &p.metric),
            Err(_) => [f64::NAN; 3],
        })
    }
}
