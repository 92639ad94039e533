//! The discretisations of the registry: each built-in method's variant with its data (a
//! [`crate::registration::DiscretisationScheme`]) and its [`RegisteredDiscretisation`] entry
//! (name, scene keys, validating builder), one file per method. This room sits above the
//! operators it builds (`finite_difference`, `finite_element`, `solid`) and below the
//! registry ([`crate::registry`]) that lists them; the operators import neither.

mod fd;
mod qk;
mod qp;
mod qp_corner;

pub use fd::FiniteDifferences;
pub use qk::FemQk;
pub use qp::FemQp;
pub use qp_corner::FemQpCorner;

pub(crate) use fd::REGISTRATION as FD_REGISTRATION;
pub(crate) use qk::{Q1_REGISTRATION, Q2_REGISTRATION};
pub(crate) use qp::REGISTRATION as QP_REGISTRATION;
pub(crate) use qp_corner::REGISTRATION as QP_CORNER_REGISTRATION;
