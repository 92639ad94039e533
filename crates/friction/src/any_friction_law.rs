//! One friction-law type for every law: enum dispatch, so a contact problem that is generic
//! over [`FrictionLaw`] can take the law from a scene file (`friction.law`).

use capstan_geometry::Real;

use crate::Frictionless;
use crate::error::FrictionError;
use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};
use crate::howell::{Howell, HowellParams};
use crate::orthotropic_coulomb::{OrthotropicCoulomb, OrthotropicCoulombParams};
use crate::regularised_coulomb::{RegularisedCoulomb, RegularisedCoulombParams};
use crate::smooth_coulomb::{SmoothCoulomb, SmoothCoulombParams};
use crate::tresca::{Tresca, TrescaParams};

/// The friction laws by name (the values of the scene key `friction.law`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FrictionLawKind {
    /// `coulomb`: [`RegularisedCoulomb`] (Kikuchi–Oden).
    Coulomb,
    /// `smooth-coulomb`: [`SmoothCoulomb`].
    SmoothCoulomb,
    /// `tresca`: [`Tresca`].
    Tresca,
    /// `howell`: [`Howell`].
    Howell,
    /// `orthotropic-coulomb`: [`OrthotropicCoulomb`].
    OrthotropicCoulomb,
    /// `frictionless`: [`Frictionless`].
    Frictionless,
}

impl FrictionLawKind {
    /// Every kind, in the order of [`FrictionLawKind::NAMES`].
    pub const ALL: [Self; 6] = [
        Self::Coulomb,
        Self::SmoothCoulomb,
        Self::Tresca,
        Self::Howell,
        Self::OrthotropicCoulomb,
        Self::Frictionless,
    ];
    /// The accepted names, for error messages.
    pub const NAMES: &'static str =
        "coulomb, smooth-coulomb, tresca, howell, orthotropic-coulomb, frictionless";

    /// The kind called `name` (one of [`FrictionLawKind::NAMES`]), or `None`.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
    /// The scene name.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Coulomb => "coulomb",
            Self::SmoothCoulomb => "smooth-coulomb",
            Self::Tresca => "tresca",
            Self::Howell => "howell",
            Self::OrthotropicCoulomb => "orthotropic-coulomb",
            Self::Frictionless => "frictionless",
        }
    }
}

/// The scalar settings every law draws its parameters from (scene table `[friction]`).
#[derive(Debug, Clone, Copy, PartialEq)]
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
        }
    }
}

/// The parameters of any law; the variant selects the law [`AnyFrictionLaw`] applies.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum AnyFrictionParams<F> {
    /// [`RegularisedCoulomb`].
    Coulomb(RegularisedCoulombParams<F>),
    /// [`SmoothCoulomb`].
    SmoothCoulomb(SmoothCoulombParams<F>),
    /// [`Tresca`].
    Tresca(TrescaParams<F>),
    /// [`Howell`].
    Howell(HowellParams<F>),
    /// [`OrthotropicCoulomb`].
    OrthotropicCoulomb(OrthotropicCoulombParams<F>),
    /// [`Frictionless`].
    Frictionless,
}

impl<F: Real> AnyFrictionParams<F> {
    /// The parameters of law `kind` drawn from `settings`.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming the scene key of the first bad value the law
    /// uses (values it does not use are not checked).
    pub fn new(kind: FrictionLawKind, settings: &FrictionSettings) -> Result<Self, FrictionError> {
        let f = |x: f64| capstan_geometry::real::<F>(x);
        let s = settings;
        Ok(match kind {
            FrictionLawKind::Coulomb => {
                Self::Coulomb(RegularisedCoulombParams::new(f(s.mu), f(s.eps))?)
            }
            FrictionLawKind::SmoothCoulomb => {
                Self::SmoothCoulomb(SmoothCoulombParams::new(f(s.mu), f(s.eps))?)
            }
            FrictionLawKind::Tresca => Self::Tresca(TrescaParams::new(f(s.bound), f(s.eps))?),
            FrictionLawKind::Howell => {
                Self::Howell(HowellParams::new(f(s.mu), f(s.exponent), f(s.eps))?)
            }
            FrictionLawKind::OrthotropicCoulomb => Self::OrthotropicCoulomb(
                OrthotropicCoulombParams::new([f(s.mu), f(s.mu2)], f(s.axis_angle), f(s.eps))?,
            ),
            FrictionLawKind::Frictionless => Self::Frictionless,
        })
    }
    /// Which law these parameters select.
    pub fn kind(&self) -> FrictionLawKind {
        match self {
            Self::Coulomb(_) => FrictionLawKind::Coulomb,
            Self::SmoothCoulomb(_) => FrictionLawKind::SmoothCoulomb,
            Self::Tresca(_) => FrictionLawKind::Tresca,
            Self::Howell(_) => FrictionLawKind::Howell,
            Self::OrthotropicCoulomb(_) => FrictionLawKind::OrthotropicCoulomb,
            Self::Frictionless => FrictionLawKind::Frictionless,
        }
    }
}

/// Every friction law behind one type: the law applied is the one the parameters' variant
/// names, so `ContactModel<D, AnyFrictionLaw>` takes its law from a scene at run time.
///
/// # Example
/// ```
/// use capstan_friction::{AnyFrictionLaw, AnyFrictionParams, ContactState, FrictionLaw,
///     FrictionLawKind, FrictionSettings, Tresca, TrescaParams};
/// let settings = FrictionSettings { bound: 0.3, ..Default::default() };
/// let any = AnyFrictionParams::new(FrictionLawKind::parse("tresca").unwrap(), &settings).unwrap();
/// let c = ContactState::new([0.1, 0.0], -2.0);
/// let direct = Tresca.traction(&c, &TrescaParams::new(0.3, 1e-5).unwrap());
/// assert_eq!(AnyFrictionLaw.traction(&c, &any), direct);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AnyFrictionLaw;

impl<F: Real> FrictionLaw<F> for AnyFrictionLaw {
    type Params = AnyFrictionParams<F>;

    fn traction(&self, c: &ContactState<F>, p: &Self::Params) -> [F; 2] {
        match p {
            AnyFrictionParams::Coulomb(q) => RegularisedCoulomb.traction(c, q),
            AnyFrictionParams::SmoothCoulomb(q) => SmoothCoulomb.traction(c, q),
            AnyFrictionParams::Tresca(q) => Tresca.traction(c, q),
            AnyFrictionParams::Howell(q) => Howell.traction(c, q),
            AnyFrictionParams::OrthotropicCoulomb(q) => OrthotropicCoulomb.traction(c, q),
            AnyFrictionParams::Frictionless => FrictionLaw::<F>::traction(&Frictionless, c, &()),
        }
    }

    fn traction_derivatives(
        &self,
        c: &ContactState<F>,
        p: &Self::Params,
    ) -> TractionDerivatives<F> {
        match p {
            AnyFrictionParams::Coulomb(q) => RegularisedCoulomb.traction_derivatives(c, q),
            AnyFrictionParams::SmoothCoulomb(q) => SmoothCoulomb.traction_derivatives(c, q),
            AnyFrictionParams::Tresca(q) => Tresca.traction_derivatives(c, q),
            AnyFrictionParams::Howell(q) => Howell.traction_derivatives(c, q),
            AnyFrictionParams::OrthotropicCoulomb(q) => {
                OrthotropicCoulomb.traction_derivatives(c, q)
            }
            AnyFrictionParams::Frictionless => {
                FrictionLaw::<F>::traction_derivatives(&Frictionless, c, &())
            }
        }
    }
}
