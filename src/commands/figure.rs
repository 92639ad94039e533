//! `capstan figure <name>|all --out DIR`: the paper's figures and tables of sections 2 and 3,
//! each as PNG + SVG + CSV, and an index with our numbers beside the paper's.

use std::path::PathBuf;

use clap::Args;

use crate::error::CliError;
use crate::figures::paper::{self, FigureIndex, FigureSettings};
use crate::output::OutputDir;

/// Arguments of `capstan figure`.
#[derive(Debug, Args, Clone)]
pub struct FigureArgs {
    /// `all`, or one of: tension-ratio, displacement, slip-stick, slip-ratio, slip-ba,
    /// slip-thickness, slip-poisson, young.
    pub name: String,
    /// Output directory (created if needed).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Coarse grid (40 x 9) and short sweeps: seconds instead of minutes.
    #[arg(long)]
    pub quick: bool,
    /// Grid points along `x2` (default: the paper's 250; 40 with `--quick`).
    #[arg(long)]
    pub n2: Option<usize>,
    /// Grid points along `x3` (default: the paper's 41; 9 with `--quick`).
    #[arg(long)]
    pub n3: Option<usize>,
    /// Print `index.json` instead of the Markdown table.
    #[arg(long)]
    pub json: bool,
}

/// Runs the figures and writes the index.
///
/// # Errors
/// Unknown names (exit 2), solver failures of single solves, output errors.
pub fn run(args: &FigureArgs, quiet: bool) -> Result<FigureIndex, CliError> {
    let names = paper::names(&args.name)?;
    let mut s = if args.quick {
        FigureSettings::quick()
    } else {
        FigureSettings::paper()
    };
    s.n2 = args.n2.unwrap_or(s.n2);
    s.n3 = args.n3.unwrap_or(s.n3);
    let out = OutputDir::create(&args.out)?;
    let bar = crate::progress::bar(names.len(), "figures", quiet);
    let mut index = FigureIndex {
        grid: [s.n2, s.n3],
        quick: s.quick,
        figures: Vec::new(),
    };
    for name in names {
        bar.set_message(name);
        index.figures.push(paper::run(name, &s, &out)?);
        bar.inc(1);
        // keep a usable index after every figure
        paper::write_index(&out, &index)?;
    }
    bar.finish_and_clear();
    Ok(index)
}

/// The Markdown table of the index (stdout).
pub fn table(index: &FigureIndex) -> String {
    paper::index_markdown(index)
}
