//! The matrix-free 3-D operator: the curvilinear Navier operator of [`super::SolidNavier`]
//! applied element by element by sum factorisation, with the chart stored once at the
//! quadrature points and no matrix assembled; and the multigrid built on it
//! ([`SolidMultigridParams::build`]).

mod hierarchy;
mod kernel;
mod lanes;
mod operator;
mod p_levels;

pub(crate) use hierarchy::p_prolongation;
pub use hierarchy::{MultigridParts, SolidMultigridParams, cell_sizes, coarse_level_nodes};
pub use operator::SolidMatrixFree;
pub use p_levels::PLevel;
