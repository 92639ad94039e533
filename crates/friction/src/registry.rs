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

use std::sync::{LazyLock, RwLock};

use crate::error::FrictionError;

pub use crate::error::check;
pub use crate::nonsmooth_law::{DynNonsmoothLaw, RegisteredNonsmoothLaw, bind_nonsmooth};
pub use crate::registration::{DynFrictionLaw, FrictionSettings, RegisteredLaw, bind};

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

/// The built-in nonsmooth laws, in the order of [`nonsmooth_names`].
fn builtin_nonsmooth() -> Vec<&'static RegisteredNonsmoothLaw> {
    vec![
        &crate::exact_coulomb::REGISTRATION,
        &crate::exact_orthotropic_coulomb::REGISTRATION,
    ]
}

static NONSMOOTH: LazyLock<RwLock<Vec<&'static RegisteredNonsmoothLaw>>> =
    LazyLock::new(|| RwLock::new(builtin_nonsmooth()));

fn nonsmooth_laws() -> std::sync::RwLockReadGuard<'static, Vec<&'static RegisteredNonsmoothLaw>> {
    NONSMOOTH
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
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

/// Whether `key` (without the `friction.` prefix) is a parameter of some registered law,
/// smooth or nonsmooth.
pub fn is_parameter(key: &str) -> bool {
    laws().iter().any(|l| l.parameters.contains(&key))
        || nonsmooth_laws().iter().any(|l| l.parameters.contains(&key))
}

/// Every registered nonsmooth law (exact Coulomb, ...), built-ins first.
pub fn nonsmooth_registry() -> Vec<&'static RegisteredNonsmoothLaw> {
    nonsmooth_laws().clone()
}

/// The nonsmooth law named `name`, if registered.
pub fn find_nonsmooth(name: &str) -> Option<&'static RegisteredNonsmoothLaw> {
    nonsmooth_laws().iter().copied().find(|l| l.name == name)
}

/// The registered nonsmooth names, comma-separated.
pub fn nonsmooth_names() -> String {
    nonsmooth_laws()
        .iter()
        .map(|l| l.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Every registered name, smooth then nonsmooth, comma-separated (the values of
/// `friction.law`).
pub fn all_names() -> String {
    let mut names = names();
    for l in nonsmooth_laws().iter() {
        names.push_str(", ");
        names.push_str(l.name);
    }
    names
}

/// Whether `name` is a registered law of either kind.
pub fn is_registered(name: &str) -> bool {
    find(name).is_some() || find_nonsmooth(name).is_some()
}

/// Adds the nonsmooth `law` to the registry, so that scenes can name it.
///
/// # Errors
/// [`FrictionError::DuplicateLaw`] if a law of that name (smooth or nonsmooth) is registered
/// already.
pub fn register_nonsmooth(law: RegisteredNonsmoothLaw) -> Result<(), FrictionError> {
    let smooth_taken = find(law.name).is_some();
    let mut all = NONSMOOTH
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if smooth_taken || all.iter().any(|l| l.name == law.name) {
        return Err(FrictionError::DuplicateLaw { name: law.name });
    }
    all.push(Box::leak(Box::new(law)));
    Ok(())
}

/// Adds `law` to the registry, so that scenes can name it.
///
/// # Errors
/// [`FrictionError::DuplicateLaw`] if a law of that name is registered already.
pub fn register(law: RegisteredLaw) -> Result<(), FrictionError> {
    let mut all = REGISTRY
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if all.iter().any(|l| l.name == law.name) || find_nonsmooth(law.name).is_some() {
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
    fn nonsmooth_builtins_are_registered_and_names_are_unique() {
        assert_eq!(
            nonsmooth_names(),
            "exact-coulomb, exact-orthotropic-coulomb"
        );
        assert!(is_registered("exact-coulomb") && is_registered("coulomb"));
        assert!(find("exact-coulomb").is_none() && find_nonsmooth("coulomb").is_none());
        assert!(all_names().ends_with("frictionless, exact-coulomb, exact-orthotropic-coulomb"));
        // a name is taken across both kinds
        let mut clash = crate::exact_coulomb::REGISTRATION;
        clash.name = "tresca";
        assert!(matches!(
            register_nonsmooth(clash),
            Err(FrictionError::DuplicateLaw { name: "tresca" })
        ));
        assert!(register_nonsmooth(crate::exact_coulomb::REGISTRATION).is_err());
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
