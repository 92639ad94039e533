//! The loads of a contact model: the paper's end tractions ([`EndLoads`]) and the names
//! (scene keys) of the entries of a model's load list.

use crate::contact::error::ContactError;
use crate::error::ElasticityError;

/// End tractions `T^2_2 = tau0` at `x2 = theta0` and `T^2_2 = tau_max` at `x2 = theta1`: the
/// paper's load, the first two entries ([`END_LOADS`]) of a contact model's load list.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EndLoads {
    /// `tau0` (the paper's minimum traction).
    pub tau0: f64,
    /// `tau_max`.
    pub tau_max: f64,
}

impl EndLoads {
    /// The loads `(tau0, tau_max)`.
    pub fn new(tau0: f64, tau_max: f64) -> Self {
        Self { tau0, tau_max }
    }

    /// `tau0 = 1`, `tau_max = ratio`.
    pub fn ratio(ratio: f64) -> Self {
        Self::new(1.0, ratio)
    }

    /// `tau_max / tau0`.
    pub fn tension_ratio(&self) -> f64 {
        self.tau_max / self.tau0
    }

    /// Both loads times `s`.
    pub fn scaled(&self, s: f64) -> Self {
        Self::new(s * self.tau0, s * self.tau_max)
    }

    /// The magnitudes of [`END_LOADS`], in that order: `[tau0, tau_max]`.
    pub fn magnitudes(&self) -> [f64; 2] {
        [self.tau0, self.tau_max]
    }

    /// `max(|tau0|, |tau_max|)`.
    pub fn magnitude(&self) -> f64 {
        self.tau0.abs().max(self.tau_max.abs())
    }

    pub(crate) fn check(&self) -> Result<(), ContactError> {
        for (field, value) in [("loads.tau0", self.tau0), ("loads.tau_max", self.tau_max)] {
            if !value.is_finite() {
                return Err(ContactError::from(ElasticityError::InvalidParameter {
                    field,
                    value,
                    allowed: "finite values",
                }));
            }
        }
        Ok(())
    }
}

/// The loads of the paper's body, by scene key: the end tractions `tau0` at `x2 = theta0`
/// and `tau_max` at `x2 = theta1` ([`EndLoads`]).
pub const END_LOADS: [&str; 2] = ["loads.tau0", "loads.tau_max"];

/// The name (scene key) of a body's body force in its contact model's load list
/// ([`crate::contact::BodyForceField`]), after [`END_LOADS`].
pub const BODY_FORCE: &str = "loads.body_force";
