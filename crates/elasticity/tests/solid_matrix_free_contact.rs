//! The matrix-free full-system Newton of the 3-D body (inexact Newton–Krylov on the matrix-free
//! bulk plus the face's friction Jacobian, V-cycle on the matrix-free levels): the same answer
//! as the assembled full-system Newton with sparse LU, on the finite-width ellipse and on
//! circular and elliptical cones, Q1 and Q2; refusals are typed and name the key.

use capstan_elasticity::contact::{
    ContactError, ContactSolution, EndLoads, FullSystemSettings, FullSystemSolver,
    MatrixFreeNewton, MatrixFreeSettings,
};
use capstan_elasticity::finite_element::ElementOrder;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{HexElement, SolidBody, SolidMultigridParams};
use capstan_geometry::{EllipticalPrism, ExpressionProfile, GeneralCone, Obstacle, Surface};

const EPS: f64 = 1e-5;

fn coulomb(mu: f64) -> RegularisedCoulombParams<f64> {
    RegularisedCoulombParams::new(mu, EPS).unwrap()
}

fn multigrid() -> SolidMultigridParams {
    SolidMultigridParams {
        coarsest_unknowns: 300,
        ..Default::default()
    }
}

/// `max |a - b| / max |a|` over the displacements.
fn relative_difference(a: &ContactSolution, b: &ContactSolution) -> f64 {
    let scale = a.displacement.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = a
        .displacement
        .iter()
        .zip(&b.displacement)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}

/// Both solves of `body` at `ratio`: (assembled LU, matrix-free).
fn both<S: Surface<f64> + Clone + Send + Sync + 'static>(
    body: &SolidBody<S>,
    ratio: f64,
) -> (ContactSolution, ContactSolution) {
    let loads = EndLoads::ratio(ratio);
    let assembled = body.model(RegularisedCoulomb, coulomb(0.5), EPS).unwrap();
    // both to 1e-12 relative residual: the comparison measures the linear algebra, not
    // where each stopped
    let mut settings = FullSystemSettings::default();
    settings.continuation.tolerance = 1e-12;
    let direct = FullSystemSolver::new(&assembled, settings)
        .unwrap()
        .solve(loads)
        .unwrap();
    let model = body
        .matrix_free_model(RegularisedCoulomb, coulomb(0.5), EPS, multigrid())
        .unwrap();
    assert!(model.is_matrix_free());
    let mut mf_settings = MatrixFreeSettings::default();
    mf_settings.continuation.tolerance = 1e-12;
    let mf = MatrixFreeNewton::new(&model, mf_settings)
        .unwrap()
        .solve(loads)
        .unwrap();
    (direct, mf)
}

#[test]
fn matrix_free_newton_equals_the_assembled_one_on_the_finite_width_ellipse() {
    for (order, nodes) in [
        (HexElement::Uniform(ElementOrder::Q1), [5, 33, 9]),
        (HexElement::Uniform(ElementOrder::Q2), [5, 33, 9]),
    ] {
        let mut body = SolidBody::new(EllipticalPrism::new(2.0, 1.5).unwrap(), [-0.5, 0.5], nodes);
        body.order = order;
        let (direct, mf) = both(&body, 1.5);
        let d = relative_difference(&direct, &mf);
        println!(
            "{order:?} {nodes:?}: {} Newton steps, {} Krylov iterations, difference {d:.2e}",
            mf.stats.newton_iterations, mf.stats.linear_iterations
        );
        assert!(d <= 1e-8, "{order:?}: {d:e}");
        assert!(mf.stats.residual < 1e-9, "{}", mf.stats.residual);
        assert!(mf.stats.linear_iterations > mf.stats.newton_iterations);
        // the same stick/slip split
        assert_eq!(direct.contact.state, mf.contact.state);
    }
}

#[test]
fn matrix_free_newton_equals_the_assembled_one_on_cones() {
    // circular (a rigid rotation about the axis) and elliptical (g_12 != 0) cones
    for (a, b) in [(0.25, 0.25), (0.3, 0.2)] {
        let profile =
            ExpressionProfile::parse(&format!("{a} * sin(t)"), &format!("{b} * cos(t)")).unwrap();
        let body = SolidBody {
            thickness: 0.1,
            ..SolidBody::new(
                Obstacle::Cone(GeneralCone::new(profile)),
                [1.0, 1.4],
                [5, 33, 5],
            )
        };
        let (direct, mf) = both(&body, 1.3);
        let d = relative_difference(&direct, &mf);
        println!(
            "cone a = {a}, b = {b}: {} Newton steps, {} Krylov iterations, difference {d:.2e}",
            mf.stats.newton_iterations, mf.stats.linear_iterations
        );
        assert!(d <= 1e-8, "a = {a}, b = {b}: {d:e}");
    }
}

#[test]
fn matrix_free_models_are_refused_by_the_assembled_solvers_and_vice_versa() {
    let body = SolidBody::new(
        EllipticalPrism::new(2.0, 1.5).unwrap(),
        [-0.5, 0.5],
        [3, 9, 3],
    );
    let model = body
        .matrix_free_model(RegularisedCoulomb, coulomb(0.5), EPS, multigrid())
        .unwrap();
    match FullSystemSolver::new(&model, FullSystemSettings::default()) {
        Err(ContactError::Unsupported { field, .. }) => assert_eq!(field, "solver.linear"),
        other => panic!("{other:?}"),
    }
    let assembled = body.model(RegularisedCoulomb, coulomb(0.5), EPS).unwrap();
    match MatrixFreeNewton::new(&assembled, MatrixFreeSettings::default()) {
        Err(ContactError::Unsupported { field, .. }) => assert_eq!(field, "solver.linear"),
        other => panic!("{other:?}"),
    }
    // a spent Krylov total is a typed error naming the budget
    let tight = MatrixFreeSettings {
        max_linear_iterations: 3,
        ..Default::default()
    };
    let err = MatrixFreeNewton::new(&model, tight)
        .unwrap()
        .solve(EndLoads::ratio(1.5))
        .unwrap_err();
    assert!(err.to_string().contains("solver.max_sweeps"), "{err}");
}
