//! The command line of the benchmark examples: positional values, `--flag`s and
//! `--option VALUE` pairs, read from `std::env::args()` without the program name.
#![allow(dead_code)] // every example uses a part of it

use std::str::FromStr;

/// The arguments after the program name.
pub struct ExampleArgs(Vec<String>);

impl ExampleArgs {
    /// The process's arguments.
    pub fn from_env() -> Self {
        Self(std::env::args().skip(1).collect())
    }

    /// The `i`-th argument (0-based) parsed as a `T`, or `default` when it is missing or does
    /// not parse.
    pub fn positional<T: FromStr>(&self, i: usize, default: T) -> T {
        self.0
            .get(i)
            .and_then(|a| a.parse().ok())
            .unwrap_or(default)
    }

    /// The `i`-th argument (0-based) as given, if any.
    pub fn word(&self, i: usize) -> Option<&str> {
        self.0.get(i).map(String::as_str)
    }

    /// Whether `name` (e.g. `--sweep`) is one of the arguments.
    pub fn flag(&self, name: &str) -> bool {
        self.0.iter().any(|a| a == name)
    }

    /// The argument after the first `name` (e.g. `--ordering nd`: `nd`), if any.
    pub fn option(&self, name: &str) -> Option<&str> {
        self.0
            .iter()
            .position(|a| a == name)
            .and_then(|k| self.0.get(k + 1))
            .map(String::as_str)
    }
}
