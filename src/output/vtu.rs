//! VTU files (VTK XML `UnstructuredGrid`) of fields on the curved body, and `.pvd` collections.
//!
//! The body's `(x2, x3)` grid is written as VTK quads (cell type 9) whose points are the
//! Cartesian positions `Theta(x1, x2, x3)` of the shell chart, so ParaView and meshio show
//! the body as it lies on the obstacle, not the parameter rectangle.
//!
//! Two encodings, both read by meshio 5 and VTK/ParaView: ASCII (shortest round-trip decimals,
//! so values read back exactly) and appended raw binary (`header_type="UInt64"`, little-endian).
//! Appended data may be zlib-compressed ([`Encoding::AppendedZlib`], VTK's
//! `vtkZLibDataCompressor` block format, written by our own code with flate2: vtkio 0.6's
//! compressed output is unreadable by both readers). A second piece can carry another surface
//! (the obstacle) beside the body.

use std::fmt::Write as _;
use std::io::Write;

use super::csv::format_f64;
use super::error::{OutputError, check_all_finite, check_finite};
pub use super::quad_grid::{QuadGrid, VTK_HEXAHEDRON, VTK_QUAD};

/// How the arrays of a VTU file are stored.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Encoding {
    /// Decimal text inside each `DataArray`: readable, larger, exact (shortest round-trip).
    Ascii,
    /// One `<AppendedData encoding="raw">` block of little-endian bytes, each array preceded by
    /// its byte count as a `UInt64`: compact and exact.
    #[default]
    AppendedRaw,
    /// Appended data compressed with zlib in blocks of 32 KiB (`compressor="vtkZLibDataCompressor"`):
    /// each array is a `UInt64` header (blocks, block size, last block size, compressed sizes)
    /// and the compressed blocks. Exact, smaller for smooth fields.
    AppendedZlib,
}

/// `output.vtu_compression`: how VTU arrays are stored.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum VtuCompression {
    /// Appended raw binary ([`Encoding::AppendedRaw`]).
    #[default]
    None,
    /// zlib ([`Encoding::AppendedZlib`]).
    Zlib,
}

impl VtuCompression {
    /// The encoding of this setting.
    pub fn encoding(self) -> Encoding {
        match self {
            Self::None => Encoding::AppendedRaw,
            Self::Zlib => Encoding::AppendedZlib,
        }
    }
}

/// Uncompressed bytes per zlib block (VTK's default).
const ZLIB_BLOCK: usize = 1 << 15;

/// `bytes` in VTK's compressed-block layout: the `UInt64` header, then the blocks.
fn zlib_blocks(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    use flate2::{Compression, write::ZlibEncoder};
    let blocks: Vec<&[u8]> = bytes.chunks(ZLIB_BLOCK).collect();
    let mut compressed = Vec::with_capacity(blocks.len());
    for b in &blocks {
        let mut e = ZlibEncoder::new(Vec::new(), Compression::default());
        e.write_all(b)?;
        compressed.push(e.finish()?);
    }
    let last = blocks.last().map_or(0, |b| b.len());
    let last = if last == ZLIB_BLOCK { 0 } else { last }; // 0: the last block is full
    let mut out = Vec::new();
    for x in [blocks.len(), ZLIB_BLOCK, last]
        .into_iter()
        .chain(compressed.iter().map(Vec::len))
    {
        out.extend((x as u64).to_le_bytes());
    }
    compressed.iter().for_each(|c| out.extend(c));
    Ok(out)
}

/// A named array of `f64` tuples attached to points or cells.
#[derive(Debug, Clone, PartialEq)]
pub struct DataArray {
    /// The array's name (`displacement`, `slip_state`).
    pub name: String,
    /// Components per tuple: 1 scalar, 3 vector, 9 tensor (row-major `T[i][j]`), or any other.
    pub components: usize,
    /// `tuples x components` values, tuple-major.
    pub values: Vec<f64>,
}

