//! Atomic file writes and the `--out DIR` directory.

use std::fs::{self, File, OpenOptions};
use std::io::BufWriter;
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use super::error::OutputError;

/// Distinguishes temporary files of concurrent writes within one process.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Removes the temporary file unless the write was committed (also on panic).
struct TempGuard {
    path: PathBuf,
    committed: bool,
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_file(&self.path); // best effort: the error being reported matters more
        }
    }
}

/// Writes `path` atomically: `write` fills a temporary file in the same directory, which is
/// flushed, synced and renamed over `path` only if `write` succeeds.
///
/// A failed or panicking `write` leaves no file at `path` (an existing file there is kept
/// unchanged) and no temporary file. Inside `write`, `?` on a [`std::io::Error`] works: the
/// error is reported as [`OutputError::Io`] naming `path`.
///
/// # Errors
/// [`OutputError::Io`] if the temporary file cannot be created, written, synced or renamed (for
/// example a missing parent directory); any error `write` returns.
///
/// # Example
/// ```
/// use std::io::Write;
/// let dir = std::env::temp_dir().join(format!("capstan-doc-atomic-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("hello.txt");
/// capstan::output::write_atomic(&path, |w| Ok(writeln!(w, "hello")?)).unwrap();
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "hello\n");
/// // a failing writer leaves nothing behind
/// let failed = dir.join("failed.txt");
/// let r: Result<(), _> = capstan::output::write_atomic(&failed, |w| {
///     writeln!(w, "half")?;
///     Err(capstan::output::OutputError::InvalidParameter { field: "n", value: 0.0, allowed: "[1, inf)" })
/// });
/// assert!(r.is_err() && !failed.exists());
/// std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn write_atomic<T>(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<T, OutputError>,
) -> Result<T, OutputError> {
    let name = path.file_name().ok_or_else(|| {
        OutputError::io(
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"),
        )
    })?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let tmp_name = format!(
        ".{}.{}-{}.tmp",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    );
    let tmp = dir.join(tmp_name);
    let file = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .map_err(|e| OutputError::io(path, e))?;
    let mut guard = TempGuard {
        path: tmp.clone(),
        committed: false,
    };
    let mut w = BufWriter::new(file);
    let value = write(&mut w).map_err(|e| name_path(e, path))?;
    let file = w
        .into_inner()
        .map_err(|e| OutputError::io(path, e.into_error()))?;
    file.sync_data().map_err(|e| OutputError::io(path, e))?;
    drop(file);
    fs::rename(&tmp, path).map_err(|e| OutputError::io(path, e))?;
    guard.committed = true;
    Ok(value)
}

/// Fills in the path of an [`OutputError::Io`] raised through `?` (which has none).
fn name_path(e: OutputError, path: &Path) -> OutputError {
    match e {
        OutputError::Io { path: p, source } if p.as_os_str().is_empty() => {
            OutputError::io(path, source)
        }
        other => other,
    }
}

/// Makes `?` on an I/O error work inside [`write_atomic`]'s closure; the path is filled in there.
impl From<std::io::Error> for OutputError {
    fn from(source: std::io::Error) -> Self {
        Self::Io {
            path: PathBuf::new(),
            source,
        }
    }
}

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
        fs::create_dir_all(&root).map_err(|e| OutputError::io(&root, e))?;
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
            fs::create_dir_all(parent).map_err(|e| OutputError::io(parent, e))?;
        }
        write_atomic(&path, write)?;
        Ok(path)
    }

    /// Writes a CSV table as file `name`; returns its path.
    ///
    /// # Errors
    /// As [`Table::write`](super::Table::write) and [`OutputDir::write`].
    pub fn write_csv(&self, name: &str, table: &super::Table) -> Result<PathBuf, OutputError> {
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
        super::json::check_finite_json(value)?;
        self.write(name, |w| super::write_json(w, value))
    }

    /// Writes a VTU file `name`; returns its path.
    ///
    /// # Errors
    /// As [`Vtu::write`](super::Vtu::write) and [`OutputDir::write`].
    pub fn write_vtu(&self, name: &str, vtu: &super::Vtu<'_>) -> Result<PathBuf, OutputError> {
        vtu.validate()?;
        self.write(name, |w| vtu.write(w))
    }

    /// Writes plot `name` as `name.svg` and `name.png`; returns both paths.
    ///
    /// # Errors
    /// As [`write_plot`](super::write_plot) and [`OutputDir::file`].
    pub fn write_plot<P: super::Plot + ?Sized>(
        &self,
        name: &str,
        plot: &P,
    ) -> Result<[PathBuf; 2], OutputError> {
        let stem = self.file(name)?;
        if let Some(parent) = stem.parent() {
            fs::create_dir_all(parent).map_err(|e| OutputError::io(parent, e))?;
        }
        super::write_plot(&stem, plot)
    }
}
