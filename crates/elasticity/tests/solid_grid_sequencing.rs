//! Grid sequencing of the 3-D matrix-free Newton (`SolidBody::solve_matrix_free_sequenced`):
//! the same answer as the unsequenced solve from the stuck start to the Newton tolerance,
//! with fewer Newton steps on the fine grid, for Q1 (geometric coarse grid) and Q2 (Q1 on the
//! element vertices); a typed error for a zero coarsest size.

use capstan_elasticity::contact::{
    ContactError, ContactSolution, EndLoads, MatrixFreeNewton, MatrixFreeSettings,
};
use capstan_elasticity::finite_element::ElementOrder;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{HexElement, SolidBody, SolidMultigridParams};
use capstan_elasticity::solvers::SilentObserver;
use capstan_geometry::EllipticalPrism;

const EPS: f64 = 1e-5;

fn coulomb() -> RegularisedCoulombParams<f64> {
    RegularisedCoulombParams::new(0.5, EPS).unwrap()
}

fn multigrid() -> SolidMultigridParams {
    SolidMultigridParams {
        coarsest_unknowns: 300,
        ..Default::default()
    }
}

fn settings() -> MatrixFreeSettings {
    let mut s = MatrixFreeSettings::default();
    s.continuation.tolerance = 1e-11;
    s
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

fn ellipse(nodes: [usize; 3], order: HexElement) -> SolidBody<EllipticalPrism<f64>> {
    let mut body = SolidBody::new(EllipticalPrism::new(2.0, 1.5).unwrap(), [-0.5, 0.5], nodes);
    body.order = order;
    body
}

#[test]
fn sequenced_newton_gives_the_unsequenced_answer_in_fewer_fine_steps() {
    let loads = EndLoads::ratio(1.5);
    // (element, fine grid, coarse grid, fine steps at most this fraction of the unsequenced)
    for (order, nodes, coarse, fraction) in [
        // Q1: 9 fine steps against 14 unsequenced since the matrix-free smoothers keep
        // MATRIX_FREE_ESTIMATE_MARGIN (within half before it; the inexact Newton's directions
        // follow the V-cycle, so the step counts moved with the smoothing interval)
        (
            HexElement::Uniform(ElementOrder::Q1),
            [9, 33, 9],
            [5, 17, 5],
            0.7,
        ),
        (
            HexElement::Uniform(ElementOrder::Q2),
            [9, 33, 9],
            [5, 17, 5],
            0.9,
        ),
    ] {
        let body = ellipse(nodes, order);
        assert_eq!(
            body.sequence_coarser().unwrap().map(|b| (b.nodes, b.order)),
            Some((coarse, HexElement::Uniform(ElementOrder::Q1)))
        );
        let model = body
            .matrix_free_model(RegularisedCoulomb, coulomb(), EPS, multigrid())
            .unwrap();
        let plain = MatrixFreeNewton::new(&model, settings())
            .unwrap()
            .solve(loads)
            .unwrap();
        let seq = body
            .solve_matrix_free_sequenced(
                RegularisedCoulomb,
                coulomb(),
                EPS,
                multigrid(),
                settings(),
                1_500,
                loads,
                &mut SilentObserver,
            )
            .unwrap();
        let d = relative_difference(&plain, &seq.solution);
        let fine = seq.levels.last().unwrap();
        println!(
            "{order:?} {nodes:?}: levels {:?}; unsequenced {} Newton steps, {} Krylov; difference {d:.2e}",
            seq.levels, plain.stats.newton_iterations, plain.stats.linear_iterations
        );
        assert_eq!(seq.levels.len(), 2, "{:?}", seq.levels);
        assert_eq!(seq.levels[0].0, coarse);
        assert_eq!(fine.0, nodes);
        assert_eq!(fine.1, seq.solution.stats.newton_iterations);
        // the same problem to its Newton tolerance (1e-11 relative residual)
        assert!(d < 1e-8, "{d:e}");
        assert!(
            model
                .relative_residual(loads, &seq.solution.displacement)
                .unwrap()
                < 1e-10
        );
        // the prolonged start saves fine-grid Newton steps and the fine stuck start
        assert!(
            fine.1 as f64 <= fraction * plain.stats.newton_iterations as f64,
            "fine steps {} against {}",
            fine.1,
            plain.stats.newton_iterations
        );
        assert!(
            3 * fine.2 <= 2 * plain.stats.linear_iterations,
            "fine Krylov {} against {}",
            fine.2,
            plain.stats.linear_iterations
        );
    }
}

#[test]
fn a_zero_coarsest_size_is_refused_naming_the_key() {
    let body = ellipse([5, 17, 5], HexElement::Uniform(ElementOrder::Q1));
    let r = body.solve_matrix_free_sequenced(
        RegularisedCoulomb,
        coulomb(),
        EPS,
        multigrid(),
        settings(),
        0,
        EndLoads::ratio(1.5),
        &mut SilentObserver,
    );
    match r {
        Err(e @ ContactError::Elasticity(_)) => {
            assert!(e.to_string().contains("solver.coarsest_unknowns"), "{e}")
        }
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("accepted"),
    }
}

#[test]
fn the_fine_grid_start_and_newton_work_stay_flat_under_refinement() {
    // the fine grid's start is the coarser solution prolonged (no stuck-start solve on it):
    // its Newton steps and Krylov iterations at 2.7e3 and 5.6e4 unknowns within 1.5x
    let loads = EndLoads::ratio(1.5);
    let fine: Vec<(usize, usize)> = [[9, 33, 9], [17, 65, 17]]
        .into_iter()
        .map(|nodes| {
            let body = ellipse(nodes, HexElement::Uniform(ElementOrder::Q1));
            let seq = body
                .solve_matrix_free_sequenced(
                    RegularisedCoulomb,
                    coulomb(),
                    EPS,
                    multigrid(),
                    settings(),
                    1_500,
                    loads,
                    &mut SilentObserver,
                )
                .unwrap();
            println!("{nodes:?}: levels {:?}", seq.levels);
            assert!(seq.levels.len() >= 2, "{:?}", seq.levels);
            let last = seq.levels.last().unwrap();
            (last.1, last.2)
        })
        .collect();
    let within = |a: usize, b: usize| 2 * a.max(b) <= 3 * a.min(b);
    assert!(within(fine[0].0, fine[1].0), "Newton steps {fine:?}");
    assert!(within(fine[0].1, fine[1].1), "Krylov iterations {fine:?}");
}

#[test]
fn a_coarse_level_of_more_than_a_quarter_of_the_unknowns_ends_the_sequence() {
    // 3 x 9 x 9: only x3 is halved (x1 cannot be, the x2 cells are the long ones), so the
    // V-cycle's coarse grid keeps more than half the unknowns and is not solved first
    let body = ellipse([3, 9, 9], HexElement::Uniform(ElementOrder::Q1));
    let coarse = body.sequence_coarser().unwrap().unwrap();
    assert_eq!(coarse.nodes, [3, 9, 5]);
    let loads = EndLoads::ratio(1.5);
    let seq = body
        .solve_matrix_free_sequenced(
            RegularisedCoulomb,
            coulomb(),
            EPS,
            multigrid(),
            settings(),
            100,
            loads,
            &mut SilentObserver,
        )
        .unwrap();
    assert_eq!(seq.levels.len(), 1, "{:?}", seq.levels);
    let model = body
        .matrix_free_model(RegularisedCoulomb, coulomb(), EPS, multigrid())
        .unwrap();
    let plain = MatrixFreeNewton::new(&model, settings())
        .unwrap()
        .solve(loads)
        .unwrap();
    // one level: the unsequenced solve itself
    assert_eq!(plain.displacement, seq.solution.displacement);
}