/// One VTU file: a [`QuadGrid`] with point data, cell data and an optional time value.
///
/// Checked before anything is written ([`Vtu::validate`]): array lengths, distinct names,
/// no NaN or infinity anywhere.
///
/// # Example
/// ```
/// use capstan::output::{Encoding, QuadGrid, Vtu};
/// let grid = QuadGrid::new(2, 2, false, vec![[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0]]).unwrap();
/// let vtu = Vtu::new(&grid)
///     .encoding(Encoding::Ascii)
///     .time(0.5)
///     .point_scalars("pressure", vec![1.0, 2.0, 3.0, 4.0])
///     .point_vectors("displacement", &[[0.0; 3]; 4])
///     .cell_scalars("area", vec![1.0]);
/// let mut s = Vec::new();
/// vtu.write(&mut s).unwrap();
/// let s = String::from_utf8(s).unwrap();
/// assert!(s.contains(r#"Name="TimeValue" NumberOfTuples="1""#));
/// assert!(s.contains(r#"<DataArray type="UInt8" Name="types" format="ascii">9</DataArray>"#));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Vtu<'g> {
    grid: &'g QuadGrid,
    encoding: Encoding,
    time: Option<f64>,
    point_data: Vec<DataArray>,
    cell_data: Vec<DataArray>,
    active: [Option<String>; 2],
    second: Option<&'g QuadGrid>,
}

impl<'g> Vtu<'g> {
    /// A file for `grid` with no data, appended raw encoding and no time value.
    pub fn new(grid: &'g QuadGrid) -> Self {
        Self {
            grid,
            encoding: Encoding::default(),
            time: None,
            point_data: Vec::new(),
            cell_data: Vec::new(),
            active: [None, None],
            second: None,
        }
    }

    /// Marks point array `name` as the active `Scalars` (what ParaView colours by first).
    pub fn active_scalars(mut self, name: impl Into<String>) -> Self {
        self.active[0] = Some(name.into());
        self
    }

    /// Marks point array `name` (3 components) as the active `Vectors` (what ParaView's
    /// "Warp By Vector" and glyphs use).
    pub fn active_vectors(mut self, name: impl Into<String>) -> Self {
        self.active[1] = Some(name.into());
        self
    }

    /// Adds `grid` as a second piece (e.g. the obstacle surface beside the body): the same
    /// point and cell arrays, zero there, so readers that merge pieces see one array per name.
    pub fn second_piece(mut self, grid: &'g QuadGrid) -> Self {
        self.second = Some(grid);
        self
    }

    /// Sets the encoding.
    pub fn encoding(mut self, encoding: Encoding) -> Self {
        self.encoding = encoding;
        self
    }

    /// Sets the dataset's `TimeValue` (FieldData, one tuple): the load step or sweep parameter.
    pub fn time(mut self, time: f64) -> Self {
        self.time = Some(time);
        self
    }

    /// Adds a scalar field, one value per node.
    pub fn point_scalars(self, name: impl Into<String>, values: impl Into<Vec<f64>>) -> Self {
        self.point_components(name, 1, values)
    }

    /// Adds a 3-vector field in Cartesian components, one per node (see
    /// [`QuadGrid::to_cartesian`] for contravariant components).
    pub fn point_vectors(self, name: impl Into<String>, values: &[[f64; 3]]) -> Self {
        self.point_components(name, 3, values.as_flattened())
    }

    /// Adds a 3x3 tensor field (stress, strain), one per node, written row-major (9 components).
    pub fn point_tensors(self, name: impl Into<String>, values: &[[[f64; 3]; 3]]) -> Self {
        self.point_components(name, 9, values.as_flattened().as_flattened())
    }

    /// Adds a point field with `components` values per node, tuple-major.
    pub fn point_components(
        mut self,
        name: impl Into<String>,
        components: usize,
        values: impl Into<Vec<f64>>,
    ) -> Self {
        self.point_data.push(DataArray {
            name: name.into(),
            components,
            values: values.into(),
        });
        self
    }

