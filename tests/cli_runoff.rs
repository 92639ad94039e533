//! `capstan contact` and `capstan threshold` on the default cone under unilateral contact
//! (Q1 `3 x 20 x 3`, width 1, `mu = 0.5`): past the fold of its equilibrium path,
//! `r* = 1.439790` (examples/solid_runoff.rs; the dense arclength of the whole system agrees to
//! 7 digits), no equilibrium exists on the path, and the commands say so (exit 3) instead of
//! failing to converge (exit 4).

mod common;

/// The scene's keys as `--set` arguments, with `extra` appended.
fn cone(extra: &[&'static str]) -> Vec<&'static str> {
    let mut args = Vec::new();
    for set in [
        "body.dimension=3",
        "obstacle.shape=\"cone\"",
        "grid.n1=3",
        "grid.n2=20",
        "grid.n3=3",
        "discretisation.method=\"fem-q1\"",
        "contact.kind=\"unilateral\"",
        "output.error_estimate=false",
    ]
    .iter()
    .chain(extra)
    {
        args.extend(["--set", set]);
    }
    args
}

/// The number after `key` in `text` (up to the next character that is not part of a number).
fn number_after(text: &str, key: &str) -> f64 {
    let start = text
        .find(key)
        .unwrap_or_else(|| panic!("no `{key}` in {text}"))
        + key.len();
    let digits: String = text[start..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    digits.parse().unwrap_or_else(|_| panic!("{text}"))
}

/// At ratio 2 (the default `loads.tau_max`) the plain Newton fails; the continuation in the
/// ratio finds the fold and the command exits 3 with `r*` and its bracket, in text and with
/// `--json` alike (no report on stdout: the error on stderr). Before: exit 4, "contact
/// Newton did not converge ... load factor reached 0.0000".
#[test]
fn contact_past_the_fold_exits_3_naming_r_star_and_its_bracket() {
    for json in [false, true] {
        let mut args = vec!["contact"];
        args.extend(cone(&[]));
        if json {
            args.push("--json");
        }
        let (code, out, err) = common::capstan_status(&args);
        assert_eq!(code, Some(3), "{err}");
        assert!(out.trim().is_empty(), "{out}");
        assert!(err.contains("no equilibrium beyond r* in ["), "{err}");
        let fold = number_after(&err, "r* = ");
        let lower = number_after(&err, "in [");
        let upper = number_after(&err, &format!("in [{lower:.6}, "));
        // examples/solid_runoff.rs: the bracket [1.439063, 1.440625] (steps of 0.05 halved to
        // below 1e-3), the largest ratio on the path 1.439790
        assert!((lower - 1.439063).abs() < 1e-6, "{err}");
        assert!((upper - 1.440625).abs() < 1e-6, "{err}");
        assert!((1.4395..=1.43980).contains(&fold), "{err}");
        assert!(lower <= fold && fold < upper, "{err}");
    }
}

/// At ratio 1.3 the plain Newton converges as before: the same answer, and no continuation
/// (one load step, the Newton iterations of the plain solve).
#[test]
fn contact_below_the_fold_is_the_plain_newton_answer() {
    let mut args = vec!["contact"];
    args.extend(cone(&["loads.tau_max=1.3"]));
    let report = common::capstan_json(&args);
    assert_eq!(report["status"], "converged");
    // measured on main before the run-off: 11 Newton iterations in 1 continuation step,
    // max v^2 = 0.038558290947098485
    assert_eq!(report["newton_iterations"], 11);
    assert_eq!(report["continuation_steps"], 1);
    let v2 = report["max_azimuthal_displacement"]["value"]
        .as_f64()
        .unwrap();
    assert!((v2 - 0.038558290947098485).abs() < 1e-9 * v2, "{v2}"); // solver tolerance 1e-10
}

/// With too few Newton iterations per load step (`solver.max_iterations = 8`) the plain
/// Newton fails at ratio 1.43 (below the fold; before: exit 4); the continuation in the ratio
/// reaches it, and its answer is the one of the plain Newton with the default budget.
#[test]
fn contact_below_the_fold_converges_by_continuation_where_newton_fails() {
    let mut plain = vec!["contact"];
    plain.extend(cone(&["loads.tau_max=1.43"]));
    let reference = common::capstan_json(&plain);
    assert_eq!(reference["continuation_steps"], 1);
    let mut args = vec!["contact"];
    args.extend(cone(&["loads.tau_max=1.43", "solver.max_iterations=8"]));
    let report = common::capstan_json(&args);
    assert_eq!(report["status"], "converged");
    // the arclength steps of the continuation (measured 28)
    assert!(report["continuation_steps"].as_u64().unwrap() > 1);
    for key in ["max_azimuthal_displacement", "max_radial_displacement"] {
        let (a, b) = (
            report[key]["value"].as_f64().unwrap(),
            reference[key]["value"].as_f64().unwrap(),
        );
        // both converged to the solver tolerance 1e-10 relative on the residual
        assert!((a - b).abs() < 1e-8 * b.abs(), "{key}: {a} vs {b}");
    }
    assert_eq!(report["slip_fraction"], reference["slip_fraction"]);
}

/// `capstan threshold` on the unilateral cone: the threshold is the fold `r*`, bracketed to
/// the threshold's tolerance (`1e-6`); `no_equilibrium_beyond`, the bracket in `run_off`.
/// Before: exit 2 (the condensed solver refuses unilateral contact).
#[test]
fn threshold_of_the_unilateral_cone_is_the_fold_of_its_path() {
    let mut args = vec!["threshold"];
    args.extend(cone(&[]));
    let report = common::capstan_json(&args);
    let ratio = report["threshold_ratio"].as_f64().unwrap();
    let below = report["below"].as_f64().unwrap();
    let fold = report["run_off"]["fold_ratio"].as_f64().unwrap();
    let bracket = common::json_array(&report["run_off"], "bracket");
    assert_eq!(bracket, [below, ratio]);
    assert!(below <= fold && fold < ratio, "{report}");
    assert!(ratio - below <= 1e-6 * ratio, "{report}");
    // the fold of examples/solid_runoff.rs, 1.439790 (to its 6 printed digits)
    assert!((fold - 1.439790).abs() < 1e-6, "{fold}");
    assert_eq!(report["no_equilibrium_beyond"], true);
    assert_eq!(report["grid_n1"], 3);
    // the text names r* and the bracket
    let (code, out, err) = common::capstan_status(&args);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("no equilibrium beyond r* = 1.43979"), "{out}");
}

/// A tiny `solver.max_continuation_steps` spends the continuation's budget: exit 4, the typed
/// error naming the key and the steps (before: the plain Newton's exit 4, with no
/// continuation in the ratio).
#[test]
fn a_tiny_continuation_budget_is_a_typed_error_naming_the_key() {
    for command in ["contact", "threshold"] {
        let mut args = vec![command];
        args.extend(cone(&["solver.max_continuation_steps=5"]));
        let (code, _, err) = common::capstan_status(&args);
        assert_eq!(code, Some(4), "{command}: {err}");
        assert!(
            err.contains("spent its budget of 5 arclength steps")
                && err.contains("`solver.max_continuation_steps` = 5"),
            "{command}: {err}"
        );
    }
}

/// Below ratio 1 (the far end pulled by half the near one's traction) the body slides the
/// other way: the plain Newton fails, the run-off goes down from ratio 1 and finds the lower
/// fold `r_*`, and the command exits 3 naming it and its bracket, in text and with `--json`.
/// Before: exit 4 ("did not converge ... load factor reached 0.0000"; the run-off only
/// climbed). The cone is symmetric under `x2 -> -x2`, which swaps the ends: the lower fold is
/// `1 / r*` (`r_* r*` = 1 + 1.6e-8, the threshold's brackets; docs/models.md).
#[test]
fn contact_below_the_lower_fold_exits_3_naming_r_star_below_and_its_bracket() {
    for json in [false, true] {
        let mut args = vec!["contact"];
        args.extend(cone(&["loads.tau_max=0.5"]));
        if json {
            args.push("--json");
        }
        let (code, out, err) = common::capstan_status(&args);
        assert_eq!(code, Some(3), "{err}");
        assert!(out.trim().is_empty(), "{out}");
        assert!(err.contains("no equilibrium below r_* in ["), "{err}");
        assert!(err.contains("at tension ratio 0.500000"), "{err}");
        let fold = number_after(&err, "r_* = ");
        let lower = number_after(&err, "in [");
        let upper = number_after(&err, &format!("in [{lower:.6}, "));
        // steps of 0.05 down from 1 to 0.7, then halved below 1e-3 (measured)
        assert!((lower - 0.693750).abs() < 1e-6, "{err}");
        assert!((upper - 0.695312).abs() < 1e-6, "{err}");
        assert!(lower < fold && fold <= upper, "{err}");
        // the mirror image of the upper fold, to the bracket's width
        assert!((fold - 1.0 / 1.439790).abs() < upper - lower, "{err}");
    }
}

/// Just above the lower fold (ratio 0.7) the plain Newton fails but the run-off down reaches
/// the ratio: the answer, with the body sliding backwards (Slip -1). Before: exit 4.
#[test]
fn contact_between_the_lower_fold_and_1_converges_by_the_run_off_down() {
    let mut args = vec!["contact"];
    args.extend(cone(&["loads.tau_max=0.7"]));
    let report = common::capstan_json(&args);
    assert_eq!(report["status"], "converged");
    assert_eq!(report["slip_fraction"], -1.0);
    // the arclength steps of the run-off (measured 20)
    assert!(report["continuation_steps"].as_u64().unwrap() > 1);
    assert!((report["tension_ratio"].as_f64().unwrap() - 0.7).abs() < 1e-15);
}

/// `capstan threshold` reports the other end of the unilateral cone's equilibrium range too:
/// the run-off down from 1 folds at `r_* = 0.694546` (the mirror image `1 / r*` of the upper
/// fold to the threshold's tolerance), bracketed to `1e-6`, in `run_off.lower_end` and the
/// text. Before: no lower end (the key absent).
#[test]
fn threshold_of_the_unilateral_cone_reports_the_lower_end_of_its_range() {
    let mut args = vec!["threshold"];
    args.extend(cone(&[]));
    let report = common::capstan_json(&args);
    let upper = report["run_off"]["fold_ratio"].as_f64().unwrap();
    let lower_end = &report["run_off"]["lower_end"];
    let fold = lower_end["fold_ratio"].as_f64().unwrap();
    let bracket = common::json_array(lower_end, "bracket");
    assert!(bracket[0] < fold && fold <= bracket[1], "{report}");
    // the smallest ratio step is half the tolerance 1e-6: the bracket at most 1e-6 wide
    assert!(bracket[1] - bracket[0] <= 1e-6, "{report}");
    assert!((fold - 0.694546).abs() < 1e-6, "{fold}");
    // r_* r* = 1 within the brackets (both 1e-6 wide): the scene's mirror symmetry
    assert!((fold * upper - 1.0).abs() < 2e-6, "{}", fold * upper);
    assert!(lower_end["solves"].as_u64().unwrap() > 1);
    let (code, out, err) = common::capstan_status(&args);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("no equilibrium below r_* = 0.69454"), "{out}");
}

/// A forced `multigrid` Newton (GMRES with the geometric multigrid) past the fold: its plain
/// solve spends the Krylov budget next to the singular Jacobian (before: exit 4, "500 Krylov
/// iterations spent", and no run-off); the run-off on sparse LU finds the fold, which replaces
/// the failure (exit 3, the bracket of the LU route), above and below ratio 1. Where the plain
/// solve does not converge but the path from 1 reaches the ratio (1.43 with 8 Newton
/// iterations per step), the method's own run-off answers as before: the plain LU Newton's
/// answer, the choice as named.
#[test]
fn a_forced_multigrid_newton_past_the_fold_exits_3_by_the_sparse_lu_run_off() {
    let multigrid = [
        "solver.nonlinear=\"full-newton\"",
        "solver.linear=\"multigrid\"",
    ];
    for (ratio, expected) in [
        (
            "loads.tau_max=2",
            "no equilibrium beyond r* in [1.439063, 1.440625]",
        ),
        (
            "loads.tau_max=0.5",
            "no equilibrium below r_* in [0.693750, 0.695312]",
        ),
    ] {
        let mut args = vec!["contact"];
        args.extend(cone(&[multigrid[0], multigrid[1], ratio]));
        let (code, _, err) = common::capstan_status(&args);
        assert_eq!(code, Some(3), "{err}");
        assert!(err.contains(expected), "{err}");
    }
    let mut plain = vec!["contact"];
    plain.extend(cone(&["loads.tau_max=1.43"]));
    let reference = common::capstan_json(&plain);
    let mut args = vec!["contact"];
    args.extend(cone(&[
        multigrid[0],
        multigrid[1],
        "loads.tau_max=1.43",
        "solver.max_iterations=8",
    ]));
    let report = common::capstan_json(&args);
    assert_eq!(report["status"], "converged");
    assert_eq!(report["solver_choice"]["linear"], "multigrid");
    assert_eq!(
        report["solver_choice"]["reason"],
        "named by the solver settings"
    );
    for key in ["max_azimuthal_displacement", "max_radial_displacement"] {
        let (a, b) = (
            report[key]["value"].as_f64().unwrap(),
            reference[key]["value"].as_f64().unwrap(),
        );
        assert!((a - b).abs() < 1e-8 * b.abs(), "{key}: {a} vs {b}");
    }
}

/// A load continuation that converges keeps its work: the bilateral cone on the full-system
/// Newton at ratio 3.8 fails at the full load and converges only at the load fraction 1/32
/// (the 5th Newton solve), then climbs to 1; a run-off would follow a failure, so the plain
/// solve runs under the watch that stops it after 7 solves with no converged step, and the
/// watch must not fire here. Measured on main before the watch: 102 Newton iterations in 10
/// continuation steps.
#[test]
fn a_load_continuation_that_converges_before_a_run_off_keeps_its_work() {
    let mut args = vec!["contact"];
    args.extend(cone(&[
        "contact.kind=\"bilateral\"",
        "solver.nonlinear=\"full-newton\"",
        "loads.tau_max=3.8",
    ]));
    let report = common::capstan_json(&args);
    assert_eq!(report["status"], "converged");
    assert_eq!(report["newton_iterations"], 102);
    assert_eq!(report["continuation_steps"], 10);
}
