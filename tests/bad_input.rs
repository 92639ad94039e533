//! Bad input is refused cleanly through the binary: exit code 2 with a message naming the key,
//! the value, the allowed range and (for scene files) the line; no equilibrium is 3,
//! non-convergence 4.

mod common;

use std::path::PathBuf;

/// Runs the binary; returns (exit code, stdout, stderr).
fn capstan(args: &[&str]) -> (i32, String, String) {
    let (code, stdout, stderr) = common::capstan_status(args);
    (
        code.expect("exited, not killed by a signal"),
        stdout,
        stderr,
    )
}

/// A scene file with `text` in a fresh temporary directory.
fn scene_file(name: &str, text: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("capstan-bad-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs `capstan ARGS` (words split at white space); asserts exit code `code` and nothing on
/// stdout; returns stderr.
#[track_caller]
fn failed(code: i32, args: &str) -> String {
    let args: Vec<&str> = args.split_whitespace().collect();
    let (found, stdout, stderr) = capstan(&args);
    assert_eq!(found, code, "{args:?}\nstderr: {stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    stderr
}

/// Asserts exit code 2 and that stderr contains every needle.
#[track_caller]
fn refused(args: &[&str], needles: &[&str]) {
    let (code, stdout, stderr) = capstan(args);
    assert_eq!(code, 2, "{args:?}\nstdout: {stdout}\nstderr: {stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for n in needles {
        assert!(stderr.contains(n), "{args:?}: `{n}` not in {stderr}");
    }
}

#[test]
fn out_of_range_set_values_name_key_value_and_range() {
    let cases: &[(&str, &[&str])] = &[
        (
            "friction.mu=-1",
            &["friction.mu", "-1", "[0, inf)", "--set"],
        ),
        ("friction.eps=0", &["friction.eps", "= 0", "(0, inf)"]),
        ("body.poisson=0.5", &["body.poisson", "0.5", "(-1, 1/2)"]),
        ("body.poisson=-1", &["body.poisson", "(-1, 1/2)"]),
        ("body.young=0", &["body.young", "(0, inf)"]),
        (
            "body.thickness=-0.1",
            &["body.thickness", "-0.1", "(0, inf)"],
        ),
        ("grid.n2=2", &["grid.n2", "= 2", "[3, 10^7]"]),
        ("grid.n3=1", &["grid.n3", "[3, 10^6]"]),
        ("membrane.samples=1", &["membrane.samples", "[2, 10^7]"]),
        (
            "membrane.theta_max=-2",
            &["membrane.theta_max", "(membrane.theta0, inf)"],
        ),
        ("membrane.t0=0", &["membrane.t0", "(0, inf)"]),
        ("obstacle.b=0", &["obstacle.b", "(0, inf)"]),
        ("loads.width=0", &["loads.width", "(0, inf)"]),
        ("solver.linear=qr", &["solver.linear", "qr", "`lu`"]),
        (
            "friction.law=stribeck",
            &["friction.law", "stribeck", "coulomb"],
        ),
    ];
    for (set, needles) in cases {
        refused(&["tension", "--set", set], needles);
    }
}

#[test]
fn nan_and_inf_are_refused_from_set_and_from_files_with_the_line() {
    refused(
        &["tension", "--set", "friction.mu=nan"],
        &["friction.mu", "NaN"],
    );
    refused(
        &["tension", "--set", "loads.tau0=-inf"],
        &["loads.tau0", "-inf", "finite"],
    );
    let f = scene_file(
        "nan.toml",
        b"# comment\n[friction]\nmu = 0.3\n\n[body]\npoisson = nan\n",
    );
    refused(
        &["geometry", f.to_str().unwrap()],
        &["nan.toml:6", "body.poisson", "NaN", "(-1, 1/2)"],
    );
    let f = scene_file("inf.toml", b"[obstacle]\nshape = \"ellipse\"\nb = inf\n");
    refused(
        &["geometry", f.to_str().unwrap()],
        &["inf.toml:3", "obstacle.b", "inf"],
    );
}

#[test]
fn set_overrides_the_file_and_is_named_as_set() {
    let f = scene_file("ok.toml", b"[friction]\nmu = 0.3\n");
    refused(
        &["tension", f.to_str().unwrap(), "--set", "friction.mu=-2"],
        &["--set", "friction.mu", "-2"],
    );
}

#[test]
fn malformed_toml_unknown_keys_and_wrong_types_point_to_the_line() {
    let cases: [(&str, &[u8], &[&str]); 6] = [
        (
            "syntax.toml",
            b"[friction\nmu = 1\n",
            &["line 1", "syntax.toml"],
        ),
        (
            "unknown.toml",
            b"[friction]\nmu = 1\nmuu = 2\n",
            &["unknown.toml:3", "friction.muu", "friction.mu"],
        ),
        (
            "table.toml",
            b"[frictions]\nmu = 1\n",
            &["table.toml:2", "frictions"],
        ),
        (
            "type.toml",
            b"[friction]\n\nmu = \"abc\"\n",
            &["line 3", "invalid type"],
        ),
        (
            "negative.toml",
            b"[grid]\nn2 = -5\n",
            &["negative.toml", "line 2"],
        ),
        (
            "binary.toml",
            &[0xff, 0xfe, 0x00, 0x81],
            &["binary.toml", "UTF-8"],
        ),
    ];
    for (name, text, needles) in cases {
        let f = scene_file(name, text);
        refused(&["geometry", f.to_str().unwrap()], needles);
    }
    refused(&["geometry", "--set", "nonsense"], &["KEY=VALUE"]);
    refused(&["geometry", "--set", "friction=1"], &["table.key"]);
}

#[test]
fn empty_files_are_the_default_scene() {
    for (name, text) in [
        ("empty.toml", &b""[..]),
        ("comments.toml", b"# nothing\n\n"),
    ] {
        let f = scene_file(name, text);
        let (code, stdout, stderr) = capstan(&["geometry", f.to_str().unwrap(), "--json"]);
        assert_eq!(code, 0, "{stderr}");
        assert!(
            stdout.contains("mean_curvature") || stdout.starts_with('{'),
            "{stdout}"
        );
    }
}

#[test]
fn expressions_must_parse_and_stay_finite_on_the_interval() {
    refused(
        &[
            "tension",
            "--set",
            "obstacle.shape=prism",
            "--set",
            "obstacle.u=2*sin(t",
        ],
        &["obstacle.u", "2*sin(t"],
    );
    // ln(t) is NaN for t < 0, inside [-pi/2, pi/2].
    refused(
        &[
            "tension",
            "--set",
            "obstacle.shape=prism",
            "--set",
            "obstacle.u=ln(t)",
        ],
        &["obstacle.u", "finite", "membrane.theta0"],
    );
    // sqrt(t) has an infinite slope at t = 0.
    refused(
        &[
            "tension",
            "--set",
            "obstacle.shape=cone",
            "--set",
            "obstacle.vbar=sqrt(t)",
            "--set",
            "membrane.theta0=0",
        ],
        &["obstacle.vbar", "derivative"],
    );
    let long = format!("obstacle.u={}", "t+".repeat(3000) + "t");
    refused(
        &["tension", "--set", "obstacle.shape=prism", "--set", &long],
        &["obstacle.u"],
    );
}

#[test]
fn reduced_volumetric_integration_is_refused_for_finite_differences() {
    refused(
        &["geometry", "--set", "discretisation.volumetric=reduced"],
        &["discretisation.volumetric", "reduced", "fem-q1"],
    );
    refused(
        &["geometry", "--set", "discretisation.volumetric=half"],
        &["discretisation.volumetric", "half", "`full`", "`reduced`"],
    );
}

#[test]
fn q2_needs_odd_grids() {
    refused(
        &[
            "geometry",
            "--set",
            "discretisation.method=fem-q2",
            "--set",
            "grid.n2=250",
        ],
        &["grid.n2", "250", "odd"],
    );
}

#[test]
fn grids_that_do_not_fit_in_memory_are_refused_with_the_estimate() {
    if capstan::scene::available_memory().is_none() {
        return; // no /proc/meminfo: nothing to compare with
    }
    let f = scene_file("huge.toml", b"[grid]\nn2 = 100000\nn3 = 20000\n");
    refused(
        &["geometry", f.to_str().unwrap()],
        &[
            "huge.toml:2",
            "100000 x 20000",
            "GiB",
            "available",
            "MemAvailable",
        ],
    );
    let need = capstan::scene::memory_estimate(
        4000,
        640,
        capstan_elasticity::finite_element::DiscretisationMethod::Fd,
        false,
    );
    // ~20.3 GiB; measured 19.9 GB (VmHWM, full-newton with grid sequencing)
    assert!(need > 18e9 && need < 25e9, "{need}");
}

#[test]
fn exit_code_3_when_no_equilibrium_exists() {
    // A falling tension: no mu >= 0 produces it.
    let (code, _, stderr) = capstan(&["infer-mu", "--set", "membrane.t_max=0.5"]);
    assert_eq!(code, 3, "{stderr}");
    assert!(stderr.contains("below 1"), "{stderr}");
    // A concave part of the profile inside the interval.
    let (code, _, stderr) = capstan(&[
        "tension",
        "--set",
        "obstacle.shape=prism",
        "--set",
        "obstacle.u=2*sin(t) - 0.6*sin(3*t)",
        "--set",
        "obstacle.v=2*cos(t) + 0.6*cos(3*t)",
    ]);
    assert_eq!(code, 3, "{stderr}");
}

#[test]
fn exit_code_4_when_a_solve_does_not_converge() {
    // mu = 100 over 20 rad: T = exp(2000) overflows; refused as a non-finite tension.
    // no NaN or inf reaches stdout
    let stderr = failed(
        4,
        "tension --set obstacle.shape=cylinder --set membrane.theta0=0 \
         --set membrane.theta_max=20 --set friction.mu=100 --json",
    );
    assert!(stderr.contains("not finite"), "{stderr}");
}

#[test]
fn contact_beyond_limiting_equilibrium_is_exit_code_3() {
    let stderr = failed(
        3,
        "contact --set grid.n2=40 --set grid.n3=9 --set loads.tau_max=100 --json",
    );
    assert!(stderr.contains("no static equilibrium"), "{stderr}");
    refused(
        &["contact", "--set", "grid.n3=2"],
        &["grid.n3", "[3, 10^6]"],
    );
}
