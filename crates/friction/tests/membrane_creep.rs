//! Belt creep: the membrane with exact Coulomb along load paths against the closed form
//! ([`capstan_friction::membrane_path::creep::BeltCreep`]): slip-zone ends and end
//! displacements with their observed orders, one step against ten, the closed hysteresis loop,
//! the energy dissipated per cycle, and regularised Coulomb -> exact Coulomb as `eps -> 0`.

use std::f64::consts::PI;

use capstan_friction::membrane_displacement::{
    EndCondition, MembraneDisplacement, MembraneDisplacementProblem, MembraneNewton,
};
use capstan_friction::membrane_path::creep::BeltCreep;
use capstan_friction::membrane_path::{
    MembranePath, MembraneStep, SemismoothMembrane, SemismoothSettings,
};
use capstan_friction::{
    ExactCoulomb, ExactCoulombParams, FrictionError, FrictionState, RegularisedCoulomb,
    RegularisedCoulombParams,
};
use capstan_geometry::CircularCylinder;

mod orders;
use orders::{observed_order, table};

const RADIUS: f64 = 2.0;
const MU: f64 = 0.3;
const K: f64 = 100.0;

fn creep() -> BeltCreep {
    BeltCreep {
        radius: RADIUS,
        mu: MU,
        stiffness: K,
        t0: 1.0,
        theta0: 0.0,
        theta1: PI,
    }
}

fn problem(nodes: usize) -> MembraneDisplacementProblem {
    MembraneDisplacementProblem {
        theta0: 0.0,
        theta1: PI,
        nodes,
        stiffness: K,
        start: EndCondition::Tension(1.0),
        end: EndCondition::Tension(1.0),
    }
}

fn path(nodes: usize, loads: &[f64], sweep: bool) -> MembranePath {
    let circle = CircularCylinder::new(RADIUS).unwrap();
    let m = SemismoothMembrane::new(&circle, ExactCoulomb, ExactCoulombParams::new(MU).unwrap());
    let settings = SemismoothSettings {
        max_iterations: 20_000,
        sweep,
        ..Default::default()
    };
    m.solve_path(&problem(nodes), loads, settings, &mut |_, _| {})
        .unwrap()
}

/// Half-cell tensions `T_{j+1/2} = k (w_{j+1} - w_j) / (R d)` and their angles.
fn half_tensions(theta: &[f64], w: &[f64]) -> Vec<(f64, f64)> {
    (0..w.len() - 1)
        .map(|j| {
            let d = theta[j + 1] - theta[j];
            (
                0.5 * (theta[j] + theta[j + 1]),
                K * (w[j + 1] - w[j]) / (RADIUS * d),
            )
        })
        .collect()
}

/// Where the slip zone at the loaded end starts: the stick zone keeps the previous tensions,
/// and in the slip zone `ln(T/T_old)` is linear in `theta` (slope `mu` when loading from a
/// uniform tension, `2 mu` when unloading a loaded profile), so it is extrapolated linearly
/// to zero from the first two half cells whose tension changed by more than round-off.
fn zone_start(before: &[f64], step: &MembraneStep) -> f64 {
    let old = half_tensions(&step.theta, before);
    let new = half_tensions(&step.theta, &step.displacement);
    let log: Vec<(f64, f64)> = old
        .iter()
        .zip(&new)
        .map(|(o, n)| (o.0, (n.1 / o.1).ln()))
        .collect();
    let j = log
        .iter()
        .position(|l| l.1.abs() > 1e-9)
        .expect("a slip zone");
    let ((s0, l0), (s1, l1)) = (log[j], log[j + 1]);
    s0 - l0 * (s1 - s0) / (l1 - l0)
}

