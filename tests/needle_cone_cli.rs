//! Issue 18's scene through the command line: the needle cone (half-aperture 1e-3, two wraps)
//! answers, to 1e-9 of the closed form `T = T0 exp(mu cot(alpha) sin(sin(alpha) theta))`.

use std::process::Command;

#[test]
fn needle_cone_two_wraps_answers_the_closed_form() {
    let out = Command::new(env!("CARGO_BIN_EXE_capstan"))
        .args([
            "tension",
            "--set",
            "obstacle.shape=cone",
            "--set",
            "obstacle.ubar=sin(t)*tan(1/1000)",
            "--set",
            "obstacle.vbar=cos(t)*tan(1/1000)",
            "--set",
            "friction.mu=0.5",
            "--set",
            "membrane.t0=1",
            "--set",
            "membrane.theta0=0",
            "--set",
            "membrane.theta_max=12.566370614359172",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let (alpha, theta, mu) = (1e-3f64, 12.566_370_614_359_172_f64, 0.5);
    let exact = (mu / alpha.tan() * (alpha.sin() * theta).sin()).exp();
    let t_max = report["t_max"].as_f64().unwrap();
    // quadrature to 1e-13 per unit length, exponent ~ 6: the bound with a wide margin
    assert!((t_max - exact).abs() <= 1e-9 * exact, "{t_max} vs {exact}");
}
