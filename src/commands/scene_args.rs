//! The arguments every command that reads a scene takes.

use std::path::PathBuf;

use clap::Args;

use crate::error::CliError;
use crate::scene::Scene;

/// Arguments shared by commands that read a scene.
#[derive(Debug, Args, Clone, Default)]
pub struct SceneArgs {
    /// Scene file (TOML); built-in defaults when omitted.
    pub scene: Option<PathBuf>,
    /// Override a scene key, e.g. `--set obstacle.b=1.5` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// An accuracy target: the same as `--set accuracy.tol=TOL` (capstan chooses the
    /// discretisation and grid and refines until every estimate is below TOL relative).
    #[arg(long, value_name = "TOL")]
    pub tol: Option<f64>,
}

impl SceneArgs {
    /// Loads the scene these arguments describe.
    ///
    /// # Errors
    /// See [`Scene::load`].
    pub fn load(&self) -> Result<Scene, CliError> {
        let mut sets = self.sets.clone();
        if let Some(tol) = self.tol {
            sets.push(format!("accuracy.tol={tol:e}"));
        }
        Scene::load(self.scene.as_deref(), &sets)
    }
}