/// Load 1 -> 2, unload 2 -> 1.2 on grids of 201 .. 3201 nodes: the zone ends and end
/// displacements converge at second order and match the closed form to 1e-6 on the finest.
#[test]
fn belt_creep_matches_the_closed_form_with_second_order() {
    let c = creep();
    let (t1, t2) = (2.0, 1.2);
    let exact = [
        c.loading_slip_start(t1).unwrap(),
        c.loading_displacement(t1).unwrap(),
        c.unloading_slip_start(t1, t2).unwrap(),
        c.unloading_displacement(t1, t2).unwrap(),
    ];
    let names = [
        "loading zone start",
        "loading end displacement",
        "unloading zone start",
        "unloading end displacement",
    ];
    let mut studies = vec![Vec::new(); 4];
    for nodes in [201, 401, 801, 1601, 3201] {
        let p = path(nodes, &[t1, t2], true);
        let w = p.end_displacements();
        let got = [
            zone_start(&p.initial.displacement, &p.steps[0]),
            w[0],
            zone_start(&p.steps[0].displacement, &p.steps[1]),
            w[1] - w[0],
        ];
        let h = PI / (nodes - 1) as f64;
        for k in 0..4 {
            studies[k].push((h, (got[k] / exact[k] - 1.0).abs()));
        }
        // the tension profile of the loaded state is the closed form to the grid error
        let s = &p.steps[0];
        for (i, &th) in s.theta.iter().enumerate() {
            let want = c.loading_tension(t1, th).unwrap();
            assert!(
                (s.tension[i] / want - 1.0).abs() < 30.0 * h,
                "T at {th}: {} vs {want}",
                s.tension[i]
            );
        }
    }
    for k in 0..4 {
        let order = observed_order(&studies[k]);
        println!("{}: order {order:.3}\n{}", names[k], table(&studies[k]));
        assert!(
            (order - 2.0).abs() < 0.2,
            "{}: {order}\n{}",
            names[k],
            table(&studies[k])
        );
        assert!(
            studies[k].last().unwrap().1 < 1e-6,
            "{}\n{}",
            names[k],
            table(&studies[k])
        );
    }
}

/// Loading in one step and in ten gives the same state when nothing unloads (every node
/// that slips keeps slipping forward), to the solver tolerance.
#[test]
fn loading_in_one_step_or_ten_gives_the_same_state() {
    let one = path(801, &[2.0], true);
    let ten: Vec<f64> = (1..=10).map(|k| 1.0 + 0.1 * k as f64).collect();
    for sweep in [true, false] {
        let many = path(801, &ten, sweep);
        let (a, b) = (&one.steps[0], many.steps.last().unwrap());
        let scale = a.displacement.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for i in 0..a.displacement.len() {
            assert!(
                (a.displacement[i] - b.displacement[i]).abs() < 1e-10 * scale,
                "node {i}"
            );
            assert!(
                (a.tension[i] - b.tension[i]).abs() < 1e-10 * 2.0,
                "node {i}"
            );
        }
        // the dissipated energy is path-independent too (to the step size: friction does
        // work at the end-of-step traction), and both are positive
        assert!(one.dissipation() > 0.0 && many.dissipation() > 0.0);
    }
}

/// Load to 2, then cycle 2 -> 1.2 -> 2 twice: each cycle closes its loop (the state after
/// reloading equals the loaded state), and the energy dissipated per cycle is positive and
/// converges to the closed form as the cycle's steps and the grid are refined (first order
/// in the load step).
#[test]
fn load_unload_reload_closes_the_loop_and_dissipates() {
    let c = creep();
    let (t1, t2) = (2.0, 1.2);
    let loop_state = path(801, &[t1, t2, t1, t2, t1], true);
    let w = loop_state.end_displacements();
    assert!((w[2] - w[0]).abs() < 1e-12 * w[0], "{w:?}");
    assert!((w[4] - w[0]).abs() < 1e-12 * w[0], "{w:?}");
    assert!((w[3] - w[1]).abs() < 1e-12 * w[0], "{w:?}");
    let exact = c.cycle_dissipation(t1, t2).unwrap();
    let mut study = Vec::new();
    for (steps, nodes) in [(8, 801), (16, 1601), (32, 3201), (64, 6401)] {
        let mut loads = vec![t1];
        for k in 1..=steps {
            loads.push(t1 - (t1 - t2) * k as f64 / steps as f64);
        }
        for k in 1..=steps {
            loads.push(t2 + (t1 - t2) * k as f64 / steps as f64);
        }
        let p = path(nodes, &loads, true);
        let cycle: f64 = p.steps[1..].iter().map(|s| s.dissipation).sum();
        assert!(cycle > 0.0);
        study.push(((t1 - t2) / steps as f64, (cycle / exact - 1.0).abs()));
        // the loop closes at every refinement
        let w = p.end_displacements();
        assert!((w.last().unwrap() - w[0]).abs() < 1e-12 * w[0]);
    }
    let order = observed_order(&study);
    println!(
        "dissipation per cycle {exact:.6e}: order {order:.3}\n{}",
        table(&study)
    );
    let finest = observed_order(&study[1..]);
    assert!((finest - 1.0).abs() < 0.15, "{finest}\n{}", table(&study));
    assert!(study.last().unwrap().1 < 5e-4, "{}", table(&study));
}

