//! Exact Coulomb friction on the thick body (semismooth Newton on the Alart–Curnier rows):
//! the limit of regularised Coulomb as `eps -> 0`, in plane strain and in 3-D.

use capstan_elasticity::contact::{
    Body, ContactSolution, EndLoads, FullSystemSettings, FullSystemSolver,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_friction::nonsmooth_law::bind_nonsmooth;
use capstan_friction::{
    ExactCoulomb, ExactCoulombParams, Frictionless, RegularisedCoulomb, RegularisedCoulombParams,
};
use capstan_geometry::{EllipticalPrism, Obstacle};

fn paper_body(n2: usize, n3: usize) -> Body {
    let circle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 2.0).unwrap());
    let mut b = Body::new(circle, n2, n3);
    b.method = DiscretisationMethod::Fd;
    b
}

fn regularised(b: &Body, eps: f64, loads: EndLoads) -> ContactSolution {
    let params = RegularisedCoulombParams::new(0.5, eps).unwrap();
    let model = b.model(RegularisedCoulomb, params, eps).unwrap();
    FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve(loads)
        .unwrap()
}

fn exact(b: &Body, loads: EndLoads) -> ContactSolution {
    exact_observed(b, loads, &mut capstan_solvers::SilentObserver)
}

fn exact_observed(
    b: &Body,
    loads: EndLoads,
    observer: &mut dyn capstan_solvers::Observer<f64>,
) -> ContactSolution {
    let law = bind_nonsmooth(ExactCoulomb, ExactCoulombParams::new(0.5).unwrap());
    let model = b
        .model(Frictionless, (), 1e-5)
        .unwrap()
        .into_exact_friction(law)
        .unwrap();
    FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve_observed(loads, observer)
        .unwrap()
}

/// Regularised Coulomb converges to exact Coulomb as `eps -> 0` on the paper's body (circle
/// `r = 2`, `h = 1`, `mu = 1/2`, FD 81 x 17, ratio 2), at first order in `eps`: max `|v2|`,
/// and the stick zone, which shrinks onto the one sticking node of the exact solution (the
/// neutral point, where the slip changes direction); the Slip measure is already the exact
/// one at these `eps`.
#[test]
fn regularised_coulomb_converges_to_exact_coulomb_at_first_order_in_eps() {
    let b = paper_body(81, 17);
    let loads = EndLoads::new(1.0, 2.0);
    let x = exact(&b, loads);
    assert!(x.stats.residual < 1e-9, "{:e}", x.stats.residual);
    let stick = x.stick_interval.unwrap();
    assert_eq!(stick.count, 1, "{stick:?}");
    assert_eq!(stick.from, stick.to);
    let v2 = x.max_azimuthal_displacement.value;
    let eps = [1e-5, 1e-6, 1e-7];
    let runs: Vec<ContactSolution> = eps.iter().map(|&e| regularised(&b, e, loads)).collect();
    let table: String = eps
        .iter()
        .zip(&runs)
        .map(|(e, s)| {
            let st = s.stick_interval.unwrap();
            format!(
                "eps {e:e}: v2 {:.10e} (exact {v2:.10e}) stick [{:.6}, {:.6}] (exact {:.6}) slip {}\n",
                s.max_azimuthal_displacement.value, st.from, st.to, stick.from, s.slip_fraction
            )
        })
        .collect();
    let errors = |f: &dyn Fn(&ContactSolution) -> f64| -> Vec<(f64, f64)> {
        eps.iter().zip(&runs).map(|(&e, s)| (e, f(s))).collect()
    };
    let order = capstan_elasticity::verification::observed_order;
    let v2_errors = errors(&|s| (s.max_azimuthal_displacement.value - v2).abs());
    let end_errors = errors(&|s| {
        let st = s.stick_interval.unwrap();
        (st.from - stick.from).abs().max((st.to - stick.to).abs())
    });
    let (p_v2, p_end) = (order(&v2_errors), order(&end_errors));
    assert!((p_v2 - 1.0).abs() < 0.05, "{p_v2}\n{table}");
    assert!((p_end - 1.0).abs() < 0.05, "{p_end}\n{table}");
    assert!(v2_errors[2].1 < 1e-5 * v2.abs(), "{table}"); // 5.5e-6 relative at eps = 1e-7
    for s in &runs {
        assert_eq!(s.slip_fraction, x.slip_fraction, "{table}");
    }
}

/// Every semismooth Newton iterate reports its active set (stick, slip) to the observer; the
/// solution sticks at one site and slides at the others.
#[test]
fn exact_coulomb_reports_its_active_set_per_iteration() {
    struct Sets(Vec<capstan_solvers::ActiveSet>);
    impl capstan_solvers::Observer<f64> for Sets {
        fn iteration(&mut self, p: &capstan_solvers::Progress<f64>) {
            if let Some(set) = p.active {
                self.0.push(set);
            }
        }
    }
    let b = paper_body(41, 9);
    let mut sets = Sets(Vec::new());
    let x = exact_observed(&b, EndLoads::new(1.0, 2.0), &mut sets);
    assert!(
        sets.0.len() >= x.stats.newton_iterations.min(2),
        "{:?}",
        sets.0
    );
    let last = sets.0.last().unwrap();
    assert_eq!(last.stick + last.slip, 41, "{last:?}");
    assert_eq!(last.stick, 1, "{last:?}");
}

/// A 3-D body of width 1 with free sides (Q1, 3 x 21 x 5, ratio 1.5): exact Coulomb with the
/// two-component slip and the friction disc converges, and regularised Coulomb approaches it
/// at first order in `eps` (max `|v2|`), with the same Slip.
#[test]
fn exact_coulomb_on_a_3d_body_is_the_limit_of_regularised_coulomb() {
    use capstan_elasticity::contact::Dimension;
    use capstan_elasticity::solid::SideFaces;
    let mut b = paper_body(21, 5);
    b.method = DiscretisationMethod::FemQ1;
    b.dimension = Dimension::Solid {
        x1: [-0.5, 0.5],
        n1: 3,
        sides: SideFaces::Free,
    };
    let loads = EndLoads::new(1.0, 1.5);
    let x = exact(&b, loads);
    assert!(x.stats.residual < 1e-9, "{:e}", x.stats.residual);
    let v2 = x.max_azimuthal_displacement.value;
    let runs: Vec<(f64, ContactSolution)> = [1e-5, 1e-6]
        .into_iter()
        .map(|e| (e, regularised(&b, e, loads)))
        .collect();
    let errors: Vec<(f64, f64)> = runs
        .iter()
        .map(|(e, s)| (*e, (s.max_azimuthal_displacement.value - v2).abs()))
        .collect();
    let p = capstan_elasticity::verification::observed_order(&errors);
    // measured: 3.79e-6, 3.81e-7 (order 0.998)
    assert!((p - 1.0).abs() < 0.1, "{p}: {errors:?}");
    assert!(errors[1].1 < 3e-4 * v2.abs(), "{errors:?}");
    for (_, s) in &runs {
        assert_eq!(s.slip_fraction, x.slip_fraction);
    }
}
