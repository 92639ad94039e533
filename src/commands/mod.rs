//! One module per subcommand.

pub mod bench;
pub mod geometry;
pub mod verify;
