//! The default cone (`obstacle.shape = "cone"`, Q1 `3 x 20 x 3`, width 1, `mu = 0.5`) under
//! unilateral contact, by continuation in the tension ratio as `examples/solid_runoff.rs`
//! runs it: past the old stall at 1.348 (issue 27), where a site about to lift off carried
//! the friction of its recovered normal stress and the residual jumped when it separated.

use capstan::Scene;
use capstan_elasticity::contact::{
    ContactError, ContactErrorKind, ContactModel, ContactOperator, ContactSolution, EndLoads,
    FullSystemProblem, FullSystemSolver, RunOffEnd, RunOffSettings, RunOffTrial,
};
use capstan_elasticity::friction::FrictionLaw;
use capstan_elasticity::solvers::{Jacobian, Residual};
use capstan_elasticity::solvers::{Progress, SilentObserver, SolveStage};

fn cone_model() -> (capstan::Problem, f64) {
    let mut scene = Scene::default();
    for (key, value) in [
        ("body.dimension", "3"),
        ("discretisation.method", "\"fem-q1\""),
        ("obstacle.shape", "\"cone\""),
        ("grid.n1", "3"),
        ("grid.n2", "20"),
        ("grid.n3", "3"),
        ("contact.kind", "\"unilateral\""),
        ("solver.nonlinear", "\"full-newton\""),
    ] {
        scene = scene.with_raw(key, value, "test").unwrap();
    }
    let problem = scene.build().unwrap();
    let mu = 0.5; // the default scene's friction.mu
    (problem, mu)
}

/// The ratios 1, 1.05, ..., `last`, each solved from the one before.
fn continue_to<D: ContactOperator, L: FrictionLaw<f64>>(
    solver: &FullSystemSolver<'_, D, L>,
    last: f64,
) -> Vec<(f64, ContactSolution)> {
    let mut out = vec![(1.0, solver.solve(EndLoads::new(1.0, 1.0)).unwrap())];
    let mut ratio = 1.0;
    while ratio < last - 1e-12 {
        ratio += 0.05;
        let start = &out.last().unwrap().1.displacement;
        let s = solver
            .solve_from(EndLoads::new(1.0, ratio), start)
            .unwrap_or_else(|e| panic!("ratio {ratio}: {e}"));
        out.push((ratio, s));
    }
    out
}

#[test]
fn the_unilateral_cone_converges_past_the_old_stall_in_a_few_newton_steps() {
    let (problem, mu) = cone_model();
    let model = problem.model().unwrap();
    let solver = FullSystemSolver::new(&model, problem.solver.full_settings()).unwrap();
    // before: 1.30 -> 1.35 failed (plain Newton frozen at residual 1.6e-2, then the stuck
    // start and load continuation failing at load factor 5e-4)
    let path = continue_to(&solver, 1.35);
    let (ratio, s) = path.last().unwrap();
    assert!((ratio - 1.35).abs() < 1e-12);
    // measured 4 (release and debug alike: the iterations do not depend on the build)
    assert!(
        s.stats.newton_iterations <= 8,
        "{}",
        s.stats.newton_iterations
    );
    assert_eq!(s.slip_fraction, 1.0);
    let separated = s.contact.separated.as_ref().unwrap();
    assert_eq!(separated.iter().filter(|&&x| x).count(), 29);
    // friction only where in contact, and never above mu |sigma_n|; at least one site in
    // contact carries less (the reaction cap holds there)
    let capped = (0..separated.len())
        .filter(|&k| !separated[k])
        .filter(|&k| {
            let t = capstan_friction_norm(s, k);
            let full = mu * s.contact.normal_stress[k].min(0.0).abs();
            assert!(t <= full * (1.0 + 1e-9) + 1e-14, "site {k}: {t} > {full}");
            t < 0.99 * full
        })
        .count();
    assert!(capped > 0);
    check_jacobian(&model, *ratio, &s.displacement);
}

/// `|t|` at site `k` (both components on the 3-D body).
fn capstan_friction_norm(s: &ContactSolution, k: usize) -> f64 {
    let t2 = s.contact.friction_traction[k];
    let t1 = s
        .contact
        .solid
        .as_ref()
        .map_or(0.0, |p| p.friction_traction_1[k]);
    t1.hypot(t2)
}

