//! Matrix Market writers (the NIST exchange format PETSc, MUMPS, scipy and sprs read).
//!
//! Values are written in Rust's shortest round-trip scientific form (`{:e}`), so a reader
//! parsing them to `f64` gets the same bits back.

use std::io::Write;

use capstan_elasticity::solvers::SparsityPattern;

use crate::output::OutputError;

fn finite(name: &str, values: &[f64]) -> Result<(), OutputError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(OutputError::NonFinite {
            column: name.to_owned(),
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

/// Writes the sparse matrix `(pattern, values)` as `matrix coordinate real general`
/// (1-based `row column value` lines, column by column), with `comment` lines after the
/// header.
///
/// # Errors
/// [`OutputError::NonFinite`] for a NaN or infinite value (checked before writing);
/// [`OutputError::LengthMismatch`] if `values` does not match the pattern; I/O errors.
///
/// # Example
/// ```
/// use capstan::scale::write_matrix_market_coordinate;
/// let (p, _) = capstan_elasticity::solvers::SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (1, 1)]).unwrap();
/// let mut s = Vec::new();
/// write_matrix_market_coordinate(&mut s, &p, &[2.0, -1.0, 0.5], &["A"]).unwrap();
/// let text = String::from_utf8(s).unwrap();
/// assert!(text.starts_with("%%MatrixMarket matrix coordinate real general\n% A\n2 2 3\n1 1 2e0\n"));
/// ```
pub fn write_matrix_market_coordinate<W: Write + ?Sized>(
    w: &mut W,
    pattern: &SparsityPattern,
    values: &[f64],
    comment: &[&str],
) -> Result<(), OutputError> {
    if values.len() != pattern.nnz() {
        return Err(OutputError::LengthMismatch {
            column: "matrix values".into(),
            expected: pattern.nnz(),
            found: values.len(),
        });
    }
    finite("A", values)?;
    header(w, "coordinate", comment)?;
    writeln!(
        w,
        "{} {} {}",
        pattern.nrows(),
        pattern.ncols(),
        pattern.nnz()
    )?;
    for ((row, col), v) in pattern.entries().zip(values) {
        writeln!(w, "{} {} {v:e}", row + 1, col + 1)?;
    }
    Ok(())
}

/// The banner `%%MatrixMarket matrix <format> real general` and one `% ` line per comment.
fn header<W: Write + ?Sized>(w: &mut W, format: &str, comment: &[&str]) -> std::io::Result<()> {
    writeln!(w, "%%MatrixMarket matrix {format} real general")?;
    for c in comment {
        writeln!(w, "% {c}")?;
    }
    Ok(())
}

/// Writes a dense column vector as `matrix array real general` (`n 1`, one value a line).
///
/// # Errors
/// [`OutputError::NonFinite`] naming `name`; I/O errors.
pub fn write_matrix_market_array<W: Write + ?Sized>(
    w: &mut W,
    name: &str,
    values: &[f64],
    comment: &[&str],
) -> Result<(), OutputError> {
    finite(name, values)?;
    header(w, "array", comment)?;
    writeln!(w, "{} 1", values.len())?;
    for v in values {
        writeln!(w, "{v:e}")?;
    }
    Ok(())
}
