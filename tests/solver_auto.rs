//! `solver.nonlinear = "auto"` (the default): what it picks, that it reports the choice, and
//! that the default scene's answer is the one of the condensed solver before it (pinned from
//! `capstan contact --json` of the previous default, the condensation by `m` bulk solves).

mod common;

use capstan::elasticity::solid::SideFaces;
use capstan::problem::{Dimension, Problem, SolveMethod, Solver};
use capstan::solvers::LinearBackend;
use common::capstan_json;

#[test]
fn auto_condenses_plane_and_small_3d_bodies_goes_matrix_free_on_large_ones_and_keeps_named_methods()
{
    let mut problem = Problem::paper();
    let (method, choice) = problem.solver.resolved(&problem.body);
    assert_eq!(method, SolveMethod::Condensed);
    assert!(choice.auto);
    assert_eq!((choice.nonlinear, choice.linear), ("newton", "lu"));
    // the first 3-D try (5 x 250 nodes on the face, 2,500 contact unknowns): the condensed
    // solver took 254 s there, full-newton with lu ran out of memory: the matrix-free Newton
    problem.body.method = "fem-q1".parse().unwrap();
    problem.body.dimension = Dimension::Solid {
        x1: [0.5, 1.5],
        n1: 5,
        sides: SideFaces::PlaneStrain,
    };
    let (method, choice) = problem.solver.resolved(&problem.body);
    assert_eq!(
        method,
        SolveMethod::FullNewton(LinearBackend::MATRIX_FREE_MG)
    );
    assert_eq!(
        (choice.nonlinear, choice.linear),
        ("full-newton", "matrix-free-mg")
    );
    assert!(
        choice.reason.contains("2500 contact unknowns"),
        "{}",
        choice.reason
    );
    // a small 3-D body keeps the condensed solver (and its limiting ratios)
    problem.body.n2 = 41;
    let (method, _) = problem.solver.resolved(&problem.body);
    assert_eq!(method, SolveMethod::Condensed);
    let named = Solver::new(SolveMethod::FullNewton(LinearBackend::LU));
    let (method, choice) = named.resolved(&problem.body);
    assert_eq!(method, SolveMethod::FullNewton(LinearBackend::LU));
    assert!(!choice.auto);
}

#[test]
fn auto_is_the_default_and_gives_the_condensed_numbers() {
    let grid = ["--set", "grid.n2=41", "--set", "grid.n3=9"];
    let auto = capstan_json(&[&["contact"], &grid[..]].concat());
    let newton = capstan_json(
        &[
            &["contact", "--set", "solver.nonlinear=\"newton\""],
            &grid[..],
        ]
        .concat(),
    );
    assert_eq!(auto["solver_choice"]["auto"], true);
    assert_eq!(auto["solver_choice"]["nonlinear"], "newton");
    assert_eq!(newton["solver_choice"]["auto"], false);
    for key in [
        "contact",
        "max_azimuthal_displacement",
        "limiting_ratios",
        "method",
    ] {
        assert_eq!(auto[key], newton[key], "{key}"); // the same solver: bitwise
    }
}

#[test]
fn default_contact_keeps_the_numbers_of_the_condensation_by_solves() {
    let r = capstan_json(&["contact"]);
    assert_eq!(r["newton_iterations"], 10);
    assert_eq!(r["method"], "condensed");
    // `capstan contact --json` before the Schur condensation; 1e-10: the two condensations
    // differ by round-off only (measured 6e-13)
    let pinned = [
        (
            &r["max_azimuthal_displacement"]["value"],
            0.003_587_235_611_083_435_4,
        ),
        (
            &r["max_radial_displacement"]["value"],
            -0.001_249_490_656_286_404,
        ),
        (&r["limiting_ratios"][0], 0.299_037_423_900_818_56),
        (&r["limiting_ratios"][1], 3.344_063_050_557_594),
        (&r["stick_interval"][0], -0.922_880_327_180_456_1),
        (&r["contact"]["shear_stress"][100], 0.434_842_226_554_070_4),
    ];
    for (value, expected) in pinned {
        let value = value.as_f64().unwrap();
        assert!(
            (value - expected).abs() <= 1e-10 * expected.abs(),
            "{value} vs {expected}"
        );
    }
}