/// Regularised Coulomb (Kikuchi–Oden) on the slip increment of the same loading step
/// converges to exact Coulomb at first order in `eps`; exact Coulomb's semismooth Newton
/// needs no more iterations than the regularised Newton at `eps = 1e-5` (without the sweep
/// too on this grid it needs more: the front moves one node per iteration).
#[test]
fn regularised_coulomb_converges_to_exact_at_first_order_in_eps() {
    let circle = CircularCylinder::new(RADIUS).unwrap();
    let nodes = 801;
    let exact = path(nodes, &[2.0], true);
    let w0 = exact.initial.displacement.clone();
    let w_exact = exact.end_displacements()[0];
    let loaded = MembraneDisplacementProblem {
        end: EndCondition::Tension(2.0),
        ..problem(nodes)
    };
    let mut study = Vec::new();
    let mut iterations_at_1e5 = 0;
    let mut regularised_iterations = Vec::new();
    for eps in [1e-3, 1e-4, 1e-5, 1e-6] {
        let m = MembraneDisplacement::new(
            &circle,
            RegularisedCoulomb,
            RegularisedCoulombParams::new(MU, eps).unwrap(),
        );
        let newton = MembraneNewton {
            max_iterations: 1000,
            ..Default::default()
        };
        let s = m
            .solve_from(&loaded, Some(&w0), Some(&w0), newton, &mut |_, _, _| {})
            .unwrap();
        let w = s.displacement[nodes - 1] - w0[nodes - 1];
        study.push((eps, (w / w_exact - 1.0).abs()));
        regularised_iterations.push(s.iterations);
        if eps == 1e-5 {
            iterations_at_1e5 = s.iterations;
        }
    }
    let order = observed_order(&study);
    let plain = path(nodes, &[2.0], false);
    println!(
        "eps order {order:.3}\n{}iterations: exact {} (sweep) {} (no sweep), regularised {:?} (eps 1e-3 .. 1e-6)",
        table(&study),
        exact.steps[0].iterations,
        plain.steps[0].iterations,
        regularised_iterations
    );
    assert!((order - 1.0).abs() < 0.05, "{order}\n{}", table(&study));
    assert!(exact.steps[0].iterations <= iterations_at_1e5);
    assert!((plain.end_displacements()[0] / w_exact - 1.0).abs() < 1e-10);
}

/// Pulled beyond the capstan ratio the belt slides as a whole: a typed no-equilibrium error,
/// not a failure to converge; a spent budget is a typed error too.
#[test]
fn beyond_the_capstan_ratio_the_belt_slides() {
    let circle = CircularCylinder::new(RADIUS).unwrap();
    let m = SemismoothMembrane::new(&circle, ExactCoulomb, ExactCoulombParams::new(MU).unwrap());
    let ratio = (MU * PI).exp();
    for sweep in [true, false] {
        let settings = SemismoothSettings {
            max_iterations: 5000,
            sweep,
            ..Default::default()
        };
        let e = m
            .solve_path(&problem(201), &[1.05 * ratio], settings, &mut |_, _| {})
            .unwrap_err();
        assert!(matches!(e, FrictionError::RigidSliding { .. }), "{e}");
    }
    let tight = SemismoothSettings {
        max_iterations: 3,
        sweep: false,
        ..Default::default()
    };
    let e = m
        .solve_path(&problem(201), &[2.0], tight, &mut |_, _| {})
        .unwrap_err();
    assert!(matches!(
        e,
        FrictionError::SemismoothNotConverged { iterations: 3, .. }
    ));
    for bad in [[0.0].as_slice(), &[f64::NAN], &[]] {
        let e = m
            .solve_path(&problem(201), bad, Default::default(), &mut |_, _| {})
            .unwrap_err();
        assert!(matches!(
            e,
            FrictionError::InvalidParameter {
                field: "loads.path",
                ..
            }
        ));
    }
}

