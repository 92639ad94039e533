//! Load paths with memory on the thick body (issue 27): quasi-static steps, each from the
//! previous state, friction on the slip increment. The paper's body (circle `r = 2`, `h = 1`,
//! `mu = 1/2`, FD) in plane strain; one 3-D consistency test.

use capstan_elasticity::contact::{
    Body, BoundarySolver, ContactModel, ContactSettings, EndLoads, FullSystemSettings,
    FullSystemSolver, PathSolver, PathStep, solve_path_silent,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_friction::nonsmooth_law::bind_nonsmooth;
use capstan_friction::{
    ExactCoulomb, ExactCoulombParams, FrictionLaw, Frictionless, RegularisedCoulomb,
    RegularisedCoulombParams,
};
use capstan_geometry::{EllipticalPrism, Obstacle};

fn paper_body(n2: usize, n3: usize) -> Body {
    let circle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 2.0).unwrap());
    let mut b = Body::new(circle, n2, n3);
    b.method = DiscretisationMethod::Fd;
    b
}

fn regularised(
    b: &Body,
    eps: f64,
) -> ContactModel<capstan_elasticity::contact::BodyOperator, RegularisedCoulomb> {
    let params = RegularisedCoulombParams::new(0.5, eps).unwrap();
    b.model(RegularisedCoulomb, params, eps).unwrap()
}

fn exact(b: &Body) -> ContactModel<capstan_elasticity::contact::BodyOperator, Frictionless> {
    let law = bind_nonsmooth(ExactCoulomb, ExactCoulombParams::new(0.5).unwrap());
    b.model(Frictionless, (), 1e-5)
        .unwrap()
        .into_exact_friction(law)
        .unwrap()
}

fn full_path<L: FrictionLaw<f64> + Clone>(
    model: &ContactModel<capstan_elasticity::contact::BodyOperator, L>,
    path: &[EndLoads],
) -> Vec<PathStep> {
    solve_path_silent(model, PathSolver::FullSystem(Box::default()), path).unwrap()
}

fn ratios(tau_max: &[f64]) -> Vec<EndLoads> {
    tau_max.iter().map(|&t| EndLoads::new(1.0, t)).collect()
}

/// `max_i |a_i - b_i| / max_i |b_i|`.
fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let d = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    d / b.iter().fold(0.0f64, |m, y| m.max(y.abs()))
}

/// The first step of a path is today's static solve from rest, on both solvers (the model
/// without a slip reference and the solver's own start: equal to round-off, in fact bit for
/// bit).
#[test]
fn first_step_of_a_path_is_the_static_solve() {
    let b = paper_body(41, 9);
    let model = regularised(&b, 1e-5);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let path = ratios(&[2.0, 1.5]);
    let steps = solve_path_silent(&model, PathSolver::Condensed(&solver), &path).unwrap();
    let statics = solver.solve(path[0]).unwrap();
    let d = relative_difference(&steps[0].solution.displacement, &statics.displacement);
    assert!(d <= 1e-12, "condensed: {d:e}");
    let full = full_path(&model, &path);
    let statics = FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .solve(path[0])
        .unwrap();
    let d = relative_difference(&full[0].solution.displacement, &statics.displacement);
    assert!(d <= 1e-12, "full system: {d:e}");
}

/// The condensed path (one condensation for every step) and the full-system path solve the
/// same equations: equal states at every step to the solvers' tolerance.
#[test]
fn condensed_and_full_system_paths_agree() {
    let b = paper_body(41, 9);
    let model = regularised(&b, 1e-5);
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let path = ratios(&[2.0, 1.5, 1.2, 2.0]);
    let condensed = solve_path_silent(&model, PathSolver::Condensed(&solver), &path).unwrap();
    let full = full_path(&model, &path);
    for (c, f) in condensed.iter().zip(&full) {
        let d = relative_difference(&c.solution.displacement, &f.solution.displacement);
        assert!(d < 1e-7, "{d:e}");
        assert_eq!(c.solution.contact.state, f.solution.contact.state);
        assert!((c.dissipation - f.dissipation).abs() < 1e-6 * f.dissipation.abs());
    }
    // the condensed path factorised once
    assert_eq!(solver.setup().factorisations, 1);
}

