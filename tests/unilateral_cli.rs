//! The CLI on unilateral contact: a body that lifts off entirely has no equilibrium (exit 3).

mod common;

#[test]
fn a_body_lifting_off_entirely_exits_with_no_equilibrium() {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/contact_lift_off.toml"
    );
    let (code, _, err) = common::capstan_status(&[
        "contact",
        scene,
        "--set",
        "loads.tau0=-1",
        "--set",
        "loads.tau_max=-1",
        "--set",
        "grid.n2=41",
        "--set",
        "grid.n3=9",
    ]);
    assert_eq!(code, Some(3), "{err}");
    assert!(
        err.contains("lifts off the obstacle entirely") && err.contains("41 contact nodes"),
        "{err}"
    );
}
