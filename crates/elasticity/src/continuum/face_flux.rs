//! The flux of a natural boundary condition through a coordinate face `x_a = const`.

use capstan_geometry::ShellPoint;

use crate::error::ElasticityError;

/// The data of a natural boundary condition at a point of a face, one component `j`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FaceData {
    /// A traction `t_j` per unit physical area of the face.
    Traction(f64),
    /// A mixed stress component `T^a_j` (`a` the face's normal direction).
    Stress(f64),
}

/// The flux `phi_j` of the weak form, per unit parameter area of the face `x_a = const` with
/// outward sign `sign` (`-1` at the lower face, `+1` at the upper):
///
/// # Math
/// ```text
/// traction t_j:   phi_j = sqrt(g) sqrt(g^aa) t_j      (dS = sqrt(g) sqrt(g^aa) dx_b dx_c)
/// stress T^a_j:   phi_j = sign sqrt(g) T^a_j
/// ```
///
/// # Errors
/// [`ElasticityError::NonFinite`] (`"boundary traction"`, at `at`) for a non-finite flux.
pub fn face_flux(
    p: &ShellPoint<f64>,
    a: usize,
    sign: f64,
    data: FaceData,
    at: [f64; 2],
) -> Result<f64, ElasticityError> {
    let flux = match data {
        FaceData::Traction(t) => p.sqrt_g * p.inverse_metric[a][a].sqrt() * t,
        FaceData::Stress(s) => sign * p.sqrt_g * s,
    };
    if !flux.is_finite() {
        return Err(ElasticityError::NonFinite {
            what: "boundary traction",
            at,
        });
    }
    Ok(flux)
}
