//! One module per subcommand.

pub mod bench;
pub mod geometry;
pub mod infer_mu;
pub mod tension;
pub mod verify;
