//! The arguments of the commands that run a fixed study rather than a scene (`capstan verify`,
//! `compare`, `stress`).

use std::path::PathBuf;

use clap::Args;

/// `--json`, `--out DIR` and `--quick`; each command words the help of `--out` and `--quick`
/// (what it writes, what it keeps) with `mut_arg`.
#[derive(Debug, Args, Clone, Default)]
pub struct StudyArgs {
    /// Print one JSON object instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Also write the report's files into this directory (listed in the command's help).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// A smaller study (see the command's help), for a quick look.
    #[arg(long)]
    pub quick: bool,
}
