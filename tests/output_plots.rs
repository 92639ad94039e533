//! Plots: each kind writes a non-trivial SVG and PNG; bad data writes nothing.
//!
//! The samples land in `target/tmp/output_plots/` for a look.

use std::path::{Path, PathBuf};

use capstan::commands::geometry::linspace;
use capstan::geometry::{CircularCylinder, EllipticalPrism, ShellChart};
use capstan::output::{
    ColourMap, LinePlot, OutputDir, OutputError, Plot, QuadGrid, Series, StateStrip, write_plot,
};

fn out_dir() -> OutputDir {
    OutputDir::create(Path::new(env!("CARGO_TARGET_TMPDIR")).join("output_plots")).unwrap()
}

/// Decodes the PNG, checks its size and that it is not blank; returns the share of
/// non-white pixels.
fn check_png(path: &Path, size: (u32, u32)) -> f64 {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), size, "{}", path.display());
    let ink = buf[..info.buffer_size()]
        .chunks(3)
        .filter(|p| p.iter().any(|&c| c < 250))
        .count();
    ink as f64 / f64::from(size.0 * size.1)
}

fn check_files(paths: &[PathBuf; 2], size: (u32, u32), texts: &[&str]) -> f64 {
    let svg = std::fs::read_to_string(&paths[0]).unwrap();
    assert!(svg.starts_with("<svg"), "{}", paths[0].display());
    for t in texts {
        assert!(svg.contains(t), "{} lacks {t:?}", paths[0].display());
    }
    let ink = check_png(&paths[1], size);
    assert!(ink > 0.01, "{} is nearly blank ({ink})", paths[1].display());
    ink
}

#[test]
fn tension_profiles_line_plot() {
    let out = out_dir();
    let theta = linspace(0.0, std::f64::consts::PI, 60);
    let mut plot = LinePlot::new("Tension along the contact, T(θ) = T₀ exp(μθ)")
        .x_label("θ (rad)")
        .y_label("T / T₀");
    for mu in [0.1, 0.3, 0.5] {
        let t: Vec<f64> = theta.iter().map(|x| (mu * x).exp()).collect();
        plot = plot.series(Series::line(format!("μ = {mu}"), theta.clone(), t));
    }
    let sample = [0.0, 0.8, 1.6, 2.4, 3.1];
    plot = plot.series(Series::markers(
        "paper, μ = 0.5",
        sample,
        sample.map(|x| (0.5 * x).exp()),
    ));
    let paths = write_plot(&out.file("tension_profiles").unwrap(), &plot).unwrap();
    check_files(&paths, plot.dimensions(), &["μ = 0.3", "T / T₀", "paper"]);
}

#[test]
fn ratio_against_b_over_a_with_markers() {
    let out = out_dir();
    let ba = linspace(0.25, 2.0, 8);
    let plot = LinePlot::new("Capstan ratio on an elliptical prism")
        .x_label("b / a")
        .y_label("T(θ₁) / T(θ₀)")
        .series(
            Series::line(
                "membrane",
                ba.clone(),
                ba.iter().map(|r| 1.0 + 0.6 / r).collect::<Vec<_>>(),
            )
            .with_markers(),
        )
        .series(
            Series::line(
                "thick body",
                ba.clone(),
                ba.iter().map(|r| 1.0 + 0.5 / r).collect::<Vec<_>>(),
            )
            .with_markers(),
        )
        .series(Series::markers(
            "paper Table 1",
            [0.5, 1.0, 2.0],
            [2.1, 1.55, 1.27],
        ));
    let paths = out.write_plot("ratio_vs_ba", &plot).unwrap();
    check_files(&paths, plot.dimensions(), &["b / a", "thick body"]);
}