/// The Jacobian along a fixed direction against central differences of the residual.
fn check_jacobian<D, L: FrictionLaw<f64>>(model: &ContactModel<D, L>, ratio: f64, v: &[f64]) {
    let p = FullSystemProblem::new(model, EndLoads::new(1.0, ratio));
    let n = v.len();
    let d: Vec<f64> = (0..n)
        .map(|i| ((i * 7919) % 101) as f64 / 101.0 - 0.5)
        .collect();
    let mut values = vec![0.0; p.pattern().nnz()];
    p.jacobian(v, &mut values).unwrap();
    let mut jd = vec![0.0; n];
    for ((i, j), a) in p.pattern().entries().zip(&values) {
        jd[i] += a * d[j];
    }
    let h = 1e-8;
    let shifted = |s: f64| {
        let w: Vec<f64> = v.iter().zip(&d).map(|(a, b)| a + s * b).collect();
        let mut r = vec![0.0; n];
        p.residual(&w, &mut r).unwrap();
        r
    };
    let (plus, minus) = (shifted(h), shifted(-h));
    let err = (0..n)
        .map(|i| ((plus[i] - minus[i]) / (2.0 * h) - jd[i]).abs())
        .fold(0.0f64, f64::max);
    let size = jd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    // central differences with h = 1e-8 on entries of size 1e3: round-off about 1e-5
    assert!(err <= 1e-6 * size, "{err:e} of {size:e}");
}

/// Past 1.35 the pseudo-arclength continuation in the ratio follows the path to its fold
/// `r* = 1.439790` (the dense arclength of the whole system agrees to 7 digits) and reports
/// no equilibrium beyond it; below the fold it converges.
#[test]
fn the_unilateral_cone_has_no_equilibrium_beyond_the_fold_of_its_path() {
    let (problem, _) = cone_model();
    let model = problem.model().unwrap();
    let solver = FullSystemSolver::new(&model, problem.solver.full_settings()).unwrap();
    let path = continue_to(&solver, 1.35);
    let (ratio, s) = path.last().unwrap();
    let below = solver
        .continue_ratio(1.0, *ratio, &s.displacement, 1.4375)
        .unwrap();
    assert_eq!(below.slip_fraction, 1.0);
    let err = solver
        .continue_ratio(1.0, 1.4375, &below.displacement, 1.45)
        .unwrap_err();
    assert_eq!(err.kind(), ContactErrorKind::NoEquilibrium, "{err}");
    let ContactError::NoEquilibrium { upper, ratio, .. } = err else {
        unreachable!("kind checked above")
    };
    assert_eq!(ratio, 1.45);
    // the largest converged point of the steps lies within the arclength step of the fold
    assert!((1.4395..=1.43980).contains(&upper), "{upper}");
}

/// The run-off driver (`examples/solid_runoff.rs`, `capstan contact`, `capstan threshold`)
/// from ratio 1 towards 2: the path folds; the bracket and `r*` of the example, and the work
/// it took (17 ratio steps, 72 arclength steps measured).
#[test]
fn run_off_brackets_the_fold_of_the_unilateral_cone() {
    let (problem, _) = cone_model();
    let model = problem.model().unwrap();
    let solver = FullSystemSolver::new(&model, problem.solver.full_settings()).unwrap();
    let mut converged = Vec::new();
    let mut trace = |(ratio, result): RunOffTrial<'_>| {
        if result.is_ok() {
            converged.push(ratio);
        }
    };
    let run = solver
        .run_off(
            1.0,
            1.0,
            2.0,
            RunOffSettings::default(),
            &mut SilentObserver,
            &mut trace,
        )
        .unwrap();
    let RunOffEnd::Folded {
        fold,
        beyond: upper,
    } = run.end
    else {
        panic!("{:?}", run.end)
    };
    // 1.0 + 0.05 k, then steps of 0.025, 0.0125, ... (halved after a fold): binary fractions
    assert!((run.reached - 1.4390625).abs() < 1e-12, "{}", run.reached);
    assert!((upper - 1.440625).abs() < 1e-12, "{upper}");
    assert!((1.4395..=1.43980).contains(&fold), "{fold}");
    assert_eq!(converged.first(), Some(&1.0));
    assert_eq!(converged.last(), Some(&run.reached));
    assert_eq!(run.ratio_steps, 17);
    assert!(run.arclength_steps <= 80, "{}", run.arclength_steps);
    assert_eq!(run.last.stats.continuation_steps, run.arclength_steps);
    assert!((run.last.loads.tension_ratio() - run.reached).abs() < 1e-12);
    // as a solve at ratio 2: no equilibrium beyond r*, with the bracket
    let err = run.into_solution(ContactError::NoContactNodes).unwrap_err();
    assert_eq!(err.kind(), ContactErrorKind::NoEquilibrium);
    let ContactError::NoEquilibriumBeyond { ratio, .. } = err else {
        panic!("{err}")
    };
    assert_eq!(ratio, 2.0);
}

