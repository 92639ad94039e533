//! The error estimates of `capstan contact` (`estimated_error`, one grid level coarser) against
//! the true error, measured against a finer reference on the default scene family (the
//! paper's body on the circle at ratio 2, `fem-q2`).

use capstan::commands::contact::{ContactReport, solve_observed};
use capstan::scene::Scene;
use capstan_elasticity::solvers::SilentObserver;

fn report(n2: usize, n3: usize, estimate: bool) -> ContactReport {
    let mut scene = Scene::default();
    scene.grid.n2 = n2;
    scene.grid.n3 = n3;
    scene.discretisation.method = "fem-q2".parse().unwrap();
    scene.output.error_estimate = estimate;
    solve_observed(&scene, &mut SilentObserver).unwrap().0
}

fn values(r: &ContactReport) -> std::collections::BTreeMap<String, f64> {
    let q = r.quantities.as_ref().unwrap();
    let mut out = std::collections::BTreeMap::from([
        ("slip_measure".to_owned(), q.slip_measure),
        (
            "max_abs_v2".to_owned(),
            r.max_azimuthal_displacement.value.abs(),
        ),
        (
            "max_abs_v3".to_owned(),
            r.max_radial_displacement.value.abs(),
        ),
    ]);
    if let Some([from, to]) = r.stick_interval {
        out.insert("stick_from".to_owned(), from);
        out.insert("stick_to".to_owned(), to);
    }
    for (i, p) in q.normal_stress_probes.iter().enumerate() {
        out.insert(format!("normal_stress_probe_{i}"), p.value);
    }
    out
}

/// Every estimate of the reports on `grids` lies in `[0.5, 10]` times the true error against
/// the reference grid.
fn check(grids: &[(usize, usize)], reference: (usize, usize)) {
    let reference = values(&report(reference.0, reference.1, false));
    for &(n2, n3) in grids {
        let r = report(n2, n3, true);
        let estimate = r.estimated_error.as_ref().unwrap();
        assert_eq!(estimate.method, "one-level-coarser");
        for (name, value) in values(&r) {
            let e = estimate.quantities[&name].unwrap();
            let truth = (value - reference[&name]).abs();
            let ratio = e / truth;
            assert!(
                (0.5..=10.0).contains(&ratio),
                "{n2} x {n3}: {name} estimate {e:.3e}, true error {truth:.3e} (ratio {ratio:.2})"
            );
        }
    }
}

#[test]
fn estimates_bracket_the_true_error_of_q2_against_a_finer_grid() {
    // 241 x 41 (the default's level) against 481 x 81, whose own errors are ~10x smaller
    // (slip measure 1e-4, from 961 x 161): measured ratios 1.1 to 3.2 (slip measure 3.2 with
    // the cubic transition locator, 2.1 with the linear one).
    // Below it the estimate is pre-asymptotic: on 121 x 21 it overestimates the stick-zone
    // start 96x (the 61 x 11 level misplaces the 2-node stick zone).
    check(&[(241, 41)], (481, 81));
}

#[test]
#[ignore = "minutes: a 961 x 161 reference"]
fn estimates_bracket_the_true_error_of_q2_against_a_much_finer_grid() {
    check(&[(241, 41), (481, 81)], (961, 161));
}

#[test]
fn grid_sequencing_gives_the_estimate_its_coarser_level_without_a_second_solve() {
    // full-system Newton on 201 x 101 (20,301 nodes, over the 20,000 of one level): the
    // sequence solves 101 x 51 first, the grid of `Problem::coarser`
    let mut scene = Scene::default();
    scene.grid.n2 = 201;
    scene.grid.n3 = 101;
    scene.solver.nonlinear = "full-newton".into();
    let problem = scene.build().unwrap();
    let solved = problem.solve().unwrap();
    let level = solved
        .coarser
        .as_ref()
        .expect("a sequenced solve keeps its coarser level");
    let coarse = problem.coarser().unwrap().unwrap();
    assert_eq!(coarse.grid(), [101, 51]);
    assert_eq!(level.model.plane().unwrap().grid().n2(), 101);
    let probes = capstan::commands::accuracy::probes(&scene);
    let kept = level.scalars(&probes).unwrap();
    let again = coarse.solve().unwrap().scalars(&probes).unwrap();
    assert_eq!(
        kept.keys().collect::<Vec<_>>(),
        again.keys().collect::<Vec<_>>()
    );
    for (name, value) in &kept {
        // the same problem on the same grid: equal to the Newton tolerances
        let other = again[name];
        assert!(
            (value - other).abs() <= 1e-7 * other.abs().max(1e-3),
            "{name}: {value} against {other}"
        );
    }
    // and the report's estimate is the difference to it
    let report = solve_observed(&scene, &mut SilentObserver).unwrap().0;
    let estimate = report.estimated_error.unwrap();
    assert_eq!(estimate.coarser_grid, [101, 51]);
    let fine = solved.scalars(&probes).unwrap();
    for (name, e) in &estimate.quantities {
        let expected = (fine[name] - kept[name]).abs();
        assert!(
            (e.unwrap() - expected).abs() <= 1e-9 * fine[name].abs().max(1e-3),
            "{name}"
        );
    }
}