/// Loading proportionally (nothing unloads: every slip increment points the way of the total
/// slip) in one step and in ten steps gives the same state under exact Coulomb, to the
/// solver tolerance; the dissipated energy is the same too.
#[test]
fn loading_in_one_step_and_in_ten_steps_agree_under_exact_coulomb() {
    let b = paper_body(41, 9);
    let model = exact(&b);
    let full = EndLoads::new(1.0, 2.0);
    let one = full_path(&model, &[full]);
    let ten: Vec<EndLoads> = (1..=10).map(|k| full.scaled(k as f64 / 10.0)).collect();
    let ten = full_path(&model, &ten);
    let last = ten.last().unwrap();
    let d = relative_difference(&last.solution.displacement, &one[0].solution.displacement);
    assert!(d < 1e-8, "{d:e}");
    // proportional loading scales the solution: the friction work of step n is s_n ds D1
    // (backward Euler: the traction at the end of each step), so ten steps dissipate
    // sum_n (n / 10)(1 / 10) = 0.55 of one step, a Riemann sum of the exact 1/2
    let work: f64 = ten.iter().map(|s| s.dissipation).sum();
    let w1 = one[0].dissipation;
    assert!(w1 > 0.0);
    assert!((work / w1 - 0.55).abs() < 1e-8, "{}", work / w1);
}

/// A thin body (`h = 1/4`) on the paper's circle behaves as a belt: loading from the
/// pretensioned state grows a slip zone from the `tau_max` end.
fn thin_body(n2: usize, n3: usize) -> Body {
    let mut b = paper_body(n2, n3);
    b.thickness = 0.25;
    b
}

/// Regularised Coulomb along a load-unload-reload path converges to exact Coulomb at first
/// order in `eps` (the rate law's stick compliance `eps / (mu |sigma_n|)` per step), at every
/// step: measured 1.09e-2, 1.12e-3, 1.12e-4 relative at the last step for eps = 1e-5, 1e-6,
/// 1e-7 (the condensed path against the exact full-system path).
#[test]
fn regularised_path_converges_to_the_exact_path_at_first_order_in_eps() {
    let b = paper_body(41, 9);
    let path = ratios(&[1.0, 2.0, 1.5, 2.0, 1.5, 2.0, 1.5]);
    let exact_steps = full_path(&exact(&b), &path);
    let last = &exact_steps.last().unwrap().solution.displacement;
    let differences: Vec<(f64, f64)> = [1e-5, 1e-6, 1e-7]
        .iter()
        .map(|&eps| {
            let model = regularised(&b, eps);
            let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
            let steps = solve_path_silent(&model, PathSolver::Condensed(&solver), &path).unwrap();
            let d = relative_difference(&steps.last().unwrap().solution.displacement, last);
            (eps, d)
        })
        .collect();
    let p = capstan_elasticity::verification::observed_order(&differences);
    assert!((p - 1.0).abs() < 0.05, "{p} {differences:?}");
    assert!(differences[2].1 < 2e-4, "{differences:?}");
}

