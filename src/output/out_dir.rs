//! The `--out DIR` directory: every output file of a run, written atomically.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Component, Path, PathBuf};

use super::atomic::{create_dirs, write_atomic};
use super::csv::Table;
use super::error::OutputError;
use super::json::{check_finite_json, write_json};
use super::plot::{Plot, write_plot};
use super::vtu::Vtu;

/// The output directory of a run (`--out DIR`): created on demand, files written atomically.
///
/// # Example
/// ```
/// use capstan::output::{OutputDir, Table};
/// let root = std::env::temp_dir().join(format!("capstan-doc-outdir-{}", std::process::id()));
/// let out = OutputDir::create(&root).unwrap();
/// let table = Table::new().f64("theta", [0.0, 0.5]).f64("tension", [1.0, 1.2]);
/// let path = out.write_csv("profile.csv", &table).unwrap();
/// assert_eq!(std::fs::read_to_string(path).unwrap(), "theta,tension\n0,1\n0.5,1.2\n");
/// std::fs::remove_dir_all(&root).unwrap();
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputDir {
    root: PathBuf,
}

impl OutputDir {
    /// Uses `root` as the output directory, creating it and its parents if needed.
    ///
    /// # Errors
    /// [`OutputError::Io`] if the directory cannot be created (or `root` is a file).
    pub fn create(root: impl Into<PathBuf>) -> Result<Self, OutputError> {
        let root = root.into();
        create_dirs(&root)?;
        Ok(Self { root })
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        &self.root
    }

    /// The path of file `name` inside the directory, after checking `name`.
    ///
    /// `name` is relative and may have subdirectories (`fields/step_0001.vtu`), but no `..`.
    ///
    /// # Errors
    /// [`OutputError::InvalidName`] for an empty, absolute or escaping name.
    pub fn file(&self, name: &str) -> Result<PathBuf, OutputError> {
        let rel = Path::new(name);
        let bad = |reason| {
            Err(OutputError::InvalidName {
                name: name.to_owned(),
                reason,
            })
        };
        if name.is_empty() || rel.file_name().is_none() {
            return bad("not a file name");
        }
        for c in rel.components() {
            match c {
                Component::Normal(_) | Component::CurDir => {}
                Component::ParentDir => return bad("contains `..`"),
                Component::RootDir | Component::Prefix(_) => return bad("is absolute"),
            }
        }
        Ok(self.root.join(rel))
    }

    /// Writes file `name` atomically with `write` (see [`write_atomic`]), creating
    /// subdirectories in `name`; returns its path.
    ///
    /// # Errors
    /// As [`OutputDir::file`] and [`write_atomic`].
    pub fn write(
        &self,
        name: &str,
        write: impl FnOnce(&mut BufWriter<File>) -> Result<(), OutputError>,
    ) -> Result<PathBuf, OutputError> {
        let path = self.file(name)?;
        if let Some(parent) = path.parent() {
            create_dirs(parent)?;
        }
        write_atomic(&path, write)?;
        Ok(path)
    }

    /// Writes a CSV table as file `name`; returns its path.
    ///
    /// # Errors
    /// As [`Table::write`](super::Table::write) and [`OutputDir::write`].
    pub fn write_csv(&self, name: &str, table: &Table) -> Result<PathBuf, OutputError> {
        table.validate()?;
        self.write(name, |w| table.write(w))
    }

    /// Writes `value` as pretty JSON in file `name`; returns its path.
    ///
    /// # Errors
    /// As [`write_json`](super::write_json) and [`OutputDir::write`].
    pub fn write_json<T: serde::Serialize + ?Sized>(
        &self,
        name: &str,
        value: &T,
    ) -> Result<PathBuf, OutputError> {
        check_finite_json(value)?;
        self.write(name, |w| write_json(w, value))
    }

    /// Writes a VTU file `name`; returns its path.
    ///
    /// # Errors
    /// As [`Vtu::write`](super::Vtu::write) and [`OutputDir::write`].
    pub fn write_vtu(&self, name: &str, vtu: &Vtu<'_>) -> Result<PathBuf, OutputError> {
        vtu.validate()?;
        self.write(name, |w| vtu.write(w))
    }

    /// Writes plot `name` as `name.svg` and `name.png`; returns both paths.
    ///
    /// # Errors
    /// As [`write_plot`](super::write_plot) and [`OutputDir::file`].
    pub fn write_plot<P: Plot + ?Sized>(
        &self,
        name: &str,
        plot: &P,
    ) -> Result<[PathBuf; 2], OutputError> {
        let stem = self.file(name)?;
        if let Some(parent) = stem.parent() {
            create_dirs(parent)?;
        }
        write_plot(&stem, plot)
    }
}
