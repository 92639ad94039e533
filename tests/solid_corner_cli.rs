//! `discretisation.method = "fem-qp-corner"` with `body.dimension = 3` through `capstan
//! contact` (issue 29): the corner layout extruded along `x1` reaches the CLI as a registered
//! variant, zero corner layers give the uniform `fem-qp` body's answer, the JSON has the keys
//! of the 3-D `fem-qp` run, `body.vtu` (linear sub-hexahedra on the mesh's own nodes) is read
//! back by meshio, and bad input is refused naming the key.

mod common;

use common::{capstan_json, capstan_status, json_array, scratch_dir};

/// The finite-width ellipse `a = 2`, `b = 1.5`, order 2: `1 x 4 x 2` cells, the full-system
/// Newton (what `auto` picks on the corner mesh) at the ratio 1.5.
const BODY: [&str; 18] = [
    "--set",
    "obstacle.shape=ellipse",
    "--set",
    "obstacle.b=1.5",
    "--set",
    "body.dimension=3",
    "--set",
    "discretisation.order=2",
    "--set",
    "grid.n1=3",
    "--set",
    "grid.n2=9",
    "--set",
    "grid.n3=5",
    "--set",
    "loads.tau_max=1.5",
    "--set",
    "solver.nonlinear=full-newton",
];

fn contact(sets: &[&str]) -> serde_json::Value {
    let mut args = vec!["contact", "-q"];
    args.extend(BODY);
    for s in sets {
        args.extend(["--set", s]);
    }
    let d = capstan_json(&args);
    assert_eq!(d["status"], "converged", "{d}");
    d
}