/// A load-unload-reload cycle closes its hysteresis loop under exact Coulomb (thin body, FD
/// 81 x 9, pretension `tau_max = tau0 = 1`, then 2 -> 1.5 -> 2 -> 1.5 -> 2): unloading slips
/// back in a zone at the `tau_max` end and sticks elsewhere, reloading slips that zone forward
/// again and returns to the loaded state (to 5e-11 relative after the first cycle, round-off
/// after the second); every cycle dissipates the same positive energy.
#[test]
fn load_unload_reload_cycle_closes_its_loop() {
    let b = thin_body(81, 9);
    let steps = full_path(&exact(&b), &ratios(&[1.0, 2.0, 1.5, 2.0, 1.5, 2.0]));
    let differ = |a: usize, c: usize| {
        relative_difference(
            &steps[c].solution.displacement,
            &steps[a].solution.displacement,
        )
    };
    assert!(differ(1, 3) < 1e-9, "{:e}", differ(1, 3));
    assert!(differ(3, 5) < 1e-12, "{:e}", differ(3, 5));
    assert!(differ(2, 4) < 1e-9, "{:e}", differ(2, 4));
    // unloading: a reverse-slip zone at the tau_max end, stick elsewhere
    let unload = &steps[2].solution.contact.state;
    let reverse = unload.iter().filter(|&&x| x == -1).count();
    assert_eq!(*unload.last().unwrap(), -1, "{unload:?}");
    assert!(reverse > 0 && reverse < unload.len() / 4, "{unload:?}");
    assert_eq!(
        unload.iter().filter(|&&x| x == 0).count() + reverse,
        unload.len()
    );
    // reloading slips the same zone forward
    let reload = &steps[3].solution.contact.state;
    assert!(
        reload.iter().rev().take(reverse).all(|&x| x == 1),
        "{reload:?}"
    );
    // the loop: unloading lowers the end displacement, reloading restores it
    assert!(steps[2].end_displacement < steps[1].end_displacement);
    let gap = (steps[3].end_displacement - steps[1].end_displacement).abs();
    assert!(gap < 1e-9 * steps[1].end_displacement, "{gap:e}");
    // the dissipation of a cycle (unload + reload) is positive and the same every cycle
    let cycle = |k: usize| steps[k].dissipation + steps[k + 1].dissipation;
    assert!(cycle(2) > 0.0);
    assert!(
        (cycle(2) - cycle(4)).abs() < 1e-7 * cycle(2),
        "{} {}",
        cycle(2),
        cycle(4)
    );
}

/// The energy dissipated per cycle converges under grid refinement (thin body, exact
/// Coulomb, FD, cycle 2 -> 1.5 -> 2 after the pretension and the first loading): observed
/// order from three grids by Richardson's ratio: 4.405e-6, 3.890e-6, 3.760e-6 on FD 41 x 5,
/// 81 x 9, 161 x 17, order 1.98.
#[test]
fn dissipation_per_cycle_converges_under_refinement() {
    let path = ratios(&[1.0, 2.0, 1.5, 2.0]);
    let grids = [(41, 5), (81, 9), (161, 17)];
    let cycles: Vec<f64> = grids
        .iter()
        .map(|&(n2, n3)| {
            let steps = full_path(&exact(&thin_body(n2, n3)), &path);
            steps[2].dissipation + steps[3].dissipation
        })
        .collect();
    let (d1, d2) = (cycles[1] - cycles[0], cycles[2] - cycles[1]);
    let order = (d1 / d2).abs().log2();
    eprintln!("cycle dissipation {cycles:?}, differences {d1:e} {d2:e}, order {order}");
    assert!(cycles.iter().all(|&c| c > 0.0), "{cycles:?}");
    assert!((order - 2.0).abs() < 0.2, "{order} {cycles:?}");
    assert!(d2.abs() < 0.05 * cycles[2], "{cycles:?}");
}

/// The 3-D body (ellipse `a = 2`, `b = 1.5`, width 1, free sides, Q1 5 x 17 x 5): the first
/// step of a path is the static solve, and the condensed and full-system paths agree.
#[test]
fn three_dimensional_path_is_consistent() {
    use capstan_elasticity::solid::SolidBody;
    let obstacle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 1.5).unwrap());
    let body = SolidBody::new(obstacle, [-0.5, 0.5], [5, 17, 5]);
    let eps = 1e-5;
    let params = RegularisedCoulombParams::new(0.5, eps).unwrap();
    let model = body.model(RegularisedCoulomb, params, eps).unwrap();
    let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let path = ratios(&[2.0, 1.5, 2.0]);
    let condensed = solve_path_silent(&model, PathSolver::Condensed(&solver), &path).unwrap();
    let statics = solver.solve(path[0]).unwrap();
    let d = relative_difference(&condensed[0].solution.displacement, &statics.displacement);
    assert!(d <= 1e-12, "{d:e}");
    let full = solve_path_silent(&model, PathSolver::FullSystem(Box::default()), &path).unwrap();
    for (c, f) in condensed.iter().zip(&full) {
        let d = relative_difference(&c.solution.displacement, &f.solution.displacement);
        assert!(d < 1e-7, "{d:e}");
        assert!(c.dissipation >= 0.0);
    }
    // unloading from 2 to 1.5 sticks at least somewhere (memory), reloading dissipates
    assert!(condensed[1].solution.contact.state.contains(&0));
}