/// The observer sees every iteration with the active set, and observing changes nothing.
#[test]
fn every_iteration_reports_its_active_set() {
    let circle = CircularCylinder::new(RADIUS).unwrap();
    let m = SemismoothMembrane::new(&circle, ExactCoulomb, ExactCoulombParams::new(MU).unwrap());
    let settings = SemismoothSettings {
        max_iterations: 1000,
        sweep: false,
        ..Default::default()
    };
    let mut seen = Vec::new();
    let p = m
        .solve_path(&problem(101), &[2.0, 1.5], settings, &mut |k, it| {
            seen.push((k, *it))
        })
        .unwrap();
    let plain = path(101, &[2.0, 1.5], false);
    assert_eq!(p, plain);
    let iterations: usize = p.steps.iter().map(|s| s.iterations).sum();
    assert_eq!(seen.len(), iterations + 2); // the start of each step and every iteration
    for (_, it) in &seen {
        assert_eq!(it.stick + it.slip + it.separated, 101);
    }
    let last = seen.iter().rev().find(|(k, _)| *k == 0).unwrap().1;
    assert_eq!(last.changes, 0);
    let slipping = p.steps[0]
        .states
        .iter()
        .filter(|s| **s == FrictionState::Slip)
        .count();
    assert_eq!(last.slip, slipping);
}

/// The capstan sweep only starts the iteration: with and without it the path has the same
/// solution, on the circle past the previous maximum load and on an ellipse (no closed form);
/// one step and ten agree on the ellipse too.
#[test]
fn the_sweep_changes_the_work_not_the_answer() {
    let loads = [2.0, 1.2, 2.4, 1.5];
    let (a, b) = (path(401, &loads, true), path(401, &loads, false));
    for (x, y) in a.steps.iter().zip(&b.steps) {
        let scale = x.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..x.displacement.len() {
            assert!((x.displacement[i] - y.displacement[i]).abs() < 1e-10 * scale);
        }
        assert_eq!(x.states, y.states);
    }
    let ellipse = capstan_geometry::EllipticalPrism::new(2.0, 1.0).unwrap();
    let m = SemismoothMembrane::new(&ellipse, ExactCoulomb, ExactCoulombParams::new(MU).unwrap());
    let p = MembraneDisplacementProblem {
        theta0: -1.2,
        theta1: 1.2,
        ..problem(401)
    };
    let solve = |loads: &[f64], sweep: bool| {
        let settings = SemismoothSettings {
            max_iterations: 20_000,
            sweep,
            ..Default::default()
        };
        m.solve_path(&p, loads, settings, &mut |_, _| {}).unwrap()
    };
    let ten: Vec<f64> = (1..=10).map(|k| 1.0 + 0.06 * k as f64).collect(); // capstan ratio 1.73
    let (one, many, plain) = (solve(&[1.6], true), solve(&ten, true), solve(&ten, false));
    let last = |p: &MembranePath| p.steps.last().unwrap().displacement.clone();
    let scale = last(&one).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for ((x, y), z) in last(&one).iter().zip(last(&many)).zip(last(&plain)) {
        assert!((x - y).abs() < 1e-10 * scale && (x - z).abs() < 1e-10 * scale);
    }
    // on the ellipse the loaded end's slip zone obeys the capstan equation: the tension ratio
    // across it is exp(mu (Psi(theta1) - Psi(theta_k))), Psi the turning angle
    let s = &one.steps[0];
    assert!(s.states.contains(&FrictionState::Stick));
    let k = (1..s.states.len())
        .find(|&i| s.states[i] == FrictionState::Slip)
        .unwrap();
    let psi = capstan_friction::membrane::PrismMembrane::new(&ellipse)
        .turning_angles(s.theta[0], &s.theta)
        .unwrap();
    let n = s.theta.len();
    let capstan = (MU * (psi[n - 1] - psi[k + 1])).exp();
    let ratio = s.tension[n - 1] / s.tension[k + 1];
    assert!((ratio / capstan - 1.0).abs() < 1e-4, "{ratio} vs {capstan}"); // grid error, 401 nodes
    assert!((s.tension_ratio() - 1.6).abs() < 1e-12);
}
