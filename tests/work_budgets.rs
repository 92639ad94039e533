//! Issue 18: every adaptive or iterative algorithm has a work budget, a scene key, and a typed
//! error naming that key when it runs out. One test per budget: the smallest scene that
//! exhausts it.

use capstan::CliError;
use capstan::commands::infer_mu::{FrictionModel, report_for};
use capstan::commands::{contact, tension};
use capstan::scene::Scene;
use capstan_friction::FrictionError;

fn scene(sets: &[&str]) -> Scene {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scene::from_text(None, &sets).expect("a valid scene")
}

/// The error names `key`, and exits with code 4 (no convergence).
fn names(e: &CliError, key: &str) {
    assert!(e.to_string().contains(key), "{key} not named in: {e}");
    assert_eq!(e.exit_code(), 4, "{e}");
}

const HEAVY_ELLIPSE: &[&str] = &["obstacle.b=1", "loads.gravity=9.81", "loads.density=1"];

#[test]
fn quadrature_panels_run_out_naming_max_subdivisions() {
    for shape in [
        ["obstacle.shape=prism", "obstacle.u=2*sin(t)+0.2*sin(2*t)"],
        [
            "obstacle.shape=cone",
            "obstacle.ubar=0.5*sin(t)+0.05*sin(2*t)",
        ],
    ] {
        let s = scene(&[shape[0], shape[1], "membrane.max_subdivisions=1"]);
        let e = tension::report(&s).unwrap_err();
        assert!(
            matches!(
                e,
                CliError::Friction(FrictionError::QuadratureNotConverged { limit: 1, .. })
            ),
            "{e}"
        );
        names(&e, "membrane.max_subdivisions");
    }
}

#[test]
fn ode_steps_run_out_naming_max_steps() {
    let s = scene(&[HEAVY_ELLIPSE, &["membrane.max_steps=2"]].concat());
    let e = tension::report(&s).unwrap_err();
    assert!(matches!(
        e,
        CliError::Friction(FrictionError::TooManySteps { max_steps: 2, .. })
    ));
    names(&e, "membrane.max_steps");
    // the default budget answers
    assert!(tension::report(&scene(HEAVY_ELLIPSE)).is_ok());
}

#[test]
fn ode_step_floor_naming_min_step() {
    let s = scene(&[HEAVY_ELLIPSE, &["membrane.min_step=1"]].concat());
    let e = tension::report(&s).unwrap_err();
    assert!(matches!(
        e,
        CliError::Friction(FrictionError::StepSizeTooSmall { .. })
    ));
    names(&e, "membrane.min_step");
}

#[test]
fn root_finder_runs_out_naming_max_root_iterations() {
    let s = scene(
        &[
            HEAVY_ELLIPSE,
            &["membrane.t_max=3", "membrane.max_root_iterations=1"],
        ]
        .concat(),
    );
    let e = report_for(&s, FrictionModel::Capstan).unwrap_err();
    assert!(
        matches!(
            e,
            CliError::Friction(FrictionError::RootNotConverged { .. })
        ),
        "{e}"
    );
    names(&e, "membrane.max_root_iterations");
}

#[test]
fn membrane_newton_runs_out_naming_max_newton_iterations() {
    use capstan_friction::membrane_displacement::{
        EndCondition, MembraneDisplacement, MembraneDisplacementProblem, MembraneNewton,
    };
    use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
    // Partial slip (the tension pair below the capstan ratio): one Newton step is not enough.
    let ellipse = capstan_geometry::EllipticalPrism::new(2.0, 2.0).unwrap();
    let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
    let model = MembraneDisplacement::new(&ellipse, RegularisedCoulomb, params);
    let problem = MembraneDisplacementProblem {
        theta0: -1.5,
        theta1: 1.5,
        nodes: 101,
        stiffness: 1e3,
        start: EndCondition::Tension(1.0),
        end: EndCondition::Tension(1.5),
    };
    let newton = |max_iterations| MembraneNewton {
        max_iterations,
        ..Default::default()
    };
    let e = model.solve(&problem, None, newton(1)).unwrap_err();
    assert!(
        matches!(e, FrictionError::NewtonNotConverged { iterations: 1, .. }),
        "{e}"
    );
    names(&CliError::Friction(e), "membrane.max_newton_iterations");
    // the scene key reaches the model (`infer-mu --model membrane`)
    let s = scene(&["membrane.t_max=2.75", "membrane.max_newton_iterations=7"]);
    assert_eq!(s.membrane.max_newton_iterations, 7);
}

const SMALL_BODY: &[&str] = &["grid.n2=21", "grid.n3=5"];

#[test]
fn contact_newton_and_continuation_run_out_naming_their_keys() {
    for (budget, key) in [
        (
            ["solver.max_iterations=1", "solver.max_continuation_steps=1"],
            "solver.max_iterations",
        ),
        (
            ["solver.max_iterations=1", "solver.max_continuation_steps=1"],
            "solver.max_continuation_steps",
        ),
        (
            ["solver.max_iterations=1", "solver.min_load_step=0.25"],
            "solver.min_load_step",
        ),
    ] {
        let s = scene(&[SMALL_BODY, &budget].concat());
        let e = contact::solve(&s).unwrap_err();
        assert!(matches!(e, CliError::ContactBudget { .. }), "{e}");
        names(&e, key);
    }
    // the default budgets answer
    assert!(contact::solve(&scene(SMALL_BODY)).is_ok());
}

#[test]
fn full_newton_iterations_and_jacobi_sweeps_run_out_naming_their_keys() {
    for (budget, key) in [
        (
            ["solver.max_iterations=1", "solver.max_continuation_steps=1"],
            "solver.max_iterations",
        ),
        (
            ["solver.linear=jacobi", "solver.max_sweeps=1"],
            "solver.max_sweeps",
        ),
    ] {
        let s = scene(&[SMALL_BODY, &["solver.nonlinear=full-newton"], &budget].concat());
        names(&contact::solve(&s).unwrap_err(), key);
    }
}

#[test]
fn multigrid_krylov_iterations_run_out_naming_max_sweeps() {
    // 8415 unknowns: above the coarsest multigrid level, so GMRES / CG iterate
    let s = scene(&[
        "body.dimension=3",
        "obstacle.b=1.5",
        "discretisation.method=fem-q1",
        "grid.n1=5",
        "grid.n2=33",
        "grid.n3=17",
        "solver.nonlinear=full-newton",
        "solver.linear=multigrid",
        "solver.max_sweeps=1",
    ]);
    let e = contact::solve(&s).unwrap_err();
    names(&e, "solver.max_sweeps");
}

#[test]
fn budgets_are_validated_naming_the_key() {
    for key in [
        "membrane.max_subdivisions",
        "membrane.max_steps",
        "membrane.max_root_iterations",
        "membrane.max_newton_iterations",
        "solver.max_iterations",
        "solver.max_continuation_steps",
        "solver.max_sweeps",
    ] {
        let e = Scene::from_text(None, &[format!("{key}=0")]).unwrap_err();
        assert!(e.to_string().contains(key) && e.exit_code() == 2, "{e}");
    }
    for (key, value) in [("membrane.min_step", "-1"), ("solver.min_load_step", "0.5")] {
        let e = Scene::from_text(None, &[format!("{key}={value}")]).unwrap_err();
        assert!(e.to_string().contains(key) && e.exit_code() == 2, "{e}");
    }
}