/// Every key path of a JSON object (`a.b.c`), arrays as leaves.
fn key_paths(v: &serde_json::Value, prefix: &str, out: &mut Vec<String>) {
    if let Some(map) = v.as_object() {
        for (k, x) in map {
            let path = format!("{prefix}{k}");
            key_paths(x, &format!("{path}."), out);
            out.push(path);
        }
    }
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

#[test]
fn no_corner_layers_give_the_uniform_fem_qp_body_with_the_same_keys() {
    let flat = contact(&[
        "discretisation.method=\"fem-qp-corner\"",
        "discretisation.corner_layers=0",
    ]);
    let qp = contact(&["discretisation.method=\"fem-qp\""]);
    assert_eq!(flat["discretisation"], "solid-qp-corner");
    assert_eq!(flat["solid"]["grid"], serde_json::json!([3, 9, 5]));
    assert_eq!(
        flat["solid"]["contact_unknowns"],
        qp["solid"]["contact_unknowns"]
    );
    // the same report, key for key (the scene echoes the corner key it was given)
    let (mut kf, mut kq) = (Vec::new(), Vec::new());
    key_paths(&flat, "", &mut kf);
    key_paths(&qp, "", &mut kq);
    kf.retain(|k| k != "scene.discretisation.corner_layers");
    kf.sort();
    kq.sort();
    assert_eq!(kf, kq);
    // the same numbers: the two assemblies differ in node numbering only (round-off)
    for key in ["x2", "v2", "normal_stress", "shear_stress", "slip"] {
        let e = max_rel(
            &json_array(&flat["contact"], key),
            &json_array(&qp["contact"], key),
        );
        assert!(e < 1e-12, "{key}: {e:e}");
    }
    for key in ["x1", "v1", "slip_1", "friction_traction_1"] {
        let e = max_rel(
            &json_array(&flat["solid"]["contact"], key),
            &json_array(&qp["solid"]["contact"], key),
        );
        assert!(e < 1e-11, "{key}: {e:e}"); // v^1 is ~1e-2 of v^2 here
    }
    for key in ["slip_fraction", "slip_measure", "slip_physical_measure"] {
        let (a, b) = (flat[key].as_f64().unwrap(), qp[key].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-12 * b.abs(), "{key}: {a} {b}");
    }
    let v = |d: &serde_json::Value| d["max_azimuthal_displacement"]["value"].as_f64().unwrap();
    assert!((v(&flat) / v(&qp) - 1.0).abs() < 1e-12);
    // unilateral contact: the free face with the semismooth Newton, the same answer
    let unilateral = "contact.kind=\"unilateral\"";
    let flat = contact(&[
        "discretisation.method=\"fem-qp-corner\"",
        "discretisation.corner_layers=0",
        unilateral,
    ]);
    let qp = contact(&["discretisation.method=\"fem-qp\"", unilateral]);
    assert!((v(&flat) / v(&qp) - 1.0).abs() < 1e-10);
    assert_eq!(flat["slip_fraction"], qp["slip_fraction"]);
}

#[test]
fn corner_layers_refine_the_face_and_the_vtu_is_read_back_by_meshio() {
    let dir = scratch_dir("solid-corner-vtu");
    let out = dir.to_str().unwrap();
    let mut args = vec!["contact", "-q", "--out", out];
    args.extend(BODY);
    args.extend(["--set", "discretisation.method=\"fem-qp-corner\""]);
    let d = capstan_json(&args);
    assert_eq!(d["status"], "converged", "{d}");
    // auto would pick the full-system Newton with LU on the mesh too
    let x2 = json_array(&d["contact"], "x2");
    let x1 = json_array(&d["solid"]["contact"], "x1");
    // per x1 line: p e2 + 1 = 9 grid nodes and p = 2 more per layer at each end (5 layers)
    let per_line = 9 + 2 * 5 * 2;
    assert_eq!(x2.len(), 3 * per_line);
    assert_eq!(d["solid"]["contact_unknowns"], 2 * 3 * per_line);
    assert!(x2[..per_line].windows(2).all(|w| w[0] < w[1]));
    let vtu = dir.join("body.vtu");
    assert!(vtu.is_file());
    let Some(python) = common::meshio_python("solid_corner_vtu") else {
        return;
    };
    // the face nodes of the VTU (x3 = 0) carry the contact profile's v^2
    let script = r#"
import json, sys
import meshio, numpy as np
m = meshio.read(sys.argv[1])
profile = json.loads(sys.argv[2])
hexes = [c.data for c in m.cells if c.type == "hexahedron"]
assert len(hexes) == 1 and len(m.cells) == 1, [c.type for c in m.cells]
h = hexes[0]
pd = m.point_data
x1, x2, x3 = pd["x1"], pd["x2"], pd["x3"]
v = pd["displacement_contravariant"]
face = {}
for k in np.nonzero(x3 == 0.0)[0]:
    face[(round(x1[k], 12), round(x2[k], 12))] = v[k, 1]
worst = 0.0
for a, b, c in zip(profile["x1"], profile["x2"], profile["v2"]):
    worst = max(worst, abs(face[(round(a, 12), round(b, 12))] - c))
finite = all(np.all(np.isfinite(pd[n])) for n in pd)
print(json.dumps({"points": len(m.points), "cells": int(h.shape[0]), "nodes_per_cell": int(h.shape[1]),
    "max_index": int(h.max()), "face_nodes": len(face), "worst_v2": worst, "finite": bool(finite),
    "arrays": sorted(pd)}))
"#;
    let profile = serde_json::json!({
        "x1": x1,
        "x2": x2,
        "v2": json_array(&d["contact"], "v2"),
    });
    let run = common::succeed(
        std::process::Command::new(python)
            .args(["-c", script])
            .arg(&vtu)
            .arg(profile.to_string()),
    );
    let r: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    // one x1 element times the layout's quads (8 coarse cells, 2 trapezoids per layer and
    // corner: 8 + 4 * 5 * 2 = 48), each as p^3 = 8 linear sub-hexahedra
    assert_eq!(r["cells"], 48 * 8, "{r}");
    assert_eq!(r["nodes_per_cell"], 8);
    assert_eq!(r["max_index"], r["points"].as_u64().unwrap() - 1);
    assert_eq!(r["face_nodes"], x2.len());
    assert!(r["worst_v2"].as_f64().unwrap() < 1e-15, "{r}");
    assert_eq!(r["finite"], true);
    let arrays: Vec<&str> = r["arrays"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    for (name, _) in capstan::figures::body::VTU_ARRAYS
        .iter()
        .chain(&capstan::output::solid_body::SOLID_EXTRA_VTU_ARRAYS)
    {
        assert!(arrays.contains(name), "{name}: {arrays:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_three_dimensional_corner_input_names_the_key() {
    let refused = |sets: &[&str], key: &str| {
        let mut args = vec!["contact", "-q"];
        args.extend(BODY);
        args.extend(["--set", "discretisation.method=\"fem-qp-corner\""]);
        for s in sets {
            args.extend(["--set", s]);
        }
        let (code, _, err) = capstan_status(&args);
        assert_eq!(code, Some(2), "{sets:?}: {err}");
        assert!(err.contains(key), "{sets:?}: {err}");
    };
    refused(
        &["discretisation.corner_layers=17"],
        "discretisation.corner_layers",
    );
    refused(
        &["discretisation.corner_ratio=0.99"],
        "discretisation.corner_ratio",
    );
    // p e + 1 nodes along x1, e >= 2 cells along x2 and x3
    refused(&["grid.n1=4"], "grid.n1");
    refused(&["grid.n3=3"], "grid.n3");
    // assembled on its mesh: no box-grid multigrid, matrix-free operator
    refused(&["solver.linear=\"multigrid\""], "solver.linear");
    refused(&["solver.linear=\"matrix-free-mg\""], "solver.linear");
}