#[test]
fn work_precision_log_log() {
    let out = out_dir();
    let time = [1e-3, 4e-3, 1.6e-2, 6.4e-2, 0.256];
    let plot = LinePlot::new("Work-precision")
        .x_label("wall time (s)")
        .y_label("error in T(θ₁)")
        .log_log()
        .series(
            Series::line("DOP853", time, time.map(|t: f64| 1e-12 * t.powf(-4.0))).with_markers(),
        )
        .series(
            Series::line("Newton + LU", time, time.map(|t: f64| 1e-6 * t.powf(-1.0)))
                .with_markers(),
        )
        .series(
            Series::line(
                "Jacobi–Newton",
                time,
                time.map(|t: f64| 3e-4 * t.powf(-0.5)),
            )
            .with_markers(),
        );
    let paths = out.write_plot("work_precision", &plot).unwrap();
    check_files(&paths, plot.dimensions(), &["Work-precision", "Jacobi"]);
}

#[test]
fn stick_slip_strip() {
    let out = out_dir();
    let x = linspace(0.0, std::f64::consts::PI, 50);
    let states: Vec<i32> = x
        .iter()
        .map(|&t| {
            if t < 0.8 {
                0
            } else if t < 2.4 {
                1
            } else {
                -1
            }
        })
        .collect();
    let strip = StateStrip::new("Contact state along x²", x, states).x_label("x² (rad)");
    let paths = out.write_plot("slip_state", &strip).unwrap();
    check_files(&paths, strip.dimensions(), &["stick", "slip +", "slip -"]);
}

#[test]
fn colour_map_on_the_curved_body() {
    let out = out_dir();
    // Half a wrap of a body of thickness 0.3 over the ellipse a = 2, b = 1.
    let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
    let x2 = linspace(0.0, std::f64::consts::PI, 80);
    let x3 = linspace(0.0, 0.3, 9);
    let grid = QuadGrid::from_chart(&chart, 0.0, &x2, &x3, false).unwrap();
    let field: Vec<f64> = (0..grid.node_count())
        .map(|k| {
            let (t, h) = (x2[k / x3.len()], x3[k % x3.len()]);
            (2.0 * t).sin() * (1.0 - h / 0.3) * 1e5
        })
        .collect();
    let map = ColourMap::nodal("Normal stress σ³³ on the body", &grid, [1, 2], &field)
        .unwrap()
        .label("σ³³ (Pa)");
    let paths = out.write_plot("colour_map_ellipse", &map).unwrap();
    check_files(&paths, map.dimensions(), &["σ³³ (Pa)"]);

    // A full wrap around a cylinder, periodic in x2, coloured per cell.
    let chart = ShellChart::new(CircularCylinder::new(1.0).unwrap());
    let n2 = 64;
    let x2: Vec<f64> = (0..n2)
        .map(|i| std::f64::consts::TAU * i as f64 / n2 as f64)
        .collect();
    let grid = QuadGrid::from_chart(&chart, 0.0, &x2, &linspace(0.0, 0.4, 5), true).unwrap();
    let cells: Vec<f64> = (0..grid.cell_count()).map(|c| (c / 4) as f64).collect();
    let map = ColourMap::cellwise("Full wrap (periodic x²)", &grid, [1, 2], &cells)
        .unwrap()
        .label("cell column");
    let paths = out.write_plot("colour_map_ring", &map).unwrap();
    check_files(&paths, map.dimensions(), &["Full wrap"]);
}

#[test]
fn bad_plot_data_writes_nothing() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("output_plots_bad");
    let _ = std::fs::remove_dir_all(&dir);
    let out = OutputDir::create(&dir).unwrap();
    let nan = LinePlot::new("x").series(Series::line("s", [0.0, 1.0], [1.0, f64::NAN]));
    assert!(matches!(
        out.write_plot("nan", &nan),
        Err(OutputError::NonFinite { ref column, index: 1, .. }) if column == "s.y"
    ));
    let log = LinePlot::new("x")
        .log_log()
        .series(Series::line("s", [0.0, 1.0], [1.0, 2.0]));
    assert!(matches!(
        out.write_plot("log", &log),
        Err(OutputError::InvalidParameter { value: 0.0, .. })
    ));
    let strip = StateStrip::new("x", [0.0, 1.0], [0, 3]); // 2 is a lifted-off node
    assert!(out.write_plot("strip", &strip).is_err());
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}
