//! One friction-law type for every registered law: a contact problem that is generic over
//! [`FrictionLaw`] takes the law a scene names (`friction.law`) from the [`crate::registry`].

use std::sync::Arc;

use crate::error::FrictionError;
use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};
use crate::registration::{DynFrictionLaw, FrictionSettings, RegisteredLaw};
use crate::registry;

/// A registered friction law, by name (the values of the scene key `friction.law`).
#[derive(Debug, Clone, Copy)]
pub struct FrictionLawKind(&'static RegisteredLaw);

impl PartialEq for FrictionLawKind {
    fn eq(&self, other: &Self) -> bool {
        self.0.name == other.0.name
    }
}

impl Eq for FrictionLawKind {}

impl FrictionLawKind {
    /// The law called `name`, if registered ([`registry::find`]).
    pub fn parse(name: &str) -> Option<Self> {
        registry::find(name).map(Self)
    }

    /// Every registered law, built-ins first.
    pub fn all() -> Vec<Self> {
        registry::registry().into_iter().map(Self).collect()
    }

    /// The registered names, comma-separated (for error messages).
    pub fn names() -> String {
        registry::names()
    }

    /// The scene name.
    pub fn name(&self) -> &'static str {
        self.0.name
    }

    /// The registration: summary, parameters, builder.
    pub fn registration(&self) -> &'static RegisteredLaw {
        self.0
    }
}

/// The parameters of any registered law: the law it names, built from a scene's settings.
#[derive(Debug, Clone)]
pub struct AnyFrictionParams {
    kind: FrictionLawKind,
    law: Arc<dyn DynFrictionLaw>,
}

impl AnyFrictionParams {
    /// The law called `name` with its parameters drawn from `settings`.
    ///
    /// # Errors
    /// [`FrictionError::UnknownLaw`] if no law of that name is registered;
    /// [`FrictionError::WrongLawKind`] if it names a nonsmooth law;
    /// [`FrictionError::InvalidParameter`] naming the scene key of the first bad value the law
    /// uses (values it does not use are not checked).
    pub fn new(name: &str, settings: &FrictionSettings) -> Result<Self, FrictionError> {
        let kind = FrictionLawKind::parse(name).ok_or_else(|| {
            if registry::find_nonsmooth(name).is_some() {
                FrictionError::WrongLawKind {
                    name: name.to_string(),
                    kind: "a nonsmooth law (a projection, no eps)",
                    hint: "it has no pointwise traction of the slip; solve it with a semismooth method (the membrane displacement model's `solve_semismooth`)",
                }
            } else {
                FrictionError::UnknownLaw {
                    name: name.to_string(),
                    allowed: registry::all_names(),
                }
            }
        })?;
        Self::of_kind(kind, settings)
    }

    /// The law `kind` with its parameters drawn from `settings`.
    ///
    /// # Errors
    /// See [`AnyFrictionParams::new`].
    pub fn of_kind(
        kind: FrictionLawKind,
        settings: &FrictionSettings,
    ) -> Result<Self, FrictionError> {
        Ok(Self {
            kind,
            law: (kind.0.build)(settings)?,
        })
    }

    /// Which law these parameters select.
    pub fn kind(&self) -> FrictionLawKind {
        self.kind
    }
}

/// Every registered friction law behind one type: the law applied is the one the parameters
/// name, so `ContactModel<D, AnyFrictionLaw>` takes its law from a scene at run time.
///
/// # Example
/// ```
/// use capstan_friction::{AnyFrictionLaw, AnyFrictionParams, ContactState, FrictionLaw,
///     FrictionSettings, Tresca, TrescaParams};
/// let settings = FrictionSettings { bound: 0.3, ..Default::default() };
/// let any = AnyFrictionParams::new("tresca", &settings).unwrap();
/// let c = ContactState::new([0.1, 0.0], -2.0);
/// let direct = Tresca.traction(&c, &TrescaParams::new(0.3, 1e-5).unwrap());
/// assert_eq!(AnyFrictionLaw.traction(&c, &any), direct);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AnyFrictionLaw;

impl FrictionLaw<f64> for AnyFrictionLaw {
    type Params = AnyFrictionParams;

    fn traction(&self, c: &ContactState<f64>, p: &Self::Params) -> [f64; 2] {
        p.law.traction(c)
    }

    fn traction_derivatives(
        &self,
        c: &ContactState<f64>,
        p: &Self::Params,
    ) -> TractionDerivatives<f64> {
        p.law.traction_derivatives(c)
    }
}
