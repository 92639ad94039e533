//! The registry of discretisations that scenes can name (`discretisation.method`).
//!
//! A discretisation becomes usable from scenes by writing its file and registering it once: a
//! [`RegisteredDiscretisation`] names it, lists the keys of `[discretisation]` it reads and
//! builds its [`DiscretisationScheme`] (the variant with its data) from the scene's
//! [`DiscretisationSettings`], validating them. The built-in ones register in [`registry`]; a
//! crate that embeds capstan adds its own with [`register`] before it reads scenes. Nothing
//! else changes: a [`crate::contact::ThickBody`] (and a scene) with that
//! [`crate::finite_element::DiscretisationMethod`] builds through the registry.
//!
//! # Example
//! Finite differences registered again under another name (a real new method implements
//! [`crate::Discretisation`] and builds it in `build`):
//! ```
//! use std::sync::Arc;
//! use capstan_elasticity::registry::{self, DiscretisationScheme, RegisteredDiscretisation};
//! use capstan_elasticity::finite_element::DiscretisationMethod;
//! use capstan_elasticity::{Discretisation, FiniteDifferenceNavier, PlaneProblem, SharedChart};
//! use capstan_elasticity::{ElasticityError, registration::PlaneOperator};
//!
//! #[derive(Debug)]
//! struct MyFd;
//! impl DiscretisationScheme for MyFd {
//!     fn name(&self) -> &'static str { "my-fd" }
//!     fn build(&self, p: PlaneProblem<SharedChart>) -> Result<PlaneOperator, ElasticityError> {
//!         Ok(Box::new(FiniteDifferenceNavier::new(p)?))
//!     }
//! }
//! registry::register(RegisteredDiscretisation {
//!     name: "my-fd",
//!     summary: "second-order finite differences, registered again",
//!     parameters: &[],
//!     build: |_| Ok(Arc::new(MyFd)),
//! })
//! .unwrap();
//! let mut body = capstan_elasticity::contact::ThickBody::paper(21, 5).unwrap();
//! body.method = DiscretisationMethod::from_name("my-fd").unwrap();
//! assert_eq!(body.discretisation(1.0, 2.0).unwrap().dof_count(), 2 * 21 * 5);
//! ```

use std::sync::{Arc, LazyLock, RwLock};

use crate::error::ElasticityError;
use crate::finite_element::DiscretisationMethod;
use crate::plane_problem::PlaneProblem;
use crate::shell_geometry::ShellGeometry;

pub use crate::registration::{
    DiscretisationScheme, DiscretisationSettings, PlaneOperator, RegisteredDiscretisation,
    SchemeParameter,
};

/// The built-in discretisations, in the order of [`names`].
fn builtin() -> Vec<&'static RegisteredDiscretisation> {
    vec![
        &crate::schemes::FD_REGISTRATION,
        &crate::schemes::Q1_REGISTRATION,
        &crate::schemes::Q2_REGISTRATION,
        &crate::schemes::QP_REGISTRATION,
        &crate::schemes::QP_CORNER_REGISTRATION,
    ]
}

static REGISTRY: LazyLock<RwLock<Vec<&'static RegisteredDiscretisation>>> =
    LazyLock::new(|| RwLock::new(builtin()));

fn all() -> std::sync::RwLockReadGuard<'static, Vec<&'static RegisteredDiscretisation>> {
    REGISTRY
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Every registered discretisation, built-ins first, then in the order of [`register`].
pub fn registry() -> Vec<&'static RegisteredDiscretisation> {
    all().clone()
}

/// The discretisation named `name`, if registered.
pub fn find(name: &str) -> Option<&'static RegisteredDiscretisation> {
    all().iter().copied().find(|d| d.name == name)
}

/// The registered names, comma-separated (for error messages).
pub fn names() -> String {
    all().iter().map(|d| d.name).collect::<Vec<_>>().join(", ")
}