    /// Adds a scalar field, one value per cell (in [`QuadGrid::cells`] order).
    pub fn cell_scalars(self, name: impl Into<String>, values: impl Into<Vec<f64>>) -> Self {
        self.cell_components(name, 1, values)
    }

    /// Adds a 3-vector field, one per cell.
    pub fn cell_vectors(self, name: impl Into<String>, values: &[[f64; 3]]) -> Self {
        self.cell_components(name, 3, values.as_flattened())
    }

    /// Adds a cell field with `components` values per cell, tuple-major.
    pub fn cell_components(
        mut self,
        name: impl Into<String>,
        components: usize,
        values: impl Into<Vec<f64>>,
    ) -> Self {
        self.cell_data.push(DataArray {
            name: name.into(),
            components,
            values: values.into(),
        });
        self
    }

    /// The point arrays, in the order they were added.
    pub fn point_arrays(&self) -> &[DataArray] {
        &self.point_data
    }

    /// The grid the arrays live on.
    pub fn grid(&self) -> &QuadGrid {
        self.grid
    }

    /// Checks the file can be written.
    ///
    /// # Errors
    /// [`OutputError::InvalidName`] for an empty name or one with `"`, `<`, `>` or `&`;
    /// [`OutputError::InvalidParameter`] for zero components; [`OutputError::DuplicateName`]
    /// within point or cell data; [`OutputError::LengthMismatch`] unless an array has
    /// `tuples x components` values; [`OutputError::NonFinite`] naming the array (the index is
    /// into its flat values) or `TimeValue`.
    pub fn validate(&self) -> Result<(), OutputError> {
        if let Some(t) = self.time {
            check_finite("TimeValue", 0, t)?;
        }
        let groups = [
            (&self.point_data, self.grid.node_count()),
            (&self.cell_data, self.grid.cell_count()),
        ];
        for (arrays, tuples) in groups {
            for (i, a) in arrays.iter().enumerate() {
                check_xml_name(&a.name)?;
                if arrays[..i].iter().any(|b| b.name == a.name) {
                    return Err(OutputError::DuplicateName {
                        name: a.name.clone(),
                    });
                }
                if a.components == 0 {
                    return Err(OutputError::InvalidParameter {
                        field: "components",
                        value: 0.0,
                        allowed: "[1, inf)",
                    });
                }
                if a.values.len() != tuples * a.components {
                    return Err(OutputError::LengthMismatch {
                        column: a.name.clone(),
                        expected: tuples * a.components,
                        found: a.values.len(),
                    });
                }
                check_all_finite(&a.name, &a.values)?;
            }
        }
        for (name, components) in self.active.iter().zip([1, 3]) {
            if let Some(name) = name {
                check_xml_name(name)?;
                let found = self.point_data.iter().find(|a| &a.name == name);
                if found.is_none_or(|a| a.components != components) {
                    return Err(OutputError::InvalidName {
                        name: name.clone(),
                        reason: if components == 1 {
                            "is not a scalar point array (active Scalars)"
                        } else {
                            "is not a 3-component point array (active Vectors)"
                        },
                    });
                }
            }
        }
        Ok(())
    }

