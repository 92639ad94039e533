//! Fuzz target `scene`: the property is [`properties::scene`] (shared with `tests/fuzz_corpus.rs`).
#![no_main]

#[path = "../properties.rs"]
mod properties;

libfuzzer_sys::fuzz_target!(|data: &[u8]| properties::scene(data));
