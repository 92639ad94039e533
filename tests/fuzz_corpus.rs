//! Replays the fuzz corpora (`fuzz/corpus/<target>/*`, minimised with `cargo fuzz cmin`) and
//! the fuzzer's findings (`fuzz/regressions/<target>/*`, kept apart so that `cmin` cannot drop
//! them) through the same properties the fuzz targets check (`fuzz/properties.rs`): expression
//! parser and evaluator, scene parser with `--set` overrides, membrane models on random valid
//! scenes.

#[path = "../fuzz/properties.rs"]
mod properties;

fn replay(target: &str, property: fn(&[u8])) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/corpus")
        .join(target);
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let data = std::fs::read(&path).unwrap();
        let outcome = std::panic::catch_unwind(|| property(&data));
        assert!(outcome.is_ok(), "{target}: {} fails", path.display());
        n += 1;
    }
    assert!(n > 0, "empty corpus {}", dir.display());
}

#[test]
fn expression_corpus_holds() {
    replay("expression", properties::expression);
}

#[test]
fn scene_corpus_holds() {
    replay("scene", properties::scene);
}

#[test]
fn membrane_corpus_holds() {
    replay("membrane", properties::membrane);
}