    /// Writes the file.
    ///
    /// # Errors
    /// As [`Vtu::validate`] (checked before anything is written), or an I/O error.
    pub fn write<W: Write + ?Sized>(&self, w: &mut W) -> Result<(), OutputError> {
        self.validate()?;
        // The second piece: its grid with every array of the first, zero.
        let zeros = |arrays: &[DataArray], tuples: usize| -> Vec<DataArray> {
            arrays
                .iter()
                .map(|a| DataArray {
                    name: a.name.clone(),
                    components: a.components,
                    values: vec![0.0; tuples * a.components],
                })
                .collect()
        };
        let second = self.second.map(|g| {
            (
                g,
                zeros(&self.point_data, g.node_count()),
                zeros(&self.cell_data, g.cell_count()),
            )
        });
        let mut pieces = vec![(self.grid, &self.point_data, &self.cell_data)];
        if let Some((g, p, c)) = &second {
            pieces.push((g, p, c));
        }
        let topology: Vec<(Vec<i64>, Vec<i64>, Vec<u8>)> = pieces
            .iter()
            .map(|(g, _, _)| {
                let (connectivity, per_cell, kind) = g.topology();
                let cells = connectivity.len() / per_cell;
                (
                    connectivity.iter().map(|&k| k as i64).collect(),
                    (1..=cells as i64).map(|c| per_cell as i64 * c).collect(),
                    vec![kind; cells],
                )
            })
            .collect();

        // The document as a list of text and arrays, rendered once the encoding is known.
        let mut items: Vec<Item<'_>> = Vec::new();
        let text = |items: &mut Vec<Item<'_>>, s: String| items.push(Item::Text(s));
        let compressor = if self.encoding == Encoding::AppendedZlib {
            " compressor=\"vtkZLibDataCompressor\""
        } else {
            ""
        };
        text(
            &mut items,
            format!(
                "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"{compressor}>\n  <UnstructuredGrid>\n"
            ),
        );
        if let Some(t) = self.time {
            // ASCII in every encoding: one value; VTK needs NumberOfTuples="1" to take it.
            text(
                &mut items,
                format!(
                    "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{}</DataArray>\n    </FieldData>\n",
                    format_f64(t)
                ),
            );
        }
        let active: String = [("Scalars", &self.active[0]), ("Vectors", &self.active[1])]
            .iter()
            .filter_map(|(k, v)| v.as_ref().map(|v| format!(" {k}=\"{v}\"")))
            .collect();
        for ((grid, point_data, cell_data), (connectivity, offsets, types)) in
            pieces.iter().zip(&topology)
        {
            text(
                &mut items,
                format!(
                    "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
                    grid.node_count(),
                    types.len()
                ),
            );
            for (tag, arrays, attrs) in [
                ("PointData", *point_data, active.as_str()),
                ("CellData", *cell_data, ""),
            ] {
                if arrays.is_empty() {
                    continue;
                }
                text(&mut items, format!("      <{tag}{attrs}>\n"));
                for a in arrays.iter() {
                    // Scalars omit NumberOfComponents (VTK's default, 1): meshio then gives
                    // shape (n,) rather than (n, 1).
                    let attributes = if a.components == 1 {
                        format!("type=\"Float64\" Name=\"{}\"", a.name)
                    } else {
                        format!(
                            "type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\"",
                            a.name, a.components
                        )
                    };
                    items.push(Item::Array(attributes, Block::F64(&a.values)));
                }
                text(&mut items, format!("      </{tag}>\n"));
            }
            text(&mut items, "      <Points>\n".to_owned());
            items.push(Item::Array(
                "type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"".to_owned(),
                Block::F64(grid.points().as_flattened()),
            ));
            text(&mut items, "      </Points>\n      <Cells>\n".to_owned());
            items.push(Item::Array(
                "type=\"Int64\" Name=\"connectivity\"".to_owned(),
                Block::I64(connectivity),
            ));
            items.push(Item::Array(
                "type=\"Int64\" Name=\"offsets\"".to_owned(),
                Block::I64(offsets),
            ));
            items.push(Item::Array(
                "type=\"UInt8\" Name=\"types\"".to_owned(),
                Block::U8(types),
            ));
            text(&mut items, "      </Cells>\n    </Piece>\n".to_owned());
        }
        text(&mut items, "  </UnstructuredGrid>\n".to_owned());

        let mut xml = String::new();
        let mut blocks: Vec<Vec<u8>> = Vec::new();
        let mut offset = 0usize;
        for item in items {
            match item {
                Item::Text(s) => xml.push_str(&s),
                Item::Array(attributes, data) => {
                    let _ = write!(xml, "        <DataArray {attributes}");
                    match self.encoding {
                        Encoding::Ascii => {
                            xml.push_str(" format=\"ascii\">");
                            data.ascii(&mut xml);
                            xml.push_str("</DataArray>\n");
                        }
                        Encoding::AppendedRaw | Encoding::AppendedZlib => {
                            let _ = writeln!(xml, " format=\"appended\" offset=\"{offset}\"/>");
                            let mut raw = Vec::with_capacity(8 + data.byte_len());
                            let block = if self.encoding == Encoding::AppendedZlib {
                                data.write_le(&mut raw)?;
                                zlib_blocks(&raw)?
                            } else {
                                raw.extend((data.byte_len() as u64).to_le_bytes());
                                data.write_le(&mut raw)?;
                                raw
                            };
                            offset += block.len();
                            blocks.push(block);
                        }
                    }
                }
            }
        }
        w.write_all(xml.as_bytes())?;
        if self.encoding != Encoding::Ascii {
            w.write_all(b"  <AppendedData encoding=\"raw\">\n   _")?;
            for b in &blocks {
                w.write_all(b)?;
            }
            // meshio drops everything after the last newline of the block: end with one.
            w.write_all(b"\n  </AppendedData>\n")?;
        }
        w.write_all(b"</VTKFile>\n")?;
        Ok(())
    }
}

