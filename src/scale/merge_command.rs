//! `capstan merge`: sweep parts written by `capstan sweep --shard I/N` back into one sweep.

use std::path::{Path, PathBuf};

use clap::Args;

use crate::commands::sweep;
use crate::error::CliError;
use crate::output::OutputDir;
use crate::scale;
use crate::scale::ShardFile;
use crate::scene::Scene;

/// Arguments of `capstan merge`.
#[derive(Debug, Args, Clone, Default)]
pub struct MergeArgs {
    /// Directories holding `shard-I-of-N.json` parts, or part files.
    #[arg(required = true, value_name = "DIR")]
    pub parts: Vec<PathBuf>,
    /// Write `sweep.json` and `sweep.csv` (as an unsharded `capstan sweep --out`) here, with
    /// the parts' `points/point_NNNN.vtu` and their collection `sweep.pvd`.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print one JSON object (the sweep report) instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Reads, checks and merges the parts; the merged report carries `capstan_version` and the
/// parts' resolved scene, as an unsharded sweep's does.
///
/// # Errors
/// See [`scale::read_parts`] and [`scale::merge`]; output errors; a part whose scene does not
/// read back.
pub fn run(args: &MergeArgs) -> Result<String, CliError> {
    let parts = scale::read_parts(&args.parts)?;
    let report = scale::merge(&parts)?;
    let scene = part_scene(&parts)?;
    if let Some(dir) = &args.out {
        let out = OutputDir::create(dir)?;
        copy_point_files(&parts, &out)?;
        sweep::write_out(dir, &report, &scene)?;
    }
    if args.json {
        Ok(crate::output::to_json_string(
            &crate::provenance::Stamped::new(&report, Some(&scene)),
        )?)
    } else {
        Ok(sweep::table(&report))
    }
}

/// The resolved scene the parts were run with (equal in every part: the merge checked the
/// hash).
fn part_scene(parts: &[(String, ShardFile)]) -> Result<Scene, CliError> {
    let (name, first) = parts.first().ok_or_else(|| CliError::Scene {
        origin: "merge".into(),
        message: "no parts".into(),
    })?;
    serde_json::from_value(first.scene.clone()).map_err(|e| CliError::Scene {
        origin: name.clone(),
        message: format!("the part's `scene` does not read back: {e}"),
    })
}

/// Copies each part's `points/point_NNNN.vtu` (written by `capstan sweep --shard I/N --out`
/// beside the part) into `out`; points without a file (not converged, or a part written
/// without fields) are skipped.
fn copy_point_files(parts: &[(String, ShardFile)], out: &OutputDir) -> Result<(), CliError> {
    for (name, part) in parts {
        let dir = Path::new(name).parent().unwrap_or(Path::new("."));
        for (&k, point) in part.indices.iter().zip(&part.points) {
            let file = format!("points/point_{k:04}.vtu");
            let source = dir.join(&file);
            if !point.converged || !source.is_file() {
                continue;
            }
            let bytes = std::fs::read(&source).map_err(|e| CliError::Io {
                path: source.display().to_string(),
                source: e,
            })?;
            out.write(&file, |w| {
                std::io::Write::write_all(w, &bytes)?;
                Ok(())
            })?;
        }
    }
    Ok(())
}
