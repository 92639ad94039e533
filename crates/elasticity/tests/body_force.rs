//! The thick body's body force in physical components ([`BodyForceField`], scene key
//! `loads.body_force`): the conversion to covariant components against the chart's base
//! vectors, manufactured solutions whose forcing goes through it (the discretisations'
//! observed orders, 2-D and 3-D, on charts with `g_12 != 0`), and the contact model's load
//! list with the force held at its full value.

use std::sync::Arc;

use capstan_elasticity::contact::{
    BODY_FORCE, Body, BodyForceField, BoundarySolver, ContactSettings, Dimension, END_LOADS,
    EndLoads, FullSystemSettings, FullSystemSolver, ThickBody,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::samples::{MmsBoundaries, PrismMms, displacement_error};
use capstan_elasticity::solid::SideFaces;
use capstan_elasticity::solvers::{SparseCholesky, SparseLu};
use capstan_elasticity::studies::solid::{SolidField, SolidMms};
use capstan_elasticity::verification::{GridLevel, observed_order};
use capstan_elasticity::{BodyForce, Discretisation, ShellGeometry};
use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_geometry::{Scalar, ShellChart, Surface};

/// The physical components `p` with `sum_j p_j g_ij / sqrt(g_jj) = f_i` (Cramer's rule): the
/// inverse of [`BodyForceField::covariant`], written independently of it.
fn physical_of(f: [f64; 3], g: &[[f64; 3]; 3]) -> [f64; 3] {
    let m = |i: usize, j: usize| g[i][j] / g[j][j].sqrt();
    let det3 = |c: [[f64; 3]; 3]| {
        c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1])
            - c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0])
            + c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0])
    };
    let a = [0, 1, 2].map(|i| [0, 1, 2].map(|j| m(i, j)));
    let d = det3(a);
    [0, 1, 2].map(|k| {
        let mut c = a;
        for i in 0..3 {
            c[i][k] = f[i];
        }
        det3(c) / d
    })
}

/// A cylinder of radius 2 sheared along its axis, `sigma = (x1 + 0.3 x2, 2 sin x2, 2 cos x2)`:
/// `g_12 = 0.3`, so physical and covariant components differ off the diagonal too.
#[derive(Debug, Clone)]
struct ShearedCylinder;

impl Surface<f64> for ShearedCylinder {
    fn sigma<S: Scalar<f64>>(&self, x: [S; 2]) -> [S; 3] {
        [x[0] + x[1] * 0.3, x[1].sin() * 2.0, x[1].cos() * 2.0]
    }
}

#[test]
fn covariant_components_are_the_force_vector_dotted_with_the_base_vectors() {
    let chart = ShellChart::new(ShearedCylinder);
    let force = BodyForceField::physical(|x| [0.4 - x[2], (3.0 * x[1]).sin(), x[0] * x[1]]);
    for x in [[0.1, -0.7, 0.0], [0.5, 0.3, 0.4], [-0.2, 1.1, 0.9]] {
        let p = chart.shell_point(x).unwrap();
        assert!(p.metric[0][1].abs() > 0.1, "the chart is not orthogonal");
        let phys = force.components(x);
        // F = sum_j f<j> g_j / |g_j|, then f_i = F . g_i, from the base vectors alone
        let mut vector = [0.0; 3];
        for (j, g) in p.covariant_basis.iter().enumerate() {
            let len = g.iter().map(|c| c * c).sum::<f64>().sqrt();
            for c in 0..3 {
                vector[c] += phys[j] * g[c] / len;
            }
        }
        let covariant = force.covariant(x, &p.metric);
        for (i, g) in p.covariant_basis.iter().enumerate() {
            let dot: f64 = (0..3).map(|c| vector[c] * g[c]).sum();
            // metric and base vectors from the same AD jet: round-off only
            assert!(
                (covariant[i] - dot).abs() <= 1e-12 * dot.abs().max(1.0),
                "f_{} = {} vs F.g_i = {dot}",
                i + 1,
                covariant[i]
            );
        }
        let back = physical_of(covariant, &p.metric);
        for (a, b) in back.iter().zip(&phys) {
            assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{a} vs {b}");
        }
        // the plane and solid closures are the same conversion on the chart
        let solid = force.solid(chart.clone())(x);
        assert_eq!(solid, covariant);
        let plane = force.plane(chart.clone())([x[1], x[2]]);
        let at_zero = force.covariant(
            [0.0, x[1], x[2]],
            &chart.shell_point([0.0, x[1], x[2]]).unwrap().metric,
        );
        assert_eq!(plane, [at_zero[1], at_zero[2]]);
    }
    let scaled = force.scaled(-2.5).components([0.5, 0.3, 0.4]);
    let unit = force.components([0.5, 0.3, 0.4]);
    assert_eq!(scaled, unit.map(|f| -2.5 * f));
}