/// A piece of the XML document: literal text or a data array (attributes, values).
enum Item<'a> {
    Text(String),
    Array(String, Block<'a>),
}

/// The values of one array on its way out.
enum Block<'a> {
    F64(&'a [f64]),
    I64(&'a [i64]),
    U8(&'a [u8]),
}

impl Block<'_> {
    fn byte_len(&self) -> usize {
        match self {
            Self::F64(v) => 8 * v.len(),
            Self::I64(v) => 8 * v.len(),
            Self::U8(v) => v.len(),
        }
    }

    fn ascii(&self, out: &mut String) {
        fn join<T>(out: &mut String, v: &[T], f: impl Fn(&T) -> String) {
            for (i, x) in v.iter().enumerate() {
                if i > 0 {
                    out.push(' ');
                }
                out.push_str(&f(x));
            }
        }
        match self {
            Self::F64(v) => join(out, v, |x| format_f64(*x)),
            Self::I64(v) => join(out, v, i64::to_string),
            Self::U8(v) => join(out, v, u8::to_string),
        }
    }

    fn write_le<W: Write + ?Sized>(&self, w: &mut W) -> std::io::Result<()> {
        let mut buf = Vec::with_capacity(self.byte_len());
        match self {
            Self::F64(v) => v.iter().for_each(|x| buf.extend(x.to_le_bytes())),
            Self::I64(v) => v.iter().for_each(|x| buf.extend(x.to_le_bytes())),
            Self::U8(v) => buf.extend_from_slice(v),
        }
        w.write_all(&buf)
    }
}

/// Names go into XML attributes unescaped: refuse the characters that would need escaping.
fn check_xml_name(name: &str) -> Result<(), OutputError> {
    let reason = if name.is_empty() {
        "is empty"
    } else if name.contains(['"', '<', '>', '&']) {
        "contains one of \" < > &"
    } else if name.chars().any(char::is_control) {
        "contains a control character"
    } else {
        return Ok(());
    };
    Err(OutputError::InvalidName {
        name: name.to_owned(),
        reason,
    })
}

/// A ParaView `.pvd` collection: one VTU file per time step or sweep point.
///
/// ParaView opens the collection as a time series, its `TimeValue` being the step's `timestep`
/// (a load factor or a swept parameter such as `b/a`). meshio cannot read `.pvd`; read the
/// VTU files one by one there.
///
/// # Example
/// ```
/// use capstan::output::Pvd;
/// let mut pvd = Pvd::new();
/// pvd.push(0.5, "fields/ratio_0.vtu").push(1.0, "fields/ratio_1.vtu");
/// let mut s = Vec::new();
/// pvd.write(&mut s).unwrap();
/// assert!(String::from_utf8(s).unwrap().contains(r#"<DataSet timestep="1" part="0" file="fields/ratio_1.vtu"/>"#));
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pvd {
    entries: Vec<(f64, String)>,
}

impl Pvd {
    /// An empty collection.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the VTU file `file` (relative to the `.pvd` file) at time `time`.
    pub fn push(&mut self, time: f64, file: impl Into<String>) -> &mut Self {
        self.entries.push((time, file.into()));
        self
    }

    /// The entries `(time, file)`, in order.
    pub fn entries(&self) -> &[(f64, String)] {
        &self.entries
    }

    /// Checks the collection can be written.
    ///
    /// # Errors
    /// [`OutputError::NonFinite`] for a non-finite time (index = entry), [`OutputError::InvalidName`]
    /// for a file name that is empty or needs XML escaping.
    pub fn validate(&self) -> Result<(), OutputError> {
        for (i, (t, file)) in self.entries.iter().enumerate() {
            check_finite("timestep", i, *t)?;
            check_xml_name(file)?;
        }
        Ok(())
    }

    /// Writes the collection.
    ///
    /// # Errors
    /// As [`Pvd::validate`] (checked before anything is written), or an I/O error.
    pub fn write<W: Write + ?Sized>(&self, w: &mut W) -> Result<(), OutputError> {
        self.validate()?;
        let mut xml = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
        );
        for (t, file) in &self.entries {
            let _ = writeln!(
                xml,
                "    <DataSet timestep=\"{}\" part=\"0\" file=\"{file}\"/>",
                format_f64(*t)
            );
        }
        xml.push_str("  </Collection>\n</VTKFile>\n");
        w.write_all(xml.as_bytes())?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_square() -> QuadGrid {
        QuadGrid::new(
            2,
            2,
            false,
            vec![[0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0]],
        )
        .unwrap()
    }

    #[test]
    fn periodic_grid_closes_the_ring() {
        let pts = vec![[0.0; 3]; 8];
        let g = QuadGrid::new(4, 2, true, pts).unwrap();
        assert_eq!(g.cell_count(), 4);
        assert_eq!(g.cells()[3], [6, 0, 1, 7]);
    }

    #[test]
    fn new_rejects_short_point_list() {
        let r = QuadGrid::new(3, 2, false, vec![[0.0; 3]; 5]);
        assert!(matches!(
            r,
            Err(OutputError::LengthMismatch {
                expected: 6,
                found: 5,
                ..
            })
        ));
    }

    #[test]
    fn appended_offsets_count_headers() {
        let g = unit_square();
        let vtu = Vtu::new(&g).point_scalars("p", vec![0.0; 4]);
        let mut s = Vec::new();
        vtu.write(&mut s).unwrap();
        let text = String::from_utf8_lossy(&s);
        // p: 8 + 32 bytes, Points at 40: 8 + 96, connectivity at 144
        assert!(
            text.contains(r#"Name="Points" NumberOfComponents="3" format="appended" offset="40""#)
        );
        assert!(text.contains(r#"Name="connectivity" format="appended" offset="144""#));
    }

    #[test]
    fn validate_names_bad_array() {
        let g = unit_square();
        let r = Vtu::new(&g)
            .point_scalars("p", vec![0.0, 1.0, f64::NAN, 0.0])
            .validate();
        assert!(
            matches!(r, Err(OutputError::NonFinite { ref column, index: 2, .. }) if column == "p")
        );
        let r = Vtu::new(&g).cell_scalars("c", vec![0.0, 1.0]).validate();
        assert!(matches!(
            r,
            Err(OutputError::LengthMismatch {
                expected: 1,
                found: 2,
                ..
            })
        ));
        let r = Vtu::new(&g).point_scalars("a<b", vec![0.0; 4]).validate();
        assert!(matches!(r, Err(OutputError::InvalidName { .. })));
    }
}
