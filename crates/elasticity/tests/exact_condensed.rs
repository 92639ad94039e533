//! Exact Coulomb friction on the condensed contact face
//! (`BoundarySolver::solve_exact_from_observed`): the same solution as the full-system
//! semismooth Newton, the `eps -> 0` limit of regularised Coulomb, the active set per
//! iteration, and the typed errors.

use capstan_elasticity::contact::{
    Body, BoundarySolver, CONDENSED_SEMISMOOTH, ContactError, ContactModel, ContactSettings,
    ContactSolution, EndLoads, FullSystemSettings, FullSystemSolver, Gap,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_friction::nonsmooth_law::bind_nonsmooth;
use capstan_friction::{
    ExactCoulomb, ExactCoulombParams, Frictionless, RegularisedCoulomb, RegularisedCoulombParams,
};
use capstan_geometry::{EllipticalPrism, Obstacle};
use capstan_solvers::{ActiveSet, Observer, Progress, SilentObserver};

fn body(a: f64, b: f64, n2: usize, n3: usize) -> Body {
    let obstacle = Obstacle::Ellipse(EllipticalPrism::new(a, b).unwrap());
    let mut body = Body::new(obstacle, n2, n3);
    body.method = DiscretisationMethod::Fd;
    body
}

fn solid(mut b: Body, n1: usize) -> Body {
    use capstan_elasticity::contact::Dimension;
    use capstan_elasticity::solid::SideFaces;
    b.method = DiscretisationMethod::FemQ1;
    b.dimension = Dimension::Solid {
        x1: [-0.5, 0.5],
        n1,
        sides: SideFaces::Free,
    };
    b
}

fn exact_law() -> std::sync::Arc<dyn capstan_friction::nonsmooth_law::DynNonsmoothLaw> {
    bind_nonsmooth(ExactCoulomb, ExactCoulombParams::new(0.5).unwrap())
}

fn regularised_model(
    b: &Body,
    eps: f64,
) -> ContactModel<capstan_elasticity::contact::BodyOperator, RegularisedCoulomb> {
    b.model(
        RegularisedCoulomb,
        RegularisedCoulombParams::new(0.5, eps).unwrap(),
        eps,
    )
    .unwrap()
}

/// The full-system semismooth Newton (from its own regularised start).
fn full_system(b: &Body, loads: EndLoads) -> ContactSolution {
    let model = b
        .model(Frictionless, (), 1e-5)
        .unwrap()
        .into_exact_friction(exact_law())
        .unwrap();
    FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap()
}

/// The condensed route: regularised Coulomb of width `eps` on the condensed solver, then
/// semismooth Newton on the contact face from its unknowns; `(exact, regularised)`.
fn condensed(
    b: &Body,
    eps: f64,
    loads: EndLoads,
    observer: &mut dyn Observer<f64>,
) -> (ContactSolution, ContactSolution) {
    let model = regularised_model(b, eps);
    let exact = model
        .with_params(*model.params())
        .into_exact_friction(exact_law())
        .unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let start = solver.solve(loads).unwrap();
    let x = solver
        .solve_exact_from_observed(&exact, loads, &start.unknowns, observer)
        .unwrap();
    (x, start)
}

/// `max |a - b| / max |b|` over the displacement.
fn relative_difference(a: &ContactSolution, b: &ContactSolution) -> f64 {
    let scale = b.displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a
        .displacement
        .iter()
        .zip(&b.displacement)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}

/// The condensed semismooth Newton gives the full-system semismooth Newton's solution to
/// 1e-10 (displacement, max-norm relative), with the same stick/slip states, on the paper's
/// circle (a rigid sliding mode, one sticking node) at two ratios, on an ellipse and on a
/// 3-D body (two-component slip, the friction disc); in a few dense steps.
#[test]
fn condensed_semismooth_newton_equals_the_full_system_one() {
    let cases = [
        ("circle 81 x 17, ratio 2", body(2.0, 2.0, 81, 17), 2.0),
        ("circle 81 x 17, ratio 1.5", body(2.0, 2.0, 81, 17), 1.5),
        (
            "ellipse 2 x 1.5, 61 x 13, ratio 1.8",
            body(2.0, 1.5, 61, 13),
            1.8,
        ),
        (
            "3-D Q1 3 x 21 x 5, ratio 1.5",
            solid(body(2.0, 2.0, 21, 5), 3),
            1.5,
        ),
    ];
    for (name, b, ratio) in cases {
        let loads = EndLoads::new(1.0, ratio);
        let full = full_system(&b, loads);
        let (x, start) = condensed(&b, 1e-5, loads, &mut SilentObserver);
        let d = relative_difference(&x, &full);
        let semismooth = x.stats.newton_iterations;
        println!(
            "{name}: |v_condensed - v_full| / |v| = {d:.2e}, semismooth steps {semismooth} (after {} regularised), full-system iterations {}, residuals {:.1e} / {:.1e}",
            start.stats.newton_iterations,
            full.stats.newton_iterations,
            x.stats.residual,
            full.stats.residual
        );
        assert_eq!(x.stats.method, CONDENSED_SEMISMOOTH);
        assert!(d < 1e-10, "{name}: {d:e}");
        assert!(x.stats.residual < 1e-9, "{name}: {:e}", x.stats.residual);
        // 0 at ratio 1.5: the converged regularised start moved to the balanced rigid
        // amplitude is already the exact solution to the tolerance
        assert!((0..=8).contains(&semismooth), "{name}: {semismooth}");
        assert_eq!(x.contact.state, full.contact.state, "{name}");
        assert_eq!(x.slip_fraction, full.slip_fraction, "{name}");
    }
}

/// The existing limit check on the condensed path: regularised Coulomb (condensed) converges
/// to the condensed exact solution at first order in `eps` (max `|v2|`, the paper's body),
/// whose stick set is the one neutral node.
#[test]
fn condensed_exact_coulomb_is_the_limit_of_regularised_coulomb() {
    let b = body(2.0, 2.0, 81, 17);
    let loads = EndLoads::new(1.0, 2.0);
    let (x, _) = condensed(&b, 1e-5, loads, &mut SilentObserver);
    let stick = x.stick_interval.unwrap();
    assert_eq!(stick.count, 1, "{stick:?}");
    let v2 = x.max_azimuthal_displacement.value;
    let errors: Vec<(f64, f64)> = [1e-5, 1e-6, 1e-7]
        .into_iter()
        .map(|eps| {
            let model = regularised_model(&b, eps);
            let s = BoundarySolver::new(&model, ContactSettings::default())
                .unwrap()
                .solve(loads)
                .unwrap();
            (eps, (s.max_azimuthal_displacement.value - v2).abs())
        })
        .collect();
    let p = capstan_elasticity::verification::observed_order(&errors);
    println!("max |v2| errors {errors:?}, order {p:.4}");
    // full-system path: 1.9802e-6, 1.9802e-7, 1.9802e-8 (order 1.000)
    assert!((p - 1.0).abs() < 0.02, "{p}: {errors:?}");
    assert!(errors[2].1 < 1e-5 * v2.abs(), "{errors:?}");
}

/// Every condensed semismooth iterate reports its active set; the last one sticks at one
/// site and slides at the other 40.
#[test]
fn condensed_semismooth_newton_reports_its_active_set_per_iteration() {
    struct Sets(Vec<ActiveSet>);
    impl Observer<f64> for Sets {
        fn iteration(&mut self, p: &Progress<f64>) {
            if let Some(set) = p.active {
                self.0.push(set);
            }
        }
    }
    let b = body(2.0, 2.0, 41, 9);
    let mut sets = Sets(Vec::new());
    let (x, _) = condensed(&b, 1e-5, EndLoads::new(1.0, 2.0), &mut sets);
    assert!(sets.0.len() >= x.stats.newton_iterations, "{:?}", sets.0);
    let last = sets.0.last().unwrap();
    assert_eq!((last.stick, last.slip), (1, 40), "{last:?}");
}

/// Typed errors: a model without exact friction (`friction.law`), a unilateral one
/// (`contact.kind`), another body, a start of the wrong length, and the budget.
#[test]
fn condensed_semismooth_newton_refuses_what_it_cannot_solve() {
    let b = body(2.0, 2.0, 41, 9);
    let loads = EndLoads::new(1.0, 2.0);
    let model = regularised_model(&b, 1e-5);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let start = solver.solve(loads).unwrap().unknowns;
    let unsupported = |e: ContactError| match e {
        ContactError::Unsupported { field, .. } => field,
        other => panic!("{other:?}"),
    };
    let e = solver
        .solve_exact_from_observed(&model, loads, &start, &mut SilentObserver)
        .unwrap_err();
    assert_eq!(unsupported(e), "friction.law");
    let unilateral = model
        .with_params(*model.params())
        .into_unilateral(&Gap::zero())
        .unwrap()
        .into_exact_friction(exact_law())
        .unwrap();
    let e = solver
        .solve_exact_from_observed(&unilateral, loads, &start, &mut SilentObserver)
        .unwrap_err();
    assert_eq!(unsupported(e), "contact.kind");
    let other = regularised_model(&body(2.0, 2.0, 41, 11), 1e-5)
        .into_exact_friction(exact_law())
        .unwrap();
    let e = solver
        .solve_exact_from_observed(&other, loads, &start, &mut SilentObserver)
        .unwrap_err();
    assert!(matches!(e, ContactError::DifferentBody { .. }), "{e:?}");
    let exact = model
        .with_params(*model.params())
        .into_exact_friction(exact_law())
        .unwrap();
    let e = solver
        .solve_exact_from_observed(&exact, loads, &start[1..], &mut SilentObserver)
        .unwrap_err();
    assert!(e.to_string().contains("contact unknowns"), "{e}");
    // one semismooth step from the stuck state is not enough: the budget's typed error
    let tight = BoundarySolver::new(
        &model,
        ContactSettings {
            max_iterations: 1,
            ..ContactSettings::default()
        },
    )
    .unwrap();
    let stuck = tight.stuck_unknowns(loads);
    match tight.solve_exact_from_observed(&exact, loads, &stuck, &mut SilentObserver) {
        Err(ContactError::NotConverged {
            iterations,
            residual,
            ..
        }) => assert!(
            iterations <= 1 && residual > 1e-10,
            "{iterations} {residual}"
        ),
        other => panic!("{other:?}"),
    }
}

/// The copy-free route (`ContactModel::exact_rows`, `BoundarySolver::solve_exact_rows_observed`,
/// `ContactModel::with_exact_rows`, `ExactFaceSolution::into_solution`: what `Problem` runs)
/// gives the copied exact model's solution bit for bit (displacement, stick/slip, residual,
/// iterations), on the circle and on a 3-D body; rows of another body and a model without
/// the rows are refused with typed errors.
#[test]
fn condensed_semismooth_newton_without_the_model_copy_is_the_same() {
    let cases = [
        ("circle 81 x 17, ratio 2", body(2.0, 2.0, 81, 17), 2.0),
        (
            "3-D Q1 3 x 21 x 5, ratio 1.5",
            solid(body(2.0, 2.0, 21, 5), 3),
            1.5,
        ),
    ];
    for (name, b, ratio) in cases {
        let loads = EndLoads::new(1.0, ratio);
        let (copied, start) = condensed(&b, 1e-5, loads, &mut SilentObserver);
        let model = regularised_model(&b, 1e-5);
        let rows = model.exact_rows(exact_law()).unwrap();
        let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let face = solver
            .solve_exact_rows_observed(&rows, loads, &start.unknowns, &mut SilentObserver)
            .unwrap();
        assert_eq!(face.iterations(), copied.stats.newton_iterations, "{name}");
        // the rows of another body are refused, by the solver and by the model
        let other = regularised_model(&body(2.0, 2.0, 41, 11), 1e-5);
        let other_rows = other.exact_rows(exact_law()).unwrap();
        let e = solver
            .solve_exact_rows_observed(&other_rows, loads, &start.unknowns, &mut SilentObserver)
            .unwrap_err();
        assert!(matches!(e, ContactError::DifferentBody { .. }), "{e:?}");
        drop(solver);
        let e = face.clone().into_solution(&model).unwrap_err();
        assert!(
            matches!(
                e,
                ContactError::Unsupported {
                    field: "friction.law",
                    ..
                }
            ),
            "{e:?}"
        );
        let e = other.with_exact_rows(rows.clone()).unwrap_err();
        assert!(matches!(e, ContactError::DifferentBody { .. }), "{e:?}");
        let exact = model.with_exact_rows(rows).unwrap();
        let x = face.into_solution(&exact).unwrap();
        assert_eq!(x.displacement, copied.displacement, "{name}");
        assert_eq!(x.unknowns, copied.unknowns, "{name}");
        assert_eq!(x.contact.state, copied.contact.state, "{name}");
        assert_eq!(x.stats.residual, copied.stats.residual, "{name}");
        assert_eq!(x.stats.method, CONDENSED_SEMISMOOTH, "{name}");
    }
}

/// The loose regularised start (`BoundarySolver::solve_exact_rows_started_observed`: the
/// regularised plain Newton stopped at `EXACT_START_TOLERANCE`, no field solve, then the
/// semismooth Newton) gives the solution of the converged start (the route before) to the
/// semismooth tolerance, with fewer regularised iterations and no more semismooth ones, on
/// the circle and on a 3-D body.
#[test]
fn condensed_semismooth_newton_from_the_loose_start_is_the_same() {
    let cases = [
        ("circle 81 x 17, ratio 2", body(2.0, 2.0, 81, 17), 2.0),
        (
            "ellipse 2 x 1.5, 61 x 13, ratio 1.8",
            body(2.0, 1.5, 61, 13),
            1.8,
        ),
        (
            "3-D Q1 3 x 21 x 5, ratio 1.5",
            solid(body(2.0, 2.0, 21, 5), 3),
            1.5,
        ),
    ];
    for (name, b, ratio) in cases {
        let loads = EndLoads::new(1.0, ratio);
        let (converged, start) = condensed(&b, 1e-5, loads, &mut SilentObserver);
        let model = regularised_model(&b, 1e-5);
        let rows = model.exact_rows(exact_law()).unwrap();
        let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let started = solver
            .solve_exact_rows_started_observed(&rows, loads, &mut SilentObserver)
            .unwrap();
        drop(solver);
        let (regularised, semismooth) = (started.start_iterations, started.face.iterations());
        let exact = model.with_exact_rows(rows).unwrap();
        let x = started.face.into_solution(&exact).unwrap();
        let difference = relative_difference(&x, &converged);
        println!(
            "{name}: start {regularised} (converged {}) + semismooth {semismooth} (from converged {}), difference {difference:.2e}",
            start.stats.newton_iterations, converged.stats.newton_iterations
        );
        assert!(difference < 1e-9, "{name}: {difference:e}");
        assert_eq!(x.contact.state, converged.contact.state, "{name}");
        assert!(x.stats.residual < 1e-9, "{name}: {}", x.stats.residual);
        assert!(
            regularised < start.stats.newton_iterations,
            "{name}: {regularised} against {}",
            start.stats.newton_iterations
        );
        assert!(
            semismooth <= converged.stats.newton_iterations,
            "{name}: {semismooth} against {}",
            converged.stats.newton_iterations
        );
    }
}

/// With a rigid sliding mode (the circle) the semismooth Newton starts at the balanced rigid
/// amplitude, where the neutral site sticks, so no step is backtracked (before, the first
/// step from the all-slip start slid the body and was cut to `alpha = 2^-9` on the default
/// scene); the answer is the full-system one to 1e-10 with the same stick/slip, also from the
/// loose start. Without a rigid mode (the ellipse) nothing moves and the steps are full too.
#[test]
fn condensed_semismooth_newton_starts_at_the_balanced_amplitude() {
    let cases = [
        ("circle 81 x 17, ratio 2", body(2.0, 2.0, 81, 17), 2.0),
        ("circle 81 x 17, ratio 1.5", body(2.0, 2.0, 81, 17), 1.5),
        (
            "ellipse 2 x 1.5, 61 x 13, ratio 1.8",
            body(2.0, 1.5, 61, 13),
            1.8,
        ),
    ];
    for (name, b, ratio) in cases {
        let loads = EndLoads::new(1.0, ratio);
        let full = full_system(&b, loads);
        let model = regularised_model(&b, 1e-5);
        let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
        let start = solver.solve(loads).unwrap();
        let rigid = solver.sliding().is_some();
        for loose in [false, true] {
            // (iteration, step length, stick sites) of every semismooth iterate
            let mut steps: Vec<(usize, f64, usize)> = Vec::new();
            let mut record = |p: &Progress<f64>| {
                if let Some(set) = p.active {
                    steps.push((p.iteration, p.step_length, set.stick));
                }
            };
            let rows = model.exact_rows(exact_law()).unwrap();
            let face = if loose {
                let started = solver
                    .solve_exact_rows_started_observed(&rows, loads, &mut record)
                    .unwrap();
                // the regularised iterates come first: keep the semismooth ones
                let k = steps.iter().rposition(|s| s.0 == 0).unwrap();
                steps.drain(..k);
                started.face
            } else {
                solver
                    .solve_exact_rows_observed(&rows, loads, &start.unknowns, &mut record)
                    .unwrap()
            };
            let exact = model
                .with_params(*model.params())
                .with_exact_rows(rows)
                .unwrap();
            let x = face.into_solution(&exact).unwrap();
            let d = relative_difference(&x, &full);
            println!(
                "{name} (rigid mode {rigid}, loose start {loose}): (iteration, step, stick) {steps:?}, difference {d:.2e}"
            );
            assert!(d < 1e-10, "{name}: {d:e}");
            assert_eq!(x.contact.state, full.contact.state, "{name}");
            // the start (iteration 0) already has a sticking site, and no step is cut
            assert!(steps[0].2 >= 1, "{name}: {steps:?}");
            assert!(
                steps.iter().skip(1).all(|s| s.1 == 1.0),
                "{name}: {steps:?}"
            );
            assert!(steps.len() <= 3, "{name}: {steps:?}");
        }
    }
}
