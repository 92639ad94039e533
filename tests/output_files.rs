//! Atomic writes, CSV and JSON: what reaches the disk, and what never does.

mod common;

use std::io::Write;
use std::path::Path;

use capstan::CliError;
use capstan::output::{OutputDir, OutputError, Table, to_json_string, write_atomic};
use common::scratch_dir as scratch;

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn failed_write_leaves_no_file_and_keeps_the_old_one() {
    let dir = scratch("output_files_failed");
    let path = dir.join("profile.csv");
    let r: Result<(), _> = write_atomic(&path, |w| {
        w.write_all(b"half a line")?;
        Err(OutputError::InvalidParameter {
            field: "n",
            value: 0.0,
            allowed: "[1, inf)",
        })
    });
    assert!(r.is_err());
    assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));

    write_atomic(&path, |w| Ok(w.write_all(b"old\n")?)).unwrap();
    let r: Result<(), _> = write_atomic(&path, |w| {
        w.write_all(b"new, but failing")?;
        Err(OutputError::DuplicateName { name: "x".into() })
    });
    assert!(r.is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old\n");
    assert_eq!(entries(&dir), ["profile.csv"]);
}

#[test]
fn panicking_writer_leaves_no_temporary_file() {
    let dir = scratch("output_files_panic");
    let path = dir.join("x.json");
    let r = std::panic::catch_unwind(|| {
        let _: Result<(), _> = write_atomic(&path, |w| {
            w.write_all(b"{")?;
            panic!("writer bug");
        });
    });
    assert!(r.is_err());
    assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));
}

#[test]
fn missing_directory_is_an_io_error_naming_the_file() {
    let dir = scratch("output_files_missing");
    let path = dir.join("no/such/dir/x.csv");
    match write_atomic(&path, |w| Ok(w.write_all(b"x")?)) {
        Err(OutputError::Io { path: p, .. }) => assert_eq!(p, path),
        other => panic!("{other:?}"),
    }
    let err = CliError::from(write_atomic(&path, |_| Ok(())).unwrap_err());
    assert_eq!(err.exit_code(), 1);
    assert!(err.to_string().contains("x.csv"), "{err}");
}

#[test]
fn output_dir_creates_nested_files_and_refuses_escapes() {
    let root = scratch("output_files_dir").join("run/out");
    let out = OutputDir::create(&root).unwrap();
    let p = out
        .write("fields/step.txt", |w| Ok(w.write_all(b"ok")?))
        .unwrap();
    assert_eq!(p, root.join("fields/step.txt"));
    assert_eq!(std::fs::read_to_string(p).unwrap(), "ok");
    for bad in ["", "../x.csv", "/tmp/x.csv", "a/.."] {
        assert!(
            matches!(out.file(bad), Err(OutputError::InvalidName { .. })),
            "{bad:?}"
        );
    }
}

#[test]
fn csv_reads_back_exactly() {
    let dir = scratch("output_files_csv");
    let out = OutputDir::create(&dir).unwrap();
    let theta: Vec<f64> = (0..50).map(|i| 0.1 * i as f64 + 1e-9).collect();
    let tension: Vec<f64> = theta.iter().map(|t| (0.3 * t).exp() * 1e-6).collect();
    let state: Vec<i32> = (0..50).map(|i| i % 3 - 1).collect();
    let table = Table::new()
        .f64("theta", theta.as_slice())
        .f64("tension", tension.as_slice())
        .i32("state", state.as_slice())
        .text(
            "note",
            (0..50).map(|i| if i == 7 { "a \"quoted\", note" } else { "" }),
        );
    let path = out.write_csv("profile.csv", &table).unwrap();
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("theta,tension,state,note"));
    for (i, line) in lines.enumerate() {
        let f: Vec<&str> = line.splitn(4, ',').collect();
        assert_eq!(f[0].parse::<f64>().unwrap(), theta[i]); // shortest round-trip: exact
        assert_eq!(f[1].parse::<f64>().unwrap(), tension[i]);
        assert_eq!(f[2].parse::<i32>().unwrap(), state[i]);
        if i == 7 {
            assert_eq!(f[3], "\"a \"\"quoted\"\", note\"");
        }
    }
}

#[test]
fn csv_refuses_nan_and_ragged_columns_without_writing() {
    let dir = scratch("output_files_csv_bad");
    let out = OutputDir::create(&dir).unwrap();
    let nan = Table::new()
        .f64("theta", [0.0, 1.0, 2.0])
        .f64("ratio", [1.0, f64::INFINITY, 2.0]);
    let err = out.write_csv("nan.csv", &nan).unwrap_err();
    assert!(
        matches!(&err, OutputError::NonFinite { column, index: 1, .. } if column == "ratio"),
        "{err:?}"
    );
    let ragged = Table::new().f64("theta", [0.0, 1.0]).i32("state", [1]);
    assert!(matches!(
        out.write_csv("ragged.csv", &ragged),
        Err(OutputError::LengthMismatch {
            expected: 2,
            found: 1,
            ..
        })
    ));
    let twice = Table::new().f64("a", [0.0]).f64("a", [1.0]);
    assert!(matches!(
        out.write_csv("twice.csv", &twice),
        Err(OutputError::DuplicateName { .. })
    ));
    assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));
}

#[derive(serde::Serialize)]
struct Summary {
    mu: f64,
    ratios: Vec<f64>,
    converged: bool,
}

#[test]
fn json_writes_pretty_and_refuses_nan() {
    let dir = scratch("output_files_json");
    let out = OutputDir::create(&dir).unwrap();
    let good = Summary {
        mu: 0.5,
        ratios: vec![1.0, 2.5],
        converged: true,
    };
    let path = out.write_json("summary.json", &good).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text, format!("{}\n", to_json_string(&good).unwrap()));
    let back: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(back["ratios"][1], 2.5);

    let bad = Summary {
        mu: 0.5,
        ratios: vec![1.0, f64::NAN],
        converged: false,
    };
    let err = out.write_json("bad.json", &bad).unwrap_err();
    assert!(err.to_string().contains("`ratios`[1] = NaN"), "{err}");
    assert_eq!(entries(&dir), ["summary.json"]);
}
