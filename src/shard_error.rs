//! Errors of sharded sweeps and their merge.

/// Why sweep parts cannot be run or merged (exit code 2: bad input).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ShardError {
    /// `--shard` is not `I/N` with `1 <= I <= N`.
    #[error("--shard {spec}: expected I/N with 1 <= I <= N (I is 1-based)")]
    InvalidSpec {
        /// The argument as given.
        spec: String,
    },
    /// No part files were found in the given directories.
    #[error("no sweep parts (shard-I-of-N.json) in {dirs}")]
    NoParts {
        /// The directories searched, comma separated.
        dirs: String,
    },
    /// A file is not a sweep part of this format version.
    #[error("{path}: not a capstan sweep part ({reason})")]
    Malformed {
        /// The file.
        path: String,
        /// What is wrong.
        reason: String,
    },
    /// Two parts come from different scenes (or sweep parameters).
    #[error(
        "{path}: scene hash {found} differs from {expected} of {first}: the parts come from different scenes"
    )]
    HashMismatch {
        /// The offending part.
        path: String,
        /// Its hash.
        found: String,
        /// The first part.
        first: String,
        /// The first part's hash.
        expected: String,
    },
    /// Two parts sweep different keys or grids.
    #[error("{path}: sweeps {found}, but {first} sweeps {expected}")]
    GridMismatch {
        /// The offending part.
        path: String,
        /// Its key and grid.
        found: String,
        /// The first part.
        first: String,
        /// The first part's key and grid.
        expected: String,
    },
    /// Two parts disagree on the number of shards `N`.
    #[error("{path}: part of {found} shards, but {first} is part of {expected}")]
    CountMismatch {
        /// The offending part.
        path: String,
        /// Its `N`.
        found: usize,
        /// The first part.
        first: String,
        /// The first part's `N`.
        expected: usize,
    },
    /// Points of the grid that no part holds.
    #[error(
        "missing sweep points {indices:?} (values {values:?}; 0-based indices): shards {shards:?} of {count} not found"
    )]
    MissingPoints {
        /// 0-based indices into the grid.
        indices: Vec<usize>,
        /// Their values.
        values: Vec<f64>,
        /// 1-based shards that would hold them.
        shards: Vec<usize>,
        /// `N`.
        count: usize,
    },
    /// Points of the grid held by more than one part.
    #[error("duplicate sweep points {indices:?} (0-based indices), e.g. in {paths:?}")]
    DuplicatePoints {
        /// 0-based indices into the grid.
        indices: Vec<usize>,
        /// Two files holding the first duplicate.
        paths: [String; 2],
    },
}
