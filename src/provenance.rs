//! How a result was made: every `--json` report and `--out` directory carries the capstan
//! version and the fully resolved scene (every key, defaults filled in), so a file can be
//! reproduced from itself (`capstan contact DIR/scene.toml`).

use std::path::Path;

use serde::Serialize;

use crate::error::CliError;
use crate::output::OutputDir;
use crate::scene::Scene;

/// The version of this build (`capstan_version` in every JSON report).
pub const CAPSTAN_VERSION: &str = env!("CARGO_PKG_VERSION");

/// A report with its provenance: the report's own keys, then `capstan_version` and `scene`
/// (the resolved scene, as `scene.toml` holds it).
#[derive(Debug, Serialize)]
pub struct Stamped<'a, T: Serialize> {
    /// The report (its keys at the top level).
    #[serde(flatten)]
    pub report: &'a T,
    /// [`CAPSTAN_VERSION`].
    pub capstan_version: &'static str,
    /// The resolved scene, when the command read one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene: Option<&'a Scene>,
}

impl<'a, T: Serialize> Stamped<'a, T> {
    /// `report` made by `scene` (or by no scene, as `capstan verify`).
    pub fn new(report: &'a T, scene: Option<&'a Scene>) -> Self {
        Self {
            report,
            capstan_version: CAPSTAN_VERSION,
            scene,
        }
    }
}

/// Writes `scene.toml`, the resolved scene, into `out` (atomically, as every output).
///
/// # Errors
/// Output errors; a scene that does not serialise to TOML.
pub fn write_scene(out: &OutputDir, scene: &Scene) -> Result<(), CliError> {
    let text = toml::to_string(scene).map_err(|e| CliError::Scene {
        origin: "scene".into(),
        message: format!("the resolved scene does not serialise to TOML: {e}"),
    })?;
    out.write("scene.toml", |w| {
        use std::io::Write;
        w.write_all(format!("# resolved by capstan {CAPSTAN_VERSION}\n").as_bytes())?;
        w.write_all(text.as_bytes())?;
        Ok(())
    })?;
    Ok(())
}

/// Writes `NAME.json` with its provenance ([`Stamped`]) and, for a report of a scene,
/// `scene.toml`.
///
/// # Errors
/// Output errors (a non-finite number refuses the file).
pub fn write_json_report<T: Serialize>(
    dir: &Path,
    name: &str,
    report: &T,
    scene: Option<&Scene>,
) -> Result<(), CliError> {
    report_dir(dir, name, report, scene).map(drop)
}

/// As [`write_json_report`]; the directory, for the report's other files.
///
/// # Errors
/// Output errors (a non-finite number refuses the file).
pub fn report_dir<T: Serialize>(
    dir: &Path,
    name: &str,
    report: &T,
    scene: Option<&Scene>,
) -> Result<OutputDir, CliError> {
    let out = OutputDir::create(dir)?;
    out.write_json(&format!("{name}.json"), &Stamped::new(report, scene))?;
    if let Some(scene) = scene {
        write_scene(&out, scene)?;
    }
    Ok(out)
}
