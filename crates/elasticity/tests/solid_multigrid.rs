//! The iterative bulk solver of the 3-D body: CG with the box multigrid on the SPD elasticity
//! matrix converges in a number of iterations bounded under refinement, the full-system
//! Newton with GMRES and multigrid reproduces the direct solution, and a spent Krylov budget
//! is a typed error naming its key.

use capstan_elasticity::ElasticityError;
use capstan_elasticity::contact::{ContactError, EndLoads, FullSystemSettings, FullSystemSolver};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{FaceComponent, FaceCondition, SolidBody, SolidNavier};
use capstan_elasticity::solvers::{
    CsrMatrix, KRYLOV_BUDGET_FIELD, KrylovMethod, KrylovParams, LinearBackend, Multigrid,
    MultigridParams, SilentObserver, Smoother, SolverError, krylov_solve,
};
use capstan_geometry::{EllipticalPrism, ShellChart};

const EPS: f64 = 1e-5;

fn ellipse_body(nodes: [usize; 3]) -> SolidBody<EllipticalPrism<f64>> {
    SolidBody::new(EllipticalPrism::new(2.0, 1.5).unwrap(), [-0.5, 0.5], nodes)
}

/// The finite-width body on the ellipse with the contact face clamped (`v = 0` on `x3 = 0`):
/// the rigid motions are held and the matrix is symmetric positive definite.
fn clamped(nodes: [usize; 3]) -> SolidNavier<ShellChart<EllipticalPrism<f64>>> {
    let body = ellipse_body(nodes);
    let mut boundary = body.boundary(1.0, 1.5);
    boundary.faces[4] = FaceCondition([
        FaceComponent::fixed(),
        FaceComponent::fixed(),
        FaceComponent::fixed(),
    ]);
    SolidNavier::new(
        ShellChart::new(body.surface),
        body.material,
        body.grid().unwrap(),
        &boundary,
        None,
        body.order,
        body.volumetric,
    )
    .unwrap()
}

/// CG iterations to `1e-10` with the V-cycle (`smoother`) on the clamped body.
fn cg_iterations(nodes: [usize; 3], smoother: Smoother) -> usize {
    let op = clamped(nodes);
    let system = op.system();
    let a = CsrMatrix::from_pattern(&system.pattern, &system.values).unwrap();
    let hierarchy = op.multigrid_hierarchy(100);
    assert!(hierarchy.counts.len() >= 3, "{:?}", hierarchy.counts);
    let params = MultigridParams {
        smoother,
        ..Default::default()
    };
    let mut mg = Multigrid::new(hierarchy.prolongations, params).unwrap();
    mg.setup(&a).unwrap();
    let mut x = vec![0.0; a.nrows()];
    let kp = KrylovParams {
        method: KrylovMethod::Cg,
        tolerance: 1e-10,
        max_iterations: 200,
        ..Default::default()
    };
    let report = krylov_solve(
        &a,
        &system.rhs,
        &mut x,
        &mut mg.with(&a),
        &kp,
        &mut SilentObserver,
    )
    .unwrap();
    // the true residual
    let mut r = vec![0.0; x.len()];
    a.residual(&x, &system.rhs, &mut r);
    let rn = r.iter().map(|v| v * v).sum::<f64>().sqrt();
    let bn = system.rhs.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(rn <= 1e-10 * bn, "{nodes:?}: {:e}", rn / bn);
    report.iterations
}

#[test]
fn multigrid_cg_iterations_stay_bounded_under_refinement() {
    for smoother in [Smoother::default(), Smoother::Jacobi { omega: 0.6 }] {
        // cells of about equal size (width 1, arc about 5.5, thickness 1): 4 x 16 x 4 .. 16 x 64 x 16
        let counts: Vec<usize> = [[5, 17, 5], [9, 33, 9], [17, 65, 17]]
            .into_iter()
            .map(|n| cg_iterations(n, smoother))
            .collect();
        // the multigrid property: 8x the unknowns per refinement, iterations grow by < 2x
        // over the three grids (unpreconditioned CG roughly doubles per refinement)
        assert!(counts[2] < 2 * counts[0], "{smoother:?}: {counts:?}");
        assert!(counts.iter().all(|&c| c <= 40), "{smoother:?}: {counts:?}");
    }
}

/// The full-system settings with the `multigrid` backend of `krylov`, `multigrid` settings,
/// or the default sparse LU (`None`).
fn settings(multigrid: Option<(KrylovParams, MultigridParams)>) -> FullSystemSettings {
    let mut s = FullSystemSettings::default();
    if let Some((krylov, multigrid)) = multigrid {
        s.newton.linear = LinearBackend::MULTIGRID;
        s.newton.krylov = krylov;
        s.newton.multigrid = multigrid;
    }
    s
}

fn default_multigrid() -> Option<(KrylovParams, MultigridParams)> {
    Some(Default::default())
}

#[test]
fn iterative_contact_solution_equals_the_direct_one() {
    // 8019 unknowns, two levels with the default coarsest size (this grid stalled GMRES with
    // a restart after 40 vectors)
    let body = ellipse_body([9, 33, 9]);
    let law = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, law, EPS).unwrap();
    let loads = EndLoads::ratio(1.5);
    let direct = FullSystemSolver::new(&model, settings(None))
        .unwrap()
        .solve(loads)
        .unwrap();
    let iterative = FullSystemSolver::new(&model, settings(default_multigrid()))
        .unwrap()
        .solve(loads)
        .unwrap();
    assert!(iterative.stats.linear_iterations > iterative.stats.newton_iterations);
    let scale = direct
        .displacement
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = direct
        .displacement
        .iter()
        .zip(&iterative.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff <= 1e-8 * scale, "{:e}", diff / scale);
    assert!(
        model
            .relative_residual(loads, &iterative.displacement)
            .unwrap()
            < 1e-9
    );
}

#[test]
fn a_spent_krylov_budget_is_a_typed_error_naming_the_key() {
    let body = ellipse_body([5, 33, 5]);
    let law = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, law, EPS).unwrap();
    let mg = (
        KrylovParams {
            max_iterations: 1,
            tolerance: 1e-12,
            ..Default::default()
        },
        MultigridParams {
            coarsest_unknowns: 200,
            ..Default::default()
        },
    );
    let err = FullSystemSolver::new(&model, settings(Some(mg)))
        .unwrap()
        .solve(EndLoads::ratio(1.5))
        .unwrap_err();
    match &err {
        ContactError::Solver(SolverError::BudgetSpent {
            field, iterations, ..
        }) => {
            assert_eq!(*field, KRYLOV_BUDGET_FIELD);
            assert_eq!(*iterations, 1);
        }
        other => panic!("{other:?}"),
    }
    assert!(err.to_string().contains("krylov.max_iterations"));
}

#[test]
fn multigrid_is_refused_without_a_hierarchy() {
    use capstan_elasticity::contact::ThickBody;
    let body = ThickBody::paper(21, 6).unwrap(); // plane strain: no box hierarchy
    let law = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, law, EPS).unwrap();
    match FullSystemSolver::new(&model, settings(default_multigrid())) {
        Err(ContactError::Elasticity(ElasticityError::InvalidParameter { field, .. })) => {
            assert_eq!(field, "solver.linear")
        }
        other => panic!("{other:?}"),
    }
}
