//! Fuzz target `membrane`: the property is [`properties::membrane`] (shared with `tests/fuzz_corpus.rs`).
#![no_main]

#[path = "../properties.rs"]
mod properties;

libfuzzer_sys::fuzz_target!(|data: &[u8]| properties::membrane(data));
