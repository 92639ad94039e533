//! CSV tables: a header line and columns of `f64`, `i32` or text.

use std::io::Write;

use super::error::{OutputError, check_all_finite, check_length};

/// The values of one column.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ColumnData {
    /// Real numbers, written in shortest round-trip form (`0.1`, `1.5e-7`).
    F64(Vec<f64>),
    /// Integers (stick/slip states, iteration counts, ...).
    I32(Vec<i32>),
    /// Text, quoted when it contains a comma, quote or line break (RFC 4180).
    Text(Vec<String>),
}

impl ColumnData {
    /// Number of entries.
    pub fn len(&self) -> usize {
        match self {
            Self::F64(v) => v.len(),
            Self::I32(v) => v.len(),
            Self::Text(v) => v.len(),
        }
    }

    /// Whether the column has no entries.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A named column.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// The header entry.
    pub name: String,
    /// The values.
    pub data: ColumnData,
}

/// Column data for a CSV file: every column has the same number of rows.
///
/// Checked when written ([`Table::validate`]): equal lengths, distinct non-empty names, and
/// no NaN or infinity (the error names the column and row).
///
/// # Example
/// ```
/// use capstan::output::{OutputError, Table};
/// let t = Table::new()
///     .f64("theta", [0.0, 1.5e-7])
///     .i32("state", [-1, 1])
///     .text("zone", ["stick", "slip, forward"]);
/// let mut s = Vec::new();
/// t.write(&mut s).unwrap();
/// assert_eq!(
///     String::from_utf8(s).unwrap(),
///     "theta,state,zone\n0,-1,stick\n1.5e-7,1,\"slip, forward\"\n"
/// );
/// let bad = Table::new().f64("tension", [1.0, f64::NAN]);
/// assert!(matches!(bad.validate(), Err(OutputError::NonFinite { index: 1, .. })));
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    columns: Vec<Column>,
}

impl Table {
    /// An empty table.
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends a column of reals.
    pub fn f64(mut self, name: impl Into<String>, values: impl Into<Vec<f64>>) -> Self {
        self.push(name, ColumnData::F64(values.into()));
        self
    }

    /// Appends a column of integers.
    pub fn i32(mut self, name: impl Into<String>, values: impl Into<Vec<i32>>) -> Self {
        self.push(name, ColumnData::I32(values.into()));
        self
    }

    /// Appends a column of text.
    pub fn text<S: Into<String>>(
        mut self,
        name: impl Into<String>,
        values: impl IntoIterator<Item = S>,
    ) -> Self {
        let values = values.into_iter().map(Into::into).collect();
        self.push(name, ColumnData::Text(values));
        self
    }

    /// Appends a column (for tables built in a loop).
    pub fn push(&mut self, name: impl Into<String>, data: ColumnData) -> &mut Self {
        self.columns.push(Column {
            name: name.into(),
            data,
        });
        self
    }

    /// The columns, in order.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// Number of rows (of the first column; 0 without columns).
    pub fn rows(&self) -> usize {
        self.columns.first().map_or(0, |c| c.data.len())
    }

    /// Checks the table can be written.
    ///
    /// # Errors
    /// [`OutputError::InvalidName`] for an empty name or one with a line break,
    /// [`OutputError::DuplicateName`], [`OutputError::LengthMismatch`] for a column shorter or
    /// longer than the first, [`OutputError::NonFinite`] naming the column and row.
    pub fn validate(&self) -> Result<(), OutputError> {
        let rows = self.rows();
        for (i, c) in self.columns.iter().enumerate() {
            if c.name.is_empty() {
                return Err(OutputError::InvalidName {
                    name: c.name.clone(),
                    reason: "is empty",
                });
            }
            if c.name.contains(['\n', '\r']) {
                return Err(OutputError::InvalidName {
                    name: c.name.clone(),
                    reason: "contains a line break",
                });
            }
            if self.columns[..i].iter().any(|d| d.name == c.name) {
                return Err(OutputError::DuplicateName {
                    name: c.name.clone(),
                });
            }
            check_length(&c.name, rows, c.data.len())?;
            if let ColumnData::F64(v) = &c.data {
                check_all_finite(&c.name, v)?;
            }
        }
        Ok(())
    }

    /// Writes the table as CSV (comma-separated, `\n` line ends, header first).
    ///
    /// # Errors
    /// As [`Table::validate`] (checked before anything is written), or an I/O error.
    pub fn write<W: Write + ?Sized>(&self, w: &mut W) -> Result<(), OutputError> {
        self.validate()?;
        let header: Vec<String> = self.columns.iter().map(|c| quote(&c.name)).collect();
        writeln!(w, "{}", header.join(","))?;
        let mut line = String::new();
        for row in 0..self.rows() {
            line.clear();
            for (i, c) in self.columns.iter().enumerate() {
                if i > 0 {
                    line.push(',');
                }
                match &c.data {
                    ColumnData::F64(v) => line.push_str(&format_f64(v[row])),
                    ColumnData::I32(v) => line.push_str(&v[row].to_string()),
                    ColumnData::Text(v) => line.push_str(&quote(&v[row])),
                }
            }
            line.push('\n');
            w.write_all(line.as_bytes())?;
        }
        Ok(())
    }
}

/// A finite `f64` in the shortest form that reads back exactly: plain for `1e-4 <= |x| < 1e15`
/// (and zero), exponent form otherwise (`1.5e-7`, `2e20`); readers in every language parse both.
pub fn format_f64(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || (1e-4..1e15).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Quotes a CSV field when needed (RFC 4180).
fn quote(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_f64_round_trips() {
        for x in [
            0.0,
            -0.0,
            0.1,
            1.0 / 3.0,
            1e-4,
            9.99e-5,
            1e15,
            -2.5e300,
            5e-324,
            123456.789,
        ] {
            let s = format_f64(x);
            assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{s}");
        }
        assert_eq!(format_f64(1e-7), "1e-7");
        assert_eq!(format_f64(0.25), "0.25");
    }

    #[test]
    fn quote_escapes_quotes() {
        assert_eq!(quote("a\"b"), "\"a\"\"b\"");
        assert_eq!(quote("plain"), "plain");
    }
}
