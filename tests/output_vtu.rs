//! VTU files read back by meshio (`tests/python/check_vtu.py`), and `.pvd` collections.
//!
//! meshio lives in the repository's `.venv` (`.ci/run` creates it). Without it the meshio test
//! prints why and passes, so a plain `cargo test` works on a machine without Python packages;
//! under `CI=true` a missing meshio fails the test instead.

mod common;

use std::path::PathBuf;

use capstan::commands::geometry::linspace;
use capstan::geometry::{CircularCylinder, EllipticalPrism, ShellChart};
use capstan::output::{Encoding, OutputDir, Pvd, QuadGrid, Vtu};
use common::scratch_dir as scratch;
use serde::Serialize;

/// What the check script compares the file against.
#[derive(Serialize)]
struct Case {
    path: PathBuf,
    points: Vec<[f64; 3]>,
    n2: usize,
    n3: usize,
    periodic: bool,
    cells: Vec<[usize; 4]>,
    point_data: serde_json::Map<String, serde_json::Value>,
    cell_data: serde_json::Map<String, serde_json::Value>,
    time: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ellipse: Option<serde_json::Value>,
}

impl Case {
    /// What `grid` written to `path` holds: its points, sizes, periodicity and cells, with
    /// `point_data` and `cell_data`; no time value and no ellipse to compare with.
    fn new(
        path: PathBuf,
        grid: &QuadGrid,
        point_data: serde_json::Map<String, serde_json::Value>,
        cell_data: serde_json::Map<String, serde_json::Value>,
    ) -> Self {
        Self {
            path,
            points: grid.points().to_vec(),
            n2: grid.n2(),
            n3: grid.n3(),
            periodic: grid.is_periodic(),
            cells: grid.cells(),
            point_data,
            cell_data,
            time: None,
            ellipse: None,
        }
    }
}

fn array(components: usize, values: &[f64]) -> serde_json::Value {
    serde_json::json!({ "components": components, "values": values })
}

/// The body over an ellipse `a = 2, b = 1`, half a wrap, with a scalar, a vector (the outward
/// normal scaled, converted from contravariant components), a tensor and a cell field.
fn ellipse_case(out: &OutputDir, encoding: Encoding, name: &str) -> Case {
    let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
    let x2 = linspace(-0.3, std::f64::consts::PI, 13);
    let x3 = linspace(0.0, 0.25, 4);
    let grid = QuadGrid::from_chart(&chart, 0.0, &x2, &x3, false).unwrap();
    let n = grid.node_count();
    let theta: Vec<f64> = (0..n).map(|k| x2[k / x3.len()]).collect();
    // u = 0.01 g_3 + 0.1 g_2: contravariant components, converted with the covariant basis
    let u = grid.to_cartesian(&vec![[0.0, 0.1, 0.01]; n]).unwrap();
    let stress: Vec<[[f64; 3]; 3]> = (0..n)
        .map(|k| {
            let s = k as f64;
            [[s, 1.0, 2.0], [1.0, -s, 3.0], [2.0, 3.0, 0.5 * s]]
        })
        .collect();
    let cell_ids: Vec<f64> = (0..grid.cell_count()).map(|c| c as f64 * 0.1).collect();
    let vtu = Vtu::new(&grid)
        .encoding(encoding)
        .time(0.25)
        .point_scalars("x2", theta.clone())
        .point_vectors("displacement", &u)
        .point_tensors("stress", &stress)
        .cell_scalars("cell_value", cell_ids.clone());
    let path = out.write_vtu(name, &vtu).unwrap();
    let mut point_data = serde_json::Map::new();
    point_data.insert("x2".into(), array(1, &theta));
    point_data.insert("displacement".into(), array(3, u.as_flattened()));
    point_data.insert(
        "stress".into(),
        array(9, stress.as_flattened().as_flattened()),
    );
    let mut cell_data = serde_json::Map::new();
    cell_data.insert("cell_value".into(), array(1, &cell_ids));
    Case {
        time: Some(0.25),
        ellipse: Some(serde_json::json!({ "a": 2.0, "b": 1.0, "x3": x3 })),
        ..Case::new(path, &grid, point_data, cell_data)
    }
}

