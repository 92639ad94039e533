//! Outputs a researcher looks at: the contact VTU read back by meshio, the plots and files of
//! `capstan contact --out` and `capstan sweep --out`, and `capstan figure all --quick`.
//!
//! meshio lives in the repository's `.venv` (`.ci/run` creates it); without it the meshio
//! check prints why and passes, unless `CI=true`.

mod common;

use std::path::Path;

use capstan::geometry::{EllipticalPrism, ShellChart};
use capstan::output::QuadGrid;
use common::{capstan, scratch_dir as scratch};

/// Columns of a CSV file by name.
fn csv(path: &Path) -> std::collections::HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let names: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let mut cols = vec![Vec::new(); names.len()];
    for l in lines {
        for (c, v) in l.split(',').enumerate() {
            cols[c].push(v.parse::<f64>().unwrap_or(f64::NAN));
        }
    }
    names.into_iter().zip(cols).collect()
}

#[test]
fn contact_out_writes_a_vtu_that_meshio_reads() {
    let dir = scratch("figures_contact_vtu");
    let d = dir.to_str().unwrap();
    let (n2, n3) = (16usize, 5usize);
    capstan(&[
        "contact",
        "--set",
        &format!("grid.n2={n2}"),
        "--set",
        &format!("grid.n3={n3}"),
        "--set",
        "loads.tau_max=1.5",
        "--out",
        d,
        "--quiet",
    ]);
    for f in [
        "contact.json",
        "contact.csv",
        "displacement.csv",
        "body.vtu",
        "body_v2.svg",
        "body_v2.png",
        "body_v3.svg",
        "body_v3.png",
        "body_state.svg",
        "body_state.png",
    ] {
        assert!(dir.join(f).is_file(), "missing {f}");
    }
    // What the VTU must hold, recomputed from the CSV files (shortest round-trip decimals).
    let nodes = csv(&dir.join("displacement.csv"));
    let contact = csv(&dir.join("contact.csv"));
    let (x2, x3) = (&nodes["x2"], &nodes["x3"]);
    assert_eq!(x2.len(), n2 * n3);
    let x2u: Vec<f64> = (0..n2).map(|i| x2[i * n3]).collect();
    let x3u: Vec<f64> = (0..n3).map(|j| x3[j]).collect();
    let chart = ShellChart::new(EllipticalPrism::new(2.0, 2.0).unwrap());
    let grid = QuadGrid::from_chart(&chart, 0.0, &x2u, &x3u, false).unwrap();
    let contra: Vec<[f64; 3]> = (0..n2 * n3)
        .map(|k| [0.0, nodes["v2"][k], nodes["v3"][k]])
        .collect();
    let cartesian = grid.to_cartesian(&contra).unwrap();
    // the contact node of each column: its state and slip spread over the column
    let column = |name: &str| -> Vec<f64> {
        (0..n2 * n3)
            .map(|k| {
                let x = x2[k];
                contact["x2"]
                    .iter()
                    .position(|&c| (c - x).abs() < 1e-12)
                    .map_or(0.0, |i| contact[name][i])
            })
            .collect()
    };
    let array = |c: usize, v: Vec<f64>| serde_json::json!({ "components": c, "values": v });
    let case = serde_json::json!([{
        "path": dir.join("body.vtu"),
        "points": grid.points(),
        "n2": n2, "n3": n3, "periodic": false,
        "cells": grid.cells(),
        "point_data": {
            "displacement_contravariant": array(3, contra.as_flattened().to_vec()),
            "displacement": array(3, cartesian.as_flattened().to_vec()),
            "contact_state": array(1, column("state")),
            "contact_slip": array(1, column("slip")),
            "x2": array(1, x2.clone()),
            "x3": array(1, x3.clone()),
        },
        "point_shapes": {
            "displacement_physical": 3,
            "stress": 9, "stress_physical": 9, "strain": 9, "strain_physical": 9,
        },
        "atol": 1e-15,
        "cell_data": {},
        "time": null,
        "ellipse": { "a": 2.0, "b": 2.0, "x3": x3u },
    }]);
    let expected = dir.join("expected.json");
    std::fs::write(&expected, serde_json::to_string(&case).unwrap()).unwrap();
    // the VTU's arrays are the documented ones
    let vtu = String::from_utf8_lossy(&std::fs::read(dir.join("body.vtu")).unwrap()).into_owned();
    for (name, _) in capstan::figures::body::VTU_ARRAYS {
        assert!(
            vtu.contains(&format!("Name=\"{name}\"")),
            "body.vtu lacks {name}"
        );
    }
    common::check_vtu_with_meshio("contact_out_writes_a_vtu_that_meshio_reads", &expected);
}

