//! Unilateral (Signorini) contact of the thick body: equal to bilateral contact where the
//! bilateral solution presses everywhere, lift-off where it would pull.

use capstan_elasticity::ElasticityError;
use capstan_elasticity::contact::{
    Body, BoundarySolver, ContactError, ContactErrorKind, ContactKind, ContactSettings,
    ContactSolution, EndLoads, FullSystemSettings, FullSystemSolver, Gap, SEPARATED,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_geometry::{EllipticalPrism, Obstacle};

fn body(method: DiscretisationMethod, n2: usize, n3: usize) -> Body {
    let circle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 2.0).unwrap());
    let mut b = Body::new(circle, n2, n3);
    b.method = method;
    b
}

#[test]
fn unilateral_equals_bilateral_where_every_node_presses() {
    for method in [DiscretisationMethod::Fd, DiscretisationMethod::FemQ1] {
        let mut b = body(method, 41, 9);
        let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
        let loads = EndLoads::new(1.0, 1.5);
        let bilateral = b.model(RegularisedCoulomb, params, 1e-5).unwrap();
        let s_bi = FullSystemSolver::new(&bilateral, FullSystemSettings::default())
            .unwrap()
            .solve(loads)
            .unwrap();
        b.contact = ContactKind::unilateral();
        let unilateral = b.model(RegularisedCoulomb, params, 1e-5).unwrap();
        let s_uni = FullSystemSolver::new(&unilateral, FullSystemSettings::default())
            .unwrap()
            .solve(loads)
            .unwrap();
        assert_eq!(s_bi.tensile_contact_nodes, 0);
        assert_eq!(s_uni.lift_off_intervals.as_deref(), Some(&[][..]));
        assert!(s_bi.lift_off_intervals.is_none());
        assert_eq!(s_uni.slip_fraction, s_bi.slip_fraction);
        let scale = s_bi.displacement.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let diff = s_bi
            .displacement
            .iter()
            .zip(&s_uni.displacement)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        // the same equations (the free rows replaced by v^3 = 0): round-off only
        assert!(diff <= 1e-12 * scale, "{method:?}: {diff:e} of {scale:e}");
    }
}

/// The paper's body whose obstacle falls away beyond `|x2| = 0.8`: the gap
/// `g = 0.01 (|x2| - 0.8)^2` there, zero in the middle.
fn falling_away(n2: usize) -> Body {
    let mut b = body(DiscretisationMethod::FemQ1, n2, (n2 - 1) / 5 + 1);
    b.contact = ContactKind::Unilateral {
        gap: Gap::new(|x: [f64; 2]| 0.01 * (x[1].abs() - 0.8).max(0.0).powi(2)),
    };
    b
}

fn solve_unilateral(b: &Body, loads: EndLoads) -> ContactSolution {
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let model = b.model(RegularisedCoulomb, params, 1e-5).unwrap();
    FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap()
}

#[test]
fn lift_off_zones_converge_under_refinement() {
    let loads = EndLoads::new(1.0, 1.5);
    let ends: Vec<[f64; 2]> = [41, 81, 161]
        .into_iter()
        .map(|n| {
            let s = solve_unilateral(&falling_away(n), loads);
            let zones = s.lift_off_intervals.clone().unwrap();
            assert_eq!(zones.len(), 2, "n2 = {n}: {zones:?}");
            let theta = core::f64::consts::FRAC_PI_2;
            assert_eq!(zones[0].from, -theta);
            assert_eq!(zones[1].to, theta);
            // complementarity at the nodes: separated nodes carry no friction, nodes in
            // contact sit on the obstacle
            let gap = |x2: f64| 0.01 * (x2.abs() - 0.8f64).max(0.0).powi(2);
            for k in 0..s.contact.x2.len() {
                let opening = s.contact.v3[k] + gap(s.contact.x2[k]);
                if s.contact.state[k] == SEPARATED {
                    assert!(opening > 0.0);
                    assert_eq!(s.contact.friction_traction[k], 0.0);
                } else {
                    assert!(opening.abs() < 1e-12, "{opening:e}");
                }
            }
            [zones[0].to, zones[1].from]
        })
        .collect();
    // the zone ends converge: successive differences shrink
    for side in 0..2 {
        let d1 = (ends[1][side] - ends[0][side]).abs();
        let d2 = (ends[2][side] - ends[1][side]).abs();
        assert!(d2 < d1, "side {side}: {ends:?}");
        assert!(d2 < 0.03, "side {side}: {ends:?}");
    }
}