/// The 2-D manufactured study's errors with the exact forcing handed through the physical
/// components of a [`BodyForceField`] (and, for comparison, as the covariant forcing directly).
fn plane_study_through_physical(mms: &PrismMms, levels: &[usize]) -> Vec<(f64, f64, f64)> {
    levels
        .iter()
        .map(|&m| {
            let level = GridLevel {
                n2: 2 * m + 1,
                n3: m + 1,
            };
            let (mut parts, exact) = mms.parts(level).unwrap();
            let direct = parts.clone().finite_difference().unwrap();
            let v = direct.solve(&mut SparseLu::default()).unwrap();
            let [_, l2_direct] = displacement_error(&direct, &v, &exact.field).unwrap();
            let chart = parts.chart.clone();
            let ex = exact.clone();
            let force = BodyForceField::physical(move |x| {
                let f = ex.forcing([x[1], x[2]]).unwrap_or([f64::NAN; 2]);
                let metric = chart.shell_point(x).map(|p| p.metric).unwrap();
                physical_of([0.0, f[0], f[1]], &metric)
            });
            let through: BodyForce = force.plane(parts.chart.clone());
            parts.body_force = Some(Arc::clone(&through));
            let op = parts.finite_difference().unwrap();
            let v = op.solve(&mut SparseLu::default()).unwrap();
            let [_, l2] = displacement_error(&op, &v, &exact.field).unwrap();
            (op.grid().dx3(), l2, l2_direct)
        })
        .collect()
}

#[test]
fn plane_manufactured_solution_through_physical_components_is_second_order() {
    // the bilateral-contact conditions (the contact body's) on the ellipse b/a = 1/2 and the
    // expression prism (orthogonal charts: f<j> = f_j / sqrt(g_jj))
    for mms in [
        PrismMms::ellipse(0.5, MmsBoundaries::BilateralContact),
        PrismMms::expression_prism(MmsBoundaries::BilateralContact),
    ] {
        let study = plane_study_through_physical(&mms, &[8, 16, 32]);
        let points: Vec<(f64, f64)> = study.iter().map(|&(h, e, _)| (h, e)).collect();
        let p = observed_order(&points);
        println!("{}: order {p:.3} {study:?}", mms.geometry);
        assert!((p - 2.0).abs() < 0.15, "order {p}: {study:?}"); // central differences
        for (_, through, direct) in &study {
            // the same forcing to round-off: the same discrete solution
            assert!(
                (through - direct).abs() <= 1e-9 * direct,
                "{through} vs {direct}"
            );
        }
        assert!(study[2].1 < 5e-3, "finest error {}", study[2].1);
    }
}

#[test]
fn solid_manufactured_solution_through_physical_components_keeps_q1_order_two() {
    // the elliptical cone: g_12 != 0, so every physical component feeds every covariant one
    let mms = SolidMms::elliptical_cone();
    let exact = mms.exact();
    let points: Vec<(f64, f64)> = [2, 4, 8]
        .iter()
        .map(|&m| {
            let n = m + 1;
            let chart = ShellChart::new(mms.obstacle.clone());
            let op = mms
                .operator_with_force(
                    [n, n, n],
                    capstan_elasticity::finite_element::ElementOrder::Q1,
                    |covariant| {
                        let metric_chart = chart.clone();
                        let force = BodyForceField::physical(move |x| {
                            let metric = metric_chart.shell_point(x).map(|p| p.metric).unwrap();
                            physical_of(covariant(x), &metric)
                        });
                        force.solid(chart)
                    },
                )
                .unwrap();
            let v = op.solve(&mut SparseCholesky::default()).unwrap();
            let (e, u) = op
                .l2_errors(&v, &|x| exact.field.displacement(x).0)
                .unwrap();
            (mms.thickness / m as f64, e / u)
        })
        .collect();
    let p = observed_order(&points);
    println!("{}: order {p:.3} {points:?}", mms.name);
    // the study through the covariant forcing (tests/solid.rs): Q1 order 2, finest below 2.5e-3
    assert!((p - 2.0).abs() < 0.15, "order {p}: {points:?}");
    assert!(points[2].1 < 2.5e-3, "finest {}", points[2].1);
}

fn params() -> RegularisedCoulombParams<f64> {
    RegularisedCoulombParams::new(0.5, 1e-5).unwrap()
}

