//! Refinement toward the stick/slip transitions (issue 28): on the default scene's body
//! (`fem-qp-corner`, order `p = 2 ... 5` on `12 x 2` cells), the slip measure's error against
//! the contact work-precision reference (docs/work-precision.md: `3.1123305`, graded `fem-qp`
//! p 6 on 1441 x 85 nodes, itself good to `1.7e-5`) stagnates without the transition grading
//! (measured `3.8e-3, 3.0e-3, 3.0e-3, 2.2e-3` relative to the face length `pi`) and falls
//! geometrically in `p` with the second pass graded toward the first pass's transitions
//! (`1.8e-3, 1.2e-3, 6.3e-4, 3.7e-4`: a factor `1.7` per order).

use capstan::Scene;
use capstan::elasticity::contact::default_probes;
use capstan::elasticity::finite_element::DiscretisationMethod;
use capstan::problem::{DEFAULT_TRANSITION_GRADING, Problem, Solved};

const SLIP_REF: f64 = 3.1123305;

fn slip_error(s: &Solved) -> f64 {
    let probes = default_probes([-core::f64::consts::FRAC_PI_2, core::f64::consts::FRAC_PI_2]);
    let slip = s.quantities(&probes).unwrap().slip_measure;
    (slip - SLIP_REF).abs() / core::f64::consts::PI
}

/// The geometric factor per order of a least-squares fit `log e = a - p log q`.
fn factor_per_order(e: &[f64]) -> f64 {
    let n = e.len() as f64;
    let xs: Vec<f64> = (0..e.len()).map(|i| i as f64).collect();
    let ys: Vec<f64> = e.iter().map(|x| x.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    (-sxy / sxx).exp()
}

#[test]
fn grading_toward_the_transitions_makes_the_slip_measure_converge_in_p() {
    let base: Problem = Scene::default().build().unwrap();
    let (layers, ratio) = DEFAULT_TRANSITION_GRADING;
    let (mut plain, mut graded) = (vec![], vec![]);
    for p in 2..=5 {
        let mut q = base.clone().with_grid(12 * p + 1, 2 * p + 1);
        q.body.method = DiscretisationMethod::FemQpCorner;
        q.body.settings.order = p;
        let two = q.solve_transition_graded(layers, ratio).unwrap();
        // one stick zone: two transitions, on the face
        assert_eq!(two.transitions.len(), 2, "{:?}", two.transitions);
        assert!(two.transitions.iter().all(|t| t.abs() < 1.5));
        plain.push(slip_error(&two.first));
        graded.push(slip_error(&two.second));
    }
    let (fp, fg) = (factor_per_order(&plain), factor_per_order(&graded));
    // measured: 1.17 without, 1.69 with the grading
    assert!(fp < 1.3, "plain {plain:?}: factor {fp}");
    assert!(fg > 1.5, "graded {graded:?}: factor {fg}");
    assert!(graded[3] < 0.25 * plain[3], "{plain:?} {graded:?}");
    assert!(graded.iter().zip(&plain).all(|(g, p)| g < p));
}

#[test]
fn a_cheap_first_pass_places_the_grading_of_a_finer_second() {
    // the bench's `fem-qp-transition` series: a first pass of order 2 on 12 x 2 cells, the
    // second of order 3 on 24 x 8 cells graded toward its transitions. Measured 1.43e-4 of
    // `pi` against 7.1e-4 for the same 24 x 8 mesh ungraded (and 1.2e-3 for the 12 x 2
    // two-pass of order 3 above)
    let base: Problem = Scene::default().build().unwrap();
    let corner = |p: usize, cells: [usize; 2]| {
        let mut q = base.clone().with_grid(cells[0] * p + 1, cells[1] * p + 1);
        q.body.method = DiscretisationMethod::FemQpCorner;
        q.body.settings.order = p;
        q
    };
    let (layers, ratio) = DEFAULT_TRANSITION_GRADING;
    let fine = corner(3, [24, 8]);
    let two = fine
        .solve_graded_after(&corner(2, [12, 2]), layers, ratio)
        .unwrap();
    assert_eq!(two.transitions.len(), 2, "{:?}", two.transitions);
    let graded = slip_error(&two.second);
    let plain = slip_error(&fine.solve().unwrap());
    assert!(graded < 2e-4, "graded {graded:e}");
    assert!(graded < 0.3 * plain, "graded {graded:e}, plain {plain:e}");
}

#[test]
fn grading_toward_points_is_refused_off_the_corner_mesh_naming_the_key() {
    let base: Problem = Scene::default().build().unwrap();
    let e = base.graded_toward(vec![0.1], 4, 0.3).unwrap_err();
    assert!(e.to_string().contains("discretisation.method"), "{e}");
    let mut q = base.with_grid(25, 5);
    q.body.method = DiscretisationMethod::FemQpCorner;
    q.body.settings.order = 2;
    let e = q.graded_toward(vec![0.1], 17, 0.3).unwrap_err();
    assert!(e.to_string().contains("transition_layers"), "{e}");
}
