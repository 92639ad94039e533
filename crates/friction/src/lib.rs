//! Friction for capstan: pointwise friction laws for contact problems, and membrane capstan
//! models — the generalised capstan equation of the paper's section 2, forward and inverse.
//!
//! # Quick start
//! ```
//! use capstan_friction::membrane::{self, MembraneProblem};
//! use capstan_geometry::{CircularCylinder, Obstacle};
//! // a belt over half a cylinder: the capstan equation T_max / T0 = exp(mu pi)
//! let cylinder = Obstacle::Cylinder(CircularCylinder::new(1.0).unwrap());
//! let problem = MembraneProblem { mu: 0.3, t0: 1.0, theta0: 0.0, theta_max: std::f64::consts::PI, ..Default::default() };
//! let profile = membrane::tension_profile(&cylinder, &problem).unwrap();
//! assert!((profile.tension_ratio() - (0.3 * std::f64::consts::PI).exp()).abs() < 1e-12);
//! ```
//!
//! # Status
//! - [`FrictionLaw`] with [`RegularisedCoulomb`] (Kikuchi–Oden), [`SmoothCoulomb`],
//!   [`Tresca`], [`Howell`]'s power law, [`OrthotropicCoulomb`] and [`Frictionless`], with
//!   consistent Newton tangents; [`AnyFrictionLaw`] selects among them at run time
//!   (`friction.law`) through the [`registry`], where a new law registers once.
//! - [`nonsmooth_law`]: exact Coulomb ([`ExactCoulomb`], `exact-coulomb`) and the exact
//!   orthotropic cone ([`ExactOrthotropicCoulomb`]) as return maps onto their friction sets,
//!   with generalised Jacobians for semismooth Newton methods ([`NonsmoothFrictionLaw`]).
//! - [`membrane_displacement`]: the membrane as a 1-D displacement problem with a pointwise
//!   friction law and bilateral contact, solved by Newton; its full-slip limit is the capstan
//!   profile.
//! - [`membrane`]: tension profiles on the cylinder, elliptical and general prisms (Theorem 1,
//!   with gravity and steady speed), the infinite membrane (Corollary 1), right circular and
//!   general cones (Theorem 2), and the coefficient of friction implied by a tension pair.
//!   Closed forms where they exist; otherwise adaptive Gauss–Kronrod quadrature
//!   ([`quadrature`]) of the exponent, or Dormand–Prince 8(5,3) ([`ode`]) of the equilibrium
//!   ODE when loads act. Everything is checked against the ODE built from the geometry layer.
//!
//! # Limitations
//! Membrane models are written for `f64` (the friction laws, the quadrature and the ODE
//! integrator are generic). Cones carry no external loads (as in Theorem 2). Loads are
//! gravity, steady speed and any [`membrane::LoadField`] on prisms.
#![warn(missing_docs)]

mod any_friction_law;
mod any_nonsmooth_law;
mod error;
mod exact_coulomb;
pub mod exact_orthotropic_coulomb;
mod friction_law;
mod frictionless;
mod howell;
pub mod membrane;
pub mod membrane_displacement;
pub mod membrane_path;
pub mod nonsmooth_law;
pub mod ode;
mod orthotropic_coulomb;
pub mod quadrature;
mod registration;
pub mod registry;
mod regularised_coulomb;
pub mod root;
pub mod samples;
mod slip_direction;
mod smooth_coulomb;
mod tresca;

pub use any_friction_law::{AnyFrictionLaw, AnyFrictionParams, FrictionLawKind};
pub use any_nonsmooth_law::{AnyNonsmoothLaw, AnyNonsmoothParams};
pub use error::{ErrorCategory, FrictionError};
pub use exact_coulomb::{ExactCoulomb, ExactCoulombParams};
pub use exact_orthotropic_coulomb::{ExactOrthotropicCoulomb, ExactOrthotropicCoulombParams};
pub use friction_law::{ContactState, FrictionLaw, TractionDerivatives};
pub use frictionless::Frictionless;
pub use howell::{Howell, HowellParams};
pub use nonsmooth_law::{FrictionState, NonsmoothFrictionLaw, Projection};
pub use orthotropic_coulomb::{OrthotropicCoulomb, OrthotropicCoulombParams};
pub use registration::FrictionSettings;
pub use regularised_coulomb::{RegularisedCoulomb, RegularisedCoulombParams};
pub use smooth_coulomb::{SmoothCoulomb, SmoothCoulombParams};
pub use tresca::{Tresca, TrescaParams};
