//! The output layer's error type.

use std::path::PathBuf;

/// Everything that can go wrong while writing an output file.
///
/// No variant leaves a partial file behind: every writer goes through
/// [`write_atomic`](super::write_atomic), which removes its temporary file on failure.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// Creating, writing, syncing or renaming a file or directory failed.
    #[error("{path}: {source}")]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A value is NaN or infinite; no output file ever contains one.
    #[error("`{column}`[{index}] = {value} is not finite; refusing to write it")]
    NonFinite {
        /// The column, array or JSON path holding the value (`report.x2[3]` style for JSON).
        column: String,
        /// Index of the value within the column (0 for a scalar).
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A column or array has the wrong number of entries.
    #[error("`{column}` has {found} entries, expected {expected}")]
    LengthMismatch {
        /// The column or array.
        column: String,
        /// Entries required (rows, points times components, cells times components, ...).
        expected: usize,
        /// Entries given.
        found: usize,
    },
    /// Two columns or arrays share a name.
    #[error("`{name}` appears twice")]
    DuplicateName {
        /// The repeated name.
        name: String,
    },
    /// A name is empty or contains a character the format cannot carry.
    #[error("name {name:?} is not allowed: {reason}")]
    InvalidName {
        /// The name.
        name: String,
        /// Why not (for example `contains '"'`).
        reason: &'static str,
    },
    /// A grid or plot is too small or malformed to be written.
    #[error("`{field}` = {value} is outside {allowed}")]
    InvalidParameter {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
        /// The allowed range.
        allowed: &'static str,
    },
    /// The data could not be serialised to JSON.
    #[error("JSON serialisation failed: {0}")]
    Json(#[from] serde_json::Error),
    /// The plotting library failed to draw.
    ///
    /// plotters' error type is generic over the drawing backend, so its message is kept as text.
    #[error("plot `{name}`: {message}")]
    Plot {
        /// The plot's file stem.
        name: String,
        /// plotters' message.
        message: String,
    },
    /// PNG encoding failed.
    #[error("PNG encoding: {0}")]
    Png(#[from] png::EncodingError),
    /// A shell-chart evaluation failed while placing grid points.
    #[error(transparent)]
    Geometry(#[from] capstan_geometry::GeometryError),
}

impl OutputError {
    /// An [`OutputError::InvalidParameter`]: `field` = `value` is outside `allowed`.
    pub(crate) fn invalid(field: &'static str, value: f64, allowed: &'static str) -> Self {
        Self::InvalidParameter {
            field,
            value,
            allowed,
        }
    }

    /// An [`OutputError::LengthMismatch`]: `column` has `found` entries, not `expected`.
    pub(crate) fn length_mismatch(
        column: impl Into<String>,
        expected: usize,
        found: usize,
    ) -> Self {
        Self::LengthMismatch {
            column: column.into(),
            expected,
            found,
        }
    }

    /// An [`OutputError::Io`] for `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }
}

/// Refuses a non-finite value, naming where it sits.
///
/// # Errors
/// [`OutputError::NonFinite`] if `value` is NaN or infinite.
pub(crate) fn check_finite(column: &str, index: usize, value: f64) -> Result<(), OutputError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(OutputError::NonFinite {
            column: column.to_owned(),
            index,
            value,
        })
    }
}

/// [`OutputError::LengthMismatch`] unless `column` has `expected` entries (`found`).
pub(crate) fn check_length(column: &str, expected: usize, found: usize) -> Result<(), OutputError> {
    if found == expected {
        Ok(())
    } else {
        Err(OutputError::length_mismatch(column, expected, found))
    }
}

/// [`OutputError::InvalidParameter`] (value 0) when `field` has no entries (`len == 0`);
/// `allowed` says how many it needs.
pub(crate) fn check_not_empty(
    field: &'static str,
    len: usize,
    allowed: &'static str,
) -> Result<(), OutputError> {
    if len == 0 {
        Err(OutputError::invalid(field, 0.0, allowed))
    } else {
        Ok(())
    }
}

/// Refuses the first non-finite value of a column.
///
/// # Errors
/// [`OutputError::NonFinite`] naming the column and the first bad index.
pub(crate) fn check_all_finite(column: &str, values: &[f64]) -> Result<(), OutputError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(index) => Err(OutputError::NonFinite {
            column: column.to_owned(),
            index,
            value: values[index],
        }),
    }
}
