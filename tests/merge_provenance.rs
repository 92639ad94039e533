//! A sharded sweep merged with `capstan merge --out` keeps what an unsharded `sweep --out`
//! writes: the per-point VTU files with identical bytes, the `.pvd` collection, `scene.toml`,
//! and `capstan_version` + the resolved scene in `sweep.json` and in `--json`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_capstan");

const SWEEP: [&str; 12] = [
    "--set",
    "grid.n2=24",
    "--set",
    "grid.n3=5",
    "--param",
    "loads.tau_max",
    "--from",
    "1",
    "--to",
    "2",
    "--steps",
    "5",
];

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("capstan-mprov-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn ok(args: &[&str]) -> Output {
    let out = Command::new(BIN).args(args).output().expect("capstan runs");
    assert!(
        out.status.success(),
        "{:?}\n{}\n{}",
        args,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn sweep(out: &Path, extra: &[&str]) {
    let mut args = vec!["sweep"];
    args.extend(SWEEP);
    args.extend(extra);
    args.extend(["--out", out.to_str().unwrap()]);
    ok(&args);
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn merged_shards_keep_point_vtu_files_pvd_and_provenance() {
    let whole = dir("whole");
    sweep(&whole, &[]);
    let parts = dir("parts");
    for s in ["1/2", "2/2"] {
        sweep(&parts, &["--shard", s]);
    }
    let merged = dir("merged");
    let stdout = ok(&[
        "merge",
        parts.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
        "--json",
    ])
    .stdout;
    for k in 0..5 {
        let name = format!("points/point_{k:04}.vtu");
        let a = std::fs::read(whole.join(&name)).expect("unsharded point file");
        let b = std::fs::read(merged.join(&name)).expect("merged point file");
        assert!(a == b, "{name} differs");
    }
    assert_eq!(
        std::fs::read_to_string(whole.join("sweep.pvd")).unwrap(),
        std::fs::read_to_string(merged.join("sweep.pvd")).unwrap()
    );
    assert_eq!(
        std::fs::read_to_string(whole.join("scene.toml")).unwrap(),
        std::fs::read_to_string(merged.join("scene.toml")).unwrap()
    );
    let stdout: serde_json::Value = serde_json::from_slice(&stdout).unwrap();
    for v in [
        json(&whole.join("sweep.json")),
        json(&merged.join("sweep.json")),
        stdout,
    ] {
        assert_eq!(v["capstan_version"], env!("CARGO_PKG_VERSION"));
        assert_eq!(v["scene"]["grid"]["n2"], 24);
        assert_eq!(v["points"].as_array().unwrap().len(), 5);
    }
    for d in [whole, parts, merged] {
        let _ = std::fs::remove_dir_all(d);
    }
}
