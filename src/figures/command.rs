//! `capstan figure <name>|all [SCENE] [--set KEY=VALUE ...] [--range KEY=A:B:N] --out DIR`:
//! the paper's figures and tables of sections 2 and 3, each as PNG + SVG + CSV, and an index
//! with our numbers beside the paper's; re-aimed at another scene, key or range on request.

use std::path::PathBuf;

use clap::Args;

use crate::error::CliError;
use crate::figures::paper::{self, FigureIndex, FigureRange, FigureSettings};
use crate::output::OutputDir;

/// Arguments of `capstan figure`.
#[derive(Debug, Args, Clone)]
pub struct FigureArgs {
    /// `all`, or one of: tension-ratio, displacement, slip-stick, slip-ratio, slip-ba,
    /// slip-thickness, slip-poisson, young, slip-panel.
    pub name: String,
    /// Scene file (TOML) to start from instead of the paper's scene.
    pub scene: Option<PathBuf>,
    /// Override a scene key (repeatable), e.g. `--set body.thickness=0.5`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Sweep `KEY` over `N` values from `A` to `B` instead of the figure's own key and range,
    /// e.g. `--range body.poisson=0:0.45:10` (sweep figures only).
    #[arg(long, value_name = "KEY=A:B:N")]
    pub range: Option<String>,
    /// Output directory (created if needed).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Coarse grid (40 x 9) and short sweeps: seconds instead of minutes.
    #[arg(long)]
    pub quick: bool,
    /// Grid points along `x2` (default: the scene's, the paper's 250; 40 with `--quick`).
    #[arg(long)]
    pub n2: Option<usize>,
    /// Grid points along `x3` (default: the scene's, the paper's 41; 9 with `--quick`).
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
    s.scene.clone_from(&args.scene);
    s.sets.clone_from(&args.sets);
    s.range = args
        .range
        .as_deref()
        .map(str::parse::<FigureRange>)
        .transpose()?;
    if args.n2.is_some() || args.n3.is_some() {
        let [n2, n3] = s.grid.unwrap_or([250, 41]);
        s.grid = Some([args.n2.unwrap_or(n2), args.n3.unwrap_or(n3)]);
    }
    // Check the scene, the overrides and the range key before any figure runs.
    let scene = s.scene_with(&[])?;
    if let Some(r) = &s.range {
        scene.with_raw(&r.key, &r.from.to_string(), "--range")?;
    }
    let out = OutputDir::create(&args.out)?;
    let bar = crate::progress::bar(names.len(), "figures", quiet);
    let mut index = FigureIndex {
        grid: [scene.grid.n2, scene.grid.n3],
        scene: args.scene.as_ref().map(|p| p.display().to_string()),
        sets: args.sets.clone(),
        range: args.range.clone(),
        quick: s.quick,
        figures: Vec::new(),
    };
    let mut cache = paper::PlotCache::new();
    for name in names {
        bar.set_message(name);
        index.figures.push(paper::run(name, &s, &out, &mut cache)?);
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
