//! Output files that researchers' tools read: CSV, JSON, VTU (+ `.pvd`), SVG and PNG plots.
//!
//! Every file is written atomically ([`write_atomic`]): into a temporary file in the same
//! directory, renamed into place only when complete, so a failed run leaves no half file.
//! No NaN or infinity ever reaches a file: each writer checks its data first and returns
//! [`OutputError::NonFinite`] naming the column, array or JSON path.
//!
//! The writers are generic over the data (columns, arrays, any `Serialize` value); the
//! commands assemble what they computed and hand it over, usually through an [`OutputDir`].
//!
//! Known limitations: VTU data arrays are `Float64` only (a stick/slip state is written as
//! -1.0/0.0/1.0); VTU files are uncompressed.

mod atomic;
pub mod body;
mod csv;
mod error;
mod json;
mod matrix_market;
mod out_dir;
mod quad_grid;
pub mod solid_body;
mod vtu;

pub use atomic::{commit_deferred, defer_commits, discard_outputs_and, write_atomic};
pub use csv::{Column, ColumnData, Table, format_f64};
pub use error::OutputError;
pub use json::{check_finite_json, to_json_string, write_json};
pub use matrix_market::{write_matrix_market_array, write_matrix_market_coordinate};
pub use out_dir::OutputDir;
pub use vtu::{DataArray, Encoding, Pvd, QuadGrid, VTK_HEXAHEDRON, VTK_QUAD, Vtu, VtuCompression};
mod plot;

pub use plot::{
    ColourMap, Legend, LinePlot, Panel, Plot, Scale, Series, StateStrip, register_fonts,
    render_png, render_svg, write_plot,
};
