//! The frictional contact problem of the paper's section 3 on coarse grids: the boundary-only
//! solver against the full-system Newton, the Jacobian against finite differences, limits
//! (frictionless, huge friction), invariances (E, symmetric loads), limiting equilibrium and
//! typed errors.

use capstan_elasticity::contact::{
    BoundarySolver, ContactError, ContactModel, ContactSettings, ContactSolution, EndLoads,
    FullSystemProblem, FullSystemSettings, FullSystemSolver, ThickBody, ThickBodyOperator,
    ThresholdSettings, solve_sequenced, threshold_ratio,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::friction::{
    FrictionLaw, Frictionless, RegularisedCoulomb, RegularisedCoulombParams, Tresca, TrescaParams,
};
use capstan_elasticity::solvers::{
    Jacobian, LinearBackend, NonlinearMethod, Residual, SilentObserver, SparseLu, max_abs,
    max_abs_difference,
};
use capstan_elasticity::{
    BoundaryConditions, Component, Discretisation, ElasticityError, Material,
};
use capstan_geometry::{EllipticalPrism, Obstacle};

const EPS: f64 = 1e-5;

fn coulomb(mu: f64, eps: f64) -> RegularisedCoulombParams<f64> {
    RegularisedCoulombParams::new(mu, eps).unwrap()
}

/// Regularised Coulomb with `mu`, regularised and classified at `eps`, on `body`.
fn coulomb_model(body: &ThickBody, mu: f64, eps: f64) -> Model<RegularisedCoulomb> {
    body.model(RegularisedCoulomb, coulomb(mu, eps), eps)
        .unwrap()
}

type Model<L> = ContactModel<ThickBodyOperator, L>;

/// The condensed solve of `model` under `loads` with the default settings.
fn condensed<L: FrictionLaw<f64>>(model: &Model<L>, loads: EndLoads) -> ContactSolution {
    BoundarySolver::new(model, ContactSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap()
}

/// `a` and `b` agree to solver tolerance (both converge to 1e-10 relative residual):
/// displacements within `1e-7 max|a|`, the same stick and slip states.
#[track_caller]
fn assert_agree(a: &ContactSolution, b: &ContactSolution, what: &str) {
    let scale = max_abs(&a.displacement);
    let difference = max_abs_difference(&a.displacement, &b.displacement);
    assert!(
        difference < 1e-7 * scale,
        "{what}: {:e}",
        difference / scale
    );
    assert_eq!(a.contact.state, b.contact.state, "{what}");
}

fn ellipse(a: f64, b: f64, n2: usize, n3: usize) -> ThickBody {
    ThickBody {
        obstacle: Obstacle::Ellipse(EllipticalPrism::new(a, b).unwrap()),
        ..ThickBody::paper(n2, n3).unwrap()
    }
}

#[test]
fn condensed_solver_agrees_with_full_system_newton() {
    // odd n2: a node at x2 = 0, so a stick node exists at every ratio below the limit (with
    // no stick node the rigid rotation on the circle is not unique)
    for body in [ThickBody::paper(41, 9).unwrap(), ellipse(2.0, 1.2, 41, 9)] {
        let model = coulomb_model(&body, 0.5, EPS);
        let condensed = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let full = FullSystemSolver::new(&model, FullSystemSettings::default()).unwrap();
        for ratio in [1.0, 2.0, 2.9] {
            let loads = EndLoads::ratio(ratio);
            let a = condensed.solve(loads).unwrap();
            let b = full.solve(loads).unwrap();
            assert_agree(&a, &b, &format!("ratio {ratio}"));
            assert!(a.contact.state.contains(&0));
            assert!(a.stats.residual < 1e-10 && b.stats.residual < 1e-9);
        }
    }
}

#[test]
fn a_factorised_bulk_serves_other_friction_parameters_and_laws() {
    // The circle (a sliding mode whose limits depend on mu) and an ellipse (none).
    for body in [ThickBody::paper(41, 9).unwrap(), ellipse(2.0, 1.2, 41, 9)] {
        let model = coulomb_model(&body, 0.5, EPS);
        let base = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let other = model.with_params(coulomb(0.3, EPS));
        let tresca = body
            .model(Tresca, TrescaParams::new(0.2, EPS).unwrap(), EPS)
            .unwrap();
        let reused = base.with_model(&other).unwrap();
        let fresh = BoundarySolver::new(&other, ContactSettings::default()).unwrap();
        let reused_tresca = base.with_model(&tresca).unwrap();
        let fresh_tresca = BoundarySolver::new(&tresca, ContactSettings::default()).unwrap();
        assert_eq!(reused.setup().factorisations, 0);
        assert_eq!(reused.setup().bulk_solves, 0);
        assert_eq!(reused.sliding(), fresh.sliding());
        assert_eq!(reused_tresca.sliding(), fresh_tresca.sliding());
        if let Some(mode) = fresh.sliding() {
            // mu = 0.3 holds less than mu = 0.5
            assert!(mode.upper_ratio < base.sliding().unwrap().upper_ratio);
        }
        for ratio in [1.0, 1.5] {
            let loads = EndLoads::ratio(ratio);
            for (a, b) in [
                (reused.solve(loads).unwrap(), fresh.solve(loads).unwrap()),
                (
                    reused_tresca.solve(loads).unwrap(),
                    fresh_tresca.solve(loads).unwrap(),
                ),
            ] {
                // the same factorisation and condensed matrices: the same arithmetic
                assert!(
                    max_abs_difference(&a.displacement, &b.displacement)
                        <= 1e-13 * max_abs(&b.displacement),
                    "ratio {ratio}"
                );
                assert_eq!(a.contact.state, b.contact.state);
            }
        }
    }
    // Another body is refused.
    let circle = ThickBody::paper(41, 9).unwrap();
    let model = coulomb_model(&circle, 0.5, EPS);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let stiffer = ThickBody {
        material: Material::new(2e3, 0.25).unwrap(),
        ..circle
    };
    let stiffer = coulomb_model(&stiffer, 0.5, EPS);
    assert!(matches!(
        solver.with_model(&stiffer),
        Err(ContactError::DifferentBody {
            what: "bulk operators"
        })
    ));
}

#[test]
fn nodal_interpolation_is_exact_for_bilinear_fields_and_second_order() {
    let fine = ThickBody::paper(161, 33)
        .unwrap()
        .discretisation(1.0, 2.0)
        .unwrap();
    let sample = |body: &ThickBody, f: &dyn Fn(f64, f64, Component) -> f64| {
        let op = body.discretisation(1.0, 2.0).unwrap();
        let mut v = vec![0.0; op.dof_count()];
        let g = op.grid();
        for i in 0..g.n2() {
            for j in 0..g.n3() {
                for c in Component::ALL {
                    v[op.dof([i, j], c)] = f(g.x2(i), g.x3(j), c);
                }
            }
        }
        (op, v)
    };
    let error = |coarse: &ThickBody, f: &dyn Fn(f64, f64, Component) -> f64| {
        let (op, v) = sample(coarse, f);
        let got = capstan_elasticity::interpolate_nodal(&op, &v, &fine);
        let (_, exact) = sample(&ThickBody::paper(161, 33).unwrap(), f);
        max_abs_difference(&got, &exact)
    };
    let bilinear = |x2: f64, x3: f64, c: Component| match c {
        Component::X2 => 1.0 + 2.0 * x2 - x3 + 0.5 * x2 * x3,
        Component::X3 => -3.0 + x3 * (1.0 - x2),
    };
    assert!(error(&ThickBody::paper(7, 3).unwrap(), &bilinear) < 1e-13);
    let smooth = |x2: f64, x3: f64, c: Component| match c {
        Component::X2 => (2.0 * x2).sin() * (3.0 * x3).cos(),
        Component::X3 => (x2 - x3).exp(),
    };
    let errors: Vec<f64> = [(17, 5), (33, 9), (65, 17)]
        .iter()
        .map(|&(n2, n3)| error(&ThickBody::paper(n2, n3).unwrap(), &smooth))
        .collect();
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((1.85..2.15).contains(&order), "{errors:?}");
    }
}

#[test]
fn coarser_grids_halve_the_spacing_and_keep_q2_odd() {
    let body = ThickBody::paper(4000, 640).unwrap();
    let c = body.coarser().unwrap();
    assert_eq!((c.n2, c.n3), (2000, 320));
    let q2 = ThickBody {
        method: DiscretisationMethod::FemQ2,
        ..ThickBody::paper(81, 17).unwrap()
    };
    let c = q2.coarser().unwrap();
    assert_eq!((c.n2, c.n3), (41, 9));
    assert!(c.coarser().is_none(), "9 x 5 would be below 9 nodes for Q2");
    assert!(ThickBody::paper(9, 9).unwrap().coarser().is_some());
    assert!(ThickBody::paper(9, 7).unwrap().coarser().is_none());
}

#[test]
fn grid_sequencing_reaches_the_direct_full_system_solution_in_fewer_steps() {
    let sequenced = |body: &ThickBody, coarsest_nodes: usize, ratio: f64| {
        let settings = FullSystemSettings {
            coarsest_nodes,
            ..Default::default()
        };
        solve_sequenced(
            body,
            RegularisedCoulomb,
            coulomb(0.5, EPS),
            EPS,
            EndLoads::ratio(ratio),
            settings,
            &mut SilentObserver,
        )
    };
    // The circle (a rigid sliding mode) and an ellipse, 161 x 33 from an 81 x 17 coarsest level
    // (from 41 x 9, still pre-asymptotic, Newton on 81 x 17 needs as many steps as from the
    // stuck start: 12 at ratio 2 on the circle); Q2 elements, whose coarser grids stay odd, on
    // 81 x 17 from 41 x 9 (agreement only).
    let q2 = ThickBody {
        method: DiscretisationMethod::FemQ2,
        ..ThickBody::paper(81, 17).unwrap()
    };
    for (body, coarsest_nodes, coarsest, fewer_steps) in [
        (ThickBody::paper(161, 33).unwrap(), 2000, (81, 17), true),
        (ellipse(2.0, 1.2, 161, 33), 2000, (81, 17), true),
        (q2, 400, (41, 9), false),
    ] {
        let seq = sequenced(&body, coarsest_nodes, 2.0).unwrap();
        assert_eq!(
            seq.levels.iter().map(|l| (l.0, l.1)).collect::<Vec<_>>(),
            [coarsest, (body.n2, body.n3)]
        );
        let model = coulomb_model(&body, 0.5, EPS);
        let direct = FullSystemSolver::new(&model, FullSystemSettings::default())
            .unwrap()
            .solve(EndLoads::ratio(2.0))
            .unwrap();
        let (a, b) = (&seq.solution, &direct);
        assert_agree(a, b, "sequenced against direct");
        assert!(a.stats.residual < 1e-10);
        if fewer_steps {
            assert!(
                a.stats.newton_iterations < b.stats.newton_iterations
                    && a.stats.newton_iterations <= 5,
                "{} vs {}",
                a.stats.newton_iterations,
                b.stats.newton_iterations
            );
        }
    }
    // Past the limiting ratio on the circle the coarsest level reports it.
    let e = sequenced(&ThickBody::paper(81, 17).unwrap(), 400, 5.0);
    assert!(matches!(e, Err(ContactError::NoEquilibrium { .. })));
}

#[test]
fn jacobi_newton_agrees_with_lu_newton_on_a_small_grid() {
    let body = ThickBody::paper(16, 5).unwrap();
    let model = coulomb_model(&body, 0.5, EPS);
    let loads = EndLoads::ratio(2.0);
    let lu = FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap();
    let mut settings = FullSystemSettings {
        method: NonlinearMethod::JacobiNewton,
        ..Default::default()
    };
    settings.newton.iterative.relaxation = 0.5; // undamped Jacobi diverges on this operator
    settings.newton.iterative.max_iterations = 200_000;
    settings.newton.iterative.tolerance = 1e-12;
    settings.newton.linear = LinearBackend::JACOBI;
    settings.continuation.tolerance = 1e-9;
    let jacobi = FullSystemSolver::new(&model, settings)
        .unwrap()
        .solve(loads)
        .unwrap();
    let scale = max_abs(&lu.displacement);
    assert!(max_abs_difference(&lu.displacement, &jacobi.displacement) < 1e-5 * scale);
    assert!(
        jacobi.stats.linear_iterations > 100 * jacobi.stats.newton_iterations.max(1),
        "{:?}",
        jacobi.stats
    );
}

#[test]
fn full_jacobian_matches_central_differences() {
    let body = ellipse(2.0, 1.5, 20, 5);
    // eps large enough that the state below has both stick and slip nodes, all off the kink
    let eps = 2e-4;
    let model = coulomb_model(&body, 0.5, eps);
    let sol = condensed(&model, EndLoads::ratio(1.6));
    assert!(sol.contact.state.contains(&0) && sol.contact.state.contains(&1));
    let problem = FullSystemProblem::new(&model, EndLoads::ratio(1.6));
    let v = &sol.displacement;
    let pattern = problem.pattern().clone();
    let mut values = vec![0.0; pattern.nnz()];
    problem.jacobian(v, &mut values).unwrap();
    let n = v.len();
    let (mut rp, mut rm) = (vec![0.0; n], vec![0.0; n]);
    let mut worst: f64 = 0.0;
    for col in 0..n {
        let h = 1e-9;
        // stay off the kink |u| = eps of stick/slip nodes
        let mut vp = v.clone();
        vp[col] += h;
        let mut vm = v.clone();
        vm[col] -= h;
        problem.residual(&vp, &mut rp).unwrap();
        problem.residual(&vm, &mut rm).unwrap();
        let rows = pattern.column_rows(col);
        for (i, &row) in rows.iter().enumerate() {
            let fd = (rp[row] - rm[row]) / (2.0 * h);
            let exact = values[pattern.col_ptr()[col] + i];
            worst = worst.max((fd - exact).abs() / exact.abs().max(1.0));
        }
        // rows outside the pattern must not change
        for row in 0..n {
            if !rows.contains(&row) {
                assert!(
                    (rp[row] - rm[row]).abs() < 1e-9,
                    "({row}, {col}) outside the pattern"
                );
            }
        }
    }
    assert!(worst < 1e-4, "worst relative difference {worst:e}");
}

#[test]
fn frictionless_limit_is_the_linear_solve_with_zero_tangential_traction() {
    // not a circle: the frictionless body on a circle has a rigid rotation
    let body = ellipse(2.0, 1.5, 30, 7);
    let loads = EndLoads::new(1.0, 1.3);
    let model = body.model(Frictionless, (), EPS).unwrap();
    let sol = condensed(&model, loads);
    let linear = body
        .discretisation(loads.tau0, loads.tau_max)
        .unwrap()
        .solve(&mut SparseLu::default())
        .unwrap();
    assert!(max_abs_difference(&sol.displacement, &linear) < 1e-10 * max_abs(&linear));
    // and Coulomb with mu = 0 is the same
    let model0 = coulomb_model(&body, 0.0, EPS);
    let sol0 = condensed(&model0, loads);
    assert!(max_abs_difference(&sol0.displacement, &linear) < 1e-10 * max_abs(&linear));
}

#[test]
fn frictionless_circle_has_no_equilibrium_unless_balanced() {
    let body = ThickBody::paper(24, 5).unwrap();
    let model = body.model(Frictionless, (), EPS).unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let mode = solver.sliding().expect("a circle has a sliding mode");
    assert!((mode.lower_ratio - 1.0).abs() < 1e-8 && (mode.upper_ratio - 1.0).abs() < 1e-8);
    assert!(matches!(
        solver.solve(EndLoads::ratio(1.01)),
        Err(ContactError::NoEquilibrium { .. })
    ));
}

#[test]
fn huge_friction_approaches_the_stuck_linear_solution() {
    let body = ThickBody::paper(30, 7).unwrap();
    let loads = EndLoads::ratio(2.0);
    let model = coulomb_model(&body, 1e3, EPS);
    let sol = condensed(&model, loads);
    // the end nodes carry almost no normal stress and may still slide
    let sticking = sol.contact.state.iter().filter(|&&s| s == 0).count();
    assert!(
        sticking + 4 >= sol.contact.state.len(),
        "{:?}",
        sol.contact.state
    );
    let clamped = {
        let grid = body.discretisation(1.0, 2.0).unwrap();
        capstan_elasticity::FiniteDifferenceNavier::new(capstan_elasticity::PlaneProblem {
            chart: capstan_geometry::ShellChart::new(body.obstacle.clone()),
            material: body.material,
            grid: *grid.grid(),
            boundary: BoundaryConditions::paper_clamped(1.0, 2.0),
            body_force: None,
        })
        .unwrap()
        .solve(&mut SparseLu::default())
        .unwrap()
    };
    // stick stiffness mu |sigma| / eps ~ 1e8 in the interior (measured 2.4e-4: the end nodes,
    // where sigma_n -> 0, still slide a little)
    let d = max_abs_difference(&sol.displacement, &clamped) / max_abs(&clamped);
    assert!(d < 1e-3, "{d:e}");
}

#[test]
fn young_modulus_scales_displacements_when_eps_scales_with_it() {
    let loads = EndLoads::ratio(2.0);
    let solve = |young: f64, eps: f64| {
        let body = ThickBody {
            material: Material::new(young, 0.25).unwrap(),
            ..ThickBody::paper(40, 9).unwrap()
        };
        let model = coulomb_model(&body, 0.5, eps);
        condensed(&model, loads)
    };
    let a = solve(1e3, EPS);
    let b = solve(2.5e3, EPS / 2.5);
    let scaled: Vec<f64> = b.displacement.iter().map(|x| 2.5 * x).collect();
    // the problem is exactly invariant under (E, eps, v) -> (k E, eps / k, v / k)
    assert!(
        max_abs_difference(&a.displacement, &scaled) < 1e-8 * max_abs(&a.displacement),
        "{:e} {:?} {:?}",
        max_abs_difference(&a.displacement, &scaled) / max_abs(&a.displacement),
        a.stats,
        b.stats
    );
    assert_eq!(a.contact.state, b.contact.state);
    assert_eq!(a.slip_fraction, b.slip_fraction);
    for (x, y) in a.contact.normal_stress.iter().zip(&b.contact.normal_stress) {
        assert!((x - y).abs() < 1e-8);
    }
}

#[test]
fn symmetric_loads_on_the_circle_give_an_odd_tangential_displacement() {
    let body = ThickBody::paper(41, 9).unwrap();
    let model = coulomb_model(&body, 0.5, EPS);
    let sol = condensed(&model, EndLoads::new(1.0, 1.0));
    let disc = model.discretisation();
    let scale = max_abs(&sol.displacement);
    for i in 0..41 {
        for j in 0..9 {
            let v2 = sol.displacement[disc.dof([i, j], Component::X2)];
            let m2 = sol.displacement[disc.dof([40 - i, j], Component::X2)];
            let v3 = sol.displacement[disc.dof([i, j], Component::X3)];
            let m3 = sol.displacement[disc.dof([40 - i, j], Component::X3)];
            assert!((v2 + m2).abs() < 1e-9 * scale);
            assert!((v3 - m3).abs() < 1e-9 * scale);
        }
    }
    assert!(sol.slip_fraction.abs() < 1e-12);
}

#[test]
fn circle_past_the_limiting_ratio_has_no_equilibrium() {
    let body = ThickBody::paper(40, 9).unwrap();
    let model = coulomb_model(&body, 0.5, EPS);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let mode = solver.sliding().unwrap();
    assert!(mode.upper_ratio > 3.0 && mode.upper_ratio < 3.6);
    assert!((mode.lower_ratio * mode.upper_ratio - 1.0).abs() < 1e-8); // mirror symmetry
    let err = solver
        .solve(EndLoads::ratio(mode.upper_ratio * 1.01))
        .unwrap_err();
    assert!(matches!(err, ContactError::NoEquilibrium { .. }), "{err}");
    assert_eq!(err.status(), "no-equilibrium");
    // just below the limit a solution exists and nearly everything slides forward
    let sol = solver
        .solve(EndLoads::ratio(mode.upper_ratio * 0.999))
        .unwrap();
    assert!(sol.slip_fraction > 0.9);
    // an ellipse has no sliding mode
    let model = coulomb_model(&ellipse(2.0, 1.5, 40, 9), 0.5, EPS);
    assert!(
        BoundarySolver::new(&model, ContactSettings::default())
            .unwrap()
            .sliding()
            .is_none()
    );
}

#[test]
fn tresca_limit_on_the_circle_is_the_exact_moment_balance() {
    // Rigid sliding of the annulus a <= r <= a + h over the half circle: the end tractions
    // (T^2_2 = sigma_thetatheta) have the moment tau ((a + h)^2 - a^2) / 2 about the axis, the
    // saturated Tresca friction g a pi a. Limiting equilibrium:
    //   (tau_max - tau0) ((a + h)^2 - a^2) / 2 = +- g pi a^2
    // a linear balance the discrete moment balance reproduces up to the grid's quadrature of
    // the end faces; the limits depend on tau0 (Tresca is not homogeneous in sigma_n).
    let (a, h, g) = (2.0, 1.0, 0.1);
    let jump = g * std::f64::consts::PI * a * a / (((a + h) * (a + h) - a * a) / 2.0);
    let mut errors = Vec::new();
    for (n2, n3) in [(20, 5), (40, 9), (80, 17)] {
        let model = ThickBody::paper(n2, n3)
            .unwrap()
            .model(Tresca, TrescaParams::new(g, EPS).unwrap(), EPS)
            .unwrap();
        let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let mut err = 0.0f64;
        for tau0 in [1.0, 2.0] {
            let mode = solver.sliding_at(tau0).unwrap().expect("sliding mode");
            assert_eq!(mode.tau0, tau0);
            err = err
                .max((mode.upper_ratio - (1.0 + jump / tau0)).abs())
                .max((mode.lower_ratio - (1.0 - jump / tau0)).abs());
            // beyond the limit: no equilibrium, typed; inside: a solution
            let beyond = EndLoads::new(tau0, tau0 * mode.upper_ratio * 1.01);
            assert!(matches!(
                solver.solve(beyond),
                Err(ContactError::NoEquilibrium { .. })
            ));
            let inside = EndLoads::new(tau0, tau0 * (1.0 + 0.5 * jump / tau0));
            assert!(solver.solve(inside).unwrap().slip_fraction < 1.0);
        }
        errors.push(err);
    }
    assert!(errors[2] < 1e-6, "{errors:?}");
    assert!(
        errors.windows(2).all(|w| w[1] <= w[0] + 1e-12),
        "{errors:?}"
    );
}

#[test]
fn coulomb_limits_are_found_on_every_grid_despite_the_corner_nodes() {
    // The full-slip normal stress at the one or two nodes next to each loaded corner is a
    // resolution artefact of either sign; the limits must not depend on it (they did: a sign
    // check on every inner node lost them on 500 x 81). Grid convergence of the upper limit:
    // its changes shrink under refinement.
    let mut limits = Vec::new();
    for (n2, n3) in [(20, 5), (40, 9), (80, 17), (160, 33)] {
        let model = coulomb_model(&ThickBody::paper(n2, n3).unwrap(), 0.5, EPS);
        let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let mode = solver.sliding().expect("sliding mode");
        assert!(
            mode.upper_ratio.is_finite() && mode.lower_ratio.is_finite(),
            "{mode:?}"
        );
        assert!((mode.lower_ratio * mode.upper_ratio - 1.0).abs() < 1e-8);
        // homogeneous law: the same limits for any tau0
        assert_eq!(solver.sliding_at(3.0).unwrap(), Some(mode));
        limits.push(mode.upper_ratio);
    }
    let d: Vec<f64> = limits.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    assert!(d[2] < d[1] && d[1] < d[0], "{limits:?}");
}

#[test]
fn regularisation_to_zero_converges_to_the_coulomb_limit() {
    // eps -> 0 down to 1e-10 (far below the displacements, ~1e-3): the condensed Newton
    // converges (full-system relative residual below 1e-9: the stick stiffness mu sigma / eps
    // amplifies rounding), and the contact slip converges as eps does: the change per decade of eps shrinks about tenfold (first order in eps).
    let model = |eps: f64| coulomb_model(&ThickBody::paper(41, 9).unwrap(), 0.5, eps);
    let mut slips = Vec::new();
    for eps in [1e-6, 1e-7, 1e-8, 1e-9, 1e-10] {
        let model = model(eps);
        let sol = condensed(&model, EndLoads::ratio(2.0));
        assert!(sol.stats.residual < 1e-9, "eps {eps}: {:?}", sol.stats);
        slips.push(sol.contact.slip.clone());
    }
    let changes: Vec<f64> = slips
        .windows(2)
        .map(|w| max_abs_difference(&w[0], &w[1]))
        .collect();
    for w in changes.windows(2) {
        let ratio = w[0] / w[1];
        assert!(ratio > 5.0 && ratio < 20.0, "{changes:?}");
    }
}

#[test]
fn threshold_on_the_circle_is_the_limiting_ratio() {
    let body = ThickBody::paper(40, 9).unwrap();
    let model = coulomb_model(&body, 0.5, EPS);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let t = threshold_ratio(&solver, ThresholdSettings::default()).unwrap();
    let limit = t.limiting_ratio.unwrap();
    assert!(
        t.ratio <= limit * (1.0 + 2e-6) && t.ratio > limit * 0.99,
        "{t:?}"
    );
}

#[test]
fn threshold_bracketed_at_the_limit_takes_three_solves_and_matches_the_bisection() {
    let body = ThickBody::paper(40, 9).unwrap();
    let model = coulomb_model(&body, 0.5, EPS);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let bisection = threshold_ratio(&solver, ThresholdSettings::default()).unwrap();
    for tolerance in [1e-4, 1e-6, 1e-8] {
        let settings = ThresholdSettings {
            tolerance,
            bracket_at_limit: true,
            ..Default::default()
        };
        let t = threshold_ratio(&solver, settings).unwrap();
        let limit = t.limiting_ratio.unwrap();
        // r = 1, L (1 + d) (no equilibrium), L (1 + d) (1 - 0.99 tolerance) (a stick node)
        assert_eq!(t.solves, 3, "{t:?}");
        assert!(t.above_is_no_equilibrium && t.slip_fraction_below < 1.0);
        assert!(t.ratio - t.below <= tolerance * t.ratio, "{t:?}");
        assert!(
            t.ratio > limit && t.ratio <= limit * (1.0 + tolerance.min(4e-6) / 4.0),
            "{t:?}"
        );
        // the bisection from 1 (tolerance 1e-6) ends on the same limit
        assert!(
            (t.ratio - bisection.ratio).abs() <= 2e-6 * limit,
            "{t:?} {bisection:?}"
        );
        assert!(bisection.solves > 15);
    }
    // without a sliding mode (an ellipse) the option changes nothing
    let body = ellipse(2.0, 1.0, 40, 9);
    let model = coulomb_model(&body, 0.5, EPS);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let settings = ThresholdSettings {
        bracket_at_limit: true,
        ..Default::default()
    };
    assert_eq!(
        threshold_ratio(&solver, settings).unwrap(),
        threshold_ratio(&solver, ThresholdSettings::default()).unwrap()
    );
}

#[test]
fn threshold_on_an_ellipse_is_where_slip_reaches_one() {
    let body = ellipse(2.0, 1.0, 40, 9);
    let model = coulomb_model(&body, 0.5, EPS);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let t = threshold_ratio(&solver, ThresholdSettings::default()).unwrap();
    assert!(t.limiting_ratio.is_none());
    assert!(
        solver
            .solve(EndLoads::ratio(t.above))
            .unwrap()
            .fully_slipping()
    );
    assert!(
        !solver
            .solve(EndLoads::ratio(t.below))
            .unwrap()
            .fully_slipping()
    );
}

#[test]
fn bad_inputs_are_typed_errors() {
    let body = ThickBody::paper(20, 5).unwrap();
    assert!(matches!(
        body.model(RegularisedCoulomb, coulomb(0.5, EPS), 0.0),
        Err(ContactError::Elasticity(
            ElasticityError::InvalidParameter {
                field: "slip_threshold",
                ..
            }
        ))
    ));
    let model = coulomb_model(&body, 0.5, EPS);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let err = solver.solve(EndLoads::new(f64::NAN, 1.0)).unwrap_err();
    assert!(matches!(
        err,
        ContactError::Elasticity(ElasticityError::InvalidParameter {
            field: "loads.tau0",
            ..
        })
    ));
    assert_eq!(err.status(), "invalid-input");
    assert_eq!(
        err.to_string(),
        "`loads.tau0` = NaN is outside finite values"
    );
    assert!(matches!(
        BoundarySolver::new(
            &model,
            ContactSettings {
                tolerance: 0.0,
                ..Default::default()
            }
        ),
        Err(ContactError::Elasticity(
            ElasticityError::InvalidParameter { .. }
        ))
    ));
    assert!(RegularisedCoulombParams::new(-1.0, EPS).is_err());
}

#[test]
fn thin_bodies_on_the_circle_converge_and_approach_the_capstan_limit() {
    // h -> 0 on a fixed 60 x 11 grid (cells up to 500 times wider than thick): the bulk's
    // diagonal grows like 1 / dx3^2 while the boundary stiffness falls like h, and the body is
    // held along the circle only by friction, slipping both ways from a neutral point. The
    // condensed Newton (softened spring, rigid amplitude rebalanced at every iterate) converges
    // in a few iterations, the full-system residual confirms the solution, and the upper
    // limiting ratio tends to the capstan value exp(mu pi) = 4.81048 as the body thins.
    let capstan = (0.5 * core::f64::consts::PI).exp();
    let mut gaps = Vec::new();
    for h in [0.1, 0.01, 0.001] {
        let body = ThickBody {
            thickness: h,
            ..ThickBody::paper(60, 11).unwrap()
        };
        let model = coulomb_model(&body, 0.5, EPS);
        let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        for ratio in [1.5, 2.75, 4.5] {
            let sol = solver.solve(EndLoads::ratio(ratio)).unwrap();
            assert!(
                sol.stats.residual < 1e-7 && sol.stats.newton_iterations <= 25,
                "h {h}, ratio {ratio}: {:?}",
                sol.stats
            );
        }
        let mode = solver.sliding().expect("sliding mode");
        gaps.push((capstan - mode.upper_ratio) / capstan);
    }
    assert!(
        gaps[0] > gaps[1] && gaps[1] > gaps[2] && gaps[2].abs() < 1e-3,
        "{gaps:?}"
    );
}
