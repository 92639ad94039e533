//! The pointwise continuum: what linear elasticity in curvilinear coordinates is at one point
//! of a shell chart, independent of how it is discretised.
//!
//! # Math
//! ```text
//! nabla_k v^n = d_k v^n + Gamma^n_km v^m          covariant derivative
//! E_kl = (g_ln nabla_k v^n + g_kn nabla_l v^n)/2  linearised strain
//! M^i_l = g^ik E_kl                               mixed strain
//! T^i_j = lambda delta^i_j tr M + 2 mu M^i_j      mixed stress (isotropic)
//! A^ijkl = lambda g^ij g^kl + mu (g^ik g^jl + g^il g^jk)
//! W = (lambda (tr M)^2 + 2 mu tr(M M)) / 2         energy density per unit sqrt(g)
//! ```
//! The operator is linear in a short list of scalar inputs at the point — displacement
//! components and their coordinate derivatives, an [`InputLayout`]: six in plane strain
//! (`v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3`), twelve in a 3-D body. Every
//! discretisation (finite differences, Q1/Q2/Qp elements, the 3-D body) builds its operator
//! from these pointwise maps, so the tensor calculus is written once:
//! - [`kinematics`]: strain and stress of a plane-strain [`kinematics::LocalDisplacement`],
//!   the coefficients of the stress in the six inputs (finite differences, recovery);
//! - [`stiffness`]: the symmetric input-by-input energy matrix `K_q` (the integrand of the
//!   weak form), its volumetric/shear split and the divergence coefficients, for any layout;
//! - [`plane_strain`]: the check that a chart admits the plane-strain reduction;
//! - [`face_flux`](mod@face_flux): the flux of a traction or stress condition through a face.

pub mod face_flux;
pub mod kinematics;
pub mod plane_strain;
pub mod stiffness;

pub use face_flux::{FaceData, face_flux};
pub use plane_strain::check_plane_strain;
pub use stiffness::{
    Input, InputLayout, PLANE_STRAIN, SOLID, divergence_coefficients, energy_matrix, mixed_strains,
    mixed_stress_of, stiffness_matrix,
};
