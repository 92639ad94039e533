//! What a friction law registers: its name, its scene parameters and how to build it from
//! the scene's values ([`RegisteredLaw`]), the values ([`FrictionSettings`]) and the law with
//! its parameters bound ([`DynFrictionLaw`]). The registry itself is [`crate::registry`].

use std::collections::BTreeMap;
use std::fmt::Debug;
use std::sync::Arc;

use crate::error::FrictionError;
use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};

/// The values of a scene's `[friction]` table that the laws draw their parameters from.
///
/// The six keys of the built-in laws are fields; any other numeric key of the table (a
/// parameter of a law registered outside this crate) is in `extra`.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionSettings {
    /// `friction.mu`: `mu` (Coulomb laws), `mu'` (Howell), `mu_1` (orthotropic).
    pub mu: f64,
    /// `friction.eps`: regularisation width (physical slip length).
    pub eps: f64,
    /// `friction.mu2`: `mu_2` of the orthotropic law.
    pub mu2: f64,
    /// `friction.axis_angle`: first orthotropy axis from the slip frame's first axis (radians).
    pub axis_angle: f64,
    /// `friction.bound`: the Tresca bound `g`.
    pub bound: f64,
    /// `friction.exponent`: Howell's `n`.
    pub exponent: f64,
    /// Every other key of `[friction]` (parameters of laws registered elsewhere).
    pub extra: BTreeMap<String, f64>,
}

impl Default for FrictionSettings {
    fn default() -> Self {
        Self {
            mu: 0.5,
            eps: 1e-5,
            mu2: 0.5,
            axis_angle: 0.0,
            bound: 0.5,
            exponent: 1.0,
            extra: BTreeMap::new(),
        }
    }
}

impl FrictionSettings {
    /// The value of `key` (without the `friction.` prefix): a field, an `extra` entry, or
    /// `default` when the table does not give it.
    pub fn get_or(&self, key: &str, default: f64) -> f64 {
        match key {
            "mu" => self.mu,
            "eps" => self.eps,
            "mu2" => self.mu2,
            "axis_angle" => self.axis_angle,
            "bound" => self.bound,
            "exponent" => self.exponent,
            other => self.extra.get(other).copied().unwrap_or(default),
        }
    }
}

/// A pointwise friction law with its parameters bound: what a scene's law is at run time.
///
/// Every [`FrictionLaw`] over `f64` with its parameters is one ([`bind`]).
pub trait DynFrictionLaw: Send + Sync + Debug {
    /// [`FrictionLaw::traction`] with the bound parameters.
    fn traction(&self, contact: &ContactState<f64>) -> [f64; 2];
    /// [`FrictionLaw::traction_derivatives`] with the bound parameters.
    fn traction_derivatives(&self, contact: &ContactState<f64>) -> TractionDerivatives<f64>;
}

#[derive(Debug)]
struct Bound<L, P> {
    law: L,
    params: P,
}

impl<L, P> DynFrictionLaw for Bound<L, P>
where
    L: FrictionLaw<f64, Params = P> + Send + Sync + Debug,
    P: Send + Sync + Debug + Clone,
{
    fn traction(&self, contact: &ContactState<f64>) -> [f64; 2] {
        self.law.traction(contact, &self.params)
    }
    fn traction_derivatives(&self, contact: &ContactState<f64>) -> TractionDerivatives<f64> {
        self.law.traction_derivatives(contact, &self.params)
    }
}

/// `law` with its `params`, as the registry stores it.
pub fn bind<L, P>(law: L, params: P) -> Arc<dyn DynFrictionLaw>
where
    L: FrictionLaw<f64, Params = P> + Send + Sync + Debug + 'static,
    P: Send + Sync + Debug + Clone + 'static,
{
    Arc::new(Bound { law, params })
}

/// A friction law that scenes can name.
#[derive(Debug, Clone, Copy)]
pub struct RegisteredLaw {
    /// The value of `friction.law` that selects it (e.g. `"coulomb"`).
    pub name: &'static str,
    /// One line for listings and docs.
    pub summary: &'static str,
    /// The keys under `[friction]` it reads (without the `friction.` prefix).
    pub parameters: &'static [&'static str],
    /// Builds the law from the scene's values, validating those it reads.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming the scene key of the first bad value.
    pub build: fn(&FrictionSettings) -> Result<Arc<dyn DynFrictionLaw>, FrictionError>,
}
