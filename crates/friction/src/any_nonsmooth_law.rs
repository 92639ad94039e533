//! One nonsmooth-law type for every registered nonsmooth law: a semismooth solver that is
//! generic over [`NonsmoothFrictionLaw`] takes the law a scene names (`friction.law`) from the
//! [`crate::registry`].

use std::sync::Arc;

use crate::error::FrictionError;
use crate::nonsmooth_law::{
    DynNonsmoothLaw, NonsmoothFrictionLaw, Projection, RegisteredNonsmoothLaw,
};
use crate::registration::FrictionSettings;

/// The parameters of any registered nonsmooth law, built from a scene's settings.
#[derive(Debug, Clone)]
pub struct AnyNonsmoothParams {
    registration: &'static RegisteredNonsmoothLaw,
    law: Arc<dyn DynNonsmoothLaw>,
}

impl AnyNonsmoothParams {
    /// The nonsmooth law called `name` with its parameters drawn from `settings`.
    ///
    /// # Errors
    /// [`FrictionError::UnknownLaw`] if no law of that name is registered;
    /// [`FrictionError::WrongLawKind`] if it names a smooth law;
    /// [`FrictionError::InvalidParameter`] naming the scene key of a bad value.
    pub fn new(name: &str, settings: &FrictionSettings) -> Result<Self, FrictionError> {
        let registration = crate::registry::find_nonsmooth(name).ok_or_else(|| {
            if crate::registry::find(name).is_some() {
                FrictionError::WrongLawKind {
                    name: name.to_string(),
                    kind: "a smooth law",
                    hint: "a semismooth solve needs a nonsmooth law (exact-coulomb, ...); smooth laws are solved by Newton",
                }
            } else {
                FrictionError::UnknownLaw {
                    name: name.to_string(),
                    allowed: crate::registry::all_names(),
                }
            }
        })?;
        Ok(Self {
            registration,
            law: (registration.build)(settings)?,
        })
    }

    /// The scene name of the law.
    pub fn name(&self) -> &'static str {
        self.registration.name
    }

    /// The law with its parameters bound.
    pub fn law(&self) -> &dyn DynNonsmoothLaw {
        &*self.law
    }
}

/// Every registered nonsmooth law behind one type, selected by [`AnyNonsmoothParams`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AnyNonsmoothLaw;

impl NonsmoothFrictionLaw<f64> for AnyNonsmoothLaw {
    type Params = AnyNonsmoothParams;

    fn project(
        &self,
        trial: [f64; 2],
        normal_pressure: f64,
        params: &Self::Params,
    ) -> Result<Projection<f64>, FrictionError> {
        params.law.project(trial, normal_pressure)
    }
}
