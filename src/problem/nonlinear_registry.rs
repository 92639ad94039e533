//! The registry of nonlinear (contact) methods that scenes name (`solver.nonlinear`).
//!
//! A method is registered once: a [`RegisteredNonlinearMethod`] gives its name (and aliases),
//! a one-line summary, the `[solver]` keys it reads with their defaults and ranges, and a
//! builder that makes the [`SolveMethod`] from the scene's [`NonlinearSettings`], validating
//! them. The built-ins (`auto`, `newton`, `full-newton`, `jacobi-newton`) register in
//! [`registry`]; a program adds its own with [`register`] before it reads scenes (e.g. a
//! preset of a method with its own backend), and `solver.nonlinear` names it at once. An
//! unknown name is refused with the registered ones listed.
//!
//! # Example
//! ```
//! use capstan::problem::nonlinear_registry::{self, NonlinearSettings, RegisteredNonlinearMethod};
//! use capstan::problem::SolveMethod;
//! use capstan::solvers::LinearBackend;
//! // the full-system Newton with a Cholesky step, whatever `solver.linear` says
//! let _ = nonlinear_registry::register(RegisteredNonlinearMethod {
//!     name: "full-newton-cholesky",
//!     aliases: &[],
//!     summary: "full-system Newton, each step by sparse Cholesky",
//!     parameters: &[],
//!     build: |_| Ok(SolveMethod::FullNewton("cholesky".parse().unwrap())),
//! });
//! let settings = NonlinearSettings { linear: LinearBackend::LU };
//! let method = nonlinear_registry::build("full-newton-cholesky", &settings).unwrap();
//! assert_eq!(method, SolveMethod::FullNewton("cholesky".parse().unwrap()));
//! // the built-in names are unchanged
//! assert_eq!(nonlinear_registry::build("newton", &settings).unwrap(), SolveMethod::Condensed);
//! let e = nonlinear_registry::build("newtn", &settings).unwrap_err().to_string();
//! assert!(e.contains("auto, newton, full-newton, jacobi-newton"), "{e}");
//! ```

use std::sync::{LazyLock, RwLock};

use capstan_elasticity::solvers::LinearBackend;

use super::solve::ProblemError;
use super::solver::SolveMethod;

/// The values of a scene's `[solver]` table a nonlinear method draws its data from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NonlinearSettings {
    /// `solver.linear`: the registered linear backend (the step solver of `full-newton`).
    pub linear: LinearBackend,
}

/// One `[solver]` key a nonlinear method reads: the key without `solver.`, its default and
/// its allowed values, as text for help and error messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NonlinearParameter {
    /// The key (`linear`).
    pub key: &'static str,
    /// The default (`lu`).
    pub default: &'static str,
    /// The allowed values.
    pub allowed: &'static str,
}

/// A nonlinear method scenes can name: registered once, listed in [`registry`].
#[derive(Debug, Clone, Copy)]
pub struct RegisteredNonlinearMethod {
    /// The scene name (`full-newton`).
    pub name: &'static str,
    /// Other names accepted for it.
    pub aliases: &'static [&'static str],
    /// One line for help texts.
    pub summary: &'static str,
    /// The `[solver]` keys it reads, with defaults and ranges.
    pub parameters: &'static [NonlinearParameter],
    /// Builds the method from the settings, validating them.
    pub build: fn(&NonlinearSettings) -> Result<SolveMethod, ProblemError>,
}

impl RegisteredNonlinearMethod {
    /// Whether `name` is this method's name or one of its aliases.
    pub fn answers_to(&self, name: &str) -> bool {
        self.name == name || self.aliases.contains(&name)
    }
}

/// `solver.linear` as the step solver of `full-newton`.
const LINEAR: NonlinearParameter = NonlinearParameter {
    key: "linear",
    default: "lu",
    allowed: "any registered linear backend (capstan_solvers::linear_registry)",
};

/// `auto` in the nonlinear registry ([`SolveMethod::Auto`]).
const AUTO: RegisteredNonlinearMethod = RegisteredNonlinearMethod {
    name: "auto",
    aliases: &[],
    summary: "chosen by the body (condensed; full-system Newton with LU for unilateral contact)",
    parameters: &[],
    build: |_| Ok(SolveMethod::Auto),
};

/// `newton` in the nonlinear registry ([`SolveMethod::Condensed`]).
const NEWTON: RegisteredNonlinearMethod = RegisteredNonlinearMethod {
    name: "newton",
    aliases: &[],
    summary: "boundary-only Newton on the contact tractions condensed onto the contact face",
    parameters: &[LINEAR],
    build: |_| Ok(SolveMethod::Condensed),
};

