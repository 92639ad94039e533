//! Isotropic linear elastic material.

use crate::error::ElasticityError;

/// An isotropic linear elastic material given by Young's modulus and Poisson's ratio.
///
/// # Math
/// ```text
/// lambda = nu E / ((1 + nu)(1 - 2 nu))        first Lamé parameter
/// mu     = E / (2 (1 + nu))                   second Lamé parameter (shear modulus)
/// A^ijkl = lambda g^ij g^kl + mu (g^ik g^jl + g^il g^jk)
/// ```
///
/// # Example
/// ```
/// use capstan_elasticity::Material;
/// let m = Material::new(1e3, 0.25).unwrap();
/// assert!((m.lambda() - 400.0).abs() < 1e-12);
/// assert!((m.mu() - 400.0).abs() < 1e-12);
/// assert!(Material::new(1e3, 0.5).is_err());
/// ```
///
/// # References
/// Paper §3 (elasticity tensor and Lamé parameters).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Material {
    young: f64,
    poisson: f64,
}

impl Material {
    /// A material with Young's modulus `young = E` and Poisson's ratio `poisson = nu`.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `young` unless `E` is finite and
    /// `> 0`, or `poisson` unless `-1 < nu < 1/2` (scenes: `body.young`, `body.poisson`).
    pub fn new(young: f64, poisson: f64) -> Result<Self, ElasticityError> {
        if !(young.is_finite() && young > 0.0) {
            return Err(ElasticityError::InvalidParameter {
                field: "young",
                value: young,
                allowed: "(0, inf)",
            });
        }
        if !(poisson > -1.0 && poisson < 0.5) {
            return Err(ElasticityError::InvalidParameter {
                field: "poisson",
                value: poisson,
                allowed: "(-1, 1/2)",
            });
        }
        Ok(Self { young, poisson })
    }

    /// Young's modulus `E`.
    pub fn young(&self) -> f64 {
        self.young
    }

    /// Poisson's ratio `nu`.
    pub fn poisson(&self) -> f64 {
        self.poisson
    }

    /// First Lamé parameter `lambda = nu E / ((1 + nu)(1 - 2 nu))`.
    pub fn lambda(&self) -> f64 {
        let (e, nu) = (self.young, self.poisson);
        nu * e / ((1.0 + nu) * (1.0 - 2.0 * nu))
    }

    /// Second Lamé parameter (shear modulus) `mu = E / (2 (1 + nu))`.
    pub fn mu(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    /// The curvilinear elasticity tensor `A^ijkl` for the inverse metric `g^ij`.
    #[allow(clippy::needless_range_loop)] // index loops mirror A^ijkl
    pub fn elasticity_tensor(&self, inverse_metric: &[[f64; 3]; 3]) -> [[[[f64; 3]; 3]; 3]; 3] {
        let (lambda, mu) = (self.lambda(), self.mu());
        let g = inverse_metric;
        let mut a = [[[[0.0; 3]; 3]; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    for l in 0..3 {
                        a[i][j][k][l] = lambda * g[i][j] * g[k][l]
                            + mu * (g[i][k] * g[j][l] + g[i][l] * g[j][k]);
                    }
                }
            }
        }
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_rejects_bad_young_and_poisson() {
        for e in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                Material::new(e, 0.3),
                Err(ElasticityError::InvalidParameter { field: "young", .. })
            ));
        }
        for nu in [0.5, -1.0, 0.7, f64::NAN] {
            let err = Material::new(1.0, nu).unwrap_err();
            assert!(matches!(
                err,
                ElasticityError::InvalidParameter {
                    field: "poisson",
                    ..
                }
            ));
            assert!(err.to_string().contains("(-1, 1/2)"));
        }
    }

    #[test]
    fn lame_constants_match_closed_form() {
        let m = Material::new(210.0, 0.3).unwrap();
        // E = mu (3 lambda + 2 mu) / (lambda + mu): round-off only
        let (l, mu) = (m.lambda(), m.mu());
        assert!((mu * (3.0 * l + 2.0 * mu) / (l + mu) - 210.0).abs() < 1e-12);
        assert!((l / (2.0 * (l + mu)) - 0.3).abs() < 1e-15);
    }
}
