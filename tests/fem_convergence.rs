//! Convergence of the finite-element Navier operator (Q1, Q2): the manufactured solutions and
//! the Lamé cylinder of the finite-difference studies. Quick variants (three coarsest grids)
//! run in CI; the four-grid studies are `#[ignore]`d
//! (`cargo test --release --test fem_convergence -- --ignored`).

use capstan_elasticity::finite_element::ElementOrder;
use capstan_elasticity::samples::{LameCylinder, MmsBoundaries, PrismMms};
use capstan_elasticity::studies::{FemProblem, FemStudy};
use capstan_elasticity::verification::{Study, StudyReport};

fn run(problem: FemProblem, order: ElementOrder, quick: bool) -> StudyReport {
    FemStudy::new(problem, order).run(quick).unwrap()
}

/// Observed L2 order within `expected +- 0.15` and the finest L2 error bounded.
fn assert_order(report: &StudyReport, expected: f64, finest_l2: f64) {
    let table = report.table();
    println!("{table}");
    assert!((report.order_l2 - expected).abs() < 0.15, "{table}");
    let finest = report.points.last().expect("levels");
    assert!(finest.l2_error < finest_l2, "{table}");
}

/// Every problem with the bound on its finest L2 error over the three coarsest grids, for Q1
/// and for Q2 (about twice the observed error, quoted in the comment).
fn quick_bounds() -> [(&'static str, FemProblem, f64, f64); 5] {
    use MmsBoundaries::{BilateralContact, TractionContact};
    [
        // observed 5.3e-6 and 5.8e-8
        (
            "ellipse half",
            FemProblem::Mms(PrismMms::ellipse(0.5, TractionContact)),
            1.1e-5,
            1.2e-7,
        ),
        // observed 7.5e-6 and 8.6e-8
        (
            "ellipse two",
            FemProblem::Mms(PrismMms::ellipse(2.0, BilateralContact)),
            1.5e-5,
            1.8e-7,
        ),
        // observed 1.7e-5 and 1.1e-7
        (
            "prism traction",
            FemProblem::Mms(PrismMms::expression_prism(TractionContact)),
            3.4e-5,
            2.2e-7,
        ),
        // observed 6.8e-6 and 1.1e-7
        (
            "prism bilateral",
            FemProblem::Mms(PrismMms::expression_prism(BilateralContact)),
            1.4e-5,
            2.2e-7,
        ),
        // observed 1.2e-5 and 5.5e-7
        (
            "lame",
            FemProblem::Lame(LameCylinder::default()),
            2.4e-5,
            1.1e-6,
        ),
    ]
}

/// The quick study of every problem with `order`: Q1 second, Q2 third order, finest L2 error
/// within its [`quick_bounds`] entry.
fn assert_quick(order: ElementOrder) {
    for (name, problem, q1, q2) in quick_bounds() {
        let (expected, bound) = match order {
            ElementOrder::Q1 => (2.0, q1),
            ElementOrder::Q2 => (3.0, q2),
        };
        println!("{name}");
        assert_order(&run(problem, order, true), expected, bound);
    }
}

#[test]
fn q1_every_problem_is_second_order_quick() {
    assert_quick(ElementOrder::Q1);
}

#[test]
fn q2_every_problem_is_third_order_quick() {
    assert_quick(ElementOrder::Q2);
}

/// The four-grid studies of the registry: every problem, Q1 order 2 and Q2 order 3 in L2
/// over four refinements, finest L2 error a quarter (Q1) or an eighth (Q2) of the
/// three-grid bound.
#[test]
#[ignore = "four grids: run with --release -- --ignored"]
fn every_problem_four_grids_q1_second_q2_third_order() {
    for (_, problem, q1, q2) in quick_bounds() {
        assert_order(
            &run(problem.clone(), ElementOrder::Q1, false),
            2.0,
            q1 / 4.0,
        );
        assert_order(&run(problem, ElementOrder::Q2, false), 3.0, q2 / 8.0);
    }
}
