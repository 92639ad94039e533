//! The CLI on the default plane body under unilateral contact past limiting equilibrium: exit 3
//! naming the unilateral limiting range (the full-slip balance along the rigid sliding mode),
//! the threshold at its upper end, and the bilateral answers unchanged.

mod common;

const UNILATERAL: &str = "contact.kind=\"unilateral\"";

/// Where the upper end must lie on the default grid (`[a, b)`; measured 3.344004): at or above
/// 3.342344, the largest ratio the run-off of the unilateral body (`FullSystemSolver::run_off`
/// from 3.2 in steps of 0.02 halved to 1e-4) converged at, Slip 0.988 (every step from 3.3425
/// failed: the Jacobian is singular near full slip; from 1 in steps of 0.05 it stalls after
/// 3.340625, so its stall is the solver's, not the limit); below the bilateral end 3.344063
/// (at full slip a node next to the loaded end separates), so that a range ignoring the
/// unilateral rows fails.
const UPPER_END: [f64; 2] = [3.342344, 3.344063];

/// `[lower, upper]` of "outside the limiting range [lower, upper]" in `text`.
fn named_range(text: &str) -> [f64; 2] {
    let tail = text
        .split("outside the limiting range [")
        .nth(1)
        .unwrap_or_else(|| panic!("no range in: {text}"));
    let inner = tail.split(']').next().unwrap();
    let mut ends = inner.split(", ").map(|x| x.trim().parse::<f64>().unwrap());
    [ends.next().unwrap(), ends.next().unwrap()]
}

#[test]
fn unilateral_past_the_limit_exits_3_with_the_range_in_the_run_off_bracket() {
    for json in [false, true] {
        let mut args = vec!["contact", "--set", UNILATERAL, "--set", "loads.tau_max=3.5"];
        if json {
            args.push("--json");
        }
        let (code, _, err) = common::capstan_status(&args);
        assert_eq!(code, Some(3), "{err}");
        assert!(err.contains("no static equilibrium"), "{err}");
        let [lower, upper] = named_range(&err);
        assert!(
            (UPPER_END[0]..UPPER_END[1]).contains(&upper),
            "{upper} not in {UPPER_END:?}: {err}"
        );
        assert!(lower > 0.0 && lower < 1.0, "{err}");
    }
}

/// Inside the range the unilateral solve is what it was (main before the range: 19 Newton
/// iterations, Slip 0.896, max `v2` 5.962265637721237e-3, no limiting ratios reported): the
/// pre-check adds one full-slip solve and changes nothing in the answer.
#[test]
fn unilateral_inside_the_range_converges_as_before() {
    let json =
        common::capstan_json(&["contact", "--set", UNILATERAL, "--set", "loads.tau_max=3.0"]);
    assert_eq!(json["status"], "converged");
    assert_eq!(json["newton_iterations"], 19);
    assert_eq!(json["slip_fraction"], 0.896);
    let v2 = json["max_azimuthal_displacement"]["value"]
        .as_f64()
        .unwrap();
    // the same solve: round-off only
    assert!((v2 - 5.962265637721237e-3).abs() <= 1e-12, "{v2:e}");
    assert!(json["limiting_ratios"].is_null());
}

/// The bilateral body past its limit: the condensed range, as before.
#[test]
fn bilateral_past_the_limit_still_exits_3_with_the_condensed_range() {
    let (code, _, err) = common::capstan_status(&["contact", "--set", "loads.tau_max=4"]);
    assert_eq!(code, Some(3), "{err}");
    assert!(
        err.contains("outside the limiting range [0.299037, 3.344063]"),
        "{err}"
    );
}

/// A step that fails without a residual reports the solver's failure, not `residual inf`:
/// just inside the range the load continuation (at the fixed ratio) meets the singular
/// Jacobian of near-full slip.
#[test]
fn a_singular_load_step_names_the_singular_jacobian_not_an_infinite_residual() {
    let (code, _, err) = common::capstan_status(&[
        "contact",
        "--set",
        UNILATERAL,
        "--set",
        "loads.tau_max=3.3415",
    ]);
    assert_eq!(code, Some(4), "{err}");
    assert!(!err.contains("residual inf"), "{err}");
    assert!(err.contains("singular"), "{err}");
}

/// `capstan threshold` on the plane body under unilateral contact: the full-system route under
/// `auto` (before: exit 2, the condensed solver refused), the threshold the upper end of the
/// range `contact` names; forcing the condensed solver still refuses.
#[test]
fn threshold_of_the_unilateral_plane_body_is_the_upper_end_of_its_range() {
    let json = common::capstan_json(&["threshold", "--set", UNILATERAL]);
    let ratio = json["threshold_ratio"].as_f64().unwrap();
    assert!((UPPER_END[0]..UPPER_END[1]).contains(&ratio), "{ratio}");
    assert_eq!(json["no_equilibrium_beyond"], true);
    assert_eq!(json["limiting_ratio"].as_f64(), Some(ratio));
    let (_, _, err) =
        common::capstan_status(&["contact", "--set", UNILATERAL, "--set", "loads.tau_max=3.5"]);
    // the same full-slip solve: the same number to the printed digits
    assert_eq!(named_range(&err)[1], (ratio * 1e6).round() / 1e6, "{err}");
    let (code, _, err) = common::capstan_status(&[
        "threshold",
        "--set",
        UNILATERAL,
        "--set",
        "solver.nonlinear=\"newton\"",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("solver.nonlinear"), "{err}");
}