/// Below the fold the run-off reaches the ratio asked for, with the plain Newton's answer
/// there (both converged to the solver tolerance).
#[test]
fn run_off_reaches_a_ratio_below_the_fold_with_the_plain_newton_answer() {
    let (problem, _) = cone_model();
    let model = problem.model().unwrap();
    let solver = FullSystemSolver::new(&model, problem.solver.full_settings()).unwrap();
    let plain = solver.solve(EndLoads::new(1.0, 1.43)).unwrap();
    let run = solver
        .run_off(
            1.0,
            1.0,
            1.43,
            RunOffSettings::default(),
            &mut SilentObserver,
            &mut |_| {},
        )
        .unwrap();
    assert!(matches!(run.end, RunOffEnd::Reached), "{:?}", run.end);
    assert_eq!(run.reached, 1.43);
    let size = plain
        .displacement
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = plain
        .displacement
        .iter()
        .zip(&run.last.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    // residual tolerance 1e-10 relative; the Jacobian's conditioning (smallest singular value
    // 1e-2 of entries 1e3) loses up to 5 digits of it
    assert!(diff <= 1e-7 * size, "{diff:e} of {size:e}");
    let solution = run.into_solution(ContactError::NoContactNodes).unwrap();
    assert_eq!(solution.slip_fraction, plain.slip_fraction);
}

/// The run-off's budget: arclength steps over every continuation; spent, a typed error with
/// the ratio reached.
#[test]
fn run_off_spends_its_budget_as_a_typed_error() {
    let (problem, _) = cone_model();
    let model = problem.model().unwrap();
    let solver = FullSystemSolver::new(&model, problem.solver.full_settings()).unwrap();
    let settings = RunOffSettings {
        max_arclength_steps: 10,
        ..Default::default()
    };
    let err = solver
        .run_off(1.0, 1.0, 2.0, settings, &mut SilentObserver, &mut |_| {})
        .unwrap_err();
    assert_eq!(err.kind(), ContactErrorKind::NotConverged, "{err}");
    let ContactError::ContinuationBudgetSpent {
        steps,
        reached,
        ratio,
    } = err
    else {
        panic!("{err}")
    };
    assert_eq!((steps, ratio), (10, 2.0));
    // the first steps of 0.05 take two or three arclength steps each
    assert!((1.05..1.4).contains(&reached), "{reached}");
    // and bad settings are refused
    let bad = RunOffSettings {
        min_step: 0.1,
        ..Default::default()
    };
    assert!(
        solver
            .run_off(1.0, 1.0, 2.0, bad, &mut SilentObserver, &mut |_| {})
            .is_err()
    );
}

/// The plain solve before a run-off stops once its load continuation is futile: at ratio 2
/// the full load fails, then the continuation's steps at the fractions 1/4, 1/8, ..., 1/128
/// (every Newton solve starts from the stuck start, whose residual scales with the load);
/// the 8th solve (1/256) is stopped at its first iteration, and the run-off starts at ratio 1
/// (its continuation steps report to no observer). Before: 13 solves of the plain problem,
/// down to the fraction 1.2e-4, 14 solve starts in all.
#[test]
fn the_plain_solve_before_a_run_off_stops_after_seven_newton_solves() {
    let (problem, _) = cone_model();
    assert_eq!(problem.loads.tension_ratio(), 2.0);
    let mut starts = Vec::new();
    let mut observer = |p: &Progress<f64>| {
        if p.stage == SolveStage::Newton && p.iteration == 0 {
            starts.push(p.residual_norm);
        }
    };
    let err = problem.solve_observed(&mut observer).unwrap_err();
    assert!(
        matches!(
            err,
            capstan::problem::ProblemError::Contact(ContactError::NoEquilibriumBeyond { .. })
        ),
        "{err}"
    );
    assert_eq!(starts.len(), 9, "{starts:?}");
    for (k, r) in starts.iter().enumerate().take(8).skip(1) {
        let fraction = 0.25 / f64::from(1 << (k - 1));
        // the stuck start is linear in the load, its residual nearly so (the regularised
        // friction is not homogeneous: measured 4e-4 off at 1/4); halvings are a factor 2
        assert!(
            (r - fraction * starts[0]).abs() <= 1e-2 * r,
            "solve {k}: {r} against {fraction} x {}",
            starts[0]
        );
    }
    // a `solver.min_load_step` below the default asks for the longer continuation: no cut
    // (down to the fraction 6.1e-5 here, 14 solves, then the run-off's start)
    let mut problem = problem;
    problem.solver.budgets.min_load_step = 5e-5;
    let mut longer = 0;
    let mut observer = |p: &Progress<f64>| {
        if p.stage == SolveStage::Newton && p.iteration == 0 {
            longer += 1;
        }
    };
    assert!(problem.solve_observed(&mut observer).is_err());
    assert_eq!(longer, 15);
}

/// The run-off down from ratio 1 towards 0.5 (the far end pulled by half the near one's
/// traction): the path folds at `r_*`, the smallest ratio it reached, with the bracket
/// `[beyond, reached]` below the start and the error `NoEquilibriumBelow`; the continuation
/// itself reports the fold as `NoEquilibrium` with `lower = r_*` and `upper = +inf`. Before:
/// the run-off refused a target below its start (`to` must lie above `from`).
#[test]
fn run_off_down_brackets_the_lower_fold_of_the_unilateral_cone() {
    let (problem, _) = cone_model();
    let model = problem.model().unwrap();
    let solver = FullSystemSolver::new(&model, problem.solver.full_settings()).unwrap();
    let mut folds = Vec::new();
    let mut trace = |(_, result): RunOffTrial<'_>| {
        if let Err(ContactError::NoEquilibrium { lower, upper, .. }) = result {
            folds.push((*lower, *upper));
        }
    };
    let run = solver
        .run_off(
            1.0,
            1.0,
            0.5,
            RunOffSettings::default(),
            &mut SilentObserver,
            &mut trace,
        )
        .unwrap();
    let RunOffEnd::Folded { fold, beyond } = run.end else {
        panic!("{:?}", run.end)
    };
    // 1 - 0.05 k down to 0.7, then steps of 0.025, 0.0125, ... (binary fractions, measured)
    assert!((run.reached - 0.6953125).abs() < 1e-12, "{}", run.reached);
    assert!((beyond - 0.69375).abs() < 1e-12, "{beyond}");
    assert!(beyond < fold && fold <= run.reached, "{fold}");
    assert_eq!(run.bracket(), Some([beyond, run.reached]));
    let reached = run.reached;
    assert!((run.last.loads.tension_ratio() - run.reached).abs() < 1e-12);
    assert!(!folds.is_empty());
    for (lower, upper) in folds {
        assert!(lower < 1.0 && upper == f64::INFINITY, "{lower} {upper}");
    }
    let err = run.into_solution(ContactError::NoContactNodes).unwrap_err();
    assert_eq!(err.kind(), ContactErrorKind::NoEquilibrium);
    let ContactError::NoEquilibriumBelow {
        ratio,
        lower,
        upper,
        ..
    } = err
    else {
        panic!("{err}")
    };
    assert_eq!((ratio, lower, upper), (0.5, beyond, reached));
}
