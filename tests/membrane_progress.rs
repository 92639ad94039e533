//! `capstan -v infer-mu --model membrane` prints the membrane's Newton iterations (stage
//! `membrane`), as every other iterative solve does.

use std::process::{Command, Output};

/// `capstan [-v] infer-mu --model membrane --set membrane.t_max=2.75 --json`.
fn infer_mu_membrane(verbose: bool) -> Output {
    let args = [
        "infer-mu",
        "--model",
        "membrane",
        "--set",
        "membrane.t_max=2.75",
        "--json",
    ];
    Command::new(env!("CARGO_BIN_EXE_capstan"))
        .args(verbose.then_some("-v"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn verbose_infer_mu_membrane_prints_membrane_iterations() {
    let out = infer_mu_membrane(true);
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
    let quiet = infer_mu_membrane(false);
    assert!(!String::from_utf8_lossy(&quiet.stderr).contains("membrane "));
}
