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

/// The 3-D lift-off scene (coarsened) writes the contact-face map `body_separated.svg`: cells
/// lifted off near both ends, the separated area in the title equal to the trapezoid rule on
/// the `separated` column of `contact.json`.
#[test]
fn the_3d_lift_off_scene_draws_its_separated_face() {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/contact_lift_off_solid.toml"
    );
    let out = common::scratch_dir("lift_off_3d_face");
    let dir = out.to_str().unwrap();
    common::capstan(&[
        "contact",
        scene,
        "--set",
        "grid.n1=3",
        "--set",
        "grid.n2=21",
        "--set",
        "grid.n3=5",
        "--out",
        dir,
    ]);
    let svg = std::fs::read_to_string(out.join("body_separated.svg")).unwrap();
    assert!(out.join("body_separated.png").exists());
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("contact.json")).unwrap()).unwrap();
    let contact = &json["contact"];
    let flags: Vec<bool> = contact["separated"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_bool().unwrap())
        .collect();
    let x1 = common::json_array(&json["solid"]["contact"], "x1");
    let x2 = common::json_array(contact, "x2");
    let face = capstan::output::solid_body::SeparatedFace::new(&x1, &x2, &flags).unwrap();
    assert!(
        face.area > 0.0 && face.area < 0.5 * face.face_area,
        "{face:?}"
    );
    assert!(
        svg.contains(&format!(
            "lifted off: area {:.4} of {:.4}",
            face.area, face.face_area
        )),
        "{}",
        &svg[..svg.len().min(2000)]
    );
}
