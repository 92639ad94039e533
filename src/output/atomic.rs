//! Atomic file writes and the `--out DIR` directory.

use std::fs::{self, File, OpenOptions};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
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