/// `full-newton` in the nonlinear registry ([`SolveMethod::FullNewton`]).
const FULL_NEWTON: RegisteredNonlinearMethod = RegisteredNonlinearMethod {
    name: "full-newton",
    aliases: &[],
    summary: "Newton on the full residual, each step by `solver.linear` (grid sequencing in 2-D)",
    parameters: &[LINEAR],
    build: |s| Ok(SolveMethod::FullNewton(s.linear)),
};

/// `jacobi-newton` in the nonlinear registry ([`SolveMethod::JacobiNewton`]).
const JACOBI_NEWTON: RegisteredNonlinearMethod = RegisteredNonlinearMethod {
    name: "jacobi-newton",
    aliases: &[],
    summary: "the paper's Jacobi-Newton (damped Jacobi, relaxation 1/2)",
    parameters: &[],
    build: |_| Ok(SolveMethod::JacobiNewton),
};

/// The built-in methods, in the order of [`names`].
fn builtin() -> Vec<&'static RegisteredNonlinearMethod> {
    vec![&AUTO, &NEWTON, &FULL_NEWTON, &JACOBI_NEWTON]
}

static REGISTRY: LazyLock<RwLock<Vec<&'static RegisteredNonlinearMethod>>> =
    LazyLock::new(|| RwLock::new(builtin()));

fn all() -> std::sync::RwLockReadGuard<'static, Vec<&'static RegisteredNonlinearMethod>> {
    REGISTRY
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Every registered method, built-ins first, then in the order of [`register`].
pub fn registry() -> Vec<&'static RegisteredNonlinearMethod> {
    all().clone()
}

/// The method named `name` (or aliased so), if registered.
pub fn find(name: &str) -> Option<&'static RegisteredNonlinearMethod> {
    all().iter().copied().find(|m| m.answers_to(name))
}

/// The registered names, comma-separated (for error messages).
pub fn names() -> String {
    all().iter().map(|m| m.name).collect::<Vec<_>>().join(", ")
}

/// The method named `name`, built from `settings`.
///
/// # Errors
/// [`ProblemError::UnknownNonlinearMethod`] for a name not registered (listing the registered
/// ones); the builder's errors.
pub fn build(name: &str, settings: &NonlinearSettings) -> Result<SolveMethod, ProblemError> {
    let entry = find(name).ok_or_else(|| ProblemError::UnknownNonlinearMethod {
        name: name.to_owned(),
        known: names(),
    })?;
    (entry.build)(settings)
}

/// Adds `method` to the registry, so that scenes can name it.
///
/// # Errors
/// [`ProblemError::DuplicateNonlinearMethod`] if its name or an alias is taken already.
pub fn register(method: RegisteredNonlinearMethod) -> Result<(), ProblemError> {
    let mut all = REGISTRY
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let taken = std::iter::once(method.name)
        .chain(method.aliases.iter().copied())
        .find(|n| all.iter().any(|m| m.answers_to(n)));
    if let Some(name) = taken {
        return Err(ProblemError::DuplicateNonlinearMethod { name });
    }
    all.push(Box::leak(Box::new(method)));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_names_build_the_methods_they_always_did() {
        let lu = NonlinearSettings::default();
        let gs = NonlinearSettings {
            linear: "gauss-seidel".parse().unwrap(),
        };
        assert_eq!(build("auto", &lu).unwrap(), SolveMethod::Auto);
        assert_eq!(build("newton", &gs).unwrap(), SolveMethod::Condensed);
        assert_eq!(
            build("full-newton", &gs).unwrap(),
            SolveMethod::FullNewton(gs.linear)
        );
        assert_eq!(
            build("jacobi-newton", &lu).unwrap(),
            SolveMethod::JacobiNewton
        );
        assert!(names().starts_with("auto, newton, full-newton, jacobi-newton"));
    }

    #[test]
    fn unknown_and_duplicate_names_are_refused() {
        let e = build("newtn", &NonlinearSettings::default()).unwrap_err();
        assert!(matches!(e, ProblemError::UnknownNonlinearMethod { .. }));
        assert!(e.to_string().contains("`newtn`"), "{e}");
        let duplicate = RegisteredNonlinearMethod {
            name: "another",
            aliases: &["newton"],
            summary: "",
            parameters: &[],
            build: |_| Ok(SolveMethod::Condensed),
        };
        assert!(matches!(
            register(duplicate),
            Err(ProblemError::DuplicateNonlinearMethod { name: "newton" })
        ));
        assert!(find("another").is_none());
    }
}
