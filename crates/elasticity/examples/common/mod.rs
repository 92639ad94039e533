//! The command line of the benchmark examples: positional values, `--flag`s and
//! `--option VALUE` pairs, read from `std::env::args()` without the program name; and the
//! process's CPU seconds.
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

/// User + system CPU seconds of this process (`/proc/self/stat`, 100 ticks a second; 0 where
/// it cannot be read).
pub fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let fields: Vec<&str> = after.split_whitespace().collect();
    let tick = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (tick(11) + tick(12)) / 100.0
}
