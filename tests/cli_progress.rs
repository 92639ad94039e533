//! `-v` prints one line per iteration of the contact solve on stderr; `--quiet` silences it.

mod common;

fn contact(args: &[&str]) -> (String, String) {
    let grid = [
        "contact",
        "--set",
        "grid.n2=41",
        "--set",
        "grid.n3=9",
        "--json",
    ];
    let out = common::capstan(&[&grid[..], args].concat());
    (
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn verbose_prints_every_newton_iteration_and_quiet_silences_it() {
    let (json, lines) = contact(&["-v"]);
    let report: serde_json::Value = serde_json::from_str(&json).unwrap();
    let iterations = report["newton_iterations"].as_u64().unwrap() as usize;
    let newton: Vec<&str> = lines
        .lines()
        .filter(|l| l.starts_with("condensed-newton"))
        .collect();
    // the initial residual and one line per Newton step, with the active set
    assert_eq!(newton.len(), iterations + 1, "{lines}");
    assert!(
        newton
            .iter()
            .all(|l| l.contains("residual") && l.contains("stick"))
    );
    let residual = |l: &str| -> f64 {
        let after = l.split("residual").nth(1).unwrap();
        after.split_whitespace().next().unwrap().parse().unwrap()
    };
    assert!(residual(newton[newton.len() - 1]) < 1e-9 * residual(newton[0]));
    let (_, quiet) = contact(&["-v", "--quiet"]);
    assert!(quiet.is_empty(), "{quiet}");
    let (_, default) = contact(&[]);
    assert!(!default.contains("condensed-newton"), "{default}");
}
