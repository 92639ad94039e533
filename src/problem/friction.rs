//! The friction law of a [`super::Problem`], by its registered name.

use std::sync::Arc;

use capstan_elasticity::friction::nonsmooth_law::DynNonsmoothLaw;

use capstan_elasticity::friction::{
    AnyFrictionLaw, AnyFrictionParams, FrictionError, FrictionSettings,
};

/// A friction law by its registered name (`coulomb`, `tresca`, ..., or a law registered with
/// [`capstan_friction::registry::register`]) with the values it draws its parameters from;
/// `settings.eps` is also the stick/slip threshold of the reports (a node slides where
/// `|u| >= eps`).
#[derive(Debug, Clone, PartialEq)]
pub struct Friction {
    /// The registered name.
    pub law: String,
    /// `mu`, `eps` and the other laws' parameters.
    pub settings: FrictionSettings,
}

impl Default for Friction {
    /// Regularised Coulomb (Kikuchi–Oden), `mu = 1/2`, `eps = 1e-5`.
    fn default() -> Self {
        Self::coulomb(0.5, 1e-5)
    }
}

impl Friction {
    /// Regularised Coulomb friction `t = mu |sigma_n| u / max(|u|, eps)`.
    pub fn coulomb(mu: f64, eps: f64) -> Self {
        Self {
            law: "coulomb".into(),
            settings: FrictionSettings {
                mu,
                eps,
                ..Default::default()
            },
        }
    }

    /// The law registered as `law`, its parameters drawn from `settings`.
    pub fn named(law: impl Into<String>, settings: FrictionSettings) -> Self {
        Self {
            law: law.into(),
            settings,
        }
    }

    /// The law with its parameters bound, and the stick/slip threshold `eps`.
    ///
    /// # Errors
    /// [`FrictionError::UnknownLaw`] naming the registered laws; the law's own parameter
    /// checks.
    pub fn build(&self) -> Result<(AnyFrictionLaw, AnyFrictionParams, f64), FrictionError> {
        let params = AnyFrictionParams::new(&self.law, &self.settings)?;
        Ok((AnyFrictionLaw, params, self.settings.eps))
    }

    /// The nonsmooth law registered as `law` (exact Coulomb and its orthotropic variant,
    /// `capstan_friction::registry::register_nonsmooth`) with its parameters bound, or `None`
    /// for a smooth (regularised) law.
    ///
    /// # Errors
    /// The nonsmooth law's own parameter checks.
    pub fn nonsmooth(&self) -> Result<Option<Arc<dyn DynNonsmoothLaw>>, FrictionError> {
        capstan_elasticity::friction::registry::find_nonsmooth(&self.law)
            .map(|entry| (entry.build)(&self.settings))
            .transpose()
    }

    /// Whether `law` names a nonsmooth law ([`Friction::nonsmooth`]).
    pub fn is_nonsmooth(&self) -> bool {
        capstan_elasticity::friction::registry::find_nonsmooth(&self.law).is_some()
    }
}
