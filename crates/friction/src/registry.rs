//! The registry of friction laws that scenes can name (`friction.law`).
//!
//! A law becomes usable from scenes by writing its file and registering it once: a
//! [`RegisteredLaw`] names the law, lists the scene keys under `[friction]` it reads and builds
//! its pointwise law from the scene's [`FrictionSettings`] (validating them). The built-in laws
//! register themselves in [`registry`]; a crate that embeds capstan adds its own with
//! [`register`] before it reads scenes. Nothing else changes: [`crate::AnyFrictionLaw`]
//! dispatches to whatever the registry built.
//!
//! # Example
//! A Coulomb law whose traction saturates at a shear strength `cap` (`friction.cap`), as
//! for a soft interlayer (the same code as in docs/guide.md):
//! ```
//! use capstan_friction::registry::{self, RegisteredLaw};
//! use capstan_friction::{ContactState, FrictionLaw, RegularisedCoulomb as C, RegularisedCoulombParams, TractionDerivatives};
//!
//! /// `t = min(1, cap / |mu p|) t_coulomb(u, p)`.
//! #[derive(Debug, Clone, Copy)]
//! struct Capped { coulomb: RegularisedCoulombParams<f64>, cap: f64 }
//! impl Capped {
//!     fn k(&self, c: &ContactState<f64>) -> f64 { (self.cap / (self.coulomb.mu() * c.normal_pressure).abs()).min(1.0) }
//! }
//! impl FrictionLaw<f64> for Capped {
//!     type Params = ();
//!     fn traction(&self, c: &ContactState<f64>, _: &()) -> [f64; 2] { C.traction(c, &self.coulomb).map(|t| self.k(c) * t) }
//!     fn traction_derivatives(&self, c: &ContactState<f64>, _: &()) -> TractionDerivatives<f64> {
//!         let (d, k) = (C.traction_derivatives(c, &self.coulomb), self.k(c));
//!         TractionDerivatives::new(d.d_slip.map(|r| r.map(|x| k * x)), if k < 1.0 { [0.0; 2] } else { d.d_pressure })
//!     }
//! }
//! registry::register(RegisteredLaw {
//!     name: "capped-coulomb",
//!     summary: "Coulomb friction capped at a shear strength `cap`",
//!     parameters: &["mu", "eps", "cap"],
//!     build: |s| {
//!         let cap = registry::check("friction.cap", s.get_or("cap", f64::INFINITY), "(0, inf]", |v| v > 0.0)?;
//!         Ok(registry::bind(Capped { coulomb: RegularisedCoulombParams::new(s.mu, s.eps)?, cap }, ()))
//!     },
//! })
//! .unwrap();
//!
//! // a scene's `[friction]` table: law = "capped-coulomb", mu = 0.5, cap = 0.2
//! use capstan_friction::{AnyFrictionLaw, AnyFrictionParams, FrictionSettings};
//! let mut settings = FrictionSettings::default();
//! settings.extra.insert("cap".into(), 0.2);
//! let any = AnyFrictionParams::new("capped-coulomb", &settings).unwrap();
//! let t = AnyFrictionLaw.traction(&ContactState::new([1.0, 0.0], -2.0), &any);
//! assert!((t[0] + 0.2).abs() < 1e-15); // mu |p| = 1 is capped at 0.2
//! ```

use std::collections::BTreeMap;
use std::fmt::Debug;
use std::sync::{Arc, LazyLock, RwLock};

use crate::error::FrictionError;
use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};

pub use crate::error::check;

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

/// The built-in laws, in the order of [`names`].
fn builtin() -> Vec<&'static RegisteredLaw> {
    vec![
        &crate::regularised_coulomb::REGISTRATION,
        &crate::smooth_coulomb::REGISTRATION,
        &crate::tresca::REGISTRATION,
        &crate::howell::REGISTRATION,
        &crate::orthotropic_coulomb::REGISTRATION,
        &crate::frictionless::REGISTRATION,
    ]
}

static REGISTRY: LazyLock<RwLock<Vec<&'static RegisteredLaw>>> =
    LazyLock::new(|| RwLock::new(builtin()));

fn laws() -> std::sync::RwLockReadGuard<'static, Vec<&'static RegisteredLaw>> {
    REGISTRY
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Every registered law, built-ins first, then in the order of [`register`].
pub fn registry() -> Vec<&'static RegisteredLaw> {
    laws().clone()
}

/// The law named `name`, if registered.
pub fn find(name: &str) -> Option<&'static RegisteredLaw> {
    laws().iter().copied().find(|l| l.name == name)
}

/// The registered names, comma-separated (for error messages).
pub fn names() -> String {
    laws().iter().map(|l| l.name).collect::<Vec<_>>().join(", ")
}

/// Whether `key` (without the `friction.` prefix) is a parameter of some registered law.
pub fn is_parameter(key: &str) -> bool {
    laws().iter().any(|l| l.parameters.contains(&key))
}

/// Adds `law` to the registry, so that scenes can name it.
///
/// # Errors
/// [`FrictionError::DuplicateLaw`] if a law of that name is registered already.
pub fn register(law: RegisteredLaw) -> Result<(), FrictionError> {
    let mut all = REGISTRY
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if all.iter().any(|l| l.name == law.name) {
        return Err(FrictionError::DuplicateLaw { name: law.name });
    }
    all.push(Box::leak(Box::new(law)));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtins_are_registered_under_their_scene_names() {
        assert_eq!(
            names(),
            "coulomb, smooth-coulomb, tresca, howell, orthotropic-coulomb, frictionless"
        );
        assert!(find("amontons").is_none());
        assert!(is_parameter("axis_angle") && !is_parameter("law"));
        let err = register(crate::tresca::REGISTRATION).unwrap_err();
        assert!(matches!(
            err,
            FrictionError::DuplicateLaw { name: "tresca" }
        ));
    }

    #[test]
    fn settings_read_fields_then_extra_then_the_default() {
        let mut s = FrictionSettings {
            bound: 0.25,
            ..Default::default()
        };
        s.extra.insert("cap".into(), 3.0);
        assert_eq!(s.get_or("bound", 9.0), 0.25);
        assert_eq!(s.get_or("cap", 9.0), 3.0);
        assert_eq!(s.get_or("stiffness", 9.0), 9.0);
    }
}
