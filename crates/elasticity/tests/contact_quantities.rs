//! Converging quantities of the contact solution under refinement (the paper's section-3
//! body on the circle at tension ratio 2): the slip measure (the length of the interpolated
//! slipping set) converges at a measured rate while the node fraction jumps by whole nodes;
//! the 3-D measures reduce to the plane-strain ones on an extrusion.

use std::collections::BTreeMap;

use capstan_elasticity::contact::{
    BoundarySolver, ContactQuantities, ContactSettings, EndLoads, ThickBody, default_probes,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{SideFaces, SolidBody};
use capstan_geometry::{EllipticalPrism, Obstacle};

const EPS: f64 = 1e-5;

fn params() -> RegularisedCoulombParams<f64> {
    RegularisedCoulombParams::new(0.5, EPS).unwrap()
}

/// `(node fraction, named quantities)` of the paper's body on an `n2 x n3` grid at ratio 2.
fn quantities(method: DiscretisationMethod, n2: usize, n3: usize) -> (f64, BTreeMap<String, f64>) {
    let body = ThickBody {
        method,
        ..ThickBody::paper(n2, n3).unwrap()
    };
    let model = body.model(RegularisedCoulomb, params(), EPS).unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let sol = solver.solve(EndLoads::ratio(2.0)).unwrap();
    let q = ContactQuantities::new(&model, &sol, &default_probes(body.theta)).unwrap();
    (sol.slip_fraction, q.scalars(&sol))
}

/// `h -> h/2` refinements of the default aspect (250 x 41 is between the last two).
const GRIDS: [(usize, usize); 4] = [(61, 11), (121, 21), (241, 41), (481, 81)];

/// Successive differences of quantity `name` over the study.
fn differences(study: &[(f64, BTreeMap<String, f64>)], name: &str) -> Vec<f64> {
    study
        .windows(2)
        .map(|w| w[1].1[name] - w[0].1[name])
        .collect()
}

fn rate(d: &[f64]) -> f64 {
    (d[d.len() - 2].abs() / d[d.len() - 1].abs()).log2()
}

#[test]
fn q2_slip_measure_converges_while_the_node_fraction_jumps() {
    let study: Vec<_> = GRIDS
        .iter()
        .map(|&(n2, n3)| quantities(DiscretisationMethod::FemQ2, n2, n3))
        .collect();
    let d = differences(&study, "slip_measure");
    let table = format!(
        "{:?}",
        study
            .iter()
            .map(|s| (s.0, s.1["slip_measure"]))
            .collect::<Vec<_>>()
    );
    // measured with the cubic transition locator: differences -3.35e-3, -2.11e-3, -6.5e-4
    // (the stick zone, ~0.028 long, grows as its boundary layer is resolved); the last rate
    // 1.69 (the linear locator: -2.74e-3, -2.35e-3, -1.11e-3, rate 1.08)
    assert!(d.windows(2).all(|w| w[1].abs() < w[0].abs()), "{table}");
    assert!(d.iter().all(|&x| x < 0.0), "monotone: {table}");
    let p = rate(&d);
    assert!((1.3..2.3).contains(&p), "rate {p}: {table}");
    assert!(d[2].abs() < 1e-3, "{table}");
    // the node fraction is not monotone: it jumps as nodes change state
    let f: Vec<f64> = study.windows(2).map(|w| w[1].0 - w[0].0).collect();
    assert!(
        f.windows(2).any(|w| w[0] * w[1] < 0.0),
        "node fraction {f:?}"
    );
    // the stick-zone ends and sigma_n at the probes settle too (measured last differences
    // 2.0e-4, 9.1e-4; 4.0e-4, 2.3e-4, 4.7e-4)
    for (name, bound) in [
        ("stick_from", 5e-4),
        ("stick_to", 2e-3),
        ("normal_stress_probe_0", 1e-3),
        ("normal_stress_probe_1", 5e-4),
        ("normal_stress_probe_2", 1e-3),
    ] {
        let d = differences(&study, name);
        assert!(d[2].abs() < bound, "{name}: {d:?}");
    }
}

#[test]
fn fd_max_radial_displacement_is_second_order_and_slip_measure_settles() {
    let study: Vec<_> = GRIDS
        .iter()
        .map(|&(n2, n3)| quantities(DiscretisationMethod::Fd, n2, n3))
        .collect();
    // max |v3| (at the loaded corner node): differences 2.5e-6, 6.9e-7, 1.8e-7, rates 1.85, 1.97
    let d = differences(&study, "max_abs_v3");
    assert!(d.windows(2).all(|w| w[1].abs() < w[0].abs()), "{d:?}");
    let p = rate(&d);
    assert!((1.7..2.3).contains(&p), "rate {p}: {d:?}");
    // the slip measure is pre-asymptotic on these grids (differences -1.89e-3, -1.93e-3,
    // -1.59e-3: the stick zone's boundary layer is 2 to 4 nodes wide), but monotone and
    // shrinking at the last step
    let d = differences(&study, "slip_measure");
    assert!(d.iter().all(|&x| x < 0.0), "{d:?}");
    assert!(d[2].abs() < d[1].abs(), "{d:?}");
    assert!(d[2].abs() < 2e-3, "{d:?}");
}

#[test]
fn solid_extrusion_measures_are_the_plane_strain_ones_times_the_width() {
    let obstacle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 1.5).unwrap());
    let (n2, n3) = (21, 6);
    let plane = ThickBody {
        obstacle: obstacle.clone(),
        method: DiscretisationMethod::FemQ1,
        ..ThickBody::paper(n2, n3).unwrap()
    };
    let width = 0.75;
    let solid = SolidBody {
        sides: SideFaces::PlaneStrain,
        ..SolidBody::new(obstacle, [-0.25, 0.5], [3, n2, n3])
    };
    let m2 = plane.model(RegularisedCoulomb, params(), EPS).unwrap();
    let m3 = solid.model(RegularisedCoulomb, params(), EPS).unwrap();
    let loads = EndLoads::ratio(2.5);
    let s2 = BoundarySolver::new(&m2, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let s3 = BoundarySolver::new(&m3, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let probes = [-1.0, 0.3];
    let q2 = ContactQuantities::new(&m2, &s2, &probes).unwrap();
    let q3 = ContactQuantities::new(&m3, &s3, &probes).unwrap();
    assert!(q2.slip_measure > 0.1 && q2.slip_measure < q2.contact_measure);
    // the solvers agree to ~1e-9 of the profile, so the slipping set's ends to about that
    let close = |a: f64, b: f64| (a - b).abs() < 1e-8 * b.abs();
    assert!(close(q3.contact_measure, width * q2.contact_measure));
    // the 3-D slipping set is cut from the piecewise-linear slip on triangles, the 2-D one by
    // the cubic transition locator: the 3-D measure is the extrusion of the linear 2-D one
    let eps = m2.slip_threshold();
    let (x, u) = (&s2.contact.x2, &s2.contact.slip);
    let linear: f64 = (1..x.len())
        .map(|k| {
            let mut part = 0.0;
            for (fa, fb) in [(u[k - 1] - eps, u[k] - eps), (-u[k - 1] - eps, -u[k] - eps)] {
                part += match (fa >= 0.0, fb >= 0.0) {
                    (true, true) => 1.0,
                    (false, false) => 0.0,
                    (true, false) => fa / (fa - fb),
                    (false, true) => fb / (fb - fa),
                };
            }
            part * (x[k] - x[k - 1])
        })
        .sum();
    assert!(close(q3.slip_measure, width * linear), "{q3:?} {linear}");
    // and within the locators' difference (1.3e-3 relative here) of the cubic one
    let near = |a: f64, b: f64| (a - b).abs() < 3e-3 * b.abs();
    assert!(
        near(q3.slip_measure, width * q2.slip_measure),
        "{q3:?} {q2:?}"
    );
    // a prism: |a_1| = 1, so the area element is sqrt(g_22) as in plane strain
    assert!(near(
        q3.slip_physical_measure,
        width * q2.slip_physical_measure
    ));
    for (a, b) in q3.normal_stress_probes.iter().zip(&q2.normal_stress_probes) {
        assert!(close(a.value, b.value), "{a:?} {b:?}");
    }
}

#[test]
fn probes_outside_the_contact_face_are_refused_by_key() {
    let body = ThickBody::paper(21, 6).unwrap();
    let model = body.model(RegularisedCoulomb, params(), EPS).unwrap();
    let sol = BoundarySolver::new(&model, ContactSettings::default())
        .unwrap()
        .solve(EndLoads::ratio(2.0))
        .unwrap();
    let e = ContactQuantities::new(&model, &sol, &[2.0]).unwrap_err();
    assert!(e.to_string().contains("output.probe_x2"), "{e}");
}