#[test]
fn figure_all_quick_writes_every_figure_and_the_index() {
    let dir = scratch("figures_all_quick");
    let out = capstan(&[
        "figure",
        "all",
        "--quick",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    let index: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let figures = index["figures"].as_array().unwrap();
    assert_eq!(figures.len(), capstan::figures::paper::FIGURES.len());
    for f in figures {
        let files = f["files"].as_array().unwrap();
        for ext in ["csv", "svg", "png"] {
            assert!(
                files.iter().any(|x| x.as_str().unwrap().ends_with(ext)),
                "{} has no {ext}",
                f["name"]
            );
        }
        for x in files {
            assert!(dir.join(x.as_str().unwrap()).is_file(), "missing {x}");
        }
        assert!(!f["comparisons"].as_array().unwrap().is_empty());
    }
    let md = std::fs::read_to_string(dir.join("index.md")).unwrap();
    for paper in [
        "1.72e-3",
        "-8.24e-4",
        "(-0.0201, 0.0201)",
        "0.0694",
        "2.75",
        "0.322",
        "71.2",
    ] {
        assert!(md.contains(paper), "index.md lacks the paper's {paper}");
    }
    // the membrane figure is exact: eq. PrismEqnPlot
    let t = csv(&dir.join("tension-ratio.csv"));
    for (r, c) in t["tension_ratio"].iter().zip(&t["closed_form"]) {
        assert!((r - c).abs() < 1e-9 * c, "{r} vs {c}");
    }
}

#[test]
fn figure_rejects_an_unknown_name() {
    let dir = scratch("figures_unknown");
    let (code, _, stderr) =
        common::capstan_status(&["figure", "nope", "--out", dir.to_str().unwrap()]);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("slip-ratio"));
}

#[test]
fn figure_with_a_scene_and_a_range_writes_the_expected_table() {
    let dir = scratch("figures_scene_range");
    let scene = dir.join("belt.toml");
    std::fs::write(
        &scene,
        "[body]\nthickness = 0.5\n[grid]\nn2 = 21\nn3 = 5\n[loads]\ntau_max = 2.2\n",
    )
    .unwrap();
    let out_dir = dir.join("out");
    let out = capstan(&[
        "figure",
        "slip-poisson",
        scene.to_str().unwrap(),
        "--set",
        "body.young=800",
        "--range",
        "body.poisson=0:0.4:3",
        "--out",
        out_dir.to_str().unwrap(),
        "--json",
    ]);
    let index: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(index["grid"], serde_json::json!([21, 5]));
    assert_eq!(index["range"], "body.poisson=0:0.4:3");
    let t = csv(&out_dir.join("slip-poisson.csv"));
    assert_eq!(t["value"], vec![0.0, 0.2, 0.4]);
    // Each point is the scene's own contact solve at that Poisson's ratio.
    for (nu, slip) in t["value"].iter().zip(&t["slip_fraction"]) {
        let one = capstan(&[
            "contact",
            scene.to_str().unwrap(),
            "--set",
            "body.young=800",
            "--set",
            &format!("body.poisson={nu}"),
            "--json",
        ]);
        let v: serde_json::Value = serde_json::from_slice(&one.stdout).unwrap();
        let expected = v["slip_fraction"].as_f64().unwrap();
        assert!(
            (slip - expected).abs() < 1e-12,
            "nu {nu}: {slip} vs {expected}"
        );
    }
    // The membrane figure re-aimed at mu on the scene's ellipse: exp(2 mu atan(b/a)).
    let scene = dir.join("ellipse.toml");
    std::fs::write(
        &scene,
        "[obstacle]\nshape = \"ellipse\"\na = 2\nb = 1\n[membrane]\ntheta0 = -0.7853981633974483\ntheta_max = 0.7853981633974483\n",
    )
    .unwrap();
    let out_dir = dir.join("mu");
    capstan(&[
        "figure",
        "tension-ratio",
        scene.to_str().unwrap(),
        "--range",
        "friction.mu=0.1:0.5:5",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let t = csv(&out_dir.join("tension-ratio.csv"));
    assert_eq!(t["value"].len(), 5);
    for (mu, r) in t["value"].iter().zip(&t["tension_ratio"]) {
        let exact = (2.0 * mu * 0.5f64.atan()).exp();
        assert!((r - exact).abs() < 1e-12 * exact, "mu {mu}: {r} vs {exact}");
    }
    // A range on a one-solve figure is refused, naming --range.
    let (code, _, stderr) = common::capstan_status(&[
        "figure",
        "slip-stick",
        "--range",
        "body.poisson=0:0.4:3",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("--range"), "{stderr}");
}
