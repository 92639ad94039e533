//! The compiled half of the Python package `capstan` (module `capstan._capstan`).
//!
//! Every function here is a thin call into the facade's library API (`capstan::api`),
//! so Python gets exactly what `capstan <command> --json` prints: the same scene keys, the same
//! result keys, the same digits. The pure-Python half (`python/capstan/`) wraps the JSON and the
//! whole-body field buffers into result objects with numpy arrays.
//!
//! Status: the PyO3 code is behind the feature `python` (maturin turns on `extension-module`);
//! without it this crate is empty, so `cargo test --workspace` needs no Python.
//!
//! # Example
//! ```
//! // Without the `python` feature the crate only states what it is.
//! assert_eq!(_capstan::MODULE, "capstan._capstan");
//! ```
#![warn(missing_docs)]

/// The Python module this crate builds.
pub const MODULE: &str = "capstan._capstan";

#[cfg(feature = "python")]
mod module;