/// The variant named `name` built from `settings`.
///
/// # Errors
/// [`ElasticityError::UnknownDiscretisation`] for a name not registered; the builder's
/// errors (naming the scene key).
pub fn build(
    name: &str,
    settings: &DiscretisationSettings,
) -> Result<Arc<dyn DiscretisationScheme>, ElasticityError> {
    let entry = find(name).ok_or_else(|| ElasticityError::UnknownDiscretisation {
        name: name.to_owned(),
        known: names(),
    })?;
    (entry.build)(settings)
}

/// Adds `discretisation` to the registry, so that scenes can name it.
///
/// # Errors
/// [`ElasticityError::DuplicateDiscretisation`] if one of that name is registered already.
pub fn register(discretisation: RegisteredDiscretisation) -> Result<(), ElasticityError> {
    let mut all = REGISTRY
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if all.iter().any(|d| d.name == discretisation.name) {
        return Err(ElasticityError::DuplicateDiscretisation {
            name: discretisation.name,
        });
    }
    all.push(Box::leak(Box::new(discretisation)));
    Ok(())
}

impl DiscretisationMethod {
    /// The registered method of a name, `None` if none is registered under it.
    pub fn from_name(name: &str) -> Option<Self> {
        find(name).map(|entry| Self::registered(entry.name))
    }

    /// The variant with its data, built from `settings` by the registry (which validates
    /// them).
    ///
    /// # Errors
    /// The builder's errors, naming the scene key; [`ElasticityError::UnknownDiscretisation`]
    /// for a method no longer registered.
    pub fn scheme(
        self,
        settings: &DiscretisationSettings,
    ) -> Result<Arc<dyn DiscretisationScheme>, ElasticityError> {
        build(self.name(), settings)
    }

    /// Whether the assembled matrix is symmetric (and, with enough Dirichlet conditions,
    /// positive definite): the Cholesky backend applies. See
    /// [`DiscretisationScheme::is_symmetric`] (default settings).
    pub fn is_symmetric(self) -> bool {
        self.scheme(&DiscretisationSettings::default())
            .is_ok_and(|s| s.is_symmetric())
    }

    /// Builds the discretisation (`fem-qp` of order [`Self::DEFAULT_ORDER`]).
    ///
    /// # Errors
    /// The constructor's errors.
    pub fn build<G: ShellGeometry + Send + Sync + 'static>(
        self,
        problem: PlaneProblem<G>,
    ) -> Result<PlaneOperator, ElasticityError> {
        self.build_with_order(problem, Self::DEFAULT_ORDER)
    }

    /// Builds the discretisation; `order` is the `p` of `fem-qp` (ignored by the others).
    ///
    /// # Errors
    /// See [`Self::build`].
    pub fn build_with_order<G: ShellGeometry + Send + Sync + 'static>(
        self,
        problem: PlaneProblem<G>,
        order: usize,
    ) -> Result<PlaneOperator, ElasticityError> {
        let settings = DiscretisationSettings {
            order,
            ..Default::default()
        };
        self.scheme(&settings)?.build(problem.share_chart())
    }
}

impl core::str::FromStr for DiscretisationMethod {
    type Err = ElasticityError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_name(s).ok_or_else(|| ElasticityError::UnknownDiscretisation {
            name: s.to_owned(),
            known: names(),
        })
    }
}

impl serde::Serialize for DiscretisationMethod {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for DiscretisationMethod {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtins_are_registered_under_their_scene_names() {
        assert!(names().starts_with("fd, fem-q1, fem-q2, fem-qp"));
        assert!(find("fem-q3").is_none());
        let err = register(crate::schemes::FD_REGISTRATION).unwrap_err();
        assert!(matches!(
            err,
            ElasticityError::DuplicateDiscretisation { name: "fd" }
        ));
        let err = build("fem-q3", &DiscretisationSettings::default()).unwrap_err();
        assert!(err.to_string().contains("fem-qp"), "{err}");
    }

    #[test]
    fn every_builtin_builds_with_its_defaults_under_its_name() {
        for entry in registry() {
            let scheme = (entry.build)(&DiscretisationSettings::default()).unwrap();
            assert_eq!(scheme.name(), entry.name);
            assert!(!entry.summary.is_empty());
        }
    }
}