#[test]
fn the_condensed_solver_refuses_unilateral_contact_naming_the_solver_key() {
    let b = falling_away(21);
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let model = b.model(RegularisedCoulomb, params, 1e-5).unwrap();
    let Err(err) = BoundarySolver::new(&model, ContactSettings::default()) else {
        panic!("the condensed solver keeps v^3 = 0")
    };
    assert!(
        matches!(
            err,
            ContactError::Unsupported {
                field: "solver.nonlinear",
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(err.status(), "invalid-input");
}

#[test]
fn a_negative_gap_is_refused_naming_contact_gap() {
    let mut b = falling_away(21);
    b.contact = ContactKind::Unilateral {
        gap: Gap::constant(-1e-3),
    };
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let Err(err) = b.model(RegularisedCoulomb, params, 1e-5) else {
        panic!("a negative gap penetrates the obstacle")
    };
    assert!(
        matches!(
            err,
            ContactError::Elasticity(ElasticityError::InvalidParameter {
                field: "contact.gap",
                ..
            })
        ),
        "{err}"
    );
}

#[test]
fn a_3d_body_of_finite_width_lifts_off_and_its_zones_converge() {
    use capstan_elasticity::contact::Dimension;
    use capstan_elasticity::solid::SideFaces;
    let loads = EndLoads::new(1.0, 1.5);
    let ends: Vec<[f64; 2]> = [(21, 5), (41, 9), (81, 17)]
        .into_iter()
        .map(|(n2, n3)| {
            let mut b = falling_away(n2);
            b.n3 = n3;
            b.dimension = Dimension::Solid {
                x1: [-0.5, 0.5],
                n1: 3,
                sides: SideFaces::Free,
            };
            let s = solve_unilateral(&b, loads);
            let zones = s.lift_off_intervals.clone().unwrap();
            assert_eq!(zones.len(), 2, "n2 = {n2}: {zones:?}");
            let separated = s.contact.separated.as_ref().unwrap();
            assert_eq!(separated.len(), s.contact.x2.len());
            [zones[0].to, zones[1].from]
        })
        .collect();
    for side in 0..2 {
        let d1 = (ends[1][side] - ends[0][side]).abs();
        let d2 = (ends[2][side] - ends[1][side]).abs();
        assert!(d2 < d1, "side {side}: {ends:?}");
    }
}

#[test]
fn every_newton_iterate_reports_its_contact_set_to_the_observer() {
    use capstan_elasticity::solvers::{Progress, SolveStage};
    let b = falling_away(41);
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let model = b.model(RegularisedCoulomb, params, 1e-5).unwrap();
    let mut sets = Vec::new();
    let mut observer = |p: &Progress<f64>| {
        if p.stage == SolveStage::Newton {
            sets.push(
                p.active
                    .expect("the full-system Newton reports its active set"),
            );
        }
    };
    let s = FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve_observed(EndLoads::new(1.0, 1.5), &mut observer)
        .unwrap();
    let last = sets.last().unwrap();
    assert_eq!(last.stick + last.slip + last.separated, s.contact.x2.len());
    let separated = s.contact.state.iter().filter(|&&x| x == SEPARATED).count();
    assert_eq!(last.separated, separated);
    assert!(separated > 0);
    // the semismooth Newton moves the active set from the closed start to the solution's
    assert!(sets.windows(2).any(|w| w[0] != w[1]), "{sets:?}");
}

/// The manufactured Signorini solution ([`SignoriniMms`]: contact on `x2 < 0.1`, lifted off
/// beyond) converges at the element's order (FD and Q1: 2; Q2: 3, nodal values up to 4),
/// over the whole body and away from the split; the discrete split brackets the exact one
/// within a grid spacing.
#[test]
fn manufactured_signorini_converges_at_the_element_order() {
    use capstan_elasticity::studies::SignoriniMms;
    use capstan_elasticity::verification::{GridLevel, observed_order};
    let mms = SignoriniMms::default();
    // (method, expected order, finest error away from the split bound)
    let cases = [
        (DiscretisationMethod::Fd, 2.0, 1e-5),
        (DiscretisationMethod::FemQ1, 2.0, 3e-6),
        (DiscretisationMethod::FemQ2, 3.0, 3e-7),
    ];
    for (method, expected, bound) in cases {
        let study: Vec<_> = [12, 24, 48]
            .into_iter()
            .map(|m| {
                let level = GridLevel {
                    n2: 2 * m + 1,
                    n3: m + 1,
                };
                mms.run(method, level, 0.25).unwrap()
            })
            .collect();
        let table: String = study
            .iter()
            .map(|p| {
                format!(
                    "{:?} h {:.4} max {:.3e} away {:.3e} split {:?} newton {}\n",
                    (p.level.n2, p.level.n3),
                    p.h,
                    p.max_error,
                    p.max_error_away,
                    p.split,
                    p.newton_iterations
                )
            })
            .collect();
        let order = |f: fn(&capstan_elasticity::studies::SignoriniPoint) -> f64| {
            observed_order(&study.iter().map(|p| (p.h, f(p))).collect::<Vec<_>>())
        };
        let (whole, away) = (order(|p| p.max_error), order(|p| p.max_error_away));
        if expected == 2.0 {
            assert!((away - 2.0).abs() < 0.15, "{method:?} {away}\n{table}");
            assert!((whole - 2.0).abs() < 0.15, "{method:?} {whole}\n{table}");
        } else {
            // nodal values of Q2 superconverge (order 4 on smooth data); the split's band
            // keeps the observed order between 3 and 4
            assert!((2.85..4.3).contains(&away), "{method:?} {away}\n{table}");
            assert!((2.85..4.3).contains(&whole), "{method:?} {whole}\n{table}");
        }
        let finest = study.last().unwrap();
        assert!(finest.max_error_away < bound, "{method:?}\n{table}");
        let [last_contact, first_separated] = finest.split.unwrap();
        assert!(
            last_contact <= mms.split + finest.h && first_separated >= mms.split - finest.h,
            "{method:?}\n{table}"
        );
        assert!(
            first_separated - last_contact < 1.5 * finest.h,
            "{method:?}\n{table}"
        );
    }
}

/// Compressed ends (`tau0 = tau_max = -1`) bow the body off the obstacle: every node
/// separates, the free body has rigid motions, and the solver says there is no equilibrium
/// (the kind behind exit code 3) instead of returning a solution off the obstacle; pressed
/// on by tension the same body solves. Unbalanced compression (`-1`, `-2`) too.
#[test]
fn a_body_lifting_off_entirely_has_no_equilibrium() {
    let mut b = body(DiscretisationMethod::FemQ1, 41, 9);
    b.contact = ContactKind::unilateral();
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let model = b.model(RegularisedCoulomb, params, 1e-5).unwrap();
    let solver = FullSystemSolver::new(&model, FullSystemSettings::default()).unwrap();
    for (tau0, tau_max) in [(-1.0, -1.0), (-1.0, -2.0)] {
        let err = solver.solve(EndLoads::new(tau0, tau_max)).unwrap_err();
        assert!(
            matches!(err, ContactError::LiftedOff { nodes: 41, .. }),
            "({tau0}, {tau_max}): {err}"
        );
        assert_eq!(err.kind(), ContactErrorKind::NoEquilibrium);
    }
    assert!(solver.solve(EndLoads::new(1.0, 1.5)).is_ok());
}
