//! The limiting range of a plane body under unilateral contact
//! (`FullSystemSolver::limiting_ratios`): the full-slip balance along the rigid sliding mode,
//! solved with the ratio and the contact set as unknowns; checked against the condensed
//! solver's bilateral range, and as an equilibrium of the unilateral model itself.

use capstan::scene::Scene;
use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, EndLoads, FullSystemSettings, FullSystemSolver,
    RIGID_MODE_DEFECT,
};

/// The default scene (circle, regularised Coulomb) on `n2 x n3`, contact `kind`.
fn scene(kind: &str, n2: usize, n3: usize) -> Scene {
    let mut scene = Scene::default();
    scene.contact.kind = kind.into();
    scene.grid.n2 = n2;
    scene.grid.n3 = n3;
    scene
}

/// The condensed solver's range of the bilateral body.
fn condensed_range(n2: usize, n3: usize) -> [f64; 2] {
    let model = scene("bilateral", n2, n3).build().unwrap().model().unwrap();
    let mode = BoundarySolver::new(&model, ContactSettings::default())
        .unwrap()
        .sliding()
        .expect("the circle has a rigid sliding mode");
    [mode.lower_ratio, mode.upper_ratio]
}

/// The full-slip range of the body of `kind` and the nodes separated at each end.
fn full_slip_range(kind: &str, n2: usize, n3: usize) -> ([f64; 2], [usize; 2]) {
    let model = scene(kind, n2, n3).build().unwrap().model().unwrap();
    let range = FullSystemSolver::new(&model, FullSystemSettings::default())
        .unwrap()
        .limiting_ratios(1.0)
        .unwrap()
        .expect("the circle has a rigid sliding mode");
    ([range.lower, range.upper], range.separated)
}

/// On the bilateral model the full-slip solve on the full system is the condensed solver's
/// balance: the same range up to the two Newton tolerances.
#[test]
fn the_full_slip_range_of_a_bilateral_body_is_the_condensed_range() {
    let condensed = condensed_range(41, 9);
    let (full, separated) = full_slip_range("bilateral", 41, 9);
    assert_eq!(separated, [0, 0]);
    for (a, b) in condensed.iter().zip(&full) {
        // measured 1e-12 relative; both balances solved to relative residuals 1e-11
        assert!((a - b).abs() <= 1e-9 * a.abs(), "{condensed:?} {full:?}");
    }
    assert!(full[0] < 1.0 && full[1] > 3.0, "{full:?}");
}

/// Where no node separates and no cap binds at full slip (21 x 5: every node presses),
/// unilateral contact has the bilateral equations, so its limiting range is the bilateral
/// one to round-off. On 41 x 9 nothing separates either, but the law differs at some node
/// (the reaction cap or `min(sigma_n, 0)`), and the upper end falls (3.320840 against
/// 3.322448): the comparison can fail.
#[test]
fn the_unilateral_range_equals_the_bilateral_one_where_nothing_lifts_off() {
    let condensed = condensed_range(21, 5);
    let (full, separated) = full_slip_range("unilateral", 21, 5);
    assert_eq!(separated, [0, 0]);
    for (a, b) in condensed.iter().zip(&full) {
        assert!((a - b).abs() <= 1e-9 * a.abs(), "{condensed:?} {full:?}");
    }
    let (full, _) = full_slip_range("unilateral", 41, 9);
    let condensed = condensed_range(41, 9);
    assert!(full[1] < condensed[1] - 1e-4, "{full:?} {condensed:?}");
}

/// The full-slip state plus a rigid slide far enough that every site slips beyond `eps` (the
/// law saturated, as the balance assumed) is an equilibrium of the unilateral model at the
/// ratio found: its residual is round-off there and grows like the ratio's error off it.
#[test]
fn the_full_slip_state_is_an_equilibrium_of_the_unilateral_model() {
    let model = scene("unilateral", 81, 17)
        .build()
        .unwrap()
        .model()
        .unwrap();
    let solver = FullSystemSolver::new(&model, FullSystemSettings::default()).unwrap();
    for direction in [-1.0, 1.0] {
        let slip = solver.full_slip_ratio(1.0, direction).unwrap();
        assert!(slip.rigid_mode_defect.abs() < RIGID_MODE_DEFECT);
        assert!(
            slip.separated > 0,
            "a node next to the loaded end lifts off"
        );
        let tangential = |x: &[f64]| {
            (0..model.active().len())
                .map(|k| x[model.active_node(k).tangential_dof])
                .collect::<Vec<_>>()
        };
        let z = tangential(&slip.rigid_mode);
        let v = tangential(&slip.displacement);
        let z_min = z.iter().fold(f64::INFINITY, |m, x| m.min(x.abs()));
        let v_max = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let a = direction * (10.0 * v_max + 100.0 * model.slip_threshold()) / z_min;
        let slid: Vec<f64> = slip
            .displacement
            .iter()
            .zip(&slip.rigid_mode)
            .map(|(x, z)| x + a * z)
            .collect();
        let at = |ratio: f64| {
            model
                .relative_residual(EndLoads::new(1.0, ratio), &slid)
                .unwrap()
        };
        // the balance's Newton tolerance: 1e-11 relative in the 2-norm
        assert!(at(slip.ratio) < 1e-9, "{direction}: {:e}", at(slip.ratio));
        // a ratio 1e-6 off leaves a residual of that size: the ratio is pinned down
        assert!(at(slip.ratio * (1.0 + 1e-6)) > 1e-7, "{direction}");
    }
}

/// An ellipse has no rigid sliding mode: the pinned Jacobian's defect is of order one, and no
/// range is reported (a pin would hold the body, and the balance would mean nothing).
#[test]
fn a_body_without_a_rigid_sliding_mode_has_no_full_slip_range() {
    let mut s = scene("unilateral", 41, 9);
    s.obstacle.shape = "ellipse".into();
    (s.obstacle.a, s.obstacle.b) = (2.0, 1.0);
    let model = s.build().unwrap().model().unwrap();
    let solver = FullSystemSolver::new(&model, FullSystemSettings::default()).unwrap();
    let slip = solver.full_slip_ratio(1.0, 1.0).unwrap();
    assert!(
        slip.rigid_mode_defect > RIGID_MODE_DEFECT,
        "{}",
        slip.rigid_mode_defect
    );
    assert!(slip.rigid_mode.is_empty());
    assert_eq!(solver.limiting_ratios(1.0).unwrap(), None);
}
