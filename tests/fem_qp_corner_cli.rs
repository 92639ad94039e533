//! `discretisation.method = "fem-qp-corner"` through `capstan contact` (issue 29): the corner
//! mesh reaches the CLI, its contact profile carries the face's nodes in `x2` order (more
//! near the ends), `auto` names the full-system Newton, zero corner layers give `fem-qp`'s
//! answer, and bad corner keys are refused naming the key.

mod common;

/// `capstan contact --json` on the paper scene, order 4, `12 x 2` elements, with `sets`.
fn contact(sets: &[&str]) -> serde_json::Value {
    let mut args = vec!["contact", "-q", "--set", "grid.n2=49", "--set", "grid.n3=9"];
    for s in sets {
        args.extend(["--set", s]);
    }
    let d = common::capstan_json(&args);
    assert_eq!(d["status"], "converged", "{d}");
    d
}

#[test]
fn corner_mesh_solves_the_default_contact_from_the_cli() {
    let corner = contact(&["discretisation.method=\"fem-qp-corner\""]);
    assert_eq!(corner["discretisation"], "fem-qp-corner");
    assert_eq!(corner["solver_choice"]["nonlinear"], "full-newton");
    let x2 = common::json_array(&corner["contact"], "x2");
    // 49 grid nodes along the face, 4 nodes more per layer and end (5 layers by default)
    assert_eq!(x2.len(), 49 + 2 * 5 * 4);
    assert!(x2.windows(2).all(|w| w[0] < w[1]));
    let flat = contact(&[
        "discretisation.method=\"fem-qp-corner\"",
        "discretisation.corner_layers=0",
        "solver.nonlinear=\"full-newton\"",
    ]);
    let qp = contact(&[
        "discretisation.method=\"fem-qp\"",
        "solver.nonlinear=\"full-newton\"",
    ]);
    for key in ["x2", "v2", "normal_stress", "slip"] {
        let (a, b) = (
            common::json_array(&flat["contact"], key),
            common::json_array(&qp["contact"], key),
        );
        let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let d = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(d <= 1e-10 * scale, "{key}: {d:e}");
    }
    let v = |d: &serde_json::Value| d["max_azimuthal_displacement"]["value"].as_f64().unwrap();
    assert!((v(&flat) / v(&qp) - 1.0).abs() < 1e-10);
}

#[test]
fn bad_corner_keys_are_refused_naming_the_key() {
    let refused = |sets: &[&str], key: &str| {
        let mut args = vec!["contact", "-q"];
        for s in sets {
            args.extend(["--set", s]);
        }
        let (code, _, err) = common::capstan_status(&args);
        assert_ne!(code, Some(0), "{sets:?}");
        assert!(err.contains(key), "{sets:?}: {err}");
    };
    let corner = "discretisation.method=\"fem-qp-corner\"";
    refused(
        &[corner, "discretisation.corner_layers=17"],
        "discretisation.corner_layers",
    );
    refused(
        &[corner, "discretisation.corner_ratio=1.5"],
        "discretisation.corner_ratio",
    );
    refused(
        &[corner, "discretisation.corner_ratio=0"],
        "discretisation.corner_ratio",
    );
    // the keys belong to the corner mesh only
    refused(
        &["discretisation.corner_layers=3"],
        "discretisation.corner_layers",
    );
    // e >= 2 cells of order p along each direction
    refused(&[corner, "grid.n3=5"], "grid.n3");
    refused(&[corner, "body.dimension=3"], "discretisation.method");
}