/// A full wrap of a cylinder, periodic in `x2`, no time value and no cell data.
fn ring_case(out: &OutputDir) -> Case {
    let chart = ShellChart::new(CircularCylinder::new(1.5).unwrap());
    let n2 = 16;
    let x2: Vec<f64> = (0..n2)
        .map(|i| std::f64::consts::TAU * i as f64 / n2 as f64)
        .collect();
    let x3 = linspace(0.0, 0.5, 3);
    let grid = QuadGrid::from_chart(&chart, 0.0, &x2, &x3, true).unwrap();
    let radius: Vec<f64> = grid.points().iter().map(|p| p[1].hypot(p[2])).collect();
    let vtu = Vtu::new(&grid).point_scalars("radius", radius.clone());
    let path = out.write_vtu("ring.vtu", &vtu).unwrap();
    let mut point_data = serde_json::Map::new();
    point_data.insert("radius".into(), array(1, &radius));
    Case::new(path, &grid, point_data, serde_json::Map::new())
}

#[test]
fn vtu_files_read_back_by_meshio() {
    let dir = scratch("output_vtu_meshio");
    let out = OutputDir::create(&dir).unwrap();
    let cases = vec![
        ellipse_case(&out, Encoding::Ascii, "ellipse_ascii.vtu"),
        ellipse_case(&out, Encoding::AppendedRaw, "fields/ellipse_raw.vtu"),
        ring_case(&out),
    ];
    let expected = out.write_json("expected.json", &cases).unwrap();
    let Some(report) = common::check_vtu_with_meshio("vtu_files_read_back_by_meshio", &expected)
    else {
        return;
    };
    assert!(report.contains("3 files read back"), "{report}");
}

#[test]
fn raw_and_ascii_files_hold_the_same_structure() {
    let dir = scratch("output_vtu_structure");
    let out = OutputDir::create(&dir).unwrap();
    let ascii = ellipse_case(&out, Encoding::Ascii, "a.vtu");
    let raw = ellipse_case(&out, Encoding::AppendedRaw, "r.vtu");
    let a = std::fs::read(&ascii.path).unwrap();
    let r = std::fs::read(&raw.path).unwrap();
    let a = String::from_utf8(a).expect("ASCII encoding is text");
    assert!(!a.contains("appended") && a.matches("format=\"ascii\"").count() == 9);
    let header = String::from_utf8_lossy(&r[..r.len().min(4096)]);
    assert!(header.contains(r#"header_type="UInt64""#));
    assert!(header.contains(r#"<AppendedData encoding="raw">"#));
    assert!(r.ends_with(b"\n  </AppendedData>\n</VTKFile>\n"));
}

/// A 2 x 2 node grid of one cell.
fn unit_square() -> QuadGrid {
    QuadGrid::new(
        2,
        2,
        false,
        vec![[0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0; 3]],
    )
    .unwrap()
}

#[test]
fn nan_in_a_field_leaves_no_file() {
    let dir = scratch("output_vtu_nan");
    let out = OutputDir::create(&dir).unwrap();
    let grid = unit_square();
    let vtu = Vtu::new(&grid).point_scalars("pressure", vec![0.0, f64::NAN, 1.0, 2.0]);
    let err = out.write_vtu("bad.vtu", &vtu).unwrap_err();
    assert!(err.to_string().contains("`pressure`[1]"), "{err}");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}

#[test]
fn pvd_lists_the_sweep() {
    let dir = scratch("output_vtu_pvd");
    let out = OutputDir::create(&dir).unwrap();
    let grid = unit_square();
    let mut pvd = Pvd::new();
    for (i, ratio) in [0.5, 1.0, 2.0].into_iter().enumerate() {
        let name = format!("sweep/ratio_{i:03}.vtu");
        out.write_vtu(&name, &Vtu::new(&grid).time(ratio)).unwrap();
        pvd.push(ratio, name);
    }
    let path = out.write("sweep.pvd", |w| pvd.write(w)).unwrap();
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains(r#"<VTKFile type="Collection""#));
    assert_eq!(text.matches("<DataSet ").count(), 3);
    assert!(text.contains(r#"timestep="2" part="0" file="sweep/ratio_002.vtu""#));
    let mut bad = Pvd::new();
    bad.push(f64::NAN, "x.vtu");
    assert!(out.write("bad.pvd", |w| bad.write(w)).is_err());
    assert!(!dir.join("bad.pvd").exists());
}
