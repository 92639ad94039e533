//! `capstan sweep --shard I/N` + `capstan merge` reproduce an unsharded sweep byte for byte,
//! refuse parts that do not belong together, and the Slurm / GNU parallel recipes in
//! `scripts/` work (Slurm's variables set by hand; GNU parallel or its shell-loop fallback).

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::{BIN, capstan, capstan_output, small_sweep, succeed, without_seconds};

/// Seven points.
fn sweep() -> [&'static str; 12] {
    small_sweep("7")
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("capstan-shard-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// `capstan sweep` of [`sweep`] with `extra` into `out`, whatever its outcome.
fn sweep_output(out: &Path, extra: &[&str]) -> Output {
    capstan_output(
        &[
            &["sweep"],
            &sweep()[..],
            extra,
            &["--out", out.to_str().unwrap()],
        ]
        .concat(),
    )
}

/// `capstan sweep` of [`sweep`] with `extra` into `out`, which must succeed.
fn sweep_into(out: &Path, extra: &[&str]) {
    let out = sweep_output(out, extra);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `capstan merge PARTS --out MERGED`, which must succeed.
fn merge_into(parts: &Path, merged: &Path) {
    capstan(&[
        "merge",
        parts.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
}

/// `capstan merge DIRS`, which must be refused with exit code 2; its stderr.
fn merge_refused(dirs: &[&Path]) -> String {
    let args: Vec<&str> = dirs.iter().map(|d| d.to_str().unwrap()).collect();
    let (code, _, stderr) = common::capstan_status(&[&["merge"], &args[..]].concat());
    assert_eq!(code, Some(2), "{stderr}");
    stderr
}

fn assert_same_outputs(unsharded: &Path, merged: &Path) {
    let read = |d: &Path, f: &str| std::fs::read(d.join(f)).unwrap();
    assert_eq!(
        read(unsharded, "sweep.csv"),
        read(merged, "sweep.csv"),
        "sweep.csv bytes"
    );
    let json = |d: &Path| String::from_utf8(read(d, "sweep.json")).unwrap();
    let (a, b) = (json(unsharded), json(merged));
    assert_eq!(without_seconds(&a), without_seconds(&b), "sweep.json bytes");
    assert_eq!(a.lines().count(), b.lines().count());
}

fn unsharded(name: &str) -> PathBuf {
    let d = dir(name).join("unsharded");
    sweep_into(&d, &[]);
    d
}

#[test]
fn three_shards_merge_to_the_unsharded_bytes() {
    let root = dir("three");
    let full = unsharded("three-full");
    let parts = root.join("parts");
    for i in 1..=3 {
        sweep_into(&parts, &["--shard", &format!("{i}/3")]);
    }
    let merged = root.join("merged");
    merge_into(&parts, &merged);
    assert_same_outputs(&full, &merged);

    // One part missing: exit 2, naming the points and the shard.
    std::fs::remove_file(parts.join("shard-2-of-3.json")).unwrap();
    let err = merge_refused(&[&parts]);
    assert!(
        err.contains("missing sweep points [1, 4]") && err.contains("shards [2] of 3"),
        "{err}"
    );

    // A part from another scene: refused by its hash.
    sweep_into(&parts, &["--shard", "2/3", "--set", "body.young=2000"]);
    let err = merge_refused(&[&parts]);
    assert!(err.contains("scene hash"), "{err}");

    // The same part twice (copied into a second directory): duplicates named.
    sweep_into(&parts, &["--shard", "2/3"]);
    let copy = root.join("copy");
    std::fs::create_dir_all(&copy).unwrap();
    std::fs::copy(
        parts.join("shard-2-of-3.json"),
        copy.join("shard-2-of-3.json"),
    )
    .unwrap();
    let err = merge_refused(&[&parts, &copy]);
    assert!(err.contains("duplicate sweep points [1, 4]"), "{err}");

    // Parts of different N.
    sweep_into(&copy, &["--shard", "1/2"]);
    std::fs::remove_file(copy.join("shard-2-of-3.json")).unwrap();
    assert!(merge_refused(&[&parts, &copy]).contains("shards"));
    let _ = std::fs::remove_dir_all(root);
}

#[test]
fn more_shards_than_points_and_a_bad_spec() {
    let root = dir("many");
    let parts = root.join("parts");
    let full = unsharded("many-full");
    for i in 1..=9 {
        sweep_into(&parts, &["--shard", &format!("{i}/9")]);
    }
    let merged = root.join("merged");
    merge_into(&parts, &merged);
    assert_same_outputs(&full, &merged);
    let out = sweep_output(&parts, &["--shard", "0/3"]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(root);
}

fn script(name: &str) -> Command {
    let mut c = Command::new("bash");
    c.arg(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scripts")
            .join(name),
    );
    c.args(sweep()).env("CAPSTAN", BIN);
    c
}

#[test]
fn slurm_array_script_shards_merge_to_the_unsharded_bytes() {
    let root = dir("slurm");
    let full = unsharded("slurm-full");
    // An array --array=0-2: Slurm sets the id, the first id and the count.
    for id in 0..3 {
        succeed(
            script("slurm_sweep.sh")
                .env("SLURM_ARRAY_TASK_ID", id.to_string())
                .env("SLURM_ARRAY_TASK_MIN", "0")
                .env("SLURM_ARRAY_TASK_COUNT", "3")
                .env("OUT", &root),
        );
    }
    assert!(root.join("parts/shard-3-of-3.json").exists());
    let merged = root.join("merged");
    let parts = root.join("parts");
    merge_into(&parts, &merged);
    assert_same_outputs(&full, &merged);
    let _ = std::fs::remove_dir_all(root);
}

#[test]
fn parallel_script_and_its_loop_fallback_merge_to_the_unsharded_bytes() {
    let full = unsharded("parallel-full");
    let has_parallel = Command::new("parallel")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    // With GNU parallel when installed; the shell loop always.
    for (name, fallback) in [("parallel", false), ("loop", true)] {
        if !fallback && !has_parallel {
            eprintln!("GNU parallel not installed: its run is covered by the loop fallback");
            continue;
        }
        let root = dir(name);
        let mut c = script("parallel_sweep.sh");
        c.env("SHARDS", "3").env("JOBS", "2").env("OUT", &root);
        if fallback {
            c.env("NO_PARALLEL", "1");
        }
        succeed(&mut c);
        assert_same_outputs(&full, &root);
        let _ = std::fs::remove_dir_all(root);
    }
}
