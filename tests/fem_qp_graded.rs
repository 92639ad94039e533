//! Geometrically graded `fem-qp` meshes (`discretisation.grading`, `discretisation.layers`) on
//! the default contact case (paper body, regularised Coulomb `mu = 0.5`, `eps = 1e-5`,
//! `tau_max / tau0 = 2`): the graded solve at equal unknowns lies closer to a fine uniform
//! reference than the uniform one, and the scene keys reach the operator through
//! `capstan contact`.

mod common;

use capstan_elasticity::Discretisation;
use capstan_elasticity::contact::ThickBody;
use capstan_elasticity::finite_element::{DiscretisationMethod, Grading};

/// `(limiting ratio, max |v^2| on the outer surface, smallest x2 node gap)` of the order-`p`
/// body on `n2 x n3` nodes with `grading`.
fn solve(p: usize, n2: usize, n3: usize, grading: Grading) -> [f64; 3] {
    let body = ThickBody {
        method: DiscretisationMethod::FemQp,
        order: p,
        grading,
        ..ThickBody::paper(n2, n3).unwrap()
    };
    let (model, sol, [_, limit, outer]) = common::default_contact(&body);
    let op = model.discretisation();
    let gap = (1..n2)
        .map(|i| op.node_position([i, 0])[0] - op.node_position([i - 1, 0])[0])
        .fold(f64::INFINITY, f64::min);
    // the fields the VTU and the figures are written from sit at the same nodes
    let fields = op.fields(&sol.displacement).unwrap();
    assert_eq!(min_gap(&fields.x2), gap);
    [limit, outer, gap]
}

/// The smallest gap between successive entries of `x`.
fn min_gap(x: &[f64]) -> f64 {
    x.windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn graded_qp_at_equal_unknowns_is_closer_to_the_fine_reference() {
    let p = 4;
    let graded = Grading::geometric(0.4, 3).unwrap();
    // two fine references, 80 x 20 elements: uniform and graded (they differ by 2.6e-4 in
    // the limiting ratio, the uniform mesh's own corner error)
    let references = [
        solve(p, 321, 81, Grading::UNIFORM),
        solve(p, 321, 81, graded),
    ];
    let (n2, n3) = (65, 25); // 16 x 6 elements, 3250 nodes either way
    let uniform = solve(p, n2, n3, Grading::UNIFORM);
    let coarse = solve(p, n2, n3, graded);
    for reference in references {
        let err = |x: [f64; 3], k: usize| (x[k] / reference[k] - 1.0).abs();
        println!("reference {reference:?}\nuniform {uniform:?}\ngraded {coarse:?}");
        // measured: ratio 6.0e-4 -> 1.8e-5 and 8.6e-4 -> 2.4e-4, max |v^2| 2.3e-3 -> 7.4e-4 and
        // 2.4e-3 -> 6.0e-4 (uniform -> graded, against the uniform / graded reference)
        for k in [0, 1] {
            assert!(
                err(coarse, k) < 0.5 * err(uniform, k),
                "{k}: graded {:.3e} uniform {:.3e}",
                err(coarse, k),
                err(uniform, k)
            );
        }
    }
    // the operator's nodes are the graded ones: the smallest gap along x2 is the end layer
    // H sigma^(n - 1) (H = (theta1 - theta0) / (e - 2n + 2)) times the first GLL gap
    // (1 - sqrt(3/7)) / 2 of order 4, against the uniform element's
    let gll = (1.0 - (3.0f64 / 7.0).sqrt()) / 2.0;
    let pi = core::f64::consts::PI;
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-12;
    assert!(
        close(coarse[2], pi / 12.0 * 0.4f64.powi(2) * gll),
        "{coarse:?}"
    );
    assert!(close(uniform[2], pi / 16.0 * gll), "{uniform:?}");
}

#[test]
fn graded_bodies_have_no_coarser_sequencing_level() {
    let uniform = ThickBody {
        method: DiscretisationMethod::FemQp,
        ..ThickBody::paper(129, 33).unwrap()
    };
    assert_eq!(uniform.coarser().map(|c| (c.n2, c.n3)), Some((65, 17)));
    let graded = ThickBody {
        grading: Grading::geometric(0.4, 3).unwrap(),
        ..uniform.clone()
    };
    assert!(graded.coarser().is_none());
    // a graded body of another method is refused naming the key
    let fd = ThickBody {
        method: DiscretisationMethod::Fd,
        ..graded
    };
    let e = fd.discretisation(1.0, 2.0).unwrap_err().to_string();
    assert!(e.contains("discretisation.grading"), "{e}");
}

/// `(limiting ratio, max |v^2|)` and the resolved discretisation table of `capstan contact
/// --json` on the paper scene with fem-qp of order 4 and `sets`.
fn cli(sets: &[&str]) -> ([f64; 2], serde_json::Value) {
    let mut args = vec!["contact", "-q", "--set", "discretisation.method=fem-qp"];
    for s in sets {
        args.extend(["--set", s]);
    }
    let d = common::capstan_json(&args);
    assert_eq!(d["status"], "converged", "{d}");
    let ratio = d["limiting_ratios"][1].as_f64().unwrap();
    let v2 = d["max_azimuthal_displacement"]["value"].as_f64().unwrap();
    let x2: Vec<f64> = d["contact"]["x2"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let gll = (1.0 - (3.0f64 / 7.0).sqrt()) / 2.0; // first GLL gap of order 4 on [0, 1]
    let (e2, graded) = (
        (x2.len() - 1) / 4,
        d["scene"]["discretisation"]["grading"].as_f64(),
    );
    // the contact profile's x2 are the operator's (graded) nodes: the smallest gap is the end
    // layer H sigma^(n - 1), H = pi / (e - 2n + 2), times the GLL gap
    let smallest = match graded {
        None => core::f64::consts::PI / e2 as f64 * gll,
        Some(sigma) => {
            let n = d["scene"]["discretisation"]["layers"].as_u64().unwrap() as i32;
            core::f64::consts::PI / (e2 as f64 - 2.0 * n as f64 + 2.0) * sigma.powi(n - 1) * gll
        }
    };
    assert!(
        (min_gap(&x2) / smallest - 1.0).abs() < 1e-12,
        "{}",
        min_gap(&x2)
    );
    ([ratio, v2], d["scene"]["discretisation"].clone())
}

#[test]
fn capstan_contact_on_a_graded_mesh_agrees_with_a_fine_uniform_solve() {
    let (graded, table) = cli(&[
        "grid.n2=241",
        "grid.n3=41",
        "discretisation.grading=0.4",
        "discretisation.layers=3",
    ]);
    assert_eq!(table["grading"], 0.4);
    assert_eq!(table["layers"], 3);
    let (fine, table) = cli(&["grid.n2=321", "grid.n3=81"]);
    assert!(table.get("grading").is_none(), "{table}");
    // measured: 3.343329 vs 3.344205 (2.6e-4), max |v^2| 3.588011e-3 vs 3.587000e-3 (2.8e-4);
    // the uniform reference's own error is about 3e-4 (graded 481 x 121: 3.343242)
    for k in [0, 1] {
        assert!(
            (graded[k] / fine[k] - 1.0).abs() < 1e-3,
            "{graded:?} {fine:?}"
        );
    }
}
