//! `capstan -v infer-mu --model membrane` prints the membrane's Newton iterations (stage
//! `membrane`), as every other iterative solve does.

use std::process::Command;

#[test]
fn verbose_infer_mu_membrane_prints_membrane_iterations() {
    let out = Command::new(env!("CARGO_BIN_EXE_capstan"))
        .args([
            "-v",
            "infer-mu",
            "--model",
            "membrane",
            "--set",
            "membrane.t_max=2.75",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("membrane "))
        .collect();
    assert!(lines.len() > 3, "{stderr}");
    assert!(
        lines
            .iter()
            .any(|l| l.contains("membrane            1  residual")),
        "{stderr}"
    );
    // without -v nothing is printed
    let quiet = Command::new(env!("CARGO_BIN_EXE_capstan"))
        .args([
            "infer-mu",
            "--model",
            "membrane",
            "--set",
            "membrane.t_max=2.75",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(!String::from_utf8_lossy(&quiet.stderr).contains("membrane "));
}
