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
}

impl SceneArgs {
    /// Loads the scene these arguments describe.
    ///
    /// # Errors
    /// See [`Scene::load`].
    pub fn load(&self) -> Result<Scene, CliError> {
        Scene::load(self.scene.as_deref(), &self.sets)
    }
}
