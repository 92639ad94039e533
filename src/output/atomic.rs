//! Atomic file writes and the `--out DIR` directory.

use std::fs::{self, File, OpenOptions};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};

use super::error::OutputError;

/// Distinguishes temporary files of concurrent writes within one process.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// The run's output files in flight, for `--timeout`: a stopped run must leave none of them.
#[derive(Debug, Default)]
struct Outputs {
    /// Renames wait for [`commit_deferred`] (set by [`defer_commits`]).
    deferred: bool,
    /// [`discard_outputs_and`] ran: no file may be created or renamed any more.
    stopped: bool,
    /// [`commit_deferred`] ran: the outputs are final, nothing is discarded any more.
    committed: bool,
    /// Temporary files being written, and written ones awaiting their rename (`(tmp, path)`).
    temporary: Vec<PathBuf>,
    pending: Vec<(PathBuf, PathBuf)>,
    /// Output directories this run created (removed again, when empty, on discard).
    created_dirs: Vec<PathBuf>,
}

static OUTPUTS: Mutex<Outputs> = Mutex::new(Outputs {
    deferred: false,
    stopped: false,
    committed: false,
    temporary: Vec::new(),
    pending: Vec::new(),
    created_dirs: Vec::new(),
});

fn outputs() -> MutexGuard<'static, Outputs> {
    // A panic while holding the lock leaves consistent lists (every update is one push/remove).
    OUTPUTS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn stopped_error(path: &Path) -> OutputError {
    OutputError::io(
        path,
        std::io::Error::new(std::io::ErrorKind::Interrupted, "the run was stopped"),
    )
}

/// From now on, [`write_atomic`] leaves each complete file as a synced temporary file and
/// renames it into place only in [`commit_deferred`]: a run stopped before that (`--timeout`)
/// leaves none of its files ([`discard_outputs_and`]).
pub fn defer_commits() {
    outputs().deferred = true;
}

/// Renames every deferred file into place (each rename followed by an fsync of its
/// directory); afterwards [`discard_outputs_and`] does nothing.
///
/// # Errors
/// [`OutputError::Io`] if a rename or sync fails, or the run was stopped already.
pub fn commit_deferred() -> Result<(), OutputError> {
    let mut o = outputs();
    if o.stopped {
        return Err(stopped_error(Path::new(".")));
    }
    o.committed = true;
    for (tmp, path) in std::mem::take(&mut o.pending) {
        fs::rename(&tmp, &path).map_err(|e| OutputError::io(&path, e))?;
        sync_parent(&path)?;
    }
    Ok(())
}

/// Stops the run's outputs: removes every temporary and deferred file and the output
/// directories the run created (when empty), then runs `then` with the outputs locked, so no
/// other thread creates or renames a file meanwhile (`then` may exit the process). `None`
/// when the outputs were committed already ([`commit_deferred`]): the run has finished.
pub fn discard_outputs_and<T>(then: impl FnOnce() -> T) -> Option<T> {
    let mut o = outputs();
    if o.committed {
        return None;
    }
    o.stopped = true;
    for tmp in o.temporary.drain(..) {
        let _ = fs::remove_file(tmp); // best effort: it may be gone already
    }
    for (tmp, _) in o.pending.drain(..) {
        let _ = fs::remove_file(tmp);
    }
    for dir in o.created_dirs.drain(..).rev() {
        let _ = fs::remove_dir(dir); // only when empty
    }
    Some(then())
}

/// Creates `dir` and its parents; records the directories created for [`discard_outputs_and`].
///
/// # Errors
/// [`OutputError::Io`] if a directory cannot be created.
pub(super) fn create_dirs(dir: &Path) -> Result<(), OutputError> {
    let mut missing = Vec::new();
    let mut at = Some(dir);
    while let Some(d) = at {
        if d.as_os_str().is_empty() || d.exists() {
            break;
        }
        missing.push(d.to_path_buf());
        at = d.parent();
    }
    fs::create_dir_all(dir).map_err(|e| OutputError::io(dir, e))?;
    outputs().created_dirs.extend(missing.into_iter().rev());
    Ok(())
}

/// Syncs the directory holding `path`, so that a rename into it survives a crash.
fn sync_parent(path: &Path) -> Result<(), OutputError> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    File::open(dir)
        .and_then(|d| d.sync_all())
        .map_err(|e| OutputError::io(dir, e))
}

/// Removes the temporary file unless the write was committed (also on panic).
struct TempGuard {
    path: PathBuf,
    committed: bool,
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_file(&self.path); // best effort: the error being reported matters more
            outputs().temporary.retain(|t| t != &self.path);
        }
    }
}

/// Writes `path` atomically: `write` fills a temporary file in the same directory, which is
/// flushed, synced and renamed over `path` only if `write` succeeds; the directory is then
/// synced too, so after a crash `path` holds the old file or the new one, never a torn one.
/// After [`defer_commits`] the rename waits for [`commit_deferred`].
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
    // Created under the lock, so a stop (`--timeout`) either sees it or prevents it.
    let file = {
        let mut o = outputs();
        if o.stopped {
            return Err(stopped_error(path));
        }
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(|e| OutputError::io(path, e))?;
        o.temporary.push(tmp.clone());
        file
    };
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
    let mut o = outputs();
    if o.stopped {
        return Err(stopped_error(path)); // the stop removed the temporary file
    }
    o.temporary.retain(|t| t != &tmp);
    if o.deferred && !o.committed {
        o.pending.push((tmp, path.to_path_buf()));
    } else {
        fs::rename(&tmp, path).map_err(|e| OutputError::io(path, e))?;
        sync_parent(path)?;
    }
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
