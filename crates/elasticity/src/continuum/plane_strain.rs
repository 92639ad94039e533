//! Whether a shell chart admits the plane-strain reduction (`d_1 = 0`, `v^1 = 0`).

use capstan_geometry::ShellPoint;

use crate::error::ElasticityError;

/// Relative tolerance of the plane-strain check, against the largest metric entry (or
/// Christoffel symbol) plus one.
pub const PLANE_STRAIN_TOLERANCE: f64 = 1e-10;

/// Checks that the chart is `x1`-invariant at `p`: the plane-strain reduction needs
/// `g_12 = g_13 = 0` and every Christoffel symbol with an index 1 zero (a prism).
///
/// # Math
/// ```text
/// |g_1a| <= tol (1 + max |g_ij|)                     a = 2, 3
/// |Gamma^1_ij|, |Gamma^i_1j| <= tol (1 + max |Gamma^k_ij|)
/// ```
///
/// # Errors
/// [`ElasticityError::NotPlaneStrain`] naming the failing quantity and the point `at`.
pub fn check_plane_strain(p: &ShellPoint<f64>, at: [f64; 3]) -> Result<(), ElasticityError> {
    let gscale = 1.0
        + p.metric
            .iter()
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()));
    if p.metric[0][1].abs() > PLANE_STRAIN_TOLERANCE * gscale
        || p.metric[0][2].abs() > PLANE_STRAIN_TOLERANCE * gscale
    {
        return Err(ElasticityError::NotPlaneStrain {
            what: "g_12 or g_13 is not zero",
            at,
        });
    }
    let cscale = 1.0 + p.christoffel_scale();
    let index_one = (0..3).any(|i| {
        (0..3).any(|j| {
            p.christoffel[0][i][j].abs() > PLANE_STRAIN_TOLERANCE * cscale
                || p.christoffel[i][0][j].abs() > PLANE_STRAIN_TOLERANCE * cscale
        })
    });
    if index_one {
        return Err(ElasticityError::NotPlaneStrain {
            what: "a Christoffel symbol with index 1 is not zero",
            at,
        });
    }
    Ok(())
}
