//! `capstan merge`: sweep parts written by `capstan sweep --shard I/N` back into one sweep.

use std::path::PathBuf;

use clap::Args;

use crate::commands::sweep;
use crate::error::CliError;
use crate::scale;

/// Arguments of `capstan merge`.
#[derive(Debug, Args, Clone, Default)]
pub struct MergeArgs {
    /// Directories holding `shard-I-of-N.json` parts, or part files.
    #[arg(required = true, value_name = "DIR")]
    pub parts: Vec<PathBuf>,
    /// Write `sweep.json` and `sweep.csv` (as an unsharded `capstan sweep --out`) here.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print one JSON object (the sweep report) instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Reads, checks and merges the parts.
///
/// # Errors
/// See [`scale::read_parts`] and [`scale::merge`]; output errors.
pub fn run(args: &MergeArgs) -> Result<String, CliError> {
    let parts = scale::read_parts(&args.parts)?;
    let report = scale::merge(&parts)?;
    if let Some(dir) = &args.out {
        sweep::write_out(dir, &report)?;
    }
    if args.json {
        Ok(crate::output::to_json_string(&report)?)
    } else {
        Ok(sweep::table(&report))
    }
}
