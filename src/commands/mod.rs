//! One module per subcommand.

pub mod geometry;