/// A drag along the belt (toward `theta_max`) growing through the thickness and a load
/// toward the obstacle, both well inside what friction holds with the end tractions (a drag
/// of 0.4 would pull the body round the circle: no equilibrium).
fn drag() -> BodyForceField {
    BodyForceField::physical(|x| [0.0, 0.05 * (1.0 + x[2]), -0.4 * x[1].cos()])
}

#[test]
fn contact_model_holds_the_body_force_while_the_end_loads_vary() {
    let mut body = ThickBody::paper(25, 7).unwrap();
    body.body_force = Some(drag());
    let model = body.model(RegularisedCoulomb, params(), 1e-5).unwrap();
    assert_eq!(model.loads(), &[END_LOADS[0], END_LOADS[1], BODY_FORCE][..]);
    for loads in [EndLoads::new(1.0, 1.5), EndLoads::new(0.5, 2.0)] {
        // b(tau) + b_f is the body assembled with its loads directly
        let direct = body
            .discretisation(loads.tau0, loads.tau_max)
            .unwrap()
            .system()
            .unwrap()
            .rhs;
        let rhs = model.rhs(loads);
        let scale = direct.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in rhs.iter().zip(&direct) {
            assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b}"); // superposition: round-off
        }
    }
    // the condensed and the full-system Newton solve the same equations independently
    let loads = EndLoads::new(1.0, 1.5);
    let condensed = BoundarySolver::new(&model, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let full = FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let diff = condensed
        .displacement
        .iter()
        .zip(&full.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let size = full.displacement.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(
        diff <= 1e-7 * size,
        "condensed vs full: {diff:.2e} of {size:.2e}"
    );
    assert!(
        model
            .relative_residual(loads, &condensed.displacement)
            .unwrap()
            < 1e-9
    );
    // the force matters: without it the solution differs
    body.body_force = None;
    let bare = body.model(RegularisedCoulomb, params(), 1e-5).unwrap();
    let without = BoundarySolver::new(&bare, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let change = without
        .displacement
        .iter()
        .zip(&condensed.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        change > 1e-2 * size,
        "the body force changes v by {change:.2e}"
    );
}

#[test]
fn a_zero_body_force_reproduces_the_unforced_body() {
    let mut body = ThickBody::paper(25, 7).unwrap();
    let bare = body.model(RegularisedCoulomb, params(), 1e-5).unwrap();
    body.body_force = Some(BodyForceField::physical(|_| [0.0; 3]));
    let zero = body.model(RegularisedCoulomb, params(), 1e-5).unwrap();
    let loads = EndLoads::new(1.0, 1.7);
    assert_eq!(bare.rhs(loads), zero.rhs(loads));
    let solve = |m| {
        BoundarySolver::new(m, ContactSettings::default())
            .unwrap()
            .solve(loads)
            .unwrap()
    };
    let (a, b) = (solve(&bare), solve(&zero));
    assert_eq!(a.displacement, b.displacement);
    assert_eq!(a.slip_fraction, b.slip_fraction);
}

#[test]
fn extruded_solid_body_with_a_body_force_is_the_plane_body() {
    // plane-strain side faces: the 3-D Q1 body with an x1-invariant force (f<1> = 0) is the
    // 2-D Q1 body with the same force
    let circle = capstan_geometry::Obstacle::Ellipse(
        capstan_geometry::EllipticalPrism::new(2.0, 2.0).unwrap(),
    );
    let mut body = Body::new(circle, 21, 5);
    body.method = DiscretisationMethod::FemQ1;
    body.body_force = Some(drag());
    let loads = EndLoads::new(1.0, 1.4);
    let solve = |body: &Body| {
        let model = body.model(RegularisedCoulomb, params(), 1e-5).unwrap();
        let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let s = solver.solve(loads).unwrap();
        (s.slip_fraction, s.contact.v2.clone())
    };
    let plane = solve(&body);
    body.dimension = Dimension::Solid {
        x1: [-0.5, 0.5],
        n1: 3,
        sides: SideFaces::PlaneStrain,
    };
    let solid = solve(&body);
    assert!(
        (plane.0 - solid.0).abs() < 1e-12,
        "{} vs {}",
        plane.0,
        solid.0
    );
    let size = plane.1.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(size > 0.0);
    // every x1 row of the extrusion carries the 2-D profile
    assert_eq!(solid.1.len(), 3 * 21);
    for row in solid.1.chunks(21) {
        for (a, b) in plane.1.iter().zip(row) {
            assert!((a - b).abs() <= 1e-9 * size, "{a} vs {b}");
        }
    }
}
