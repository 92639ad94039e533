//! Every scene in `examples/scenes/` runs through the binary and yields its number.
//!
//! A scene names its command in a `# command: NAME` line and the JSON key to check in a
//! `# expect: KEY` line at the top. The grid is overridden to 30 x 7 so the thick-body
//! scenes run in well under a second (the membrane commands ignore it).

mod common;

use std::path::Path;

fn header(text: &str, key: &str) -> Option<String> {
    text.lines()
        .take_while(|l| l.starts_with('#') || l.trim().is_empty())
        .find_map(|l| l.strip_prefix(&format!("# {key}:")))
        .map(|v| v.trim().to_owned())
}

#[test]
fn every_example_scene_runs_and_yields_its_number() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    let mut scenes: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    assert!(
        scenes.len() >= 6,
        "expected the six documented scenes, found {scenes:?}"
    );
    for scene in &scenes {
        let text = std::fs::read_to_string(scene).unwrap();
        let command = header(&text, "command")
            .unwrap_or_else(|| panic!("{}: no `# command:` line", scene.display()));
        let key = header(&text, "expect")
            .unwrap_or_else(|| panic!("{}: no `# expect:` line", scene.display()));
        let out = common::capstan(&[
            &command,
            scene.to_str().unwrap(),
            "--set",
            "grid.n2=30",
            "--set",
            "grid.n3=7",
            "--json",
            "--quiet",
        ]);
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let value = json[&key]
            .as_f64()
            .unwrap_or_else(|| panic!("{}: `{key}` is not a number in {json}", scene.display()));
        assert!(value.is_finite(), "{}: {key} = {value}", scene.display());
        if command == "tension" {
            assert!(
                value > 1.0,
                "{}: a tension ratio above 1, got {value}",
                scene.display()
            );
        } else {
            assert!(
                (-1.0..=1.0).contains(&value),
                "{}: Slip in [-1, 1], got {value}",
                scene.display()
            );
        }
    }
}

#[test]
fn ellipse_scene_matches_the_closed_form() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/capstan_ellipse.toml");
    let json = common::capstan_json(&["tension", scene.to_str().unwrap()]);
    let ratio = json["tension_ratio"].as_f64().unwrap();
    // eq. PrismEqnPlot: exp(2 mu atan(b/a)) with mu = 1/2, b/a = 0.75
    let exact = (0.75f64).atan().exp();
    assert!((ratio - exact).abs() < 1e-9 * exact, "{ratio} vs {exact}");
}
