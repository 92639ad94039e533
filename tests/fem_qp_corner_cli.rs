//! `discretisation.method = "fem-qp-corner"` through `capstan contact` (issue 29): the corner
//! mesh reaches the CLI, its contact profile carries the face's nodes in `x2` order (more
//! near the ends), `auto` names the full-system Newton, zero corner layers give `fem-qp`'s
//! answer, the condensed `newton` and `capstan threshold` agree with the full-system Newton on
//! the default 5 layers, and bad corner keys are refused naming the key.

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
    // the 3-D corner body is assembled on its mesh: no box-grid multigrid
    refused(
        &[
            corner,
            "body.dimension=3",
            "solver.nonlinear=\"full-newton\"",
            "solver.linear=\"multigrid\"",
        ],
        "solver.linear",
    );
}

/// The condensed `newton` and `capstan threshold` (which runs it) on the default 5 corner
/// layers (`p = 5`, `12 x 2` cells: face nodes down to about `2e-3` of a cell apart), where the
/// condensed Newton stalled before its spring was evened out: the contact profile equals the
/// full-system Newton's to 1e-8 relative and the threshold converges, equal to its limiting
/// ratio to 1e-6 and within 1e-4 of the `p = 7`, 8-layer reference 3.3429618.
#[test]
fn condensed_newton_and_threshold_run_on_five_corner_layers() {
    let mesh = [
        "discretisation.method=\"fem-qp-corner\"",
        "discretisation.order=5",
        "grid.n2=61",
        "grid.n3=11",
    ];
    let run = |solver: &str| {
        let mut args = vec!["contact", "-q", "--set", solver];
        for s in &mesh {
            args.extend(["--set", s]);
        }
        let d = common::capstan_json(&args);
        assert_eq!(d["status"], "converged", "{d}");
        d
    };
    let (condensed, full) = (
        run("solver.nonlinear=\"newton\""),
        run("solver.nonlinear=\"full-newton\""),
    );
    for key in ["x2", "v2", "normal_stress", "slip"] {
        let (a, b) = (
            common::json_array(&condensed["contact"], key),
            common::json_array(&full["contact"], key),
        );
        let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let d = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(d <= 1e-8 * scale, "{key}: {d:e}");
    }
    let mut args = vec!["threshold", "-q"];
    for s in &mesh {
        args.extend(["--set", s]);
    }
    let t = common::capstan_json(&args);
    let ratio = t["threshold_ratio"].as_f64().unwrap();
    let limit = t["limiting_ratio"].as_f64().unwrap();
    assert!((ratio - limit).abs() < 1e-6 * limit, "{ratio} {limit}");
    assert!((ratio - 3.342_961_8).abs() < 1e-4 * ratio, "{ratio}");
}
