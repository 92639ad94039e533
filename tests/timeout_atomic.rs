//! Issue 18: `--timeout SECONDS` (exit code 5, `timed out`, no partial files) and atomic outputs
//! (a run killed with SIGKILL mid-write leaves the old file or the new one, never a torn one).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("capstan-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn files(dir: &Path) -> Vec<String> {
    match std::fs::read_dir(dir) {
        Ok(entries) => entries
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect(),
        Err(_) => Vec::new(),
    }
}

/// A tension run writing about 19 MB (200,000 samples) into `out`.
fn big_tension(out: &Path, mu: &str, timeout: Option<f64>) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_capstan"));
    if let Some(t) = timeout {
        c.arg("--timeout").arg(t.to_string());
    }
    c.args(["-q", "tension", "--set", "membrane.samples=200000", "--set"])
        .arg(format!("friction.mu={mu}"))
        .arg("--out")
        .arg(out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    c
}

#[test]
fn timeout_stops_a_long_contact_solve_with_exit_code_5_and_no_files() {
    let out = dir("timeout-contact");
    let run = Command::new(env!("CARGO_BIN_EXE_capstan"))
        .args([
            "--timeout",
            "1",
            "contact",
            "--set",
            "grid.n2=1500",
            "--set",
            "grid.n3=200",
        ])
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(5), "{stderr}");
    assert!(stderr.contains("timed out"), "{stderr}");
    assert!(files(&out).is_empty(), "{:?}", files(&out));
}

#[test]
fn timeout_while_writing_leaves_all_files_or_none() {
    // Timers from before the first write to after the last (a run takes about 0.4 s).
    let whole = [
        "scene.toml",
        "tension.csv",
        "tension.json",
        "tension.png",
        "tension.svg",
    ];
    let (mut finished, mut stopped) = (0, 0);
    for k in 1..=16 {
        let out = dir(&format!("timeout-write-{k}"));
        let run = big_tension(&out, "0.5", Some(0.04 * f64::from(k)))
            .output()
            .unwrap();
        let mut found = files(&out);
        found.sort();
        match run.status.code() {
            Some(0) => {
                assert_eq!(found, whole);
                finished += 1;
            }
            Some(5) => {
                assert!(found.is_empty(), "timed out at k = {k}, left {found:?}");
                stopped += 1;
            }
            other => panic!("exit {other:?}: {}", String::from_utf8_lossy(&run.stderr)),
        }
        let _ = std::fs::remove_dir_all(&out);
    }
    assert!(stopped > 0, "no run timed out ({finished} finished)");
}

#[test]
fn sigkill_mid_write_leaves_the_old_file_or_the_new_one() {
    let reference = |mu: &str| {
        let out = dir(&format!("atomic-ref-{mu}"));
        assert!(big_tension(&out, mu, None).status().unwrap().success());
        let read = |f: &str| std::fs::read(out.join(f)).unwrap();
        (read("tension.csv"), read("tension.json"))
    };
    let versions = [reference("0.5"), reference("0.3")];
    assert_ne!(versions[0].0, versions[1].0);
    let out = dir("atomic-kill");
    assert!(big_tension(&out, "0.5", None).status().unwrap().success());
    // Kill times from a fixed-seed generator (64-bit LCG), 0 to 0.5 s.
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    for k in 0..12 {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1);
        let delay = Duration::from_millis((state >> 33) % 500);
        let mut child = big_tension(&out, ["0.3", "0.5"][k % 2], None)
            .spawn()
            .unwrap();
        std::thread::sleep(delay);
        let _ = child.kill(); // SIGKILL; the run may have finished already
        child.wait().unwrap();
        let csv = std::fs::read(out.join("tension.csv")).unwrap();
        let json = std::fs::read(out.join("tension.json")).unwrap();
        assert!(
            versions.iter().any(|v| v.0 == csv),
            "torn tension.csv after a kill at {delay:?}"
        );
        assert!(
            versions.iter().any(|v| v.1 == json),
            "torn tension.json after a kill at {delay:?}"
        );
        serde_json::from_slice::<serde_json::Value>(&json).unwrap();
    }
}
