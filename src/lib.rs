//! capstan: friction between elastic bodies and rough rigid curved obstacles.
//!
//! The facade re-exports the member crates and provides scene files, the command line and
//! output writers. See the README for the two problems it solves.
#![warn(missing_docs)]

pub mod cli;
pub mod commands;
pub mod error;
pub mod figures;
pub mod output;
pub mod progress;
pub mod provenance;
pub mod scale;
pub mod scene;

pub use capstan_elasticity as elasticity;
pub use capstan_elasticity::solvers;
pub use capstan_friction as friction;
pub use capstan_geometry as geometry;
pub use error::CliError;
pub use scene::Scene;
